"""A dyad's two vector equations, their exact solve, and the construction the plans draw.

A dyad kind (:mod:`~planmethod.kinematics.groups.rrr` …) writes one function,
``place(context)``: its closed-form positions, and its two vector equations as two
:class:`Side` — the statement a student writes on the plan,

    v_X = v_base1 + u1·e1 = v_base2 + u2·e2,

where a *rotation* side has e = J·(X − centre) and u = ω of the turning link, and a *sliding*
side has e along the guide and u the relative sliding speed. Everything after the positions is
the same for every dyad (:func:`evaluate_dyad`): the 2 × 2 solve by Cramer's rule (parallel
lines are the group's toggle), the normal (−ω²·r) and Coriolis (2ω × v_rel) terms of the
accelerations, each link's ω and ε, its origin's velocity and acceleration. The plan emulator
draws the same two sides (:func:`construction`).

Examples
--------
>>> axes_towards(Vec(0.0, 2.0), (0.0, 0.0), (0.5, 0.0), 2.0)  # a link along +y
(0.0, 1.0)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import NamedTuple, TypeVar

import numpy as np

from ... import vectors
from ...model import Slide
from ...structure import AssurGroup
from ..algebra import Body, Number, Vec, cross, dot
from .base import GroupInputs, Pin, Theta, turned_axes
from .checks import EPS, MARGIN, size_ratio

__all__ = ["Anchor", "Construction", "DyadRates", "Placed", "Side", "axes_towards",
           "construction", "evaluate_dyad", "follow_tied", "pinned_sliding_side", "place_origin",
           "rotation_side", "sliding_side"]

#: an ω or ε: a number, an array or a traced value (the solve), a reading (the plans)
T = TypeVar("T")


# -- the two sides ---------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Side:
    """One side of v_X = v_base + u·e.

    ``rotation``: ``link`` (of the group) turns about the base, e = J·``radius``; else ``link``
    is the carrier X slides on, e the unit guide direction. The base is the material point
    ``base`` (its printed name) of the known ``base_link`` at ``position`` (``offset`` from that
    link's origin); ``length`` is |e|; ``slide`` the prismatic pair of a sliding side.

    A placed dyad's sides hold :class:`~planmethod.kinematics.algebra.Vec` (numbers, arrays or
    traced values: what the formulas computed); a :class:`Construction`'s hold (N, 2) arrays
    over the angles, with a unit ``direction`` (``length`` 1).
    """

    rotation: bool
    link: str
    base: str
    base_link: str
    position: Vec | np.ndarray
    offset: Vec | np.ndarray
    direction: Vec | np.ndarray
    radius: Vec | np.ndarray | None
    length: Number
    slide: Slide | None = None


@dataclass(frozen=True, slots=True)
class Anchor:
    """The pin a group link's motion is referred to: ``name`` on the known link ``known``
    (at ``position``, ``offset`` from the known link's origin), at ``local`` on the group link.
    A group link without one is referred to X (at ``Placed.x_local`` on it, where X is one of
    its named points). Vectors as in :class:`Side`."""

    name: str
    position: Vec | np.ndarray
    known: str
    offset: Vec | np.ndarray
    local: tuple[float, float]


@dataclass(slots=True)
class Placed:
    """A dyad at its closed-form positions: its links' bodies (positions), X (named ``point``)
    at ``x``, the two sides, how each link's ω follows (``rotating``: link → side index;
    ``tied``: link → the link it cannot turn against), the :class:`Anchor` of each link pinned
    to a known link, how each θ is read, and an upper bound of the size ratio R = L/l at every
    assembled position (see :func:`~planmethod.kinematics.groups.checks.size_ratio`)."""

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
    det = cross(s1.direction, s2.direction)
    sine = det / (s1.length * s2.length)
    # the digits left near the toggle: ε·R/s³ (velocities), ε·R/s⁵ (accelerations) below 1
    power = 3.0 if level == 1 else 5.0
    bound = (EPS * placed.ratio_bound) ** (1.0 / power) * MARGIN
    context.guard(sine, bound, check_stage, sine, s1.position.x, s1.position.y,
                  s2.position.x, s2.position.y,
                  *(side.length if side.rotation else -1.0 for side in (s1, s2)), magnitude=True)
    rates = _velocities(context, placed, det)
    if level < 2:
        return DyadRates(sine, rates.v_x)
    return DyadRates(sine, rates.v_x, _accelerations(context, placed, det, rates))


class _Rates(NamedTuple):
    """A dyad's sliding rates along its two sides (u1, u2), X's velocity, and whether X's
    motion is taken from the second side."""

    u1: Number
    u2: Number
    v_x: Vec
    second: bool


def _velocities(context: GroupInputs, placed: Placed, det) -> _Rates:
    """The dyad's velocities: the rates along its sides from its bases' velocities, X's
    velocity, each group link's ω and its origin's velocity (filled in its body)."""
    bodies = context.bodies
    s1, s2 = placed.sides
    e1, e2 = s1.direction, s2.direction
    vb1 = bodies[s1.base_link].velocity(s1.offset)
    vb2 = bodies[s2.base_link].velocity(s2.offset)
    w = vb2 - vb1
    u1 = cross(w, e2) / det
    u2 = cross(w, e1) / det
    # X's velocity from the side whose base motion and direction are known constants more
    # often (a guide fixed in the frame: v_X = u2·e2 exactly, no rounding across it)
    second = _constants(vb2, e2) > _constants(vb1, e1)
    v_x = vb2 + e2 * u2 if second else vb1 + e1 * u1
    omegas = follow_tied(placed.tied, {link: (u1, u2)[index]
                                       for link, index in placed.rotating.items()},
                         lambda link: None if link in placed.bodies else bodies[link].omega)
    for link, body in placed.bodies.items():
        reference, velocity, _ = _reference(context, placed, link, v_x, None)
        body.omega = omegas[link]
        r = body.origin - reference if reference is not None else None
        if r is None:
            body.vx, body.vy = velocity.x, velocity.y
        else:
            moved = velocity + r.perp() * body.omega
            body.vx, body.vy = moved.x, moved.y
    return _Rates(u1, u2, v_x, second)


def _accelerations(context: GroupInputs, placed: Placed, det, rates: _Rates) -> Vec:
    """The dyad's accelerations: the sides' relative accelerations from their bases' (with
    the normal and Coriolis terms), each group link's ε and its origin's acceleration (filled
    in its body); returns X's acceleration."""
    bodies = context.bodies
    s1, s2 = placed.sides
    e1, e2 = s1.direction, s2.direction
    ab1 = bodies[s1.base_link].acceleration(s1.offset)
    ab2 = bodies[s2.base_link].acceleration(s2.offset)
    known = []
    for side, u in ((s1, rates.u1), (s2, rates.u2)):
        if side.rotation:
            known.append(side.radius * -(u * u))
        else:  # the Coriolis term 2ω_carrier·J·v_rel
            known.append((side.direction * u).perp() * (2.0 * bodies[side.link].omega))
    rhs = (ab2 + known[1]) - (ab1 + known[0])
    du1 = cross(rhs, e2) / det
    du2 = cross(rhs, e1) / det
    a_x = ab2 + known[1] + e2 * du2 if rates.second else ab1 + known[0] + e1 * du1
    epsilons = follow_tied(placed.tied, {link: (du1, du2)[index]
                                         for link, index in placed.rotating.items()},
                           lambda link: None if link in placed.bodies else bodies[link].epsilon)
    for link, body in placed.bodies.items():
        reference, _, acceleration = _reference(context, placed, link, rates.v_x, a_x)
        body.epsilon = epsilons[link]
        if reference is None:
            body.ax, body.ay = acceleration.x, acceleration.y
        else:
            r = body.origin - reference
            square = body.omega * body.omega
            moved = acceleration + r.perp() * body.epsilon - r * square
            body.ax, body.ay = moved.x, moved.y
    return a_x


def _constants(*vectors: Vec) -> int:
    """How many of the vectors' components are plain numbers (not traced or arrays)."""
    return sum(isinstance(value, float | int) for vector in vectors
               for value in (vector.x, vector.y))


def follow_tied(tied: Mapping[str, str], values: dict[str, T],
                known: Callable[[str], T | None]) -> dict[str, T]:
    """Each link tied to another by a prismatic pair (``tied``: link → the link it cannot turn
    against) takes that link's ω (or ε): ``values`` holds the rotating links' own,
    ``known(link)`` gives a link's from outside (None: not known yet). Returns ``values``, every
    tied link added — the solve's ω and ε as the plans' readings.

    >>> follow_tied({"slider": "frame", "block": "rod"}, {"rod": 2.5},
    ...             lambda link: 0.0 if link == "frame" else None)
    {'rod': 2.5, 'slider': 0.0, 'block': 2.5}
    """
    pending = dict(tied)
    while pending:
        for link, other in list(pending.items()):
            source = values[other] if other in values else known(other)
            if source is not None:
                values[link] = source
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


# -- the construction a plan draws -------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Construction:
    """A dyad's construction point X (``point`` at ``position``), its two :class:`Side` and how
    its links' ω follow (``rotating``, ``tied``), with the :class:`Anchor` of each link pinned
    to a known link, at the solved positions (arrays over the angles): what the plan emulator
    draws."""

    group: AssurGroup
    point: str
    position: np.ndarray
    sides: tuple[Side, Side]
    rotating: Mapping[str, int]
    tied: Mapping[str, str]
    anchors: Mapping[str, Anchor]
    x_links: tuple[str, ...] = field(default=())

    def reference(self, link: str) -> tuple[str, np.ndarray, str | None]:
        """(name, position, known link) of the point a group link's motion is referred to:
        its pin on a known link, or X itself (known link None)."""
        anchor = self.anchors.get(link)
        if anchor is not None:
            return anchor.name, anchor.position, anchor.known
        return self.point, self.position, None

    def size_ratio(self) -> np.ndarray:
        """R = L/l of :func:`~planmethod.kinematics.groups.checks.size_ratio` at each angle."""
        s1, s2 = self.sides
        lengths = [-1.0 if side.radius is None else vectors.norm(side.radius)
                   for side in self.sides]
        return size_ratio(s1.position[:, 0], s1.position[:, 1],
                          s2.position[:, 0], s2.position[:, 1], *lengths)


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
        sides.append(Side(side.rotation, side.link, side.base, side.base_link,
                          _array(side.position, count), _array(side.offset, count), direction,
                          _array(side.radius, count) if side.radius is not None else None, 1.0,
                          side.slide))
    anchors = {link: Anchor(anchor.name, _array(anchor.position, count), anchor.known,
                            _array(anchor.offset, count), anchor.local)
               for link, anchor in placed.anchors.items()}
    return Construction(group, placed.point, _array(placed.x, count), tuple(sides),
                        dict(placed.rotating), dict(placed.tied), anchors, placed.x_links)
