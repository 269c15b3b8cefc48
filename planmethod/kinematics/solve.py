"""Exact kinematics of a whole mechanism, group by group in build order, vectorised over angles.

:func:`solve` returns a :class:`Motion`: every solved link's pose, ω, ε and origin velocity and
acceleration at each crank angle, from which any point, any point of a link coincident with
another point (``B@lever``), sliding quantities and the curvature of a path are read.

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

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import AssemblyError, PlanmethodError, SpecError, ToggleError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Structure, analyse_structure
from .dyads import (
    Construction,
    construct,
    dyad_positions,
    solve_pair,
)
from .state import LinkState, cross, norm, perp, rotate, unit_angle

__all__ = ["STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "Sliding", "solve"]

STAGES = ("position", "velocity", "acceleration")


@dataclass(frozen=True, slots=True)
class Branch:
    """The assembly a group takes: ``sign`` ±1 (see README, "Branches") and why."""

    sign: int
    reason: str  # "sketch", "default" or "unique"


@dataclass(frozen=True, slots=True)
class GroupMotion:
    """A solved dyad: its construction and the unknown lengths of its two vector equations.

    ``velocity_unknowns`` (u1, u2) and ``acceleration_unknowns`` (u̇1, u̇2) are the signed
    magnitudes along the sides' directions; ``line_sine`` the sine of the angle from side 1's
    line to side 2's; ``error_estimate`` the estimated relative error of the group's
    velocities and accelerations near its toggle, ε·R/s³ and ε·R/s⁵ (per stage solved).
    """

    construction: Construction | None  # None for a class III group (kinematics/higher.py)
    velocity_unknowns: tuple[np.ndarray, np.ndarray] | None = None
    acceleration_unknowns: tuple[np.ndarray, np.ndarray] | None = None
    line_sine: np.ndarray | None = None
    error_estimate: Mapping[str, np.ndarray] | None = None


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


@dataclass(frozen=True)
class Motion:
    """The exact kinematics of a mechanism at one or many crank angles."""

    mechanism: Mechanism
    structure: Structure
    angles: np.ndarray
    scalar: bool
    stage: str
    links: Mapping[str, LinkState]
    groups: Mapping[int, GroupMotion]
    branches: Mapping[int, Branch]
    #: reference → (link, position), filled on first use (positions never change)
    _located: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    # -- shaping ---------------------------------------------------------------------------
    def _out(self, array: np.ndarray) -> np.ndarray:
        return array[0] if self.scalar else array

    def _need(self, stage: str, what: str) -> None:
        if STAGES.index(self.stage) < STAGES.index(stage):
            raise PlanmethodError(f"{what} needs the {stage} stage, but only the {self.stage} "
                                  "stage was solved")

    def link_state(self, link: str) -> LinkState:
        if link not in self.mechanism.links:
            raise SpecError(f"unknown link '{link}'")
        if link not in self.links:
            raise PlanmethodError(f"link {link} was not solved in this scene")
        return self.links[link]

    # -- points --------------------------------------------------------------------------------
    def _locate(self, ref: str) -> tuple[str, np.ndarray]:
        """(link whose material point is meant, its current global position)."""
        found = self._located.get(ref)
        if found is None:
            found = self._located[ref] = self._find(ref)
            found[1].flags.writeable = False  # shared by later reads
        return found

    def _find(self, ref: str) -> tuple[str, np.ndarray]:
        name, _, on = ref.partition("@")
        owners = [link for link in self.mechanism.links_with_point(name) if link in self.links]
        if not owners:
            if not self.mechanism.links_with_point(name):
                raise SpecError(f"unknown point '{name}'")
            raise PlanmethodError(f"point {name} was not solved in this scene")
        position = self.links[owners[0]].place(self.mechanism.local(owners[0], name))
        if on:
            self.link_state(on)
            return on, position
        return owners[0], position

    def position(self, ref: str) -> np.ndarray:
        """Global position (m) of a point (``"C"``) or of a link's point under another
        (``"B@lever"``)."""
        return self._out(self._locate(ref)[1].copy())

    def velocity(self, ref: str) -> np.ndarray:
        """Absolute velocity (m/s) of a point."""
        self._need("velocity", f"the velocity of {ref}")
        link, position = self._locate(ref)
        if link == FRAME:  # a point of the frame does not move
            return self._out(np.zeros_like(position))
        return self._out(self.links[link].velocity_at(position))

    def acceleration(self, ref: str) -> np.ndarray:
        """Absolute acceleration (m/s²) of a point."""
        self._need("acceleration", f"the acceleration of {ref}")
        link, position = self._locate(ref)
        if link == FRAME:
            return self._out(np.zeros_like(position))
        return self._out(self.links[link].acceleration_at(position))

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

    # -- links ---------------------------------------------------------------------------------
    def theta(self, link: str) -> np.ndarray:
        """Global angle (rad) of the link's own +x axis."""
        return self._out(self.link_state(link).theta)

    def omega(self, link: str) -> np.ndarray:
        """Angular velocity (rad/s, counter-clockwise positive)."""
        self._need("velocity", f"ω of {link}")
        return self._out(self.link_state(link).omega)

    def epsilon(self, link: str) -> np.ndarray:
        """Angular acceleration (rad/s², counter-clockwise positive)."""
        self._need("acceleration", f"ε of {link}")
        return self._out(self.link_state(link).epsilon)

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
        d = unit_angle(guide.theta + slide.direction_rad)
        s = np.einsum("...i,...i->...", point - through, d)
        if STAGES.index(self.stage) < 1:
            return Sliding(self._out(s))
        v_rel = mover.velocity_at(point) - guide.velocity_at(point)
        ds = np.einsum("...i,...i->...", v_rel, d)
        if STAGES.index(self.stage) < 2:
            return Sliding(self._out(s), self._out(ds))
        coriolis = 2 * guide.omega[..., None] * perp(v_rel)
        a_rel = mover.acceleration_at(point) - guide.acceleration_at(point) - coriolis
        dds = np.einsum("...i,...i->...", a_rel, d)
        return Sliding(self._out(s), self._out(ds), self._out(dds), self._out(coriolis))

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
        link, position = self._locate(ref)
        state = self.links[link]
        v, a = state.velocity_at(position), state.acceleration_at(position)
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
def _frame_state(count: int) -> LinkState:
    zeros = np.zeros(count)
    axes = np.zeros((count, 2))
    axes[:, 0] = 1.0
    return LinkState(zeros, np.zeros((count, 2)), zeros, np.zeros((count, 2)), zeros,
                     np.zeros((count, 2)), axes)


def _drive_state(mechanism: Mechanism, angles_rad: np.ndarray) -> LinkState:
    drive = mechanism.drive
    pivot_local = mechanism.local(drive.link, drive.pivot)
    pivot = np.asarray(mechanism.local(FRAME, drive.pivot), float)
    axes = unit_angle(angles_rad)
    origin = pivot - rotate(pivot_local, angles_rad, axes)
    count = angles_rad.shape[0]
    omega = np.full(count, float(drive.omega))
    epsilon = np.full(count, float(drive.epsilon))
    r = origin - pivot
    turned = perp(r)
    velocity = float(drive.omega) * turned
    acceleration = float(drive.epsilon) * turned - float(drive.omega) ** 2 * r
    return LinkState(angles_rad, origin, omega, velocity, epsilon, acceleration, axes)


def _sketch_distance(mechanism: Mechanism, group: AssurGroup, poses) -> float | None:
    total, used = 0.0, False
    for link in group.links:
        theta, origin = poses[link]
        for name, local in mechanism.links[link].points.items():
            if name in mechanism.sketch:
                place = origin + rotate(local, theta)
                total += float(np.sum((place - np.asarray(mechanism.sketch[name])) ** 2))
                used = True
    return total if used else None


def _choose_branch(mechanism, group, states, angle_deg) -> tuple[Branch, dict | None]:
    """The group's branch and, when already computed, its poses on that branch."""
    if group.kind not in ("RRR", "RRP", "RPR"):
        return Branch(1, "unique"), None
    angles = np.array([angle_deg])
    candidates, poses = {}, {}
    errors = []
    for sign in (1, -1):
        try:
            poses[sign] = dyad_positions(mechanism, group, states, sign, angles)
        except AssemblyError as error:
            errors.append(error)
            continue
        candidates[sign] = _sketch_distance(mechanism, group, poses[sign])
    if not candidates:
        raise errors[0]
    plus, minus = candidates.get(1), candidates.get(-1)
    if plus is None or minus is None or abs(plus - minus) <= 1e-12 * (plus + minus) + 1e-24:
        return Branch(1, "default"), poses.get(1)
    sign = 1 if plus < minus else -1
    return Branch(sign, "sketch"), poses[sign]


def choose_branches(mechanism: Mechanism, structure: Structure | None = None,
                    groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]:
    """Pick each group's assembly at ``drive.angle``: nearest to the sketch, else the default."""
    structure = structure or analyse_structure(mechanism)
    groups = structure.groups if groups is None else tuple(groups)
    angle = np.radians(np.array([mechanism.drive.angle]))
    states = {FRAME: _frame_state(1), mechanism.drive.link: _drive_state(mechanism, angle)}
    branches = {}
    for group in groups:
        if not group.is_dyad:
            from .higher import choose_higher_branch  # class III groups: Newton from the sketch

            branch, poses = choose_higher_branch(mechanism, group, states, angle)
            branches[group.index] = branch
        else:
            branches[group.index], poses = _choose_branch(mechanism, group, states,
                                                          mechanism.drive.angle)
            if poses is None:
                poses = dyad_positions(mechanism, group, states, branches[group.index].sign,
                                       np.array([mechanism.drive.angle]))
        for link, (theta, origin) in poses.items():
            states[link] = LinkState(theta, origin)
    return branches


#: the arithmetic's resolution (unit roundoff)
EPS = float(np.finfo(float).eps)
#: estimated relative errors above this are flagged in reports
FLAG_ERROR = 1e-6


def _condition(construction: Construction, sine: np.ndarray, angles_deg: np.ndarray,
               stage: str) -> np.ndarray:
    """The estimated relative error ε·R/s^(2k+1) of a dyad's velocities (k = 1) or
    accelerations (k = 2), s the sine of the angle between its construction lines and R its size
    ratio (:meth:`Construction.size_ratio`). Near a toggle a displacement δ of the group's
    input moves s by about δ/(l·s) while |v| grows like 1/s and |a| like 1/s³, so the crank
    angle's own rounding is amplified that much; measured errors stay 20–40 times below this
    estimate (benchmarks/stress.py). Where it reaches 1 no digit is left: a ToggleError."""
    power = 3 if stage == "velocity" else 5
    with np.errstate(divide="ignore", over="ignore"):
        estimate = EPS * construction.size_ratio() / np.abs(sine) ** power
    bad = ~(estimate < 1.0)
    if np.any(bad):
        index = int(np.flatnonzero(bad)[0])
        angle = float(np.degrees(np.arcsin(min(1.0, abs(float(sine[index]))))))
        raise ToggleError(
            f"toggle position: the group's two construction lines meet at {angle:.3g}°, so "
            f"close to parallel that its {stage}s would have no correct digit",
            line_angle_deg=angle, link=construction.group.name, angle=float(angles_deg[index]))
    return estimate


def _group_velocity(construction: Construction, states: dict[str, LinkState],
                    angles_deg: np.ndarray):
    side1, side2 = construction.sides
    v1 = states[side1.base_link].velocity_at(side1.base_position)
    v2 = states[side2.base_link].velocity_at(side2.base_position)
    u1, u2, sine = solve_pair(v2 - v1, side1.direction, side2.direction)
    estimate = _condition(construction, sine, angles_deg, "velocity")
    v_x = v1 + u1[..., None] * side1.direction
    omegas: dict[str, np.ndarray] = {}
    for link, index in construction.rotating.items():
        side = construction.sides[index]
        omegas[link] = (u1, u2)[index] / norm(side.radius)
    construction.follow_tied(omegas, lambda link: states[link].omega)
    velocities = {}
    for link in construction.group.links:
        _, ref, known = construction.reference(link)
        v_ref = states[known].velocity_at(ref) if known else v_x
        velocities[link] = v_ref + omegas[link][..., None] * perp(states[link].origin - ref)
    return (u1, u2), sine, omegas, velocities, estimate


def _group_acceleration(construction: Construction, states: dict[str, LinkState],
                        velocity_unknowns):
    known = []
    for side, u in zip(construction.sides, velocity_unknowns, strict=True):
        a_base = states[side.base_link].acceleration_at(side.base_position)
        if side.kind == "rotation":
            known.append(a_base - (states[side.link].omega ** 2)[..., None] * side.radius)
        else:
            carrier = states[side.link].omega
            known.append(a_base + 2 * carrier[..., None] * perp(u[..., None] * side.direction))
    side1, side2 = construction.sides
    du1, du2, _ = solve_pair(known[1] - known[0], side1.direction, side2.direction)
    a_x = known[0] + du1[..., None] * side1.direction
    epsilons: dict[str, np.ndarray] = {}
    for link, index in construction.rotating.items():
        epsilons[link] = (du1, du2)[index] / norm(construction.sides[index].radius)
    construction.follow_tied(epsilons, lambda link: states[link].epsilon)
    accelerations = {}
    for link in construction.group.links:
        state = states[link]
        _, ref, known = construction.reference(link)
        a_ref = states[known].acceleration_at(ref) if known else a_x
        r = state.origin - ref
        accelerations[link] = (a_ref + epsilons[link][..., None] * perp(r)
                               - (state.omega ** 2)[..., None] * r)
    return (du1, du2), epsilons, accelerations


def solve(mechanism: Mechanism, angles=None, *, stage: str = "acceleration",
          links: Iterable[str] | None = None, structure: Structure | None = None,
          branches: Mapping[int, Branch] | None = None) -> Motion:
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
    structure, branches
        Reuse an earlier structural analysis and branch choice.

    Raises
    ------
    AssemblyError, ToggleError, ConvergenceError
        At the first crank angle where a group cannot be assembled, is in its toggle position,
        or (class III) does not converge.
    """
    if stage not in STAGES:
        raise ValueError(f"stage must be one of {STAGES}, got {stage!r}")
    structure = structure or analyse_structure(mechanism)
    groups = structure.groups if links is None else structure.groups_needed(links)
    if branches is None:
        branches = choose_branches(mechanism, structure, groups)
    scalar = angles is None or np.ndim(angles) == 0
    angles_deg = np.atleast_1d(np.asarray(
        mechanism.drive.angle if angles is None else angles, dtype=float)).ravel()
    if not np.all(np.isfinite(angles_deg)):
        raise SpecError("crank angles must be finite numbers")
    level = STAGES.index(stage)
    count = angles_deg.shape[0]
    states: dict[str, LinkState] = {FRAME: _frame_state(count)}
    drive = _drive_state(mechanism, np.radians(angles_deg))
    states[mechanism.drive.link] = drive if level == 2 else drive.moving(
        drive.omega if level else None, drive.velocity if level else None)
    solved: dict[int, GroupMotion] = {}
    for group in groups:
        sign = branches[group.index].sign
        if not group.is_dyad:
            from .higher import solve_higher

            solved[group.index] = solve_higher(mechanism, group, states, sign, angles_deg,
                                               level, branches[group.index])
            continue
        poses = dyad_positions(mechanism, group, states, sign, angles_deg)
        for link, (theta, origin) in poses.items():
            states[link] = LinkState(theta, origin)
        construction = construct(mechanism, group, states)
        record = GroupMotion(construction)
        if level >= 1:
            unknowns, sine, omegas, velocities, estimate = _group_velocity(
                construction, states, angles_deg)
            for link in group.links:
                states[link] = states[link].moving(omegas[link], velocities[link])
            record = GroupMotion(construction, unknowns, None, sine, {"velocity": estimate})
        if level >= 2:
            accel_unknowns, epsilons, accelerations = _group_acceleration(
                construction, states, record.velocity_unknowns)
            for link in group.links:
                s = states[link]
                states[link] = s.moving(s.omega, s.velocity, epsilons[link], accelerations[link])
            estimates = dict(record.error_estimate,
                             acceleration=_condition(construction, record.line_sine, angles_deg,
                                                     "acceleration"))
            record = GroupMotion(construction, record.velocity_unknowns, accel_unknowns,
                                 record.line_sine, estimates)
        solved[group.index] = record
    return Motion(mechanism, structure, angles_deg, scalar, stage, states, solved,
                  dict(branches))
