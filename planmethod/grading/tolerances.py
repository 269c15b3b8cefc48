"""Tolerances that follow from the drawing (the mistakes and their answers are in
:mod:`planmethod.grading.mistakes`).

The drafting-error model is the one of ``PlanSettings.precision_mm`` (docs/accuracy.md): every
length laid off or read off a drawing — on the position plan, the velocity plan and the acceleration
plan — carries an error uniform in ±precision/2; directions are drawn exactly. The plan
emulator (:func:`planmethod.plans.draw_plans`) is run once exactly, recording the segments,
and once more drawing one copy per segment, copy i with segment i lengthened by a small δ (its
``perturb`` hook returns one length per copy, so the whole drawing is made for every copy at
once), which gives the sensitivity ∂q/∂e_i of every quantity read off the plans and ∂X/∂e_i of
every plan point to every segment error. The tolerance is the linear worst case

    tol(q) = Σ_i |∂q/∂e_i| · precision/2,        radius(X) = Σ_i |∂X/∂e_i| · precision/2,

so that any drawing whose every segment is within ±precision/2 is accepted (to first order);
:func:`emulate_drawings` draws many random drawings to check it. A floor keeps tolerances
sensible near zero values and for an exact drawing: ``rel_floor``·|q| (default 0.5 %), and an
absolute floor of 0.1 % of the drive's own value of the same kind (v_B, a_B, ω1, …).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> found = propagate(load_exercise("exercises/compressor_slider_crank.toml"), 0.5)
>>> round(found.values["v_C"], 4), 0.0 < found.tolerances["v_C"] < 0.1 * found.values["v_C"]
(5.2716, True)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..model import Exercise
from ..plans.construction import Segment
from ..plans.steps import DropSteps
from ..vectors import norm
from ..vocabulary import QUANTITY_KINDS

__all__ = [
    "Propagation",
    "emulate_drawings",
    "kind_of",
    "propagate",
    "scale_factor",
]

#: The segment lengthening used to measure sensitivities (mm).
DELTA_MM = 1e-4

def kind_of(quantity: str) -> str:
    """The kind of a quantity name: ``v_C`` → ``v``, ``omega_BC`` → ``omega``."""
    return quantity.partition("_")[0]


@dataclass(frozen=True)
class Propagation:
    """Exact values and drawing-derived tolerances of one exercise at one angle.

    ``values``: quantity → exact value; ``tolerances``: quantity → absolute tolerance from the
    drawing (before floors); ``sensitivity``: quantity → array of ∂q/∂e_i; ``points``:
    plan → label → exact point (mm); ``radii``: plan → label → tolerance radius (mm);
    ``segments``: the :class:`~planmethod.plans.construction.Segment` of each e_i;
    ``lengths``: the exact length (mm) drawn for each.
    """

    values: Mapping[str, float]
    readings: Mapping[str, float]
    tolerances: Mapping[str, float]
    sensitivity: Mapping[str, np.ndarray]
    points: Mapping[str, Mapping[str, tuple[float, float]]]
    radii: Mapping[str, Mapping[str, float]]
    segments: tuple[Segment, ...]
    precision_mm: float
    plans: object
    lengths: tuple[float, ...] = ()


class _Recorder:
    """A perturbation model: records the segments and adds to segment i the errors
    ``errors[..., i]`` — a number (one drawing), or one number per copy of the drawing (an
    array over copies: the emulator then draws every copy at once). Without errors the lengths
    are drawn as they are."""

    def __init__(self, errors=None) -> None:
        self.errors = None if errors is None else np.asarray(errors, dtype=float)
        self.segments: list[Segment] = []
        self.lengths: list = []

    def __call__(self, length, segment: Segment):
        index = len(self.segments)
        self.segments.append(segment)
        self.lengths.append(length)
        if self.errors is None or index >= self.errors.shape[-1]:
            return length
        return length + self.errors[..., index]


def _plan_points(plans) -> dict[str, dict[str, np.ndarray]]:
    out = {"velocity": {k: np.asarray(v) for k, v in plans.velocity.points_mm.items()}}
    if plans.acceleration is not None:
        out["acceleration"] = {k: np.asarray(v) for k, v in plans.acceleration.points_mm.items()}
    return out


def propagate(exercise: Exercise, precision_mm: float, *, quantities=None,
              motion=None, plans=None) -> Propagation:
    """Exact values, readings and drawing tolerances of the exercise's asked quantities.

    Parameters
    ----------
    exercise
        The exercise (drawn at its own scales, at ``drive.angle``).
    precision_mm
        The drafting precision: each segment within ±precision_mm/2.
    quantities
        The quantities (default: those the exercise asks, see
        :func:`planmethod.report.asked_quantities`).
    motion
        The exact motion at ``drive.angle``, if solved already.
    plans
        The exercise's plans drawn already, if so: taken as the exact drawing where they are
        one (:func:`exact_drawing`), not drawn again.
    """
    from ..kinematics import solve
    from ..report import asked_quantities, exact_value

    mechanism = exercise.mechanism
    acceleration = exercise.ask.needs_acceleration
    if motion is None:
        motion = solve(mechanism, mechanism.drive.angle,
                       stage="acceleration" if acceleration else "velocity")
    settings = replace(exercise.plan, precision_mm=0.0)
    base, recorder = _base_drawing(exercise, settings, motion, plans)
    if quantities is None:
        quantities = asked_quantities(exercise, motion)
    here = motion.at(0)
    values = {q: exact_value(here, q) for q in quantities}
    points = _plan_points(base)
    sensitivity, point_sensitivity = _sensitivities(exercise, settings, motion, base,
                                                    len(recorder.segments), quantities, points)
    half = precision_mm / 2.0
    tolerances = {q: float(np.sum(np.abs(sensitivity[q]))) * half for q in quantities}
    radii = {plan: {label: float(np.sum(norm(s))) * half
                    for label, s in labels.items()}
             for plan, labels in point_sensitivity.items()}
    return Propagation(
        values=values, readings=dict(base.readings), tolerances=tolerances,
        sensitivity=sensitivity,
        points={plan: {k: (float(v[0]), float(v[1])) for k, v in labels.items()}
                for plan, labels in points.items()},
        radii=radii, segments=tuple(recorder.segments), precision_mm=precision_mm, plans=base,
        lengths=tuple(float(length) for length in recorder.lengths))


def _sensitivities(exercise: Exercise, settings, motion, base, count: int, quantities,
                   points: Mapping[str, Mapping[str, np.ndarray]]) -> tuple[dict, dict]:
    """Each quantity's and each plan point's change per mm of each of the ``count`` segments
    of the exact drawing ``base``: one drawing in copies, copy i with segment i lengthened by
    δ (the same position, the scales kept, no mechanism drawn)."""
    from ..plans import draw_plans

    sensitivity = {q: np.zeros(count) for q in quantities}
    point_sensitivity = {plan: {label: np.zeros((count, 2)) for label in labels}
                         for plan, labels in points.items()}
    if not count:
        return sensitivity, point_sensitivity
    drawn = draw_plans(exercise, settings=settings, motion=motion,
                       acceleration=exercise.ask.needs_acceleration,
                       perturb=_Recorder(DELTA_MM * np.eye(count)), scales=base.scales,
                       position=False, recorder=DropSteps)
    for q in quantities:
        if q in base.readings and q in drawn.readings:
            sensitivity[q][:] = (drawn.readings[q] - base.readings[q]) / DELTA_MM
    for plan, labels in _plan_points(drawn).items():
        for label, xy in labels.items():
            if label in point_sensitivity[plan]:
                point_sensitivity[plan][label][:] = (xy - points[plan][label]) / DELTA_MM
    return sensitivity, point_sensitivity


def _base_drawing(exercise: Exercise, settings, motion, plans) -> tuple[Any, _Recorder]:
    """The exact drawing the tolerances are found round, and the recorder of what it laid off
    and read off: ``plans`` where they are it (:func:`exact_drawing`), else drawn now."""
    from ..plans import draw_plans

    recorder = _Recorder()
    if exact_drawing(plans, exercise):
        for length, segment in plans.exact:
            recorder(length, segment)
        return plans, recorder
    return draw_plans(exercise, settings=settings, motion=motion,
                      acceleration=exercise.ask.needs_acceleration, perturb=recorder), recorder


def exact_drawing(plans, exercise: Exercise) -> bool:
    """Whether ``plans`` are the exact drawing :func:`propagate` would draw of ``exercise``:
    drawn of that very exercise at its own angle, with its position plan and every plan it
    asks for, with no drafting error (precision 0), with their steps.

    >>> from planmethod.plans import draw_plans
    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
    >>> exact_drawing(draw_plans(exercise), exercise), exact_drawing(None, exercise)
    (True, False)
    """
    return (plans is not None and plans.exact is not None and plans.exercise is exercise
            and plans.angle == exercise.mechanism.drive.angle and plans.position is not None
            and (plans.acceleration is not None) == exercise.ask.needs_acceleration
            and bool(plans.velocity.steps))


def emulate_drawings(exercise: Exercise, precision_mm: float, count: int, *, seed: int = 0,
                     quantities=None, motion=None) -> dict[str, np.ndarray]:
    """Read the quantities off ``count`` random drawings (every segment's error uniform in
    ±precision_mm/2): quantity → array of values, plus ``points:<plan>:<label>`` → (count, 2).
    """
    from ..kinematics import solve
    from ..plans import draw_plans
    from ..report import asked_quantities

    mechanism = exercise.mechanism
    acceleration = exercise.ask.needs_acceleration
    if motion is None:
        motion = solve(mechanism, mechanism.drive.angle,
                       stage="acceleration" if acceleration else "velocity")
    if quantities is None:
        quantities = asked_quantities(exercise, motion)
    settings = replace(exercise.plan, precision_mm=0.0)
    generator = np.random.default_rng(seed)
    errors = generator.uniform(-precision_mm / 2, precision_mm / 2, size=(count, 256))
    # every drawing at once: copy k draws with errors[k]
    drawn = draw_plans(exercise, settings=settings, motion=motion, acceleration=acceleration,
                       perturb=_Recorder(errors), position=False, recorder=DropSteps)
    out = {q: np.broadcast_to(np.asarray(drawn.readings.get(q, math.nan), dtype=float),
                              (count,)).copy() for q in quantities}
    for plan, labels in _plan_points(drawn).items():
        for label, xy in labels.items():
            out[f"points:{plan}:{label}"] = np.broadcast_to(np.asarray(xy, dtype=float),
                                                            (count, 2)).copy()
    return out


def scale_factor(quantity: str, mu_l: float, mu_v: float, mu_a: float) -> float | None:
    """The factor that turns a drawn length (mm, or mm/mm) into the quantity: the scale a
    student might leave out or apply twice."""
    kind = QUANTITY_KINDS.get(kind_of(quantity))
    if kind is None or kind.scale is None:
        return None
    if kind.prefix == "rho":  # ρ = (pd)²·μv² / ((πn_D)·μa): mm at μv²/μa
        return mu_v ** 2 / mu_a
    factor = {"mu_l": mu_l, "mu_v": mu_v, "mu_a": mu_a}[kind.scale]
    return factor / mu_l if kind.subject == "link" else factor  # ω = (bc)·μv / ((BC)·μl)
