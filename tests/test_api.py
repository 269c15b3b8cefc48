"""The Python API (``planmethod.load`` …): reachable from the top level, loaded only when used,
typed, and giving what the command line writes — the same report, figures and JSON, the same
grades and variants."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from test_import_light import heavy_after, run_fresh

import planmethod
from planmethod.application.tasks import CancelledError, Watch
from planmethod.cli import main
from planmethod.errors import SpecError

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"
FORCES = ROOT / "exercises" / "fourbar_forces.toml"
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"


def test_import_planmethod_loads_the_api_only_when_it_is_used():
    code = ("import sys, planmethod\n"
            "print('planmethod.application' in sys.modules, 'numpy' in sys.modules)\n"
            "planmethod.load\n"
            "print('planmethod.application.api' in sys.modules)\n")
    assert run_fresh(code).split() == ["False", "False", "True"]
    # solving through the API, plans and report as data, loads no drawing library
    assert heavy_after("import planmethod\n"
                       "solution = planmethod.load('exercises/compressor_slider_crank.toml')"
                       ".solve(60)\nsolution.as_dict(); solution.report(); solution.plans\n") == []


def test_the_top_level_names_the_api_and_nothing_else():
    assert {"load", "parse", "Exercise", "Solution"} <= set(dir(planmethod))
    assert planmethod.Exercise is planmethod.load(COMPRESSOR).__class__
    with pytest.raises(AttributeError, match="no attribute 'solve'"):
        planmethod.solve   # noqa: B018


@pytest.mark.parametrize(("path", "options"), [(COMPRESSOR, []),
                                               (FORCES, ["--angle", "200", "--precision", "0.5"])])
def test_a_solution_is_what_solve_writes(capsys, tmp_path, path, options):
    """The report, the figures and the JSON report of ``solve`` at the same angle and
    precision, byte for byte."""
    angle = float(options[1]) if options else None
    precision = float(options[3]) if options else None
    solution = planmethod.load(path).solve(angle, precision_mm=precision)
    assert main(["solve", str(path), "--json", *options]) == 0
    written = capsys.readouterr().out
    assert written == json.dumps(solution.as_dict(), ensure_ascii=False, indent=2,
                                 allow_nan=False) + "\n"
    assert main(["solve", str(path), "--svg", str(tmp_path), *options]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith(solution.report() + "\n\nWrote ")
    figures = solution.svg()
    assert sorted(f"{name}.svg" for name in figures) == sorted(p.name for p in tmp_path.iterdir())
    for name, text in figures.items():
        assert (tmp_path / f"{name}.svg").read_text(encoding="utf-8") == text
        assert solution.svg(name) == text
    assert solution.plans.velocity.pole == "p" and solution.checks
    assert (solution.forces is not None) == (path == FORCES)
    with pytest.raises(SpecError, match="no figure 'speed'"):
        solution.svg("speed")


def test_grading_through_the_api_is_grade_at_the_command_line(tmp_path):
    """One student's answers graded as ``planmethod grade EXERCISE ANSWERS --json``."""
    exercise = planmethod.load(COMPRESSOR)
    answers = {"v_C": "5.27", "a_C": "300", "omega_BC": "-24.25"}
    graded = exercise.grade(answers)
    table = tmp_path / "answers.csv"
    table.write_text("student," + ",".join(answers) + "\n1," + ",".join(answers.values())
                     + "\n", encoding="utf-8")
    out = tmp_path / "graded.json"
    assert main(["grade", str(COMPRESSOR), str(table), "--json", str(out), "--quiet"]) == 0
    assert json.loads(out.read_text(encoding="utf-8"))["answers"] == [graded.as_dict()]
    verdicts = {q.id: q.correct for q in graded.questions}
    assert verdicts["v_C"] and not verdicts["a_C"] and verdicts["omega_BC"]
    assert exercise.key()["questions"] == graded_key_questions(COMPRESSOR)


def graded_key_questions(path: Path) -> list:
    from planmethod.application.grades import load_any_key

    return load_any_key(str(path))["*"]["questions"]


def test_variants_written_through_the_api_are_those_of_the_command(tmp_path):
    template = planmethod.load(str(TEMPLATE.relative_to(ROOT)))
    assert template.is_template and template.model is None
    with pytest.raises(SpecError, match="draw its variants"):
        template.solve()
    drawn = template.variants(3, seed=7)
    assert [variant.student for variant in drawn.variants] == ["001", "002", "003"]
    assert drawn.write(tmp_path / "api") is None
    assert main(["variants", str(TEMPLATE.relative_to(ROOT)), "--count", "3", "--seed", "7",
                 "--out", str(tmp_path / "cli")]) == 0
    api_files = {p.relative_to(tmp_path / "api"): p.read_bytes()
                 for p in (tmp_path / "api").rglob("*") if p.is_file()}
    cli_files = {p.relative_to(tmp_path / "cli"): p.read_bytes()
                 for p in (tmp_path / "cli").rglob("*") if p.is_file()}
    assert api_files == cli_files and len(api_files) > 10
    with pytest.raises(SpecError, match="not empty"):
        drawn.write(tmp_path / "api")
    assert drawn.write(tmp_path / "api", force=True) is None


def test_a_workbook_through_the_api_is_the_commands(tmp_path):
    page = planmethod.load(COMPRESSOR).workbook(120)
    assert main(["workbook", str(COMPRESSOR), "-o", str(tmp_path / "w.html"), "--step", "120",
                 "--jobs", "1"]) == 0
    assert (tmp_path / "w.html").read_text(encoding="utf-8") == page


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_long_use_case_is_cancelled_between_two_steps(jobs):
    """A watch hears each frame, and a cancel ends the page at the next one."""
    from planmethod.application.workbook import build_workbook

    heard = []

    def tell(phase: str, done: int, total: int) -> None:
        heard.append((phase, done, total))
        watch.cancel()

    watch = Watch(tell)
    exercise = planmethod.load(COMPRESSOR).model
    with pytest.raises(CancelledError):
        build_workbook(exercise, 10.0, jobs=jobs, watch=watch)
    assert heard and heard[0][0] == "frames" and heard[0][2] == 36 and len(heard) == 1
    assert watch.cancelled


def test_variants_are_cancelled_between_two_students():
    heard = []
    watch = Watch(lambda *step: (heard.append(step), watch.cancel()))
    with pytest.raises(CancelledError):
        planmethod.load(TEMPLATE).variants(5, sheets=False, watch=watch)
    assert heard == [("variants", 1, 5)]


def test_a_bad_language_given_to_the_api_is_refused():
    exercise = planmethod.load(COMPRESSOR, language="x y")
    with pytest.raises(SpecError, match=r"^language: 'x y' is no language code"):
        exercise.solve()
