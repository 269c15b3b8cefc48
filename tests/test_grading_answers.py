"""Keys, drawing tolerances and numeric grading with feedback on common mistakes."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from planmethod.errors import SpecError
from planmethod.grading.answers import grade_answers, grade_many, read_answers
from planmethod.grading.keys import build_key, bundle, load_keys
from planmethod.grading.templates import draw_variant, load_template, parse_template
from planmethod.grading.tolerances import emulate_drawings, propagate
from planmethod.spec import load_exercise

DATA = Path(__file__).parent / "data" / "grading"
SEED = "exercises/compressor_slider_crank.toml"


@pytest.fixture(scope="module")
def seed_key():
    return build_key(draw_variant(load_template(SEED)))


def by_id(result):
    return {q["id"]: q for q in result["questions"]}


@pytest.mark.parametrize("path", [SEED, "exercises/fourbar_coupler_point.toml",
                                  "exercises/slotted_lever.toml"])
def test_worst_case_tolerance_covers_random_drawings(path):
    exercise = load_exercise(path)
    found = propagate(exercise, 0.5)
    drawings = emulate_drawings(exercise, 0.5, 300, seed=4)
    for quantity, value in found.values.items():
        if value is None:
            continue
        deviation = np.abs(drawings[quantity] - value)
        tolerance = found.tolerances[quantity]
        assert deviation.max() <= tolerance * 1.001, quantity
        # …and is not absurdly loose: random drawings use at least a third of it
        assert deviation.max() >= tolerance / 3, quantity
    for plan, radii in found.radii.items():
        for label, radius in radii.items():
            spread = np.hypot(*(drawings[f"points:{plan}:{label}"]
                                - np.asarray(found.points[plan][label])).T)
            assert spread.max() <= radius * 1.001 + 1e-9, (plan, label)


def test_tolerance_grows_with_the_drafting_precision():
    exercise = load_exercise(SEED)
    fine, coarse = propagate(exercise, 0.25), propagate(exercise, 1.0)
    for quantity in fine.values:
        assert coarse.tolerances[quantity] == pytest.approx(4 * fine.tolerances[quantity])


def test_key_holds_every_asked_value_plan_points_and_tolerances(seed_key):
    questions = by_id(seed_key)
    assert set(questions) == {"v_C", "v_D", "a_C", "a_D", "omega_BC", "epsilon_BC", "rho_D"}
    assert questions["v_C"]["value"] == pytest.approx(5.2716, abs=1e-4)
    assert questions["omega_BC"]["value"] == pytest.approx(-24.2536, abs=1e-4)
    assert questions["rho_D"]["value"] == pytest.approx(0.07377, abs=1e-5)
    for question in questions.values():
        assert 0 < question["tolerance"] < 0.15 * abs(question["value"])
    velocity = seed_key["plans"]["velocity"]
    assert velocity["points_mm"]["b"] == pytest.approx([-21.2132, 21.2132], abs=1e-4)
    assert set(velocity["tolerance_mm"]) == set(velocity["points_mm"])
    assert velocity["tolerance_mm"]["c"] >= 0.25
    assert seed_key["scales"]["mu_v"] == pytest.approx(0.2)
    json.dumps(seed_key, allow_nan=False)


def test_instructor_overrides_and_floors():
    text = Path(SEED).read_text() + """
[grading]
precision_mm = 0
rel_floor = 0.01
points = { rho_D = 3 }
[grading.tolerance]
v_C = { rel = 0.05 }
a_C = 20.0
"""
    key = build_key(draw_variant(parse_template(text, file="seed.toml")))
    questions = by_id(key)
    assert questions["v_C"]["tolerance"] == pytest.approx(0.05 * 5.27163, rel=1e-4)
    assert questions["a_C"]["tolerance"] == 20.0
    assert questions["v_D"]["tolerance_from"] == "floor"          # an exact drawing
    assert questions["v_D"]["tolerance"] == pytest.approx(0.01 * 5.20868, rel=1e-4)
    assert questions["rho_D"]["points"] == 3 and questions["v_D"]["points"] == 1


@pytest.mark.parametrize(("table", "key"), [
    ("[grading]\nprecision_mm = -1\n", "grading.precision_mm"),
    ("[grading]\ncolour = 1\n", "grading.colour"),
    ("[grading.tolerance]\nv_X = { rel = 0.1 }\n", "grading.tolerance.v_X"),
    ("[grading.tolerance]\nv_C = { rel = 0 }\n", "grading.tolerance.v_C.rel"),
    ("[grading.tolerance]\nv_C = \"wide\"\n", "grading.tolerance.v_C"),
])
def test_bad_grading_tables_name_the_key(table, key):
    text = Path(SEED).read_text() + "\n" + table
    with pytest.raises(SpecError) as caught:
        build_key(draw_variant(parse_template(text, file="seed.toml")))
    assert f"seed.toml: {key}:" in str(caught.value)


def test_seed_001_printed_answers_are_marked_wrong_and_by_how_much(seed_key):
    rows = read_answers(DATA / "compressor_paper_answers.csv")
    (result,) = grade_many({"*": seed_key}, rows)
    questions = by_id(result)
    assert result["score"] == 0
    for name in ("v_C", "omega_BC", "a_C", "epsilon_BC", "rho_D"):
        assert not questions[name]["correct"], name
    assert "24.1 % low" in questions["v_C"]["feedback"]
    assert "17.3 % low" in questions["a_C"]["feedback"]
    assert "12.4 % low" in questions["epsilon_BC"]["feedback"]
    omega = questions["omega_BC"]["feedback"]
    assert "sense is reversed" in omega and "clockwise" in omega and "17.5 % low" in omega
    assert "18.0 % low" in questions["rho_D"]["feedback"]


EXPECTED_MISTAKES = {
    "sense": {"omega_BC": "sense", "epsilon_BC": "sense"},
    "mm_per_s": {"v_C": "millimetres", "v_D": "millimetres", "rho_D": "millimetres"},
    "no_scale": {"v_C": "scale_none", "v_D": "scale_none", "a_C": "scale_none",
                 "a_D": "scale_none", "omega_BC": "scale_none", "epsilon_BC": "scale_none"},
    "scale_twice": {"v_C": "scale_twice", "v_D": "scale_twice", "a_C": "scale_twice",
                    "a_D": "scale_twice", "omega_BC": "scale_twice"},
    "degrees": {"omega_BC": "degrees", "epsilon_BC": "degrees"},
    "no_normal": {"a_C": "no_normal", "epsilon_BC": "no_normal",
                  "rho_D": "full_acceleration"},
}


def test_common_mistakes_get_the_right_feedback(seed_key):
    results = {r["student"]: r for r in grade_many({"*": seed_key},
                                                   read_answers(DATA / "compressor_mistakes.csv"))}
    assert results["exact"]["score"] == results["exact"]["max_score"] == 7
    assert results["careful"]["score"] == 7        # a careful drawing passes everywhere
    for student, expected in EXPECTED_MISTAKES.items():
        questions = by_id(results[student])
        for name, question in questions.items():
            if name in expected:
                assert not question["correct"], (student, name)
                assert question["mistake"] == expected[name], (student, name,
                                                               question["feedback"])
            else:
                assert question["correct"], (student, name, question["feedback"])
    feedback = by_id(results["no_normal"])["a_C"]["feedback"]
    assert "normal component aⁿ was left out" in feedback


def test_a_negative_magnitude_is_told_it_is_a_magnitude(seed_key):
    """A speed given with a minus sign is not "199.8 % low": the feedback says that a speed is
    a magnitude; a signed quantity with the wrong sign still says the sense is reversed."""
    values = {q["id"]: q["value"] for q in seed_key["questions"]}
    result = by_id(grade_answers(seed_key, {"v_C": -values["v_C"],
                                            "omega_BC": -values["omega_BC"]}))
    speed = result["v_C"]
    assert not speed["correct"] and "%" not in speed["feedback"]
    assert "v_C is the speed of C, |v_C|: a magnitude, never negative" in speed["feedback"]
    assert speed["hint"].endswith("a magnitude, never negative")
    assert "right" not in speed["hint"] and "right: " in speed["feedback"]
    assert result["omega_BC"]["mistake"] == "sense"


def test_a_negative_magnitude_is_told_in_the_courses_names():
    """The Coriolis magnitude aᵏ₂₃ and the speed of B₃ of the slotted lever, given negative,
    are told they are magnitudes in the course's symbols (never ``v_B@lever`` or
    ``block/lever``), as the workbook page tells them (its note comes from the same
    function)."""
    from test_workbook import page_data

    from planmethod.commands.workbook import build_workbook
    from planmethod.grading.answers import magnitude_note
    from planmethod.numbering import course_numbers

    path = "exercises/slotted_lever.toml"
    key = build_key(draw_variant(load_template(path)))
    values = {q["id"]: q["value"] for q in key["questions"]}
    result = by_id(grade_answers(key, {"coriolis_block/lever": -values["coriolis_block/lever"],
                                       "v_B@lever": -values["v_B@lever"]}))
    coriolis, speed = result["coriolis_block/lever"], result["v_B@lever"]
    assert "%" not in coriolis["feedback"] and coriolis["feedback"].startswith(
        "aᵏ₂₃ = -2.77145 m/s²: wrong — aᵏ₂₃ is the magnitude of the Coriolis acceleration "
        "aᵏ₂₃ of link 2 (block) along link 3 (lever): a magnitude, never negative")
    assert "v_B₃ is the speed of B₃, |v_B₃|: a magnitude, never negative" in speed["feedback"]
    exercise = load_exercise(path)
    notes = {q["name"]: q["negative"] for q in page_data(build_workbook(exercise, 120))
             ["quantities"]}
    numbers = course_numbers(exercise.mechanism)
    assert notes["v_B@lever"] == magnitude_note("v_B@lever", numbers) and \
        notes["v_B@lever"] in speed["feedback"]
    assert notes["coriolis_block/lever"] in coriolis["feedback"]
    assert not any("@" in note or "/" in note for note in notes.values() if note)


def test_a_reversed_sign_is_told_in_the_quantitys_own_sense():
    """A slide's travel or sliding velocity with the wrong sign is not told "the right answer
    is counter-clockwise": its sign is along or against the guide; a link's ω still turns
    counter-clockwise or clockwise."""
    key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    values = {q["id"]: q["value"] for q in key["questions"]}
    assert values["s_block/lever"] > 0 and values["dds_block/lever"] < 0
    result = by_id(grade_answers(key, {
        "s_block/lever": -0.8 * values["s_block/lever"],
        "dds_block/lever": -0.5 * values["dds_block/lever"],
        "omega_lever": -0.5 * values["omega_lever"]}))
    travel = result["s_block/lever"]["feedback"]
    assert "the sense is reversed (the right answer is positive, along the guide, 0.360555 m" \
        in travel and "clockwise" not in travel
    assert "(the right answer is negative, against the guide, -5.60034 m/s²" in \
        result["dds_block/lever"]["feedback"]
    assert "(the right answer is counter-clockwise, 1.92308 rad/s" in \
        result["omega_lever"]["feedback"]


def test_junk_answers_are_reported_not_crashed(seed_key):
    (result,) = grade_many({"*": seed_key}, [r for r in read_answers(
        DATA / "compressor_mistakes.csv") if r[0] == "junk"])
    questions = by_id(result)
    assert "'abc' is not a number" in questions["v_C"]["feedback"]
    assert "no answer" in questions["v_D"]["feedback"]
    assert questions["a_C"]["answer"] == -5.27          # a typographic minus is a minus
    assert questions["a_D"]["answer"] == 5.27           # a decimal comma
    assert "is not a number" in questions["omega_BC"]["feedback"]   # 1e999
    assert result["score"] == 0


@pytest.mark.parametrize(("text", "fragment"), [
    ("", "empty"),
    ("student\n", "header row"),
    ("student,v_C\n,5\n", "no student id"),
    ("student,v_C\ns1,5,6,7\n", "cells"),
    ("{not json", "not valid JSON"),
    ("[1, 2]", "must be an object"),
])
def test_malformed_answer_files(tmp_path, text, fragment):
    path = tmp_path / ("answers.json" if text.startswith(("{", "[")) else "answers.csv")
    path.write_text(text)
    with pytest.raises(SpecError) as caught:
        read_answers(path)
    assert fragment in str(caught.value) and str(path) in str(caught.value)


def test_json_answers_and_per_student_keys(tmp_path):
    template = load_template("exercises/templates/slider_crank.toml")
    keys = [build_key(draw_variant(template, seed=9, student=s)) for s in ("ann", "bob")]
    path = tmp_path / "keys.json"
    path.write_text(json.dumps(bundle(keys, template="slider_crank", seed=9)))
    loaded = load_keys(path)
    answers = {k["student"]: {q["id"]: q["value"] for q in k["questions"]} for k in keys}
    (tmp_path / "answers.json").write_text(json.dumps(answers))
    # each student is graded against their own variant: full marks
    results = grade_many(loaded, read_answers(tmp_path / "answers.json"))
    assert [r["score"] == r["max_score"] for r in results] == [True, True]
    # swapped answers (ann hands in bob's) are wrong somewhere
    swapped = grade_many(loaded, [("ann", answers["bob"])])
    assert swapped[0]["score"] < swapped[0]["max_score"]
    unknown = grade_many(loaded, [("eve", answers["bob"])])
    assert "no key for student 'eve'" in unknown[0]["error"]


def test_grade_answers_matches_ids_ignoring_case(seed_key):
    result = grade_answers(seed_key, {"V_c": 5.27, "colour": "blue"})
    assert by_id(result)["v_C"]["correct"] and result["ignored"] == ["colour"]


def test_a_csv_without_a_student_column_is_one_students_answers(tmp_path, capsys, seed_key):
    """A header of question ids only, with one row of the exact answers, grades full marks:
    nothing is taken for a student id, nothing is dropped (through the command, too)."""
    from planmethod.cli import main

    questions = seed_key["questions"]
    path = tmp_path / "answers.csv"
    path.write_text(",".join(q["id"] for q in questions) + "\n"
                    + ",".join(repr(q["value"]) for q in questions) + "\n")
    ((student, answers),) = read_answers(path)
    assert student == "*"
    assert len(answers) == len(questions)
    result = grade_answers(seed_key, answers)
    assert result["score"] == result["max_score"] and not result["ignored"]
    assert main(["grade", SEED, str(path), "--json", str(tmp_path / "out.json")]) == 0
    assert capsys.readouterr().out.startswith(f"the answers: {len(questions)}/{len(questions)}")
    (graded,) = json.loads((tmp_path / "out.json").read_text())["answers"]
    assert graded["score"] == graded["max_score"] == len(questions)


@pytest.mark.parametrize(("text", "fragment"), [
    ("v_C,omega_BC\n5.27,-24.25\n5.3,-24\n", "no student column"),
    ("student,v_C\ns1,5\ns2,6\nS1,7\n", "student 'S1' answers twice (entries 1 and 3)"),
    ('[{"student": "a", "v_C": 1}, {"student": "a", "v_C": 2}]', "student 'a' answers twice"),
])
def test_ambiguous_answer_files_are_refused(tmp_path, text, fragment):
    path = tmp_path / ("answers.json" if text.startswith("[") else "answers.csv")
    path.write_text(text)
    with pytest.raises(SpecError) as caught:
        read_answers(path)
    assert fragment in str(caught.value) and str(path) in str(caught.value)


def test_the_class_report_counts_right_answers_and_named_mistakes(tmp_path, capsys):
    """grade --report: per question the share right and the share each mistake explains, as
    CSV and a chart (the numbers are the ones put in)."""
    import csv as csv_module

    from planmethod.cli import main

    template = load_template("exercises/templates/slider_crank.toml")
    keys = [build_key(draw_variant(template, seed=2, student=f"s{i}")) for i in range(10)]
    (tmp_path / "keys.json").write_text(json.dumps(bundle(keys, template="t", seed=2)))
    first = keys[0]["questions"][0]
    mistake = first["mistakes"][0]
    answers = {}
    for index, key in enumerate(keys):
        row = {q["id"]: q["value"] for q in key["questions"]}
        question = key["questions"][0]
        if index < 4:      # four students make the first mistake on the first question
            kind = next(m for m in question["mistakes"] if m["kind"] == mistake["kind"])
            row[question["id"]] = kind["value"]
        elif index < 6:    # two are wrong in no recognisable way
            row[question["id"]] = 1.37 * question["value"]
        answers[key["student"]] = row
    (tmp_path / "answers.json").write_text(json.dumps(answers))
    assert main(["grade", str(tmp_path / "keys.json"), str(tmp_path / "answers.json"),
                 "--report", str(tmp_path / "report"), "--quiet"]) == 0
    rows = list(csv_module.DictReader((tmp_path / "report" / "questions.csv").open()))
    top = rows[0]
    assert top["question"] == first["id"] and top["students"] == "10"
    assert float(top["correct"]) == 0.4 and float(top["unexplained"]) == 0.2
    assert top["top_mistake"] == mistake["kind"] and float(top["top_mistake_share"]) == 0.4
    assert all(float(row["correct"]) == 1.0 for row in rows[1:])
    assert (tmp_path / "report" / "class_report.png").stat().st_size > 5000
