"""Hostile and careless text (issue 35): text that every writer must write so that it reads
back, text that no renderer may read as markup, text that must not make unbounded work, and
files that are valid and must be read.

Each case checks its post-condition: the file written reads back to the same values; the
figure holds the text as given; a refusal is one line naming the file and key, exit 2, with
nothing written.
"""

from __future__ import annotations

import datetime
import math
import re
import tomllib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from planmethod.cli import main
from planmethod.grading.templates import to_toml

ROOT = Path(__file__).resolve().parent.parent
BASE = (ROOT / "exercises" / "compressor_slider_crank.toml").read_text(encoding="utf-8")
TEMPLATE = (ROOT / "exercises" / "templates" / "slider_crank.toml").read_text(encoding="utf-8")


def _with(text: str, key: str, value: str) -> str:
    """``text`` (an exercise or template) with its top-level ``key`` set to ``value`` (TOML)."""
    pattern = re.compile(rf'^{key} = (""".*?"""|\'\'\'.*?\'\'\'|".*?")$', re.M | re.S)
    assert pattern.search(text), key
    return pattern.sub(lambda _: f"{key} = {value}", text, count=1)


def _fails(capsys, argv: list, folder: Path) -> str:
    """Run ``argv``: exit 2, one line on stderr, no traceback, nothing written in ``folder``."""
    before = set(folder.rglob("*"))
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 2, (argv, code, out[-300:], err[-300:])
    assert "Traceback" not in out + err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("planmethod") and ": error: " in lines[0], err
    assert set(folder.rglob("*")) == before, "a file was written"
    return lines[0]


# ---------------------------------------------------------------------------------------------
# text written that the tool must read back: the one TOML writer

#: any text (hypothesis leaves out surrogates, which no UTF-8 file holds)
TEXT = st.text()
SCALARS = (TEXT | st.booleans() | st.integers(-2**63 + 1, 2**63 - 1)
           | st.floats(allow_nan=False, allow_infinity=False)
           | st.dates() | st.times() | st.datetimes()
           | st.datetimes(timezones=st.just(datetime.timezone(datetime.timedelta(hours=5)))))
VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=3)
                      | st.dictionaries(TEXT, inner, max_size=3), max_leaves=8)
TABLES = st.dictionaries(TEXT, VALUES | st.dictionaries(TEXT, VALUES, max_size=3)
                         | st.lists(st.dictionaries(TEXT, VALUES, max_size=3), min_size=1,
                                    max_size=2), max_size=5)


@settings(max_examples=300, deadline=None)
@given(TABLES)
def test_every_table_written_reads_back_equal(data):
    """Write → tomllib read → equal, for any text as keys and values: control characters,
    DEL, quotes, backslashes, ''' and paragraphs, keys that need quotes, dates, floats."""
    assert tomllib.loads(to_toml(data)) == data


@settings(max_examples=300, deadline=None)
@given(TEXT)
def test_every_text_written_as_a_title_reads_back(text):
    data = {"title": text, "description": text + "\n" + text, "links": {text: {"k": text}}}
    assert tomllib.loads(to_toml(data)) == data


@pytest.mark.parametrize("text", ["\x7f", "a\x7fb", "\x00", "\x1b[2J", "\u2028", '"""', "'''",
                                  "\\", 'it\'s "x"\n\x7f', "a\n\x7f\n", "''\n''"])
def test_each_awkward_text_reads_back(text):
    data = {"title": text, text: [text], "t": {text: text}}
    assert tomllib.loads(to_toml(data)) == data


def test_a_lone_surrogate_is_refused_by_name():
    with pytest.raises(ValueError, match="lone surrogate"):
        to_toml({"title": "a\ud800"})


def test_convert_writes_a_title_with_del_that_solve_reads(tmp_path, capsys):
    source = tmp_path / "del.toml"
    source.write_text(_with(BASE, "title", '"Lever\\u007f press"'), encoding="utf-8")
    for to, name in (("drawn", "drawn.toml"), ("frames", "frames.toml")):
        target = tmp_path / name
        assert main(["convert", str(source if to == "drawn" else tmp_path / "drawn.toml"),
                     "--to", to, "-o", str(target)]) == 0
        assert tomllib.loads(target.read_text(encoding="utf-8"))["title"] == "Lever\x7f press"
        assert main(["solve", str(target)]) == 0
    capsys.readouterr()


def test_variants_write_exercises_with_del_that_solve_reads(tmp_path, capsys):
    template = tmp_path / "template.toml"
    template.write_text(_with(TEMPLATE, "title", '"Press\\u007f"'), encoding="utf-8")
    out = tmp_path / "course"
    assert main(["variants", str(template), "--count", "2", "--out", str(out),
                 "--no-sheets"]) == 0
    written = sorted(out.glob("*/exercise.toml"))
    assert len(written) == 2
    for path in written:
        assert tomllib.loads(path.read_text(encoding="utf-8"))["title"] == "Press\x7f"
        assert main(["solve", str(path)]) == 0
    capsys.readouterr()
