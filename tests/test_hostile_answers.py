"""Hostile input that was read without a word (issue 24): numbers a reader cannot take
(subnormal coordinates, 5,000-digit whole numbers, a drawn label at ``x="NaN"``), answers files
that lose or merge students, study options beyond the limits, spreadsheet formulas in the CSV
files planmethod writes, and text that adds sub-questions to a Moodle Cloze quiz.

Every refused case gives one line on stderr (``planmethod…: error: …`` naming the file and the
line or key), exit 2, no traceback and nothing written. Each test was seen to fail without the
change it covers.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from planmethod.cli import main

ROOT = Path(__file__).resolve().parent.parent
GOOD = ROOT / "exercises" / "compressor_slider_crank.toml"
BASE = GOOD.read_text(encoding="utf-8")
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"
STUDY = ROOT / "exercises" / "fourbar_study.toml"
HUGE = "9" * 5000


def refused(capsys, argv, folder: Path) -> str:
    """Run ``argv`` in-process; return its one error line after checking the contract: exit
    2, one line, no traceback or warning, nothing written in ``folder``."""
    before = set(folder.rglob("*"))
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 2, (argv, code, out[-300:], err[-300:])
    assert "Traceback" not in err + out and "Warning" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("planmethod") and ": error: " in lines[0], err
    assert set(folder.rglob("*")) == before, "a file was written"
    return lines[0]


# -- numbers at reading ----------------------------------------------------------------------
EXERCISE_COMMANDS = {
    "solve": lambda f, out: ["solve", f],
    "workbook": lambda f, out: ["workbook", f, "-o", out / "page.html", "--step", "90"],
    "variants": lambda f, out: ["variants", f, "--out", out / "run", "--no-sheets"],
    "grade": lambda f, out: ["grade", f, out / "answers.csv"],
}

SUBNORMAL = {
    # a crank of 5e-324 m divided by zero (or gave +inf %) in solve, workbook and variants
    "a subnormal crank": ("B = [0.06, 0] }", "B = [5e-324, 0] }", "links.AB.B"),
    "a crank of 1e-300 m": ("B = [0.06, 0] }", "B = [1e-300, 0] }", "links.AB.B"),
    "a crank of 1e-9 m": ("B = [0.06, 0] }", "B = [1e-9, 0] }", "links.AB.B"),
    # two joints of one moving link 1e-10 m apart
    "joints 1e-10 m apart": ("C = [0.18, 0], D = [0.09, 0] }",
                             "C = [0.18, 0], D = [1e-10, 0] }\nCD = { D = [0, 0] }",
                             "links.BC.D"),
    "a 5,000-digit angle": ("angle = 45", f"angle = {HUGE}", "line "),
    "a hexadecimal number beyond 64 bits": ("angle = 45", "angle = 0x" + "f" * 5000,
                                            "drive.angle"),
}


@pytest.mark.parametrize("command", list(EXERCISE_COMMANDS))
@pytest.mark.parametrize("case", list(SUBNORMAL))
def test_numbers_out_of_range_are_refused_at_reading(capsys, tmp_path, command, case):
    old, new, where = SUBNORMAL[case]
    assert old in BASE
    path = tmp_path / "bad.toml"
    path.write_text(BASE.replace(old, new, 1), encoding="utf-8")
    (tmp_path / "answers.csv").write_text("student,v_C\ns1,5\n")
    line = refused(capsys, EXERCISE_COMMANDS[command](path, tmp_path), tmp_path)
    assert "bad.toml" in line and where in line, line
    assert ("at least 1e-08 m" in line) or ("64-bit" in line), line


@pytest.mark.parametrize(("old", "new"), [
    ("B = [0.06, 0] }", "B = [1e-8, 0] }"),             # the shortest crank in range
    ("B = [0.06, 0] }", "B = [0.06, 5e-324] }"),        # a subnormal coordinate: harmless
    ("A = [0, 0] }", "A = [0, 0], G = [0, -1e-309] }"),  # frame points: no length counts
    ("D = [0.09, 0] }", "D = [1e-300, 0] }"),           # a coupler point beside a joint
])
def test_what_lies_in_range_still_solves(capsys, tmp_path, old, new):
    """The new bound refuses only a moving link's length below 1e-8 m."""
    path = tmp_path / "ok.toml"
    path.write_text(BASE.replace(old, new, 1), encoding="utf-8")
    assert new in path.read_text()
    assert main(["solve", str(path)]) == 0
    capsys.readouterr()


def _key_files(tmp_path: Path) -> Path:
    assert main(["variants", str(GOOD), "--out", str(tmp_path / "run"), "--no-sheets"]) == 0
    return tmp_path / "run" / "keys.json"


def test_a_5000_digit_number_in_json_is_one_line_naming_its_key(capsys, tmp_path):
    keys = _key_files(tmp_path)
    capsys.readouterr()
    answers = tmp_path / "answers.json"
    answers.write_text('{"s1": {"v_C": 5}}')
    drawing = tmp_path / "plan.json"
    drawing.write_text('{"plan": "velocity", "points": {"p": [0, 0], "b": [' + HUGE + ", 1]}}")
    line = refused(capsys, ["grade", GOOD, "--drawing", drawing], tmp_path)
    assert "plan.json: points.b[0]: a whole number of 5000 digits" in line
    text = keys.read_text()
    keys.write_text(text.replace('"version": 1', '"version": ' + HUGE, 1))
    line = refused(capsys, ["grade", keys, answers], tmp_path)
    assert "keys.json: version: a whole number of 5000 digits" in line


@pytest.mark.parametrize("value", ["NaN", "inf", "-Infinity", "1e999"])
def test_a_drawn_label_at_a_coordinate_that_is_not_finite_is_refused(capsys, tmp_path, value):
    """A label at x="NaN" counted as a point at the pole."""
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
           'viewBox="0 0 100 100"><line x1="0" y1="0" x2="30" y2="10"/>'
           f'<text x="0" y="0">p</text><text x="{value}" y="0">b</text></svg>')
    path = tmp_path / "plan.svg"
    path.write_text(svg)
    line = refused(capsys, ["grade", GOOD, "--drawing", path, "--plan", "velocity"], tmp_path)
    assert f"plan.svg: <text> 'b': x='{value}' is not a finite number" in line


def test_a_polyline_with_a_point_that_is_not_a_number_is_refused(capsys, tmp_path):
    """``NaN`` among a polyline's points shifted every pair after it."""
    path = tmp_path / "plan.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
                    'viewBox="0 0 100 100"><polyline id="v" points="0 0 NaN 10 30 10"/>'
                    '<text x="0" y="0">p</text><text x="30" y="10">b</text></svg>')
    line = refused(capsys, ["grade", GOOD, "--drawing", path, "--plan", "velocity"], tmp_path)
    assert 'plan.svg: <polyline id="v">: points=' in line
