"""The solve of one exercise at one angle: exact values, plans, checks, and the JSON report.

:func:`analyse` runs the scene (structure → exact kinematics → plans → forces when asked) and
returns an :class:`Analysis`; :func:`report_dict` turns it into the JSON report
(docs/json-report.md), section by section from the typed results; its sentences (the flags,
the steps) are rendered in the language spoken. The text ``planmethod solve`` prints is the
render layer's (:mod:`planmethod.render.report_text`).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> analysis = analyse(load_exercise("exercises/compressor_slider_crank.toml"))
>>> check = next(c for c in analysis.checks if c.quantity == "a_C")
>>> round(check.analytic, 2), check.rel_error < 1e-9
(430.32, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from . import vocabulary
from .errors import PlanmethodError
from .kinematics import Motion, MotionAt, solve
from .kinematics.continuation import pose
from .model import FRAME, Exercise
from .numbering import course_numbers
from .plans import Plans, draw_plans
from .plans.construction import PlansUnavailableError
from .render.plan_words import flag_message, plan_dict
from .scene import Scene, plan_scene
from .structure import Structure
from .vectors import norm
from .words import Message, render, template

if TYPE_CHECKING:
    from .forces import ForceAnalysis

__all__ = ["FLAG_ERROR", "Analysis", "Check", "PublishedValue", "analyse", "asked_quantities",
           "published_comparison", "report_dict"]

#: a group's exact values whose estimated relative error is above this are flagged
FLAG_ERROR = 1e-6

#: the flag of a group near its toggle, by the stage whose exact values lose digits there
_NEAR_TOGGLE = {
    "position": template("group {number} ({links}) is near its toggle: its exact positions are "
                         "good to about {estimate:.0e} relative"),
    "velocity": template("group {number} ({links}) is near its toggle: its exact velocities "
                         "are good to about {estimate:.0e} relative"),
    "acceleration": template("group {number} ({links}) is near its toggle: its exact "
                             "accelerations are good to about {estimate:.0e} relative")}


@dataclass(frozen=True, slots=True)
class Check:
    """One asked quantity: the value read off the plan against the exact value; ``noise`` is
    the exact value's own error bound (round-off, and near a toggle the group's estimate): an
    exact value within it is zero, and has no relative error (a speed at a dead centre)."""

    quantity: str
    plan: float | None
    analytic: float | None
    unit: str
    noise: float = 0.0

    @property
    def abs_error(self) -> float | None:
        if self.plan is None or self.analytic is None:
            return None
        return abs(self.plan - self.analytic)

    @property
    def rel_error(self) -> float | None:
        if self.abs_error is None or abs(self.analytic) <= self.noise:
            return None
        return self.abs_error / abs(self.analytic)

    def as_dict(self) -> dict:
        return {"quantity": self.quantity, "plan": self.plan, "analytic": self.analytic,
                "abs_error": self.abs_error, "rel_error": self.rel_error, "unit": self.unit}


@dataclass(frozen=True)
class Analysis:
    """Everything computed for one exercise at one crank angle."""

    exercise: Exercise
    angle: float
    structure: Structure
    scene: Scene
    motion: Motion
    plans: Plans | None
    checks: tuple[Check, ...]
    forces: ForceAnalysis | None = None

    @property
    def flags(self) -> tuple[Message | str, ...]:
        """Plan flags (intersections at small angles) and groups whose exact values lose
        digits near their toggle (estimated relative error above 1e-6)."""
        numbers = course_numbers(self.exercise.mechanism)
        flags: list[Message | str] = ([flag_message(flag, numbers) for flag in self.plans.flags]
                                      if self.plans else [])
        for index, solved in sorted(self.motion.groups.items()):
            for stage, values in (solved.error_estimate or {}).items():
                estimate = float(np.max(values))
                if estimate > FLAG_ERROR:
                    links = vocabulary.links_text(self.structure.groups[index].links,
                                                  numbers)            # words: vocabulary
                    flags.append(_NEAR_TOGGLE[stage].replace(number=index + 1, links=links,
                                                             estimate=estimate))
        return tuple(flags)


def asked_quantities(exercise: Exercise, motion: Motion) -> list[str]:
    """The quantities a check table lists: ``v_C``, ``a_C``, ``omega_BC``, ``epsilon_BC``,
    ``rho_D``, and ``s_``/``ds_``/``dds_``/``coriolis_`` of a prismatic pair."""
    ask, mechanism = exercise.ask, exercise.mechanism
    if ask.everything:
        points = [p for link in motion.links if link != FRAME
                  for p in mechanism.links[link].points
                  if FRAME not in mechanism.links_with_point(p)]  # fixed pivots do not move
        points = list(dict.fromkeys(points))
        links = [link for link in motion.links if link not in (FRAME, mechanism.drive.link)]
        slides = [s.key for s in mechanism.slides]
        return ([f"v_{p}" for p in points] + [f"a_{p}" for p in points]
                + [f"omega_{link}" for link in links] + [f"epsilon_{link}" for link in links]
                + [f"{q}_{key}" for key in slides for q in ("s", "ds", "dds", "coriolis")])
    acceleration = motion.stage == "acceleration"
    out = [f"v_{p}" for p in ask.velocity] + [f"a_{p}" for p in ask.acceleration]
    out += [f"omega_{link}" for link in ask.omega] + [f"epsilon_{link}" for link in ask.epsilon]
    out += [f"rho_{p}" for p in ask.curvature]
    for key in ask.sliding:
        out += [f"s_{key}", f"ds_{key}"]
        if acceleration:
            out += [f"dds_{key}", f"coriolis_{key}"]
    return out


def _radius(motion: MotionAt, point: str) -> float | None:
    rho = float(motion.curvature(point).rho)
    return None if math.isnan(rho) else rho


#: how each kind of quantity (vocabulary.QUANTITY_KINDS) is read from a motion, by its prefix
EXACT_READERS = {
    "v": lambda motion, name: float(norm(motion.velocity(name))),
    "a": lambda motion, name: float(norm(motion.acceleration(name))),
    "omega": lambda motion, name: float(motion.omega(name)),
    "epsilon": lambda motion, name: float(motion.epsilon(name)),
    "rho": _radius,
    "s": lambda motion, name: float(motion.sliding(name).s),
    "ds": lambda motion, name: float(motion.sliding(name).velocity),
    "dds": lambda motion, name: float(motion.sliding(name).acceleration),
    "coriolis": lambda motion, name: float(norm(motion.sliding(name).coriolis)),
}


def exact_value(motion: MotionAt, quantity: str) -> float | None:
    """The exact value of a check quantity (magnitudes for v and a; signed ω, ε, s, ds, dds)
    at one crank angle.

    Raises
    ------
    KeyError
        If the quantity's prefix names no known kind.
    """
    kind, _, name = quantity.partition("_")
    return EXACT_READERS[kind](motion, name)


#: the relative round-off of an exact value: a value below this times its kind's typical size
#: (the mechanism's size L, ω1·L, (ω1² + |ε1|)·L; per L for a link's ω, ε) is zero
ROUND_OFF = 64 * float(np.finfo(float).eps)
#: the stage whose exact values a scale's quantities are
_STAGE_OF_SCALE = {"mu_l": "position", "mu_v": "velocity", "mu_a": "acceleration"}


def _noise(motion: Motion, quantity: str) -> float:
    """The error bound of a quantity's exact value at the motion's first angle: its kind's
    typical size times the round-off, or the groups' estimate near a toggle where larger."""
    mechanism = motion.mechanism
    kind = vocabulary.quantity(quantity).kind
    if kind.scale not in _STAGE_OF_SCALE:
        return 0.0
    size = max((link.length(first, second) for link in mechanism.links.values()
                for first in link.points for second in link.points), default=0.0) or 1.0
    omega, epsilon = abs(mechanism.drive.omega), abs(mechanism.drive.epsilon)
    typical = {"mu_l": size, "mu_v": omega * size, "mu_a": (omega ** 2 + epsilon) * size}
    scale = typical[kind.scale] / (size if kind.subject == "link" else 1.0)
    stage = _STAGE_OF_SCALE[kind.scale]
    estimates = [float(np.max(solved.error_estimate[stage]))
                 for solved in motion.groups.values()
                 if solved.error_estimate and stage in solved.error_estimate]
    return scale * max([ROUND_OFF, *estimates])


def analyse(exercise: Exercise, angle: float | None = None, *, precision_mm: float | None = None,
            plans: bool = True) -> Analysis:
    """Solve the exercise's scene at one crank angle (default ``drive.angle``).

    Parameters
    ----------
    exercise
        The exercise.
    angle
        Crank angle (deg). The assemblies are those chosen at ``drive.angle`` (the sketch or
        the default branch), followed to this angle as a sweep follows them
        (:func:`~planmethod.kinematics.continuation.pose`); a group that meets a limit position on
        the way is a ``ToggleError`` naming it and the crank angle of the limit.
    precision_mm
        Overrides ``[plan] precision_mm``.
    plans
        Draw the plans (and check them); with False only the exact values are computed.
    """
    scene = plan_scene(exercise)
    branches = None
    if angle is not None and angle != exercise.mechanism.drive.angle:
        # the assembly chosen at drive.angle, followed to the angle as a sweep follows it
        posed = pose(exercise.mechanism, angle, links=scene.links)
        exercise, branches = replace(exercise, mechanism=posed.mechanism), posed.branches
    if precision_mm is not None:
        exercise = replace(exercise, plan=replace(exercise.plan, precision_mm=precision_mm))
    mechanism = exercise.mechanism
    angle = mechanism.drive.angle
    motion = solve(mechanism, angle, stage=scene.stage, links=scene.links, branches=branches)
    structure = motion.structure
    drawn = None
    if plans:
        try:
            drawn = draw_plans(exercise, angle, motion=motion,
                               acceleration=scene.stage == "acceleration")
        except PlansUnavailableError:  # a higher group that is not drawn: exact values only
            drawn = None
    checks = []
    here = motion.at(0)
    for quantity in asked_quantities(exercise, motion):
        plan_value = drawn.readings.get(quantity) if drawn else None
        checks.append(Check(quantity, plan_value, exact_value(here, quantity),
                            vocabulary.quantity(quantity).unit, _noise(motion, quantity)))
    forces = None
    if scene.forces:
        from .forces import analyse_forces

        forces = analyse_forces(exercise, motion, plans=drawn)
    return Analysis(exercise, angle, structure, scene, motion, drawn, tuple(checks), forces)


def _vector(array) -> list[float]:
    return [float(array[0]), float(array[1])]


def _finite(value):
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def report_dict(analysis: Analysis) -> dict:
    """The JSON report (docs/json-report.md).

    Parameters
    ----------
    analysis
        What :func:`analyse` returned.
    """
    exercise, motion = analysis.exercise, analysis.motion
    report: dict[str, Any] = {"title": exercise.mechanism.title, "angle": analysis.angle,
                              "structure": _structure_dict(analysis)}
    if analysis.plans:
        report["scales"] = analysis.plans.scales.as_dict()
    asked = _Asked.of(analysis)
    here = motion.at(0)
    acceleration = motion.stage == "acceleration"
    report["points"] = {point: _point_dict(here, point, acceleration)
                        for point in asked.points}
    report["links"] = {link: _link_dict(here, link, acceleration) for link in asked.links}
    if acceleration and asked.curvature:
        report["curvature"] = {point: _curvature_dict(here.curvature(point))
                               for point in asked.curvature}
    if asked.sliding:
        report["sliding"] = {key: _sliding_dict(here.sliding(key), acceleration)
                             for key in asked.sliding}
    if analysis.plans:
        report["plans"] = _plans_dict(analysis.plans)
    report["checks"] = [check.as_dict() for check in analysis.checks]
    if exercise.published:
        report["published"] = {"source": exercise.published_source,
                               "values": [row.as_dict()
                                          for row in published_comparison(analysis)]}
    report["flags"] = [render(flag) for flag in analysis.flags]
    if analysis.forces is not None:
        report["forces"] = analysis.forces.as_dict()
    return report


def _structure_dict(analysis: Analysis) -> dict:
    """The structure: the counts, W, and each Assur group with its assembly (its branch and
    why) and, for a dyad, how far from its toggle its lines meet."""
    structure, motion = analysis.structure, analysis.motion
    numbers = course_numbers(analysis.exercise.mechanism)
    return {"n": structure.n, "p5": structure.p5, "p4": structure.p4, "W": structure.mobility,
            "groups": [_group_dict(group, motion, numbers) for group in structure.groups]}


def _group_dict(group, motion: Motion, numbers: dict[str, int]) -> dict:
    """One Assur group of the structure (see :func:`_structure_dict`), its links in the
    order of their numbers in the course's notation (as the text lists them)."""
    links = sorted(group.links, key=lambda link: numbers.get(link, len(numbers)))
    entry: dict[str, Any] = {"type": group.kind, "links": links,
                             "class": group.group_class, "order": group.order,
                             "pairs": [joint.label for joint in group.joints]}
    if group.type_number:
        entry["type_number"] = group.type_number
    if group.index in motion.branches:
        branch = motion.branches[group.index]
        entry["branch"] = {"sign": branch.sign, "reason": branch.reason}
    solved = motion.groups.get(group.index)
    if solved is not None and solved.line_sine is not None and group.is_dyad:
        sine = abs(float(solved.line_sine[0]))
        entry["line_angle_deg"] = math.degrees(math.asin(min(1.0, sine)))
        entry["error_estimate"] = {stage: float(values[0]) for stage, values in
                                   (solved.error_estimate or {}).items()}
    return entry


@dataclass(frozen=True, slots=True)
class _Asked:
    """What the report tabulates: the points (velocity, acceleration, curvature, in that
    order, each once), the links, the points whose curvature and the pairs whose sliding it
    gives."""

    points: tuple[str, ...]
    links: tuple[str, ...]
    curvature: tuple[str, ...]
    sliding: tuple[str, ...]

    @classmethod
    def of(cls, analysis: Analysis) -> _Asked:
        exercise, motion = analysis.exercise, analysis.motion
        mechanism, ask = exercise.mechanism, exercise.ask
        if ask.everything:
            points = tuple(dict.fromkeys(p for link in motion.links
                                         for p in mechanism.links[link].points))
            return cls(points, tuple(link for link in motion.links if link != FRAME),
                       tuple(p for p in points if link_of(motion, p) != FRAME),
                       tuple(s.key for s in mechanism.slides))
        points = tuple(dict.fromkeys(tuple(ask.velocity) + tuple(ask.acceleration)
                                     + tuple(ask.curvature)))
        return cls(points, tuple(dict.fromkeys(ask.omega + ask.epsilon)),
                   tuple(ask.curvature), tuple(ask.sliding))


def _point_dict(here: MotionAt, point: str, acceleration: bool) -> dict:
    """A point's position, velocity (and acceleration)."""
    entry = {"position": _vector(here.position(point)), "velocity": _vector(here.velocity(point))}
    if acceleration:
        entry["acceleration"] = _vector(here.acceleration(point))
    return entry


def _link_dict(here: MotionAt, link: str, acceleration: bool) -> dict:
    """A link's ω and θ (and ε)."""
    entry = {"omega": float(here.omega(link)), "theta": float(here.theta(link))}
    if acceleration:
        entry["epsilon"] = float(here.epsilon(link))
    return entry


def _curvature_dict(found) -> dict:
    """A point's path curvature: ρ and the centre, or straight; an inflection, a stop."""
    if found.straight:
        return {"rho": None, "center": None, "straight": True}
    rho = _finite(found.rho)
    entry = {"rho": rho, "center": _vector(found.center) if rho else None}
    if bool(found.inflection):
        entry["inflection"] = True
    if bool(found.stationary):
        entry["stationary"] = True
    return entry


def _sliding_dict(found, acceleration: bool) -> dict:
    """A prismatic pair's travel and sliding velocity (and acceleration, Coriolis)."""
    entry = {"s": float(found.s), "velocity": float(found.velocity)}
    if acceleration:
        entry |= {"acceleration": float(found.acceleration),
                  "coriolis": _vector(found.coriolis)}
    return entry


def _plans_dict(plans: Plans) -> dict:
    """The plans' data (docs/json-report.md, "Plans")."""
    out = {"position": plans.position.as_dict(), "velocity": plan_dict(plans.velocity)}
    if plans.acceleration:
        out["acceleration"] = plan_dict(plans.acceleration)
    return out


#: a published value further than this from the exact one (relative) is flagged as a slip
SLIP_RELATIVE = 0.05


@dataclass(frozen=True, slots=True)
class PublishedValue:
    """A book's printed value against the exact one: the quantity, the printed value, the
    exact one (None where the quantity cannot be computed), their difference in per cent of
    the exact magnitude and whether it is likely a slip (more than :data:`SLIP_RELATIVE`)."""

    quantity: str
    published: float
    exact: float | None
    difference_percent: float | None
    likely_slip: bool

    def as_dict(self) -> dict:
        """The JSON report's ``published.values`` entry."""
        return {"quantity": self.quantity, "published": self.published, "exact": self.exact,
                "difference_percent": self.difference_percent,
                "likely_slip": self.likely_slip}


def published_comparison(analysis: Analysis) -> list[PublishedValue]:
    """The book's printed values against the exact ones (of the magnitudes, since books print
    magnitudes and state the sense in words), each likely a slip when more than 5 % off:
    beyond any drawing error at a course's scales.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> path = "exercises/compressor_slider_crank.toml"
    >>> rows = published_comparison(analyse(load_exercise(path)))
    >>> [(r.quantity, round(r.difference_percent, 1), r.likely_slip) for r in rows][:2]
    [('v_B', 0.0, False), ('v_C', -24.1, True)]
    """
    rows = []
    for name, printed in analysis.exercise.published.items():
        try:
            exact = exact_value(analysis.motion.at(0), name)
        except (KeyError, ValueError, PlanmethodError):
            exact = None
        difference, slip = None, False
        noise = _noise(analysis.motion, name) if exact is not None else 0.0
        if exact is not None and abs(exact) > noise:
            difference = (abs(printed) - abs(exact)) / abs(exact)
            slip = abs(difference) > SLIP_RELATIVE
        elif exact is not None:            # zero to within its round-off: no relative error
            slip = abs(printed) > noise
        rows.append(PublishedValue(name, float(printed), exact,
                                   None if difference is None else 100 * difference, slip))
    return rows


def link_of(motion: Motion, point: str) -> str:
    return motion.locate(point)[0]
