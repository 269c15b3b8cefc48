"""Every command against careless and hostile input: malformed, wrong-typed, out-of-range,
huge, deeply nested, unreadable, unwritable, path-climbing. Each case must give exactly one
line on stderr (``planmethod…: error: …``), exit 2, no traceback, no numpy warning, and write
nothing anywhere: neither in the case's folder nor in the working directory.

The cases run the command line in-process (``planmethod.cli.main``); one runs it as a real
subprocess to prove the exit path. Each guard this module exercises was seen to fail it when
removed (e.g. without the sweep's angle bound, ``--step 1e-9`` is a MemoryError traceback).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from planmethod.cli import main

ROOT = Path(__file__).resolve().parent.parent
BASE = (ROOT / "exercises" / "compressor_slider_crank.toml").read_text(encoding="utf-8")
STUDY = ROOT / "exercises" / "fourbar_study.toml"
TABLE = ROOT / "exercises" / "conveyor_sixbar_table2.csv"
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"


def _replace(line_start: str, new_line: str) -> str:
    """The base exercise with the first line starting with ``line_start`` replaced."""
    lines = BASE.splitlines()
    index = next(i for i, line in enumerate(lines) if line.startswith(line_start))
    return "\n".join([*lines[:index], new_line, *lines[index + 1:]]) + "\n"


#: bad exercise files: name → file content (bytes or text); every exercise-reading command
#: gets each of them
BAD_EXERCISES: dict[str, str | bytes] = {
    "empty": "",
    "binary": bytes(range(256)) * 40,
    "not TOML": "title = \n[[[",
    "key twice": 'title = "a"\ntitle = "b"\n',
    "no links": 'title = "x"\n[drive]\nlink = "AB"\npivot = "A"\nangle = 0\nomega = 1\n',
    "omega a string": _replace("omega", 'omega = "fast"'),
    "omega huge": _replace("omega", "omega = -1e300"),
    "omega huge integer": _replace("omega", "omega = -" + "9" * 400),
    "omega nan": _replace("omega", "omega = nan"),
    "angle huge": _replace("angle", "angle = 1e300"),
    "angle inf": _replace("angle", "angle = inf"),
    "epsilon huge": _replace("epsilon", "epsilon = 1e30") if "\nepsilon" in BASE
    else BASE.replace("omega", "epsilon = 1e30\nomega", 1),
    "nested 5000 deep": "x = " + "[" * 5000 + "1" + "]" * 5000 + "\n",
    "nested tables": "x = " + "{a = " * 3000 + "1" + "}" * 3000 + "\n",
    "utf-16": BASE.encode("utf-16"),
}

EXERCISE_COMMANDS = {
    "solve": lambda f, out: ["solve", f],
    "solve --json": lambda f, out: ["solve", f, "--json"],
    "sweep": lambda f, out: ["sweep", f, "--step", "30", "--csv", str(out / "t.csv")],
    "check": lambda f, out: ["check", f, str(TABLE)],
    "study": lambda f, out: ["study", f, "--step", "30"],
    "variants": lambda f, out: ["variants", f, "--out", str(out / "run"), "--no-sheets"],
    "grade": lambda f, out: ["grade", f, str(out / "answers.csv")],
    "workbook": lambda f, out: ["workbook", f, "-o", str(out / "page.html"), "--step", "90"],
    "animate": lambda f, out: ["animate", f, "-o", str(out / "turn.svg"), "--step", "90"],
    "convert": lambda f, out: ["convert", f, "-o", str(out / "converted.toml")],
}


def _run(capsys, argv, folder: Path) -> str:
    """Run ``argv`` in-process; return the one error line, after checking the contract."""
    before = {p for p in folder.rglob("*")}
    cwd_before = set(Path.cwd().iterdir())
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 2, (argv, code, out[-300:], err[-300:])
    assert "Traceback" not in err + out and "Warning" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("planmethod") and ": error: " in lines[0], err
    assert {p for p in folder.rglob("*")} == before, "a file was written"
    assert set(Path.cwd().iterdir()) == cwd_before, "a file was written in the working folder"
    return lines[0]


@pytest.fixture
def folder(tmp_path) -> Path:
    (tmp_path / "answers.csv").write_text("student,v_C\ns1,5\n")
    return tmp_path


@pytest.mark.parametrize("command", list(EXERCISE_COMMANDS))
@pytest.mark.parametrize("case", list(BAD_EXERCISES))
def test_a_bad_exercise_file(capsys, folder, command, case):
    content = BAD_EXERCISES[case]
    path = folder / "bad.toml"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    line = _run(capsys, EXERCISE_COMMANDS[command](path, folder), folder)
    assert "bad.toml" in line


@pytest.mark.parametrize("command", list(EXERCISE_COMMANDS))
@pytest.mark.parametrize("case", ["missing", "a folder"])
def test_an_exercise_that_is_not_a_file(capsys, folder, command, case):
    path = folder / "none.toml"
    if case == "a folder":
        path.mkdir()
    _run(capsys, EXERCISE_COMMANDS[command](path, folder), folder)


GOOD = str(ROOT / "exercises" / "compressor_slider_crank.toml")
FORCES = str(ROOT / "exercises" / "fourbar_forces.toml")

OPTION_CASES = {
    "solve --angle inf": ["solve", GOOD, "--angle", "inf"],
    "solve --angle nan": ["solve", GOOD, "--angle", "nan"],
    "solve --angle text": ["solve", GOOD, "--angle", "ten"],
    "solve --precision -1": ["solve", GOOD, "--precision", "-1"],
    "solve unknown option": ["solve", GOOD, "--colour", "red"],
    "solve no file": ["solve"],
    "sweep --step 0": ["sweep", GOOD, "--step", "0"],
    "sweep --step -5": ["sweep", GOOD, "--step", "-5"],
    "sweep --step 1e-9": ["sweep", GOOD, "--step", "1e-9"],
    "sweep --step nan": ["sweep", GOOD, "--step", "nan"],
    "sweep --from -1e300": ["sweep", GOOD, "--from", "-1e300"],
    "sweep --to < --from": ["sweep", GOOD, "--from", "90", "--to", "10"],
    "sweep --forces without forces": ["sweep", GOOD, "--forces"],
    "sweep --plot .txt": ["sweep", GOOD, "--plot", "{out}/c.txt"],
    "sweep --plot no suffix": ["sweep", GOOD, "--plot", "{out}/curves"],
    "sweep --csv in /proc": ["sweep", GOOD, "--step", "90", "--csv", "/proc/x.csv"],
    "sweep --csv in a missing root folder": ["sweep", GOOD, "--step", "90", "--csv",
                                             "/proc/nope/x.csv"],
    "solve --svg in /proc": ["solve", GOOD, "--svg", "/proc/planmethod-figures"],
    "study --weights 1:1e9:1": ["study", str(STUDY), "--weights", "1:1e9:1"],
    "study --weights text": ["study", str(STUDY), "--weights", "heavy"],
    "study --step 0": ["study", str(STUDY), "--step", "0"],
    "study --plot .txt": ["study", str(STUDY), "--plot", "{out}/s.txt"],
    "study --csv in /proc": ["study", str(STUDY), "--step", "90", "--csv", "/proc/s.csv"],
    "variants --count 0": ["variants", str(TEMPLATE), "--count", "0", "--out", "{out}/v"],
    "variants --count huge": ["variants", str(TEMPLATE), "--count", "100000000", "--out",
                              "{out}/v"],
    "variants --count text": ["variants", str(TEMPLATE), "--count", "many", "--out", "{out}/v"],
    "variants missing roster": ["variants", str(TEMPLATE), "--students", "{out}/none.csv",
                                "--out", "{out}/v"],
    "variants into /proc": ["variants", str(TEMPLATE), "--count", "1", "--out", "/proc/v"],
    "grade nothing to grade": ["grade", GOOD],
    "grade missing answers": ["grade", GOOD, "{out}/none.csv"],
    "grade --json in /proc": ["grade", GOOD, "{out}/answers.csv", "--json", "/proc/g.json"],
    "export unknown format": ["export", GOOD, "--format", "blackboard", "--out", "{out}/x"],
    "export slug ../": ["export", GOOD, "--format", "prairielearn", "--out", "{out}/pl",
                        "--slug", "../../x"],
    "export slug empty": ["export", GOOD, "--format", "prairielearn", "--out", "{out}/pl",
                          "--slug", ""],
    "export slug absolute": ["export", GOOD, "--format", "prairielearn", "--out", "{out}/pl",
                             "--slug", "/tmp/evil"],
    "export moodle into /proc": ["export", GOOD, "--format", "moodle", "--out",
                                 "/proc/quiz.xml"],
    "export csv without answers": ["export", GOOD, "--format", "csv", "--out", "{out}/g.csv"],
    "check missing table": ["check", str(ROOT / "exercises" / "conveyor_sixbar.toml"),
                            "{out}/none.csv"],
    "unknown command": ["draw", GOOD],
    "workbook --step 1e-9": ["workbook", GOOD, "-o", "{out}/w.html", "--step", "1e-9"],
    "workbook --step 0": ["workbook", GOOD, "-o", "{out}/w.html", "--step", "0"],
    "workbook -o .txt": ["workbook", GOOD, "-o", "{out}/w.txt"],
    "workbook into /proc": ["workbook", GOOD, "-o", "/proc/w.html", "--step", "90"],
    "animate --step 1e-9": ["animate", GOOD, "-o", "{out}/a.svg", "--step", "1e-9"],
    "animate -o .txt": ["animate", GOOD, "-o", "{out}/a.txt"],
    "animate into /proc": ["animate", GOOD, "-o", "/proc/a.svg", "--step", "90"],
}


@pytest.mark.parametrize("case", list(OPTION_CASES))
def test_a_bad_option_or_output(capsys, folder, case):
    argv = [a.replace("{out}", str(folder)) for a in OPTION_CASES[case]]
    _run(capsys, argv, folder)


ANSWER_FILES: dict[str, str | bytes] = {
    "deep JSON": "[" * 100_000 + "]" * 100_000,
    "binary": bytes(range(256)) * 10,
    "a student twice": "student,v_C\ns1,5\ns1,6\n",
    "rows without a student column": "v_C,a_C\n5,400\n6,410\n",
    "JSON of a number": "12",
    "no student id": "student,v_C\n,5\n",
}


@pytest.mark.parametrize("case", list(ANSWER_FILES))
def test_a_bad_answers_file(capsys, folder, case):
    content = ANSWER_FILES[case]
    path = folder / ("answers.json" if case.endswith("JSON") or "JSON" in case
                     else "bad_answers.csv")
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    _run(capsys, ["grade", GOOD, path, "--json", folder / "out.json"], folder)


def test_the_error_path_of_a_real_process(tmp_path):
    """The same contract through the installed entry point: exit status 2, one stderr line,
    nothing on stdout, no file."""
    done = subprocess.run([sys.executable, "-m", "planmethod", "sweep", FORCES, "--step",
                           "1e-12", "--csv", str(tmp_path / "t.csv")],
                          capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert done.returncode == 2 and not done.stdout
    assert len(done.stderr.strip().splitlines()) == 1 and "at most" in done.stderr
    assert list(tmp_path.iterdir()) == []


def test_there_are_more_than_eighty_cases():
    count = (len(BAD_EXERCISES) * len(EXERCISE_COMMANDS) + 2 * len(EXERCISE_COMMANDS)
             + len(OPTION_CASES) + len(ANSWER_FILES) + 1)
    assert count >= 80
    json.dumps(count)


def test_sigterm_leaves_no_temporary_file(tmp_path):
    """kill -TERM during a long sweep --csv: exit 143 and no hidden temporary file left."""
    import signal
    import time

    process = subprocess.Popen([sys.executable, "-m", "planmethod", "sweep", GOOD, "--step",
                                "0.0001", "--csv", str(tmp_path / "t.csv")], cwd=ROOT,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    def writing() -> bool:   # the temporary file exists and rows are being written into it
        try:
            return any(path.stat().st_size > 0 for path in tmp_path.iterdir())
        except FileNotFoundError:
            return False

    while not writing() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert writing(), "the sweep never started writing"
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 143 and err.strip() == "planmethod: terminated"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("svg", [
    '<svg xmlns="http://www.w3.org/2000/svg" width="0mm" height="100mm" viewBox="0 0 0 100">'
    '<circle cx="1" cy="1" r="1"/><text x="2" y="2">b</text></svg>',
    '<svg xmlns="http://www.w3.org/2000/svg" width="-100mm" height="100mm">'
    '<circle cx="1" cy="1" r="1"/><text x="2" y="2">b</text></svg>',
    '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
    'viewBox="0 0 100 100"><g transform="scale(0)"><circle cx="1" cy="1" r="1"/>'
    '<text x="2" y="2">b</text></g></svg>',
    '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" '
    'viewBox="0 0 100 100"><g transform="matrix(1 2 2 4 0 0)"><circle cx="1" cy="1" r="1"/>'
    '</g></svg>',
])
def test_a_degenerate_drawing_is_refused(capsys, folder, svg):
    path = folder / "plan.svg"
    path.write_text(svg)
    line = _run(capsys, ["grade", GOOD, "--drawing", path, "--plan", "velocity"], folder)
    assert "plan.svg" in line and ("size" in line or "singular" in line)


def test_variants_never_mixes_two_runs(capsys, tmp_path):
    out = tmp_path / "run"
    argv = ["variants", str(TEMPLATE), "--out", str(out), "--no-sheets", "--count"]
    assert main([*argv, "3"]) == 0
    line = _run(capsys, [*argv, "2"], tmp_path)          # not empty, no --force
    assert "not empty" in line
    assert main([*argv, "2", "--force"]) == 0             # replaces the earlier run
    assert sorted(p.name for p in out.iterdir()) == ["001", "002", "index.csv", "keys.json",
                                                     "manifest.json"]
    (out / "notes.txt").write_text("mine")
    line = _run(capsys, [*argv, "2", "--force"], tmp_path)
    assert "notes.txt" in line and (out / "notes.txt").read_text() == "mine"
