"""One rulebook for Python and the page: the number grammar, the quoting, the verdicts and the
templates the workbook page receives as data (planmethod/render/page_rules.py), Python's own
reader derived from the same data, and the page's scripts checked under Node against the golden
file Python writes (tests/page_golden.py; in Chromium: tests/test_browser.py)."""

from __future__ import annotations

import json
import math
import re
import shutil
import string
import subprocess
import unicodedata
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planmethod.grading.reading import number_grammar, read_number
from planmethod.render.page_rules import (
    PAGE_WORDS,
    page_rules,
    quoted,
    rule_templates,
    template_text,
    unprintable_points,
)
from planmethod.words import template

ROOT = Path(__file__).resolve().parent.parent
#: the pages' scripts: no sentence is written in them
SCRIPTS = sorted([*(ROOT / "planmethod" / "render").glob("*.js"),
                  *(ROOT / "planmethod" / "studio").glob("*.js")])


def float_reading(raw):
    """How ``grade`` read a typed answer before its grammar was data: Python's ``float``."""
    text = str(raw).strip()
    if not text:
        return None
    cleaned = text.replace("\u2212", "-").replace(" ", "")
    if cleaned.count(",") == 1 and "." not in cleaned:
        cleaned = cleaned.replace(",", ".")
    try:
        value = float(cleaned)
    except ValueError:
        return text[:40]
    return value if math.isfinite(value) else text[:40]


#: characters a typed number is made of, and some of other scripts and spaces
NUMBERISH = st.text(st.sampled_from("0123456789_.,eE+- \u2212\t٣५５\u00a0\u3000\u2009"
                                    "infatyINF\ufeff٫"), max_size=14)


@settings(max_examples=400, deadline=None)
@given(st.one_of(NUMBERISH, st.text(max_size=16)))
def test_the_grammar_reads_as_float_read(text):
    """The grammar as data reads every text as ``float`` did: digits of any script,
    underscores between digits, exponents, a decimal comma, spaces around."""
    assert read_number(text) == float_reading(text) or (
        read_number(text) != read_number(text))          # never NaN: a value equals itself


def test_the_grammars_digits_and_spaces_are_unicodes():
    grammar = number_grammar()
    digits = {zero + step for zero in grammar.zeros for step in range(10)}
    assert digits == {point for point in range(0x110000)
                      if unicodedata.decimal(chr(point), None) is not None}
    assert set(grammar.spaces) == {chr(p) for p in range(0x110000) if chr(p).isspace()}
    assert read_number("٥,٢٧") == 5.27 and read_number("１_０００") == 1000.0
    # one pattern, read alike by Python and by JavaScript: ASCII classes, no \d, no anchors
    assert "\\d" not in grammar.pattern and "$" not in grammar.pattern


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=20))
def test_the_quoting_is_reprs(text):
    assert quoted(text, unprintable_points()) == repr(text)


def test_the_page_is_sent_grades_one_table():
    """The page grades by grading's verdict table itself (planmethod.grading.verdicts): every
    class of every table, by ``<table>.<class>``, in the page's language; the page's own
    words are none of grade's sentences."""
    from planmethod.grading.verdicts import rulebook

    table = rulebook()
    templates = page_rules("en").templates
    expected = {f"{name}.{kind}": entry["template"] for name, entries in table.items()
                for kind, entry in entries.items()}
    assert {name: templates[name] for name in expected} == expected
    assert templates["parts.on_the_line"] == ("it lies on the line {line} through {through} "
                                              "but {along:.1f} mm off along it")
    assert set(templates) == set(expected) | set(PAGE_WORDS)
    assert not {text.template for text in PAGE_WORDS.values()} & set(expected.values())


def test_every_page_template_is_one_the_pages_formatter_writes():
    """The page's formatter writes the specifications Python's ``format`` knows that the
    templates use: a precision and e, f, g or d, or nothing; a text quoted (``!r``) has
    none."""
    for name, text in {**PAGE_WORDS, **rule_templates()}.items():
        for _, field, specification, conversion in string.Formatter().parse(text.template):
            if field is None:
                continue
            assert conversion in (None, "r"), name
            assert not (conversion and specification), name
            assert re.fullmatch(r"(\.[0-9]+)?[defg]|", specification), (name, specification)
            assert not re.fullmatch(r"\.[0-9]+", specification), (name, specification)


def test_a_template_keeps_its_fields_in_the_pages_language(tmp_path, monkeypatch):
    """The page receives each template translated by the catalogue, fields left to fill; a
    translation that does not fit its fields gives the English template."""
    pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel")
    from planmethod.testing.pseudo import PSEUDO, pseudo_catalogue
    from planmethod.words import language

    pseudo_catalogue(tmp_path)
    monkeypatch.setenv(language.LOCALE_ENVIRONMENT, str(tmp_path))
    language.catalogue.cache_clear()
    try:
        rules = page_rules(PSEUDO)
        assert rules.templates["amounts.right"] == "⟦{amount} ± {tolerance:.3g}⟧"
        assert rules.templates["answers.not_a_number"] == ("⟦{symbol}: {given!r} is not a "
                                                           "number (right: {right})⟧")
        assert rules.language == PSEUDO
        assert template_text(template("no {such} template"), PSEUDO) == "no {such} template"
    finally:
        language.catalogue.cache_clear()
    with pytest.raises(ValueError, match="literal braces"):
        template_text(template("{{x}}"))


# -- the scripts ----------------------------------------------------------------------------------
_LITERAL = re.compile(r"""//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\\n])*"|'(?:\\.|[^'\\\n])*'"""
                      r"""|`(?:\\.|[^`\\])*`""", re.S)
#: two words of letters in a row: what a sentence has and a selector, a class or an id lacks
_WORDS = re.compile(r"[^\W\d_]{2,}[ ]+[^\W\d_]{2,}")
#: what marks a literal as a CSS selector or a markup attribute, not words
_SELECTOR = re.compile(r"[#\[\]>:=.]")
#: a programmer's message: an error thrown for a bug (words for a developer, never shown)
_THROWN = re.compile(r"new Error\((?:[^()]|\([^()]*\))*\)")


def string_literals(source: str) -> list[str]:
    """The string literals of a script (comments skipped; a template literal's ``${…}``
    parts left out)."""
    out = []
    source = _THROWN.sub("", source.replace('"use strict"', ""))
    for found in _LITERAL.finditer(source):
        text = found.group()
        if text.startswith(("//", "/*")):
            continue
        body = text[1:-1]
        if text.startswith("`"):
            body = re.sub(r"\$\{[^}]*\}", " ", body)
        out.append(body)
    return out


def sentences(source: str) -> list[str]:
    """The literals of a script that read as words for a person: two words in a row, not a
    CSS selector."""
    return [text for text in string_literals(source)
            if _WORDS.search(text) and not _SELECTOR.search(text)]


def test_no_script_of_a_page_writes_a_sentence():
    """Every sentence a page shows comes from a template Python sends (translated): the
    scripts' string literals hold none."""
    assert sentences('x("a selector > td", "two words", `${a} ok`, "one"); '
                     'throw new Error("a bug " + f(x) + " here")') == ["two words"]
    found = {script.name: sentences(script.read_text(encoding="utf-8")) for script in SCRIPTS}
    assert {"page_rules.js", "page_words.js", "workbook.js", "workbook_draw.js"} <= set(found)
    assert {name: texts for name, texts in found.items() if texts} == {}


def test_the_scripts_agree_with_python_under_node(tmp_path_factory):
    """The page's own scripts, run by Node's test runner on the golden file: every typed answer
    gets ``grade``'s verdict, every drawn point ``grade --drawing``'s sentence (a point of the
    wrong link: on the line, off along it), every number Python's writing."""
    node = shutil.which("node")
    if node is None:
        pytest.skip("no Node.js on the PATH (apt-get install nodejs): the pages' scripts are "
                    "checked in Chromium only")
    import page_golden

    golden = page_golden.golden_file(tmp_path_factory)
    data = json.loads(golden.read_text(encoding="utf-8"))
    assert len(data["answers"]) >= 2000
    assert sum(len(drawing["expected"]) for drawing in data["drawings"]) >= 500
    done = subprocess.run([node, "--test", str(ROOT / "tests" / "js")], cwd=ROOT,
                          env={"PATH": "/usr/bin:/bin", "PLANMETHOD_GOLDEN": str(golden)},
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert "# skipped 0" in done.stdout and "# fail 0" in done.stdout
