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

import dataclasses
import heapq
import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import PlanmethodError, SpecError, ToggleError
from ..model import FRAME, Mechanism
from ..spec import MAX_ANGLE_DEG
from ..structure import AssurGroup, Structure
from ..vectors import cross, norm, perp
from .algebra import Body
from .groups import kind_module
from .groups.base import (
    Construction,
    GroupInputs,
    Theta,
    ThetaKind,
    construction,
    error_estimate,
)
from .program import STAGES, Branch, Result, model
from .state import LinkState
from .tracing import CHUNK

__all__ = ["FLAG_ERROR", "STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "Posed",
           "Sliding", "choose_branches", "follow", "pose", "solve"]

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

    # -- reading -----------------------------------------------------------------------------
    def _out(self, array: np.ndarray) -> np.ndarray:
        return array[0] if self.scalar else array


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
            raise SpecError(f"unknown point '{name}'")
        solved = self.solved
        for owner in carriers:
            if owner in solved:
                break
        else:
            raise PlanmethodError(f"point {name} was not solved in this scene")
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
            found = self._result.read(rows.position)
            return found[0] if self.scalar else found
        return self._out(self.locate(ref)[1])

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
            self._need(stage, f"the {stage} of {ref}")
        rows = self._result.schema.points.get(ref)
        if rows is not None:
            found = self._result.read(getattr(rows, stage))
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
        return self._out(self._theta(link))

    def omega(self, link: str) -> np.ndarray:
        """Angular velocity (rad/s, counter-clockwise positive)."""
        self._need("velocity", f"ω of {link}")
        self._check_link(link)
        return self._out(self._result.read(self._result.schema.links[link].omega))

    def epsilon(self, link: str) -> np.ndarray:
        """Angular acceleration (rad/s², counter-clockwise positive)."""
        self._need("acceleration", f"ε of {link}")
        self._check_link(link)
        return self._out(self._result.read(self._result.schema.links[link].epsilon))

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
        axes = guide.axes()
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
        return Curvature(self._out(rho), self._out(center), straight,
                         self._out(inflection & (not straight)), self._out(stationary))


# -- the solve ---------------------------------------------------------------------------------
def choose_branches(mechanism: Mechanism, structure: Structure | None = None,
                    groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]:
    """Each group's assembly at ``drive.angle``: nearest to the sketch, else the default (see
    docs/exercise-file.md, "Branches"); chosen once per mechanism."""
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
    if links is None and branches is None:
        program = found.program(level)
    else:
        groups = found.groups(links)
        program = found.program(level, groups, found.branches(groups) if branches is None else {
            group.index: branches[group.index] for group in groups})
    if reference:
        result = program.direct(angles_deg)
    else:
        try:
            result = program.run(angles_deg)
        except PlanmethodError:
            if angles_deg.shape[0] <= CHUNK:
                raise
            # a chunk came near a refused position: the direct evaluation over every angle
            # finds the first angle refused, group by group in build order
            program.direct(angles_deg)
            raise
    return Motion(mechanism, found.structure, angles_deg, scalar, stage, program.branches,
                  result.schema.solved, result, found.carriers)


# -- following the assembly from drive.angle to another crank angle --------------------------
#: the crank-angle step (deg) of the sweep that follows the assembly from ``drive.angle``
FOLLOW_STEP_DEG = 1.0
#: angles per refinement of a stretch of that sweep where a group may meet its limit position
FOLLOW_POINTS = 16
#: stretches are refined down to this width (deg)
FOLLOW_FLOOR_DEG = 1e-10
#: the most stretches refined in one :func:`follow`
FOLLOW_REFINEMENTS = 256


@dataclass(frozen=True, slots=True)
class Posed:
    """A mechanism posed at another crank angle on the assembly followed from its own
    ``drive.angle`` (``start``): its ``drive.angle`` is the new angle and its sketch holds the
    followed positions of every point of its groups, so that any solve of it at its
    ``drive.angle`` takes that assembly. ``branches``: its groups' branches, each with the
    reason it was chosen for at ``start`` (``sketch``, ``default``, ``unique``)."""

    mechanism: Mechanism
    branches: Mapping[int, Branch]
    start: float


def _path_order(start: float, angles: np.ndarray) -> np.ndarray:
    return np.abs(angles - start)


def _doubtful(sine: np.ndarray) -> np.ndarray:
    """The stretches [k, k + 1] of a sweep (uniform steps) where a dyad may meet its limit
    position between the samples: its lines' sine s changes sign there, or s², extrapolated
    linearly from a neighbouring stretch over twice the step, reaches zero across it (near a
    limit position s² falls linearly with the crank angle; an ordinary minimum of s is
    resolved by the samples and extrapolates to a positive value)."""
    sine = np.asarray(sine, dtype=float)
    square = sine * sine
    doubtful = sine[:-1] * sine[1:] <= 0.0
    if sine.shape[0] >= 3:
        doubtful[1:] |= 3.0 * square[1:-1] - 2.0 * square[:-2] <= 0.0     # from the left
        doubtful[:-1] |= 3.0 * square[1:-1] - 2.0 * square[2:] <= 0.0     # from the right
    return np.flatnonzero(doubtful)


def _solvable_prefix(mechanism: Mechanism, angles: np.ndarray, links, stage: str
                     ) -> tuple[Motion | None, int, PlanmethodError | None]:
    """(the motion over the longest prefix of ``angles`` that solves, its length, the error at
    the next angle or None)."""
    try:
        return solve(mechanism, angles, stage=stage, links=links), angles.shape[0], None
    except PlanmethodError:
        pass
    good, bad = 0, angles.shape[0]          # angles[:good] solves, angles[:bad] does not
    while bad - good > 1:
        middle = (good + bad) // 2
        try:
            solve(mechanism, angles[:middle], stage=stage, links=links)
            good = middle
        except PlanmethodError:
            bad = middle
    motion = solve(mechanism, angles[:good], stage=stage, links=links) if good else None
    try:
        solve(mechanism, angles[good:good + 1], stage=stage, links=links)
    except PlanmethodError as error:
        return motion, good, error
    # the angle solves alone (a chunk's refusal): take the error of the prefix
    try:
        solve(mechanism, angles[:good + 1], stage=stage, links=links)
    except PlanmethodError as error:
        return motion, good, error
    raise PlanmethodError("internal error: a refused prefix solves")  # pragma: no cover


def follow(mechanism: Mechanism, angle: float, *, links: Iterable[str] | None = None) -> None:
    """Check that each group's assembly chosen at ``drive.angle`` can be followed to crank
    angle ``angle`` (deg), turning the crank from ``drive.angle`` to ``angle`` (as numbers, not
    modulo 360°), as a sweep follows it.

    A dyad's assembly is its branch sign, the same at every angle: what is checked is that no
    group whose assembly was chosen among several (nor a group it rests on) meets a limit
    (toggle) position on the way. The way is swept every
    :data:`FOLLOW_STEP_DEG` (one turn at most: a dyad's positions repeat every turn) with the
    compiled program, to the velocity stage (each dyad's sine s of the angle between its
    construction lines), and refined only where a dyad's s may reach zero between two samples
    (:func:`_doubtful`). A class III group follows its own continuation path.

    Parameters
    ----------
    mechanism
        The model (its ``drive.angle`` is where the assemblies were chosen).
    angle
        The crank angle to follow the assembly to (deg).
    links
        Only the groups on the way to these links (default: all).

    Raises
    ------
    ToggleError
        Where a dyad meets a limit (toggle) position on the way: the message names the group,
        the crank angle of the limit (to 1e-9°) and why the group cannot go on.
    AssemblyError, ConvergenceError, BranchJumpError
        As :func:`solve`, where the mechanism cannot be assembled at ``drive.angle`` or a class
        III group cannot be continued.

    Examples
    --------
    >>> from planmethod.spec import exercise_from_dict
    >>> rocker = exercise_from_dict({
    ...     "drive": {"link": "AB", "pivot": "A", "angle": 60, "omega": 1},
    ...     "links": {"frame": {"A": [0, 0], "D": [0.30, 0]},
    ...               "AB": {"A": [0, 0], "B": [0.20, 0]},
    ...               "BC": {"B": [0, 0], "C": [0.22, 0]},
    ...               "CD": {"C": [0, 0], "D": [0.18, 0]}}}).mechanism
    >>> follow(rocker, 90.0)
    >>> follow(rocker, 150.0)
    Traceback (most recent call last):
    ...
    planmethod.errors.ToggleError: link BC+CD, crank angle 104.478°: the assembly chosen at \
drive.angle 60° cannot be followed to 150°: turning the crank from 60°, the group reaches \
a limit (toggle) position at crank angle 104.477512°, past which its assembly cannot be \
followed (just beyond: ... short by ... m)
    """
    start, angle = float(mechanism.drive.angle), float(angle)
    span = angle - start
    if span == 0.0:
        return
    width = min(abs(span), 360.0)
    count = max(2, math.ceil(width / FOLLOW_STEP_DEG - 1e-9) + 1)
    grid = start + math.copysign(1.0, span) * np.linspace(0.0, width, count)
    if abs(span) <= 360.0:
        grid[-1] = angle
    found = model(mechanism)
    # the groups whose assembly was chosen among several (with what they rest on): a dyad with
    # one assembly has nothing to follow
    chosen = [link for group in found.groups(links)
              if not group.is_dyad or kind_module(group).branches > 1 for link in group.links]
    if not chosen:
        return
    links = chosen
    dyads = [group.index for group in found.groups(links) if group.is_dyad]
    failure: tuple[float, float, PlanmethodError] | None = None   # (last good, bad, error)
    stretches = [(0.0, 0, grid)]   # (distance along the way, tie-break, angles), nearest first
    refinements = 0
    while stretches:
        _, _, angles = heapq.heappop(stretches)
        if failure is not None:                 # only what lies before the failure found
            before = _path_order(start, angles) < _path_order(start, np.array([failure[1]]))
            angles = angles[before]
            if angles.shape[0] < 2:
                continue
        motion, good, error = _solvable_prefix(mechanism, angles, links, "velocity")
        if error is not None:
            if good == 0:   # the start of the stretch was solved before, or is drive.angle
                raise error
            failure = (float(angles[good - 1]), float(angles[good]), error)
            angles = angles[:good]
        if motion is None or angles.shape[0] < 2:
            continue
        for index in dyads:
            sine = np.atleast_1d(motion.groups[index].line_sine)[:angles.shape[0]]
            for k in _doubtful(sine):
                low, high = float(angles[k]), float(angles[k + 1])
                if abs(high - low) <= FOLLOW_FLOOR_DEG or refinements >= FOLLOW_REFINEMENTS:
                    continue
                refinements += 1
                heapq.heappush(stretches, (abs(low - start), refinements,
                                           np.linspace(low, high, FOLLOW_POINTS + 1)))
    if failure is not None:
        _raise_limit(mechanism, found, links, start, angle, *failure)


def _raise_limit(mechanism: Mechanism, found, links, start: float, angle: float, good: float,
                 bad: float, error: PlanmethodError) -> None:
    """Raise the error of a group that cannot be followed past a crank angle between ``good``
    (solved) and ``bad`` (refused with ``error``): a dyad's limit position, found to 1e-9°;
    a class III group's own continuation error as it is."""
    group = next((g for g in found.structure.groups if g.name == error.link), None)
    if group is None or not group.is_dyad:
        raise error
    stage = "velocity"
    try:   # where the links no longer reach, the limit itself is found by the positions
        solve(mechanism, bad, stage="position", links=links)
    except PlanmethodError as refused:
        stage, error = "position", refused
    while abs(bad - good) > 1e-9:
        middle = 0.5 * (good + bad)
        try:
            solve(mechanism, middle, stage=stage, links=links)
            good = middle
        except PlanmethodError as refused:
            bad, error = middle, refused
    refused_group = next((g for g in found.structure.groups if g.name == error.link), group)
    raise ToggleError(
        f"the assembly chosen at drive.angle {start:g}° cannot be followed to {angle:g}°: "
        f"turning the crank from {start:g}°, the group reaches a limit (toggle) position at "
        f"crank angle {good:.9g}°, past which its assembly cannot be followed (just beyond: "
        f"{error.message})", line_angle_deg=0.0, link=refused_group.name, angle=good)


def pose(mechanism: Mechanism, angle: float, *, links: Iterable[str] | None = None) -> Posed:
    """The mechanism posed at crank angle ``angle`` (deg) on the assembly chosen at its
    ``drive.angle`` and followed to ``angle`` as a sweep follows it (:func:`follow`), rather
    than chosen again there from a sketch made for ``drive.angle``.

    Parameters
    ----------
    mechanism
        The model.
    angle
        The crank angle (deg), within ±36,000° as ``drive.angle``.
    links
        Only the groups on the way to these links are followed and checked (default: all);
        the positions of the others are posed where they can be assembled.

    Raises
    ------
    SpecError
        If ``angle`` is not a finite number within ±36,000°.
    ToggleError, AssemblyError, ConvergenceError, BranchJumpError
        As :func:`follow`.

    Examples
    --------
    A Whitworth quick-return whose sketch, made for ``drive.angle`` = 30°, is nearer the other
    assembly of its slotted lever at 250°: posed there, the lever keeps the assembly a sweep
    from 30° follows.

    >>> from planmethod.spec import load_exercise
    >>> mechanism = load_exercise("tests/data/continuation/whitworth_quick_return.toml").mechanism
    >>> posed = pose(mechanism, 250.0)
    >>> posed.mechanism.drive.angle, posed.branches[0]
    (250.0, Branch(sign=1, reason='sketch'))
    >>> solve(posed.mechanism).position("C").round(4)
    array([-0.0642, -0.1414])
    >>> solve(mechanism, 250.0).position("C").round(4)   # as a sweep from 30° finds it
    array([-0.0642, -0.1414])
    """
    start = float(mechanism.drive.angle)
    if not (math.isfinite(angle) and abs(angle) <= MAX_ANGLE_DEG):
        raise SpecError(f"the crank angle must be a finite number of degrees within "
                        f"±{MAX_ANGLE_DEG:g}°, got {angle!r}")
    angle = float(angle)
    found = model(mechanism)
    groups = found.groups(links)
    try:
        original = found.branches(groups)
    except PlanmethodError as error:
        if angle != start and error.angle == start:   # say why that angle, not the one asked
            error.message += (f" (at drive.angle, where the assembly followed to {angle:g}° "
                              "is chosen)")
            error.args = (str(error),)
        raise
    if angle == start:
        return Posed(mechanism, original, start)
    follow(mechanism, angle, links=links)
    try:   # every group's points, where the whole mechanism assembles at the angle
        here = solve(mechanism, angle, stage="position")
    except PlanmethodError:
        here = solve(mechanism, angle, stage="position", links=links)
    fixed = (FRAME, mechanism.drive.link)
    points = {point: tuple(float(v) for v in here.position(point))
              for link in here.solved if link not in fixed
              for point in mechanism.links[link].points}
    posed = dataclasses.replace(mechanism, drive=dataclasses.replace(mechanism.drive,
                                                                     angle=angle),
                                sketch={**mechanism.sketch, **points})
    chosen = model(posed).branches(groups)
    branches = {index: dataclasses.replace(branch, reason=original[index].reason)
                for index, branch in chosen.items()}
    if not all(group.is_dyad for group in groups):
        # a dyad's assembly nearest its exact positions is that one; a class III group's is
        # the nearest its search found at the angle: make sure it found the followed one
        check = solve(posed, angle, stage="position", links=links, branches=branches,
                      reference=True)
        size = max(math.hypot(*xy) for xy in points.values())
        for point, xy in points.items():
            away = (math.dist(check.position(point), xy)
                    if point in check._result.schema.points else 0.0)
            if away > 1e-9 * size:
                raise PlanmethodError(
                    f"the assembly followed from drive.angle {start:g}° is not among the "
                    f"assemblies found at crank angle {angle:g}° (point {point} is "
                    f"{away:.3g} m away)", angle=angle)
    return Posed(posed, branches, start)


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
