"""The force commands: ``check`` (seed 000's Table 2), ``study`` (seed 003), ``sweep --forces``
and ``solve`` on the force exercises."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from planmethod.application.checking import Row, check_row
from planmethod.cli import main
from planmethod.forces.study import NOT_SIGNIFICANT, Parameter, Study
from planmethod.kinematics import solve
from planmethod.spec import load_exercise
from planmethod.words import message

CONVEYOR = "exercises/conveyor_sixbar.toml"
TABLE2 = "exercises/conveyor_sixbar_table2.csv"
STUDY = "exercises/fourbar_study.toml"


# -- check ----------------------------------------------------------------------------------------
def test_check_flags_the_papers_rows(capsys):
    assert main(["check", CONVEYOR, TABLE2, "--json"]) == 1
    report = json.loads(capsys.readouterr().out)
    first, second = report["rows"]
    assert first["angle"] == 135 and first["flagged"]
    assert first["flagged_points"] == ["D"]
    positions = {p["point"]: p for p in first["positions"]}
    for point in "ABCEFG":
        assert positions[point]["error"] <= 0.002 and not positions[point]["flagged"]
    cd = next(c for c in first["lengths"] if c["pair"] == "CD")
    assert cd["violated"] and cd["given"] == pytest.approx(0.61, abs=0.005)
    assert cd["expected"] == pytest.approx(1.14)
    assert second["angle"] == 225 and second["flagged"]
    ef = next(c for c in second["lengths"] if c["link"] == "rocker_EF")
    assert ef["violated"] and ef["given"] == pytest.approx(1.05, abs=0.005)
    assert ef["expected"] == pytest.approx(0.44)


def test_check_text_report(capsys):
    assert main(["check", CONVEYOR, TABLE2]) == 1
    text = capsys.readouterr().out
    assert "φ₁ = 135° (line 4): FLAGGED" in text and "flagged: D" in text
    assert "link 4 (rocker EF): |FE| = 1.049 m, should be 0.44 m" in text


def test_check_accepts_exact_coordinates(tmp_path, capsys):
    exercise = load_exercise(CONVEYOR)
    angles = [0.0, 135.0, 300.0]
    motion = solve(exercise.mechanism, angles, stage="position")
    points = "ABCDE"
    lines = ["angle," + ",".join(f"x_{p},y_{p}" for p in points)]
    for i, angle in enumerate(angles):
        cells = [repr(angle)] + [repr(float(v)) for p in points
                                 for v in motion.position(p)[i]]
        lines.append(",".join(cells))
    table = tmp_path / "exact.csv"
    table.write_text("\n".join(lines) + "\n")
    assert main(["check", CONVEYOR, str(table), "--tolerance", "0.01"]) == 0
    assert "FLAGGED" not in capsys.readouterr().out


def test_check_row_without_an_assembly_blames_the_lengths():
    exercise = load_exercise("exercises/fourbar_forces.toml")
    row = Row(60.0, {"B": (0.04, 0.0693), "C": (0.5, 0.5)}, 2)
    found = check_row(exercise, row, 0.002)
    assert found.flagged and "C" in found.flagged_points


@pytest.mark.parametrize(("text", "message"), [
    ("x_A,y_A\n1,2\n", "no crank-angle column"),
    ("angle,x_Q,y_Q\n0,1,2\n", "unknown point 'Q'"),
    ("angle,x_A\n0,1\n", "only a x column"),
    ("angle,x_A,y_A\n0,one,2\n", "line 2, column x_A: not a number"),
    ("angle,x_A,y_A\n0,1\n", "line 2: 2 values for 3 columns"),
    ("angle,x_A,y_A\n", "no rows"),
    ("angle,foo\n0,1\n", "expected x_P or y_P"),
])
def test_check_bad_tables(tmp_path, capsys, text, message):
    table = tmp_path / "bad.csv"
    table.write_text(text)
    assert main(["check", CONVEYOR, str(table)]) == 2
    error = capsys.readouterr().err
    assert message in error and "bad.csv" in error


def test_check_bad_arguments(capsys):
    assert main(["check", CONVEYOR, "no_such.csv"]) == 2
    assert "no such file" in capsys.readouterr().err
    assert main(["check", CONVEYOR, TABLE2, "--tolerance", "-1"]) == 2
    assert "--tolerance" in capsys.readouterr().err


# -- study ----------------------------------------------------------------------------------------
def test_study_command_table_csv_and_plot(tmp_path, capsys):
    csv, plot = tmp_path / "study.csv", tmp_path / "study.png"
    assert main(["study", STUDY, "--step", "10", "--csv", str(csv), "--plot", str(plot)]) == 0
    text = capsys.readouterr().out
    # the rocker CD is link 3 and the crank 1 in the course's numbering; reactions R₀₁ …
    assert "rocker weight G₃ (N)" in text and "crank speed ω₁ (rad/s)" in text
    assert "R₀₁        R₁₂        R₂₃        R₀₃" in text and "R_A" not in text
    assert text.count("the data support it") + text.count("the data do not support it") == 2
    assert "REFUTED" not in text and "CONFIRMED" not in text
    rows = csv.read_text().splitlines()
    assert rows[0] == "parameter,value,R_A_max,R_B_max,R_C_max,R_D_max,M_b_max"
    assert len(rows) == 1 + 15
    assert plot.stat().st_size > 10_000


def test_study_numbers_are_consistent_with_a_single_solve(capsys):
    """The base row of each table is the same full turn: all three agree, and they equal the
    maxima of a plain force sweep of the exercise."""
    from planmethod.forces import solve_forces
    from planmethod.forces.study import run_study

    exercise = load_exercise(STUDY)
    study = run_study(exercise, step=5.0)
    base = {p.name: int(np.argmin(np.abs(study.values[p.name] - p.base)))
            for p in study.parameters}
    solution = solve_forces(solve(exercise.mechanism, np.arange(0.0, 360.0, 5.0)))
    for pair in study.pairs:
        expected = float(solution.reactions[pair].magnitude.max())
        for name, index in base.items():
            assert study.maxima[name][pair][index] == pytest.approx(expected, rel=1e-12)


def synthetic_study(weight_change: float, moment_change: float) -> Study:
    parameters = (Parameter("weight", message("rocker weight {symbol}", symbol="G4"), "N",
                            (20.0, 100.0), 60.0),
                  Parameter("omega", message("crank speed {symbol}", symbol="ω1"), "rad/s",
                            (10.0, 50.0), 30.0),
                  Parameter("moment", message("resisting moment {symbol}", symbol="Mc"), "N·m",
                            (80.0, 160.0), 120.0))
    maxima = {"weight": {"B": np.array([100.0, 100.0 * (1 + weight_change)])},
              "omega": {"B": np.array([100.0, 110.0])},
              "moment": {"B": np.array([100.0, 100.0 * (1 + moment_change)])}}
    values = {p.name: np.array(p.values) for p in parameters}
    return Study("t", "CD", parameters, ("B",), values, maxima,
                 {p.name: np.zeros(2) for p in parameters})


def test_study_conclusions_follow_the_numbers():
    agrees = synthetic_study(0.5 * NOT_SIGNIFICANT, 0.9)
    assert [verdict for _, verdict, _ in agrees.conclusions()] == [True, True]
    disagrees = synthetic_study(2 * NOT_SIGNIFICANT, 0.05)
    assert [verdict for _, verdict, _ in disagrees.conclusions()] == [False, False]


@pytest.mark.parametrize(("arguments", "message"), [
    (["--weights", "100:20:20"], "first:last:step"),
    (["--omegas", "a,b"], "first:last:step"),
    (["--step", "0"], "--step"),
    (["--weights", "0,20"], "must be positive"),
])
def test_study_bad_arguments(capsys, arguments, message):
    assert main(["study", STUDY, *arguments]) == 2
    assert message in capsys.readouterr().err


def test_study_needs_a_resisting_moment(capsys):
    assert main(["study", "exercises/fourbar_forces.toml"]) == 2
    assert "resisting moment" in capsys.readouterr().err


# -- sweep --forces and solve ---------------------------------------------------------------------
def test_sweep_forces_columns_and_plot(tmp_path, capsys):
    csv, plot = tmp_path / "forces.csv", tmp_path / "forces.png"
    assert main(["sweep", CONVEYOR, "--forces", "--step", "30", "--csv", str(csv),
                 "--plot", str(plot)]) == 0
    header = csv.read_text().splitlines()[0].split(",")
    for pair in "OABEDFG":
        assert {f"Rx_{pair}", f"Ry_{pair}", f"R_{pair}"} <= set(header)
    assert {"M_b", "M_b_system", "M_b_no_friction", "friction_iterations"} <= set(header)
    assert plot.stat().st_size > 20_000
    rows = [line.split(",") for line in csv.read_text().splitlines()[1:]]
    column = header.index("M_b")
    other = header.index("M_b_system")
    for row in rows:
        assert float(row[column]) == pytest.approx(float(row[other]), rel=1e-9, abs=1e-9)


def test_sweep_forces_of_a_prismatic_pair_has_its_couple(tmp_path):
    csv = tmp_path / "shaper.csv"
    data = tmp_path / "shaper.toml"
    text = Path("exercises/shaper_sixbar.toml").read_text(encoding="utf-8")
    text += "\n[mass.rod]\nm = 2.0\nJ = 0.01\n\n[mass.lever]\nm = 3.0\nJ = 0.09\n" \
            "S = [0.3, 0]\n"
    data.write_text(text.replace("[ask]", "[ask]\nforces = true"), encoding="utf-8")
    assert main(["sweep", str(data), "--forces", "--step", "45", "--csv", str(csv)]) == 0
    header = csv.read_text().splitlines()[0].split(",")
    assert "M_block/lever" in header and "M_ram/frame" in header


@pytest.mark.parametrize("exercise", [CONVEYOR, STUDY, "exercises/fourbar_forces.toml"])
def test_solve_json_has_the_forces_block(capsys, exercise):
    assert main(["solve", exercise, "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    forces = report["forces"]
    assert forces["whole_system"]["agrees"]
    assert forces["power_residual"] < 1e-12
    assert forces["zhukovsky_moment"] == pytest.approx(forces["balancing_moment"], rel=1e-9)
    for entry in forces["reactions"].values():
        assert set(entry) >= {"from", "on", "force"}


@pytest.mark.parametrize("name", ["combined_force_slider_crank", "conveyor_sixbar",
                                  "fourbar_forces", "fourbar_study", "loaded_press_sixbar"])
def test_no_reaction_is_printed_as_round_off(capsys, name):
    """A reaction component or a block's couple that is zero in exact arithmetic prints as 0,
    not as the round-off of the sums that make it (-1.4e-15 N, -3.9e-31 N·m); the rest of
    the table as it was."""
    assert main(["solve", f"exercises/{name}.toml"]) == 0
    text = capsys.readouterr().out
    table = text[text.index("reaction  pair"):text.index("balancing moment")]
    rows = [line.split()[2:] for line in table.splitlines()[1:] if line.strip()]
    assert rows and all("e-" not in value for row in rows for value in row)
    assert all(float(row[2]) > 0 for row in rows)       # the magnitudes themselves are kept
