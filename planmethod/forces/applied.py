"""The known forces on each link: weight, inertia (d'Alembert) and external loads.

For a link with mass m, moment of inertia J_S about its centre of mass S and angular
acceleration ε (as in I. H. Aliyev, "Studies of the possibility of determining amplifications
in kinematic pairs"):

* weight G = m·g, along −y, at S;
* principal vector of the inertia forces F_u = −m·a_S, at S;
* principal moment of the inertia forces M_u = −J_S·ε;
* the combined force Q = G + F_u = m·(g − a_S) (Aliyev's), at S;
* the equivalent single inertia force: F_u on the line through S + h·J·F̂_u (F̂_u turned 90°
  counter-clockwise), h = J_S·ε / (m·|a_S|); its moment about S is then M_u.

External loads (``[[load]]``) are forces at points of links (global axes) or moments on links;
``oppose_velocity`` turns a force against the velocity of its point, and a moment against the
angular velocity of its link (a resisting torque on a rocker) (at v = 0 or ω = 0 it acts as given
and is flagged).

Every array has the crank angles on its leading axis. Results are frozen values; nothing here
draws.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> exercise = load_exercise("exercises/fourbar_forces.toml")
>>> motion = solve(exercise.mechanism, 60.0)
>>> loads = applied_loads(exercise.mechanism, motion.links)
>>> inertia = next(item for item in loads.items if item.name == "F_u,BC")
>>> inertia.force.round(4)
array([[11.4642, 10.9008]])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import SpecError
from ..kinematics.state import LinkState
from ..model import FRAME, Mechanism
from ..vectors import cross, dot, norm
from ..vocabulary import AppliedKind
from ..words import Message, message
from .names import ForceName, PointNames, crank_angles

__all__ = [
    "AppliedItem",
    "AppliedLoads",
    "Inertia",
    "Wrench",
    "applied_loads",
    "inertia_of",
]

#: below this speed (relative to the mechanism's typical speed) a point counts as at rest for
#: ``oppose_velocity`` loads and friction (the direction of motion is undefined there)
REST_SPEED = 1e-12


@dataclass(frozen=True, slots=True)
class Wrench:
    """A force system on one link reduced to the global origin: the resultant ``force`` (N, 2)
    and its ``moment`` about (0, 0) (N,), counter-clockwise positive."""

    force: np.ndarray
    moment: np.ndarray

    @classmethod
    def zero(cls, count: int) -> Wrench:
        return cls(np.zeros((count, 2)), np.zeros(count))

    @classmethod
    def at(cls, point: np.ndarray, force: np.ndarray, couple=None) -> Wrench:
        """A force through ``point`` plus a ``couple`` (N·m)."""
        moment = cross(point, force)
        if couple is not None:
            moment = moment + couple
        return cls(force, moment)

    def __add__(self, other: Wrench) -> Wrench:
        return Wrench(self.force + other.force, self.moment + other.moment)

    def __neg__(self) -> Wrench:
        return Wrench(-self.force, -self.moment)

    def __sub__(self, other: Wrench) -> Wrench:
        return self + (-other)

    def moment_about(self, point: np.ndarray) -> np.ndarray:
        """Moment of the system about ``point`` (N, 2)."""
        return self.moment - cross(point, self.force)


@dataclass(frozen=True, slots=True)
class AppliedItem:
    """One known force or moment on a link.

    ``kind`` is an :class:`~planmethod.vocabulary.AppliedKind` (weight, inertia force or
    moment, load, friction);
    ``point`` and ``force`` are set for a force (global, N × 2), ``moment`` for a couple.
    ``local`` is the point's coordinates in the link's frame (for the similarity rule on plans),
    ``label`` the point's name when it is a named point (``S_BC`` for a centre of mass).
    """

    link: str
    name: str
    kind: AppliedKind
    point: np.ndarray | None = None
    force: np.ndarray | None = None
    moment: np.ndarray | None = None
    local: tuple[float, float] | None = None
    label: str | None = None

    def wrench(self) -> Wrench:
        if self.force is not None:
            return Wrench.at(self.point, self.force)
        return Wrench(np.zeros((self.moment.shape[0], 2)), self.moment)

    def power(self, state: LinkState) -> np.ndarray:
        """Power of this force or moment (W) with the link's motion: F·v or M·ω."""
        if self.force is not None:
            velocity = state.velocity_at(self.point)
            return dot(self.force, velocity)
        return self.moment * state.omega


@dataclass(frozen=True, slots=True)
class Inertia:
    """Inertia of one link (arrays over angles): S, a_S, ε, F_u, M_u, weight G, combined force
    Q = G + F_u, and the offset h = J·ε/(m·|a_S|) of the equivalent single force, whose line
    passes through S + h·J·F̂_u (zero where a_S = 0, with ``single_force_defined`` False: a
    pure couple has no single equivalent force)."""

    link: str
    mass: float
    J: float
    centre_local: tuple[float, float]
    centre: np.ndarray
    acceleration: np.ndarray
    epsilon: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    weight: np.ndarray
    combined: np.ndarray
    offset: np.ndarray
    single_force_defined: np.ndarray


@dataclass(frozen=True, slots=True)
class AppliedLoads:
    """Everything known that acts on the links: ``items`` (weights, inertia forces and moments,
    loads), ``inertia`` per link with mass, and ``flags`` (loads whose point is at rest)."""

    items: tuple[AppliedItem, ...]
    inertia: Mapping[str, Inertia]
    flags: tuple[Message, ...]
    count: int

    def wrenches(self, links) -> dict[str, Wrench]:
        """The resultant known wrench on each of ``links``."""
        out = {link: Wrench.zero(self.count) for link in links}
        for item in self.items:
            if item.link in out:
                out[item.link] = out[item.link] + item.wrench()
        return out

    def with_items(self, extra) -> AppliedLoads:
        return AppliedLoads(self.items + tuple(extra), self.inertia, self.flags, self.count)


def inertia_of(mechanism: Mechanism, link: str, state: LinkState, gravity: float) -> Inertia:
    """The inertia of ``link`` from its mass properties and exact motion."""
    props = mechanism.masses[link]
    centre = state.place(props.S)
    a_s = state.acceleration_at(centre)
    epsilon = state.epsilon
    force = -props.m * a_s
    moment = -props.J * epsilon + 0.0  # no negative zero
    weight = np.zeros_like(force)
    weight[..., 1] = -props.m * gravity
    magnitude = norm(a_s)
    defined = magnitude > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        offset = np.where(defined, props.J * epsilon / (props.m * np.where(defined, magnitude,
                                                                             1.0)), 0.0)
    return Inertia(link, props.m, props.J, props.S, centre, a_s, epsilon, force, moment, weight,
                   weight + force, offset, defined)


def _speed_scale(mechanism: Mechanism, states: Mapping[str, LinkState]) -> float:
    drive = mechanism.drive
    link = mechanism.links[drive.link]
    radius = max(link.length(drive.pivot, p) for p in link.points)
    return max(abs(drive.omega) * radius, 1e-300)


def _at_rest(angles: np.ndarray, resting: np.ndarray) -> list[Message]:
    """The first crank angles where something is at rest, as a flag quotes them."""
    return crank_angles(np.asarray(angles)[resting][:5])


def _given_moment(mechanism: Mechanism, load, state: LinkState, count: int,
                 angles: np.ndarray | None, flags: list[Message]) -> AppliedItem:
    """A given moment on a link; with ``oppose_velocity`` its magnitude against the link's ω
    (as given, and flagged, where the link is at rest)."""
    name = f"load[{load.index}]"
    moment = np.full(count, float(load.moment))
    if load.oppose_velocity:
        omega = np.broadcast_to(np.asarray(state.omega, float), (count,))
        turning = np.abs(omega) > REST_SPEED * max(abs(mechanism.drive.omega), 1e-300)
        moment = np.where(turning, -abs(float(load.moment)) * np.sign(omega), moment)
        if not np.all(turning) and angles is None:
            flags.append(message("{load} on {link}: the link is at rest, the moment acts as "
                                 "given", load=ForceName(name), link=load.link))
        elif not np.all(turning):
            flags.append(message("{load} on {link}: the link is at rest (crank angle "
                                 "{angles}), the moment acts as given", load=ForceName(name),
                                 link=load.link, angles=_at_rest(angles, ~turning)))
    return AppliedItem(load.link, name, AppliedKind.LOAD, moment=moment)


def _given_force(mechanism: Mechanism, load, state: LinkState, count: int, rest: float,
                angles: np.ndarray | None, flags: list[Message]) -> AppliedItem:
    """A given force at a point of a link; with ``oppose_velocity`` its magnitude against the
    point's velocity (as given, and flagged, where the point is at rest: speed ≤ ``rest``)."""
    name = f"load[{load.index}]"
    local = mechanism.local(load.link, load.point)
    point = state.place(local)
    force = np.broadcast_to(np.asarray(load.force, float), (count, 2)).copy()
    if load.oppose_velocity:
        velocity = state.velocity_at(point)
        speed = norm(velocity)
        moving = speed > rest
        magnitude = float(norm(np.asarray(load.force)))
        with np.errstate(divide="ignore", invalid="ignore"):
            against = -magnitude * velocity / np.where(moving, speed, 1.0)[..., None]
        force = np.where(moving[..., None], against, force)
        if not np.all(moving) and angles is None:
            flags.append(message("{load} on {link} at {point}: the point is at rest, the "
                                 "force acts as given", load=ForceName(name), link=load.link,
                                 point=PointNames(load.point)))
        elif not np.all(moving):
            flags.append(message("{load} on {link} at {point}: the point is at rest (crank "
                                 "angle {angles}), the force acts as given",
                                 load=ForceName(name), link=load.link,
                                 point=PointNames(load.point),
                                 angles=_at_rest(angles, ~moving)))
    return AppliedItem(load.link, name, AppliedKind.LOAD, point, force, local=local,
                       label=load.point)


def applied_loads(mechanism: Mechanism, states: Mapping[str, LinkState], *,
                  angles: np.ndarray | None = None, file: str | None = None) -> AppliedLoads:
    """Weights, inertia forces and moments, and the external loads, at every solved angle.

    Parameters
    ----------
    mechanism
        The model (masses, gravity, loads).
    states
        Every moving link's exact state with accelerations (``Motion.links``).
    angles
        The crank angles (deg), for the flags.

    Raises
    ------
    SpecError
        If a load names a point that is not on its link (spec catches this; kept for models
        built in code).
    """
    count = states[FRAME].theta.shape[0]
    gravity = mechanism.gravity or 0.0
    items: list[AppliedItem] = []
    inertia: dict[str, Inertia] = {}
    flags: list[Message] = []
    for link, props in mechanism.masses.items():
        if link not in states:
            continue
        found = inertia[link] = inertia_of(mechanism, link, states[link], gravity)
        label = f"S_{link}"
        if gravity:
            items.append(AppliedItem(link, f"G_{link}", AppliedKind.WEIGHT, found.centre,
                                     found.weight, local=props.S, label=label))
        items.append(AppliedItem(link, f"F_u,{link}", AppliedKind.INERTIA_FORCE, found.centre,
                                 found.force, local=props.S, label=label))
        if props.J:
            items.append(AppliedItem(link, f"M_u,{link}", AppliedKind.INERTIA_MOMENT,
                                     moment=found.moment))
    rest = REST_SPEED * _speed_scale(mechanism, states)
    for load in mechanism.loads:
        if load.link not in states:
            continue
        if load.moment is not None:
            items.append(_given_moment(mechanism, load, states[load.link], count, angles, flags))
            continue
        if load.point not in mechanism.links[load.link].points:
            raise SpecError(message("'{point}' is not a point of '{link}'", point=load.point,
                                    link=load.link), file=file,
                            key=f"load[{load.index}].point")
        items.append(_given_force(mechanism, load, states[load.link], count, rest, angles,
                                 flags))
    return AppliedLoads(tuple(items), inertia, tuple(flags), count)
