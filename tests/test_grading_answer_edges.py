"""The answer grader at the edges mutation testing found unchecked: one student's JSON file,
results refused by their exact keys, the row limit, which way a wrong answer is off at 0 and
between 0 and 1, the exact match of a question id before its case-folded one, the entries
of students without a key, what a CSV's cells are and where a bad one is, a JSON file by its
content, and a plans sheet's margins."""

from __future__ import annotations

import json

import pytest

from planmethod.errors import SpecError
from planmethod.grading import answers as answers_module
from planmethod.grading.answers import grade_answers, grade_many, grade_question, read_answers
from planmethod.grading.keys import key_exercise
from planmethod.words import render


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
    (0.5, 0.4, False, "about 20 % too low", "20.0 % low"),     # no 'in magnitude' for 0.5
])
def test_which_way_a_wrong_answer_is_off_around_0_and_1(right, answer, signed, hint, off):
    graded = grade_question({"id": "x", "unit": "m", "value": right, "tolerance": 0.01,
                             "signed": signed}, answer).as_dict()
    assert graded["hint"] == f"x = {answer:g} m: wrong ({hint})"
    if off is not None:
        assert graded["feedback"].startswith(f"x = {answer:g} m: wrong — {off} (off by ")


def _key() -> dict:
    return {"student": "s07", "variant": "v07",
            "questions": [{"id": "v_C", "unit": "m/s", "value": 5.0, "tolerance": 0.1}]}


def test_an_exact_question_id_wins_over_one_of_another_case():
    graded = grade_answers(_key(), {"v_c": 1.0, "v_C": 5.0}).as_dict()
    assert graded["score"] == 1 and graded["ignored"] == ["v_c"]
    graded = grade_answers(_key(), {"V_C": 5.0}).as_dict()
    assert graded["score"] == 1 and graded["ignored"] == []


def test_a_result_names_the_keys_student_unless_told_another():
    assert grade_answers(_key(), {}).as_dict()["student"] == "s07"
    assert grade_answers(_key(), {}, student="s08").as_dict()["student"] == "s08"


def test_every_student_without_a_key_gets_an_entry_saying_so():
    rows = [("s1", {"v_C": 1}), ("s2", {}), ("s07", {"v_C": 5.0})]
    graded = [r.as_dict() for r in grade_many({"s07": _key()}, rows)]
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

    assert render(mistake_sentence(["sense"])) == (
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
        "required": ["b"], "helpers": [], "mistakes": {}, "lines": {}, "placed": {},
        "reads": [], "others": {}}}


def test_a_reversed_sense_of_the_right_magnitude_says_the_magnitude_is_right():
    """Not 'the magnitude 2 is 0.0 % low' (found by a mutant of the high/low boundary)."""
    graded = grade_question({"id": "x", "unit": "m", "value": -2.0, "tolerance": 0.01,
                             "signed": True}, 2.005).as_dict()
    assert graded["feedback"] == ("x = 2.005 m: wrong — the sense is reversed (the right answer "
                                  "is negative, -2 m ± 0.01) and the magnitude 2.005 is right")
    graded = grade_question({"id": "x", "unit": "m", "value": -2.0, "tolerance": 0.01,
                             "signed": True}, 2.02).as_dict()
    assert graded["feedback"].endswith("and the magnitude 2.02 is 1.0 % high")


def test_a_quantity_without_sense_words_is_positive_or_negative():
    from planmethod.grading.answers import sense_words

    def words(name):
        return tuple(render(word) for word in sense_words(name))

    assert words("not_a_quantity") == ("positive", "negative")
    assert words("x") == ("positive", "negative")
    # a quantity of a point (no sense of its own) has the plain words too
    assert words("v_B") == ("positive", "negative")


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


_SIGNED = {"id": "x", "unit": "m", "value": 2.0, "tolerance": 0.5, "signed": True}


@pytest.mark.parametrize("answer, told", [
    pytest.param(0, "x = 0 m: wrong — 100.0 % low (off by 2 m; right: 2 m ± 0.5 = ± 25 %)",
                 id="zero"),
    pytest.param(0.75, "x = 0.75 m: wrong — 62.5 % low (off by 1.25 m; right: 2 m ± 0.5 = "
                       "± 25 %)", id="below one"),
    pytest.param(-2.5, "x = -2.5 m: wrong — the sense is reversed (the right answer is "
                       "positive, 2 m ± 0.5) and the magnitude 2.5 is right",
                 id="reversed, magnitude off by the tolerance"),
])
def test_a_signed_answer_is_reversed_only_when_its_sign_is_the_other(answer, told):
    """0 and a value between 0 and 1 of the right sign are not a reversed sense; a reversed
    answer whose magnitude is off by exactly the tolerance has the right magnitude."""
    graded = grade_question(_SIGNED, answer).as_dict()
    assert graded["feedback"] == told


def test_a_reversed_answer_of_1_for_a_negative_value_is_a_reversed_sense():
    graded = grade_question({**_SIGNED, "value": -2.0}, 1).as_dict()
    assert graded["hint"] == "x = 1 m: wrong (the sense is reversed)"
    assert "the sense is reversed (the right answer is negative" in graded["feedback"]


def test_an_answer_that_overflows_is_quoted_to_40_characters():
    text = "1" + "0" * 400          # a number beyond a float's range: not a number
    graded = grade_question({"id": "v_C", "value": 2.0, "tolerance": 0.1}, text).as_dict()
    assert graded["hint"] == f"v_C: {text[:40]!r} is not a number"


def test_a_csv_row_with_more_cells_than_its_header_is_refused_at_its_line(tmp_path):
    path = tmp_path / "answers.csv"
    path.write_text("student,v_C\ns01,5.2\ns02,5.3,7\n")
    assert _refusal(path) == f"{path}: line 3: has 3 cells, the header 2"


def test_a_quoted_cell_holding_a_bare_carriage_return_is_refused(tmp_path):
    path = tmp_path / "answers.csv"
    path.write_bytes(b'student,v_C\ns01,"5\r2"\n')
    assert _refusal(path) == (f"{path}: line 2: a quoted cell runs on to line 2: is a "
                              "closing quote (\") missing?")


def test_a_json_object_is_read_as_json_whatever_the_files_suffix(tmp_path):
    path = tmp_path / "answers.txt"
    path.write_text(json.dumps({"s01": {"v_C": 5.2}}))
    assert read_answers(path) == [("s01", {"v_C": 5.2})]


def test_only_commas_semicolons_and_tabs_separate_cells():
    """A letter is never taken for the separator, however regular its use."""
    from planmethod.grading.answers import answers_from_csv

    assert answers_from_csv("studentXv_C\ns01X5.2\n", "a.csv") == [
        ("*", {"studentXv_C": "s01X5.2"})]


def test_a_cell_keeps_its_leading_space_where_no_separator_is_found():
    from planmethod.grading.answers import answers_from_csv

    assert answers_from_csv("v_C\n 5.2\n", "a.csv") == [("*", {"v_C": " 5.2"})]


def test_student_ids_that_differ_only_in_case_are_one_student(tmp_path):
    """Compared in lower case: the Kelvin sign K (U+212A) is a capital k."""
    path = tmp_path / "answers.csv"
    path.write_text("student,v_C\nk,5.2\n\u212a,5.3\n", encoding="utf-8")
    assert _refusal(path) == (f"{path}: student 'k' and student '\u212a' are one student, "
                              "compared ignoring case (entries 1 and 2); keep one")


def test_a_plans_sheet_has_a_15_mm_margin_rounded_out_to_10_mm():
    from planmethod.grading.plan_points import plan_extent

    # 15 + 15 = 30 mm is on a 10 mm line: not widened further
    frames = [{"velocity": {"points": {"b": [15.0, -3.0, 0.5]}}}]
    assert plan_extent(frames, "velocity") == (-20.0, -20.0, 30.0, 20.0)
    # 10.5 mm below the pole rounds out to 20 mm
    frames = [{"velocity": {"points": {"b": [3.0, -10.0, 0.5]}}}]
    assert plan_extent(frames, "velocity", margin=0.5) == (-10.0, -20.0, 10.0, 10.0)
