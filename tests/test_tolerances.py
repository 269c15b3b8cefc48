"""The drawing tolerances come from one drawing made in copies (one copy per segment, that
segment lengthened by δ) — the same numbers as drawing the plans once per segment, which is
what a student's error in one segment does and what these tests do the slow way."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from planmethod.errors import PlanmethodError
from planmethod.grading.tolerances import (
    DELTA_MM,
    _plan_points,
    _Recorder,
    emulate_drawings,
    propagate,
)
from planmethod.kinematics import solve
from planmethod.plans import draw_plans
from planmethod.plans.construction import PlansUnavailableError
from planmethod.report import asked_quantities
from planmethod.spec import load_exercise

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))


def by_redrawing(exercise, precision_mm: float):
    """(sensitivity of each quantity, of each plan point): one drawing per segment."""
    acceleration = exercise.ask.needs_acceleration
    motion = solve(exercise.mechanism, exercise.mechanism.drive.angle,
                   stage="acceleration" if acceleration else "velocity")
    settings = replace(exercise.plan, precision_mm=0.0)
    recorder = _Recorder()
    base = draw_plans(exercise, settings=settings, motion=motion, acceleration=acceleration,
                      perturb=recorder)
    quantities = asked_quantities(exercise, motion)
    count = len(recorder.segments)
    values = {q: np.zeros(count) for q in quantities}
    points = {}
    for index in range(count):
        errors = np.zeros(count)
        errors[index] = DELTA_MM
        drawn = draw_plans(exercise, settings=settings, motion=motion,
                           acceleration=acceleration, perturb=_Recorder(errors),
                           scales=base.scales, position=False)
        for q in quantities:
            if q in base.readings and q in drawn.readings:
                values[q][index] = (drawn.readings[q] - base.readings[q]) / DELTA_MM
        for plan, labels in _plan_points(drawn).items():
            for label, xy in labels.items():
                before = _plan_points(base)[plan][label]
                points.setdefault((plan, label), np.zeros((count, 2)))[index] = (
                    (xy - before) / DELTA_MM)
    return values, points


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.stem)
def test_one_drawing_in_copies_gives_each_segments_sensitivity(path):
    exercise = load_exercise(path)
    try:
        found = propagate(exercise, 0.5)
    except PlansUnavailableError:
        pytest.skip("no drawn plans for this exercise's groups")
    values, points = by_redrawing(exercise, 0.5)
    assert found.sensitivity.keys() == values.keys()
    for quantity, expected in values.items():
        got = found.sensitivity[quantity]
        scale = max(1.0, float(np.max(np.abs(expected))))
        assert np.max(np.abs(got - expected)) <= 1e-8 * scale, quantity
    radii = found.radii
    for (plan, label), expected in points.items():
        # the radius of a point is Σ|∂X/∂e_i|·precision/2 from the same sensitivities
        radius = float(np.sum(np.hypot(expected[:, 0], expected[:, 1]))) * 0.25
        assert abs(radii[plan][label] - radius) <= 1e-8 * max(1.0, radius), (plan, label)


def test_the_tolerance_analysis_carries_its_own_errors_whatever_the_exercises_precision():
    """The tolerance analysis and the random drawings draw exactly and add the errors given:
    the exercise's own drafting precision plays no part — one of 1000 mm, at which no plan
    can be drawn (the links' lengths round to 0 mm, and any two construction lines are
    parallel to within the precision of a 1000 mm sheet), changes nothing."""
    exercise = load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml")
    coarse = replace(exercise, plan=replace(exercise.plan, precision_mm=1000.0))
    fine = replace(exercise, plan=replace(exercise.plan, precision_mm=0.0))
    with pytest.raises(PlanmethodError, match="precision"):
        draw_plans(coarse, position=False)
    exact = emulate_drawings(fine, 0.5, 5, seed=11)
    drawn = emulate_drawings(coarse, 0.5, 5, seed=11)
    assert drawn.keys() == exact.keys()
    for name, values in exact.items():
        assert np.array_equal(drawn[name], values, equal_nan=True), name
    found, expected = propagate(coarse, 0.5), propagate(fine, 0.5)
    assert (found.readings, found.tolerances, found.radii, found.lengths) == (
        expected.readings, expected.tolerances, expected.radii, expected.lengths)


def test_random_drawings_in_copies_equal_the_drawings_one_by_one():
    exercise = load_exercise(ROOT / "exercises" / "slotted_lever.toml")
    together = emulate_drawings(exercise, 0.5, 5, seed=11)
    generator = np.random.default_rng(11)
    errors = generator.uniform(-0.25, 0.25, size=(5, 256))
    settings = replace(exercise.plan, precision_mm=0.0)
    for k in range(5):
        alone = draw_plans(exercise, settings=settings, perturb=_Recorder(errors[k]),
                           position=False)
        for quantity, value in alone.readings.items():
            if quantity in together:
                assert abs(together[quantity][k] - value) <= 1e-12 * max(1.0, abs(value))
        for plan, labels in _plan_points(alone).items():
            for label, xy in labels.items():
                assert np.allclose(together[f"points:{plan}:{label}"][k], xy, rtol=0,
                                   atol=1e-9)


@pytest.mark.parametrize("name", ["compressor_slider_crank", "conveyor_sixbar",
                                  "slotted_lever", "loaded_press_sixbar"])
def test_a_key_keyed_on_an_analysiss_exact_drawing_is_the_key_drawn_anew(name):
    """A workbook frame's key takes the analysis's plans as its exact drawing instead of
    drawing them again: the same key, to the last bit, at the exercise's own angle and at
    others (followed there as a sweep follows the assembly)."""
    from planmethod.grading.keys import build_key
    from planmethod.grading.templates import draw_variant, load_template
    from planmethod.grading.tolerances import exact_drawing
    from planmethod.report import analyse

    path = ROOT / "exercises" / f"{name}.toml"
    variant = draw_variant(load_template(str(path)))
    exercise = load_exercise(path)
    for angle in (exercise.mechanism.drive.angle, 37.0, 200.0):
        analysis = analyse(exercise, angle)
        assert exact_drawing(analysis.plans, analysis.exercise)
        keyed = replace(variant, exercise=analysis.exercise)
        assert build_key(keyed, plans=analysis.plans) == build_key(keyed)


def test_only_an_exact_drawing_of_that_exercise_stands_for_the_keys_own():
    """Drawn with a drafting precision, with an error model, of another exercise object or
    without the acceleration plan it asks for, plans are drawn again for the key."""
    from planmethod.grading.tolerances import exact_drawing

    exercise = load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml")
    exact = draw_plans(exercise)
    assert exact_drawing(exact, exercise) and len(exact.exact) > 10
    rounded = replace(exercise.plan, precision_mm=0.5)
    assert draw_plans(exercise, settings=rounded).exact is None
    assert draw_plans(exercise, perturb=_Recorder()).exact is None
    assert not exact_drawing(exact, replace(exercise))
    assert not exact_drawing(draw_plans(exercise, acceleration=False), exercise)
    recorder = _Recorder()
    draw_plans(exercise, perturb=recorder)
    assert [length for length, _ in exact.exact] == recorder.lengths
    assert [segment for _, segment in exact.exact] == recorder.segments
