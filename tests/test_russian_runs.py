"""A Russian course from end to end: every command run in Russian on the shipped exercises and
on a Russian template's class shows no English word of the messages and no unit in English.

Run in Russian (``--lang ru``, or the course's language a key records): ``solve`` of every
shipped exercise with its figures and its ``--json`` report's sentences, ``check`` of the
conveyor's table, ``variants`` of ``exercises/templates/ru/slider_crank.toml`` (task sheets,
blank plan sheets, the keys' sentences), ``grade`` of answers and of a drawn plan, ``export``
to Moodle, PrairieLearn, Gradescope and a CSV gradebook, ``workbook`` and ``booklet``. The
words looked for are those of :func:`planmethod.testing.pseudo.message_words`; a unit is
looked for by its English writing (``m/s``, ``rad``, ``N·m``, a number followed by ``m``).

What is not a word of the messages is left out, each by name: the names an exercise's author
gave (title, links, points, the published source), the names of files and folders, the answer
columns' names (``omega_BC``), Roman numerals that label a drawing's details, what is quoted
as a command (```planmethod grade```), keys of a keyboard and the products a course exports
to. The same runs in English show those words (the last tests), so the check can fail.
"""

from __future__ import annotations

import html
import io
import json
import re
import xml.etree.ElementTree as ElementTree
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the catalogues are read with Babel (test extra)")

from planmethod.cli import main
from planmethod.spec import load_exercise
from planmethod.testing.pseudo import message_words, texts_of_html, texts_of_svg, unmarked_words
from planmethod.words import language

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))
TEMPLATE = ROOT / "exercises" / "templates" / "ru" / "slider_crank.toml"
ANSWERS = ROOT / "exercises" / "templates" / "slider_crank_answers_example.csv"
TABLE = ROOT / "exercises" / "conveyor_sixbar_table2.csv"
#: a symbol written with its underscore (``v_C``) where a page could set its subscript
UNDERSCORED = re.compile(r"_[^\W\d_]")
#: a unit written in English: alone, or after a number
LATIN_UNIT = re.compile(r"m/s²?|m/mm|\brad\b|N·m|kg·m²|N/mm|\d[ \u00a0\u202f](?:mm|m|N|kg|W)"
                        r"(?![\w/·²])")
#: what is not a word in a run's text: a file's or folder's name, a command quoted, a Roman
#: numeral labelling a detail, an identifier (an answer column, a JSON name), a template's
#: field (``{omega:g}`` in a template's description a key keeps, ``{point}`` in the sentences
#: PrairieLearn's server fills)
NOT_WORDS = re.compile(r"(?:/[^\s\"'<>]*)?[\w.+-]+\."
                       r"(?:svg|toml|csv|json|html|pdf|xml|txt|png|sh|zip)\b|`[^`\n]*`|"
                       r"\b[IVX]+\b|\b\w+_\w+\b|/tmp/\S+|\S*/pytest-\S+|\{[\w.]+(?::[^{}]*)?\}")
#: keys of a keyboard, products and tools a course's texts name
PRODUCTS = ("planmethod", "Gradescope", "PrairieLearn", "Moodle", "Python", "Alt", "Shift",
            "Delete", "Enter", "Ctrl", "wheel", "zip", "run_autograder", "src")
#: a JSON string meant for programs: a name, a key, an enum value
MACHINE_WORD = re.compile(r"[A-Za-z_(][\w@/*.+,()²·\[\]-]*(?: at [A-Za-z]\w*)?|velocity plan|"
                          r"exact velocities")


def _run(*argv, codes=(0,)) -> str:
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main([str(argument) for argument in argv])
    assert code in codes, err.getvalue()
    return out.getvalue() + err.getvalue()


def exercise_names(path: Path) -> list[str]:
    """What the author of an exercise or template named: its title, source, links, points."""
    exercise = load_exercise(path)
    mechanism = exercise.mechanism
    links = [name for link in mechanism.links for name in (link, link.replace("_", " "))]
    return [mechanism.title, exercise.published_source or "", *links,
            *(point for link in mechanism.links.values() for point in link.points)]


def english(text: str, names: list[str]) -> list[str]:
    """The English words of the messages and the English units ``text`` shows, the names
    and what is no word (:data:`NOT_WORDS`) left out."""
    shown = NOT_WORDS.sub(" ", text)
    for name in sorted([*names, *PRODUCTS], key=len, reverse=True):
        if name:
            shown = shown.replace(name, " ")
    return unmarked_words(shown, message_words()) + LATIN_UNIT.findall(shown)


def _sentences(report) -> list[str]:
    """The human-readable strings of a JSON document (its names and keys left out)."""
    if isinstance(report, dict):
        return [text for value in report.values() for text in _sentences(value)]
    if isinstance(report, list):
        return [text for value in report for text in _sentences(value)]
    return ([report] if isinstance(report, str) and not MACHINE_WORD.fullmatch(report)
            else [])


def _svg_texts(folder: Path) -> str:
    return "\n".join(text for path in sorted(folder.rglob("*.svg"))
                     for text in texts_of_svg(path.read_text(encoding="utf-8")))


@pytest.mark.parametrize("path", EXERCISES, ids=[path.stem for path in EXERCISES])
def test_every_shipped_exercise_solves_in_russian(path, tmp_path):
    """The printed report, every figure, and the JSON report's sentences."""
    names = exercise_names(path)
    shown = _run("solve", path, "--lang", "ru", "--svg", tmp_path)
    assert "Структурный анализ" in shown
    assert english(shown, names) == [], shown
    figures = _svg_texts(tmp_path)
    assert "план" in figures
    assert english(figures, names) == [], figures
    report = json.loads(_run("solve", path, "--lang", "ru", "--json"))
    assert english("\n".join(_sentences(report)), names) == []


def test_check_speaks_russian():
    names = exercise_names(ROOT / "exercises" / "conveyor_sixbar.toml")
    shown = _run("check", ROOT / "exercises" / "conveyor_sixbar.toml", TABLE, "--lang", "ru",
                 codes=(0, 1))
    assert "точки в сравнении с точной сборкой (группа 1: по эскизу)" in shown
    assert english(shown, names) == [], shown


@pytest.fixture(scope="module")
def course(tmp_path_factory) -> Path:
    """Two students' variants of the Russian template (its ``[course] language``)."""
    folder = tmp_path_factory.mktemp("class") / "course"
    _run("variants", TEMPLATE, "--count", 2, "--seed", 2026, "--out", folder)
    return folder


@pytest.fixture(scope="module")
def course_names() -> list[str]:
    from planmethod.grading.templates import draw_variant, load_template

    variant = draw_variant(load_template(TEMPLATE))
    mechanism = variant.exercise.mechanism
    return [mechanism.title, *mechanism.links,
            *(point for link in mechanism.links.values() for point in link.points)]


def test_a_russian_class_sheets_and_keys(course, course_names):
    """The task sheets (text and figure), the blank plan sheets and the keys' sentences
    (questions, task, mistakes' feedback, construction steps)."""
    task = (course / "001" / "task.txt").read_text(encoding="utf-8")
    assert "Звенья: 0 стойка, 1 AB, 2 BC, 3 slider." in task
    assert re.search(r"ω₂, рад/с +угловая скорость ω₂ звена 2 \(BC\) +\[omega_BC\]", task)
    assert english(task, course_names) == [], task
    sheets = _svg_texts(course)
    assert "стойка" in sheets and "бланк плана скоростей" in sheets
    assert english(sheets, course_names) == [], sheets
    keys = json.loads((course / "keys.json").read_text(encoding="utf-8"))
    assert english("\n".join(_sentences(keys)), course_names) == []


def _drawing(course: Path, folder: Path) -> Path:
    """Student 001's velocity plan with point c moved 4 mm off its place."""
    key = json.loads((course / "001" / "key.json").read_text(encoding="utf-8"))
    points = {name: list(xy) for name, xy in key["plans"]["velocity"]["points_mm"].items()}
    points["c"] = [points["c"][0] + 4.0, points["c"][1]]
    path = folder / "velocity.json"
    path.write_text(json.dumps({"plan": "velocity", "points": points}), encoding="utf-8")
    return path


def test_grade_speaks_the_keys_russian(course, course_names, tmp_path):
    """No ``--lang``: the keys' course language; answers and a drawn plan graded."""
    shown = _run("grade", course / "keys.json", ANSWERS, "--json", tmp_path / "grades.json",
                 "--csv", tmp_path / "grades.csv")
    assert "неверно" in shown and "м/с" in shown
    assert english(shown, course_names) == [], shown
    graded = json.loads((tmp_path / "grades.json").read_text(encoding="utf-8"))
    assert english("\n".join(_sentences(graded)), course_names) == []
    drawn = _run("grade", course / "keys.json", "--drawing", _drawing(course, tmp_path),
                 "--student", "001")
    assert english(drawn, course_names) == [], drawn


def test_the_exports_speak_the_keys_russian(course, course_names, tmp_path):
    """Moodle's questions, PrairieLearn's question page and sentences, Gradescope's README
    and a CSV gradebook, each without ``--lang``."""
    _run("export", course / "keys.json", "--format", "moodle", "--out", tmp_path / "quiz.xml")
    quiz = ElementTree.parse(tmp_path / "quiz.xml").getroot()
    shown = "\n".join(text for question in quiz.iter("question")
                      for text in texts_of_html(question.findtext("questiontext/text") or ""))
    assert "рад/с" in shown
    assert english(shown, course_names) == [], shown
    assert UNDERSCORED.search(shown) is None, shown      # v_C set as v with C below
    _run("export", course / "keys.json", "--format", "prairielearn", "--out", tmp_path / "pl")
    page = next((tmp_path / "pl").rglob("question.html")).read_text(encoding="utf-8")
    page = re.sub(r"\{\{\{?[^{}]*\}?\}\}", " ", page)         # its {{params…}} fields
    shown = (texts_of_html(page) + re.findall(r'suffix="([^"]*)"', page)
             + [run for label in re.findall(r'label="([^"]*)"', page)   # HTML, as it is
                for run in texts_of_html(html.unescape(label))])
    assert UNDERSCORED.search("\n".join(shown)) is None, shown
    server = next((tmp_path / "pl").rglob("server.py")).read_text(encoding="utf-8")
    shown += json.loads(re.search(r"\nTEXTS = (\{.*?\n\})", server, re.S).group(1)).values()
    text = "\n".join(shown)
    assert english(text, course_names) == [], text
    _run("export", course / "keys.json", "--format", "gradescope", "--out", tmp_path / "gs")
    readme = (tmp_path / "gs" / "README.txt").read_text(encoding="utf-8")
    assert english(readme, course_names) == [], readme
    _run("grade", course / "keys.json", ANSWERS, "--json", tmp_path / "grades.json")
    _run("export", course / "keys.json", "--format", "csv", "--answers", ANSWERS, "--out",
         tmp_path / "gradebook.csv")
    assert (tmp_path / "gradebook.csv").exists()


def test_a_russian_workbook_and_booklet(course, course_names, tmp_path):
    path = ROOT / "exercises" / "compressor_slider_crank.toml"
    names = exercise_names(path)
    shown = _run("workbook", path, "--lang", "ru", "--step", 60, "-o", tmp_path / "wb.html")
    page = "\n".join(texts_of_html((tmp_path / "wb.html").read_text(encoding="utf-8")))
    assert "рад/с" in page and "м/с²" in page
    assert english(shown + page, names) == [], page
    pytest.importorskip("segno", reason="the booklet needs the paper extra")
    shown = _run("booklet", course, "-o", tmp_path / "class.pdf")
    assert "Записан" in shown and english(shown, course_names) == [], shown


def test_the_same_class_in_english_shows_the_words(course, course_names, tmp_path):
    """``--lang en`` wins over the keys' language, and its words are found: the checks
    above could fail."""
    shown = _run("grade", course / "keys.json", ANSWERS, "--lang", "en")
    found = {word.lower() for word in english(shown, course_names)}
    assert {"wrong", "right", "high"} <= found and "m/s" in found
    task = _run("solve", ROOT / "exercises" / "conveyor_sixbar.toml", "--lang", "en")
    assert {"sketch", "triad", "rad"} <= {word.lower() for word in english(
        task, exercise_names(ROOT / "exercises" / "conveyor_sixbar.toml"))}


def test_grade_and_export_take_the_keys_language(course, tmp_path, monkeypatch):
    """A keys.json (or its folder) chooses the template's language over ``PLANMETHOD_LANG``;
    ``--lang`` chooses over both; an English class's keys stay English."""
    monkeypatch.setenv(language.ENVIRONMENT, "en")
    assert "неверно" in _run("grade", course, ANSWERS)
    assert "неверно" not in _run("grade", course / "keys.json", ANSWERS, "--lang", "en")
    _run("export", course, "--format", "moodle", "--out", tmp_path / "ru.xml")
    _run("export", course, "--format", "moodle", "--out", tmp_path / "en.xml", "--lang", "en")
    assert "Дайте ответ" in (tmp_path / "ru.xml").read_text(encoding="utf-8")
    assert "Give in SI units" in (tmp_path / "en.xml").read_text(encoding="utf-8")
    english_class = tmp_path / "english"
    _run("variants", ROOT / "exercises" / "templates" / "slider_crank.toml", "--count", 1,
         "--out", english_class, "--no-sheets")
    monkeypatch.setenv(language.ENVIRONMENT, "ru")
    assert "неверно" in _run("grade", english_class / "keys.json", ANSWERS)   # no [course]


def _force_steps(report: str) -> list[str]:
    """The force analysis's step sentences of a printed report: the lines under a group's or
    the drive's heading (``  группа RRP — звенья 2, 3 (BC, piston):``)."""
    steps, inside = [], False
    for line in report.splitlines():
        if line.startswith("  ") and not line.startswith("   ") and line.endswith(":"):
            inside = True
        elif inside and line.startswith("    "):
            steps.append(line.strip())
        else:
            inside = False
    return steps


def _word_names(path: Path) -> list[str]:
    """An exercise's link names that are words (``piston``, ``rocker_EF``), not a segment of
    its points (``BC``, which a step names as the segment BC)."""
    mechanism = load_exercise(path).mechanism
    points = {point for link in mechanism.links.values() for point in link.points}
    return [name for link in mechanism.links for name in (link, link.replace("_", " "))
            if not re.fullmatch(f"(?:{'|'.join(map(re.escape, points))})+", link)]


@pytest.mark.parametrize("name", ["combined_force_slider_crank", "conveyor_sixbar"])
def test_the_force_steps_name_links_and_pairs_by_number(name):
    """A step names a link by its course number and a prismatic pair by its links' numbers
    (the guide of pair 3–0), never by the exercise's names, in Russian and in English."""
    path = ROOT / "exercises" / f"{name}.toml"
    names = _word_names(path)
    russian = _force_steps(_run("solve", path, "--lang", "ru"))
    english_steps = _force_steps(_run("solve", path, "--lang", "en"))
    assert len(russian) == len(english_steps) >= 5
    for steps in (russian, english_steps):
        shown = "\n".join(steps)
        assert [name for name in names if re.search(rf"\b{re.escape(name)}\b", shown)] == []
    if name == "combined_force_slider_crank":
        assert "N ⟂ направляющей пары 3–0" in "\n".join(russian)
        assert "N ⟂ the guide of pair 3–0" in "\n".join(english_steps)
        assert "R₀₁ from the force polygon of link 1" in english_steps
