"""Every shipped exercise's reports are what they were before the restructuring (see
``tests/baselines.py``: 1e-12 relative, text identical)."""

from __future__ import annotations

import json

import pytest
from baselines import FOLDER, differences, exercises, record


@pytest.mark.parametrize("path", exercises(), ids=lambda path: path.stem)
def test_reports_match_the_baseline(path):
    baseline = FOLDER / f"{path.stem}.json"
    assert baseline.is_file(), f"no baseline for {path.name}: python -m tests.baselines"
    found = differences(json.loads(baseline.read_text(encoding="utf-8")), record(path))
    assert not found, "\n".join(found[:20])


def test_the_comparison_can_fail():
    old = {"points": {"C": {"velocity": [5.2716, 1e-17]}}, "title": "Compressor",
           "checks": [{"analytic": 5.0, "abs_error": 0.0}]}
    assert not differences(old, {"points": {"C": {"velocity": [5.2716 * (1 + 5e-13), 3e-17]}},
                                 "title": "Compressor",
                                 "checks": [{"analytic": 5.0, "abs_error": 1e-15}]})
    assert differences(old, {"points": {"C": {"velocity": [5.2716 * (1 + 5e-12), 0.0]}},
                             "title": "Compressor", "checks": [{"analytic": 5.0,
                                                                "abs_error": 0.0}]})
    assert differences(old, {**old, "title": "Other"})
    assert differences(old, {**old, "checks": [{"analytic": 5.0, "abs_error": 1e-9}]})
    angles = {"line_angle_deg": 89.99999914622636}
    assert not differences(angles, {"line_angle_deg": 90.0})   # sines 1 − 1 ulp and 1
    assert differences(angles, {"line_angle_deg": 89.99})


def test_a_sweep_may_gain_a_friction_sense_column_and_nothing_else():
    old = {"header": ["angle", "M_b"], "rows": [[0.0, 1.5]]}
    assert not differences(old, {"header": ["angle", "M_b", "friction_sense_B"],
                                 "rows": [[0.0, 1.5, -1.0]]})
    assert differences(old, {"header": ["angle", "M_b", "R_B"], "rows": [[0.0, 1.5, 2.0]]})
    assert differences(old, {"header": ["angle", "M_b", "friction_sense_B"],
                             "rows": [[0.0, 1.6, -1.0]]})


def test_scale_dependent_values_are_left_out_and_nothing_else():
    old = {"scales": {"mu_v": 0.00942478}, "plans": {"velocity": {
        "scale": 0.00942478, "points_mm": {"b": [40.0, 0.0]},
        "steps": [{"text": "(pb) = 40 mm", "length_mm": 40.0, "value": 5.2716}]}},
        "checks": [{"plan": 5.2716, "analytic": 5.2716, "abs_error": 0.0}]}
    rounded = {"scales": {"mu_v": 0.01}, "plans": {"velocity": {
        "scale": 0.01, "points_mm": {"b": [37.699, 0.0]},
        "steps": [{"text": "(pb) = 37.7 mm", "length_mm": 37.699, "value": 5.2716}]}},
        "checks": [{"plan": 5.2716, "analytic": 5.2716, "abs_error": 0.0}]}
    assert not differences(old, rounded)
    moved = json.loads(json.dumps(rounded))
    moved["plans"]["velocity"]["steps"][0]["value"] = 5.3     # an SI reading: compared
    assert differences(old, moved)
    moved = json.loads(json.dumps(rounded))
    moved["checks"][0]["plan"] = 5.3
    assert differences(old, moved)
