"""The Russian course pack: a complete catalogue, and a Russian run that shows no English
word of the messages.

The catalogue (``planmethod/locale/ru``) translates every template of the package's
catalogue template, none fuzzy, each translation with exactly the fields of its English
template (names, format specifications and conversions), every plural with Russian's three
forms. A run of ``planmethod solve`` in Russian — chosen with ``--lang ru`` or with
``[course] language = "ru"`` in the exercise — prints no English word the messages use
(:func:`planmethod.testing.pseudo.unmarked_words`) and writes its numbers with a decimal
comma, while its ``--json`` report keeps its keys, names and numbers. So does a Russian run
of the force analysis (``exercises/fourbar_forces.toml``: kinetostatics, reactions, the
balancing moment and its checks, Aliyev's constants), its text and its figures.

What is not a word of the messages is left out of the run's text, each by name (computed
here and removed before the words are counted): the exercise's names (title, links, points,
the published source) and the names of the files a run writes. The assembly's reasons
(``по эскизу``) and the check table's units (``рад/с``) are the catalogue's words. Every other
command of a Russian course is run in tests/test_russian_runs.py.
"""

from __future__ import annotations

import io
import json
import re
import string
from collections import Counter
from contextlib import redirect_stdout
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the catalogues are read with Babel (test extra)")

from babel.messages import pofile

from planmethod.cli import main
from planmethod.testing.pseudo import message_words, unmarked_words
from planmethod.words import language, message, plural, render

ROOT = Path(__file__).resolve().parent.parent
LOCALE = ROOT / "planmethod" / "locale"
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"
FORCES = ROOT / "exercises" / "fourbar_forces.toml"
RUSSIAN_TEMPLATE = ROOT / "exercises" / "templates" / "ru" / "slider_crank.toml"
#: a number written with a decimal point (0.002), as the Russian course never writes one
POINT_NUMBER = re.compile(r"\d\.\d")
#: a string of a report meant for programs: a name, a key, an enum value
MACHINE_WORD = re.compile(r"[A-Za-z_][\w@/*.+-]*")
#: the name of a figure's file (with its folder), as a run's lines name it
SVG_FILE = re.compile(r"\S+\.svg\b")


def _read(path: Path):
    with open(path, "rb") as file:
        return pofile.read_po(file)


@pytest.fixture(scope="module")
def catalogues():
    return _read(LOCALE / "planmethod.pot"), _read(LOCALE / "ru" / "LC_MESSAGES" / "planmethod.po")


def _fields(form: str) -> Counter:
    """A form's fields with their format specifications and conversions (``{{`` is none)."""
    return Counter((name, spec, conversion)
                   for _, name, spec, conversion in string.Formatter().parse(form)
                   if name is not None)


def test_every_template_is_translated_and_none_is_fuzzy(catalogues):
    template, russian = catalogues
    ids = [(entry.id, entry.context) for entry in template if entry.id]
    assert len(ids) > 800
    untranslated, fuzzy = [], []
    for key, context in ids:
        entry = russian.get(key, context=context)
        forms = () if entry is None else (
            entry.string if isinstance(entry.string, tuple) else (entry.string,))
        if not forms or not all(forms):
            untranslated.append(key)
        elif entry.fuzzy:
            fuzzy.append(key)
    assert (untranslated, fuzzy) == ([], [])
    assert language.missing("ru") == 0


def test_each_translation_has_exactly_its_templates_fields(catalogues):
    template, russian = catalogues
    wrong = []
    for entry in template:
        if not entry.id:
            continue
        english = entry.id if isinstance(entry.id, tuple) else (entry.id,)
        found = russian.get(entry.id, context=entry.context).string
        translated = found if isinstance(found, tuple) else (found,)
        wrong += [(english[0], form) for form in translated
                  if _fields(form) != _fields(english[0])]
    assert wrong == []


def test_plurals_have_russians_three_forms(catalogues):
    _, russian = catalogues
    assert russian.num_plurals == 3
    assert "n % 10 == 1 && n % 100 != 11" in russian.plural_forms
    plurals = [entry for entry in russian if entry.id and entry.pluralizable]
    assert len(plurals) > 20
    assert all(len(entry.string) == 3 and all(entry.string) for entry in plurals)
    digits = [render(plural("{count} digit", "{count} digits", count=count), "ru")
              for count in (1, 3, 5, 11, 21, 22, 25, 111)]
    assert digits == ["1 цифра", "3 цифры", "5 цифр", "11 цифр", "21 цифра", "22 цифры",
                      "25 цифр", "111 цифр"]


def test_the_decimal_sign_and_the_units_are_russian():
    assert render(message(".", context="decimal sign"), "ru") == ","
    units = {unit: render(message(unit, context="unit"), "ru")
             for unit in ("m", "mm", "m/s", "m/s²", "rad/s", "N", "N·m", "kg·m²", "m/mm")}
    assert units == {"m": "м", "mm": "мм", "m/s": "м/с", "m/s²": "м/с²", "rad/s": "рад/с",
                     "N": "Н", "N·m": "Н·м", "kg·m²": "кг·м²", "m/mm": "м/мм"}
    assert render(message("μl = {scale:g} m/mm", scale=0.002), "ru") == "μl = 0,002 m/mm"


def _run(*argv) -> str:
    out = io.StringIO()
    with redirect_stdout(out):
        code = main([str(argument) for argument in argv])
    assert code == 0
    return out.getvalue()


def _foreign(path: Path) -> list[str]:
    """The names a solve of ``path`` prints that are no words (see the module's docstring)."""
    from planmethod.spec import load_exercise

    exercise = load_exercise(path)
    mechanism = exercise.mechanism
    texts = [mechanism.title, exercise.published_source or "", *mechanism.links,
             *(point for link in mechanism.links.values() for point in link.points)]
    return [text for text in texts if text]


def _russian_words_only(shown: str, foreign: list[str]) -> tuple[list[str], list[str]]:
    """The English words of the messages in ``shown`` and its numbers with a decimal point,
    the foreign texts left out."""
    for text in sorted(foreign, key=len, reverse=True):
        shown = shown.replace(text, " ")
    return unmarked_words(shown, message_words()), POINT_NUMBER.findall(shown)


@pytest.fixture(scope="module")
def course_file(tmp_path_factory) -> Path:
    """The compressor with ``[course] language = "ru"``."""
    path = tmp_path_factory.mktemp("course") / "compressor_ru.toml"
    path.write_text(COMPRESSOR.read_text(encoding="utf-8") + '\n[course]\nlanguage = "ru"\n',
                    encoding="utf-8")
    return path


@pytest.mark.parametrize("chosen", ["option", "course file"])
def test_a_russian_solve_shows_no_english_word_and_decimal_commas(chosen, course_file):
    path, argv = ((COMPRESSOR, ["--lang", "ru"]) if chosen == "option" else (course_file, []))
    shown = _run("solve", path, *argv)
    assert "Структурный анализ" in shown and "Масштабы" in shown
    assert "μl = 0,002 м/мм" in shown and "μv = 0,2 (м/с)/мм" in shown
    assert "ведущее звено 1 (AB) со стойкой 0: механизм I класса" in shown
    assert _russian_words_only(shown, _foreign(path)) == ([], [])


def test_the_english_run_is_still_english():
    """The same run without a language: the words the Russian one must not show are there,
    so the test above could fail."""
    shown = _run("solve", COMPRESSOR)
    words, points = _russian_words_only(shown, _foreign(COMPRESSOR))
    assert {"structural", "analysis", "scales", "drive", "link"} <= {
        word.lower() for word in words}
    assert "μl = 0.002 m/mm" in shown and points


def _force_run(folder: Path, *argv) -> tuple[str, list[str]]:
    """A solve of the four-bar's force analysis with its figures written into ``folder``:
    its text (the names of the figures' files left out: ``lever.svg``, and
    ``combined_force.svg`` that it says it does not draw) and its figures' visible texts."""
    from planmethod.testing.pseudo import texts_of_svg

    shown = SVG_FILE.sub(" ", _run("solve", FORCES, "--svg", folder, *argv))
    written = sorted(folder.glob("*.svg"))
    assert {"loaded.svg", "lever.svg"} <= {path.name for path in written}
    return shown, [text for path in written
                   for text in texts_of_svg(path.read_text(encoding="utf-8"))]


def test_a_russian_force_analysis_shows_no_english_word(tmp_path):
    shown, figures = _force_run(tmp_path, "--lang", "ru")
    assert "Кинетостатический расчёт (принцип Даламбера) при φ₁ = 60°" in shown
    assert "уравновешивающий момент Mур = 0,642055 Н·м (по группам Ассура)" in shown
    assert "рычаг Жуковского (план скоростей): Mур = 0,642055 Н·м" in shown
    assert "Fи = −m·a_S (Н)" in shown and "R₀₁       A" in shown
    assert any(text.startswith("уравновешивающая сила Fур") for text in figures)
    foreign = _foreign(FORCES)
    assert _russian_words_only(shown, foreign) == ([], [])
    assert _russian_words_only("\n".join(figures), foreign) == ([], [])


def test_the_english_force_analysis_is_still_english(tmp_path):
    """The force run without a language shows the words the Russian one must not."""
    shown, figures = _force_run(tmp_path)
    foreign = _foreign(FORCES)
    words = {word.lower() for word in _russian_words_only(shown, foreign)[0]}
    assert {"balancing", "moment", "group", "method", "lever", "reaction", "force",
            "polygon", "combined", "constants"} <= words
    drawn = {word.lower() for word in _russian_words_only("\n".join(figures), foreign)[0]}
    assert {"inertia", "force", "balancing", "lever", "arm"} <= drawn
    assert "balancing moment M_b = 0.642055 N·m (group method)" in shown


def _machine_parts(report, path: str = "") -> list:
    """A JSON report's keys, numbers, flags and machine words, in order (its sentences
    left out: they are rendered in the run's language)."""
    if isinstance(report, dict):
        return [(path, list(report))] + [part for key, value in report.items()
                                         for part in _machine_parts(value, f"{path}.{key}")]
    if isinstance(report, list):
        return [(path, len(report))] + [part for index, value in enumerate(report)
                                        for part in _machine_parts(value, f"{path}[{index}]")]
    if isinstance(report, str) and not MACHINE_WORD.fullmatch(report):
        return []
    return [(path, report)]


def test_the_json_report_keeps_its_keys_and_numbers_in_russian(course_file):
    english = json.loads(_run("solve", COMPRESSOR, "--json"))
    for argv in (["solve", COMPRESSOR, "--json", "--lang", "ru"], ["solve", course_file,
                                                                   "--json"]):
        russian = json.loads(_run(*argv))
        assert _machine_parts(russian) == _machine_parts(english)
        sentences = [text for text in _strings(russian) if not MACHINE_WORD.fullmatch(text)]
        assert sentences and not [text for text in sentences if POINT_NUMBER.search(text)]


def _strings(report) -> list[str]:
    """Every text of a JSON report, in order."""
    if isinstance(report, dict):
        return [text for value in report.values() for text in _strings(value)]
    if isinstance(report, list):
        return [text for value in report for text in _strings(value)]
    return [report] if isinstance(report, str) else []


def test_a_russian_templates_task_writes_its_numbers_with_a_decimal_comma():
    """The task a template's description makes (its placeholders filled) writes the numbers
    as the course does; the same variant in English keeps the decimal point."""
    from planmethod.grading.templates import draw_variant, load_template

    variant = draw_variant(load_template(RUSSIAN_TEMPLATE), student="001")
    assert variant.exercise.course.language == "ru"
    with language.speaking("ru"):
        russian = variant.description
    assert re.search(r"Кривошип AB = 0,0\d\d м", russian) and not POINT_NUMBER.search(russian)
    assert re.search(r"Кривошип AB = 0\.0\d\d м", variant.description)
