"""Drawing scales: the standard series where a scale is chosen freely, exact lengths on request."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import pytest

from planmethod.cli import main
from planmethod.errors import SpecError
from planmethod.plans.scales import STANDARD_MANTISSAS, choose_scales, standard
from planmethod.spec import exercise_from_dict, load_exercise

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))


def is_standard(value: float) -> bool:
    mantissa = value / 10 ** math.floor(math.log10(value) + 1e-12)
    return any(abs(mantissa - m) <= 1e-9 * m for m in STANDARD_MANTISSAS)


def test_standard_is_the_nearest_value_of_the_series():
    assert [standard(v) for v in (0.00942478, 0.0592176, 0.00333333, 1.0, 0.3, 6.2, 8.9)] == [
        0.01, 0.05, 0.004, 1.0, 0.25, 7.5, 10.0]
    for value in (1e-5, 3.3e-3, 0.071, 12.0, 4.4e3):
        chosen = standard(value)
        assert is_standard(chosen)
        assert all(abs(math.log(chosen / value)) <= abs(math.log(c / value)) + 1e-12
                   for c in (m * 10.0 ** k for m in STANDARD_MANTISSAS for k in range(-7, 6)))


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.stem)
def test_every_freely_chosen_scale_is_standard(path, capsys):
    """Without mu_* and exact_mm, every scale the report lists that was chosen from a drawn
    length is a standard value; at the crank scale μl is, and μv = ω1·μl where that is
    round (the shipped exercises are written so)."""
    table = tomllib.loads(path.read_text(encoding="utf-8")).get("plan", {})
    assert not any(key.startswith("mu_") for key in table) and not table.get("exact_mm")
    assert main(["solve", str(path), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    scales = report["scales"]
    assert is_standard(scales["mu_l"])
    crank = table.get("crank_mm") == table.get("velocity_mm") == table.get("acceleration_mm")
    omega = tomllib.loads(path.read_text(encoding="utf-8"))["drive"]["omega"]
    if crank:
        assert scales["mu_v"] == pytest.approx(abs(omega) * scales["mu_l"], rel=1e-15)
    assert is_standard(scales["mu_v"]) and is_standard(scales["mu_a"])
    mu_f = (report.get("forces") or {}).get("scales", {}).get("mu_f")
    if mu_f is not None:
        assert is_standard(mu_f)


def _slider(**plan):
    data = tomllib.loads((ROOT / "exercises" / "compressor_slider_crank.toml").read_text())
    data["plan"] = {**{k: v for k, v in data["plan"].items() if not k.endswith("_mm")
                       or k == "precision_mm"}, **plan}
    return exercise_from_dict(data)


def test_exact_mm_keeps_the_lengths_as_written():
    rounded = choose_scales(_slider(crank_mm=33, velocity_mm=45, acceleration_mm=50))
    exact = choose_scales(_slider(crank_mm=33, velocity_mm=45, acceleration_mm=50,
                                  exact_mm=True))
    assert (rounded.mu_l, rounded.mu_v, rounded.mu_a) == (0.002, 0.15, 10.0)
    assert exact.mu_l == pytest.approx(0.06 / 33) and exact.mu_v == pytest.approx(6.0 / 45)


def test_the_compressors_printed_scales_stay_as_printed():
    scales = choose_scales(load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml"))
    assert (scales.mu_l, scales.mu_v, scales.mu_a) == (0.002, 0.2, 20.0)


def test_the_reference_vector_follows_from_a_rounded_scale(capsys):
    """(pb) is v_B/μv once μv is rounded: the plan still reads v_B exactly."""
    exercise = _slider(crank_mm=33, velocity_mm=45, acceleration_mm=50)
    from planmethod.plans import draw_plans

    plans = draw_plans(exercise)
    b = plans.velocity.points_mm["b"]
    assert math.hypot(*b) == pytest.approx(6.0 / 0.15, rel=1e-12)      # 40 mm, not 45
    from planmethod.kinematics import solve

    exact = solve(exercise.mechanism, exercise.mechanism.drive.angle).at(0)
    assert plans.readings["v_C"] == pytest.approx(float(math.hypot(*exact.velocity("C"))),
                                                  rel=1e-12)


def test_published_values_are_compared_and_checked(capsys):
    """[published]: the book's values in the JSON report beside the exact ones, differences
    over 5 % flagged; a key that names no quantity is an error naming it."""
    assert main(["solve", str(ROOT / "exercises" / "compressor_slider_crank.toml"),
                 "--json"]) == 0
    published = json.loads(capsys.readouterr().out)["published"]
    assert "Abduvaliev" in published["source"]
    rows = {row["quantity"]: row for row in published["values"]}
    assert rows["v_B"]["likely_slip"] is False and rows["v_B"]["difference_percent"] == 0.0
    assert rows["a_C"]["published"] == 356.0 and rows["a_C"]["likely_slip"] is True
    assert rows["a_C"]["difference_percent"] == pytest.approx(
        100 * (356.0 - rows["a_C"]["exact"]) / rows["a_C"]["exact"])
    data = tomllib.loads((ROOT / "exercises" / "compressor_slider_crank.toml").read_text())
    data["published"] = {"speed_C": 4.0}
    with pytest.raises(Exception, match=r"published\.speed_C: is not a quantity"):
        exercise_from_dict(data)


def test_the_force_scale_is_printed_with_the_others_when_it_is_set():
    from planmethod.plans.scales import Scales
    from planmethod.render.plan_words import scale_lines
    from planmethod.words import render

    lines = [render(line) for line in scale_lines(Scales(0.002, 0.2, 20.0, 100.0, "B",
                                                         mu_f=50.0))]
    assert lines[-1] == "μF = 50 N/mm" and len(lines) == 6
    assert not any(render(line).startswith("μF")
                   for line in scale_lines(Scales(0.002, 0.2, 20.0, 100.0, "B")))


def test_a_scale_point_where_the_pivot_is_is_refused_by_its_key():
    """A scale point of the crank other than its pivot but at the pivot's place gives no
    reference length to choose the scales from: refused by key, with the file."""
    data = tomllib.loads((ROOT / "exercises" / "compressor_slider_crank.toml").read_text())
    data["links"]["AB"]["P"] = [0, 0]
    data["plan"]["scale_point"] = "P"
    exercise = exercise_from_dict(data, file="slider.toml")
    with pytest.raises(SpecError) as caught:
        choose_scales(exercise)
    assert str(caught.value) == ("slider.toml: plan.scale_point: the scale point P coincides "
                                 "with the pivot A")


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.stem)
@pytest.mark.parametrize("omega", [None, 9.0, 12.0, 7.3])
def test_every_default_scale_is_round(path, omega):
    """Without a [plan] table (30 mm for the crank, its velocity and its acceleration) every
    scale is round — 1, 1.5, 2, 2.5, 3, 4, 5, 6, 7.5 or 8 × 10ᵏ — whatever ω1 is (ω1·μl of
    the crank scale was printed as μv = 0.0135, 0.024, 0.0375)."""
    from planmethod.plans.scales import is_round

    data = tomllib.loads(path.read_text(encoding="utf-8"))
    data.pop("plan", None)
    if omega is not None:
        data["drive"]["omega"] = omega
    scales = choose_scales(exercise_from_dict(data))
    for name in ("mu_l", "mu_v", "mu_a"):
        assert is_round(getattr(scales, name)), (name, getattr(scales, name))


@pytest.mark.parametrize("path", sorted((ROOT / "exercises" / "templates").glob("*.toml")),
                         ids=lambda p: p.stem)
def test_every_variants_scales_are_round(path):
    """The scales a variant's task sheet prints (and its workbook frames draw at)."""
    from planmethod.grading.templates import draw_variant, load_template
    from planmethod.plans.scales import is_round

    for seed in range(5):
        exercise = draw_variant(load_template(str(path)), seed=seed).exercise
        scales = choose_scales(exercise)
        for name in ("mu_l", "mu_v", "mu_a"):
            assert is_round(getattr(scales, name)), (path.stem, seed, name)


def test_the_crank_scale_rounds_what_omega_gives():
    """μl = 0.0015 and ω1 = 9 rad/s gave μv = 0.0135 (m/s)/mm: now the round 0.015 nearest
    to it, μa the round value nearest ω1²·μl = 0.1215 (0.1); a round product stays."""
    data = tomllib.loads((ROOT / "exercises" / "compressor_slider_crank.toml").read_text())
    data.pop("plan")
    data["links"]["AB"]["B"] = [0.045, 0]
    data["drive"]["omega"] = 9.0
    scales = choose_scales(exercise_from_dict(data))
    assert (scales.mu_l, scales.mu_v, scales.mu_a) == (0.0015, 0.015, 0.1)
    data["drive"]["omega"] = 100.0
    scales = choose_scales(exercise_from_dict(data))
    assert (scales.mu_l, scales.mu_v, scales.mu_a) == (0.0015, 0.15, 15.0)
