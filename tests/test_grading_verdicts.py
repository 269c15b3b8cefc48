"""The grader's rulebook as data: typed results that write the JSON ``grade --json`` writes,
every verdict class with its template, and a drawn point's sentence made of fields a page
can be given (the wrong link's line among them)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from planmethod.grading.answers import classify, grade_many, grade_question, read_answers
from planmethod.grading.drawings import Drawing, grade_drawing
from planmethod.grading.keys import build_key, key_questions, load_keys
from planmethod.grading.plan_points import point_lines
from planmethod.grading.results import KeyQuestion
from planmethod.grading.templates import draw_variant, load_template
from planmethod.grading.verdicts import (
    FEEDBACK,
    HINTS,
    POINT_PARTS,
    POINTS,
    AnswerVerdict,
    PointPart,
    PointVerdict,
    rulebook,
)
from planmethod.render.plan_words import label_text
from planmethod.words import render

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def lever() -> dict:
    return build_key(draw_variant(load_template(ROOT / "exercises" / "slotted_lever.toml")))


def test_a_keys_questions_read_typed_write_back_the_same_tables(lever):
    assert [question.as_dict() for question in key_questions(lever)] == lever["questions"]
    assert all(isinstance(question, KeyQuestion) and question.mistakes
               for question in key_questions(lever))


def test_grade_json_writes_the_typed_results_as_dicts(tmp_path):
    """What ``grade --json`` writes is each typed grade's as_dict(), in order."""
    subprocess.run([sys.executable, "-m", "planmethod", "variants",
                    "exercises/templates/slider_crank.toml", "--count", "6", "--seed", "2026",
                    "--no-sheets", "--out", str(tmp_path / "course")], cwd=ROOT, check=True,
                   capture_output=True)
    answers = ROOT / "exercises" / "templates" / "slider_crank_answers_example.csv"
    subprocess.run([sys.executable, "-m", "planmethod", "grade",
                    str(tmp_path / "course" / "keys.json"), str(answers), "--json",
                    str(tmp_path / "graded.json"), "--quiet"], cwd=ROOT, check=True,
                   capture_output=True)
    written = json.loads((tmp_path / "graded.json").read_text(encoding="utf-8"))
    graded = grade_many(load_keys(tmp_path / "course" / "keys.json"), read_answers(answers))
    assert written == {"answers": [grade.as_dict() for grade in graded], "drawings": []}
    assert sum(not question.correct for grade in graded for question in grade.questions) == 6


def test_every_verdict_class_has_its_sentences():
    assert set(FEEDBACK) == set(HINTS) == set(AnswerVerdict)
    assert set(POINTS) == set(PointVerdict) and set(POINT_PARTS) == set(PointPart)
    table = rulebook()
    assert set(table["answers"]) == {str(kind) for kind in AnswerVerdict}
    assert table["answers"]["mistake"] == {
        "template": "{answer}: wrong, {off} — it looks as if {mistake} (that gives "
                    "{gives:.6g}; right: {right})",
        "fields": ["answer", "gives", "mistake", "off", "right"]}


_QUESTION = {"id": "omega_BC", "symbol": "ω₂", "unit": "rad/s", "value": -2.0,
             "tolerance": 0.1, "signed": True,
             "mistakes": [{"kind": "sense", "value": 2.0, "tolerance": 0.01, "feedback": "S"},
                          {"kind": "scale_ten", "value": -20.0, "tolerance": 1.0,
                           "feedback": "T"}]}


@pytest.mark.parametrize(("question", "answer", "kind"), [
    (_QUESTION, -2.05, AnswerVerdict.CORRECT), (_QUESTION, 2.0, AnswerVerdict.SENSE_MISTAKE),
    (_QUESTION, -20.0, AnswerVerdict.MISTAKE),
    (_QUESTION, 20.0, AnswerVerdict.MISTAKE_AND_SENSE),
    (_QUESTION, 2.05, AnswerVerdict.SENSE_REVERSED),
    (_QUESTION, 3.0, AnswerVerdict.SENSE_AND_SIZE), (_QUESTION, -3.0, AnswerVerdict.WRONG),
    ({"id": "v_C", "value": 5.0, "tolerance": 0.1}, -5.0, AnswerVerdict.NEGATIVE_MAGNITUDE),
    ({"id": "v_C", "value": 0.0, "tolerance": 0.1}, 0.3, AnswerVerdict.WRONG_OF_ZERO)])
def test_an_answer_is_classified_first_and_its_sentences_are_its_classs_templates(
        question, answer, kind):
    """The verdict carries every field its class's two templates name; the graded answer's
    sentences are those templates filled with them."""
    question = KeyQuestion.read(question)
    verdict, _, _ = classify(question, answer)
    assert verdict.kind is kind
    table = rulebook()
    names = {*table["answers"][kind]["fields"], *table["hints"][kind]["fields"]}
    assert names <= dict(verdict.fields).keys()
    graded = grade_question(question, answer)
    assert graded.feedback == FEEDBACK[kind].replace(**dict(verdict.fields))
    assert render(graded.hint) == render(HINTS[kind].replace(**dict(verdict.fields)))


@pytest.mark.parametrize(("raw", "kind"), [(None, AnswerVerdict.NO_ANSWER),
                                           ("five", AnswerVerdict.NOT_A_NUMBER)])
def test_no_number_is_a_verdict_of_its_own(raw, kind):
    graded = grade_question(_QUESTION, raw)
    assert graded.verdict.kind is kind and graded.answer is None and not graded.correct
    assert set(rulebook()["answers"][kind]["fields"]) <= dict(graded.verdict.fields).keys()


def test_the_wrong_links_sentence_is_made_of_the_lines_fields(lever):
    """b₃ placed at b lies on the line of the relative velocity along the guide: the sentence
    ``grade --drawing`` says is the template filled with the fields a page has — the lines
    of b₃'s intersection (point_lines), the point they pass through, how far off along."""
    entry = lever["plans"]["velocity"]
    points = {label: tuple(xy) for label, xy in entry["points_mm"].items()}
    points["b@lever"] = points["b"]
    result = grade_drawing(lever, Drawing(points, "velocity"))
    told = render(next(p for p in result.points if p.point == "b@lever").feedback)
    line = next(line for line in point_lines(entry)["b@lever"] if line.through == "b")
    along = float(np.hypot(*(np.asarray(entry["points_mm"]["b"])
                             - np.asarray(entry["points_mm"]["b@lever"]))))
    sentence = render(POINT_PARTS[PointPart.ON_THE_LINE].replace(
        line=line.name, through=label_text(line.through, lever["numbers"]), along=along))
    assert sentence == ("it lies on the line v_B₃B along the guide of pair 2–3 through b but "
                        "28.8 mm off along it")
    assert told.startswith(f"b₃ is 28.8 mm off: {sentence}; it is ")
