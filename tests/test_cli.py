"""The command line: seed 001's printed answers, the JSON contract, sweeps, and every error path
(one line naming file and key, exit 2, no traceback, no output written)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from planmethod.cli import main

ROOT = Path(__file__).resolve().parent.parent
SEED = ROOT / "exercises" / "compressor_slider_crank.toml"
SHIPPED = sorted((ROOT / "exercises").glob("*.toml"))


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_solve_prints_seed001_answers(capsys):
    code, out, err = run(capsys, "solve", SEED)
    assert code == 0 and not err
    for text in ("W = 3n − 2p5 − p4 = 3·3 − 2·4 − 0 = 1", "RRP (type 2), class 2, order 2",
                 "μl = 0.002 m/mm", "μv = 0.2 (m/s)/mm", "μa = 20 (m/s²)/mm",
                 "μφv = μv/ω₁ = 0.002 m/mm", "crank angle φ₁ = 45°",
                 "group 1: links 2, 3 (BC, slider) — RRP"):
        assert text in out
    table = out.split("Published values")[0]      # the check table, not the book's values
    rows = {line.split()[0]: line.split() for line in table.splitlines()
            if line.startswith("  ") and len(line.split()) >= 5}
    assert "v_C                              4       5.27163     -24.1 %   likely a slip" in out
    # the course's symbols (the rod BC is link 2), never the report's names
    expected = {"v_C": 5.2716, "ω₂": -24.254, "a_C": 430.32, "ε₂": 2282.7, "ρ_D": 0.0738}
    for quantity, value in expected.items():
        plan, exact = float(rows[quantity][1]), float(rows[quantity][2])
        assert plan == pytest.approx(exact, rel=1e-9)
        decimals = len(str(value).split(".")[1])
        assert round(exact, decimals) == value


def _contract_checks(report):
    assert set(report) >= {"title", "angle", "structure", "scales", "points", "links", "plans",
                           "checks"}
    structure = report["structure"]
    assert {"n", "p5", "p4", "W", "groups"} <= set(structure) and structure["W"] == 1
    for group in structure["groups"]:
        assert {"type", "links", "class", "order"} <= set(group)
    assert {"mu_l", "mu_v", "mu_a"} <= set(report["scales"])
    for name in ("velocity", "acceleration"):
        plan = report["plans"][name]
        assert plan["pole"] == {"velocity": "p", "acceleration": "π"}[name]
        assert plan["points_mm"][plan["pole"]] == [0.0, 0.0]
        assert plan["steps"] and all("action" in step for step in plan["steps"])
    for check in report["checks"]:
        assert set(check) >= {"quantity", "plan", "analytic", "abs_error", "rel_error"}
        if check["rel_error"] is not None:
            assert check["rel_error"] <= 1e-6
        elif check["analytic"] is not None:                    # zero to its round-off
            assert abs(check["analytic"]) <= 1e-12


@pytest.mark.parametrize("path", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_json_report_follows_the_contract_for_every_shipped_exercise(capsys, path):
    code, out, err = run(capsys, "solve", path, "--json")
    if code == 2 and "class III" in err:
        pytest.skip("plans of class III groups are not drawn")
    assert code == 0, err
    report = json.loads(out)
    assert report["title"] and isinstance(report["angle"], float)
    if "forces" in report and "plans" not in report:
        return
    _contract_checks(report)


def test_json_holds_every_asked_quantity(capsys):
    code, out, _ = run(capsys, "solve", ROOT / "exercises" / "shaper_sixbar.toml", "--json")
    assert code == 0
    report = json.loads(out)
    kinds = [g["type"] for g in report["structure"]["groups"]]
    assert kinds == ["RPR", "RRP"]  # two groups in series
    assert set(report["points"]) == {"B@lever", "C", "D"}
    assert set(report["links"]) == {"lever", "rod"}
    assert set(report["sliding"]) == {"block/lever", "ram/frame"}
    sliding = report["sliding"]["block/lever"]
    assert math.hypot(*sliding["coriolis"]) > 0
    assert "b@lever" in report["plans"]["velocity"]["points_mm"]
    assert "k_B@lever" in report["plans"]["acceleration"]["points_mm"]


def test_straight_path_is_null_rho(capsys):
    import tomllib

    data = tomllib.loads(SEED.read_text())
    data["ask"]["curvature"] = ["C", "D"]
    from planmethod.report import analyse, report_dict
    from planmethod.spec import exercise_from_dict

    report = report_dict(analyse(exercise_from_dict(data)))
    assert report["curvature"]["C"] == {"rho": None, "center": None, "straight": True}
    assert report["curvature"]["D"]["rho"] == pytest.approx(0.0737712, rel=1e-6)


def test_precision_option_shows_the_drawing_error(capsys):
    code, out, _ = run(capsys, "solve", SEED, "--json", "--precision", "0.5")
    assert code == 0
    checks = {c["quantity"]: c for c in json.loads(out)["checks"]}
    assert 0 < checks["v_C"]["rel_error"] < 0.05


def test_angle_option(capsys):
    code, out, _ = run(capsys, "solve", SEED, "--json", "--angle", "0")
    assert code == 0
    report = json.loads(out)
    assert report["angle"] == 0.0
    assert report["points"]["C"]["velocity"][0] == pytest.approx(0.0, abs=1e-12)


def test_sweep_writes_csv_and_prints_extremes(capsys, tmp_path):
    csv = tmp_path / "turn.csv"
    code, out, err = run(capsys, "sweep", SEED, "--step", "10", "--csv", csv)
    assert code == 0, err
    lines = csv.read_text().splitlines()
    assert len(lines) == 37 and lines[0].startswith("angle,")
    header = lines[0].split(",")
    assert "v_C" in header and "epsilon_BC" in header
    assert "v_C" in out and "max" in out


BAD = {  # name → (edit of seed 001's text, expected fragment of the error line)
    "unknown link": (('link = "slider"', 'link = "slidr"'),
                     "slide[1].link: unknown link 'slidr'"),
    "unknown point asked": (('velocity = ["C", "D"]', 'velocity = ["C", "Z"]'),
                            "ask.velocity[1]: unknown point 'Z'"),
    "pivot not in frame": (('frame = { A = [0, 0] }', 'frame = { A1 = [0, 0] }'),
                           "slide[1].through: 'A' is not a point of 'frame'"),
    "point in one link only": ((('slider = { C = [0, 0] }\n', 'slider = { K = [0, 0] }\n'),
                                ('point = "C"', 'point = "K"')),
                               "points named in one link only"),
    "misnamed drive": (("[drive]", "[drvie]"), "drvie: unknown key (did you mean 'drive'?)"),
    "not a number": (("angle = 45", 'angle = "abc"'), "drive.angle: must be a finite number"),
    "nan": (("omega = 100", "omega = nan"), "drive.omega: must be a finite number, got nan"),
    "inf": (("B = [0.06, 0] }", "B = [inf, 0] }"), "links.AB.B[0]: must be a finite number"),
    "duplicate link": (("slider = { C = [0, 0] }",
                        "slider = { C = [0, 0] }\nSlider = { C = [0, 0] }"),
                       "links.Slider: duplicate link name"),
    "duplicate key": (("omega = 100", "omega = 100\nomega = 50"), "a key is given twice"),
    "ask for a missing link": (('omega = ["BC"]', 'omega = ["XY"]'),
                               "ask.omega[0]: unknown link 'XY'"),
    "ask for a missing pair": (('curvature = ["D"]', 'curvature = ["D"]\nsliding = ["a/b"]'),
                               "ask.sliding[0]: no prismatic pair 'a/b'"),
    "bad TOML": (("[plan]", "[plan"), "not valid TOML"),
    "cannot reach": (("C = [0.18, 0], D = [0.09, 0]", "C = [0.03, 0], D = [0.015, 0]"),
                     "short by 0.0124264 m"),
    "zero scale": (("crank_mm = 30", "crank_mm = 0"), "plan.crank_mm: must be positive"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_input_is_one_line_exit_2_and_writes_nothing(capsys, tmp_path, case):
    edits, fragment = BAD[case]
    if isinstance(edits[0], str):
        edits = (edits,)
    text = SEED.read_text()
    for old, new in edits:
        assert old in text
        text = text.replace(old, new, 1)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    out_dir = tmp_path / "plans"
    code, out, err = run(capsys, "solve", path, "--svg", out_dir)
    assert code == 2
    assert err.startswith("planmethod: error: ") and err.count("\n") == 1
    assert str(path) in err and fragment in err
    assert "Traceback" not in err and not out
    assert not out_dir.exists()


def test_structure_errors_name_the_links(capsys, tmp_path):
    text = SEED.read_text()
    start, end = text.index("[[slide]]"), text.index("[sketch]")
    path = tmp_path / "w3.toml"
    path.write_text(text[:start] + text[end:])
    code, _, err = run(capsys, "solve", path)
    assert code == 2 and "links:" in err and "W = 3n − 2p5 − p4 = 3·3 − 2·3 − 0 = 3" in err
    assert "slider" in err


def test_missing_file_and_bad_options(capsys, tmp_path):
    code, _, err = run(capsys, "solve", tmp_path / "none.toml")
    assert code == 2 and "no such file" in err
    code, _, err = run(capsys, "solve", SEED, "--precision", "-1")
    assert code == 2 and "--precision" in err
    code, _, err = run(capsys, "solve", SEED, "--angle", "nan")
    assert code == 2 and "finite" in err
    code, _, err = run(capsys, "sweep", SEED, "--step", "0")
    assert code == 2 and "--step" in err
    code, _, err = run(capsys, "solve")
    assert code == 2 and err.splitlines() == [
        "planmethod solve: error: the following arguments are required: file "
        "(see 'planmethod solve --help')"]
    # a negative number in any float notation is a value, not an option
    code, _, err = run(capsys, "sweep", SEED, "--from", "-1e300")
    assert code == 2 and err.splitlines() == [
        f"planmethod: error: {SEED}: --from and --to must lie within ±36000°, got -1e+300 "
        "and 360"]


def test_sweep_error_names_the_angle_and_writes_no_csv(capsys, tmp_path):
    text = SEED.read_text().replace("C = [0.18, 0], D = [0.09, 0]",
                                    "C = [0.03, 0], D = [0.02, 0]")
    path = tmp_path / "short.toml"
    path.write_text(text.replace("angle = 45", "angle = 0").replace(
        "frame = { A = [0, 0] }", "frame = { A = [0, 0], G = [0, -0.02] }").replace(
        'through = "A"', 'through = "G"'))
    csv = tmp_path / "out.csv"
    code, _, err = run(capsys, "sweep", path, "--csv", csv)
    assert code == 2 and "crank angle 10°" in err and "short by" in err
    assert err.rstrip().endswith("; give the angles the crank reaches with --from and --to")
    assert len(err.strip().splitlines()) == 1 and not csv.exists()


def test_console_script_has_no_traceback(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[drive]\nlink = 1\n")
    result = subprocess.run([sys.executable, "-m", "planmethod.cli", "solve", str(bad)],
                            capture_output=True, text=True, cwd=ROOT)
    assert result.returncode == 2
    assert "Traceback" not in result.stderr and result.stderr.count("\n") == 1


def test_shipped_exercises_cover_all_five_dyad_kinds_and_groups_in_series(capsys):
    kinds, series = set(), False
    for name in ("compressor_slider_crank", "fourbar_coupler_point", "slotted_lever",
                 "slotted_crank_crosshead", "scotch_yoke", "shaper_sixbar"):
        code, out, err = run(capsys, "solve", ROOT / "exercises" / f"{name}.toml", "--json")
        assert code == 0, err
        report = json.loads(out)
        _contract_checks(report)
        groups = report["structure"]["groups"]
        kinds |= {group["type"] for group in groups}
        series |= len(groups) >= 2
    assert kinds == {"RRR", "RRP", "RPR", "PRP", "RPP"} and series


@pytest.mark.parametrize("argv", [
    ["sweep", "{missing}", "--plot", "{out}/curves.txt"],
    ["sweep", "{missing}", "--forces", "--plot", "{out}/curves.txt"],
    ["study", "{missing}", "--plot", "{out}/curves.txt"],
])
def test_a_plot_format_is_refused_before_any_work(capsys, tmp_path, argv):
    """Every command that plots names the unsupported suffix and the supported ones in one line,
    exit 2, before it reads the exercise (so the file named here need not even exist) and
    before it writes anything."""
    argv = [a.format(missing=tmp_path / "no_such.toml", out=tmp_path) for a in argv]
    code, out, err = run(capsys, *argv, "--csv", tmp_path / "table.csv")
    assert code == 2 and not out
    assert err.splitlines() == [f"planmethod: error: {tmp_path}/curves.txt: plot format '.txt' "
                                "not supported; use .png, .svg or .pdf"]
    assert list(tmp_path.iterdir()) == []
