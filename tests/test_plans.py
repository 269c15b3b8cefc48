"""The plan emulator: at precision 0 every plan point and reading equals the exact vector; plans
close; images obey the similarity rule; scales change no result; drafting precision shows."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planmethod.errors import AssemblyError, SpecError, ToggleError
from planmethod.kinematics import solve
from planmethod.plans import draw_plans, image_label
from planmethod.render.plan_words import flag_message, step_text
from planmethod.render.report_text import check_lines
from planmethod.report import analyse, report_dict
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.testing import (
    fourbar,
    scotch_yoke,
    shaper,
    slider_crank,
    slotted_lever,
    two_guides,
)
from planmethod.words import render

MECHANISMS = {
    "RRR four-bar": fourbar(),
    "RRP slider-crank": slider_crank(),
    "RRP offset, ε1 ≠ 0": slider_crank(offset=0.02, epsilon=250.0),
    "RPR slotted lever": slotted_lever(epsilon=3.0),
    "RPP scotch yoke": scotch_yoke(),
    "PRP two guides": two_guides(),
    "RPR + RRP shaper": shaper(),
}
EXERCISES = ["compressor_slider_crank", "fourbar_coupler_point", "offset_slider_crank",
             "slotted_lever", "shaper_sixbar"]


def _ref_of(label: str) -> str | None:
    """The point reference a plan label stands for (None for poles and n_/k_ points)."""
    if label in ("p", "π") or label.startswith(("n_", "k_", "k1_", "k2_")):
        return None
    name, at, link = label.partition("@")
    return name.replace("′", "").upper() + (at + link)


def _check_plan_points(plans, motion, tolerance=1e-9):
    for plan, exact in ((plans.velocity, motion.velocity), (plans.acceleration,
                                                             motion.acceleration)):
        size = max(1.0, max(math.hypot(*xy) for xy in plan.points_mm.values()))
        for label, xy in plan.points_mm.items():
            ref = _ref_of(label)
            if ref is None:
                continue
            expected = np.asarray(exact(ref)) / plan.scale
            assert np.allclose(xy, expected, rtol=0, atol=tolerance * size), (plan.kind, label)


def _angles(data):
    """Angles every 15° at which the mechanism assembles."""
    exercise = exercise_from_dict(data)
    out = []
    for angle in np.arange(0.0, 360.0, 15.0):
        try:
            solve(exercise.mechanism, angle, stage="position")
        except (AssemblyError, ToggleError):
            continue
        out.append(float(angle))
    return out


@pytest.mark.parametrize("name", list(MECHANISMS))
def test_exact_plan_equals_analytic_at_every_angle(name):
    data = MECHANISMS[name]
    for angle in _angles(data):
        changed = dict(data)
        changed["drive"] = dict(data["drive"], angle=angle)
        exercise = exercise_from_dict(changed)
        analysis = analyse(exercise)
        _check_plan_points(analysis.plans, analysis.motion)
        for check in analysis.checks:
            if check.analytic is None:
                assert check.plan is None, check.quantity
                continue
            assert check.plan == pytest.approx(check.analytic, rel=1e-9, abs=1e-9), (
                name, angle, check.quantity)


@pytest.mark.parametrize("name", EXERCISES)
def test_shipped_exercises_plan_equals_exact(name):
    analysis = analyse(load_exercise(f"exercises/{name}.toml"))
    _check_plan_points(analysis.plans, analysis.motion)
    assert analysis.checks
    for check in analysis.checks:
        if check.rel_error is not None:
            assert check.rel_error <= 1e-9, check.quantity
        elif check.analytic is not None:
            assert check.abs_error <= 1e-12, check.quantity


@pytest.mark.parametrize("angle", [0.0, 180.0])
def test_crank_dead_centre_is_an_ordinary_position(angle):
    exercise = exercise_from_dict(slider_crank(angle=angle) | {
        "ask": {"velocity": ["C", "D"], "acceleration": ["C"], "omega": ["BC"],
                "epsilon": ["BC"], "curvature": ["D"]}})
    analysis = analyse(exercise)
    assert float(np.hypot(*analysis.motion.at(0).velocity("C"))) == pytest.approx(0.0, abs=1e-12)
    readings = analysis.plans.readings
    assert readings["v_C"] == pytest.approx(0.0, abs=1e-12)
    # the images of C coincides with the pole, and ω_BC = ∓ω1·l_AB/l_BC
    assert np.allclose(analysis.plans.velocity.points_mm["c"], 0.0, atol=1e-9)
    assert readings["omega_BC"] == pytest.approx(-100 * 0.06 / 0.18 * math.cos(
        math.radians(angle)), rel=1e-9)
    assert not analysis.plans.flags
    # v_C and ε_BC are zero to within their round-off: no relative error, printed "—"
    checks = {check.quantity: check for check in analysis.checks}
    assert checks["v_C"].rel_error is None and checks["epsilon_BC"].rel_error is None
    assert checks["v_D"].rel_error is not None and checks["v_D"].rel_error <= 1e-9
    assert abs(checks["v_C"].analytic) <= checks["v_C"].noise <= 1e-12
    lines = [line.split() for line in check_lines(analysis)[2:]]
    assert {line[0]: line[-2] for line in lines}["v_C"] == "—"


def test_every_intersection_lies_on_both_lines():
    for data in MECHANISMS.values():
        plans = draw_plans(exercise_from_dict(data))
        for plan in (plans.velocity, plans.acceleration):
            lines = {step.number: step for step in plan.steps if step.action == "line"}
            for step in plan.steps:
                if step.action != "intersect":
                    continue
                point = np.asarray(plan.points_mm[step.end])
                for number in step.lines:
                    line = lines[number]
                    through = np.asarray(plan.points_mm[line.start])
                    direction = np.array([math.cos(math.radians(line.direction_deg)),
                                          math.sin(math.radians(line.direction_deg))])
                    offset = point - through
                    distance = abs(offset[0] * direction[1] - offset[1] * direction[0])
                    assert distance < 1e-9 * max(1.0, float(np.hypot(*offset)))


def test_steps_are_numbered_and_refer_to_drawn_points():
    plans = draw_plans(load_exercise("exercises/shaper_sixbar.toml"))
    for plan in (plans.velocity, plans.acceleration):
        assert [step.number for step in plan.steps] == list(range(1, len(plan.steps) + 1))
        for step in plan.steps:
            for label in (step.start, step.end):
                assert label is None or label in plan.points_mm, (plan.kind, step)


def test_normal_component_from_plan_segments_in_general_scales():
    """(bn) = (bc)²·μv²/((BC)·μl·μa) when the three plans are at different scales."""
    exercise = load_exercise("exercises/compressor_slider_crank.toml")
    settings = dataclasses.replace(exercise.plan, crank_mm=45.0, velocity_mm=25.0,
                                   acceleration_mm=70.0)
    plans = draw_plans(exercise, settings=settings)
    s = plans.scales
    v, a = plans.velocity.points_mm, plans.acceleration.points_mm
    bc = math.dist(v["b"], v["c"])
    length_bc = 0.18 / s.mu_l
    assert math.dist(a["b"], a["n_CB"]) == pytest.approx(
        bc ** 2 * s.mu_v ** 2 / (length_bc * s.mu_l * s.mu_a), rel=1e-12)


@settings(max_examples=25, deadline=None)
@given(crank_mm=st.floats(5, 200), velocity_mm=st.floats(5, 200),
       acceleration_mm=st.floats(5, 200), angle=st.floats(0, 360))
def test_scale_choices_change_no_result(crank_mm, velocity_mm, acceleration_mm, angle):
    data = fourbar(angle=angle)
    exercise = exercise_from_dict(data | {"plan": {
        "crank_mm": crank_mm, "velocity_mm": velocity_mm, "acceleration_mm": acceleration_mm}})
    base = analyse(exercise_from_dict(data))
    scaled = analyse(exercise)
    for first, second in zip(base.checks, scaled.checks, strict=True):
        assert second.plan == pytest.approx(first.plan, rel=1e-9, abs=1e-12), first.quantity


@settings(max_examples=25, deadline=None)
@given(angle=st.floats(0, 360), ratio=st.floats(2.2, 6.0), omega=st.floats(-50, 50).filter(
    lambda w: abs(w) > 0.1))
def test_velocity_image_is_similar_and_turned_90_degrees(angle, ratio, omega):
    """The image of each link on the velocity plan is the link turned 90° in the sense of ω and
    scaled by ω·μl/μv (the similarity rule)."""
    data = fourbar(angle=angle, coupler=0.22, rocker=0.18, crank=0.30 / ratio, omega=omega)
    exercise = exercise_from_dict(data)
    try:
        plans = draw_plans(exercise)
    except (AssemblyError, ToggleError):
        return
    v, position = plans.velocity.points_mm, plans.position.points_mm
    omega_bc = plans.readings["omega_BC"]
    factor = omega_bc * plans.scales.mu_l / plans.scales.mu_v
    for first, second in (("B", "C"), ("B", "P"), ("C", "P")):
        link = complex(*np.subtract(position[second], position[first]))
        image = complex(*np.subtract(v[image_label(second)], v[image_label(first)]))
        assert image == pytest.approx(1j * factor * link, abs=1e-9 * max(1, abs(image)))


def test_drafting_precision_rounds_lengths_and_costs_accuracy():
    exercise = load_exercise("exercises/compressor_slider_crank.toml")
    rough = dataclasses.replace(exercise.plan, precision_mm=0.5)
    plans = draw_plans(exercise, settings=rough)
    for plan in (plans.velocity, plans.acceleration):
        for step in plan.steps:
            if step.action in ("lay_off", "read") and step.length_mm is not None:
                assert step.length_mm / 0.5 == pytest.approx(round(step.length_mm / 0.5),
                                                             abs=1e-9), step
    exact = draw_plans(exercise).readings
    errors = {q: abs(plans.readings[q] - exact[q]) / abs(exact[q])
              for q in ("v_C", "a_C", "omega_BC", "epsilon_BC", "rho_D")}
    assert max(errors.values()) > 1e-4  # a real drawing is not exact…
    assert max(errors.values()) < 0.05  # …but a careful one is within a few per cent


@pytest.mark.parametrize(("name", "precision", "radius"), [
    ("compressor_slider_crank", 900.0, "90"),     # a dyad's ω read off the plan
    ("conveyor_sixbar", 30.0, "11.9"),            # the triad's
])
def test_a_precision_that_draws_a_radius_as_0_mm_is_refused(name, precision, radius):
    """A reading that divides by a radius drawn on the position plan refuses a drafting
    precision that rounds the radius to 0 mm, naming the key and the crank angle (it was a
    ZeroDivisionError)."""
    exercise = load_exercise(f"exercises/{name}.toml")
    coarse = dataclasses.replace(exercise.plan, precision_mm=precision)
    with pytest.raises(SpecError) as caught:
        draw_plans(exercise, settings=coarse)
    assert (caught.value.key, caught.value.angle) == ("plan.precision_mm",
                                                      exercise.mechanism.drive.angle)
    assert str(caught.value) == (
        f"plan.precision_mm: crank angle {exercise.mechanism.drive.angle:g}°: a precision of "
        f"{precision:g} mm draws a radius of {radius} mm on the position plan as 0 mm, and a "
        "reading divides by it: the precision must be finer than the drawing")


def _near_toggle_fourbar(offset_deg: float) -> dict:
    # A = (0,0), D = (0.3,0), AB = 0.1, BC = 0.15, CD = 0.1: B, C, D in line at cos φ = 0.625
    toggle = math.degrees(math.acos(0.625))
    return fourbar(ground=0.3, crank=0.1, coupler=0.15, rocker=0.1, angle=toggle - offset_deg)


def test_toggle_position_is_a_named_error():
    with pytest.raises(ToggleError) as caught:
        solve(exercise_from_dict(_near_toggle_fourbar(0.0)).mechanism)
    assert "toggle" in str(caught.value) and caught.value.angle == pytest.approx(51.3178, abs=1e-4)
    with pytest.raises(AssemblyError) as missed:
        solve(exercise_from_dict(_near_toggle_fourbar(-0.5)).mechanism)
    assert missed.value.shortfall > 0


def test_lines_meeting_at_a_small_angle_are_flagged_not_wrong():
    exercise = exercise_from_dict(_near_toggle_fourbar(0.001))
    plans = draw_plans(exercise)
    flagged = [s for s in plans.velocity.steps if s.action == "intersect" and s.flagged]
    assert flagged and flagged[0].angle_deg < 1.0
    assert any("below 1°" in render(flag_message(flag, plans.velocity.numbers))
               for flag in plans.flags)
    motion = solve(exercise.mechanism).at(0)
    assert plans.readings["omega_CD"] == pytest.approx(float(motion.omega("CD")), rel=1e-9)


def test_near_parallel_lines_are_a_toggle_within_the_drawings_precision():
    data = _near_toggle_fourbar(1e-6)
    exact = draw_plans(exercise_from_dict(data))  # exact construction still resolves them
    assert exact.flags
    rough = exercise_from_dict(data | {"plan": {"precision_mm": 0.5}})
    with pytest.raises(ToggleError) as caught:
        draw_plans(rough)
    assert "precision" in str(caught.value)
    # where, as every refusal says it: the crank angle (the velocity plan's lines already)
    assert caught.value.angle == rough.mechanism.drive.angle
    assert f"crank angle {rough.mechanism.drive.angle:g}°" in str(caught.value)


def test_rotated_velocity_plan_puts_b_along_the_crank():
    plans = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
    lever = plans.rotated_velocity_plan()
    a, b = np.asarray(plans.position.points_mm["A"]), np.asarray(plans.position.points_mm["B"])
    # crank scale: (pb) = (AB) = 30 mm, so the rotated b lands on B itself
    assert np.allclose(lever["b"], b, atol=1e-9)
    assert np.allclose(lever["p"], a, atol=1e-12)


def test_near_a_toggle_the_error_estimate_is_reported_and_digitless_stages_refused():
    """ε·R/s^(2k+1): velocities survive closer to the toggle than accelerations do."""
    near = exercise_from_dict(_near_toggle_fourbar(1e-5))  # lines at 0.04°
    velocity = solve(near.mechanism, stage="velocity")
    estimate = float(velocity.groups[0].error_estimate["velocity"][0])
    assert 1e-9 < estimate < 1
    with pytest.raises(ToggleError) as caught:
        solve(near.mechanism)
    assert "accelerations would have no correct digit" in str(caught.value)
    flagged = analyse(exercise_from_dict(_near_toggle_fourbar(0.001)))
    assert any("near its toggle" in render(flag) for flag in flagged.flags)
    report_groups = report_dict(flagged)["structure"]["groups"]
    assert 1e-6 < report_groups[0]["error_estimate"]["acceleration"] < 1
    assert report_groups[0]["line_angle_deg"] < 1


def test_an_exercise_without_ask_reads_no_fixed_pivot():
    """With no [ask] table everything is asked, but a fixed pivot's image is the pole: it is
    placed (its links' images start there) and never read as a zero-length segment."""
    exercise = load_exercise("exercises/combined_force_slider_crank.toml")
    assert exercise.ask.everything
    plans = draw_plans(exercise)
    mechanism = exercise.mechanism
    fixed = [p for p in mechanism.links["frame"].points
             if len(mechanism.links_with_point(p)) > 1]
    assert fixed
    for plan in (plans.velocity, plans.acceleration):
        read = {step.quantity for step in plan.steps if step.action == "read"}
        for point in fixed:
            assert image_label(point, plan.pole) in plan.points_mm
            assert f"v_{point}" not in read and f"a_{point}" not in read
    assert not any(f"_{point}" in name and name.startswith(("v_", "a_"))
                   for name in plans.readings for point in fixed)



def test_a_sliding_pair_no_group_drew_is_an_internal_error(monkeypatch):
    """A prismatic pair's ds, aᵏ and dds are read off the segments its dyad drew (every pair a
    plan is drawn for is a side of a dyad); a pair no group drew is an internal error naming
    the pair, never a reading made up on the side."""
    from planmethod.errors import PlanmethodError
    from planmethod.plans import construction

    exercise = load_exercise("exercises/slotted_crank_crosshead.toml")
    assert {"ds_block/crank", "ds_crosshead/frame"} <= set(
        draw_plans(exercise, acceleration=False).readings)
    drawn = construction._Emulator.velocity_group

    def forgetting(emulator, group):       # a group that drew its sides but kept no record
        drawn(emulator, group)
        emulator.sliding_sides.clear()

    monkeypatch.setattr(construction._Emulator, "velocity_group", forgetting)
    with pytest.raises(PlanmethodError) as caught:
        draw_plans(exercise, acceleration=False)
    assert str(caught.value) == (
        "link block: internal error: no group drew the relative motion of the prismatic pair "
        "block/crank, so its sliding velocity cannot be read off the plans")


def test_a_point_of_a_link_under_another_links_pin_is_placed_by_similarity_and_read():
    """C@AB, the crank's material point under the slider's pin C, is on no group's drawing:
    the plans place its image by the similarity rule on the crank and read it off — ω₁·AC and
    ω₁²·AC for the crank turning at a constant rate."""
    import tomllib

    with open("exercises/compressor_slider_crank.toml", "rb") as file:
        data = tomllib.load(file)
    for stage in ("velocity", "acceleration"):
        data["ask"][stage] = ["C", "C@AB"]
    exercise = exercise_from_dict(data)
    plans = draw_plans(exercise, settings=dataclasses.replace(exercise.plan, precision_mm=0.0))
    motion = solve(exercise.mechanism, stage="acceleration")
    a, c = (np.asarray(motion.position(name)).reshape(-1, 2)[0] for name in ("A", "C"))
    omega = exercise.mechanism.drive.omega
    distance = float(np.linalg.norm(c - a))
    assert plans.readings["v_C@AB"] == pytest.approx(abs(omega) * distance, rel=1e-12)
    assert plans.readings["a_C@AB"] == pytest.approx(omega ** 2 * distance, rel=1e-12)
    assert plans.readings["v_C"] != pytest.approx(plans.readings["v_C@AB"], rel=1e-3)


@pytest.mark.parametrize("sense", [1.0, -1.0])
def test_the_radius_of_curvature_is_read_right_with_the_crank_turning_either_way(sense):
    """ρ = (pd)²μv²/((πn)μa) off an exact drawing is the exact ρ at every angle, the crank
    turning counter-clockwise or clockwise (the path is then run the other way round: the
    normal component lies on the other side of the velocity)."""
    import tomllib

    from planmethod.report import exact_value

    with open("exercises/fourbar_coupler_point.toml", "rb") as file:
        data = tomllib.load(file)
    data["drive"]["omega"] = sense * abs(data["drive"]["omega"])
    for angle in range(0, 360, 30):
        data["drive"]["angle"] = angle
        exercise = exercise_from_dict(data)
        plans = draw_plans(exercise,
                           settings=dataclasses.replace(exercise.plan, precision_mm=0.0))
        motion = solve(exercise.mechanism, stage="acceleration").at(0)
        for point in ("E", "C"):
            assert plans.readings[f"rho_{point}"] == pytest.approx(
                exact_value(motion, f"rho_{point}"), rel=1e-9), (angle, point)


def test_the_intersection_step_states_the_groups_vector_equation():
    """The velocity plan's intersection step says which point it finds and by which vector
    equation, as the course writes them (b₃ of the slotted lever); the position plan draws a
    slide's guide through the guide's own point, in mm of the drawing (O₂ at 120 mm below O₁)."""
    plans = draw_plans(load_exercise("exercises/slotted_lever.toml"))
    said = [step_text(step, plans.velocity) for step in plans.velocity.steps
            if step.action == "intersect"]
    assert said == ["b₃: v_B₃ = v_B + v_B₃B = v_O₂ + v_B₃O₂"]
    (slide,) = plans.position.slides
    assert slide["through"] == "O2"
    assert slide["through_mm"] == pytest.approx(list(plans.position.points_mm["O2"]), abs=1e-9)


def test_a_mirrored_image_uses_any_pin_farther_than_a_rounding_unit_from_the_reference():
    """The mirror line runs through the image's reference and another pin of the link; a pin
    within 1e-12 (of the larger of 1 m and |ref|) of the reference is the reference itself and
    is passed over. A pin 1.5e-12 m away still gives the line (here the x axis)."""
    from types import SimpleNamespace

    from planmethod.plans.construction import LinkImage, _Emulator

    pins = {"R": np.zeros(2), "Q": np.array([1.5e-12, 0.0])}
    fake = SimpleNamespace(
        mirror=lambda segment: True,
        mechanism=SimpleNamespace(links={"bar": SimpleNamespace(points={"R": 0, "Q": 0})},
                                  links_with_point=lambda name: ("bar", "other")),
        where=lambda link, name: pins[name])
    image = LinkImage(np.zeros(2), np.zeros(2), "r", 0.0)
    sheet = SimpleNamespace(kind="velocity")
    mirrored = _Emulator.similar(fake, sheet, "bar", image, np.array([0.3, 0.4]), "e")
    assert np.allclose(mirrored, [0.3, -0.4], rtol=0, atol=1e-15)
