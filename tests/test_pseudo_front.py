"""Pseudo-translation of the front (planmethod.testing.pseudo): under the made-up language
``qps``, whose catalogue marks every message ⟦…⟧, every word of the one-line error a bad
exercise file gets from ``planmethod solve`` — the reader's, the file handling's, the
structure's and the kinematics' — and every word of the structural analysis comes from the
catalogue. The file's name and key, the exercise's names and the file's own values (inside
the marks) aside; and the command line's own ``planmethod: error:`` prefix, which is the
command layer's words."""

from __future__ import annotations

import copy
import tomllib
from collections.abc import Iterator
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from test_cli import BAD, SEED
from test_hostile_text import BASE, DEEP_TEXTS, WRONG_KINDS, _with

from planmethod.cli import main
from planmethod.convert import convert_tables
from planmethod.errors import PlanmethodError
from planmethod.grading.templates import to_toml
from planmethod.numbering import course_numbers
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.structure import analyse_structure, describe
from planmethod.testing.pseudo import PSEUDO, message_words, pseudo_catalogue, unmarked_words
from planmethod.words import language

ROOT = Path(__file__).resolve().parent.parent
#: the command line's prefix of an error line (the commands' words, not the front's)
PREFIX = "planmethod: error: "


@pytest.fixture(scope="module")
def catalogue(tmp_path_factory) -> tuple[Path, set[str]]:
    """The ``qps`` catalogue's folder, and the words of the messages."""
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    return folder, message_words()


@pytest.fixture
def pseudo(catalogue, monkeypatch) -> Iterator[set[str]]:
    """Speak ``qps`` (as PLANMETHOD_LANG chooses it); yields the words of the messages."""
    folder, words = catalogue
    monkeypatch.setenv(language.LOCALE_ENVIRONMENT, str(folder))
    monkeypatch.setenv(language.ENVIRONMENT, PSEUDO)
    language.catalogue.cache_clear()
    yield words
    language.catalogue.cache_clear()


def _error_line(capsys, argv: list) -> str:
    code = main([str(part) for part in argv])
    out, err = capsys.readouterr()
    assert code == 2, (argv, code, out[-300:], err[-300:])
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]


def _unmarked(line: str, path: Path, words: set[str]) -> list[str]:
    """The words of the messages ``line`` shows outside the marks, the file and its key
    aside (the key: the part after the file that no mark holds)."""
    text = line.removeprefix(PREFIX)
    names = [str(path)]
    rest = text.removeprefix(f"{path}: ")
    key = rest.split(": ", 1)[0]
    if "⟦" not in key and ": " in rest:
        names.append(key)
    assert "⟦" in text, line
    return unmarked_words(text, words, names=names)


def _edited(text: str, edits) -> str:
    if isinstance(edits[0], str):
        edits = (edits,)
    for old, new in edits:
        assert old in text
        text = text.replace(old, new, 1)
    return text


#: bad files, by name: their text
FILES = {
    **{f"cli: {case}": _edited(SEED.read_text(encoding="utf-8"), BAD[case][0]) for case in BAD},
    **{f"kind: {key} = {value}": _with(BASE, key, value) for key, value, _ in WRONG_KINDS},
    **{f"deep: {case}": DEEP_TEXTS[case] + "\n" for case in ("brackets", "a dotted key")},
    "a long whole number": BASE.replace("omega = 100", "omega = " + "9" * 5000, 1),
    "a key given twice": BASE.replace("omega = 100", "omega = 100\nomega = 100", 1),
    "half of a UTF-16 pair": BASE.replace("omega = 100", 'omega = "\\ud800"', 1),
    "a course language that is none": BASE + '\n[course]\nlanguage = "zz"\n',
    "a template": BASE + "\n[vars]\nx = 1\n",
    "W = 3": BASE.replace('[[slide]]\nlink = "slider"', '[[slid]]\nlink = "slider"', 1),
}


@pytest.mark.parametrize("case", list(FILES))
def test_a_bad_files_error_is_marked(pseudo, tmp_path, capsys, case):
    path = tmp_path / "bad.toml"
    path.write_text(FILES[case], encoding="utf-8")
    line = _error_line(capsys, ["solve", path])
    assert _unmarked(line, path, pseudo) == [], line


def test_the_files_own_troubles_are_marked(pseudo, tmp_path, capsys):
    """A file that is missing, a folder, not UTF-8 or too large."""
    (tmp_path / "folder.toml").mkdir()
    (tmp_path / "latin.toml").write_bytes(b"title = '\xe9'\n")
    (tmp_path / "large.toml").write_text("# " + "x" * 1_000_001, encoding="utf-8")
    for name in ("missing.toml", "folder.toml", "latin.toml", "large.toml"):
        path = tmp_path / name
        line = _error_line(capsys, ["solve", path])
        assert _unmarked(line, path, pseudo) == [], line


def test_the_kinematics_errors_are_marked(pseudo, tmp_path, capsys):
    """An assembly refused on a sweep, and an assembly that cannot be followed to an angle."""
    short = (SEED.read_text(encoding="utf-8").replace("C = [0.18, 0], D = [0.09, 0]",
                                                       "C = [0.03, 0], D = [0.02, 0]")
             .replace("angle = 45", "angle = 0")
             .replace("frame = { A = [0, 0] }", "frame = { A = [0, 0], G = [0, -0.02] }")
             .replace('through = "A"', 'through = "G"'))
    rocker = ('[drive]\nlink = "AB"\npivot = "A"\nangle = 60\nomega = 1\n[links]\n'
              'frame = { A = [0, 0], D = [0.30, 0] }\nAB = { A = [0, 0], B = [0.20, 0] }\n'
              'BC = { B = [0, 0], C = [0.22, 0] }\nCD = { C = [0, 0], D = [0.18, 0] }\n')
    cases = [("short.toml", short, ["sweep", "--csv", tmp_path / "out.csv"]),
             ("rocker.toml", rocker, ["solve", "--angle", "150"])]
    for name, text, argv in cases:
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        line = _error_line(capsys, [argv[0], path, *argv[1:]])
        assert "⟦" in line and _unmarked(line, path, pseudo) == [], line


#: what a generated case puts in place of a value (None: the key is removed)
REPLACEMENTS = (None, "abc", [1], {"x": 1}, -1.0, 1e13, "crnak")


def _leaf_paths(node, path=()) -> Iterator[tuple]:
    if isinstance(node, dict | list):
        items = node.items() if isinstance(node, dict) else enumerate(node)
        for key, value in items:
            yield from _leaf_paths(value, (*path, key))
    if path:
        yield path


def _refused_variants(tables: dict) -> Iterator[dict]:
    """``tables`` with one value removed or replaced, each that the reader refuses."""
    for path in _leaf_paths(tables):
        for replacement in REPLACEMENTS:
            changed = copy.deepcopy(tables)
            node = changed
            for part in path[:-1]:
                node = node[part]
            if replacement is None:
                del node[path[-1]]
            else:
                node[path[-1]] = copy.deepcopy(replacement)
            try:
                exercise_from_dict(changed)
            except PlanmethodError:
                yield changed


@pytest.mark.parametrize("form", ["link frames", "as drawn"])
def test_every_refusal_of_a_changed_value_is_marked(pseudo, tmp_path, capsys, form):
    """Each value of the compressor's file (in either form) removed or replaced by a value of
    another kind: every refusal of the reader is marked."""
    tables = tomllib.loads(BASE)
    if form == "as drawn":
        tables = convert_tables(tables, to="drawn")
    path = tmp_path / "changed.toml"
    problems, seen = [], 0
    for changed in _refused_variants(tables):
        path.write_text(to_toml(changed), encoding="utf-8")
        line = _error_line(capsys, ["solve", path])
        seen += 1
        if _unmarked(line, path, pseudo):
            problems.append(line)
    assert seen > 50 and not problems, "\n".join(problems[:20])


@pytest.mark.parametrize("file", sorted(path.name for path in (ROOT / "exercises").glob("*.toml")))
def test_the_structural_analysis_is_marked(pseudo, file):
    mechanism = load_exercise(ROOT / "exercises" / file).mechanism
    structure = analyse_structure(mechanism)
    names = [*mechanism.links, *(link.replace("_", " ") for link in mechanism.links),
             *(point for link in mechanism.links.values() for point in link.points)]
    for numbers in (None, course_numbers(mechanism)):
        for line in describe(structure, numbers).splitlines():
            assert line.startswith("⟦") and line.endswith("⟧"), line
            assert unmarked_words(line, pseudo, names=names) == [], line
