"""What the workbook page showed before the answers were downloaded: an answers file from the
page names its exercise, its angle and the answers revealed; ``planmethod grade`` grades it at
that angle and reports the answers revealed, in its text (a note in course words) and in its
JSON (``revealed``); a malformed envelope is refused in one line (exit 2), and older answers
files read as before."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from commands import cli

from planmethod.errors import SpecError
from planmethod.grading.answers import ANSWERS_FORMAT, read_answers
from planmethod.grading.drawings import exercise_digest
from planmethod.grading.page_answers import page_answers, read_page_answers
from planmethod.spec import load_exercise

ROOT = Path(__file__).resolve().parent.parent
SLOTTED = ROOT / "exercises" / "slotted_lever.toml"


@pytest.fixture(scope="module")
def right() -> dict:
    """The slotted lever's right values at 45° (not its own angle, 30°)."""
    report = json.loads(cli("solve", SLOTTED, "--angle", 45, "--json").stdout)
    return {check["quantity"]: check["analytic"] for check in report["checks"]}


@pytest.fixture()
def envelope() -> dict:
    exercise = load_exercise(SLOTTED)
    return {"format": ANSWERS_FORMAT, "version": 1, "title": exercise.mechanism.title,
            "exercise": exercise_digest(exercise), "angle": 45,
            "answers": {}, "revealed": ["v_B@lever"]}


def test_grade_reports_the_answers_the_page_showed(envelope, right, tmp_path):
    path = tmp_path / "answers.json"
    path.write_text(json.dumps(dict(envelope, answers={"omega_lever": right["omega_lever"]})))
    done = cli("grade", SLOTTED, path, "--json", tmp_path / "graded.json")
    graded = json.loads((tmp_path / "graded.json").read_text())["answers"][0]
    assert graded["revealed"] == ["v_B@lever"]
    # graded at the file's angle: the right value at 45° is right
    assert next(q for q in graded["questions"] if q["id"] == "omega_lever")["correct"]
    assert "  !  the page showed the right values of these before the answers were " \
           "downloaded: v_B₃\n" in done.stdout
    assert "@" not in done.stdout


def test_an_older_answers_file_says_nothing_revealed(right, tmp_path):
    path = tmp_path / "answers.json"
    path.write_text(json.dumps({"omega_lever": right["omega_lever"]}))
    done = cli("grade", SLOTTED, path, "--json", tmp_path / "graded.json")
    graded = json.loads((tmp_path / "graded.json").read_text())["answers"][0]
    assert "revealed" not in graded and "showed" not in done.stdout
    assert read_page_answers(path) is None


def test_the_envelope_is_read(envelope, tmp_path):
    path = tmp_path / "answers.json"
    path.write_text(json.dumps(dict(envelope, answers={"v_C": "1,5"},
                                    revealed=["v_C", "v_C", "a_C"])))
    assert read_answers(path) == [("*", {"v_C": "1,5"})]
    page = read_page_answers(path)
    assert (page.angle, page.revealed) == (45.0, ("v_C", "a_C"))


@pytest.mark.parametrize("field, value, says", [
    ("revealed", "v_C", "revealed: must be a list of what the page showed"),
    ("revealed", [1], "revealed: must be a list of what the page showed"),
    ("revealed", ["v_C"] * 1001, "revealed: must be a list of what the page showed"),
    ("angle", "45", "angle: must be the crank angle in degrees"),
    ("title", None, "title: must be the exercise's title"),
    ("exercise", "zz", "exercise: must be the exercise's digest"),
])
def test_a_malformed_envelope_is_refused_in_one_line(envelope, field, value, says):
    with pytest.raises(SpecError) as caught:
        page_answers(dict(envelope, **{field: value}), source="a.json")
    text = str(caught.value)
    assert text.startswith(f"a.json: {says}") and "\n" not in text and len(text) < 300


@pytest.mark.parametrize("change, says", [
    ({"revealed": {"45": ["v_C"]}}, "revealed: must be a list of what the page showed"),
    ({"answers": ["v_C"]}, "answers: must be an object of answers"),
    ({"title": "Another mechanism"}, "the answers are of 'Another mechanism'"),
    ({"exercise": "0" * 16}, "the answers were given on the page of another version"),
])
def test_grade_refuses_a_bad_file_in_one_line_with_exit_2(envelope, tmp_path, change, says):
    path = tmp_path / "answers.json"
    path.write_text(json.dumps(envelope | change))
    done = cli("grade", SLOTTED, path, check=False)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and says in done.stderr
