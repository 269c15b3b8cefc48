"""Kinetostatics of a whole exercise: the solve over any crank angles and the one-angle report.

:func:`solve_forces` (vectorised over the angles of a :class:`~planmethod.kinematics.Motion`)
runs the known loads, the group-by-group method (with the friction iteration when the exercise
has friction), the independent whole-system solve, Zhukovsky's lever and the power balance.
:func:`analyse_forces` adds, at one crank angle with plans, the combined-force construction of
I. H. Aliyev ("Studies of the possibility of determining amplifications in kinematic pairs"),
its constants and its rule for the sense of ε, and returns the ``forces`` block of the JSON
report (``as_dict``); the text for ``planmethod solve`` is the render layer's
(:func:`planmethod.render.report_text.force_lines`).

Examples
--------
>>> from planmethod.report import analyse
>>> from planmethod.spec import load_exercise
>>> forces = analyse(load_exercise("exercises/fourbar_forces.toml")).forces
>>> report = forces.as_dict()
>>> round(report["balancing_moment"], 6), round(report["zhukovsky_moment"], 6)
(0.642055, 0.642055)
>>> [round(x, 5) for x in report["reactions"]["B"]["force"]]
[-15.95286, -11.57979]
>>> report["whole_system"]["agrees"], report["power_residual"] < 1e-12
(True, True)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

import numpy as np

from ..errors import SpecError
from ..kinematics import Motion
from ..model import Exercise, Mechanism
from ..numbering import course_numbers
from ..plans.scales import standard
from ..vectors import norm
from ..vocabulary import AppliedKind, numbered
from ..words import Message, message, render
from .applied import AppliedLoads, applied_loads
from .checks import ZhukovskyLever, power_moment, power_residual, zhukovsky_lever
from .combined import (
    CombinedConstants,
    CombinedConstruction,
    EpsilonSense,
    combined_constants,
    combined_construction,
    epsilon_senses,
)
from .friction import FrictionResult, friction_settings, solve_with_friction
from .group_method import GroupSolution, solve_by_groups
from .names import load_symbol, load_symbols
from .system import SystemSolution, solve_whole_system

__all__ = ["AGREEMENT", "ForceAnalysis", "ForceSolution", "analyse_forces", "force_columns",
           "solve_forces"]

#: the group method and the whole-system solve must agree to this (relative), else a flag
AGREEMENT = 1e-9
#: default drawn length (mm) of the largest vector of the force polygons
FORCE_MM = 80.0


@dataclass(frozen=True)
class ForceSolution:
    """Kinetostatics over N crank angles (arrays on the leading axis)."""

    mechanism: Mechanism
    angles: np.ndarray
    applied: AppliedLoads
    groups: GroupSolution
    system: SystemSolution
    lever: ZhukovskyLever
    power_residual: np.ndarray
    power_moment: np.ndarray
    agreement: np.ndarray
    friction: FrictionResult | None
    flags: tuple[Message, ...]

    @property
    def reactions(self):
        return self.groups.reactions

    @property
    def balancing_moment(self) -> np.ndarray:
        return self.groups.balancing_moment


def _relative_difference(groups: GroupSolution, system: SystemSolution,
                         length: float) -> np.ndarray:
    """Largest difference between the two solves, relative to the largest reaction (moments
    divided by the crank length)."""
    scale = np.zeros_like(groups.balancing_moment)
    difference = np.abs(groups.balancing_moment - system.balancing_moment) / length
    scale = np.maximum(scale, np.abs(groups.balancing_moment) / length)
    for key, reaction in groups.reactions.items():
        other = system.reactions[key]
        scale = np.maximum(scale, reaction.magnitude)
        difference = np.maximum(difference, norm(reaction.force - other.force))
        if reaction.moment is not None:
            difference = np.maximum(difference, np.abs(reaction.moment - other.moment) / length)
    return np.where(scale > 0, difference / np.where(scale > 0, scale, 1.0), difference)


def _crank_length(mechanism: Mechanism) -> float:
    drive = mechanism.drive
    link = mechanism.links[drive.link]
    return max(link.length(drive.pivot, p) for p in link.points) or 1.0


def solve_forces(motion: Motion, *, plans=None, file: str | None = None) -> ForceSolution:
    """Reactions, balancing moment and the checks at every angle of ``motion``.

    Parameters
    ----------
    motion
        Exact kinematics up to accelerations of every link.
    plans
        The drawn plans at a single angle: Zhukovsky's lever then uses the drawn velocity plan.

    Raises
    ------
    ForceError
        A singular force system (a toggle position) at some angle.
    ConvergenceError
        The friction iteration does not converge.
    """
    mechanism = motion.mechanism
    structure = motion.structure
    states = motion.links
    angles = motion.angles
    applied = applied_loads(mechanism, states, angles=angles, file=file)
    flags = list(applied.flags)
    settings = friction_settings(mechanism.friction)
    friction = None
    if settings is not None:
        friction = solve_with_friction(mechanism, structure, states, applied, settings,
                                       angles=angles)
        groups = friction.solution
        applied = applied.with_items(friction.items)
        flags += friction.flags
    else:
        groups = solve_by_groups(mechanism, structure, states, applied, angles=angles)
    system = solve_whole_system(mechanism, structure, states, applied, angles=angles)
    length = _crank_length(mechanism)
    agreement = _relative_difference(groups, system, length)
    if np.any(agreement > AGREEMENT):
        index = int(np.argmax(agreement))
        flags.append(message("the group method and the whole-system solve differ by "
                             "{difference:.3g} (relative) at crank angle {angle:g}°: an "
                             "ill-conditioned position", difference=float(agreement[index]),
                             angle=float(angles[index])))
    lever = zhukovsky_lever(mechanism, states, applied, plans=plans)
    if not np.all(np.isfinite(lever.balancing_moment)):
        omega = numbered("ω", course_numbers(mechanism)[mechanism.drive.link])
        flags.append(message("Zhukovsky's lever is undefined where the crank does not move "
                             "({omega} = 0): every image lies at the pole", omega=omega))
    power = power_residual(mechanism, states, applied, groups.balancing_moment)
    by_power = power_moment(mechanism, states, applied)
    return ForceSolution(mechanism, angles, applied, groups, system, lever, power, by_power,
                         agreement, friction, tuple(flags))


def _number(value) -> float | None:
    value = float(value)
    return value if math.isfinite(value) else None


def _pair(array) -> list[float]:
    return [float(array[0]), float(array[1])]


@dataclass(frozen=True)
class ForceAnalysis:
    """Kinetostatics at one crank angle: the vectorised solution at that angle, and what the
    plans add (Aliyev's construction, constants and ε rule, the force scale μF)."""

    angle: float
    solution: ForceSolution
    combined: CombinedConstruction | None
    constants: CombinedConstants | None
    epsilon: tuple[EpsilonSense, ...]
    mu_f: float
    plans: object = None

    # -- scalars ---------------------------------------------------------------------------
    @property
    def balancing_moment(self) -> float:
        return float(self.solution.balancing_moment[0])

    @property
    def zhukovsky_moment(self) -> float | None:
        return _number(self.solution.lever.balancing_moment[0])

    @property
    def power_residual(self) -> float:
        return float(self.solution.power_residual[0])

    @property
    def reactions(self) -> dict:
        return {key: reaction.take(0) for key, reaction in self.solution.reactions.items()}

    @property
    def flags(self) -> tuple[Message, ...]:
        return self.solution.flags

    # -- the report ------------------------------------------------------------------------
    def as_dict(self) -> dict:
        """The ``forces`` block of the JSON report (docs/kinetostatics.md), and what else was
        computed; its sentences (a group's steps, the flags) rendered in the language spoken,
        with the forces by their report names."""
        solution = self.solution
        symbols = load_symbols(solution.mechanism)
        numbers = course_numbers(solution.mechanism)
        out: dict = {"reactions": {key: _reaction_dict(reaction)
                                   for key, reaction in self.reactions.items()},
                     "balancing_moment": self.balancing_moment,
                     "zhukovsky_moment": self.zhukovsky_moment,
                     "power_residual": self.power_residual,
                     "power_balance_moment": _number(solution.power_moment[0]),
                     "zhukovsky": self._zhukovsky_dict(),
                     "whole_system": _whole_system_dict(solution),
                     "inertia": {link: _inertia_dict(item)
                                 for link, item in solution.applied.inertia.items()},
                     "loads": [_load_dict(item, symbols) for item in solution.applied.items
                               if item.kind in (AppliedKind.LOAD, AppliedKind.FRICTION)],
                     "groups": [_group_dict(group, numbers)
                                for group in solution.groups.groups],
                     "scales": {"mu_f": self.mu_f}}
        if self.combined is not None:
            out["combined_force"] = _combined_dict(self.combined)
        if self.constants is not None:
            out["constants"] = _constants_dict(self.constants)
        if self.epsilon:
            out["epsilon_sense"] = {e.link: {"points": list(e.points), "rule": e.rule,
                                             "exact": e.exact, "agrees": e.agrees}
                                    for e in self.epsilon}
        if solution.friction is not None:
            friction = solution.friction
            out["friction"] = {
                "iterations": int(friction.iterations[0]),
                "history": list(friction.history),
                "losses_W": {key: float(value[0]) for key, value in friction.losses.items()}}
        out["flags"] = [render(flag) for flag in self.flags]
        return out

    def _zhukovsky_dict(self) -> dict:
        """Zhukovsky's lever: its forces' images and moments, the balancing force."""
        lever = self.solution.lever
        return {"source": lever.source, "mu_v": lever.mu_v,
                "balancing_force": (_pair(lever.balancing_force[0])
                                    if self.zhukovsky_moment is not None else None),
                "at": lever.balancing_point,
                "difference": (None if self.zhukovsky_moment is None else
                               self.zhukovsky_moment - self.balancing_moment),
                "forces": [_lever_force_dict(force) for force in lever.forces]}


def _lever_force_dict(force) -> dict:
    """A force on the lever; a couple's moment term M·ω/μv (a link with one point) with the
    ``omega`` (rad/s) its moment was multiplied by."""
    entry = {"name": force.name, "link": force.link, "image_mm": _pair(force.image_mm[0]),
             "force": _pair(force.force[0]), "moment_N_mm": float(force.moment[0])}
    if force.term:
        entry["omega"] = float(force.omega[0])
    return entry


def _reaction_dict(reaction) -> dict:
    """A pair's reaction at the angle: from, on, force, magnitude, point (and couple)."""
    entry = {"from": reaction.source, "on": reaction.target,
             "force": _pair(reaction.force), "magnitude": float(reaction.magnitude),
             "point": _pair(reaction.point)}
    if reaction.moment is not None:
        entry["moment"] = float(reaction.moment)
    return entry


def _load_dict(item, symbols: Mapping[str, tuple[str, str]]) -> dict:
    """A given load or a friction force or moment at the first angle; a load with the
    symbol figures print it by (``symbol``: P₃, the number of its link)."""
    if item.force is not None:
        given = {"point": _pair(item.point[0]), "force": _pair(item.force[0])}
    else:
        given = {"moment": float(item.moment[0])}
    shown = {"symbol": load_symbol(symbols[item.name])} if item.name in symbols else {}
    return {"name": item.name, **shown, "link": item.link, "kind": item.kind, **given}


def _group_dict(group, numbers: Mapping[str, int]) -> dict:
    """A group's solve: its kind, links (in the order of their numbers in the course's
    notation, as the text lists them), steps (rendered), reactions and special point."""
    links = sorted(group.links, key=lambda link: numbers.get(link, len(numbers)))
    out = {"name": group.name, "kind": group.kind, "links": links,
           "steps": [render(step) for step in group.steps],
           "reactions": list(group.reactions)}
    if group.special_point is not None:
        out["special_point"] = _pair(group.special_point[0])
    return out


def _whole_system_dict(solution) -> dict:
    """The whole mechanism's linear system: its reactions and how well they agree."""
    system = solution.system
    return {
        "equations": system.equations,
        "balancing_moment": float(system.balancing_moment[0]),
        "reactions": {key: {"force": _pair(r.take(0).force),
                            **({"moment": float(r.moment[0])} if r.moment is not None
                               else {})}
                      for key, r in system.reactions.items()},
        "max_rel_difference": float(solution.agreement[0]),
        "agrees": bool(solution.agreement[0] <= AGREEMENT),
        "rcond": float(system.rcond[0])}


def _inertia_dict(item) -> dict:
    """A link's mass properties, inertia force and moment, weight and combined force."""
    return {"m": item.mass, "J": item.J, "S": list(item.centre_local),
            "centre": _pair(item.centre[0]), "a_S": _pair(item.acceleration[0]),
            "epsilon": float(item.epsilon[0]), "force": _pair(item.force[0]),
            "moment": float(item.moment[0]), "weight": _pair(item.weight[0]),
            "combined": _pair(item.combined[0]),
            "offset_h": (float(item.offset[0]) if bool(item.single_force_defined[0])
                         else None)}


def _combined_dict(combined) -> dict:
    """The combined force (inertia + weight) read off the acceleration plan."""
    return {"g": combined.g, "mu_a": combined.mu_a,
            "gravity_image_mm": combined.gravity_image_mm,
            "new_pole_mm": list(combined.new_pole_mm),
            "links": {f.link: {"m": f.mass, "s_mm": list(f.image_mm),
                               "segment_mm": list(f.segment_mm),
                               "from_plan": list(f.from_plan), "exact": list(f.exact)}
                      for f in combined.forces}}


def _constants_dict(constants) -> dict:
    """Aliyev's constants, computed once for all positions."""
    return {"mu_f_mu_l": constants.force_moment, "mu_f": constants.mu_f,
            "mu_l": constants.mu_l, "mu_a": constants.mu_a,
            "m_mu_a_mu_l": dict(constants.combined_moment),
            "J_mu_a_over_l": {link: entry.as_dict()
                              for link, entry in constants.inertia_moment.items()}}


def _force_scale(exercise: Exercise, solution: ForceSolution) -> float:
    plan = exercise.plan
    if plan.mu_f is not None:
        return plan.mu_f
    largest = 0.0
    for group in solution.groups.groups:
        for edge in group.polygon:
            largest = max(largest, float(norm(edge.vector[0])))
    drawn = plan.force_mm or FORCE_MM
    if largest <= 0:
        return 1.0
    return largest / drawn if plan.exact_mm else standard(largest / drawn)


def analyse_forces(exercise: Exercise, motion: Motion, *, plans=None) -> ForceAnalysis:
    """Kinetostatics of ``exercise`` at the (single) angle of ``motion`` (see the module
    docstring); ``plans`` (drawn at that angle) adds Aliyev's construction and the lever on
    the drawn velocity plan.

    Parameters
    ----------
    exercise
        The exercise, with its masses, gravity and loads.
    motion
        Its exact motion at one crank angle.
    plans
        The plans drawn at that angle (optional).
    """
    solution = solve_forces(motion, plans=plans, file=exercise.source)
    mu_f = _force_scale(exercise, solution)
    g = exercise.mechanism.gravity or 0.0
    combined = combined_construction(plans, solution.applied, g)
    constants = combined_constants(plans, solution.applied, mu_f)
    epsilon = epsilon_senses(plans)
    return ForceAnalysis(float(motion.angles[0]), solution, combined, constants, epsilon, mu_f,
                         plans)


def force_columns(exercise: Exercise) -> Callable[[Motion], Mapping[str, np.ndarray]]:
    """The ``extra`` callable of :func:`planmethod.sweep.sweep_table` for ``--forces``:
    ``Rx_K Ry_K R_K`` (and ``M_K`` for a prismatic pair's couple) per pair, ``M_b``,
    ``M_b_system`` and ``power_residual``; with friction also ``friction_iterations`` and
    ``M_b_no_friction`` (the conveyor of Umbetkulov et al. compares the motor torque with and
    without friction) and ``friction_sense_K`` per pair with friction: the sense of the relative
    motion (+1, −1, 0 at rest), which the friction load follows.

    Raises
    ------
    SpecError
        If the exercise defines no forces at all (no masses and no loads): its reactions
        would all be zero.
    """
    mechanism = exercise.mechanism
    if not mechanism.masses and not mechanism.loads:
        raise SpecError(message("defines no forces (no [mass.…] and no [[load]] tables): "
                                "there is nothing to sweep with --forces"),
                        file=exercise.source)

    def columns(motion: Motion) -> dict[str, np.ndarray]:
        solution = solve_forces(motion, file=exercise.source)
        out: dict[str, np.ndarray] = {}
        for key, reaction in solution.reactions.items():
            out[f"Rx_{key}"] = reaction.force[:, 0]
            out[f"Ry_{key}"] = reaction.force[:, 1]
            out[f"R_{key}"] = reaction.magnitude
            if reaction.moment is not None:
                out[f"M_{key}"] = reaction.moment
        out["M_b"] = solution.balancing_moment
        out["M_b_system"] = solution.system.balancing_moment
        out["power_residual"] = solution.power_residual
        if solution.friction is not None:
            out["friction_iterations"] = solution.friction.iterations.astype(float)
            plain = replace(motion, mechanism=replace(motion.mechanism, friction={}))
            out["M_b_no_friction"] = solve_forces(plain, file=exercise.source).balancing_moment
            for key, sense in solution.friction.senses.items():
                out[f"friction_sense_{key}"] = sense.astype(float)
        return out

    return columns
