"""Grading speaks only through the catalogue: under the pseudo-language ``qps`` (every
template marked ⟦…⟧) no English word of the messages shows outside a mark in what grading
makes — ``planmethod grade``'s feedback on the example answers and on drawn plans, a variant's
task sheet and blank plan sheet, and the LMS exports' visible texts.

What other areas still make is left out, exactly: the words a course's author wrote (the
template's task description, the exercise's title), a key question's text (made by
vocabulary's ``question_text``) and a unit standing alone (vocabulary's units: a Moodle
question's unit column), the line ``FILE (velocity plan): score`` that ``grade`` prints
itself (commands/grade.py), and PrairieLearn's mustache placeholders (machine names)."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
from html import unescape
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod.grading.exports import gradescope_autograder, moodle_xml, prairielearn_questions
from planmethod.grading.keys import build_key, bundle, load_keys
from planmethod.grading.templates import draw_variant, load_template
from planmethod.render.canvas import formula_runs
from planmethod.testing.pseudo import (
    PSEUDO,
    message_words,
    pseudo_catalogue,
    texts_of_html,
    texts_of_svg,
    unmarked_words,
)
from planmethod.words import language, speaking

ROOT = Path(__file__).resolve().parent.parent
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"
ANSWERS = ROOT / "exercises" / "templates" / "slider_crank_answers_example.csv"
LEVER = ROOT / "exercises" / "slotted_lever.toml"
#: the plan ``grade`` names in the line it prints itself for a drawing (commands/grade.py)
PLAN_LINE = re.compile(r"\((?:velocity|acceleration) plan\)")
#: PrairieLearn's mustache placeholders (``{{params.task_html}}``): machine names
MUSTACHE = re.compile(r"\{\{\{?[^{}]*\}?\}\}")


@pytest.fixture(scope="module")
def pseudo(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    return folder


@pytest.fixture(scope="module")
def environment(pseudo) -> dict[str, str]:
    return {**os.environ, language.LOCALE_ENVIRONMENT: str(pseudo),
            language.ENVIRONMENT: PSEUDO, "PYTHONPATH": str(ROOT)}


@pytest.fixture(scope="module")
def words() -> set[str]:
    return message_words()


def _run(environment, *argv) -> str:
    done = subprocess.run([sys.executable, "-m", "planmethod", *map(str, argv)], cwd=ROOT,
                          env=environment, capture_output=True, text=True, check=True)
    return done.stdout


@pytest.fixture(scope="module")
def course(environment, tmp_path_factory) -> Path:
    """The example answers' variants (the first six of the quick start's), drawn in ``qps``."""
    folder = tmp_path_factory.mktemp("course")
    _run(environment, "variants", TEMPLATE, "--count", 6, "--seed", 2026, "--out", folder)
    return folder


@pytest.fixture()
def speaking_pseudo(pseudo, monkeypatch):
    """``qps`` spoken here (its catalogue found through the environment, read afresh)."""
    monkeypatch.setenv(language.LOCALE_ENVIRONMENT, str(pseudo))
    language.catalogue.cache_clear()
    try:
        with speaking(PSEUDO):
            yield
    finally:
        language.catalogue.cache_clear()


def _plain(text: str) -> str:
    """Whitespace as one space (wrapped lines joined)."""
    return " ".join(text.split())


@pytest.mark.parametrize("level", ["full", "hints"])
def test_grading_the_example_answers_prints_only_marked_sentences(environment, course, words,
                                                                  level):
    printed = _run(environment, "grade", course / "keys.json", ANSWERS, "--feedback", level)
    assert printed.count("⟦") >= 42, printed          # every answer's sentence, marked
    assert unmarked_words(printed, words) == [], printed


def test_a_drawn_plan_is_told_in_marked_sentences(environment, words, tmp_path):
    """The slotted lever's b₃ placed at b (the wrong link: on the line v_B₃B along the guide),
    an image off by the similarity rule, an acceleration plan drawn 10 % too large (graded
    after scaling), a point off its lines and the readings it makes wrong."""
    key = build_key(draw_variant(load_template(LEVER)))
    velocity = {k: list(xy) for k, xy in key["plans"]["velocity"]["points_mm"].items()}
    velocity["b@lever"] = velocity["b"]
    velocity["c"] = [velocity["c"][0] + 4.0, velocity["c"][1]]
    acceleration = {k: [1.1 * v for v in xy]
                    for k, xy in key["plans"]["acceleration"]["points_mm"].items()}
    acceleration["b@lever"] = [acceleration["b@lever"][0] + 6.0, acceleration["b@lever"][1]]
    files = []
    for plan, points in (("velocity", velocity), ("acceleration", acceleration)):
        files.append(tmp_path / f"{plan}.json")
        files[-1].write_text(json.dumps({"plan": plan, "points": points}), encoding="utf-8")
    printed = _run(environment, "grade", LEVER, *(arg for path in files
                                                   for arg in ("--drawing", path)))
    # the line's name is a message of its own, kept by the key apart from its step's sentence
    assert "⟦it lies on the line ⟦v_B₃B along the guide of pair 2–3⟧ through b but" in printed
    assert "⟦the drawing's scale is off:" in printed and "read 44 % high⟧" in printed
    shown = PLAN_LINE.sub(" ", printed)
    assert unmarked_words(shown, words, names=[str(path) for path in files]) == [], printed


def test_a_task_sheet_and_a_blank_plan_sheet_are_marked(course, words):
    """The figure (the position plan: its title, scale, drive and bar), the task text under
    it and the blank sheet's header and title; the author's task description aside."""
    key = load_keys(course / "keys.json")["001"]
    sheet = texts_of_svg((course / "001" / "task.svg").read_text(encoding="utf-8"))
    text = _plain(" ".join(sheet))
    assert "⟦μl = " in text and " rad/s, ⟦drive link 1 (AB)⟧⟧" in text   # the figure's
    assert "⟦Answer (SI units" in text and "⟦Given: ⟦" in text
    # the author's description as the sheet sets it (its symbols' subscripts runs of their own)
    shown = " ".join(part for part, _ in formula_runs(key["task"]))
    text = text.replace(_plain(shown), " ")
    assert unmarked_words(text, words, names=[key["title"]]) == [], text
    for plan in ("velocity", "acceleration"):
        blank = texts_of_svg((course / "001" / f"{plan}_sheet.svg").read_text(encoding="utf-8"))
        text = _plain(" ".join(blank))
        assert f"⟦{key['title']} — blank {plan} plan sheet⟧" in text
        assert unmarked_words(text, words, names=[key["title"]]) == [], text


def _key_texts(keys) -> list[str]:
    """What the keys hold that others make: the questions' texts and units (vocabulary), the
    author's task and title — the texts also as a page shows them, their subscripts set
    apart (``|v_C|`` → ``|v C |``)."""
    texts = ([question[field] for key in keys for question in key["questions"]
              for field in ("text", "unit")]
             + [key["title"] for key in keys] + [_plain(key["task"]) for key in keys])
    return texts + [_plain(" ".join(part for part, _ in formula_runs(text))) for text in texts]


def test_the_lms_exports_visible_texts_are_marked(course, words, speaking_pseudo):
    """Moodle's question texts (the cloze fields' feedback too), PrairieLearn's question.html
    (its labels too) and server.py's sentences, and Gradescope's README."""
    keys = list(load_keys(course / "keys.json").values())
    names = _key_texts(keys)
    sheets = {key["student"]: (course / key["student"] / "task.svg").read_text("utf-8")
              for key in keys}
    quiz = ElementTree.fromstring(moodle_xml(keys, sheets=sheets).encode("utf-8"))
    questions = [question.findtext("questiontext/text")
                 for question in quiz.iter("question") if question.get("type") == "cloze"]
    assert len(questions) == len(keys)
    for html in questions:
        text = _plain(" ".join(texts_of_html(html)))
        assert "⟦It looks as if ⟦" in text and "⟦Right: within" in text
        assert unmarked_words(text, words, names=names) == [], text
    files = prairielearn_questions(bundle(keys, seed=2026), slug="q")
    page = files["q/question.html"]
    shown = texts_of_html(page) + [run for label in re.findall(r'label="([^"]*)"', page)
                                   for run in texts_of_html(unescape(label))]   # HTML
    text = _plain(MUSTACHE.sub(" ", " ".join(shown)))
    assert "⟦Draw the velocity plan" in text and "⟦Plan points:⟧" in text
    assert unmarked_words(text, words, names=names) == [], text
    server = re.search(r"\nTEXTS = (\{.*?\n\})", files["q/server.py"], re.S).group(1)
    assert all(sentence.startswith("⟦") for sentence in json.loads(server).values())
    readme = gradescope_autograder(bundle(keys))["README.txt"]
    assert unmarked_words(readme, words) == [], readme
