"""Two checks of the balancing moment: Zhukovsky's rigid lever and the power balance.

**Zhukovsky's lever.** The velocity plan turned 90° clockwise about its pole is a rigid lever
pivoted at the pole; every force carried to the image of its point (forces unchanged in size
and direction) and the balancing force at the crank pin hold it in equilibrium. The moment of F
about the pole on the turned plan is cross(r, F) with r the turned image, equal to F·v/μv, so
the lever is the power balance drawn. A couple M on a link is carried as a pair of forces
±M/|PQ| ⟂ PQ at two points of the link; on a link with one point (a sliding block, a slider)
it is a moment term of its own, M·ω/μv (its power over μv, as the power balance gives it),
set at the image of that point (``omega``: the ω it was multiplied by). With plans, the
images are those of the *drawn* velocity plan (read to its drafting precision), so the lever
shows how far a graphical answer is; without plans the exact velocities are used.

**Power balance.** ΣF·v + ΣM·ω + M_b·ω1 = 0 over all known forces and moments (weights,
inertia, loads, friction): it gives M_b = −ΣP/ω1 by itself, and with the group method's M_b the
residual |ΣP| / Σ|P_i| (0 where nothing moves).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> from planmethod.forces.applied import applied_loads
>>> exercise = load_exercise("exercises/fourbar_forces.toml")
>>> motion = solve(exercise.mechanism, [0.0, 60.0, 150.0])
>>> applied = applied_loads(exercise.mechanism, motion.links)
>>> lever = zhukovsky_lever(exercise.mechanism, motion.links, applied)
>>> lever.balancing_moment.round(6)
array([-0.910965,  0.642055, -0.577299])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from ..kinematics.state import LinkState
from ..model import FRAME, Mechanism
from ..vectors import cross, dot, perp
from .applied import AppliedItem, AppliedLoads

__all__ = ["LeverForce", "VelocitySource", "ZhukovskyLever", "power_moment", "power_residual",
           "zhukovsky_lever"]


class VelocitySource(StrEnum):
    """Whose velocities the lever was built from (the JSON report's ``zhukovsky.source``)."""

    PLAN = "velocity plan"
    EXACT = "exact velocities"


@dataclass(frozen=True, slots=True)
class LeverForce:
    """One force on the lever: the known force or couple it carries (``source``: its report
    name), the image of its point on the turned velocity plan (mm, pole at 0, 0), the force
    (N) and its moment about the pole (N·mm). A couple is carried as a pair of forces, each
    at a ``point`` of its link (None for any other force)."""

    source: str
    link: str
    image_mm: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    point: str | None = None
    omega: np.ndarray | None = None

    @property
    def term(self) -> bool:
        """Whether it is a couple's moment term M·ω/μv (a link with one point), no force."""
        return self.omega is not None

    @property
    def name(self) -> str:
        """Its name in the JSON report: the source's, with the point of a couple's force
        (``M_u,BC at C``)."""
        return self.source if self.point is None else f"{self.source} at {self.point}"


@dataclass(frozen=True, slots=True)
class ZhukovskyLever:
    """The lever's forces, the balancing force F_b at the drive's scale point (⟂ the crank),
    and the balancing moment M_b = F_b·l it gives. ``source`` says whose velocities were used
    (:class:`VelocitySource`)."""

    forces: tuple[LeverForce, ...]
    balancing_force: np.ndarray
    balancing_point: str
    balancing_image_mm: np.ndarray
    balancing_moment: np.ndarray
    mu_v: float
    source: VelocitySource


class _Velocities:
    """Velocities of material points, from the drawn plan or exact."""

    def __init__(self, mechanism: Mechanism, states: Mapping[str, LinkState], plans=None):
        self.mechanism, self.states, self.plans = mechanism, states, plans

    def omega(self, link: str) -> np.ndarray:
        if self.plans is not None:
            value = self.plans.omega(link)
            if value is not None:
                return np.atleast_1d(np.asarray(value, float))
        return self.states[link].omega

    def at(self, link: str, position: np.ndarray) -> np.ndarray:
        """Velocity (m/s) of ``link``'s material point at ``position``."""
        if self.plans is None or link == FRAME:
            return self.states[link].velocity_at(position)
        from ..plans.construction import image_label

        plan = self.plans.velocity
        for name, local in self.mechanism.links[link].points.items():
            label = image_label(name, plan.pole)
            if label in plan.points_mm:
                reference = self.states[link].place(local)
                image = plan.vector(label)[None, :]
                return image + self.omega(link)[..., None] * perp(position - reference)
        return self.states[link].velocity_at(position)


def _turned(velocity: np.ndarray, mu_v: float) -> np.ndarray:
    """The image on the velocity plan turned 90° clockwise (mm)."""
    return np.stack((velocity[..., 1], -velocity[..., 0]), axis=-1) / mu_v


def zhukovsky_lever(mechanism: Mechanism, states: Mapping[str, LinkState],
                    applied: AppliedLoads, *, plans=None, mu_v: float | None = None
                    ) -> ZhukovskyLever:
    """The balancing moment by Zhukovsky's lever (see the module docstring)."""
    velocities = _Velocities(mechanism, states, plans)
    drive = mechanism.drive
    if plans is not None:
        mu_v = plans.scales.mu_v
        scale_point = plans.scales.scale_point
    else:
        link = mechanism.links[drive.link]
        scale_point = next(p for p in link.points if p != drive.pivot)
        if mu_v is None:
            mu_v = abs(drive.omega) * link.length(drive.pivot, scale_point) / 40.0 or 1.0
    forces: list[LeverForce] = []

    def carry(item: AppliedItem, point: np.ndarray, force: np.ndarray,
              at: str | None = None) -> None:
        image = _turned(velocities.at(item.link, point), mu_v)
        forces.append(LeverForce(item.name, item.link, image, force, cross(image, force), at))

    for item in applied.items:
        if item.link == FRAME:
            continue
        if item.force is not None:
            carry(item, item.point, item.force)
            continue
        points = list(mechanism.links[item.link].points)
        state = states[item.link]
        if len(points) >= 2:
            first, second = (state.place(mechanism.local(item.link, p)) for p in points[:2])
            arm = second - first
            pair = (item.moment / dot(arm, arm))[..., None] * perp(arm)
            carry(item, second, pair, points[1])
            carry(item, first, -pair, points[0])
        else:  # a one-point link: the couple's lever moment is M·ω/μv
            omega = velocities.omega(item.link)
            where = (state.place(mechanism.local(item.link, points[0])) if points
                     else state.origin)
            image = _turned(velocities.at(item.link, where), mu_v)
            forces.append(LeverForce(item.name, item.link, image, np.zeros_like(state.origin),
                                     item.moment * omega / mu_v, omega=omega))
    state = states[drive.link]
    pivot = state.place(mechanism.local(drive.link, drive.pivot))
    pin = state.place(mechanism.local(drive.link, scale_point))
    arm = pin - pivot
    direction = perp(arm) / dot(arm, arm)[..., None]  # F_b per M_b
    image = _turned(velocities.at(drive.link, pin), mu_v)
    image_pivot = _turned(velocities.at(drive.link, pivot), mu_v)
    per_unit = cross(image, direction) - cross(image_pivot, direction)
    total = sum((force.moment for force in forces), np.zeros(state.theta.shape[0]))
    with np.errstate(divide="ignore", invalid="ignore"):
        balancing = np.where(per_unit != 0, -total / np.where(per_unit != 0, per_unit, 1.0),
                             np.nan)
    return ZhukovskyLever(tuple(forces), balancing[..., None] * direction, scale_point, image,
                          balancing, float(mu_v),
                          VelocitySource.PLAN if plans is not None else VelocitySource.EXACT)


def power_residual(mechanism: Mechanism, states: Mapping[str, LinkState],
                   applied: AppliedLoads, balancing: np.ndarray) -> np.ndarray:
    """|ΣP| / Σ|P_i| of all known forces and moments and the balancing moment (0 where every
    power is zero)."""
    powers = [item.power(states[item.link]) for item in applied.items if item.link != FRAME]
    powers.append(balancing * states[mechanism.drive.link].omega)
    stacked = np.stack(powers)
    total = np.abs(stacked).sum(axis=0)
    return np.where(total > 0, np.abs(stacked.sum(axis=0)) / np.where(total > 0, total, 1.0),
                    0.0)


def power_moment(mechanism: Mechanism, states: Mapping[str, LinkState],
                 applied: AppliedLoads) -> np.ndarray:
    """The balancing moment from the power balance alone: M_b = −ΣP/ω1 (NaN where ω1 = 0)."""
    total = sum((item.power(states[item.link]) for item in applied.items
                 if item.link != FRAME), np.zeros(states[FRAME].theta.shape[0]))
    omega = states[mechanism.drive.link].omega
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(omega != 0, -total / np.where(omega != 0, omega, 1.0), np.nan)
