"""The answer grader at the edges mutation testing found unchecked: one student's JSON file,
results refused by their exact keys, the row limit, which way a wrong answer is off at 0 and
between 0 and 1, the exact match of a question id before its case-folded one, and the entries
of students without a key."""

from __future__ import annotations

import json

import pytest

from planmethod.errors import SpecError
from planmethod.grading import answers as answers_module
from planmethod.grading.answers import grade_answers, grade_many, grade_question, read_answers
from planmethod.grading.keys import key_exercise


def _refusal(path) -> str:
    with pytest.raises(SpecError) as caught:
        read_answers(path)
    return str(caught.value)


def test_one_students_json_answers_are_read_under_the_common_key(tmp_path):
    path = tmp_path / "answers.json"
    path.write_text(json.dumps({"v_C": 5.2, "omega_BC": "1.5"}))
    assert read_answers(path) == [("*", {"v_C": 5.2, "omega_BC": "1.5"})]
    path.write_text(json.dumps({"v_C": [1]}))
    assert _refusal(path) == (f"{path}: v_C: is a list, not an answer (a number): give "
                              "{\"question id\": answer, …} for each student")


@pytest.mark.parametrize("results", [{"score": 1, "max_score": 2, "questions": []},
                                     {"answers": [], "drawings": []}])
def test_graded_results_with_exactly_their_own_keys_are_refused(tmp_path, results):
    path = tmp_path / "graded.json"
    path.write_text(json.dumps(results))
    assert _refusal(path) == (f"{path}: this is planmethod grade's --json output (graded "
                              "results), not an answers file")


def test_a_file_of_exactly_the_row_limit_is_read_and_one_more_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(answers_module, "MAX_ROWS", 3)
    path = tmp_path / "answers.json"
    path.write_text(json.dumps([{"student": f"s{k}", "v_C": 1} for k in range(3)]))
    assert [student for student, _ in read_answers(path)] == ["s0", "s1", "s2"]
    path.write_text(json.dumps([{"student": f"s{k}", "v_C": 1} for k in range(4)]))
    assert _refusal(path) == f"{path}: more than 3 students"


@pytest.mark.parametrize(("right", "answer", "signed", "hint", "off"), [
    (0.0, -1.0, False, "too low", "1 off"),                    # a right value of 0: no magnitude
    (-2.0, 1.0, True, "the sense is reversed", None),          # an answer of 1 against −2
    (-2.0, 0.5, True, "the sense is reversed", None),          # between 0 and 1
    (0.5, -1.0, True, "the sense is reversed", None),          # a right value between 0 and 1
    (-2.0, 0.5, False, "too high", "125.0 % low"),             # a magnitude's sign: no sense
    (0.5, 0.4, False, "too low", "20.0 % low"),                # no 'in magnitude' for 0.5
])
def test_which_way_a_wrong_answer_is_off_around_0_and_1(right, answer, signed, hint, off):
    graded = grade_question({"id": "x", "unit": "m", "value": right, "tolerance": 0.01,
                             "signed": signed}, answer)
    assert graded["hint"] == f"x = {answer:g} m: wrong ({hint})"
    if off is not None:
        assert graded["feedback"].startswith(f"x = {answer:g} m: wrong — {off} (off by ")


def _key() -> dict:
    return {"student": "s07", "variant": "v07",
            "questions": [{"id": "v_C", "unit": "m/s", "value": 5.0, "tolerance": 0.1}]}


def test_an_exact_question_id_wins_over_one_of_another_case():
    graded = grade_answers(_key(), {"v_c": 1.0, "v_C": 5.0})
    assert graded["score"] == 1 and graded["ignored"] == ["v_c"]
    graded = grade_answers(_key(), {"V_C": 5.0})
    assert graded["score"] == 1 and graded["ignored"] == []


def test_a_result_names_the_keys_student_unless_told_another():
    assert grade_answers(_key(), {})["student"] == "s07"
    assert grade_answers(_key(), {}, student="s08")["student"] == "s08"


def test_every_student_without_a_key_gets_an_entry_saying_so():
    rows = [("s1", {"v_C": 1}), ("s2", {}), ("s07", {"v_C": 5.0})]
    graded = grade_many({"s07": _key()}, rows)
    assert graded[:2] == [
        {"student": student, "score": 0.0, "max_score": None, "questions": [],
         "error": f"no key for student {student!r}"} for student in ("s1", "s2")]
    assert graded[2]["student"] == "s07" and graded[2]["score"] == 1


def test_a_keys_broken_exercise_is_told_with_the_keys_source():
    with pytest.raises(SpecError) as caught:
        key_exercise({"exercise": {"title": "x"}, "source": "variant-07.toml"})
    assert str(caught.value).startswith("variant-07.toml: ")


# -- the drawing data of the page --------------------------------------------------------------
def test_a_points_mistake_is_told_in_one_sentence():
    from planmethod.grading.plan_points import mistake_sentence

    assert mistake_sentence(["sense"]) == (
        "it lies where the construction puts it when the crank's sense of rotation was "
        "reversed (the plan is turned 180°)")


def test_a_frame_of_an_acceleration_plan_alone_with_no_radii_or_mistakes_given():
    """A key without a velocity plan still gives its acceleration plan; a point without a
    tolerance gets the default disc (0.5 mm), and a plan without mistakes' positions none."""
    from planmethod.grading.plan_points import drawing_frame

    key = {"plans": {"acceleration": {
        "pole": "π", "scale": 2.0, "unit": "(m/s²)/mm", "tolerance_mm": {},
        "points_mm": {"π": [0, 0], "b": [3.0, 4.0]}, "steps": []}}}
    assert drawing_frame(key) == {"acceleration": {
        "pole": "π", "scale": "2", "unit": "(m/s²)/mm", "points": {"b": [3.0, 4.0, 0.5]},
        "required": ["b"], "mistakes": {}}}


def test_a_reversed_sense_of_the_right_magnitude_says_the_magnitude_is_right():
    """Not 'the magnitude 2 is 0.0 % low' (found by a mutant of the high/low boundary)."""
    graded = grade_question({"id": "x", "unit": "m", "value": -2.0, "tolerance": 0.01,
                             "signed": True}, 2.005)
    assert graded["feedback"] == ("x = 2.005 m: wrong — the sense is reversed (the right answer "
                                  "is negative, -2 m ± 0.01) and the magnitude 2.005 is right")
    graded = grade_question({"id": "x", "unit": "m", "value": -2.0, "tolerance": 0.01,
                             "signed": True}, 2.02)
    assert graded["feedback"].endswith("and the magnitude 2.02 is 1.0 % high")


def test_a_quantity_without_sense_words_is_positive_or_negative():
    from planmethod.grading.answers import sense_words

    assert sense_words("not_a_quantity") == ("positive", "negative")
    assert sense_words("x") == ("positive", "negative")


@pytest.mark.parametrize("text", ["v_C,student\n5.2\n", "student,v_C\n,5.2\n"])
def test_a_csv_row_without_its_student_is_refused_at_its_line(tmp_path, text):
    path = tmp_path / "answers.csv"
    path.write_text(text)
    assert _refusal(path) == f"{path}: line 2: no student id (column 'student')"


def test_a_plans_sheet_holds_the_pole_where_every_point_lies_to_one_side():
    """The pole (0, 0) is on the sheet even when all points lie to its right and above: with
    a margin of 0.5 mm the sheet starts at −10 mm, not at 0."""
    from planmethod.grading.plan_points import plan_extent

    right = [{"velocity": {"points": {"b": [12.0, 3.0, 0.5]}}}]
    assert plan_extent(right, "velocity", margin=0.5) == (-10.0, -10.0, 20.0, 10.0)
    left = [{"velocity": {"points": {"b": [-12.0, -3.0, 0.5]}}}]
    assert plan_extent(left, "velocity", margin=0.5) == (-20.0, -10.0, 10.0, 10.0)
