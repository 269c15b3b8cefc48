"""What the workbook page showed before a drawing was downloaded: the drawing's ``revealed``
list is read defensively and ``planmethod grade --drawing`` reports it, in its text (a note in
course words) and in its JSON (``revealed``)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from commands import cli

from planmethod.grading.drawings import (
    DRAWING_FORMAT,
    SubmissionError,
    exercise_digest,
    parse_drawing_json,
)
from planmethod.spec import load_exercise

ROOT = Path(__file__).resolve().parent.parent
SLOTTED = ROOT / "exercises" / "slotted_lever.toml"


@pytest.fixture(scope="module")
def page_drawing() -> dict:
    """The right velocity plan of the slotted lever at its own angle, as the page saves it."""
    report = json.loads(cli("solve", SLOTTED, "--json").stdout)
    return {"format": DRAWING_FORMAT, "version": 1, "title": report["title"],
            "exercise": exercise_digest(load_exercise(SLOTTED)), "angle": 30,
            "plan": "velocity", "points": {"p": [0, 0], **report["plans"]["velocity"]
                                           ["points_mm"]}, "lines": []}


def test_grade_reports_what_the_page_showed(page_drawing, tmp_path):
    path = tmp_path / "drawn.json"
    path.write_text(json.dumps(dict(page_drawing, revealed=[
        "omega_lever", "v_B@lever", "construction:velocity", "plan:velocity"])))
    done = cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
    graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
    assert graded["revealed"] == ["omega_lever", "v_B@lever", "construction:velocity",
                                  "plan:velocity"]
    assert graded["score"] == graded["max_score"]       # the grade itself is unchanged
    notes = ["the page showed the construction of the velocity plan before the drawing was "
             "downloaded", "the page showed the right velocity plan before the drawing was "
             "downloaded", "the page showed the right values of these before the drawing was "
             "downloaded: ω₃, v_B₃"]
    assert graded["feedback"][-3:] == notes
    for note in notes:
        assert f"  !  {note}\n" in done.stdout
    assert "omega_lever" not in done.stdout and "@" not in done.stdout


def test_a_drawing_that_shows_nothing_revealed_says_nothing(page_drawing, tmp_path):
    path = tmp_path / "drawn.json"
    path.write_text(json.dumps(page_drawing))
    done = cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
    graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
    assert graded["revealed"] == [] and "showed" not in done.stdout


@pytest.mark.parametrize("revealed", ["v_C", [1], [""], ["x" * 201], ["v_C"] * 1001, None])
def test_a_revealed_list_that_is_no_list_of_names_is_refused_in_one_line(page_drawing,
                                                                         revealed):
    with pytest.raises(SubmissionError) as caught:
        parse_drawing_json(json.dumps(dict(page_drawing, revealed=revealed)), source="d.json")
    text = str(caught.value)
    assert text.startswith("d.json: revealed: must be a list of what the page showed")
    assert "\n" not in text and len(text) < 300


def test_the_same_name_twice_is_kept_once(page_drawing):
    drawing = parse_drawing_json(json.dumps(dict(page_drawing, revealed=["v_C", "v_C"])))
    assert drawing.revealed == ("v_C",)
