"""The words: message templates in the code, the catalogues made from them, and rendering in a
language — the English template and its fields, a translation, a course's own catalogue."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from planmethod.words import language as languages
from planmethod.words.catalogue import package_templates, templates_in
from planmethod.words.message import message, plural
from planmethod.words.render import render

ROOT = Path(__file__).resolve().parent.parent
LOCALE = ROOT / "planmethod" / "locale"

babel = pytest.importorskip("babel", reason="the catalogue build needs Babel (test extra)")


def test_every_template_is_a_literal_with_the_fields_it_names():
    """A template is read from its call, so it must be a literal; and the call gives exactly
    the fields the template names (a missing one would fail only when the sentence is shown,
    an extra one is a field no translator sees)."""
    problems = []
    for found in package_templates():
        where = f"{found.file}:{found.line}"
        if not all(found.forms):
            problems.append(f"{where}: the template is not a literal string")
        elif found.fields is not None and found.names() != set(found.fields):
            problems.append(f"{where}: the template names {sorted(found.names())}, the call "
                            f"gives {sorted(found.fields)}")
    assert not problems, "\n".join(problems)


def test_templates_read_from_code():
    source = ('x = plural("{count} file", "{count} files", count=n, context="disk")\n'
              'y = words.message(f"{name}")\n')
    found = list(templates_in(source, "m.py"))
    assert [(item.forms, item.context, item.fields) for item in found] == [
        (("{count} file", "{count} files"), "disk", ("count",)), (("",), None, ())]


def _rebuilt(tmp_path: Path) -> Path:
    """A copy of the package's catalogues, rebuilt from the code."""
    import shutil

    from planmethod.words.catalogue import build

    copy = tmp_path / "planmethod"
    shutil.copytree(ROOT / "planmethod", copy, ignore=shutil.ignore_patterns("__pycache__"))
    build(copy)
    return copy / "locale"


def test_catalogues_are_up_to_date_with_the_code(tmp_path):
    """``python -m planmethod.words.catalogue build`` was run after the last template changed:
    the shipped template, the catalogues and their compiled forms are what it writes."""
    rebuilt = _rebuilt(tmp_path)
    stale = [str(path.relative_to(rebuilt)) for path in sorted(rebuilt.rglob("*.*"))
             if path.read_bytes() != (LOCALE / path.relative_to(rebuilt)).read_bytes()]
    assert not stale, ("run `python -m planmethod.words.catalogue build`: stale "
                       + ", ".join(stale))


def test_a_number_is_written_as_the_language_writes_it():
    scale = message("μl = {scale:g} m/mm", scale=0.002)
    assert render(scale, "en") == "μl = 0.002 m/mm"
    assert "0,002" in render(scale, "ru")
    # text given as a field is never touched, only numbers are
    assert render(message("{file} written", file="a.b.svg"), "ru").startswith("a.b.svg")


def test_english_plural_and_nested_messages():
    assert render(plural("{count} variant", "{count} variants", count=1), "en") == "1 variant"
    assert render(message("{a}; {b}", a=message("x"), b=[1.5, message("y")]), "en") == (
        "x; 1.5, y")


def test_a_template_never_takes_positional_fields():
    with pytest.raises(KeyError):
        render(message("{0} and {1}"), "en")


@pytest.mark.parametrize("template, values", [
    ("{a:.3g} m/s, {b!r} {c:>6}", {"a": 0.70093, "b": "x", "c": -0.0}),
    ("{a[0]} {b.real}", {"a": [1.25], "b": 2.5}),         # not plain names: string.Formatter
    ("{a:{width}}", {"a": 1.5, "width": 6}),              # a nested field: string.Formatter
    ("{{literal}} {a}", {"a": message("x")}),
])
def test_a_template_is_filled_as_string_formatter_fills_it(template, values):
    """The quick fill of plain-named fields writes what ``string.Formatter`` writes."""
    from planmethod.words.render import _filled, _Formatter

    for language, sign in (("en", "."), ("ru", ",")):
        formatter = _Formatter(language, sign)
        assert _filled(formatter, template, values) == formatter.vformat(template, (), values)


def test_every_catalogue_template_fills_the_quick_way_or_falls_back():
    """Every template of the package, in English and in Russian, is filled the quick way (or
    said to need string.Formatter), and its fields filled alike either way."""
    from planmethod.words.language import catalogue
    from planmethod.words.render import _filled, _Formatter, _simple_fields

    russian = catalogue("ru")
    for found in package_templates():
        for template in found.forms:
            for value in (3, -0.25, "x"):
                fields = {name: value for name in found.names()}
                for text, sign in ((template, "."), (russian.gettext(template), ",")):
                    formatter = _Formatter("ru", sign)
                    if _simple_fields(text) is None or not set(fields) >= _names(text):
                        continue
                    try:
                        expected = formatter.vformat(text, (), fields)
                    except ValueError:        # a number's format given text: fails alike
                        with pytest.raises(ValueError):
                            _filled(formatter, text, fields)
                        continue
                    assert _filled(formatter, text, fields) == expected


def _names(template: str) -> set[str]:
    import string

    return {name for _, name, _, _ in string.Formatter().parse(template) if name}


def _course_catalogue(folder: Path, language: str, entries: dict[str, str]) -> None:
    """A course's catalogue, as docs/languages.md makes one: started from the package's
    template with the catalogue command, a few messages filled in, compiled."""
    from babel.messages import pofile

    command = [sys.executable, "-m", "planmethod.words.catalogue"]
    subprocess.run([*command, "new", language, str(folder)], check=True, cwd=ROOT,
                   capture_output=True)
    po = folder / language / "LC_MESSAGES" / "planmethod.po"
    with open(po, "rb") as file:
        catalogue = pofile.read_po(file)
    for key, text in entries.items():
        catalogue[key].string = text
    with open(po, "wb") as file:
        pofile.write_po(file, catalogue)
    subprocess.run([*command, "compile", str(folder)], check=True, cwd=ROOT,
                   capture_output=True)


def test_a_course_adds_a_language(tmp_path, monkeypatch):
    """A course's catalogue is found through PLANMETHOD_LOCALE_DIR; what it does not translate
    shows in English, and :func:`missing` counts it."""
    wrong = "'{language}' is no language code (such as en or ru)"
    _course_catalogue(tmp_path, "uz", {wrong: "«{language}» til kodi emas (masalan, en yoki ru)"})
    monkeypatch.setenv(languages.LOCALE_ENVIRONMENT, str(tmp_path))
    languages.catalogue.cache_clear()
    try:
        assert languages.problem("uz") is None
        assert render(message(wrong, language="q q"), "uz") == (
            "«q q» til kodi emas (masalan, en yoki ru)")
        untranslated = languages.problem("xx")      # not in uz's catalogue: English
        assert render(untranslated, "uz") == render(untranslated, "en")
        known = {(template.context, template.template) for template in package_templates()}
        assert languages.missing("uz") == len(known) - 1
    finally:
        languages.catalogue.cache_clear()


def test_a_run_in_an_incomplete_language_says_how_many_messages_are_missing(tmp_path,
                                                                            monkeypatch,
                                                                            capsys):
    """The command line says, in one line on stderr, how many messages the chosen language
    lacks (shown in English); a complete catalogue says nothing."""
    from planmethod.cli import main

    wrong = "'{language}' is no language code (such as en or ru)"
    _course_catalogue(tmp_path, "uz", {wrong: "«{language}» til kodi emas (masalan, en yoki ru)"})
    monkeypatch.setenv(languages.LOCALE_ENVIRONMENT, str(tmp_path))
    languages.catalogue.cache_clear()
    exercise = str(ROOT / "exercises" / "compressor_slider_crank.toml")
    try:
        lacking = languages.missing("uz")
        assert main(["solve", exercise, "--lang", "uz"]) == 0
        assert capsys.readouterr().err == (f"planmethod: note: the catalogue of uz lacks "
                                           f"{lacking} messages; they are shown in English\n")
        assert main(["solve", exercise, "--lang", "ru"]) == 0
        assert capsys.readouterr().err == ""
    finally:
        languages.catalogue.cache_clear()


def test_a_translation_that_does_not_fit_its_fields_shows_in_english(tmp_path, monkeypatch):
    wrong = "'{language}' is no language code (such as en or ru)"
    _course_catalogue(tmp_path, "kk", {wrong: "{tili} — тіл коды емес"})
    monkeypatch.setenv(languages.LOCALE_ENVIRONMENT, str(tmp_path))
    languages.catalogue.cache_clear()
    try:
        assert render(message(wrong, language="q"), "kk") == render(message(wrong, language="q"),
                                                                    "en")
    finally:
        languages.catalogue.cache_clear()


def test_the_language_is_chosen_option_first_then_file_then_environment():
    environment = {languages.ENVIRONMENT: "ru"}
    assert languages.choose("en", "ru", environment) == "en"
    assert languages.choose(None, "en", environment) == "en"
    assert languages.choose(None, None, environment) == "ru"
    assert languages.choose(None, None, {}) == "en"


def test_an_unknown_language_is_named(tmp_path):
    assert languages.problem("ru") is None
    assert "no catalogue for the language zz" in render(languages.problem("zz"), "en")
    assert "is no language code" in render(languages.problem("r u"), "en")


def test_the_environment_speaks_only_a_language_it_can(monkeypatch):
    script = "from planmethod.words import current; print(current())"
    for chosen, spoken in (("ru", "ru"), ("zz", "en")):
        result = subprocess.run([sys.executable, "-c", script], cwd=ROOT, text=True,
                                capture_output=True, check=True,
                                env={**os.environ, languages.ENVIRONMENT: chosen})
        assert result.stdout.strip() == spoken
