"""The combined force on the acceleration plan, its constants, and the sense of ε — the method
of I. H. Aliyev, "Studies of the possibility of determining amplifications in kinematic pairs".

**Combined force.** The weight and the principal vector of inertia of a link act at the same
point S, so they add into one force Q = G + F_u = m·(g − a_S). On the acceleration plan, with
the pole π and the image s of S (πs represents a_S), move the pole down by the image of g,
Z_g = g/μa mm, to a new pole π′: the segment from s to π′ represents g − a_S, so
Q = m·μa·(s→π′). (Aliyev writes his scales as mm per unit, M_a = 1/μa; his "Z_g = M_a·g" is
this g/μa.)

**Constants computed once for all positions** (Aliyev's eqs. 1–3, in μ's, i.e. units per mm):

1. moment of a force drawn W_Q mm long at an arm of h mm on the position plan:
   M = W_Q·h·(μF·μl) — the constant μF·μl (N·m/mm²) is the same for every link;
2. moment of the combined force of link i: M = z_i·h·(m_i·μa·μl), z_i = (sπ′) in mm — the
   constant m_i·μa·μl is proportional to the mass;
3. inertia moment of link i: M_u = Z_T·(J_i·μa/l_i), Z_T the image (mm) of the tangential
   acceleration of one end of the link about the other, l_i their distance — the constant is
   proportional to J_i and inversely to the length. (The paper prints the reciprocals, in its
   mm-per-unit scales; its cross-checks "inversely proportional to the masses" and
   "proportional to the length, inversely to the moment of inertia" hold for those.)

**The sense of ε read off the plan** (Aliyev's rule): ε turns from the full relative
acceleration of two points of the link towards its normal component. Indeed with
a_YX = aⁿ + aᵗ, aⁿ = ω²·(X − Y) and aᵗ = ε·J(Y − X), cross(a_YX, aⁿ) = ε·ω⁴·|XY|², whose sign
is that of ε whenever ω ≠ 0. M_u = −J·ε turns the other way. Where ω = 0 there is no normal
component and the rule says nothing (reported as undefined).

Examples
--------
>>> from planmethod.report import analyse
>>> from planmethod.spec import load_exercise
>>> analysis = analyse(load_exercise("exercises/fourbar_forces.toml"))
>>> construction = combined_construction(analysis.plans, analysis.forces.solution.applied, 9.81)
>>> round(construction.gravity_image_mm, 4)
49.05
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np

from ..model import FRAME
from ..vectors import cross, norm, perp
from .applied import AppliedLoads

__all__ = ["CombinedConstants", "CombinedConstruction", "CombinedForce", "EpsilonSense",
           "InertiaConstant", "combined_constants", "combined_construction", "epsilon_senses"]


@dataclass(frozen=True, slots=True)
class CombinedForce:
    """One link's combined force on the plan: the image s of its centre of mass (mm), the
    segment s→π′ (mm), Q read from it (N) and the exact Q."""

    link: str
    mass: float
    image_mm: tuple[float, float]
    segment_mm: tuple[float, float]
    from_plan: tuple[float, float]
    exact: tuple[float, float]


@dataclass(frozen=True, slots=True)
class CombinedConstruction:
    """Aliyev's construction on one acceleration plan."""

    g: float
    mu_a: float
    gravity_image_mm: float
    new_pole_mm: tuple[float, float]
    forces: tuple[CombinedForce, ...]


@dataclass(frozen=True, slots=True)
class EpsilonSense:
    """The sense of ε of a link by Aliyev's rule on the plan, against the exact sign:
    +1 counter-clockwise, −1 clockwise, 0 none; ``rule`` None where undefined (ω = 0)."""

    link: str
    points: tuple[str, str]
    rule: int | None
    exact: int

    @property
    def agrees(self) -> bool | None:
        return None if self.rule is None else self.rule == self.exact


@dataclass(frozen=True, slots=True)
class InertiaConstant:
    """A link's constant J·μa/l of Aliyev's eq. 3: the two points whose distance is l, l
    (m), the constant (N·m/mm), the exact inertia moment −J·ε (N·m) and, with an
    acceleration plan, Z_T (mm) and the inertia moment read off the plan with it (N·m)."""

    points: tuple[str, str]
    length: float
    constant: float
    exact_moment: float
    z_t_mm: float | None = None
    from_plan: float | None = None

    def as_dict(self) -> dict:
        """The JSON report's ``constants.J_mu_a_over_l`` entry of the link."""
        out = {"points": list(self.points), "length": self.length, "constant": self.constant,
               "exact_moment": self.exact_moment}
        if self.z_t_mm is not None:
            out |= {"Z_T_mm": self.z_t_mm, "from_plan": self.from_plan}
        return out


@dataclass(frozen=True, slots=True)
class CombinedConstants:
    """Aliyev's constants: μF·μl for every force, and per link m·μa·μl and J·μa/l (with the
    two points whose distance is l), and the inertia moment read off the plan by eq. 3 with
    Z_T (mm) against the exact −J·ε."""

    mu_f: float | None
    mu_l: float
    mu_a: float
    force_moment: float | None
    combined_moment: Mapping[str, float]
    inertia_moment: Mapping[str, InertiaConstant]


def _image(plans, link: str, position: np.ndarray):
    """Image (mm) on the acceleration plan of ``link``'s material point at ``position``, by
    the similarity rule from a drawn image of one of its named points and the ω, ε read off
    the plans."""
    from ..plans.construction import image_label

    plan, motion = plans.acceleration, plans.motion
    mechanism = motion.mechanism
    omega, epsilon = plans.omega(link), plans.epsilon(link)
    if omega is None:
        omega = float(motion.links[link].omega[0])
    if epsilon is None:
        epsilon = float(motion.links[link].epsilon[0])
    for name, local in mechanism.links[link].points.items():
        label = image_label(name, plan.pole)
        if label in plan.points_mm:
            reference = motion.links[link].place(local)[0]
            r = position - reference
            return plan.point(label) + (epsilon * perp(r) - omega ** 2 * r) / plan.scale
    return None


def combined_construction(plans, applied: AppliedLoads, g: float) -> CombinedConstruction | None:
    """The combined-force construction on ``plans``' acceleration plan (None without one)."""
    if plans is None or plans.acceleration is None:
        return None
    mu_a = plans.acceleration.scale
    z_g = g / mu_a
    new_pole = np.array([0.0, -z_g])
    forces = []
    for link, inertia in applied.inertia.items():
        s = _image(plans, link, inertia.centre[0])
        if s is None:
            continue
        segment = new_pole - s
        q_plan = inertia.mass * mu_a * segment
        exact = inertia.combined[0]
        forces.append(CombinedForce(link, inertia.mass, (float(s[0]), float(s[1])),
                                    (float(segment[0]), float(segment[1])),
                                    (float(q_plan[0]), float(q_plan[1])),
                                    (float(exact[0]), float(exact[1]))))
    return CombinedConstruction(g, mu_a, z_g, (0.0, float(-z_g)), tuple(forces))


def _two_points(mechanism, link: str) -> tuple[str, str] | None:
    points = list(mechanism.links[link].points)
    return (points[0], points[1]) if len(points) >= 2 else None


def epsilon_senses(plans) -> tuple[EpsilonSense, ...]:
    """Aliyev's rule for each moving link with two named points (not the drive)."""
    if plans is None or plans.acceleration is None:
        return ()
    from ..plans.construction import image_label

    motion = plans.motion
    mechanism = motion.mechanism
    plan = plans.acceleration
    out = []
    for link in motion.links:
        if link in (FRAME, mechanism.drive.link):
            continue
        pair = _two_points(mechanism, link)
        if pair is None:
            continue
        first, second = pair
        labels = [image_label(p, plan.pole) for p in pair]
        if not all(label in plan.points_mm for label in labels):
            continue
        state = motion.links[link]
        x = state.place(mechanism.local(link, first))[0]
        y = state.place(mechanism.local(link, second))[0]
        relative = plan.point(labels[1]) - plan.point(labels[0])
        epsilon = float(state.epsilon[0])
        omega = plans.omega(link)
        if omega is None:
            omega = float(state.omega[0])
        normal_mm = omega ** 2 * float(norm(x - y)) / plan.scale
        turn = float(cross(relative, x - y))
        resolution = max(plan.precision_mm, 1e-9 * float(norm(relative)) + 1e-300)
        rule = None if normal_mm <= resolution else int(np.sign(turn))
        out.append(EpsilonSense(link, (first, second), rule, int(np.sign(epsilon))))
    return tuple(out)


def combined_constants(plans, applied: AppliedLoads,
                       mu_f: float | None) -> CombinedConstants | None:
    """Aliyev's constants for the scales of ``plans`` (see the module docstring)."""
    if plans is None:
        return None
    scales = plans.scales
    mu_l, mu_a = scales.mu_l, scales.mu_a
    motion = plans.motion
    mechanism = motion.mechanism
    combined = {}
    inertia_moment = {}
    for link, inertia in applied.inertia.items():
        combined[link] = inertia.mass * mu_a * mu_l
        pair = _two_points(mechanism, link)
        if pair is None or not inertia.J:
            continue
        length = mechanism.links[link].length(*pair)
        constant = inertia.J * mu_a / length
        epsilon = float(inertia.epsilon[0])
        entry = InertiaConstant(pair, length, constant, -inertia.J * epsilon)
        if plans.acceleration is not None:
            read = plans.epsilon(link)
            if read is None:
                read = epsilon
            z_t = abs(read) * length / mu_a
            entry = replace(entry, z_t_mm=z_t,
                            from_plan=float(-np.sign(read) * z_t * constant))
        inertia_moment[link] = entry
    return CombinedConstants(mu_f, mu_l, mu_a, None if mu_f is None else mu_f * mu_l, combined,
                             inertia_moment)
