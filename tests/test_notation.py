"""One course notation, chosen per exercise: the compressor under each ``[notation]`` choice
names its connecting rod BC, its reactions and its task sheet as that course does; every task
sheet states the drawing lengths its own scales give; bad ``[notation]`` tables are refused
with the key at fault."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import pytest

from planmethod.errors import SpecError
from planmethod.grading.keys import build_key
from planmethod.grading.sheets import task_text
from planmethod.grading.templates import Variant, draw_variant, load_template
from planmethod.numbering import course_numbers
from planmethod.render.figures import plan_files
from planmethod.render.notation import ForceNotation
from planmethod.render.plan_words import step_text
from planmethod.report import analyse
from planmethod.spec import exercise_from_dict

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"

#: each convention: its [notation] table, and the numbers of frame, AB (the crank), BC, slider
CONVENTIONS = {
    "papers (default)": ({}, (0, 1, 2, 3)),
    "frame last (post 4)": ({"frame": "last"}, (4, 1, 2, 3)),
    "frame 1, crank 2": ({"frame": 1}, (1, 2, 3, 4)),
    "explicit": ({"numbers": {"frame": 9, "AB": 5, "BC": 6, "slider": 7}}, (9, 5, 6, 7)),
}

SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _compressor(notation: dict) -> dict:
    data = tomllib.loads(COMPRESSOR.read_text(encoding="utf-8"))
    data["mass"] = {"BC": {"m": 2.0, "J": 0.01, "S": [0.09, 0.0]}}  # so that it has reactions
    data.pop("ask", None)
    if notation:
        data["notation"] = notation
    return data


@pytest.mark.parametrize("name", CONVENTIONS)
def test_the_compressor_speaks_each_notation(name):
    notation, (frame, crank, rod, slider) = CONVENTIONS[name]
    exercise = exercise_from_dict(_compressor(notation), file="compressor.toml")
    assert course_numbers(exercise.mechanism) == dict(sorted(
        {"frame": frame, "AB": crank, "BC": rod, "slider": slider}.items(),
        key=lambda item: item[1]))
    omega, epsilon = f"ω{str(rod).translate(SUB)}", f"ε{str(rod).translate(SUB)}"
    phi = f"φ{str(crank).translate(SUB)}"
    analysis = analyse(exercise)
    # the step sentences read ω and ε of BC off the plans by BC's number
    sentences = " ".join(step_text(step, plan) for plan in (analysis.plans.velocity,
                                                            analysis.plans.acceleration)
                         for step in plan.steps)
    assert f"→ {omega} = " in sentences and f"→ {epsilon} = " in sentences
    # the reactions: R_ij is the force of link i on link j
    notation_ = ForceNotation(analysis.forces.solution)
    pair = lambda i, j: (f"{i}{j}" if max(i, j) < 10 else f"{i},{j}").translate(  # noqa: E731
        str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉‚"))
    assert notation_.plain("R_B", "BC") == "R" + pair(crank, rod)
    assert notation_.plain("R_A", "AB") == "R" + pair(frame, crank)
    assert notation_.plain("R_slider/frame", "slider") == "R" + pair(frame, slider)
    assert notation_.plain("G_BC") == "G" + str(rod).translate(SUB)
    # the figures: titles by the crank's φ, polygons and lever by the reactions' numbers
    files = plan_files(analysis.plans, analysis.forces)
    assert f"position plan, {phi} = 45°" in files["position.svg"]
    assert f"ω{str(crank).translate(SUB)} = 100 rad/s" in files["position.svg"]
    polygons = " ".join(svg for file, svg in files.items() if file.startswith("forces_"))
    assert f"Fᵘ{str(rod).translate(SUB)}" in polygons or f"G{str(rod).translate(SUB)}" in \
        polygons
    # the task sheet: links listed by number, BC's questions by its number
    key = build_key(Variant("s1", 0, 0, _compressor(notation), {}, exercise))
    text = task_text(key)
    listed = ", ".join(f"{number} {link}" for link, number in sorted(
        {"frame": frame, "AB": crank, "BC": rod, "slider": slider}.items(),
        key=lambda item: item[1]))
    assert f"Links: {listed}." in text
    rows = {line.split()[0].rstrip(","): line for line in text.splitlines()
            if line.startswith("  ")}
    assert rows[omega].endswith("[omega_BC]") and rows[epsilon].endswith("[epsilon_BC]")
    assert f"{phi} = 45°" in text
    # machine names stay: the answer columns, the key's ids, the report's keys
    assert {q["id"] for q in key["questions"]} >= {"omega_BC", "epsilon_BC"}


def test_the_notation_changes_no_number_of_the_report():
    plain = analyse(exercise_from_dict(_compressor({})))
    last = analyse(exercise_from_dict(_compressor({"frame": "last"})))
    assert [c.analytic for c in plain.checks] == [c.analytic for c in last.checks]
    assert [c.quantity for c in plain.checks] == [c.quantity for c in last.checks]


@pytest.mark.parametrize(("table", "key", "words"), [
    ({"frame": 2}, "notation.frame", 'must be 0, 1 or "last"'),
    ({"frame": "first"}, "notation.frame", 'must be 0, 1 or "last"'),
    ({"numbers": {"CD": 1}}, "notation.numbers.CD", "unknown link 'CD'"),
    ({"numbers": {"AB": 1, "BC": 1}}, "notation.numbers.BC", "already the number of 'AB'"),
    ({"numbers": {"AB": -1}}, "notation.numbers.AB", "whole number from 0 to 99"),
    ({"numbers": {"AB": 0}}, "notation.numbers.AB", "the frame's number"),
    ({"frame": 1, "numbers": {"frame": 3}}, "notation.numbers.frame", "given twice"),
    ({"style": "russian"}, "notation.style", "unknown key"),
])
def test_a_bad_notation_table_names_its_key(table, key, words):
    with pytest.raises(SpecError) as raised:
        exercise_from_dict(_compressor(table), file="c.toml")
    assert str(raised.value).startswith(f"c.toml: {key}: ") and words in str(raised.value)


#: a drawn length a sheet states: "(AB) = 27.5 mm", "(pb) = (πb) = 30 mm"
STATED = re.compile(r"((?:\([A-Za-zπ]\w*\)\s*=\s*)+)(\d+(?:\.\d+)?) mm")


def _expected_lengths(key: dict) -> dict[str, float]:
    """The lengths the key's scales draw for the crank pin, computed here from the key."""
    data = key["exercise"]
    drive = data["drive"]
    point = (data.get("plan") or {}).get("scale_point") or next(
        p for p in data["links"][drive["link"]] if p != drive["pivot"])
    (x0, y0), (x1, y1) = (data["links"][drive["link"]][p] for p in (drive["pivot"], point))
    length = math.hypot(x1 - x0, y1 - y0)
    omega, epsilon = drive["omega"], drive.get("epsilon", 0.0)
    scales = key["scales"]
    return {f"({drive['pivot']}{point})": length / scales["mu_l"],
            f"(p{point.lower()})": abs(omega) * length / scales["mu_v"],
            f"(π{point.lower()})": length * math.hypot(omega ** 2, epsilon) / scales["mu_a"]}


TEMPLATES = [*sorted((ROOT / "exercises" / "templates").glob("*.toml")), COMPRESSOR]


def _mismatches(key: dict) -> list[str]:
    """Each drawn length the key's task sheet states that its scales do not draw."""
    expected = _expected_lengths(key)
    text = task_text(key)
    found = STATED.findall(text)
    out = [] if found else ["no length stated"]
    for segments, value in found:
        for segment in re.findall(r"\([^)]*\)", segments):
            if segment not in expected:
                out.append(f"{segment}: not a length of the crank pin")
            elif float(value) != pytest.approx(expected[segment], rel=5e-3, abs=0.05):
                out.append(f"{key['student']}: {segment} = {value} mm stated, its scale draws "
                           f"{expected[segment]:.4g} mm")
    return out


@pytest.mark.parametrize("path", TEMPLATES, ids=lambda path: path.stem)
def test_every_task_sheet_states_the_lengths_its_scales_draw(path):
    template = load_template(path)
    for number in range(12 if template.is_random else 1):
        key = build_key(draw_variant(template, seed=11, student=f"s{number}"))
        assert not _mismatches(key)


def test_the_length_check_can_fail():
    template = load_template(TEMPLATES[0])
    keys = (build_key(draw_variant(template, seed=11, student=f"s{n}")) for n in range(40))
    key = next(key for key in keys if abs(_expected_lengths(key)["(AB)"] - 30.0) > 1.0)
    assert _mismatches({**key, "task": "Draw the crank with (AB) = 30 mm."})


def test_a_variant_keeps_its_machine_names():
    variant = draw_variant(load_template(TEMPLATES[0]), seed=3, student="x")
    key = build_key(variant)
    assert key["numbers"] == course_numbers(variant.exercise.mechanism)
    assert all("_" in q["id"] and q["symbol"] for q in key["questions"])


def test_the_force_steps_name_points_as_the_course_writes_them():
    """A step of the force analysis names its points with their digits as subscripts where
    a course reads it (the text report, the force figure: ΣM_O₁(1), O₂B), and by the file's
    names in the JSON report's sentences (ΣM_O1)."""
    from planmethod.forces.names import PointNames
    from planmethod.render.report_text import force_lines
    from planmethod.spec import load_exercise
    from planmethod.words import render

    forces = analyse(load_exercise(ROOT / "exercises" / "loaded_press_sixbar.toml")).forces
    text = "\n".join(force_lines(forces))
    assert "ΣM_O₁(1) = 0" in text and "Rᵗ₀₃ ⟂ O₂B from ΣM_B(3)" in text
    assert not re.search(r"O[12](?![₀-₉])", text), text
    steps = [step for group in forces.solution.groups.groups for step in group.steps]
    plain = [render(step) for step in steps]
    assert "M_b from ΣM_O1(crank) = 0" in plain
    assert any(isinstance(value, PointNames) for step in steps for _, value in step.fields)
