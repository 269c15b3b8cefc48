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
from planmethod.words import message, render

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
epsilon_BC = { abs = 30.0 }
"""
    key = build_key(draw_variant(parse_template(text, file="seed.toml")))
    assert (key["precision_mm"], key["rel_floor"]) == (0, 0.01)   # the key records them
    questions = by_id(key)
    assert questions["v_C"]["tolerance"] == pytest.approx(0.05 * 5.27163, rel=1e-4)
    assert questions["a_C"]["tolerance"] == 20.0
    assert (questions["epsilon_BC"]["tolerance"], questions["epsilon_BC"]["tolerance_from"]) == (
        30.0, "override (abs)")
    assert questions["v_D"]["tolerance_from"] == "floor"          # an exact drawing
    assert questions["v_D"]["tolerance"] == pytest.approx(0.01 * 5.20868, rel=1e-4)
    assert questions["rho_D"]["points"] == 3 and questions["v_D"]["points"] == 1


def test_a_sheet_worth_no_points_is_read():
    """points = 0 (a practice sheet): every question is worth 0 and is still graded."""
    text = Path(SEED).read_text() + "\n[grading]\npoints = 0\n"
    key = build_key(draw_variant(parse_template(text, file="seed.toml")))
    assert key["questions"] and all(q["points"] == 0 for q in key["questions"])


@pytest.mark.parametrize(("table", "key"), [
    ("[grading]\nprecision_mm = -1\n", "grading.precision_mm"),
    ("[grading]\ncolour = 1\n", "grading.colour"),
    ("[grading.tolerance]\nv_X = { rel = 0.1 }\n", "grading.tolerance.v_X"),
    ("[grading.tolerance]\nv_C = { rel = 0 }\n", "grading.tolerance.v_C.rel"),
    ("[grading.tolerance]\nv_C = \"wide\"\n", "grading.tolerance.v_C"),
    ("[grading.points]\nv_C = -1\n", "grading.points.v_C"),
    ("[grading]\npoints = -2\n", "grading.points"),
])
def test_bad_grading_tables_name_the_key(table, key):
    text = Path(SEED).read_text() + "\n" + table
    with pytest.raises(SpecError) as caught:
        build_key(draw_variant(parse_template(text, file="seed.toml")))
    assert f"seed.toml: {key}:" in str(caught.value)


def test_seed_001_printed_answers_are_marked_wrong_and_by_how_much(seed_key):
    rows = read_answers(DATA / "compressor_paper_answers.csv")
    (result,) = [r.as_dict() for r in grade_many({"*": seed_key}, rows)]
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
    results = {r["student"]: r for r in [r.as_dict() for r in grade_many({"*": seed_key},
                                                   read_answers(DATA / "compressor_mistakes.csv"))]}
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
                                            "omega_BC": -values["omega_BC"]}).as_dict())
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

    from planmethod.application.workbook import build_workbook
    from planmethod.grading.answers import magnitude_note
    from planmethod.numbering import course_numbers

    path = "exercises/slotted_lever.toml"
    key = build_key(draw_variant(load_template(path)))
    values = {q["id"]: q["value"] for q in key["questions"]}
    result = by_id(grade_answers(key, {"coriolis_block/lever": -values["coriolis_block/lever"],
                                       "v_B@lever": -values["v_B@lever"]}).as_dict())
    coriolis, speed = result["coriolis_block/lever"], result["v_B@lever"]
    assert "%" not in coriolis["feedback"] and coriolis["feedback"].startswith(
        "aᵏ₂₃ = -2.77145 m/s²: wrong — aᵏ₂₃ is the magnitude of the Coriolis acceleration "
        "aᵏ₂₃ of link 2 (block) along link 3 (lever): a magnitude, never negative")
    assert "v_B₃ is the speed of B₃, |v_B₃|: a magnitude, never negative" in speed["feedback"]
    exercise = load_exercise(path)
    notes = {q["name"]: q["negative"] for q in page_data(build_workbook(exercise, 120))
             ["quantities"]}
    numbers = course_numbers(exercise.mechanism)
    assert notes["v_B@lever"] == render(magnitude_note("v_B@lever", numbers)) and \
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
        "omega_lever": -0.5 * values["omega_lever"]}).as_dict())
    travel = result["s_block/lever"]["feedback"]
    assert "the sense is reversed (the right answer is positive, along the guide, 0.360555 m" \
        in travel and "clockwise" not in travel
    assert "(the right answer is negative, against the guide, -5.60034 m/s²" in \
        result["dds_block/lever"]["feedback"]
    assert "(the right answer is counter-clockwise, 1.92308 rad/s" in \
        result["omega_lever"]["feedback"]


def test_junk_answers_are_reported_not_crashed(seed_key):
    (result,) = [r.as_dict() for r in grade_many({"*": seed_key}, [r for r in read_answers(
        DATA / "compressor_mistakes.csv") if r[0] == "junk"])]
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
    results = [r.as_dict() for r in grade_many(loaded, read_answers(tmp_path / "answers.json"))]
    assert [r["score"] == r["max_score"] for r in results] == [True, True]
    # swapped answers (ann hands in bob's) are wrong somewhere
    swapped = [r.as_dict() for r in grade_many(loaded, [("ann", answers["bob"])])]
    assert swapped[0]["score"] < swapped[0]["max_score"]
    unknown = [r.as_dict() for r in grade_many(loaded, [("eve", answers["bob"])])]
    assert "no key for student 'eve'" in unknown[0]["error"]


def test_grade_answers_matches_ids_ignoring_case(seed_key):
    result = grade_answers(seed_key, {"V_c": 5.27, "colour": "blue"}).as_dict()
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
    result = grade_answers(seed_key, answers).as_dict()
    assert result["score"] == result["max_score"] and not result["ignored"]
    assert main(["grade", SEED, str(path), "--json", str(tmp_path / "out.json")]) == 0
    assert capsys.readouterr().out.startswith(f"the answers: {len(questions)}/{len(questions)}")
    (graded,) = json.loads((tmp_path / "out.json").read_text())["answers"]
    assert graded["score"] == graded["max_score"] == len(questions)


@pytest.mark.parametrize(("text", "fragment"), [
    ("v_C,omega_BC\n5.27,-24.25\n5.3,-24\n", "no student column"),
    ("student,v_C\ns1,5\ns2,6\nS1,7\n", "student 's1' and student 'S1' are one student, "
                                       "compared ignoring case (entries 1 and 3)"),
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


_ONE_OBJECT = ("the file is either {\"student\": {\"question id\": answer, …}, …} or one "
               "student's {\"question id\": answer, …}")


@pytest.mark.parametrize(("name", "text", "message"), [
    ("a.json", '{"s01": {"v_C": [1]}}', 's01.v_C: is a list, not an answer (a number): give '
     '{"question id": answer, …} for each student'),
    ("b.json", '{"s01": {"v_C": {"x": 1}}}', 's01.v_C: is an object, not an answer (a number): '
     'give {"question id": answer, …} for each student'),
    ("c.json", '{"s01": {"v_C": 1}, "s02": true}',
     f"s02: is true/false, not an object of one student's answers like the 1 other: {_ONE_OBJECT}"),
    ("d.json", '{"s01": {"v_C": 1}, "s02": null}',
     f"s02: is null, not an object of one student's answers like the 1 other: {_ONE_OBJECT}"),
    ("e.json", '{"s01": {"v_C": 1}, "s02": "x"}',
     f"s02: is a text, not an object of one student's answers like the 1 other: {_ONE_OBJECT}"),
    ("f.json", '{"s01": {"v_C": 1}, "s02": 2.5}',
     f"s02: is a number, not an object of one student's answers like the 1 other: {_ONE_OBJECT}"),
    ("h.csv", "v_C,omega_BC\n1,2\n3,4\n", "has no student column (student, student_id, id, …) "
     "but 2 rows of answers: without one, the file holds one student's answers in one row"),
    ("i.csv", "v_C,omega_BC\n1,2,3\n", "line 2: has 3 cells, the header 2"),
    ("j.json", "[1]", "[0]: each entry must be an object"),
    ("k.json", '[{"v_C": 1}]', "[0]: no student id (give 'student')"),
    ("l.json", '[{"student": "", "v_C": 1}]', "[0].student: no student id (give 'student')"),
    ("m.json", '[{"student": {"a": 1}}]', "[0].student: no student id (give 'student')"),
    ("n.json", '[{"student": "s1", "answers": [1]}]', "[0].answers: must be an object of answers"),
    ("o.json", '[{"id": "s1", "answers": {"v_C": [1]}}]', '[0].answers.v_C: is a list, not an '
     'answer (a number): give {"question id": answer, …} for each student'),
    ("p.json", '{"answers": 1, "drawings": 2}',
     "this is planmethod grade's --json output (graded results), not an answers file"),
    ("q.json", '{"s1": {"score": 1, "max_score": 2, "questions": []}}',
     "s1: this is planmethod grade's --json output (graded results), not an answers file"),
    ("r.json", '{"v_C": 1, "a_C": 2, "w": {"x": 1}}',
     f"w: is an object, not an answer like the 2 others: {_ONE_OBJECT}"),
    ("s.json", '{"s1": {"v_C": 1}, "s2": {"v_C": 2}, "s3": 5}',
     f"s3: is a number, not an object of one student's answers like the 2 others: {_ONE_OBJECT}"),
    ("t.json", '[{"sid": "s1", "v_C": 1}, {"email": "S1", "v_C": 2}]',
     "student 's1' and student 'S1' are one student, compared ignoring case (entries 1 and "
     "2); keep one"),
    ("u.json", "{}", "no student's answers (the object is empty)"),
    ("v.json", "[]", "no student's answers (the list is empty)"),
    ("w.json", '"x"', "must be an object or a list of objects"),
])
def test_a_refused_answers_file_is_told_exactly_why(tmp_path, name, text, message):
    (tmp_path / name).write_text(text)
    with pytest.raises(SpecError) as caught:
        read_answers(tmp_path / name)
    assert str(caught.value) == f"{tmp_path / name}: {message}"


def test_a_reversed_sense_names_the_right_sense_in_words():
    from planmethod.grading.answers import grade_question

    question = {"id": "omega_BC", "symbol": "ω₂", "unit": "rad/s", "value": -24.25,
                "tolerance": 0.5, "signed": True, "mistakes": []}
    assert grade_question(question, 30.0).as_dict()["feedback"] == (
        "ω₂ = 30 rad/s: wrong — the sense is reversed (the right answer is clockwise, "
        "-24.25 rad/s ± 0.5) and the magnitude 30 is 23.7 % high")
    assert grade_question(dict(question, value=24.25), -30.0).as_dict()["feedback"] == (
        "ω₂ = -30 rad/s: wrong — the sense is reversed (the right answer is counter-clockwise, "
        "24.25 rad/s ± 0.5) and the magnitude 30 is 23.7 % high")


def test_feedback_levels_show_the_values_the_hint_or_nothing():
    from planmethod.grading.answers import feedback_text, grade_question

    typed = grade_question({"id": "v_C", "value": 5.27, "tolerance": 0.1}, 6.0)
    assert render(feedback_text(typed, "hints")) == "v_C = 6: wrong (about 10 % too high)"
    assert feedback_text(typed) == typed.feedback and feedback_text(typed, "score") == ""
    graded = typed.as_dict()        # as grade --json writes it
    assert feedback_text(graded) == graded["feedback"] == feedback_text(graded, "full")
    assert feedback_text(graded, "hints") == "v_C = 6: wrong (about 10 % too high)"
    assert feedback_text(graded, "score") == ""
    assert feedback_text({"feedback": "kept"}, "hints") == ""     # no hint: nothing shown
    with pytest.raises(ValueError) as caught:
        feedback_text(graded, "all")
    assert str(caught.value) == "feedback level 'all' is not one of full, hints, score"


def test_the_class_report_of_five_results_whole():
    """Per question in the order first met: students graded, answers given, the mean share of
    the points (a question worth nothing counts 0), the share right, each named mistake's
    share sorted by name, the share wrong and unexplained; the most common mistake in the
    CSV; a result without questions (no key) counts nowhere."""
    from dataclasses import asdict, replace

    from planmethod.grading.report import class_statistics, mistakes_csv, questions_csv
    from planmethod.grading.results import GradedQuestion, StudentGrade
    from planmethod.grading.verdicts import AnswerVerdict, Verdict

    def graded(question, score, points, correct, answer, mistake):
        return GradedQuestion(question, answer, 1.0, 0.1, "", points, score, correct, mistake,
                              Verdict(AnswerVerdict.WRONG))

    def student(*questions):
        return StudentGrade("s", "s", 0.0, 1.0, questions)

    results = [
        student(graded("v_C", 2.0, 2.0, True, 5.2, None), graded("w", 0.0, 0.0, False, None, None)),
        student(graded("v_C", 0.0, 2.0, False, 2.6, "sense"),
                graded("w", 0.0, 0.0, False, 3.0, "sense")),
        student(graded("v_C", 1.0, 2.0, False, -1.0, "scale_twice")),
        student(graded("v_C", 0.0, 2.0, False, 9.9, "sense")),
        StudentGrade("s", None, 0.0, None, error=message("no key"))]
    rows = class_statistics(results)
    assert [asdict(row) for row in rows] == [
        {"question": "v_C", "students": 4, "answered": 4, "mean_score": 0.375, "correct": 0.25,
         "mistakes": {"scale_twice": 0.25, "sense": 0.5}, "unexplained": 0.0},
        {"question": "w", "students": 2, "answered": 1, "mean_score": 0.0, "correct": 0.0,
         "mistakes": {"sense": 0.5}, "unexplained": 0.5}]
    assert list(rows[0].mistakes) == ["scale_twice", "sense"]
    assert questions_csv(rows) == (
        "question,students,answered,mean_score,correct,unexplained,top_mistake,"
        "top_mistake_share\n"
        "v_C,4,4,0.3750,0.2500,0.0000,sense,0.5000\n"
        "w,2,1,0.0000,0.0000,0.5000,sense,0.5000\n")
    assert mistakes_csv(rows) == ("question,mistake,share\nv_C,scale_twice,0.2500\n"
                                  "v_C,sense,0.5000\nw,sense,0.5000\n")
    no_mistakes = [replace(rows[0], mistakes={})]
    assert questions_csv(no_mistakes).splitlines()[1] == "v_C,4,4,0.3750,0.2500,0.0000,,0.0000"


@pytest.mark.parametrize(("right", "answer", "signed", "feedback", "hint"), [
    (0.0, 0.5, True, "0.5 off (off by 0.5 m; right: 0 m ± 0.001)", "too high"),
    (2.0, 20.0, False, "10 times the right value (off by 18 m; right: 2 m ± 0.001 = ± 0.05 %)",
     "about 10 times what it should be"),
    (2.0, 19.98, False, "899.0 % high (off by 17.98 m; right: 2 m ± 0.001 = ± 0.05 %)",
     "about 10 times what it should be"),
    (2.0, 0.2, False, "0.1 times the right value (off by 1.8 m; right: 2 m ± 0.001 = ± 0.05 %)",
     "about 0.1 times what it should be"),
    (2.0, 0.2002, False, "90.0 % low (off by 1.7998 m; right: 2 m ± 0.001 = ± 0.05 %)",
     "about 90 % too low"),
    (2.0, 2.25, False, "12.5 % high (off by 0.25 m; right: 2 m ± 0.001 = ± 0.05 %)",
     "about 10 % too high"),                                # to one digit: never the value
    (-2.0, -3.0, True, "50.0 % high in magnitude (off by 1 m; right: -2 m ± 0.001 = ± 0.05 %)",
     "about 50 % too large in magnitude"),
    (-2.0, -1.0, True, "50.0 % low in magnitude (off by 1 m; right: -2 m ± 0.001 = ± 0.05 %)",
     "about 50 % too small in magnitude"),
    (-2.0, 0.0, True, "100.0 % low in magnitude (off by 2 m; right: -2 m ± 0.001 = ± 0.05 %)",
     "too small in magnitude"),
    (2.0, 0.0, False, "100.0 % low (off by 2 m; right: 2 m ± 0.001 = ± 0.05 %)", "too low"),
])
def test_how_far_off_an_answer_is_told(right, answer, signed, feedback, hint):
    """Off by a factor of 10 or more (or 0.1 or less): so many times the right value; else
    the percentage, in magnitude for a negative right answer (an answer of 0 for −2 is 100 %
    low in magnitude, and too small in magnitude — not "too high"); a right answer of 0: by
    how much."""
    from planmethod.grading.answers import grade_question

    graded = grade_question({"id": "x", "unit": "m", "value": right, "tolerance": 0.001,
                             "signed": signed}, answer).as_dict()
    assert graded["feedback"] == f"x = {answer:g} m: wrong — {feedback}"
    assert graded["hint"] == f"x = {answer:g} m: wrong ({hint})"


_OMEGA = {"id": "omega_BC", "symbol": "ω₂", "unit": "rad/s", "value": -2.0, "tolerance": 0.5,
          "signed": True, "points": 2.0,
          "mistakes": [{"kind": "sense", "value": 2.0, "tolerance": 0.5,
                        "feedback": "the sense (sign) is reversed"},
                       {"kind": "scale_ten", "value": -20.0, "tolerance": 5.0, "also": ["degrees"],
                        "feedback": "the plan's scale was misread ten times too large"}]}
_RIGHT = "-2 rad/s ± 0.5"


@pytest.mark.parametrize(("answer", "fields", "feedback", "hint"), [
    (None, {}, f"ω₂: no answer (right: {_RIGHT})", "ω₂: no answer"),
    ("  ", {}, f"ω₂: no answer (right: {_RIGHT})", "ω₂: no answer"),
    ("abc", {}, f"ω₂: 'abc' is not a number (right: {_RIGHT})", "ω₂: 'abc' is not a number"),
    (True, {}, f"ω₂: 'True' is not a number (right: {_RIGHT})", "ω₂: 'True' is not a number"),
    (float("nan"), {}, f"ω₂: 'nan' is not a number (right: {_RIGHT})",
     "ω₂: 'nan' is not a number"),
    ("1e999", {}, f"ω₂: '1e999' is not a number (right: {_RIGHT})",
     "ω₂: '1e999' is not a number"),
    ("x" * 50, {}, f"ω₂: {'x' * 40!r} is not a number (right: {_RIGHT})",
     f"ω₂: {'x' * 40!r} is not a number"),
    ("\u22122,4", {"answer": -2.4, "correct": True, "score": 2.0},
     "ω₂ = -2.4 rad/s: correct (exact -2, tolerance ± 0.5)", "ω₂ = -2.4 rad/s: correct"),
    ("- 2 . 5", {"answer": -2.5, "correct": True, "score": 2.0},     # exactly at the tolerance
     "ω₂ = -2.5 rad/s: correct (exact -2, tolerance ± 0.5)", "ω₂ = -2.5 rad/s: correct"),
    ("1,000.5", {}, f"ω₂: '1,000.5' is not a number (right: {_RIGHT})",
     "ω₂: '1,000.5' is not a number"),
    (-2.51, {"answer": -2.51},
     "ω₂ = -2.51 rad/s: wrong — 25.5 % high in magnitude (off by 0.51 rad/s; right: "
     f"{_RIGHT} = ± 25 %)", "ω₂ = -2.51 rad/s: wrong (about 30 % too large in magnitude)"),
    (2.5, {"answer": 2.5, "mistake": "sense"},      # at the sense mistake's tolerance
     f"ω₂ = 2.5 rad/s: wrong — it looks as if the sense (sign) is reversed (that gives 2; right: "
     f"{_RIGHT})", "ω₂ = 2.5 rad/s: wrong (too high) — it looks as if the sense (sign) is "
     "reversed"),
    (-25.0, {"answer": -25.0, "mistake": "scale_ten", "also": ["degrees"]},
     "ω₂ = -25 rad/s: wrong, 12.5 times the right value — it looks as if the plan's scale was "
     f"misread ten times too large (that gives -20; right: {_RIGHT})",
     "ω₂ = -25 rad/s: wrong (about 10 times what it should be) — it looks as if the plan's "
     "scale was "
     "misread ten times too large"),
    (25.0, {"answer": 25.0, "mistake": "scale_ten+sense"},
     "ω₂ = 25 rad/s: wrong — it looks as if the plan's scale was misread ten times too large, "
     f"and the sense is reversed (right: {_RIGHT})",
     "ω₂ = 25 rad/s: wrong — it looks as if the plan's scale was misread ten times too large, "
     "and the sense is reversed"),
    (6.0, {"answer": 6.0},
     f"ω₂ = 6 rad/s: wrong — the sense is reversed (the right answer is clockwise, {_RIGHT}) "
     "and the magnitude 6 is 200.0 % high", "ω₂ = 6 rad/s: wrong (the sense is reversed)"),
])
def test_a_graded_answer_field_by_field(answer, fields, feedback, hint):
    """Every branch of the grader on one question: nothing or no number given (cut to 40
    characters), a minus sign and a decimal comma read, right up to exactly the tolerance,
    wrong, a named mistake up to exactly its tolerance (and the others it stands for), a
    mistake with the sense reversed too, the sense reversed; with the errors against the
    right value."""
    from planmethod.grading.answers import grade_question

    graded = grade_question(_OMEGA, answer).as_dict()
    given = fields.get("answer")
    expected = {"id": "omega_BC", "answer": None, "value": -2.0, "tolerance": 0.5,
                "unit": "rad/s", "max_score": 2.0, "score": 0.0, "correct": False,
                "mistake": None, **fields, "feedback": feedback, "hint": hint}
    if given is not None:
        expected["error_abs"] = pytest.approx(abs(given + 2.0), rel=1e-12)
        expected["error_rel"] = pytest.approx(abs(given + 2.0) / 2.0, rel=1e-12)
    assert graded == expected


def test_a_question_without_unit_symbol_or_points_and_a_right_value_of_zero():
    from planmethod.grading.answers import grade_question

    assert grade_question({"id": "v_C", "value": 0.0, "tolerance": 0.1}, 0.3).as_dict() == {
        "id": "v_C", "answer": 0.3, "value": 0.0, "tolerance": 0.1, "unit": "",
        "max_score": 1.0, "score": 0.0, "correct": False, "mistake": None,
        "error_abs": 0.3, "error_rel": None,
        "feedback": "v_C = 0.3: wrong — 0.3 off (off by 0.3; right: 0 ± 0.1)",
        "hint": "v_C = 0.3: wrong (too high)"}
    assert render(grade_question({"id": "v_C", "value": 5.0, "tolerance": 0.1}, -5.0).feedback) == (
        "v_C = -5: wrong — v_C is the speed of C, |v_C|: a magnitude, never negative "
        "(right: 5 ± 0.1)")
    assert render(grade_question({"id": "v_C", "value": 5.0, "tolerance": 0.1}, 0.0).feedback) == (
        "v_C = 0: wrong — 100.0 % low (off by 5; right: 5 ± 0.1 = ± 2 %)")


@pytest.mark.parametrize(("name", "text", "rows"), [
    ("a.csv", "\ufeffstudent,v_C\ns1,5.2\n", [("s1", {"v_C": "5.2"})]),          # a BOM
    ("b.JSON", '{"s1": {"v_C": 5}}', [("s1", {"v_C": 5})]),
    ("c.txt", '  [{"student": "s1", "v_C": 5}]', [("s1", {"v_C": 5})]),     # JSON by content
    ("d.csv", "student;v_C;a_C\ns1;5,2;7\n", [("s1", {"v_C": "5,2", "a_C": "7"})]),
    ("e.csv", "student\tv_C\ns1\t5.2\n", [("s1", {"v_C": "5.2"})]),
    ("k.csv", "student, v_C\ns1, 5.2\n", [("s1", {"v_C": "5.2"})]),        # spaces after
])
def test_answers_files_in_every_form_read_alike(tmp_path, name, text, rows):
    (tmp_path / name).write_text(text, encoding="utf-8")
    assert read_answers(tmp_path / name) == rows


@pytest.mark.parametrize(("name", "text", "message"), [
    ("f.csv", 'student,v_C\ns1,"5.2\ns2,3\n', 'line 2: not valid CSV: unexpected end of data (is '
     'a quote (") left open or a cell quoted twice?)'),
    ("g.csv", 'student,v_C\ns1,"5.2\n3"\n',
     'line 2: a quoted cell runs on to line 3: is a closing quote (") missing?'),
    ("h.csv", "", "the file is empty"),
    ("i.csv", "student\ns1\n", "needs a header row with a student column and question columns "
     "(e.g. student,v_C,omega_BC)"),
    ("l.csv", "student,v_C\n\n,5\n", "line 3: no student id (column 'student')"),
])
def test_a_broken_csv_is_told_where_and_why(tmp_path, name, text, message):
    (tmp_path / name).write_text(text, encoding="utf-8")
    with pytest.raises(SpecError) as caught:
        read_answers(tmp_path / name)
    assert str(caught.value) == f"{tmp_path / name}: {message}"


def test_a_class_of_at_most_max_rows_students_is_read(tmp_path, monkeypatch):
    """MAX_ROWS students (200,000; here set to 3) are read, one more is refused by name, in
    CSV and in JSON."""
    from planmethod.grading import answers

    monkeypatch.setattr(answers, "MAX_ROWS", 3)
    rows = "".join(f"s{i},1\n" for i in range(3))
    (tmp_path / "all.csv").write_text("student,v_C\n" + rows, encoding="utf-8")
    assert len(read_answers(tmp_path / "all.csv")) == 3
    (tmp_path / "more.csv").write_text(f"student,v_C\n{rows}x,1\n", encoding="utf-8")
    (tmp_path / "more.json").write_text(json.dumps({f"s{i}": {"v_C": 1} for i in range(4)}))
    for name in ("more.csv", "more.json"):
        with pytest.raises(SpecError) as caught:
            read_answers(tmp_path / name)
        assert str(caught.value) == f"{tmp_path / name}: more than 3 students"


_NOT_A_KEY = "not a planmethod answer key (format must be 'planmethod-key')"


@pytest.mark.parametrize(("text", "message"), [
    ("[1]", _NOT_A_KEY), ('{"format": "x"}', _NOT_A_KEY),
    ('{"format": "planmethod-key"}', "questions: the key has no list of questions"),
    ('{"format": "planmethod-key", "questions": [1]}', "questions[0]: must be a table"),
    ('{"format": "planmethod-key", "questions": [{"id": "v", "value": 1}]}',
     "questions[0].tolerance: missing"),
    ('{"format": "planmethod-key", "questions": [{"id": "v", "value": true, "tolerance": 1}]}',
     "questions[0].value: must be a finite number, got true"),
    ('{"format": "planmethod-key", "questions": [{"id": "v", "value": 1, "tolerance": NaN}]}',
     "questions[0].tolerance: must be a finite number, got nan"),
    ('{"format": "planmethod-keys", "keys": 1}', "keys: the bundle has no list of keys"),
    ('{"format": "planmethod-keys", "keys": [{"format": "planmethod-key", "questions": []}, '
     '{"format": "y"}]}', f"keys[1]: {_NOT_A_KEY}"),
])
def test_a_refused_key_is_told_exactly_why(tmp_path, text, message):
    (tmp_path / "keys.json").write_text(text)
    with pytest.raises(SpecError) as caught:
        load_keys(tmp_path)                     # a folder: its keys.json
    assert str(caught.value) == f"{tmp_path / 'keys.json'}: {message}"


def test_a_single_key_grades_everyone_and_names_the_links_it_was_written_with(tmp_path):
    from planmethod.grading.keys import key_numbers

    key = {"format": "planmethod-key", "student": "s9", "questions": []}
    (tmp_path / "key.json").write_text(json.dumps(key))
    assert load_keys(tmp_path / "key.json") == {"s9": key, "*": key}
    assert key_numbers({"numbers": {"AB": "1", "frame": 0}}) == {"AB": 1, "frame": 0}
    assert key_numbers({}) == {} and key_numbers({"exercise": {"bad": 1}}) == {}
    written = build_key(draw_variant(load_template(SEED)))
    assert key_numbers({"exercise": written["exercise"]}) == written["numbers"] == {
        "frame": 0, "AB": 1, "BC": 2, "slider": 3}


def test_a_key_records_the_variant_it_keys():
    """Who and which draw a key is for (student, seed, attempt): what a later step builds
    the same variant from (a drawing's key at another angle, the instructor's re-grade)."""
    from dataclasses import replace

    variant = draw_variant(load_template(SEED), seed=3, student="s07")
    key = build_key(replace(variant, attempt=2))
    assert (key["student"], key["seed"], key["attempt"]) == ("s07", 3, 2)


def test_a_key_file_read_twice_is_parsed_once_and_read_again_when_it_changes(tmp_path,
                                                                              monkeypatch):
    import os

    from planmethod.grading import keys as keys_module

    parsed = []
    real = keys_module.parse_json
    monkeypatch.setattr(keys_module, "parse_json",
                        lambda text, **kw: parsed.append(1) or real(text, **kw))
    path = tmp_path / "key.json"
    key = {"format": "planmethod-key", "student": "s1", "questions": []}
    path.write_text(json.dumps(key))
    first, again = load_keys(path), load_keys(tmp_path / "." / "key.json")
    assert first == again and len(parsed) == 1      # the language's read, then the grading's
    first["s1"]["student"] = "changed by a caller"  # a caller's change is not kept
    assert load_keys(path)["s1"]["student"] == "s1"
    path.write_text(json.dumps({**key, "student": "s22"}))   # rewritten: read again
    os.utime(path, ns=(1, 1))
    assert list(load_keys(path)) == ["s22", "*"] and len(parsed) == 2
