"""Templates: the safe expression language, ranges and choices, reproducible variants,
rejection of unfit draws, key-precise errors."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from planmethod.errors import SpecError
from planmethod.grading.expressions import ExpressionError, evaluate, parse
from planmethod.grading.templates import (
    TemplateSettings,
    check_variant,
    draw_variant,
    load_template,
    parse_template,
    to_toml,
)
from planmethod.numbering import course_numbers
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.vocabulary import symbol
from planmethod.words import render

SLIDER = "exercises/templates/slider_crank.toml"
FOUR_BAR = "exercises/templates/four_bar.toml"


def value(text: str, **names: float) -> float:
    return evaluate(parse(text), names.__getitem__)


@pytest.mark.parametrize(("text", "expected"), [
    ("1 + 2 * 3", 7.0),
    ("(1 + 2) * 3", 9.0),
    ("2 ^ 3 ^ 2", 512.0),          # right-associative
    ("-2 ^ 2", -4.0),              # unary minus binds looser than ^
    ("10 / 4 - 1", 1.5),
    ("min(3, 1, 2) + max(1, 5)", 6.0),
    ("round(2.71828, 2)", 2.72),
    ("sqrt(16) + abs(-1)", 5.0),
    ("atan2(1, 1)", 45.0),
    ("hypot(3, 4)", 5.0),
    ("1.5e-3 * 1000", 1.5),
    ("pi", math.pi),
])
def test_expressions_compute(text, expected):
    assert value(text) == pytest.approx(expected, rel=1e-12)


def test_references_are_resolved_not_executed():
    assert value("a.b[1] * 2", **{"a.b[1]": 3.0}) == 6.0
    # a name that looks like Python is only ever a reference
    with pytest.raises(KeyError):
        value("__import__")


@pytest.mark.parametrize(("text", "fragment"), [
    ("", "empty"),
    ("1 +", "expected a number"),
    ("(1 + 2", "expected ')'"),
    ("1 + 2)", "unexpected ')'"),
    ("foo(1)", "unknown function 'foo'"),
    ("round(1, 2, 3)", "takes 1…2 argument"),
    ("1 ; 2", "unexpected ';'"),
    ("'a'", "unexpected"),
    ("lambda: 1", "unexpected ':'"),
    ("(" * 100 + "1" + ")" * 100, "nested deeper"),
    ("1" * 600, "longer than"),
])
def test_bad_expressions_are_rejected(text, fragment):
    with pytest.raises(ExpressionError, match=None) as caught:
        parse(text)
    assert fragment in str(caught.value)


def test_round_takes_whole_digits_from_minus_12_to_12_and_0_by_default():
    assert value("round(2.567)") == 3.0
    assert value("round(0.1234567890125, 12)") == 0.123456789012
    assert value("round(123456789012345, -12)") == 123e12
    for digits in ("13", "-13", "0.5"):
        with pytest.raises(ExpressionError) as caught:
            value(f"round(1, {digits})")
        assert str(caught.value) == ("round(x, digits) needs a whole number of digits in "
                                     f"-12…12, got {float(digits):g}")


@pytest.mark.parametrize(("text", "fragment"), [
    ("1 / 0", "division by zero"),
    ("sqrt(-1)", "sqrt(-1) is undefined"),
    ("asin(2)", "undefined"),
    ("(-8) ^ 0.5", "not a finite number"),
    ("10 ^ 400", "out of range"),
    ("round(1, 0.5)", "whole number"),
])
def test_evaluation_errors(text, fragment):
    with pytest.raises(ExpressionError) as caught:
        value(text)
    assert fragment in str(caught.value)


@pytest.mark.parametrize(("text", "expected"), [
    ("sin(30)", 0.5), ("cos(60)", 0.5), ("tan(45)", 1.0),        # angles in degrees
    ("asin(1)", 90.0), ("asin(-1)", -90.0), ("acos(-1)", 180.0), ("acos(1)", 0.0),
    ("sqrt(0)", 0.0), ("2 ^ 64", 2.0 ** 64), ("2 ^ -64", 2.0 ** -64),
])
def test_functions_at_the_ends_of_their_domains(text, expected):
    assert value(text) == pytest.approx(expected, rel=1e-12, abs=1e-15)


@pytest.mark.parametrize(("text", "message"), [
    ("sqrt(-0.0001)", "sqrt(-0.0001) is undefined"),
    ("asin(1.0001)", "asin(1.0001) is undefined"), ("asin(-1.0001)", "asin(-1.0001) is undefined"),
    ("acos(1.0001)", "acos(1.0001) is undefined"), ("acos(-1.0001)", "acos(-1.0001) is undefined"),
    ("2 ^ 64.5", "exponent 64.5 is out of range (|x| ≤ 64)"),
    ("2 ^ -65", "exponent -65 is out of range (|x| ≤ 64)"),
    # a missing bracket: the character where it was due, counted from 1
    ("(1 + 2", "at character 7: expected ')', got the end"),
    ("round(1 2)", "at character 9: expected ')', got '2'"),
    # a wrong count of arguments: the character where the function's name starts
    ("1 + sqrt(1, 2)", "at character 5: sqrt() takes 1 argument(s), got 2"),
])
def test_functions_just_outside_their_domains_and_missing_brackets_say_so(text, message):
    with pytest.raises(ExpressionError) as caught:
        value(text)
    assert str(caught.value) == message


BASE = """
[vars]
l = {{ range = [0.05, 0.08], step = 0.005 }}
{extra}
[drive]
link = "AB"
pivot = "A"
angle = {angle}
omega = 100
[links]
frame = {{ A = [0, 0] }}
AB = {{ A = [0, 0], B = ["= l", 0] }}
BC = {{ B = [0, 0], C = [{rod}, 0] }}
slider = {{ C = [0, 0] }}
[[slide]]
link = "slider"
along = "frame"
through = "A"
[sketch]
C = [0.3, 0]
[ask]
velocity = ["C"]
acceleration = ["C"]
omega = ["BC"]
"""


def template_text(extra: str = "", angle: str = "45", rod: str = '"= 4 * l"') -> str:
    return BASE.format(extra=extra, angle=angle, rod=rod)


@pytest.mark.parametrize(("extra", "angle", "key", "fragment"), [
    ("", '"= 2 *"', "drive.angle", "bad expression"),
    ("", '"= nope + 1"', "drive.angle", "refers to 'nope'"),
    ("", "{ range = [50, 10] }", "drive.angle.range", "low above high"),
    ("", '{ range = [10, 50], step = -1 }', "drive.angle.step", "positive"),
    ("", '{ range = [10, 50], step = 0 }', "drive.angle.step", "positive number, got 0"),
    ("", '{ range = [10, 50], step = 1e-6 }', "drive.angle.step", "more than 10 million"),
    ("", "{ choice = [] }", "drive.angle.choice", "non-empty"),
    ("", '{ range = [10, "x"] }', "drive.angle.range", "finite numbers"),
    ("a = \"= b\"\nb = \"= a\"", '"= a"', "vars.", "cycle"),
    ('"2x" = 1', "45", "vars.2x", "a variable name must be an identifier"),
])
def test_bad_templates_name_the_key(extra, angle, key, fragment):
    text = template_text(extra, angle)
    with pytest.raises(SpecError) as caught:
        template = parse_template(text, file="t.toml")
        draw_variant(template, seed=1, student="x")
    message = str(caught.value)
    assert message.startswith("t.toml: ")
    assert key in message and fragment in message


def test_a_template_without_ask_is_refused_by_name():
    """Without [ask] an exercise asks for everything, which is no student's task: a template
    must say what is asked (a draw could otherwise never pass: v_A = 0 of the fixed pivot)."""
    text = template_text().split("[ask]")[0]
    with pytest.raises(SpecError) as caught:
        parse_template(text, file="t.toml")
    assert str(caught.value).startswith("t.toml: ask: a template with random values must say")
    parse_template(template_text(), file="t.toml")   # with it: read
    fixed = text.replace('l = { range = [0.05, 0.08], step = 0.005 }', "l = 0.06")
    parse_template(fixed, file="t.toml")    # an exercise as written asks what it asks


@pytest.mark.parametrize(("line", "message"), [
    ("min_line_angle_deg = 90", "min_line_angle_deg: must be an angle in [0, 90) degrees, got 90"),
    ("dead_centre_deg = -1", "dead_centre_deg: must be an angle in [0, 90) degrees, got -1"),
    ("max_attempts = 0", "max_attempts: must be a whole number in 1…10000, got 0"),
    ("min_segment_mm = 300", "min_segment_mm: must be a length in [0, 200] mm, got 300"),
    ("max_tolerance = 0", "max_tolerance: must be a share in (0, 1] (0.1 = 10 %), got 0"),
])
def test_bad_template_settings_are_one_exact_line(line, message):
    with pytest.raises(SpecError) as caught:
        parse_template(template_text() + f"\n[template]\n{line}\n", file="t.toml")
    assert str(caught.value) == f"t.toml: template.{message}"


def test_bad_template_settings():
    with pytest.raises(SpecError, match=r"template\.colour"):
        parse_template(template_text() + "\n[template]\ncolour = 1\n", file="t.toml")
    with pytest.raises(SpecError, match=r"template\.require: must be a list of components"):
        parse_template(template_text() + '\n[template]\nrequire = ["spin"]\n', file="t.toml")


def test_variants_are_reproducible_and_differ_between_students():
    template = load_template(SLIDER)
    first = [draw_variant(template, seed=11, student=f"s{i}") for i in range(12)]
    again = [draw_variant(template, seed=11, student=f"s{i}") for i in range(12)]
    assert [v.data for v in first] == [v.data for v in again]
    assert len({(v.values["l_AB"], v.values["phi"], v.values["omega"]) for v in first}) > 8
    other_seed = [draw_variant(template, seed=12, student=f"s{i}") for i in range(12)]
    assert [v.data for v in other_seed] != [v.data for v in first]
    for variant in first:
        values = variant.values
        assert 0.05 <= values["l_AB"] <= 0.08
        assert round(values["l_AB"] / 0.005) * 0.005 == pytest.approx(values["l_AB"])
        assert values["l_BC"] == pytest.approx(round(values["l_AB"] * values["ratio"], 3))
        links = variant.data["links"]
        assert links["BC"]["D"][0] == pytest.approx(values["l_BC"] / 2)
        assert variant.exercise.mechanism.drive.angle == values["phi"]
        assert "{" not in variant.description


def test_rejected_draws_are_redrawn_deterministically():
    # the crank angle is 0 (a dead centre) or 60 (fine): 0 must never be set
    text = template_text(angle="{ choice = [0, 60] }")
    template = parse_template(text, file="t.toml")
    variants = [draw_variant(template, seed=3, student=str(i)) for i in range(30)]
    assert {v.exercise.mechanism.drive.angle for v in variants} == {60}
    redrawn = [v for v in variants if v.attempt > 0]
    assert redrawn, "with a 50 % chance of 0°, some students must need a second attempt"
    assert all("dead centre" in render(reason) for v in redrawn for reason in v.rejected)
    assert [v.attempt for v in variants] == [
        draw_variant(template, seed=3, student=str(i)).attempt for i in range(30)]


def test_a_refusal_sums_up_the_three_most_frequent_kinds_of_rejection(monkeypatch):
    """Every attempt rejected, four ways (numbers aside: 'lines meet at 3°' and 'at 5°' are
    one kind): the refusal names the three most frequent kinds, most frequent first, each
    number as the range it took (not a '#' in its place)."""
    from planmethod.grading import templates

    cycle = ["a", "a", "a", "a", "b", "b", "b", "c", "c", "d"]
    kinds = iter(f"kind {cycle[n % len(cycle)]} at {n}°" for n in range(1000))
    monkeypatch.setattr(templates, "check_variant", lambda *args, **kwargs: next(kinds))
    template = parse_template(template_text(), file="t.toml")
    with pytest.raises(SpecError) as caught:
        draw_variant(template, seed=1, student="x")
    summary = str(caught.value).rpartition("): ")[2]
    assert summary == "80× kind a at 0–193°; 60× kind b at 4–196°; 40× kind c at 7–198°"


def test_a_template_that_never_assembles_fails_with_the_reasons():
    text = template_text(rod='"= 0.5 * l"', angle="90")  # the rod is shorter than the crank
    template = parse_template(text, file="t.toml")
    with pytest.raises(SpecError) as caught:
        draw_variant(template, seed=1, student="x")
    assert "no acceptable variant in 200 attempts" in str(caught.value)
    assert "cannot be assembled" in str(caught.value)


def test_small_line_angles_are_rejected():
    exercise = draw_variant(load_template(SLIDER), seed=1, student="a").exercise
    assert check_variant(exercise, TemplateSettings(min_line_angle_deg=89.9)) is not None
    assert check_variant(exercise, TemplateSettings(min_line_angle_deg=0,
                                                    dead_centre_deg=0)) is None


def test_a_random_draw_is_held_to_the_measuring_rules_and_a_written_exercise_is_not():
    """A drawn variant (drawable, the default) must have segments long enough to measure; an
    exercise set as written is not held to that rule."""
    exercise = draw_variant(load_template(SLIDER), seed=1, student="a").exercise
    strict = TemplateSettings(min_line_angle_deg=0, dead_centre_deg=0, min_segment_mm=1000)
    problem = check_variant(exercise, strict)
    assert problem is not None and "below 1000 mm" in render(problem)
    assert check_variant(exercise, strict, drawable=False) is None


def test_a_plain_exercise_is_a_template_without_randomness():
    template = load_template("exercises/compressor_slider_crank.toml")
    assert not template.is_random
    variant = draw_variant(template, seed=5, student="anyone")
    assert variant.attempt == 0 and variant.data["drive"]["angle"] == 45


def test_written_toml_reads_back_to_the_same_exercise():
    for path in (SLIDER, FOUR_BAR):
        variant = draw_variant(load_template(path), seed=2, student="w")
        data = tomllib.loads(to_toml(variant.data))
        assert data == variant.data
        assert exercise_from_dict(data) == exercise_from_dict(variant.data)


def test_task_sheets_write_quantities_as_the_course_does():
    """The answer table leads with the course's symbol and unit (ω₂, rad/s; a_C, m/s²), links
    numbered frame 0, crank 1, …; the answer id follows in brackets for typing answers; the
    given data are in the course's symbols with units, never a template's variables."""
    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import task_text
    from planmethod.grading.templates import draw_variant, load_template

    variant = draw_variant(load_template("exercises/templates/four_bar.toml"))
    key = build_key(variant)
    text = task_text(key)
    assert "Links: 0 frame, 1 AB, 2 BC, 3 CD." in text
    rows = {line.split()[0].rstrip(","): line for line in text.splitlines()
            if line.startswith("  ")}
    assert rows["ω₂"].split()[1] == "rad/s" and rows["ω₂"].endswith("[omega_BC]")
    assert rows["ε₃"].split()[1] == "rad/s²" and rows["a_C"].split()[1] == "m/s²"
    assert not any(row.lstrip().startswith(("omega_", "epsilon_")) for row in rows.values())
    given = next(line for line in text.splitlines() if line.startswith("Given: "))
    assert f"l_AB = {variant.values['l_AB']:.4g} m" in given
    assert f"φ₁ = {variant.values['phi']:g}°" in given and "ω₁ = " in given
    assert not any(f"{name} = " in given for name in variant.values if "_" not in name)


def test_variants_a_student_cannot_measure_or_without_a_required_component_are_rejected():
    from planmethod.grading.templates import plan_problem
    from planmethod.plans import draw_plans

    compressor = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
    assert plan_problem(compressor, TemplateSettings(min_segment_mm=0.0)) is None
    reason = render(plan_problem(compressor, TemplateSettings(min_segment_mm=500.0)))
    assert "segment read for" in reason and "below 500 mm" in reason
    # the slider-crank has no Coriolis component; the slotted lever has one, long enough
    reason = render(plan_problem(compressor, TemplateSettings(min_segment_mm=1.0,
                                                              require=("coriolis",))))
    assert "coriolis component required" in reason
    lever = draw_plans(load_exercise("exercises/slotted_lever.toml"))
    assert plan_problem(lever, TemplateSettings(min_segment_mm=1.0, require=("coriolis",))) \
        is None


def test_a_segment_below_its_limit_never_reads_as_the_limit():
    """A segment just short of its limit is shown cut to a tenth, below the limit (18.3 mm
    below 18.4 mm), not rounded up to it ('18.4 mm (below 18.4 mm)')."""
    import re

    from planmethod.grading.templates import plan_problem
    from planmethod.plans import draw_plans

    compressor = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
    shortest = min(abs(step.length_mm) for plan in (compressor.velocity, compressor.acceleration)
                   for step in plan.steps if step.action == "read" and step.length_mm)
    assert (shortest * 10) % 1 >= 0.5          # rounded to a tenth, it would reach the limit
    limit = math.ceil(shortest * 10) / 10
    reason = render(plan_problem(compressor, TemplateSettings(min_segment_mm=limit)))
    shown = float(re.search(r"is (\d+\.\d) mm \(below", reason).group(1))
    assert shown == math.floor(shortest * 10) / 10 < limit


def test_a_draw_whose_plan_would_not_fit_its_printed_sheet_is_rejected():
    """Drawn at 300 mm for the crank pin's acceleration, the compressor's acceleration plan
    spans more than a plan sheet's drawing area holds: a random draw is rejected (the booklet
    could not print it), an exercise set as written is not held to it."""
    from dataclasses import replace

    from planmethod.grading.sheet_area import PLAN_ROOM_MM, plan_size_mm
    from planmethod.grading.templates import plan_problem
    from planmethod.plans import draw_plans

    exercise = load_exercise("exercises/compressor_slider_crank.toml")
    settings = TemplateSettings(min_segment_mm=0.0, min_line_angle_deg=0.0, dead_centre_deg=0.0)
    assert plan_problem(draw_plans(exercise), settings) is None
    large = draw_plans(replace(exercise, plan=replace(exercise.plan, acceleration_mm=300.0)))
    width, height = plan_size_mm(large.acceleration.points_mm)
    assert width > PLAN_ROOM_MM[0] or height > PLAN_ROOM_MM[1]
    reason = render(plan_problem(large, settings))
    assert reason.startswith("the acceleration plan spans ")
    assert f"{math.ceil(width)} × {math.ceil(height)} mm" in reason
    assert reason.endswith("more than its printed sheet holds (162 × 194 mm)")
    assert plan_problem(large, settings, drawable=False) is None


def test_variants_whose_drawing_tolerance_is_too_large_are_rejected():
    from dataclasses import replace

    from planmethod.grading.keys import build_key
    from planmethod.grading.templates import tolerance_problem

    exercise = load_exercise("exercises/compressor_slider_crank.toml")
    data = tomllib.loads(Path("exercises/compressor_slider_crank.toml").read_text("utf-8"))
    assert tolerance_problem(exercise, data, TemplateSettings())[0] is None
    problem, found = tolerance_problem(exercise, data, TemplateSettings(max_tolerance=0.001))
    assert problem is not None
    reason = render(problem)
    assert "drafting tolerance of" in reason and "above 0.1 %" in reason
    shown = reason.split("tolerance of ")[1].split(" is")[0]     # as the course writes it
    mechanism = exercise.mechanism
    numbers = course_numbers(mechanism)
    quantity = next(q for q in found.values if symbol(q, numbers) == shown)
    assert found.tolerances[quantity] > 0.001 * abs(found.values[quantity])
    # every variant drawn keeps each drawing-derived tolerance within 10 % of its value, and
    # its key (which reuses the tolerances found while checking) is the key built afresh
    template = load_template(SLIDER)
    for student in ("s1", "s2", "s3", "s4", "s5", "s6"):
        variant = draw_variant(template, seed=3, student=student)
        key = build_key(variant)
        assert key == build_key(replace(variant, propagation=None))
        for question in key["questions"]:
            if question["tolerance_from"] == "drawing":
                assert question["tolerance"] <= 0.10 * abs(question["value"]), question["id"]


@pytest.mark.parametrize(("table", "fragment"), [
    ("min_segment_mm = -1", "template.min_segment_mm"),
    ('require = ["gravity"]', "template.require"),
    ("max_tolerance = 0", "template.max_tolerance"),
    ("max_tolerance = 2", "template.max_tolerance"),
])
def test_bad_drawability_settings_are_named(table, fragment):
    text = template_text(angle="60").replace("[drive]", f"[template]\n{table}\n\n[drive]", 1)
    with pytest.raises(SpecError, match=fragment.replace(".", r"\.")):
        parse_template(text, file="t.toml")


def test_rejected_draws_are_summed_up_in_course_notation(tmp_path, capsys):
    """``planmethod variants`` says why draws were rejected as a student reads a task — ω₂,
    aʳ_CC₀, ρ_D, never a report name — with the range each number took."""
    from planmethod.cli import main

    assert main(["variants", str(SLIDER), "--count", "30", "--out", str(tmp_path / "out"),
                 "--no-sheets"]) == 0
    out = capsys.readouterr().out
    summary = out.split("draws rejected:")[1].strip().splitlines()
    assert summary, out
    for line in summary:
        assert "#" not in line and "_rel" not in line and "omega" not in line, line
        assert "epsilon" not in line and "rho_" not in line, line
    assert any("ω₂" in line for line in summary), summary


def test_a_task_text_whole():
    """The task of the offset slider-crank's variant as a student reads it: the exercise's
    words, the given data (lengths from the crank's pivot, the guide that does not pass
    through it, φ₁, ω₁, ε₁), the scales and the lengths they give, the links' numbers, and one
    row a question — its symbol and unit, its words, its column in an answers file."""
    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import task_text

    key = build_key(draw_variant(load_template("exercises/offset_slider_crank.toml")))
    assert task_text(key) == (
        'Offset slider-crank — variant for 1\n'
        '\n'
        'The crank AB = 0.05 m turns about A at ω1 = 150 rad/s counter-clockwise with ε1 = 200 '
        'rad/s².\n'
        'The connecting rod BC = 0.20 m drives the slider C along a horizontal guide that passe'
        's\n'
        'e = 0.02 m below A (through the frame point G). Its midpoint is E. At φ1 = 120° constr'
        'uct the\n'
        "plans and find the slider's velocity and acceleration, ω and ε of the rod, the velocit"
        'y and\n'
        "acceleration of E, and the radius of curvature of E's path. Note the tangential compon"
        'ent of\n'
        "the crank pin's acceleration, aᵗ_B = ε1·l_AB.\n"
        '\n'
        'Given: l_AB = 0.05 m, l_BC = 0.2 m, l_BE = 0.1 m, x_AG = 0 m, y_AG = -0.02 m, the guid'
        'e of C through G at 0°, φ₁ = 120°, ω₁ = 150 rad/s, ε₁ = 200 rad/s².\n'
        'Crank angle φ₁ = 120°; scales μl = 0.002 m/mm, μv = 0.2 (m/s)/mm, μa = 25 (m/s²)/mm.\n'
        'At these scales: (AB) = 25 mm, (pb) = 37.5 mm, (πb) = 45 mm.\n'
        'Links: 0 frame, 1 AB, 2 BC, 3 slider.\n'
        '\n'
        'Answer (SI units, counter-clockwise positive; in an answers file, the column named in '
        'brackets):\n'
        '  v_C, m/s         speed of C, |v_C|   [v_C]\n'
        '  v_E, m/s         speed of E, |v_E|   [v_E]\n'
        '  a_C, m/s²        magnitude of the acceleration of C, |a_C|   [a_C]\n'
        '  a_E, m/s²        magnitude of the acceleration of E, |a_E|   [a_E]\n'
        '  ω₂, rad/s        angular velocity ω₂ of link 2 (BC)   [omega_BC]\n'
        '  ε₂, rad/s²       angular acceleration ε₂ of link 2 (BC)   [epsilon_BC]\n'
        '  ρ_E, m           radius of curvature ρ of the path of E   [rho_E]\n'
        '  s₃₀, m           travel s₃₀ of link 3 (slider) along link 0 (frame)   [s_slider/fram'
        'e]\n'
        '  ds/dt₃₀, m/s     sliding velocity ds/dt₃₀ of link 3 (slider) along link 0 (frame) (a'
        'long the guide)   [ds_slider/frame]\n'
        '  d²s/dt²₃₀, m/s²  sliding (relative) acceleration d²s/dt²₃₀ of link 3 (slider) along '
        'link 0 (frame) (along the guide)   [dds_slider/frame]\n'
        '  aᵏ₃₀, m/s²       magnitude of the Coriolis acceleration aᵏ₃₀ of link 3 (slider) alon'
        'g link 0 (frame)   [coriolis_slider/frame]\n')


def test_a_task_text_of_a_key_without_its_exercise():
    from planmethod.grading.sheets import task_text

    key = {"title": "T", "student": "s1", "task": "  Do it.  ", "angle": 30,
           "questions": [{"id": "omega_BC", "unit": "rad/s",
                          "text": "angular velocity ω of BC (counter-clockwise positive)"},
                         {"id": "n", "text": "plain", "symbol": "n₁"}]}
    assert task_text(key) == (
        "T — variant for s1\n\nDo it.\n\n"
        "Crank angle φ₁ = 30°; scales μl = 0 m/mm, μv = 0 (m/s)/mm, μa = 0 (m/s²)/mm.\n\n"
        "Answer (SI units, counter-clockwise positive; in an answers file, the column named in "
        "brackets):\n"
        "  ω_BC, rad/s      angular velocity ω of BC   [omega_BC]\n"
        "  n₁               plain   [n]\n")
    assert task_text({}).startswith("Exercise — variant for None\n\n\n\nCrank angle φ₁ = 0°")


def test_the_task_sheet_shows_the_figure_without_rho_and_the_text_wrapped_but_its_rows():
    """The task figure is the position plan without its curvature construction (it would
    give ρ away); the task text under it is wrapped at 100 characters, its answer rows kept
    whole however long; its symbols are set with real subscripts (l_AB: l with AB below, a
    smaller tspan), the answer columns' names in brackets as they are."""
    import xml.etree.ElementTree as ElementTree

    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import task_figure_svg, task_sheet_svg, task_text
    from planmethod.plans import draw_plans
    from planmethod.render.canvas import formula_runs
    from planmethod.render.svg import position_drawing

    def as_shown(line: str) -> str:     # a formula's runs, its underscores gone
        return "".join(part for part, _ in formula_runs(line))

    variant = draw_variant(load_template("exercises/offset_slider_crank.toml"))
    plans = draw_plans(variant.exercise)
    assert "ρ" in position_drawing(plans.position, notes=[]).svg     # ρ_E is asked
    assert "ρ" not in task_figure_svg(plans)
    key = build_key(variant)
    root = ElementTree.fromstring(task_sheet_svg(key, plans).encode("utf-8"))
    shown = ["".join(text.itertext()) for text in root.iter("{http://www.w3.org/2000/svg}text")]
    lines = task_text(key).splitlines()
    given = next(line for line in lines if line.startswith("Given: "))
    row = next(line for line in lines if "[dds_slider/frame]" in line)
    assert len(given) > 100 and len(row) > 100 and "l_AB" in given
    given, row = as_shown(given), as_shown(row)
    assert row in shown and given not in shown and "[dds_slider/frame]" in row
    start = next(index for index, text in enumerate(shown) if text.startswith("Given: "))
    parts = []
    while len("".join(parts)) < len(given):
        parts.append(shown[start + len(parts)])
    assert "".join(parts) == given and all(len(part) <= 100 for part in parts)
    assert len(parts) == 2


    svg = task_sheet_svg(key, plans)
    assert "l<tspan" in svg and ">AB</tspan>" in svg and "[a_C]" in svg
    outside = [text for text in shown if "_" in text.split("[")[0]]
    assert outside == []


def test_resolved_tables_written_as_toml_whole():
    """Every kind of value as a person would write it — a whole-number float with its .0, a
    paragraph as a literal block (unless it holds ''' or a control character, or ends in a
    quote), a key that needs quotes quoted, tables and arrays of tables after the plain keys,
    nested tables inline — and read back equal; a value TOML cannot hold is refused by name."""
    from planmethod.grading.templates import to_toml

    data = {"title": "Lever ω", "flag": True, "off": False, "n": 3, "whole": 2.0, "x": 0.5,
            "big": 1e300, "text": "line one\nline two", "quoted": "it's\n'''", "endq": "ab\n'",
            "ctrl": "x\n\x01", "tabs": "a\n\tb", "odd key": 1, "ключ": 2,
            "list": [1, 2.5, "s"], "empty": [], "drive": {"link": "AB", "omega": 10.0},
            "load": [{"link": "BC", "force": [1, 2]}, {"link": "CD", "moment": -1.5}],
            "nested": {"inner": {"k": "v", "w": [True]}}}
    text = to_toml(data)
    assert text == (
        'title = "Lever ω"\nflag = true\noff = false\nn = 3\nwhole = 2.0\nx = 0.5\n'
        "big = 1e+300\ntext = '''\nline one\nline two'''\nquoted = \"it's\\n'''\"\n"
        'endq = "ab\\n\'"\nctrl = "x\\n\\u0001"\ntabs = \'\'\'\na\n\tb\'\'\'\n'
        '"odd key" = 1\n"ключ" = 2\nlist = [1, 2.5, "s"]\nempty = []\n\n'
        '[drive]\nlink = "AB"\nomega = 10.0\n\n[[load]]\nlink = "BC"\nforce = [1, 2]\n\n'
        '[[load]]\nlink = "CD"\nmoment = -1.5\n\n[nested]\ninner = { k = "v", w = [true] }\n')
    assert tomllib.loads(text) == data
    for value, error, message in ((math.nan, ValueError, "cannot write nan to TOML"),
                                  (-math.inf, ValueError, "cannot write -inf to TOML"),
                                  (object(), TypeError, "cannot write object to TOML")):
        with pytest.raises(error) as caught:
            to_toml({"a": value})
        assert str(caught.value) == message
