"""Exact kinematics of a whole mechanism, group by group in build order, vectorised over angles.

:func:`solve` runs the mechanism's compiled program (:mod:`~planmethod.kinematics.program`: the
group kinds' closed forms, traced once per mechanism into one straight-line numpy function) at
the crank angles and returns a :class:`Motion`: every solved link's pose, ω, ε and origin
velocity and acceleration at each angle, from which any point, any point of a link coincident
with another point (``B@lever``), sliding quantities and the curvature of a path are read.

A :class:`Motion` is a value: its arrays are read-only, and what it returns are read-only views
of them (copy one to change it).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
>>> motion = solve(exercise.mechanism)
>>> round(float(abs(motion.velocity("C")[0])), 4), round(float(motion.omega("BC")), 3)
(5.2716, -24.254)
>>> round(float(motion.curvature("D").rho), 5)
0.07377
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import PlanmethodError, SpecError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Structure
from ..vectors import cross, norm, perp
from .algebra import Body
from .groups import kind_module
from .groups.base import Construction, GroupInputs, ThetaKind, construction, error_estimate
from .program import STAGES, Branch, model, owners
from .state import LinkState
from .tracing import CHUNK

__all__ = ["FLAG_ERROR", "STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "Sliding",
           "choose_branches", "solve"]

_LEVELS = {stage: level for level, stage in enumerate(STAGES)}
#: estimated relative errors above this are flagged in reports
FLAG_ERROR = 1e-6


@dataclass(frozen=True, slots=True)
class Sliding:
    """A prismatic pair's travel s (m), sliding velocity ds/dt and acceleration d²s/dt², and the
    Coriolis acceleration 2ω_along × v_rel (global vector)."""

    s: np.ndarray
    velocity: np.ndarray | None = None
    acceleration: np.ndarray | None = None
    coriolis: np.ndarray | None = None


@dataclass(frozen=True, slots=True)
class Curvature:
    """Radius and centre of curvature of a point's path.

    ``rho`` is NaN where it is undefined, with the reason flagged: ``straight`` (the point moves
    on a straight line by construction), ``inflection`` (v × a = 0 on a curved path) or
    ``stationary`` (v = 0).
    """

    rho: np.ndarray
    center: np.ndarray
    straight: bool
    inflection: np.ndarray
    stationary: np.ndarray


class GroupMotion:
    """A solved group: the sine of the angle between its two construction lines
    (``line_sine``; for a class III group the reciprocal condition number of its Jacobian),
    and — computed when first read, and kept by the motion — its :class:`~planmethod.
    kinematics.groups.base.Construction` (what the plans draw; None for a higher group) and
    ``error_estimate``, the estimated relative error of its velocities and accelerations near
    its toggle, ε·R/s³ and ε·R/s⁵ (per stage solved)."""

    __slots__ = ("_group", "_motion", "line_sine")

    def __init__(self, motion: Motion, group: AssurGroup) -> None:
        self._motion, self._group = motion, group
        level = _LEVELS[motion.stage]
        self.line_sine = motion._read(f"sine:{group.index}") if level >= 1 else None

    @property
    def construction(self) -> Construction | None:
        if not self._group.is_dyad:
            return None
        kept = self._motion._kept
        key = ("construction", self._group.index)
        found = kept.get(key)
        if found is None:
            found = kept[key] = _construction(self._motion, self._group)
        return found

    @property
    def error_estimate(self) -> Mapping[str, np.ndarray] | None:
        stages = STAGES[1:_LEVELS[self._motion.stage] + 1]
        if not stages or self.line_sine is None or not self._group.is_dyad:
            return None
        kept = self._motion._kept
        key = ("estimates", self._group.index)
        found = kept.get(key)
        if found is None:
            ratio = self.construction.size_ratio()
            found = kept[key] = {stage: error_estimate(ratio, self.line_sine, stage)
                                 for stage in stages}
        return found


class _Groups(Mapping):
    """The solved groups' :class:`GroupMotion` by index, made when read (a motion holds no
    object that refers back to it, so it is freed as soon as it is dropped)."""

    def __init__(self, motion: Motion) -> None:
        self._motion = motion

    def __getitem__(self, index: int) -> GroupMotion:
        for group in self._motion._groups:
            if group.index == index:
                return GroupMotion(self._motion, group)
        raise KeyError(index)

    def __iter__(self) -> Iterator[int]:
        return (group.index for group in self._motion._groups)

    def __len__(self) -> int:
        return len(self._motion._groups)


class _Links(Mapping):
    """The solved links' :class:`LinkState`, made when read."""

    def __init__(self, motion: Motion, names: tuple[str, ...]) -> None:
        self._motion, self._names = motion, names

    def __getitem__(self, link: str) -> LinkState:
        if link not in self._names:
            raise KeyError(link)
        return self._motion._state(link)

    def __iter__(self) -> Iterator[str]:
        return iter(self._names)

    def __len__(self) -> int:
        return len(self._names)

    def __contains__(self, link: object) -> bool:
        return link in self._names


@dataclass(frozen=True, eq=False)
class Motion:
    """The exact kinematics of a mechanism at one or many crank angles (see the module
    docstring). ``links`` maps each solved link to its :class:`LinkState`, ``groups`` each
    solved group's index to its :class:`GroupMotion`, ``branches`` to its :class:`Branch`."""

    mechanism: Mechanism
    structure: Structure
    angles: np.ndarray
    scalar: bool
    stage: str
    branches: Mapping[int, Branch]
    solved: tuple[str, ...]
    _groups: tuple[AssurGroup, ...] = field(repr=False)
    _values: Any = field(repr=False)   # name → read-only array (see program.py's names)
    _thetas: Mapping = field(repr=False)
    _carriers: Mapping[str, tuple[str, ...]] = field(repr=False)
    #: each point of the solved links → the first of them (in file order) that carries it
    _owners: Mapping[str, str] = field(repr=False)
    #: what is computed when first read (constructions, error estimates), kept
    _kept: dict = field(repr=False, default_factory=dict, compare=False, init=False)

    @property
    def links(self) -> Mapping[str, LinkState]:
        return _Links(self, self.solved)

    @property
    def groups(self) -> Mapping[int, GroupMotion]:
        """Each solved group's :class:`GroupMotion`, by the group's index."""
        return _Groups(self)

    # -- reading -----------------------------------------------------------------------------
    def _out(self, array: np.ndarray) -> np.ndarray:
        return array[0] if self.scalar else array

    def _read(self, name: str) -> np.ndarray:
        return self._values(name)

    def _need(self, stage: str, what: str) -> None:
        if _LEVELS[self.stage] < _LEVELS[stage]:
            raise PlanmethodError(f"{what} needs the {stage} stage, but only the {self.stage} "
                                  "stage was solved")

    def _check_link(self, link: str) -> None:
        if link not in self.mechanism.links:
            raise SpecError(f"unknown link '{link}'")
        if link not in self.solved:
            raise PlanmethodError(f"link {link} was not solved in this scene")

    def _state(self, link: str) -> LinkState:
        level = _LEVELS[self.stage]
        read = self._read
        return LinkState(
            self._theta(link), read(f"origin:{link}"),
            read(f"omega:{link}") if level >= 1 else None,
            read(f"velocity:{link}") if level >= 1 else None,
            read(f"epsilon:{link}") if level >= 2 else None,
            read(f"acceleration:{link}") if level >= 2 else None, read(f"axes:{link}"))

    def link_state(self, link: str) -> LinkState:
        self._check_link(link)
        return self._state(link)

    def body(self, link: str) -> Body:
        """The link's :class:`~planmethod.kinematics.algebra.Body` (arrays)."""
        self._check_link(link)
        level, read = _LEVELS[self.stage], self._read
        axes, origin = read(f"axes:{link}"), read(f"origin:{link}")
        body = Body(axes[:, 0], axes[:, 1], origin[:, 0], origin[:, 1])
        if level >= 1:
            velocity = read(f"velocity:{link}")
            body.omega, body.vx, body.vy = read(f"omega:{link}"), velocity[:, 0], velocity[:, 1]
        if level >= 2:
            acceleration = read(f"acceleration:{link}")
            body.epsilon, body.ax, body.ay = (read(f"epsilon:{link}"), acceleration[:, 0],
                                        acceleration[:, 1])
        return body

    def locate(self, ref: str) -> tuple[str, np.ndarray]:
        """(the link whose material point ``ref`` means, its global position (N, 2)): the first
        solved link in file order that carries a point ``"C"``, or ``link`` of ``"B@link"``."""
        name, _, on = ref.partition("@")
        carriers = self._carriers.get(name)
        if not carriers:
            raise SpecError(f"unknown point '{name}'")
        solved = self.solved
        for owner in carriers:
            if owner in solved:
                break
        else:
            raise PlanmethodError(f"point {name} was not solved in this scene")
        if on:
            self._check_link(on)
            return on, self._values(f"p:{name}")
        return owner, self._values(f"p:{name}")

    def position(self, ref: str) -> np.ndarray:
        """Global position (m) of a point (``"C"``) or of a link's point under another
        (``"B@lever"``)."""
        if ref in self._owners:
            found = self._values("p:" + ref)
            return found[0] if self.scalar else found
        return self._out(self.locate(ref)[1])

    def velocity(self, ref: str) -> np.ndarray:
        """Absolute velocity (m/s) of a point."""
        return self._point_motion(ref, "velocity", "v:", LinkState.velocity_at)

    def acceleration(self, ref: str) -> np.ndarray:
        """Absolute acceleration (m/s²) of a point."""
        return self._point_motion(ref, "acceleration", "a:", LinkState.acceleration_at)

    def _point_motion(self, ref: str, stage: str, prefix: str, rigid) -> np.ndarray:
        """A named point's velocity or acceleration as solved (``prefix`` + its name), or a
        link's point under another (``"B@lever"``) by the link's rigid motion (``rigid``)."""
        if _LEVELS[self.stage] < _LEVELS[stage]:
            self._need(stage, f"the {stage} of {ref}")
        if ref in self._owners:
            found = self._values(prefix + ref)
            return found[0] if self.scalar else found
        link, position = self.locate(ref)   # a point under another, or an error
        return self._out(rigid(self._state(link), position))

    def place(self, link: str, local) -> np.ndarray:
        """Global position of the point of ``link`` at local coordinates ``local``."""
        return self._out(self.link_state(link).place(local))

    def velocity_of(self, link: str, local) -> np.ndarray:
        self._need("velocity", f"a velocity on {link}")
        state = self.link_state(link)
        return self._out(state.velocity_at(state.place(local)))

    def acceleration_of(self, link: str, local) -> np.ndarray:
        self._need("acceleration", f"an acceleration on {link}")
        state = self.link_state(link)
        return self._out(state.acceleration_at(state.place(local)))

    # -- links -----------------------------------------------------------------------------------
    def _theta(self, link: str) -> np.ndarray:
        recipe = self._thetas.get(link)
        if link == FRAME:
            return np.zeros(self.angles.shape[0])
        if recipe is None:  # the drive, or a link whose θ is a result of its own
            return self._read(f"theta:{link}")
        if recipe.kind is ThetaKind.TWO:
            first, second = self._read(f"p:{recipe.first}"), self._read(f"p:{recipe.second}")
            return np.arctan2(second[:, 1] - first[:, 1], second[:, 0] - first[:, 0]) - (
                recipe.alpha)
        if recipe.kind is ThetaKind.TIED:
            return self._theta(recipe.link) + recipe.alpha
        # ThetaKind.SPAN
        span = self._read(f"p:{recipe.first}") - self._read(f"p:{recipe.second}")
        axes = self._read(f"axes:{link}")
        c, s = axes[:, 0], axes[:, 1]
        inside_x = c * span[:, 0] + s * span[:, 1]
        inside_y = c * span[:, 1] - s * span[:, 0]
        return np.arctan2(span[:, 1], span[:, 0]) - np.arctan2(inside_y, inside_x)

    def theta(self, link: str) -> np.ndarray:
        """Global angle (rad) of the link's own +x axis."""
        self._check_link(link)
        return self._out(self._theta(link))

    def omega(self, link: str) -> np.ndarray:
        """Angular velocity (rad/s, counter-clockwise positive)."""
        self._need("velocity", f"ω of {link}")
        self._check_link(link)
        return self._out(self._read(f"omega:{link}"))

    def epsilon(self, link: str) -> np.ndarray:
        """Angular acceleration (rad/s², counter-clockwise positive)."""
        self._need("acceleration", f"ε of {link}")
        self._check_link(link)
        return self._out(self._read(f"epsilon:{link}"))

    # -- pairs and paths -------------------------------------------------------------------------
    def sliding(self, key: str) -> Sliding:
        """Travel, sliding velocity and acceleration and Coriolis term of a prismatic pair
        (``"link/along"``)."""
        slide = self.mechanism.slide(key)
        if slide is None:
            raise SpecError(f"no prismatic pair '{key}'")
        mover, guide = self.link_state(slide.link), self.link_state(slide.along)
        point = mover.place(self.mechanism.local(slide.link, slide.point))
        through = guide.place(self.mechanism.local(slide.along, slide.through))
        c, s = np.cos(slide.direction_rad), np.sin(slide.direction_rad)
        axes = guide.basis
        d = np.stack((axes[:, 0] * c - axes[:, 1] * s, axes[:, 0] * s + axes[:, 1] * c), axis=-1)
        travel = np.einsum("...i,...i->...", point - through, d)
        level = _LEVELS[self.stage]
        if level < 1:
            return Sliding(self._out(travel))
        v_rel = mover.velocity_at(point) - guide.velocity_at(point)
        ds = np.einsum("...i,...i->...", v_rel, d)
        if level < 2:
            return Sliding(self._out(travel), self._out(ds))
        coriolis = 2 * guide.omega[..., None] * perp(v_rel)
        a_rel = mover.acceleration_at(point) - guide.acceleration_at(point) - coriolis
        dds = np.einsum("...i,...i->...", a_rel, d)
        return Sliding(self._out(travel), self._out(ds), self._out(dds), self._out(coriolis))

    def moves_straight(self, ref: str) -> bool:
        """Whether the point moves on a straight line by construction: it belongs to a link
        that is held against turning by a prismatic pair with the frame."""
        name, _, on = ref.partition("@")
        carriers = (on,) if on else self.mechanism.links_with_point(name)
        return any(link == FRAME or any(FRAME in (s.link, s.along) and link in (s.link, s.along)
                                        for s in self.mechanism.slides)
                   for link in carriers)

    def curvature(self, ref: str) -> Curvature:
        """Radius ρ = v³/|v × a| and centre of curvature of the point's path."""
        self._need("acceleration", f"the curvature of {ref}'s path")
        name, _, on = ref.partition("@")
        link, position = self.locate(ref)
        if on:
            state = self._state(link)
            v, a = state.velocity_at(position), state.acceleration_at(position)
        else:
            v, a = self._read(f"v:{name}"), self._read(f"a:{name}")
        speed = norm(v)
        turn = cross(v, a)
        scale = np.maximum(speed * norm(a), np.finfo(float).tiny)
        stationary = speed <= 1e-12 * np.maximum(1.0, norm(a))
        straight = self.moves_straight(ref)
        inflection = ~stationary & (np.abs(turn) <= 1e-12 * scale)
        undefined = stationary | inflection | straight
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = np.where(undefined, np.nan, speed ** 3 / np.abs(turn))
            normal = np.sign(turn)[..., None] * perp(v / speed[..., None])
            center = np.where(undefined[..., None], np.nan, position + rho[..., None] * normal)
        return Curvature(self._out(rho), self._out(center), straight,
                         self._out(inflection & (not straight)), self._out(stationary))


# -- the solve ---------------------------------------------------------------------------------
def choose_branches(mechanism: Mechanism, structure: Structure | None = None,
                    groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]:
    """Each group's assembly at ``drive.angle``: nearest to the sketch, else the default (see
    README, "Branches"); chosen once per mechanism."""
    found = model(mechanism)
    return dict(found.branches(found.groups() if groups is None else tuple(groups)))


def _angles(mechanism: Mechanism, angles) -> tuple[bool, np.ndarray]:
    if (type(angles) is np.ndarray and angles.ndim == 1 and angles.dtype == np.float64
            and angles.flags.c_contiguous):
        return False, angles
    scalar = angles is None or np.ndim(angles) == 0
    values = np.atleast_1d(np.asarray(mechanism.drive.angle if angles is None else angles,
                                      dtype=float)).ravel()
    return scalar, np.ascontiguousarray(values)


class _Rows:
    """Reads a compiled program's result rows by name (read-only views)."""

    __slots__ = ("_read", "_rows")

    def __init__(self, program, rows: np.ndarray) -> None:
        self._rows, self._read = rows, program.read

    def __call__(self, name: str) -> np.ndarray:
        return self._read(self._rows, name)


class _Direct:
    """Reads the direct evaluation's outputs by name (read-only)."""

    __slots__ = ("_values",)

    def __init__(self, values: dict) -> None:
        for array in values.values():
            if array.flags.writeable:
                array.flags.writeable = False
        self._values = values

    def __call__(self, name: str) -> np.ndarray:
        return self._values[name]


def solve(mechanism: Mechanism, angles=None, *, stage: str = "acceleration",
          links: Iterable[str] | None = None, structure: Structure | None = None,
          branches: Mapping[int, Branch] | None = None, reference: bool = False) -> Motion:
    """Exact positions, velocities and accelerations at crank angle(s) ``angles`` (deg).

    Parameters
    ----------
    mechanism
        The model.
    angles
        One crank angle or an array of them, in degrees (default: ``drive.angle``).
    stage
        ``"position"``, ``"velocity"`` or ``"acceleration"``: the last stage computed.
    links
        Only the groups on the way to these links are solved (default: all).
    structure
        Accepted for compatibility (the mechanism's own structure is used).
    branches
        The groups' assemblies (default: chosen at ``drive.angle``, once per mechanism).
    reference
        Run the group kinds' formulas directly on numpy arrays (the reference path) instead of
        the mechanism's compiled program (the same formulas, traced once): for tests.

    Raises
    ------
    AssemblyError, ToggleError, ConvergenceError, BranchJumpError
        At the first crank angle where a group cannot be assembled, is in its toggle position,
        or (class III) does not converge or would jump to another branch.
    """
    if stage not in _LEVELS:
        raise ValueError(f"stage must be one of {STAGES}, got {stage!r}")
    found = model(mechanism)
    scalar, angles_deg = _angles(mechanism, angles)
    if not np.isfinite(angles_deg).all():
        raise SpecError("crank angles must be finite numbers")
    level = _LEVELS[stage]
    whole = found.whole.get(level) if links is None and branches is None else None
    if whole is None:
        groups = found.groups(links)
        chosen = found.branches(groups) if branches is None else {
            group.index: branches[group.index] for group in groups}
        solved = (FRAME, mechanism.drive.link, *(link for g in groups for link in g.links))
        point_owners = owners(mechanism, solved)
        if not reference:
            program, thetas = found.program(level, groups, chosen)
            if links is None and branches is None:
                found.whole[level] = (groups, chosen, program, thetas, solved, point_owners)
    else:
        groups, chosen, program, thetas, solved, point_owners = whole
    if reference:
        values, thetas = found.direct(level, groups, chosen, angles_deg)
        read = _Direct(values)
    else:
        rows = np.empty((program.layout.count, angles_deg.shape[0]))
        try:
            program.run(angles_deg, list(rows))
        except PlanmethodError:
            if angles_deg.shape[0] <= CHUNK:
                raise
            # a chunk came near a refused position: the direct evaluation over every angle
            # finds the first angle refused, group by group in build order
            found.direct(level, groups, chosen, angles_deg)
            raise
        rows.flags.writeable = False
        read = _Rows(program, rows)
    return Motion(mechanism, found.structure, angles_deg, scalar, stage, chosen, solved,
                  tuple(groups), read, thetas, found.carriers, point_owners)


def _construction(motion: Motion, group: AssurGroup) -> Construction:
    """The group's construction from the solved positions: the kind's closed form run directly
    on the motion's arrays (the same numbers)."""
    bodies = {link: motion.body(link) for link in motion.solved if link not in group.links}
    context = GroupInputs(motion.mechanism, group, bodies, motion.branches[group.index].sign,
                      motion.angles, {})
    placed = kind_module(group).place(context)
    return construction(placed, group, motion.angles.shape[0])
