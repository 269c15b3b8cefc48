"""What every group kind shares: the context its formulas see, the two vector equations of a
dyad and their exact solve, the checks that refuse a position, and the protocols through which
the plans and the force analysis run a kind's own construction steps.

A dyad kind (:mod:`~planmethod.kinematics.groups.rrr` …) writes one function, ``place(context)``:
its closed-form positions, and its two vector equations as two :class:`Side` — the statement a
student writes on the plan,

    v_X = v_base1 + u1·e1 = v_base2 + u2·e2,

where a *rotation* side has e = J·(X − centre) and u = ω of the turning link, and a *sliding*
side has e along the guide and u the relative sliding speed. Everything after the positions is
the same for every dyad (:func:`evaluate_dyad`): the 2 × 2 solve by Cramer's rule (parallel
lines are the group's toggle), the normal (−ω²·r) and Coriolis (2ω × v_rel) terms of the
accelerations, each link's ω and ε, its origin's velocity and acceleration. The plan emulator
draws the same two sides (:func:`construction`).

The formulas run on floats, numpy arrays or traced values (:mod:`planmethod.kinematics.algebra`);
checks go through :meth:`GroupInputs.guard`: a cheap bound at every evaluation, the exact check
(which raises the error) only where the bound fails.

Examples
--------
>>> axes_towards(Vec(0.0, 2.0), (0.0, 0.0), (0.5, 0.0), 2.0)  # a link along +y
(0.0, 1.0)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable, Iterable, Mapping
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any, NamedTuple, Protocol

import numpy as np

from ... import vectors
from ...errors import AssemblyError, StructureError, ToggleError
from ...model import Mechanism, Slide
from ...structure import AssurGroup, Joint, Structure
from ...vocabulary import STAGE_PLURAL, EdgeKind
from ..algebra import Body, Number, Vec, cross, dot
from ..tracing import Traced

__all__ = [
    "EPS",
    "ROUNDING_UNITS",
    "TOGGLE_SINE",
    "Anchor",
    "Branch",
    "Construction",
    "DyadRates",
    "ForceSolver",
    "GroupInputs",
    "KindModel",
    "Pin",
    "Placed",
    "PlanDrawer",
    "Side",
    "SolvedGroup",
    "Theta",
    "ThetaKind",
    "evaluate_dyad",
    "sense",
    "split",
    "turned_axes",
]

#: the arithmetic's resolution (unit roundoff)
EPS = float(np.finfo(float).eps)
#: a vanishing factor within this many units of its own rounding error of zero is a toggle
#: position (the two assemblies coincide), not a failure to assemble
ROUNDING_UNITS = 16.0
#: below this |sin| of the angle between two guides a PRP or RPP dyad has no definite position
TOGGLE_SINE = 1e-10
#: the margin by which a guard's bound is widened, so that its rounding never hides an angle the
#: exact check refuses
MARGIN = 1.0 + 1e-6


@dataclass(frozen=True, slots=True)
class Branch:
    """The assembly a group takes: ``sign`` (±1 for a dyad, the assembly's number for a higher
    group; see docs/exercise-file.md) and why (``sketch``, ``default`` or ``unique``)."""

    sign: int
    reason: str


# -- the context -----------------------------------------------------------------------------
class KindModel(Protocol):
    """What a higher group kind is given of the mechanism's model
    (:class:`planmethod.kinematics.program.Model`): the mechanism and its structure, the
    branches chosen at ``drive.angle``, the direct evaluation of the groups before it, the
    model of a sibling mechanism (the same at unit crank speed), and ``memo``, where a kind
    keeps what it finds once per model (its assemblies, its continuation path)."""

    mechanism: Mechanism
    structure: Structure
    memo: dict[Hashable, object]

    def sibling(self, mechanism: Mechanism) -> KindModel: ...

    def branches(self, groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]: ...

    def bodies(self, level: int, groups: tuple[AssurGroup, ...],
               branches: Mapping[int, Branch], angles_deg: np.ndarray) -> dict[str, Body]: ...


@dataclass(frozen=True, slots=True)
class Pin:
    """A revolute pair of a group with a known link: ``link`` (of the group) carries the pin at
    local ``local``; ``known`` carries it at ``known_local``; ``at`` is its global position and
    ``offset`` its offset from the known link's origin."""

    joint: Joint
    link: str
    known: str
    local: tuple[float, float]
    known_local: tuple[float, float]
    at: Vec
    offset: Vec
    bound: float | None


class Dyad(NamedTuple):
    """A dyad's pairs and links: ``link1`` is joined to a known link by ``external1`` and to
    ``link2`` by ``internal``; ``link2`` to a known link by ``external2`` (a prismatic pair's
    guide may be on either side)."""

    external1: Joint
    internal: Joint
    external2: Joint
    link1: str
    link2: str


class GroupInputs:
    """What a group kind's formulas see: the model, the group, its branch ``sign``, the bodies
    of the links known so far (and of the group's links once placed), the crank angles (deg),
    and :meth:`guard`. ``bounds`` holds, where known, an upper bound of the distance of a named
    point from the global origin over every assembled position."""

    def __init__(self, mechanism: Mechanism, group: AssurGroup, bodies: dict[str, Body],
                 sign: float, angles, bounds: dict[str, float]) -> None:
        self.mechanism, self.group, self.sign = mechanism, group, float(sign)
        self.bodies, self.angles, self.bounds = bodies, angles, bounds

    def local(self, link: str, point: str) -> tuple[float, float]:
        x, y = self.mechanism.local(link, point)
        return float(x), float(y)

    def dyad(self) -> Dyad:
        """The group's pairs and links as a dyad kind's formulas name them."""
        external1, internal, external2 = self.group.joints
        link1, link2 = self.group.links
        return Dyad(external1, internal, external2, link1, link2)

    def group_link(self, joint: Joint) -> str:
        return joint.links[0] if joint.links[0] in self.group.links else joint.links[1]

    def pin(self, joint: Joint) -> Pin:
        """The revolute pair ``joint`` between a group link and a known link."""
        link = self.group_link(joint)
        known = joint.other(link)
        known_local = self.local(known, joint.point)
        body = self.bodies[known]
        offset = body.offset(*known_local)
        return Pin(joint, link, known, self.local(link, joint.point), known_local,
                   body.origin + offset, offset, self.bounds.get(joint.point))

    def length(self, link: str, first: str, second: str) -> float:
        """Distance between two points of a link; a zero length is a :class:`StructureError`."""
        length = self.mechanism.links[link].length(first, second)
        if not length > 1e-12:
            raise StructureError(f"{link} ({first}{second}) has zero length: the group has no "
                                 "definite position", link=self.group.name)
        return length

    def guard(self, value, bound: float, check: Callable, *args,
              magnitude: bool = False) -> None:
        """Refuse a position: where ``value > bound`` (with ``magnitude``: ``|value| > bound``)
        fails at some angle, ``check(angles, *args)`` runs on the arrays and raises (or returns,
        where the bound was too cautious)."""
        if isinstance(value, Traced):
            value.tracer.guard(value, bound, check, *args, magnitude=magnitude)
        elif not (np.min(np.abs(value) if magnitude else value) > bound):
            check(self.angles, *args)

    def guide(self, slide: Slide, unknown: str, body: Body | None = None
              ) -> tuple[Vec, Vec, Any]:
        """A prismatic pair's guide as a line for the *unknown* link's frame: (d, n, c) with d
        the guide's global direction, n = J·d, and n·(origin of ``unknown``) = c. The guide's
        orientation comes from the known link's axes (``body``, default its known body)."""
        along_known = unknown == slide.link
        known = slide.along if along_known else slide.link
        body = body or self.bodies[known]
        angle = slide.direction_rad if along_known else -slide.direction_rad
        c, s = turned_axes(body.cos, body.sin, angle)
        if along_known:  # the guide is fixed in the known link
            d = Vec(c, s)
            n = d.perp()
            through = body.point(*self.local(slide.along, slide.through))
            own = Vec(*self.local(slide.link, slide.point)).turned(c, s)
            return d, n, dot(n, through - own)
        # the guide is fixed in the unknown link, whose axes are the known link's turned back
        d = Vec(body.cos, body.sin)
        n = d.perp()
        point = body.point(*self.local(slide.link, slide.point))
        own = Vec(*self.local(slide.along, slide.through)).turned(c, s)
        return d, n, dot(n, point - own)

    def slide_axes(self, slide: Slide, unknown: str) -> tuple[Any, Any]:
        """The axes (cos θ, sin θ) of ``unknown``, held by a prismatic pair to a known link."""
        if unknown == slide.link:
            body = self.bodies[slide.along]
            return turned_axes(body.cos, body.sin, slide.direction_rad)
        body = self.bodies[slide.link]
        return turned_axes(body.cos, body.sin, -slide.direction_rad)


def turned_axes(c, s, angle: float) -> tuple[Any, Any]:
    """(cos, sin) of θ + ``angle`` (rad, a constant) from (cos θ, sin θ).

    >>> turned_axes(1.0, 0.0, math.pi / 2)
    (6.123233995736766e-17, 1.0)
    """
    if angle == 0.0:
        return c, s
    turned = Vec(c, s).turned(math.cos(angle), math.sin(angle))
    return turned.x, turned.y


# -- how a link's angle is read --------------------------------------------------------------
class ThetaKind(StrEnum):
    """How a link's angle θ is read from the solved points (see :class:`Theta`)."""

    TWO = "two"      # θ = atan2(P_second − P_first) − alpha: a link through two pins
    TIED = "tied"    # θ = θ(link) + alpha: a prismatic pair forbids relative rotation
    SPAN = "span"    # θ = atan2(span) − atan2(span in the link's axes): a guide link turning
    #                  about its pivot, span = P_first − P_second


@dataclass(frozen=True, slots=True)
class Theta:
    """How a link's angle θ is read from the solved points (computed only when asked): its
    :class:`ThetaKind`, the points it is read from, the angle ``alpha`` (rad) and the ``link``
    it follows. A link with no recipe (the drive, a link whose θ Newton solved) has a result
    row of its own."""

    kind: ThetaKind
    first: str | None = None
    second: str | None = None
    alpha: float = 0.0
    link: str | None = None


class SolvedGroup(NamedTuple):
    """A higher group solved (what an iterative kind's ``evaluate`` returns, its links' bodies
    put into the context): the θ of its links that are results of their own (``thetas``:
    link → value), how the others' angles are read (``recipes``), and the conditioning of its
    Jacobian (``sine``: 1 at best, 0 at a toggle)."""

    thetas: Mapping[str, Number]
    recipes: Mapping[str, Theta]
    sine: Number


# -- a placed dyad ---------------------------------------------------------------------------
@dataclass(slots=True)
class Side:
    """One side of v_X = v_base + u·e at the placed positions.

    ``rotation``: ``link`` (of the group) turns about the base, e = J·``radius``; else ``link``
    is the carrier X slides on, e the unit guide direction. The base is the material point of
    the known ``base_link`` at ``position`` (``offset`` from that link's origin); ``length`` is
    |e|; ``slide`` the prismatic pair of a sliding side.
    """

    rotation: bool
    link: str
    base: str
    base_link: str
    position: Vec
    offset: Vec
    direction: Vec
    radius: Vec | None
    length: Any
    slide: Slide | None = None


@dataclass(frozen=True, slots=True)
class Anchor:
    """The pin a group link's motion is referred to: ``name`` on the known link ``known``
    (at ``position``, ``offset`` from the known link's origin), at ``local`` on the group link.
    A group link without one is referred to X (at ``Placed.x_local`` on it, where X is one of
    its named points)."""

    name: str
    position: Vec
    known: str
    offset: Vec
    local: tuple[float, float]


@dataclass(slots=True)
class Placed:
    """A dyad at its closed-form positions: its links' bodies (positions), X (named ``point``)
    at ``x``, the two sides, how each link's ω follows (``rotating``: link → side index;
    ``tied``: link → the link it cannot turn against), the :class:`Anchor` of each link pinned
    to a known link, how each θ is read, and an upper bound of the size ratio R = L/l at every
    assembled position (see :func:`size_ratio`)."""

    bodies: dict[str, Body]
    point: str
    x: Vec
    sides: tuple[Side, Side]
    rotating: dict[str, int]
    tied: dict[str, str]
    anchors: dict[str, Anchor]
    thetas: dict[str, Theta]
    ratio_bound: float
    x_links: tuple[str, ...] = ()
    #: X's local coordinates on those group links on which it is a named point
    x_local: dict[str, tuple[float, float]] = field(default_factory=dict)


def rotation_side(link: str, pin: Pin, radius: Vec, length) -> Side:
    """A side turning about ``pin`` to X: ``radius`` = X − pin, ``length`` = |radius|."""
    return Side(True, link, pin.joint.point, pin.known, pin.at, pin.offset, radius.perp(),
                radius, length)


def sliding_side(context: GroupInputs, slide: Slide, carrier: str, base: str, base_link: str,
                 position: Vec, placed: Mapping[str, Body]) -> Side:
    """A side along the guide of ``slide`` from the point of the known ``base_link`` at
    ``position`` (the guide's direction from its ``along`` link, a known link or one of the
    group's ``placed`` bodies)."""
    offset = position - context.bodies[base_link].origin
    return Side(False, carrier, base, base_link, position, offset,
                _guide_direction(context, slide, placed), None, 1.0, slide)


def pinned_sliding_side(context: GroupInputs, slide: Slide, carrier: str, pin: Pin,
                        placed: Mapping[str, Body]) -> Side:
    """A side along the guide of ``slide`` from ``pin`` (see :func:`sliding_side`)."""
    return Side(False, carrier, pin.joint.point, pin.known, pin.at, pin.offset,
                _guide_direction(context, slide, placed), None, 1.0, slide)


def _guide_direction(context: GroupInputs, slide: Slide, placed: Mapping[str, Body]) -> Vec:
    body = placed.get(slide.along) or context.bodies[slide.along]
    return Vec(*turned_axes(body.cos, body.sin, slide.direction_rad))


def sense(segment, direction):
    """+1 where a segment drawn on a plan points along ``direction`` (a unit vector), −1 where
    against it: the sense a student reads an ω, ε or sliding speed with. A segment across the
    direction (a construction drawn with a mistake) has no sense; +1 (counter-clockwise) is
    taken there, whatever the rounding. ``segment`` may hold one vector per copy of a drawing
    (N, 2): one sense per copy.

    >>> sense(np.array([0.0, -2.0]), np.array([0.0, 1.0])), sense(np.array([3.0, 1e-17]),
    ...                                                           np.array([0.0, 1.0]))
    (-1.0, 1.0)
    """
    along = vectors.dot(segment, direction)
    across = 1e-9 * vectors.norm(segment)
    positive = (along >= 0) | (np.abs(along) <= across)
    return np.where(positive, 1.0, -1.0) if np.ndim(positive) else (1.0 if positive else -1.0)


def axes_towards(r: Vec, first: tuple[float, float], second: tuple[float, float], length):
    """The axes (cos θ, sin θ) of a link whose points ``first`` → ``second`` (local) lie along
    ``r`` (global), |r| = ``length``: θ = angle(r) − angle(second − first)."""
    lx, ly = second[0] - first[0], second[1] - first[1]
    size = math.hypot(lx, ly)
    along = Vec(lx / size, ly / size)
    return dot(r, along) / length, cross(along, r) / length


# -- the generic solve of the two vector equations ---------------------------------------------
class DyadRates(NamedTuple):
    """What :func:`evaluate_dyad` finds besides the bodies: the sine of the angle between the
    dyad's two construction lines, X's velocity and acceleration (None: not solved)."""

    sine: Number | None = None
    velocity: Vec | None = None
    acceleration: Vec | None = None


def evaluate_dyad(context: GroupInputs, placed: Placed, level: int,
                  check_stage: Callable) -> DyadRates:
    """Velocities (``level`` ≥ 1) and accelerations (``level`` 2) of a placed dyad: fills the
    group links' bodies in ``context.bodies`` and returns the lines' sine and X's velocity and
    acceleration."""
    bodies = context.bodies
    for link, body in placed.bodies.items():
        bodies[link] = body
    if level < 1:
        return DyadRates()
    s1, s2 = placed.sides
    e1, e2 = s1.direction, s2.direction
    det = cross(e1, e2)
    sine = det / (s1.length * s2.length)
    # the digits left near the toggle: ε·R/s³ (velocities), ε·R/s⁵ (accelerations) below 1
    power = 3.0 if level == 1 else 5.0
    bound = (EPS * placed.ratio_bound) ** (1.0 / power) * MARGIN
    context.guard(sine, bound, check_stage, sine, s1.position.x, s1.position.y,
                  s2.position.x, s2.position.y,
                  *(side.length if side.rotation else -1.0 for side in (s1, s2)), magnitude=True)
    vb1 = bodies[s1.base_link].velocity(s1.offset)
    vb2 = bodies[s2.base_link].velocity(s2.offset)
    w = vb2 - vb1
    u1 = cross(w, e2) / det
    u2 = cross(w, e1) / det
    # X's velocity from the side whose base motion and direction are known constants more
    # often (a guide fixed in the frame: v_X = u2·e2 exactly, no rounding across it)
    second = _constants(vb2, e2) > _constants(vb1, e1)
    v_x = vb2 + e2 * u2 if second else vb1 + e1 * u1
    omegas = _follow(placed, {link: (u1, u2)[index] for link, index in placed.rotating.items()},
                     lambda link: bodies[link].omega)
    for link, body in placed.bodies.items():
        reference, velocity, _ = _reference(context, placed, link, v_x, None)
        body.omega = omegas[link]
        r = body.origin - reference if reference is not None else None
        if r is None:
            body.vx, body.vy = velocity.x, velocity.y
        else:
            moved = velocity + r.perp() * body.omega
            body.vx, body.vy = moved.x, moved.y
    if level < 2:
        return DyadRates(sine, v_x)
    ab1 = bodies[s1.base_link].acceleration(s1.offset)
    ab2 = bodies[s2.base_link].acceleration(s2.offset)
    known = []
    for side, u in ((s1, u1), (s2, u2)):
        if side.rotation:
            known.append(side.radius * -(u * u))
        else:  # the Coriolis term 2ω_carrier·J·v_rel
            known.append((side.direction * u).perp() * (2.0 * bodies[side.link].omega))
    rhs = (ab2 + known[1]) - (ab1 + known[0])
    du1 = cross(rhs, e2) / det
    du2 = cross(rhs, e1) / det
    a_x = ab2 + known[1] + e2 * du2 if second else ab1 + known[0] + e1 * du1
    epsilons = _follow(placed, {link: (du1, du2)[index]
                                for link, index in placed.rotating.items()},
                       lambda link: bodies[link].epsilon)
    for link, body in placed.bodies.items():
        reference, _, acceleration = _reference(context, placed, link, v_x, a_x)
        body.epsilon = epsilons[link]
        if reference is None:
            body.ax, body.ay = acceleration.x, acceleration.y
        else:
            r = body.origin - reference
            square = body.omega * body.omega
            moved = acceleration + r.perp() * body.epsilon - r * square
            body.ax, body.ay = moved.x, moved.y
    return DyadRates(sine, v_x, a_x)


def _constants(*vectors: Vec) -> int:
    """How many of the vectors' components are plain numbers (not traced or arrays)."""
    return sum(isinstance(value, float | int) for vector in vectors
               for value in (vector.x, vector.y))


def _follow(placed: Placed, values: dict, known: Callable) -> dict:
    """Each link's ω (or ε): the rotating links' own, tied links follow theirs."""
    pending = dict(placed.tied)
    while pending:
        for link, other in list(pending.items()):
            if other in values:
                values[link] = values[other]
            elif other not in placed.bodies:
                values[link] = known(other)
            else:
                continue
            del pending[link]
    return values


def _reference(context: GroupInputs, placed: Placed, link: str, v_x: Vec, a_x: Vec | None):
    """(reference position, or None where it is the link's origin; its velocity; its
    acceleration) of a group link's motion: its pin on a known link, or X — whichever is the
    link's origin, else the pin."""
    anchor = placed.anchors.get(link)
    on_x = placed.x_local.get(link)
    if anchor is not None and not (anchor.local != (0.0, 0.0) and on_x == (0.0, 0.0)):
        known = context.bodies[anchor.known]
        velocity = known.velocity(anchor.offset)
        acceleration = known.acceleration(anchor.offset) if a_x is not None else None
        return (None if anchor.local == (0.0, 0.0) else anchor.position), velocity, acceleration
    return (None if on_x == (0.0, 0.0) else placed.x), v_x, a_x


def place_origin(body: Body, references) -> None:
    """Set a placed link's origin from the first of ``references`` — (global position, local
    coordinates) of its points — that is the origin itself, else from the first."""
    chosen = next((item for item in references if item[1] == (0.0, 0.0)), references[0])
    position, local = chosen
    origin = position if local == (0.0, 0.0) else position - body.offset(*local)
    body.x, body.y = origin.x, origin.y


# -- exact checks (run on arrays where a guard's bound fails) ----------------------------------
def first(mask) -> int:
    return int(np.flatnonzero(np.atleast_1d(mask))[0])


def assembly_error(group: AssurGroup, angles, bad, text: str, shortfall) -> AssemblyError:
    index = first(bad)
    amount = float(np.broadcast_to(np.asarray(shortfall, dtype=float),
                                   np.shape(np.atleast_1d(bad)))[index])
    # two points that coincide are no shortfall: the text says what is wrong
    told = f"{text}: short by {amount:.6g} m" if amount else text
    return AssemblyError(told, shortfall=amount, link=group.name,
                         angle=float(np.atleast_1d(angles)[index]))


def toggle_or_miss(group: AssurGroup, angles, vanishing, scale, text: str, shortfall) -> None:
    """Raise at the first angle where a group cannot be assembled or is in its toggle position.

    ``vanishing`` is the factor of the discriminant that goes to zero at the toggle (a + b −
    |P1P2| for RRR), ``scale`` the size of the terms it was computed from: where |vanishing| ≤
    ROUNDING_UNITS·eps·scale its sign is lost in rounding — a toggle (ToggleError); below
    that the links cannot reach (AssemblyError saying by how much)."""
    vanishing = np.atleast_1d(np.asarray(vanishing, dtype=float))
    tolerance = ROUNDING_UNITS * EPS * np.asarray(scale, dtype=float)
    toggle = np.abs(vanishing) <= tolerance
    miss = (vanishing < 0) & ~toggle
    toggles, misses = np.flatnonzero(toggle), np.flatnonzero(miss)
    if misses.size and (not toggles.size or misses[0] < toggles[0]):
        raise assembly_error(group, angles, miss, text, shortfall)
    if toggles.size:
        raise ToggleError(
            "toggle position: the group's links are stretched out or folded in line, its two "
            "construction lines are parallel and its motion is not determined",
            line_angle_deg=0.0, link=group.name,
            angle=float(np.atleast_1d(angles)[int(toggles[0])]))


def parallel_guides(group: AssurGroup, angles, det, text: str) -> None:
    bad = ~(np.abs(np.atleast_1d(det)) >= TOGGLE_SINE)
    if np.any(bad):
        raise ToggleError(text, line_angle_deg=0.0, link=group.name,
                          angle=float(np.atleast_1d(angles)[first(bad)]))


def stage_check(group: AssurGroup, stage: str) -> Callable:
    """The exact check of a stage's digits (a guard's ``check``): ε·R/s^(2k+1) must stay below
    1, R the size ratio at each angle (:func:`size_ratio`)."""

    def check(angles, sine, x1, y1, x2, y2, length1, length2) -> None:
        ratio = size_ratio(x1, y1, x2, y2, length1, length2)
        estimate = error_estimate(ratio, np.asarray(sine), stage)
        bad = ~(np.atleast_1d(estimate) < 1.0)
        if np.any(bad):
            index = first(bad)
            value = float(np.broadcast_to(np.asarray(sine), bad.shape)[index])
            angle = math.degrees(math.asin(min(1.0, abs(value))))
            raise ToggleError(
                f"toggle position: the group's two construction lines meet at {angle:.3g}°, "
                f"so close to parallel that its {STAGE_PLURAL.get(stage, stage)} would have no "
                "correct digit",
                line_angle_deg=angle, link=group.name,
                angle=float(np.atleast_1d(angles)[index]))

    return check


def size_ratio(x1, y1, x2, y2, length1, length2):
    """R = L / l: the group's size L (its radii plus the distance between its two base points)
    over its shortest radius l (R = 1 for a group without a rotation side; a sliding side's
    length is given as −1). The group's conditioning near its toggle is ε·R/s^(2k+1)."""
    radii = [np.asarray(length, dtype=float) for length in (length1, length2)
             if not (np.ndim(length) == 0 and float(length) < 0)]
    if not radii:
        return np.ones(np.shape(np.asarray(x1) - np.asarray(x2)))
    span = np.hypot(np.asarray(x1) - np.asarray(x2), np.asarray(y1) - np.asarray(y2))
    return (span + sum(radii)) / np.minimum.reduce(radii)


def error_estimate(ratio, sine, stage: str):
    """ε·R/s³ (velocities) or ε·R/s⁵ (accelerations)."""
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        size = np.abs(sine)
        power = size * size * size
        if stage == "acceleration":
            power = power * size * size
        return EPS * ratio / power


# -- the construction a plan draws -------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Construction:
    """A dyad's construction point X, its two sides and how its links' ω follow, at the solved
    positions (arrays over the angles): what the plan emulator draws.

    Each side: ``kind`` (``rotation`` or ``sliding``), ``link``, ``base`` (its printed name),
    ``base_link``, ``base_position``, unit ``direction``, ``radius`` (rotation), ``slide``.
    """

    group: AssurGroup
    point: str
    position: np.ndarray
    sides: tuple
    rotating: Mapping[str, int]
    tied: Mapping[str, str]
    anchors: Mapping[str, tuple[str, np.ndarray, str]]
    x_links: tuple[str, ...] = field(default=())

    def reference(self, link: str) -> tuple[str, np.ndarray, str | None]:
        """(name, position, known link) of the point a group link's motion is referred to:
        its pin on a known link, or X itself (known link None)."""
        if link in self.anchors:
            return self.anchors[link]
        return self.point, self.position, None

    def size_ratio(self) -> np.ndarray:
        """R = L/l of :func:`size_ratio` at each angle."""
        s1, s2 = self.sides
        lengths = [-1.0 if side.radius is None else vectors.norm(side.radius)
                   for side in self.sides]
        return size_ratio(s1.base_position[:, 0], s1.base_position[:, 1],
                          s2.base_position[:, 0], s2.base_position[:, 1], *lengths)

    def follow_tied(self, values: dict, known: Callable[[str], object]) -> None:
        """Give each link tied to another by a prismatic pair that link's ω (or ε): ``values``
        holds the group's own, ``known(link)`` those of links already known."""
        pending = dict(self.tied)
        while pending:
            for link, other in list(pending.items()):
                source = values.get(other)
                if source is None:
                    source = known(other)
                if source is not None:
                    values[link] = source
                    del pending[link]


@dataclass(frozen=True, slots=True)
class ConstructionSide:
    """A side of a dyad's two vector equations as the plans draw it (see :class:`Side`)."""

    rotation: bool
    link: str
    base: str
    base_link: str
    base_position: np.ndarray
    direction: np.ndarray
    radius: np.ndarray | None = None
    slide: Slide | None = None


def _array(vec: Vec, count: int) -> np.ndarray:
    out = np.empty((count, 2))
    out[:, 0], out[:, 1] = vec.x, vec.y
    return out


def construction(placed: Placed, group: AssurGroup, count: int) -> Construction:
    """The :class:`Construction` of a dyad placed by the direct evaluation."""
    sides = []
    for side in placed.sides:
        direction = _array(side.direction, count)
        if side.rotation:
            direction = vectors.unit(direction)
        sides.append(ConstructionSide(
            side.rotation, side.link, side.base, side.base_link,
            _array(side.position, count), direction,
            _array(side.radius, count) if side.radius is not None else None, side.slide))
    anchors = {link: (anchor.name, _array(anchor.position, count), anchor.known)
               for link, anchor in placed.anchors.items()}
    return Construction(group, placed.point, _array(placed.x, count), tuple(sides),
                        dict(placed.rotating), dict(placed.tied), anchors, placed.x_links)


# -- the protocols later layers implement ------------------------------------------------------
class PlanDrawer(Protocol):
    """What a group kind's own plan construction (a module's ``draw_velocity(drawer, group)``
    and ``draw_acceleration``: a class III triad's) is given by the plan emulator
    (:mod:`planmethod.plans.construction`): the two plan sheets ``v`` and ``a`` (``line``,
    ``intersect``, ``lay_off``, ``read``, ``points``), the scales, the readings so far, the
    images of the links solved so far, and a ``memo`` kept between the two plans."""

    v: Any
    a: Any
    scales: Any
    readings: dict
    vimages: dict
    aimages: dict
    memo: dict
    angle: float

    def where(self, link: str, point: str) -> np.ndarray: ...

    def label(self, point: str, sheet) -> str: ...

    def image_at(self, sheet, images: dict, link: str, position, label: str) -> str: ...

    def length_mm(self, first, second) -> float: ...

    def radius_mm(self, centre, point) -> float: ...

    def drawn_length(self, sheet, start: str, end: str) -> float: ...

    def fix_velocity(self, link: str, ref, label: str, omega: float) -> None: ...

    def fix_acceleration(self, link: str, ref, label: str, omega: float,
                         epsilon: float) -> None: ...


class ForceSolver(Protocol):
    """What a group kind's textbook reaction sequence (its module's ``reactions(solver,
    group)``) is given by the force analysis (:mod:`planmethod.forces.groups`): the solved
    positions, each link's known wrench (``wrench[link]``: ``force`` and ``moment_about``), the
    2 × 2 solve with its singularity check, and the recording of reactions, polygon edges and
    the group's result. Arrays are over the crank angles."""

    count: int
    wrench: Mapping[str, Any]

    def at(self, link: str, point: str) -> np.ndarray: ...

    def guide(self, joint: Joint) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...

    def solve2(self, e1, e2, w, group: str, what: str): ...

    def singular(self, value, scale, group: str, what: str) -> None: ...

    def record(self, joint: Joint, group_links, target: str, source: str, point, force,
               moment=None): ...

    def known_edges(self, links) -> list: ...

    def edge(self, label: str, vector, kind: EdgeKind, link: str): ...

    def total(self, links) -> Any: ...

    def result(self, group: AssurGroup, steps, edges, keys, special=None): ...


def split(vector: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(unit vector, length) of arrays of 2-vectors."""
    length = vectors.norm(vector)
    return vector / length[..., None], length

