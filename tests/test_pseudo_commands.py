"""Every line a command prints goes through the catalogue: under the pseudo language ``qps``
(every message marked ⟦…⟧, :mod:`planmethod.testing.pseudo`) no English word of the messages
shows outside the marks — in the commands' reports, summaries, "Wrote …" lines, errors, help
texts and argparse's own lines, and in the studio's answers.

What other areas still make as plain text is left out, each by name (the texts are computed
here, in the same language, and not counted): the structural analysis
(``structure.describe``), the scales (``Scales.describe``), the force analysis and the note
on an undrawn combined force (``ForceAnalysis.describe``, ``combined_omitted``), the sweep's
extremes table (``Extremes.describe``), the study's labels, base case and conclusions
(``forces.study``), the reasons of rejected draws counted by ``variants``, the assembly's
branch reasons and errors (kinematics), the vocabulary's link texts (``link_text``), units
and titles. When those areas speak through the catalogue, these exclusions only remove marked
text.
"""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod.testing.pseudo import PSEUDO, message_words, pseudo_catalogue, unmarked_words
from planmethod.words import language

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = ROOT / "exercises"
COMPRESSOR = EXERCISES / "compressor_slider_crank.toml"
FORCES = EXERCISES / "fourbar_forces.toml"
STUDY = EXERCISES / "fourbar_study.toml"
CONVEYOR = EXERCISES / "conveyor_sixbar.toml"
TABLE = EXERCISES / "conveyor_sixbar_table2.csv"
TEMPLATE = EXERCISES / "templates" / "slider_crank.toml"
ANSWERS = EXERCISES / "templates" / "slider_crank_answers_example.csv"
COMMANDS = ("solve", "sweep", "variants", "grade", "export", "check", "study", "workbook",
            "animate", "convert", "studio")


# -- run in a fresh process that speaks the pseudo language ---------------------------------------
class _Probe:
    """The cases, run in this process (``PLANMETHOD_LANG=qps``): each command's output and
    the texts other areas make in it."""

    def __init__(self, work: Path) -> None:
        self.work = work
        self.cases: list[dict] = []

    def run(self, name: str, argv: list, foreign: list[str] = ()) -> None:
        from planmethod.cli import main

        out, err = io.StringIO(), io.StringIO()
        with redirect_stdout(out), redirect_stderr(err):
            code = main([str(argument) for argument in argv])
        self.cases.append({"name": name, "code": code, "out": out.getvalue(),
                           "err": err.getvalue(), "foreign": [t for t in foreign if t]})


def _names(exercise) -> list[str]:
    """An exercise's names: title, links, points (no words of the messages)."""
    from planmethod.vocabulary import shown_title

    mechanism = exercise.mechanism
    return [mechanism.title, shown_title(mechanism.title), *mechanism.links,
            *(point for link in mechanism.links.values() for point in link.points)]


def _solve_foreign(path: Path) -> list[str]:
    from planmethod.numbering import course_numbers
    from planmethod.render.force_svg import combined_omitted
    from planmethod.render.notation import ForceNotation
    from planmethod.report import analyse
    from planmethod.spec import load_exercise
    from planmethod.structure import describe
    from planmethod.words import render

    exercise = load_exercise(path)
    analysis = analyse(exercise)
    numbers = course_numbers(exercise.mechanism)
    texts = [*_names(exercise), exercise.published_source or ""]
    texts += describe(analysis.structure, numbers).splitlines()
    texts += [str(branch.reason) for branch in analysis.motion.branches.values()]
    texts += analysis.plans.scales.describe() if analysis.plans else []
    texts += [render(check.unit) for check in analysis.checks if "rad" in render(check.unit)]
    texts += [render(flag) for flag in analysis.flags]
    if analysis.forces is not None:
        texts += analysis.forces.describe(ForceNotation(analysis.forces.solution)).splitlines()
        texts.append(combined_omitted(analysis.forces, analysis.plans) or "")
    return texts


def _sweep_foreign(path: Path, step: float, forces: bool) -> list[str]:
    from planmethod.application.sweeping import SweepRequest, sweep
    from planmethod.spec import load_exercise

    return sweep(load_exercise(path), SweepRequest(step=step, forces=forces)).summary.splitlines()


def _check_foreign() -> list[str]:
    from planmethod.application.checking import check_table
    from planmethod.numbering import course_numbers
    from planmethod.spec import load_exercise
    from planmethod.vocabulary import link_text

    exercise = load_exercise(CONVEYOR)
    numbers = course_numbers(exercise.mechanism)
    found = check_table(exercise, str(TABLE), 2.0)
    texts = [*_names(exercise), *(link_text(link, numbers) for link in exercise.mechanism.links)]
    for row in found.rows:
        texts += [row.branch or "", str(row.assembly_error or "")]
    return texts


def _study_foreign() -> list[str]:
    from planmethod.application.studying import _printed_names
    from planmethod.forces.study import run_study
    from planmethod.spec import load_exercise

    exercise = load_exercise(STUDY)
    study = run_study(exercise, weights=(20.0, 40.0), omegas=(10.0, 20.0),
                      moments=(80.0, 100.0), step=30.0)
    names, rocker = _printed_names(exercise, study)
    texts = [*_names(exercise), study.base_text(), rocker, *names.values()]
    texts += [f"{p.label} ({p.unit})" for p in study.parameters]
    for statement, _, evidence in study.conclusions(names):
        texts += [statement, evidence]
    return texts


def _variants_foreign(out: str) -> list[str]:
    return [line.strip() for line in out.splitlines() if "×" in line]


def _commands(probe: _Probe) -> None:
    work = probe.work
    for command in ("", *COMMANDS):
        probe.run(f"help {command}".strip(), [command, "--help"] if command else ["--help"])
    probe.run("solve", ["solve", COMPRESSOR, "--svg", work / "svg"], _solve_foreign(COMPRESSOR))
    probe.run("solve forces", ["solve", FORCES, "--svg", work / "forces"], _solve_foreign(FORCES))
    probe.run("sweep", ["sweep", COMPRESSOR, "--step", "30", "--csv", work / "s.csv"],
              _sweep_foreign(COMPRESSOR, 30.0, False))
    probe.run("sweep forces", ["sweep", FORCES, "--step", "30", "--forces", "--csv",
                               work / "f.csv"],
              _sweep_foreign(FORCES, 30.0, True))
    probe.run("check", ["check", CONVEYOR, TABLE], _check_foreign())
    probe.run("study", ["study", STUDY, "--weights", "20,40", "--omegas", "10,20", "--moments",
                        "80,100", "--step", "30", "--csv", work / "study.csv"], _study_foreign())
    probe.run("variants", ["variants", TEMPLATE, "--count", "3", "--seed", "7", "--out",
                           work / "course"])
    probe.cases[-1]["foreign"] = _variants_foreign(probe.cases[-1]["out"])
    keys = work / "course" / "keys.json"
    probe.run("grade", ["grade", keys, ANSWERS])
    drawing = _drawing(work)
    probe.run("grade drawing", ["grade", COMPRESSOR, "--drawing", drawing])
    probe.run("export", ["export", keys, "--format", "moodle", "--out", work / "quiz.xml"])
    probe.run("export folder", ["export", keys, "--format", "gradescope", "--out", work / "gs"])
    probe.run("workbook", ["workbook", COMPRESSOR, "-o", work / "w.html", "--step", "120"])
    probe.run("animate", ["animate", COMPRESSOR, "-o", work / "a.svg", "--step", "120"])


def _drawing(work: Path) -> Path:
    """A drawn velocity plan, its points off: graded with feedback."""
    path = work / "drawn.json"
    path.write_text(json.dumps({"plan": "velocity", "points": {"p": [0, 0], "b": [10, 20],
                                                                "c": [25, 1]}}),
                    encoding="utf-8")
    return path


def _errors(probe: _Probe) -> None:
    """Lines of refusal that the commands and argparse make."""
    work = probe.work
    for name, argv in [
            ("no command", ["nosuch"]), ("missing file", ["solve"]),
            ("bad choice", ["grade", "k.json", "--plan", "x"]),
            ("bad float", ["solve", COMPRESSOR, "--angle", "x"]),
            ("unrecognized", ["check", CONVEYOR, TABLE, "--nosuch"]),
            ("bad grid", ["study", STUDY, "--weights", "1:2"]),
            ("bad seed", ["variants", TEMPLATE, "--out", work / "x", "--seed", "abc"]),
            ("precision", ["solve", COMPRESSOR, "--precision", "-1"]),
            ("angle", ["solve", COMPRESSOR, "--angle", "1e9"]),
            ("tolerance", ["check", CONVEYOR, TABLE, "--tolerance", "0"]),
            ("count", ["variants", TEMPLATE, "--count", "0", "--out", work / "c0"]),
            ("grade nothing", ["grade", COMPRESSOR]),
            ("page", ["workbook", COMPRESSOR, "-o", work / "w.txt"]),
            ("jobs", ["workbook", COMPRESSOR, "-o", work / "w.html", "--jobs", "100000"]),
            ("step", ["workbook", COMPRESSOR, "-o", work / "w.html", "--step", "0"]),
            ("animation", ["animate", COMPRESSOR, "-o", work / "a.avi"]),
            ("csv answers", ["export", COMPRESSOR, "--format", "csv", "--out", work / "g.csv"]),
            ("studio port", ["studio", "--port", "70000"])]:
        probe.run(name, argv)


def _studio(probe: _Probe) -> None:
    """The studio's answers to refused requests: each one line, in the language spoken."""
    import http.client

    from planmethod.studio.server import HOST, StudioServer

    folder = probe.work / "studio"
    folder.mkdir()
    (folder / "gone.toml").symlink_to(folder / "nowhere.toml")
    server = StudioServer(folder, 0)
    server.start()

    def ask(method: str, path: str, body=None, token: bool = True) -> str:
        connection = http.client.HTTPConnection(HOST, server.port, timeout=60)
        headers = {"Host": f"{HOST}:{server.port}", "Content-Type": "application/json"}
        if token:
            headers["X-Planmethod-Token"] = server.token
        data = None if body is None else json.dumps(body).encode()
        connection.request(method, path, body=data, headers=headers)
        answer = connection.getresponse().read().decode()
        connection.close()
        return answer

    text = COMPRESSOR.read_text(encoding="utf-8")
    try:
        answers = [ask("GET", "/api/files", token=False), ask("GET", "/api/nosuch"),
                   ask("POST", "/api/save", {"path": "a.toml", "toml": text,
                                             "overwrite": "false"}),
                   ask("POST", "/api/save", {"path": "a.toml", "toml": text, "nosuch": 1}),
                   ask("POST", "/api/open", {"path": "/abs.toml"}),
                   ask("POST", "/api/save", {"path": "a.toml", "toml": text, "ranges": {}}),
                   ask("POST", "/api/variants", {"toml": text, "count": 999}),
                   ask("POST", "/api/variants", {"toml": text, "ranges": {
                       "lengths": {"nosuch": [1, 2]}}}),
                   ask("POST", "/api/export", {"toml": text, "folder": "x", "count": 0}),
                   ask("GET", "/api/job?id=zzz"), ask("GET", "/api/files")]
    finally:
        server.stop()
    # what a person reads of an answer: its error line, and why a file is not listed (the
    # keys of the JSON and of the request are the page's, not words)
    said = [json.loads(answer) for answer in answers]
    shown = [answer["error"] for answer in said if "error" in answer]
    shown += [skipped["why"] for answer in said for skipped in answer.get("skipped", ())]
    probe.cases.append({"name": "studio", "code": 0, "out": "\n".join(shown), "err": "",
                        "foreign": ["count", "path", "ranges.lengths.nosuch", "overwrite",
                                    "nosuch", "ranges"]})


def probe(work: str) -> None:
    """Run every case and print them as JSON (in a process with ``PLANMETHOD_LANG=qps``)."""
    found = _Probe(Path(work))
    _commands(found)
    _errors(found)
    _studio(found)
    print(json.dumps(found.cases, ensure_ascii=False))


# -- the test -------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def cases(tmp_path_factory) -> dict[str, dict]:
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    work = tmp_path_factory.mktemp("work")
    env = {**os.environ, language.LOCALE_ENVIRONMENT: str(folder),
           language.ENVIRONMENT: PSEUDO, "COLUMNS": "100"}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), str(ROOT / "tests"),
                                         *filter(None, [env.get("PYTHONPATH")])])
    done = subprocess.run([sys.executable, "-c", "import test_pseudo_commands as t; "
                           f"t.probe({str(work)!r})"], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    return {case["name"]: case for case in json.loads(done.stdout.splitlines()[-1])}


#: what a command line shows that is no word: option strings, choices, command names, the
#: program's name, the environment variable, file formats and the keys an error names
NOT_WORDS = ["planmethod", "PLANMETHOD_LANG", "[course]", "drive.angle", "precision_mm",
             "[plan]", "[[load]]", "manifest.json", "results.json", "quiz.xml",
             "gradebook.csv", "questions.csv", "mistakes.csv", "class_report.png",
             "option --angle", "option --jobs", "option --step", "option -o", "--nosuch",
             *COMMANDS, "velocity,acceleration", "full,hints,score", "drawn,frames",
             "gradescope,prairielearn,moodle,csv", "'velocity', 'acceleration'"]


def _option_strings() -> list[str]:
    from planmethod.cli import _parser

    parser = _parser()
    found = [option for action in parser._actions for option in action.option_strings]
    for sub in parser._subparsers._group_actions[0].choices.values():
        found += [option for action in sub._actions for option in action.option_strings]
    return sorted(set(found), key=len, reverse=True)


@pytest.mark.parametrize("name", [
    "help", *(f"help {command}" for command in COMMANDS), "solve", "solve forces", "sweep",
    "sweep forces", "check", "study", "variants", "grade", "grade drawing", "export",
    "export folder", "workbook", "animate", "no command", "missing file", "bad choice",
    "bad float", "unrecognized", "bad grid", "bad seed", "precision", "angle", "tolerance",
    "count", "grade nothing", "page", "jobs", "step", "animation", "csv answers",
    "studio port", "studio"])
def test_every_line_a_command_prints_is_marked(cases, name):
    case = cases[name]
    shown = case["out"] + case["err"]
    assert shown.strip(), f"{name}: printed nothing"
    assert "⟦" in shown, f"{name}: nothing of it came from the catalogue:\n{shown}"
    names = [*case["foreign"], *NOT_WORDS, *_option_strings(), str(ROOT)]
    left = unmarked_words(shown, message_words(), names=names)
    assert left == [], f"{name}: English outside the catalogue: {left}\n{shown}"


def test_the_probe_finds_english_outside_the_marks(cases):
    """The check can fail: the same output with a mark taken off shows its words."""
    shown = cases["variants"]["out"]
    assert unmarked_words(shown.replace("⟦", "", 1).replace("⟧", "", 1), message_words(),
                          names=NOT_WORDS + _option_strings() + [str(ROOT)])
