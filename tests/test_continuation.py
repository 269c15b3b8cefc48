"""One assembly for every angle: the assembly chosen at ``drive.angle`` (sketch or default
branch) is the one every entry point gives at any other crank angle — ``solve --angle`` (its
JSON report), the Python API (:func:`planmethod.report.analyse`, as the workbook and animate use
it), the workbook's frames — namely the one a sweep from ``drive.angle`` follows; where the way
from ``drive.angle`` to the angle meets a limit (toggle) position, the one-line error names the
group and the crank angle of the limit.
"""

from __future__ import annotations

import csv
import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from planmethod.cli import main
from planmethod.errors import PlanmethodError, ToggleError
from planmethod.kinematics import solve
from planmethod.kinematics.continuation import FOLLOW_STEP_DEG, follow, pose
from planmethod.report import analyse
from planmethod.spec import load_exercise
from planmethod.sweep import sweep_table
from planmethod.testing.stress import exercise_of, fourbar_case

ROOT = Path(__file__).resolve().parent.parent
SHIPPED = sorted((ROOT / "exercises").glob("*.toml"))
DATA = ROOT / "tests" / "data" / "continuation"
WHITWORTH = DATA / "whitworth_quick_return.toml"
ROCKER = DATA / "rocking_fourbar.toml"
#: the rocking four-bar's crank reaches its limits where |BD| = BC + CD: cos φ = −1/4
ROCKER_LIMIT = math.degrees(math.acos(-0.25))
#: the two ways of getting a quantity agree to this share of its kind's size
AGREE = 1e-9


def angles_of(drive: float) -> list[float]:
    """Twelve crank angles, every 30° away from ``drive.angle``: up to +180°, down to −150°
    (below zero for every shipped exercise), and one full turn further (past 360°)."""
    return ([drive + 30.0 * k for k in range(1, 7)] + [drive - 30.0 * k for k in range(1, 6)]
            + [drive + 360.0])


def run(capsys, *argv) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def cli_sweep_row(capsys, path: Path, angle: float, folder: Path) -> dict[str, float] | str:
    """The row of ``planmethod sweep`` at one crank angle, or its error line."""
    target = folder / "sweep.csv"
    code, _, err = run(capsys, "sweep", path, f"--from={angle!r}", f"--to={angle + 0.5!r}",
                       "--csv", target)
    if code:
        return err
    header, row = list(csv.reader(target.read_text(encoding="utf-8").splitlines()))
    return {name: float(value) if value else math.nan
            for name, value in zip(header, row, strict=True)}


def report_values(report: dict) -> dict[str, float]:
    """A JSON report's values under the sweep's column names (link angles as cos and sin)."""
    out = {}
    for point, entry in report["points"].items():
        for stage, prefix in (("position", ""), ("velocity", "v"), ("acceleration", "a")):
            if entry.get(stage) is not None:
                x, y = entry[stage]
                out[f"{prefix}x_{point}"], out[f"{prefix}y_{point}"] = x, y
    for link, entry in report["links"].items():
        for key in ("omega", "epsilon"):
            if entry.get(key) is not None:
                out[f"{key}_{link}"] = entry[key]
        out[f"cos_{link}"], out[f"sin_{link}"] = math.cos(entry["theta"]), math.sin(entry["theta"])
    for key, entry in (report.get("sliding") or {}).items():
        for name, column in (("s", "s"), ("velocity", "ds"), ("acceleration", "dds")):
            if entry.get(name) is not None:
                out[f"{column}_{key}"] = entry[name]
    return out


def sweep_values(row: dict[str, float]) -> dict[str, float]:
    out = dict(row)
    for name in row:
        if name.startswith("theta_"):
            link = name.removeprefix("theta_")
            out[f"cos_{link}"] = math.cos(math.radians(row[name]))
            out[f"sin_{link}"] = math.sin(math.radians(row[name]))
    return out


def kind(name: str) -> str:
    """The size class of a column: what its tolerance is relative to."""
    prefix = name.split("_")[0]
    return {"x": "position", "y": "position", "s": "position", "cos": "angle", "sin": "angle",
            "vx": "velocity", "vy": "velocity", "ds": "velocity", "omega": "omega",
            "ax": "acceleration", "ay": "acceleration", "dds": "acceleration",
            "epsilon": "epsilon"}[prefix]


def assert_same_assembly(found: dict[str, float], swept: dict[str, float], where: str) -> None:
    shared = [name for name in found if name in swept]
    assert any(name.startswith("x_") for name in shared), where
    sizes: dict[str, float] = {}
    for name in shared:
        sizes[kind(name)] = max(sizes.get(kind(name), 0.0), abs(found[name]), abs(swept[name]))
    for name in shared:
        limit = AGREE * max(sizes[kind(name)], 1e-300)
        assert abs(found[name] - swept[name]) <= limit, (
            f"{where}: {name} = {found[name]!r} against the sweep's {swept[name]!r}")


# -- every shipped exercise, every 30° ---------------------------------------------------------
@pytest.mark.parametrize("path", SHIPPED, ids=lambda path: path.stem)
def test_solve_angle_gives_the_sweeps_assembly(path, capsys, tmp_path):
    """``solve --angle X --json`` against ``sweep`` at X (the command line), and
    ``analyse(exercise, X)`` against ``sweep_table`` (the Python API), at twelve angles."""
    exercise = load_exercise(path)
    compared = 0
    for angle in angles_of(exercise.mechanism.drive.angle):
        where = f"{path.name} at {angle:g}°"
        code, out, err = run(capsys, "solve", path, f"--angle={angle!r}", "--json")
        row = cli_sweep_row(capsys, path, angle, tmp_path)
        try:
            analysis = analyse(exercise, angle, plans=False)
            table = sweep_table(exercise, angles=[angle])
        except PlanmethodError:
            analysis = table = None
        if code:   # refused: then the sweep refuses that angle too, and so does the API
            assert isinstance(row, str) and err.count("\n") == 1, where
            assert analysis is None, where
            continue
        assert not isinstance(row, str), f"{where}: the sweep refused: {row}"
        report = json.loads(out)
        assert report["angle"] == angle, where
        assert_same_assembly(report_values(report), sweep_values(row), f"{where} (CLI)")
        here = analysis.motion.at(0)
        from_api = report_values({"points": {p: {"position": list(here.position(p))}
                                             for p in report["points"]}, "links": {}})
        assert_same_assembly(from_api, {name: float(values[0]) for name, values in table.items()},
                             f"{where} (API)")
        compared += 1
    assert compared >= 10, f"{path.name}: only {compared} angles solved"


# -- the Whitworth quick-return: the sketch at 250° is nearer the other assembly ----------------
def lever_side(position_c, position_b, pivot=(0.0, -0.04)) -> float:
    """> 0 where the lever's end C lies on the crank pin B's side of the pivot O2 (the
    assembly the sketch picks at drive.angle = 30°), < 0 on the other."""
    return float(np.dot(np.subtract(position_c, pivot), np.subtract(position_b, pivot)))


def test_whitworth_sketch_would_pick_the_other_assembly_at_250():
    """Why the data file tests something: choosing again at 250° from the sketch made for 30°
    (what ``solve --angle 250`` did) takes the lever turned half a turn."""
    mechanism = load_exercise(WHITWORTH).mechanism
    chosen_there = replace(mechanism, drive=replace(mechanism.drive, angle=250.0))
    at_start = solve(mechanism).at(0)
    assert lever_side(at_start.position("C"), at_start.position("B")) > 0
    motion = solve(chosen_there).at(0)
    assert lever_side(motion.position("C"), motion.position("B")) < 0


def test_whitworth_every_entry_point_follows_the_sweep(capsys, tmp_path):
    from planmethod.application.workbook import solve_frames

    exercise = load_exercise(WHITWORTH)
    code, out, err = run(capsys, "solve", WHITWORTH, "--angle", "250", "--json")
    assert code == 0, err
    report = json.loads(out)
    row = cli_sweep_row(capsys, WHITWORTH, 250.0, tmp_path)
    assert_same_assembly(report_values(report), sweep_values(row), "solve --angle 250")
    position_c, position_b = report["points"]["C"]["position"], report["points"]["B@lever"][
        "position"]
    assert lever_side(position_c, position_b) > 0
    for angle in (250.0, 250.0 - 360.0, 250.0 + 720.0):
        analysis = analyse(exercise, angle)
        motion = analysis.motion
        here = motion.at(0)
        assert lever_side(here.position("C"), here.position("B")) > 0, angle
        assert motion.branches[0].sign == 1 and motion.branches[0].reason == "sketch"
    # the workbook's frame at 250° reads the same exact values as the sweep
    frame = solve_frames(exercise, [250.0])[0]
    exact = dict(zip((q for q, _ in frame["quantities"]),
                     (analytic for analytic, _ in frame["readings"]), strict=True))
    assert exact["v_C"] == pytest.approx(row["v_C"], rel=AGREE)
    assert exact["omega_lever"] == pytest.approx(row["omega_lever"], rel=AGREE)
    assert exact["a_D"] == pytest.approx(row["a_D"], rel=AGREE)


def test_whitworth_variant_at_another_angle_keeps_the_assembly():
    from planmethod.grading.templates import draw_variant, load_template, variant_exercise

    exercise = variant_exercise(draw_variant(load_template(WHITWORTH)), 250.0)
    motion = solve(exercise.mechanism).at(0)
    assert exercise.mechanism.drive.angle == 250.0
    assert lever_side(motion.position("C"), motion.position("B")) > 0


def test_whitworth_posed_mechanism_keeps_the_assembly():
    """The posed exercise (what the workbook builds its keys from) solves at its own
    drive.angle on the followed assembly, whatever solves it next."""
    mechanism = load_exercise(WHITWORTH).mechanism
    posed = pose(mechanism, 250.0)
    assert posed.mechanism.drive.angle == 250.0 and posed.start == 30.0
    again = solve(posed.mechanism)
    followed = solve(mechanism, 250.0)
    for point in ("B", "C", "D"):
        assert np.allclose(again.position(point), followed.position(point), rtol=0, atol=1e-12)


# -- limit positions on the way -----------------------------------------------------------------
def test_limit_position_on_the_way_is_one_line_naming_group_and_angle(capsys):
    code, out, err = run(capsys, "solve", ROCKER, "--angle", "150")
    assert code == 2 and not out and err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"planmethod: error: {ROCKER}: link BC+CD, crank angle 104.478°: ")
    assert "limit (toggle) position at crank angle 104.477512°" in err
    assert "drive.angle 60°" in err and "150°" in err
    code, out, err = run(capsys, "solve", ROCKER, "--angle=-150")
    assert code == 2 and "limit (toggle) position at crank angle -104.477512°" in err


def test_limit_position_error_from_the_api():
    exercise = load_exercise(ROCKER)
    with pytest.raises(ToggleError) as raised:
        analyse(exercise, 200.0)
    assert raised.value.link == "BC+CD"
    assert raised.value.angle == pytest.approx(ROCKER_LIMIT, abs=1e-8)
    # the crank turns from 60° down to −100° without meeting it, and up to 100°
    for angle in (-100.0, 100.0):
        assert analyse(exercise, angle, plans=False).angle == angle


def test_a_limit_between_the_coarse_steps_is_found():
    """Just past the Grashof limit the crank cannot pass 180° by a gap of 0.26°, between two
    steps of the coarse sweep (x.5°): the refinement finds it."""
    change = -1e-6
    rocker, coupler, crank, ground = 0.20 * (1 + change), 0.30, 0.10, 0.40
    mechanism = exercise_of(fourbar_case(crank=crank, coupler=coupler, rocker=rocker,
                                         ground=(ground, 0.0), drive_angle=90.5)).mechanism
    steps = 90.5 + FOLLOW_STEP_DEG * np.arange(0, 211)
    solve(mechanism, steps, stage="velocity")        # every step of the way solves
    cosine = (crank ** 2 + ground ** 2 - (coupler + rocker) ** 2) / (2 * crank * ground)
    limit = math.degrees(math.acos(cosine))
    with pytest.raises(ToggleError) as raised:
        follow(mechanism, 300.5)
    assert raised.value.link == "BC+CD"
    assert raised.value.angle == pytest.approx(limit, abs=1e-6)
    follow(mechanism, 170.0)           # short of it
    follow(mechanism, -60.0)           # the other way round


def test_an_assembly_that_cannot_be_chosen_says_where(capsys, tmp_path):
    """The assembly is chosen at drive.angle: where the file's links do not join there, the
    error says so, whatever angle was asked."""
    text = ROCKER.read_text(encoding="utf-8").replace("angle = 60", "angle = 150")
    path = tmp_path / "rocker_at_150.toml"
    path.write_text(text, encoding="utf-8")
    code, out, err = run(capsys, "solve", path, "--angle", "60")
    assert code == 2 and not out and err.count("\n") == 1
    assert "crank angle 150°" in err and "cannot join" in err
    assert "at drive.angle, where the assembly followed to 60° is chosen" in err


def test_out_of_range_angle_is_refused(capsys):
    for text in ("nan", "1e300", "36000.5"):
        code, out, err = run(capsys, "solve", WHITWORTH, f"--angle={text}")
        assert code == 2 and not out and "option --angle" in err and "36000" in err
