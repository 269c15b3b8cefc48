"""The exact kinematics of a whole mechanism over any number of crank angles: :class:`Motion`.

:func:`solve` runs the mechanism's compiled program (:mod:`~planmethod.kinematics.program`: the
group kinds' closed forms, traced once per mechanism into one straight-line numpy function) at
the crank angles and returns a :class:`Motion`: every solved link's pose, ω, ε and origin
velocity and acceleration at each angle, from which any point, any point of a link coincident
with another point (``B@lever``), sliding quantities and the curvature of a path are read — as
arrays over the angles, one angle or a million alike. :meth:`Motion.at` reads the same at one
of the angles (:class:`MotionAt`).

A :class:`Motion` is a value: its arrays are read-only, and what it returns are read-only views
of them (copy one to change it).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
>>> motion = solve(exercise.mechanism)          # at drive.angle: one angle
>>> motion.velocity("C").round(4)
array([[-5.2716,  0.    ]])
>>> here = motion.at(0)
>>> round(float(abs(here.velocity("C")[0])), 4), round(float(here.omega("BC")), 3)
(5.2716, -24.254)
>>> round(float(here.curvature("D").rho), 5)
0.07377
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import PlanmethodError, SpecError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Structure
from ..vectors import cross, norm, perp
from ..words.message import message, template
from ..words.render import render
from .algebra import Body
from .groups import kind_module
from .groups.base import GroupInputs, Theta, ThetaKind
from .groups.checks import error_estimate
from .groups.dyad import Construction, construction
from .program import STAGES, Branch, Result, model
from .state import LinkState
from .tracing import CHUNK

__all__ = ["STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "MotionAt", "Sliding",
           "choose_branches", "solve"]

_LEVELS = {stage: level for level, stage in enumerate(STAGES)}
#: what a reading needs a stage for, by the reading (its ``{subject}``: a point or a link)
_NEEDS = {"velocity": template("the velocity of {subject}"),
          "acceleration": template("the acceleration of {subject}"),
          "velocity_of": template("a velocity on {subject}"),
          "acceleration_of": template("an acceleration on {subject}"),
          "omega": template("ω of {subject}"), "epsilon": template("ε of {subject}"),
          "curvature": template("the curvature of {subject}'s path")}


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
    kinematics.groups.dyad.Construction` (what the plans draw; None for a higher group) and
    ``error_estimate``, the estimated relative error of its velocities and accelerations near
    its toggle, ε·R/s³ and ε·R/s⁵ (per stage solved)."""

    __slots__ = ("_group", "_motion", "line_sine")

    def __init__(self, motion: Motion, group: AssurGroup) -> None:
        self._motion, self._group = motion, group
        sine = motion._result.schema.sines.get(group.index)
        self.line_sine = motion._result.read(sine) if sine is not None else None

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
        for group in self._motion._result.schema.groups:
            if group.index == index:
                return GroupMotion(self._motion, group)
        raise KeyError(index)

    def __iter__(self) -> Iterator[int]:
        return (group.index for group in self._motion._result.schema.groups)

    def __len__(self) -> int:
        return len(self._motion._result.schema.groups)


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
    """The exact kinematics of a mechanism at N crank angles ``angles`` (deg; see the module
    docstring): what it returns is an array over the angles — a scalar quantity (N,), a vector
    (N, 2). ``links`` maps each solved link to its :class:`LinkState`, ``groups`` each solved
    group's index to its :class:`GroupMotion`, ``branches`` to its :class:`Branch`;
    :meth:`at` reads one angle."""

    mechanism: Mechanism
    structure: Structure
    angles: np.ndarray
    stage: str
    branches: Mapping[int, Branch]
    solved: tuple[str, ...]
    #: what the program wrote, read through its schema
    _result: Result = field(repr=False)
    #: each point → the links that carry it, in file order
    _carriers: Mapping[str, tuple[str, ...]] = field(repr=False)
    #: what is computed when first read (constructions, error estimates), kept
    _kept: dict = field(repr=False, default_factory=dict, compare=False, init=False)

    @property
    def links(self) -> Mapping[str, LinkState]:
        return _Links(self, self.solved)

    @property
    def groups(self) -> Mapping[int, GroupMotion]:
        """Each solved group's :class:`GroupMotion`, by the group's index."""
        return _Groups(self)

    def at(self, index: int) -> MotionAt:
        """The motion at one of its crank angles, ``angles[index]``."""
        return MotionAt(self, index)

    # -- reading -----------------------------------------------------------------------------

    def _need(self, stage: str, reading: str, subject: str) -> None:
        """Refuse ``reading`` (a key of :data:`_NEEDS`) of ``subject`` unless ``stage`` was
        solved."""
        if _LEVELS[self.stage] < _LEVELS[stage]:
            raise PlanmethodError(message(
                "{what} needs the {stage} stage, but only the {solved} stage was solved",
                what=_NEEDS[reading].replace(subject=subject), stage=stage, solved=self.stage))

    def _check_link(self, link: str) -> None:
        if link not in self.mechanism.links:
            raise SpecError(message("unknown link '{link}'", link=link))
        if link not in self.solved:
            raise PlanmethodError(message("link {link} was not solved in this scene",
                                          link=link))

    def _state(self, link: str) -> LinkState:
        """The link's :class:`LinkState`, made once (its arrays read-only: it is shared)."""
        key = ("state", link)
        found = self._kept.get(key)
        if found is not None:
            return found
        rows, read = self._result.schema.links[link], self._result.read
        theta = self._theta(link)
        theta.flags.writeable = False
        found = self._kept[key] = LinkState(
            theta, read(rows.origin),
            None if rows.omega is None else read(rows.omega),
            None if rows.velocity is None else read(rows.velocity),
            None if rows.epsilon is None else read(rows.epsilon),
            None if rows.acceleration is None else read(rows.acceleration), read(rows.axes))
        return found

    def link_state(self, link: str) -> LinkState:
        self._check_link(link)
        return self._state(link)

    def body(self, link: str) -> Body:
        """The link's :class:`~planmethod.kinematics.algebra.Body` (arrays)."""
        self._check_link(link)
        return self._result.body(link)

    def locate(self, ref: str) -> tuple[str, np.ndarray]:
        """(the link whose material point ``ref`` means, its global position (N, 2)): the first
        solved link in file order that carries a point ``"C"``, or ``link`` of ``"B@link"``."""
        name, _, on = ref.partition("@")
        carriers = self._carriers.get(name)
        if not carriers:
            raise SpecError(message("unknown point '{point}'", point=name))
        solved = self.solved
        for owner in carriers:
            if owner in solved:
                break
        else:
            raise PlanmethodError(message("point {point} was not solved in this scene",
                                          point=name))
        position = self._result.read(self._result.schema.points[name].position)
        if on:
            self._check_link(on)
            return on, position
        return owner, position

    def position(self, ref: str) -> np.ndarray:
        """Global position (m) of a point (``"C"``) or of a link's point under another
        (``"B@lever"``)."""
        rows = self._result.schema.points.get(ref)
        if rows is not None:
            return self._result.read(rows.position)
        return self.locate(ref)[1]

    def velocity(self, ref: str) -> np.ndarray:
        """Absolute velocity (m/s) of a point."""
        return self._point_motion(ref, "velocity", LinkState.velocity_at)

    def acceleration(self, ref: str) -> np.ndarray:
        """Absolute acceleration (m/s²) of a point."""
        return self._point_motion(ref, "acceleration", LinkState.acceleration_at)

    def _point_motion(self, ref: str, stage: str, rigid) -> np.ndarray:
        """A named point's velocity or acceleration (``stage``) as solved, or a link's point
        under another (``"B@lever"``) by the link's rigid motion (``rigid``)."""
        if _LEVELS[self.stage] < _LEVELS[stage]:
            self._need(stage, stage, ref)
        rows = self._result.schema.points.get(ref)
        if rows is not None:
            return self._result.read(getattr(rows, stage))
        link, position = self.locate(ref)   # a point under another, or an error
        return rigid(self._state(link), position)

    def place(self, link: str, local) -> np.ndarray:
        """Global position of the point of ``link`` at local coordinates ``local``."""
        return self.link_state(link).place(local)

    def velocity_of(self, link: str, local) -> np.ndarray:
        self._need("velocity", "velocity_of", link)
        state = self.link_state(link)
        return state.velocity_at(state.place(local))

    def acceleration_of(self, link: str, local) -> np.ndarray:
        self._need("acceleration", "acceleration_of", link)
        state = self.link_state(link)
        return state.acceleration_at(state.place(local))

    # -- links -----------------------------------------------------------------------------------
    def _theta(self, link: str) -> np.ndarray:
        schema = self._result.schema
        recipe = schema.recipes.get(link)
        if link == FRAME:
            return np.zeros(self.angles.shape[0])
        if recipe is None:  # the drive, or a link whose θ is a result of its own
            return self._result.read(schema.thetas[link])
        return _THETA_READERS[recipe.kind](self, link, recipe)

    def _at(self, point: str) -> np.ndarray:
        """A named point's position (N, 2)."""
        return self._result.read(self._result.schema.points[point].position)

    def _theta_two(self, link: str, recipe: Theta) -> np.ndarray:
        first, second = self._at(recipe.first), self._at(recipe.second)
        return np.arctan2(second[:, 1] - first[:, 1], second[:, 0] - first[:, 0]) - recipe.alpha

    def _theta_tied(self, link: str, recipe: Theta) -> np.ndarray:
        return self._theta(recipe.link) + recipe.alpha

    def _theta_span(self, link: str, recipe: Theta) -> np.ndarray:
        span = self._at(recipe.first) - self._at(recipe.second)
        axes = self._result.read(self._result.schema.links[link].axes)
        c, s = axes[:, 0], axes[:, 1]
        inside_x = c * span[:, 0] + s * span[:, 1]
        inside_y = c * span[:, 1] - s * span[:, 0]
        return np.arctan2(span[:, 1], span[:, 0]) - np.arctan2(inside_y, inside_x)

    def theta(self, link: str) -> np.ndarray:
        """Global angle (rad) of the link's own +x axis."""
        self._check_link(link)
        return self._theta(link)

    def omega(self, link: str) -> np.ndarray:
        """Angular velocity (rad/s, counter-clockwise positive)."""
        self._need("velocity", "omega", link)
        self._check_link(link)
        return self._result.read(self._result.schema.links[link].omega)

    def epsilon(self, link: str) -> np.ndarray:
        """Angular acceleration (rad/s², counter-clockwise positive)."""
        self._need("acceleration", "epsilon", link)
        self._check_link(link)
        return self._result.read(self._result.schema.links[link].epsilon)

    # -- pairs and paths -------------------------------------------------------------------------
    def sliding(self, key: str) -> Sliding:
        """Travel, sliding velocity and acceleration and Coriolis term of a prismatic pair
        (``"link/along"``)."""
        slide = self.mechanism.slide(key)
        if slide is None:
            raise SpecError(message("no prismatic pair '{pair}'", pair=key))
        mover, guide = self.link_state(slide.link), self.link_state(slide.along)
        point = mover.place(self.mechanism.local(slide.link, slide.point))
        through = guide.place(self.mechanism.local(slide.along, slide.through))
        c, s = np.cos(slide.direction_rad), np.sin(slide.direction_rad)
        axes = guide.axes()
        d = np.stack((axes[:, 0] * c - axes[:, 1] * s, axes[:, 0] * s + axes[:, 1] * c), axis=-1)
        travel = np.einsum("...i,...i->...", point - through, d)
        level = _LEVELS[self.stage]
        if level < 1:
            return Sliding(travel)
        v_rel = mover.velocity_at(point) - guide.velocity_at(point)
        ds = np.einsum("...i,...i->...", v_rel, d)
        if level < 2:
            return Sliding(travel, ds)
        coriolis = 2 * guide.omega[..., None] * perp(v_rel)
        a_rel = mover.acceleration_at(point) - guide.acceleration_at(point) - coriolis
        dds = np.einsum("...i,...i->...", a_rel, d)
        return Sliding(travel, ds, dds, coriolis)

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
        self._need("acceleration", "curvature", ref)
        name, _, on = ref.partition("@")
        link, position = self.locate(ref)
        if on:
            state = self._state(link)
            v, a = state.velocity_at(position), state.acceleration_at(position)
        else:
            rows = self._result.schema.points[name]
            v, a = self._result.read(rows.velocity), self._result.read(rows.acceleration)
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
        return Curvature(rho, center, straight, inflection & (not straight), stationary)


# -- one angle -----------------------------------------------------------------------------------
class MotionAt:
    """A :class:`Motion` at one of its crank angles (``motion.at(index)``): the same readers,
    each giving the value at that angle — a number, or a vector of shape (2,)."""

    __slots__ = ("angle", "index", "motion")

    def __init__(self, motion: Motion, index: int) -> None:
        self.motion, self.index = motion, index
        #: the crank angle (deg)
        self.angle = float(motion.angles[index])

    def position(self, ref: str) -> np.ndarray:
        """Global position (m) of a point (see :meth:`Motion.position`)."""
        return self.motion.position(ref)[self.index]

    def velocity(self, ref: str) -> np.ndarray:
        """Absolute velocity (m/s) of a point."""
        return self.motion.velocity(ref)[self.index]

    def acceleration(self, ref: str) -> np.ndarray:
        """Absolute acceleration (m/s²) of a point."""
        return self.motion.acceleration(ref)[self.index]

    def place(self, link: str, local) -> np.ndarray:
        """Global position of the point of ``link`` at local coordinates ``local``."""
        return self.motion.place(link, local)[self.index]

    def theta(self, link: str) -> np.float64:
        """Global angle (rad) of the link's own +x axis."""
        return self.motion.theta(link)[self.index]

    def omega(self, link: str) -> np.float64:
        """Angular velocity (rad/s, counter-clockwise positive)."""
        return self.motion.omega(link)[self.index]

    def epsilon(self, link: str) -> np.float64:
        """Angular acceleration (rad/s², counter-clockwise positive)."""
        return self.motion.epsilon(link)[self.index]

    def sliding(self, key: str) -> Sliding:
        """A prismatic pair's travel, sliding velocity and acceleration and Coriolis term."""
        found, index = self.motion.sliding(key), self.index
        return Sliding(*(None if value is None else value[index] for value in (
            found.s, found.velocity, found.acceleration, found.coriolis)))

    def curvature(self, ref: str) -> Curvature:
        """Radius ρ and centre of curvature of the point's path."""
        found, index = self.motion.curvature(ref), self.index
        return Curvature(found.rho[index], found.center[index], found.straight,
                         found.inflection[index], found.stationary[index])


# -- the solve ---------------------------------------------------------------------------------
def choose_branches(mechanism: Mechanism, groups: Iterable[AssurGroup] | None = None
                    ) -> dict[int, Branch]:
    """Each group's assembly at ``drive.angle`` (of ``groups``, default all): nearest to the
    sketch, else the default (see docs/exercise-file.md, "Branches"); chosen once per
    mechanism."""
    found = model(mechanism)
    return dict(found.branches(found.groups() if groups is None else tuple(groups)))


def _angles(mechanism: Mechanism, angles) -> np.ndarray:
    if (type(angles) is np.ndarray and angles.ndim == 1 and angles.dtype == np.float64
            and angles.flags.c_contiguous):
        return angles
    values = np.atleast_1d(np.asarray(mechanism.drive.angle if angles is None else angles,
                                      dtype=float)).ravel()
    return np.ascontiguousarray(values)


def solve(mechanism: Mechanism, angles=None, *, stage: str = "acceleration",
          links: Iterable[str] | None = None, branches: Mapping[int, Branch] | None = None,
          reference: bool = False) -> Motion:
    """Exact positions, velocities and accelerations at crank angles ``angles`` (deg).

    Parameters
    ----------
    mechanism
        The model.
    angles
        The crank angles in degrees: an array of them, or one (default: ``drive.angle``);
        the motion is over an array of angles either way (one angle: :meth:`Motion.at`).
    stage
        ``"position"``, ``"velocity"`` or ``"acceleration"``: the last stage computed.
    links
        Only the groups on the way to these links are solved (default: all).
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
        raise ValueError(render(message("stage must be one of {stages}, got {stage!r}",
                                        stages=str(STAGES), stage=stage)))
    found = model(mechanism)
    angles_deg = _angles(mechanism, angles)
    if not np.isfinite(angles_deg).all():
        raise SpecError(message("crank angles must be finite numbers"))
    level = _LEVELS[stage]
    if reference:
        return _reference_motion(mechanism, angles_deg, stage, links, branches)
    if links is None and branches is None:
        program = found.program(level)
    else:
        groups = found.groups(links)
        program = found.program(level, groups, found.branches(groups) if branches is None else {
            group.index: branches[group.index] for group in groups})
    try:
        result = program.run(angles_deg)
    except PlanmethodError:
        if angles_deg.shape[0] <= CHUNK:
            raise
        # a chunk came near a refused position: the direct evaluation over every angle
        # finds the first angle refused, group by group in build order
        program.direct(angles_deg)
        raise
    return Motion(mechanism, found.structure, angles_deg, stage, program.branches,
                  result.schema.solved, result, found.carriers)


def _reference_motion(mechanism: Mechanism, angles_deg: np.ndarray, stage: str, links,
                      branches: Mapping[int, Branch] | None) -> Motion:
    """The motion :func:`solve` gives with ``reference``: the group kinds' formulas run
    directly, with no program compiled (a posed mechanism's check compiles none)."""
    found = model(mechanism)
    groups = found.groups(links)
    chosen = dict(found.branches(groups) if branches is None else {
        group.index: branches[group.index] for group in groups})
    result = found.direct(_LEVELS[stage], groups, chosen, angles_deg)
    return Motion(mechanism, found.structure, angles_deg, stage, chosen,
                  result.schema.solved, result, found.carriers)


#: how a link's θ is read from the solved points, by the recipe's kind
_THETA_READERS = {ThetaKind.TWO: Motion._theta_two, ThetaKind.TIED: Motion._theta_tied,
                  ThetaKind.SPAN: Motion._theta_span}


def _construction(motion: Motion, group: AssurGroup) -> Construction:
    """The group's construction from the solved positions: the kind's closed form run directly
    on the motion's arrays (the same numbers)."""
    bodies = {link: motion.body(link) for link in motion.solved if link not in group.links}
    context = GroupInputs(motion.mechanism, group, bodies, motion.branches[group.index].sign,
                      motion.angles, {})
    placed = kind_module(group).place(context)
    return construction(placed, group, motion.angles.shape[0])
