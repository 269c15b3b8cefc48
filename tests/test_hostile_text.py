"""Hostile and careless text (issue 35): text that every writer must write so that it reads
back, text that no renderer may read as markup, text that must not make unbounded work, and
files that are valid and must be read.

Each case checks its post-condition: the file written reads back to the same values; the
figure holds the text as given; a refusal is one line naming the file and key, exit 2, with
nothing written.
"""

from __future__ import annotations

import datetime
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


# ---------------------------------------------------------------------------------------------
# a file that starts with a UTF-8 byte-order mark (Notepad, Excel) is read as UTF-8

BOM = "\ufeff"


def test_every_reader_drops_a_byte_order_mark(tmp_path, capsys):
    """The exercise, the template, the answers (CSV and JSON), the roster, the keys, the
    coordinate table and a drawing, each written with a byte-order mark first, read as
    without it."""
    from planmethod.application.checking import read_coordinates
    from planmethod.application.variants import read_roster
    from planmethod.grading.answers import read_answers
    from planmethod.grading.drawings import read_drawing
    from planmethod.grading.keys import load_keys
    from planmethod.grading.templates import load_template
    from planmethod.spec import load_exercise

    def marked(name: str, text: str) -> Path:
        path = tmp_path / name
        path.write_text(BOM + text, encoding="utf-8")
        return path

    exercise = marked("exercise.toml", BASE)
    assert load_exercise(exercise).mechanism.title == "Compressor slider-crank " \
        "(Abduvaliev & Abduxoshimov)"
    assert main(["solve", str(exercise)]) == 0
    template = marked("template.toml", TEMPLATE)
    assert load_template(template).data["title"] == tomllib.loads(TEMPLATE)["title"]
    assert read_answers(marked("answers.csv", "student,v_C\ns1,5\n")) == [("s1", {"v_C": "5"})]
    assert read_answers(marked("answers.json", '{"s1": {"v_C": 5}}')) == [("s1", {"v_C": 5})]
    assert read_roster(str(marked("roster.csv", "student\ns1\n"))) == [("s1", [])]
    course = tmp_path / "course"
    assert main(["variants", str(template), "--count", "1", "--out", str(course),
                 "--no-sheets"]) == 0
    keys = marked("keys.json", (course / "keys.json").read_text(encoding="utf-8"))
    assert len(load_keys(keys)) == 1
    table = ROOT / "exercises" / "conveyor_sixbar_table2.csv"
    conveyor = load_exercise(ROOT / "exercises" / "conveyor_sixbar.toml")
    assert len(read_coordinates(marked("table.csv", table.read_text(encoding="utf-8")),
                                conveyor)) == len(read_coordinates(table, conveyor))
    drawing = marked("plan.json", '{"plan": "velocity", "points": {"p": [0, 0], "b": [1, 2]}}')
    assert read_drawing(drawing).points["b"] == (1.0, 2.0)
    capsys.readouterr()


def test_the_studio_opens_a_file_with_a_byte_order_mark(tmp_path):
    from planmethod.studio.api import Workspace, open_exercise

    (tmp_path / "marked.toml").write_text(BOM + BASE, encoding="utf-8")
    opened = open_exercise(Workspace(tmp_path), "marked.toml")
    assert opened["tables"]["title"].startswith("Compressor slider-crank")


def test_text_parsed_in_memory_drops_a_byte_order_mark():
    from planmethod.spec import parse_json, parse_toml

    assert parse_toml(BOM + 'title = "x"') == {"title": "x"}
    assert parse_json(BOM + '{"a": [1]}') == {"a": [1]}


def test_a_lone_surrogate_in_toml_text_is_one_line():
    """Text that came through JSON (the studio) may hold half a UTF-16 pair: refused, naming
    its line, never written into a file that cannot be encoded."""
    from planmethod.errors import SpecError
    from planmethod.spec import parse_toml

    with pytest.raises(SpecError, match=r"^x\.toml: not valid TOML: U\+D800 .* \(line 2\)$"):
        parse_toml('a = 1\ntitle = "\ud800"', file="x.toml")


# ---------------------------------------------------------------------------------------------
# the nesting guard reads TOML's strings and comments as TOML does


def _depth(value) -> int:
    """How deep lists and tables nest in ``value`` (a scalar: 0)."""
    if isinstance(value, dict | list):
        children = value.values() if isinstance(value, dict) else value
        return 1 + max((_depth(child) for child in children), default=0)
    return 0


def _document_depth(data: dict) -> int:
    """The nesting of the TOML document :func:`to_toml` writes of ``data``: a ``[table]``
    header is one level and an ``[[array]]`` two, and the keys under them are below them."""
    deepest = 0
    for value in data.values():
        if isinstance(value, dict):
            deepest = max(deepest, 1 + max(map(_depth, value.values()), default=0))
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            deepest = max(deepest, 2 + max((_depth(v) for item in value
                                            for v in item.values()), default=0))
        else:
            deepest = max(deepest, _depth(value))
    return deepest


#: text made of what a nesting guard could mistake: brackets, quotes, comments, escapes, dots
TRICKY = st.text(alphabet=st.sampled_from("[]{}\"'#\\\n\t .=,a1"), max_size=30) | TEXT
TRICKY_VALUES = st.recursive(TRICKY | st.floats(allow_nan=False, allow_infinity=False)
                             | st.integers(-5, 5) | st.times(), lambda inner:
                             st.lists(inner, max_size=3)
                             | st.dictionaries(TRICKY, inner, max_size=3), max_leaves=10)
TRICKY_TABLES = st.dictionaries(TRICKY, TRICKY_VALUES
                                | st.dictionaries(TRICKY, TRICKY_VALUES, max_size=3)
                                | st.lists(st.dictionaries(TRICKY, TRICKY_VALUES, max_size=3),
                                           min_size=1, max_size=2), max_size=4)


@settings(max_examples=400, deadline=None)
@given(TRICKY_TABLES)
def test_the_guard_counts_only_the_brackets_toml_reads(data):
    """For any document, the guard's depth is the document's own: no bracket, quote or #
    inside a string counts, and every real level does."""
    from planmethod.spec import nesting_depth

    text = to_toml(data)
    assert tomllib.loads(text) == data
    assert nesting_depth(text) == _document_depth(data)


@settings(max_examples=300, deadline=None)
@given(TRICKY_VALUES)
def test_the_guard_counts_only_the_brackets_json_reads(value):
    import json

    from planmethod.spec import nesting_depth

    assert nesting_depth(json.dumps(value, default=str), syntax="json") == _depth(value)


#: valid files whose strings and comments hold brackets, each read by solve
VALID_TEXTS = {
    "the issue's description": 'description = """He wrote " and then ' + "[" * 40 + '"""',
    "a multi-line literal": "description = '''He wrote ' and then " + "[" * 40 + "''''",
    "closing quotes inside": 'description = """a [[[[""""',
    "an escaped quote": 'description = "say \\" ' + "[" * 40 + '"',
    "an escaped backslash": 'description = "C:\\\\"  # ' + "[" * 40,
    "a literal backslash": "description = 'C:\\' # " + "[" * 40,
    "a comment": "# it's a [[[[ " + "{" * 40 + "\ndescription = 'x'",
    "a line-ending backslash": 'description = """a \\\n  ' + "[" * 40 + '"""',
}


@pytest.mark.parametrize("case", list(VALID_TEXTS))
def test_brackets_in_strings_and_comments_never_count(tmp_path, capsys, case):
    path = tmp_path / "valid.toml"
    text = re.sub(r'^description = """.*?"""\n', "", BASE, count=1, flags=re.M | re.S)
    path.write_text(VALID_TEXTS[case] + "\n" + text, encoding="utf-8")
    assert main(["solve", str(path)]) == 0, capsys.readouterr().err
    capsys.readouterr()


#: really deep files, each refused before it is parsed (no RecursionError, no long stall)
DEEP_TEXTS = {
    "brackets": "x = " + "[" * 40 + "]" * 40,
    "brackets after a string": 'a = "]]]]"\nx = ' + "[" * 40 + "]" * 40,
    "brackets after a literal string": "a = 'C:\\'\nx = " + "[" * 40 + "]" * 40,
    "inline tables": "x = " + "{a = " * 40 + "1" + "}" * 40,
    "a dotted key": "a" + ".a" * 50_000 + " = 1",
    "a dotted key of numbers": "1" + ".1" * 50_000 + " = 1",
    "a quoted dotted key": '"a"' + '."a"' * 50_000 + " = 1",
    "a dotted table header": "[" + ".".join(["a"] * 50_000) + "]\nx = 1",
    "dotted keys under a header": "[" + ".".join(["a"] * 20) + "]\n" + ".".join(["b"] * 20)
                                  + " = 1",
    "dotted keys in inline tables": "x = " + "{a.a.a = " * 20 + "1" + "}" * 20,
}


@pytest.mark.parametrize("case", list(DEEP_TEXTS))
def test_deep_nesting_is_still_refused(tmp_path, capsys, case):
    path = tmp_path / "deep.toml"
    path.write_text(DEEP_TEXTS[case] + "\n", encoding="utf-8")
    line = _fails(capsys, ["solve", path], tmp_path)
    assert "deep.toml: tables or arrays nested" in line and "at most 32" in line


# ---------------------------------------------------------------------------------------------
# a value of the wrong kind is named in the file's words, never as Python writes it

#: (key, TOML value given, what the error says it got)
WRONG_KINDS = [
    ("title", "1979-05-27T07:32:00", "got a date-time 1979-05-27T07:32:00"),
    ("title", "1979-05-27", "got a date 1979-05-27"),
    ("title", "07:32:00", "got a time 07:32:00"),
    ("title", "true", "got true"),
    ("title", '["a", 1979-05-27]', "got ['a', 1979-05-27]"),
    ("title", "{ a = 1 }", "got {a = 1}"),
    ("description", "1979-05-27T07:32:00Z", "got a date-time 1979-05-27T07:32:00+00:00"),
    ("description", "[1, 2]", "got [1, 2]"),
]


@pytest.mark.parametrize(("key", "value", "said"), WRONG_KINDS)
def test_a_wrong_kind_is_said_in_the_files_words(tmp_path, capsys, key, value, said):
    path = tmp_path / "kinds.toml"
    path.write_text(_with(BASE, key, value), encoding="utf-8")
    line = _fails(capsys, ["solve", path], tmp_path)
    assert line.startswith(f"planmethod: error: {path}: {key}: must be ") and line.endswith(said)
    assert "datetime" not in line and "True" not in line


@pytest.mark.parametrize("case", ["omega", "angle", "link", "published"])
def test_a_date_anywhere_is_said_as_a_date(tmp_path, capsys, case):
    """Every key that expects a number, text or a list says what it got the same way."""
    lines = {"omega": ("omega = 100", "omega = 1979-05-27"),
             "angle": ("angle = 45", "angle = [1979-05-27, 2]"),
             "link": ('link = "AB"', "link = 07:32:00"),
             "published": ("v_B = 6.0", "v_B = 1979-05-27T07:32:00")}
    old, new = lines[case]
    assert old in BASE
    path = tmp_path / "kinds.toml"
    path.write_text(BASE.replace(old, new, 1), encoding="utf-8")
    line = _fails(capsys, ["solve", path], tmp_path)
    assert re.search(r"got (a date 1979-05-27|\[1979-05-27, 2\]|a time 07:32:00|"
                     r"a date-time 1979-05-27T07:32:00)$", line), line
    assert "datetime" not in line


def test_a_template_setting_of_the_wrong_kind_is_said_in_the_files_words(tmp_path, capsys):
    path = tmp_path / "template.toml"
    path.write_text(TEMPLATE.replace("[template]", "[template]\nmax_attempts = 1979-05-27", 1),
                    encoding="utf-8")
    assert "[template]" in TEMPLATE
    line = _fails(capsys, ["variants", path, "--out", tmp_path / "out"], tmp_path)
    assert line.endswith("template.max_attempts: must be a whole number in 1…10000, got a date "
                         "1979-05-27")


def test_a_long_wrong_value_is_cut_in_its_error(tmp_path, capsys):
    path = tmp_path / "long.toml"
    path.write_text(BASE.replace("omega = 100", f'omega = "{"x" * 500_000}"', 1),
                    encoding="utf-8")
    line = _fails(capsys, ["solve", path], tmp_path)
    assert line.endswith("drive.omega: must be a finite number, got '" + "x" * 60 + "'…")


# ---------------------------------------------------------------------------------------------
# no unbounded work from a short input: a placeholder's format and a task's length are bounded

#: a placeholder appended to the template's description → what the refusal says
FORMATS = {
    "a precision of 100000000": ("{l_AB:.100000000f}", "has a precision of 100000000; at most 15"),
    "a width of 100000000": ("{l_AB:100000000}", "has a width of 100000000; at most 40"),
    "a width of 5000 digits": ("{l_AB:" + "9" * 5000 + "}", "has a width of 5000 digits"),
    "a zero-padded width": ("{l_AB:041.3f}", "has a width of 41; at most 40"),
    "a precision of 16": ("{omega:.16g}", "has a precision of 16; at most 15"),
}


def _described(extra: str) -> str:
    """The shipped template with ``extra`` at the end of its description."""
    start = TEMPLATE.index('description = """') + len('description = """')
    end = TEMPLATE.index('"""', start)
    return TEMPLATE[:end] + extra + TEMPLATE[end:]


@pytest.mark.parametrize("case", list(FORMATS))
def test_a_placeholder_asking_for_too_much_is_refused(tmp_path, capsys, case):
    placeholder, said = FORMATS[case]
    path = tmp_path / "template.toml"
    path.write_text(_described(placeholder), encoding="utf-8")
    line = _fails(capsys, ["variants", path, "--count", "2", "--out", tmp_path / "out"],
                  tmp_path)
    assert f"{path}: description: the placeholder '" in line and said in line
    assert len(line) < 300


def test_a_placeholder_at_its_bounds_is_filled(tmp_path, capsys):
    path = tmp_path / "template.toml"
    path.write_text(_described(" [{l_AB:40.15f}]"), encoding="utf-8")
    assert main(["variants", str(path), "--count", "1", "--out", str(tmp_path / "out"),
                 "--no-sheets"]) == 0
    written = tomllib.loads((tmp_path / "out" / "001" / "exercise.toml").read_text("utf-8"))
    filled = re.search(r"\[( *\d\.\d+)\]", written["description"]).group(1)
    assert len(filled) == 40 and len(filled.split(".")[1]) == 15
    capsys.readouterr()


def test_a_task_that_grows_beyond_its_bound_is_refused(tmp_path, capsys):
    """A placeholder may quote the file's keys, the description itself among them: the text
    filled in is bounded, however it grows."""
    from planmethod.errors import SpecError
    from planmethod.grading.templates import MAX_TASK_CHARACTERS, format_description

    text = "x" * 300 + " {description}" * 100
    with pytest.raises(SpecError, match=f"more than {MAX_TASK_CHARACTERS} characters"):
        format_description(text, {}, {"description": text})
    path = tmp_path / "template.toml"
    path.write_text(_with(_described(" {title}" * 100), "title", '"' + "T" * 1000 + '"'),
                    encoding="utf-8")
    line = _fails(capsys, ["variants", path, "--count", "1", "--out", tmp_path / "out"],
                  tmp_path)
    assert f"{path}: description: the task's text is more than" in line


def test_the_studio_quotes_a_title_and_never_reads_it_as_a_placeholder():
    """The studio's template quotes the drawing's title by ``{title}``: a title that looks
    like a placeholder is printed as it is, at once."""
    from planmethod.studio.api import variants

    title = "{l_BC:.100000000f}"
    answer = variants(_with(BASE, "title", f'"{title}"'), {"lengths": {"BC": [0.16, 0.2]}},
                      count=1)
    assert tomllib.loads(answer["template"])["description"].startswith("{title}. ")
    assert title in answer["variants"][0]["sheet"]


# ---------------------------------------------------------------------------------------------
# user text is never read as markup: matplotlib's mathtext, XML, HTML

FOURBAR = (ROOT / "exercises" / "fourbar_forces.toml").read_text(encoding="utf-8")
STUDY = (ROOT / "exercises" / "fourbar_study.toml").read_text(encoding="utf-8")
#: titles a library could read as markup, each shown as written
MARKUP_TITLES = ["Mechanism $^^^$", "$5 and $6", r"cost \$5 $x", "<b>&amp;</b> ]]> {{x}}"]


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet=st.sampled_from("$\\^_{}ab ")) | TEXT)
def test_matplotlib_shows_plain_text_as_written(text):
    """What the plotting module gives matplotlib for a file's text is never mathtext, and is
    shown exactly as written."""
    from matplotlib.text import Text

    from planmethod.render.plots import _plain_text

    shown = Text(0, 0, _plain_text(text))
    assert shown._preprocess_math(shown.get_text()) == (text, False)


@pytest.mark.parametrize("title", MARKUP_TITLES)
def test_plots_show_a_title_with_dollars_as_written(tmp_path, capsys, title):
    """sweep --plot, sweep --forces --plot, study --plot and grade --report draw a title that
    holds $…$ (mathtext would stop them with a parse error, or set $5 and $6 as math)."""
    from xml.sax.saxutils import escape

    value = '"' + title.replace("\\", "\\\\") + '"'
    files = {name: tmp_path / f"{name}.toml" for name in ("base", "forces", "study")}
    for name, text in (("base", BASE), ("forces", FOURBAR), ("study", STUDY)):
        files[name].write_text(_with(text, "title", value), encoding="utf-8")
    (tmp_path / "answers.csv").write_text("student,v_C,a_C\ns1,5.2,430\ns2,4,300\n")
    assert main(["sweep", str(files["base"]), "--step", "30", "--plot",
                 str(tmp_path / "curves.png")]) == 0
    assert main(["sweep", str(files["forces"]), "--forces", "--step", "30", "--plot",
                 str(tmp_path / "forces.svg")]) == 0
    assert main(["study", str(files["study"]), "--step", "30", "--plot",
                 str(tmp_path / "study.svg")]) == 0
    assert main(["grade", str(files["base"]), str(tmp_path / "answers.csv"), "--report",
                 str(tmp_path / "report")]) == 0
    capsys.readouterr()
    assert (tmp_path / "curves.png").stat().st_size > 1000
    assert (tmp_path / "report" / "class_report.png").stat().st_size > 1000
    for name in ("forces.svg", "study.svg"):     # these keep their text as text
        assert escape(title) in (tmp_path / name).read_text(encoding="utf-8")


def _xml_files(folder: Path) -> list[Path]:
    return sorted([*folder.rglob("*.svg"), *folder.rglob("*.xml")])


def test_control_characters_never_make_a_file_unreadable(tmp_path, capsys):
    """A title and a task holding control characters (TOML's \\u0001, \\u001b): every SVG
    and the Moodle quiz written stay XML a browser and Moodle read, the text shown with the
    character replaced."""
    from xml.etree import ElementTree

    template = tmp_path / "template.toml"
    template.write_text(_with(_described("\\u0001 \\u001b[2J end."), "title",
                              '"Press\\u0001\\u001b[31m"'), encoding="utf-8")
    course = tmp_path / "course"
    assert main(["variants", str(template), "--count", "2", "--out", str(course)]) == 0
    assert main(["export", str(course / "keys.json"), "--format", "moodle", "--out",
                 str(tmp_path / "quiz.xml")]) == 0
    assert main(["solve", str(course / "001" / "exercise.toml"), "--svg",
                 str(tmp_path / "figures")]) == 0
    capsys.readouterr()
    written = _xml_files(tmp_path)
    assert len(written) >= 8
    for path in written:
        ElementTree.parse(path)        # well-formed, or it raises
    task = (course / "001" / "task.svg").read_text(encoding="utf-8")
    assert "\ufffd \ufffd[2J end." in task and "Press  [31m" in task   # title: spaces
    quiz = (tmp_path / "quiz.xml").read_text(encoding="utf-8")
    assert "\x01" not in quiz and "\x1b" not in quiz


def test_a_title_is_shown_cut_the_same_way_everywhere(tmp_path, capsys):
    """A title of 500 kB (inside the file limit) is shown cut to 80 characters with an
    ellipsis by every figure, sheet, page and report line — one function — and kept whole
    where it is data (the key, the JSON report)."""
    import json
    from xml.sax.saxutils import escape

    from planmethod.vocabulary import TITLE_SHOWN_CHARACTERS, shown_title

    title = "Long & <b>" + "x" * 500_000
    shown = shown_title(title)
    assert len(shown) == TITLE_SHOWN_CHARACTERS and shown.endswith("…")
    exercise = tmp_path / "long.toml"
    exercise.write_text(_with(BASE, "title", f'"{title}"'), encoding="utf-8")
    template = tmp_path / "template.toml"
    template.write_text(_with(TEMPLATE, "title", f'"{title}"'), encoding="utf-8")
    assert main(["solve", str(exercise), "--svg", str(tmp_path / "figures")]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith(f"{shown} — crank angle") and "x" * 100 not in printed
    assert main(["solve", str(exercise), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["title"] == title
    assert main(["workbook", str(exercise), "-o", str(tmp_path / "page.html"), "--step",
                 "90"]) == 0
    assert main(["sweep", str(exercise), "--step", "90", "--plot",
                 str(tmp_path / "curves.png")]) == 0
    assert main(["variants", str(template), "--count", "1", "--out", str(tmp_path / "course")
                 ]) == 0
    assert main(["export", str(tmp_path / "course" / "keys.json"), "--format", "moodle",
                 "--out", str(tmp_path / "quiz.xml")]) == 0
    capsys.readouterr()
    escaped = escape(shown)
    page = (tmp_path / "page.html").read_text(encoding="utf-8")
    assert f"<h1>{escaped}</h1>" in page and f"<title>{escaped} — workbook</title>" in page
    for path in sorted((tmp_path / "figures").glob("*.svg")):
        assert f"<title>{escaped} — " in path.read_text(encoding="utf-8"), path.name
    sheets = sorted((tmp_path / "course" / "001").glob("*.svg"))
    assert len(sheets) >= 2
    for path in [*sheets, tmp_path / "quiz.xml"]:
        text = path.read_text(encoding="utf-8")
        assert escaped in text and "x" * 100 not in text, path.name
    task = (tmp_path / "course" / "001" / "task.txt").read_text(encoding="utf-8")
    assert task.startswith(f"{shown} — variant for")
    key = json.loads((tmp_path / "course" / "keys.json").read_text(encoding="utf-8"))
    assert key["keys"][0]["title"] == title
