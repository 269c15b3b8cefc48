"""The reference cases of docs/reference-cases.md (the compressor slider-crank of Abduvaliev &
Abduxoshimov, cases A and C) and published textbook examples, by the exact solver and by the
plans (which at precision 0 must equal the exact vectors)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from planmethod.kinematics import solve
from planmethod.plans import draw_plans
from planmethod.report import exact_value
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.testing import fourbar, slider_crank, slotted_lever


def close(value: float, printed: float, digits_after_point: int) -> bool:
    """Equal to a printed value within half a unit of its last printed digit."""
    return abs(value - printed) <= 0.5 * 10.0 ** -digits_after_point + 1e-12


# -- the compressor slider-crank (Abduvaliev & Abduxoshimov), as stated -------------------------
@pytest.fixture(scope="module")
def compressor():
    exercise = load_exercise("exercises/compressor_slider_crank.toml")
    return exercise, solve(exercise.mechanism).at(0), draw_plans(exercise)


PRINTED = [  # (quantity, exact value as printed in docs/reference-cases.md, decimals)
    ("v_B", 6.000, 3), ("v_C", 5.2716, 4), ("omega_BC", -24.2536, 4), ("a_B", 600.0, 1),
    ("a_C", 430.317, 3), ("epsilon_BC", 2282.69, 2), ("v_D", 5.2087, 4), ("a_D", 477.05, 2),
    ("rho_D", 0.07377, 5),
]


def _exact(motion, quantity: str) -> float:
    return exact_value(motion, quantity)


@pytest.mark.parametrize(("quantity", "printed", "digits"), PRINTED)
def test_compressor_exact_values(compressor, quantity, printed, digits):
    _, motion, _ = compressor
    assert close(_exact(motion, quantity), printed, digits)


@pytest.mark.parametrize(("quantity", "printed", "digits"),
                         [q for q in PRINTED if q[0] not in ("v_B", "a_B")])
def test_compressor_plan_at_precision_zero_equals_exact(compressor, quantity, printed, digits):
    _, motion, plans = compressor
    exact = _exact(motion, quantity)
    assert plans.readings[quantity] == pytest.approx(exact, rel=1e-9)
    assert close(plans.readings[quantity], printed, digits)


def test_compressor_directions_and_normal_component(compressor):
    _, motion, plans = compressor
    a_c = motion.acceleration("C")
    assert a_c[0] < 0 and abs(a_c[1]) < 1e-9 * abs(a_c[0])  # along −x
    omega = float(motion.omega("BC"))
    assert omega < 0  # clockwise
    assert omega ** 2 * 0.18 == pytest.approx(105.882, abs=5e-4)  # aⁿ_CB
    # the paper's shortcut at the crank scale: (bn) = (bc)²/(BC)
    v, a = plans.velocity.points_mm, plans.acceleration.points_mm
    bc = math.dist(v["b"], v["c"])
    assert math.dist(a["b"], a["n_CB"]) == pytest.approx(bc ** 2 / 90.0, rel=1e-12)
    # the line drawn for the slider runs along Ax, and the scales are those of the paper
    assert (plans.scales.mu_l, plans.scales.mu_v, plans.scales.mu_a) == pytest.approx(
        (0.002, 0.2, 20.0))


def test_compressor_printed_answers_are_wrong_by_12_to_30_percent(compressor):
    """The paper's graphical answers fit no reading of its data (docs/reference-cases.md)."""
    _, motion, _ = compressor
    printed = {"v_C": 4.0, "omega_BC": 20.0, "a_C": 356.0, "epsilon_BC": 2000.0,
               "rho_D": 0.0605}
    for quantity, value in printed.items():
        exact = abs(_exact(motion, quantity))
        assert 0.12 <= abs(value - exact) / exact <= 0.30, quantity


def test_compressor_figure_angle_fits_some_printed_answers():
    """Near φ1 ≈ 125° the paper's v_C, ω2 and ρ_D fit (3.94, 19.87, 0.062)."""
    exercise = load_exercise("exercises/compressor_slider_crank.toml")
    motion = solve(exercise.mechanism, 125.0).at(0)
    assert float(np.hypot(*motion.velocity("C"))) == pytest.approx(3.94, abs=0.005)
    assert abs(float(motion.omega("BC"))) == pytest.approx(19.87, abs=0.005)
    assert float(motion.curvature("D").rho) == pytest.approx(0.062, abs=0.0005)


# -- A: four-bar --------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def case_a():
    mechanism = exercise_from_dict(fourbar()).mechanism
    return solve(mechanism, [0.0, 60.0, 150.0])


def test_case_a_positions_at_60(case_a):
    assert np.allclose(case_a.position("C")[1], [0.236410, 0.168393], atol=5e-7)
    assert close(float(case_a.theta("BC")[1]), 0.467332, 6)
    # CD's own x axis runs C → D; docs/reference-cases.md measures the rocker from D to C
    rocker = math.remainder(float(case_a.theta("CD")[1]) + math.pi, 2 * math.pi)
    assert close(rocker, 1.931868, 6)


@pytest.mark.parametrize(("index", "omega_bc", "omega_cd", "epsilon_bc", "epsilon_cd"), [
    (0, -3.636364, -3.636364, -22.230840, 44.187225),
    (1, -2.829436, 2.448975, 19.087707, 46.590844),
    (2, 0.034915, 4.413543, 29.512029, -26.331020),
])
def test_case_a_angular(case_a, index, omega_bc, omega_cd, epsilon_bc, epsilon_cd):
    assert close(float(case_a.omega("BC")[index]), omega_bc, 6)
    assert close(float(case_a.omega("CD")[index]), omega_cd, 6)
    assert close(float(case_a.epsilon("BC")[index]), epsilon_bc, 6)
    assert close(float(case_a.epsilon("CD")[index]), epsilon_cd, 6)


def test_case_a_point_motion(case_a):
    assert np.allclose(case_a.velocity("C")[1], [-0.412391, -0.155730], atol=5e-7)
    assert np.allclose(case_a.acceleration("C")[1], [-7.464211, -3.972641], atol=5e-7)
    assert np.allclose(case_a.velocity("P")[1], [-0.439050, 0.211129], atol=5e-7)
    assert np.allclose(case_a.acceleration("P")[1], [-6.24636, -6.37209], atol=5e-6)


def test_case_a_curvature(case_a):
    rho_p = case_a.curvature("P").rho
    assert np.allclose(rho_p, [0.151688, 0.028089, 0.130323], atol=5e-7)
    # C turns about D: its path is the circle of radius CD, centred at D
    curvature = case_a.curvature("C")
    assert np.allclose(curvature.rho, 0.18, rtol=1e-12)
    assert np.allclose(curvature.center, [0.30, 0.0], atol=1e-12)


# -- C: crank and slotted lever ---------------------------------------------------------------
@pytest.mark.parametrize(("angle", "s", "ds", "omega3", "dds", "epsilon3", "coriolis"), [
    (0.0, 0.316228, 0.948683, 1.000000, -2.846050, 24.000000, 1.897367),
    (30.0, 0.360555, 0.720577, 1.923077, -5.600339, 12.298586, 2.771449),
    (90.0, 0.4, 0.0, 2.5, -7.5, 0.0, 0.0),
])
def test_case_c(angle, s, ds, omega3, dds, epsilon3, coriolis):
    exercise = exercise_from_dict(slotted_lever(angle=angle))
    motion = solve(exercise.mechanism).at(0)
    sliding = motion.sliding("block/lever")
    assert close(float(sliding.s), s, 6)
    assert close(float(sliding.velocity), ds, 6)
    assert close(float(motion.omega("lever")), omega3, 6)
    assert close(float(sliding.acceleration), dds, 6)
    assert close(float(motion.epsilon("lever")), epsilon3, 6)
    assert close(float(np.hypot(*sliding.coriolis)), coriolis, 6)
    # 2·ω3·ṡ, perpendicular to the slot
    assert float(np.hypot(*sliding.coriolis)) == pytest.approx(
        2 * abs(float(motion.omega("lever")) * float(sliding.velocity)), abs=1e-12)


def test_case_c_plan_reads_the_same():
    exercise = exercise_from_dict(slotted_lever(angle=30.0) | {
        "ask": {"sliding": ["block/lever"], "omega": ["lever"], "epsilon": ["lever"]}})
    plans = draw_plans(exercise)
    assert plans.readings["ds_block/lever"] == pytest.approx(0.720577, abs=5e-7)
    assert plans.readings["dds_block/lever"] == pytest.approx(-5.600339, abs=5e-7)
    assert plans.readings["coriolis_block/lever"] == pytest.approx(2.771449, abs=5e-7)
    assert plans.readings["epsilon_lever"] == pytest.approx(12.298586, abs=5e-7)
    # the Coriolis component is drawn on the acceleration plan
    assert any(step.component == "coriolis" and step.length_mm > 0
               for step in plans.acceleration.steps)


# -- published textbook examples --------------------------------------------------------------
def test_gate_fourbar_with_ab_and_dc_perpendicular_to_ad():
    """A GATE (ME) theory-of-machines question, printed with its answer on interviewmania.com
    (discussion 89107): AB = 5 cm, AD = 4 cm, DC = 2 cm, AB and DC both ⟂ AD, ω_AB = 10 rad/s;
    |ω_DC| = 25 rad/s (BC is momentarily in translation)."""
    data = {
        "drive": {"link": "AB", "pivot": "A", "angle": 90, "omega": 10},
        "links": {"frame": {"A": [0, 0], "D": [0.04, 0]}, "AB": {"A": [0, 0], "B": [0.05, 0]},
                  "BC": {"B": [0, 0], "C": [0.05, 0]}, "CD": {"C": [0, 0], "D": [0.02, 0]}},
        "sketch": {"C": [0.04, 0.02]},
        "ask": {"omega": ["BC", "CD"]},
    }
    exercise = exercise_from_dict(data)
    motion = solve(exercise.mechanism).at(0)
    assert abs(float(motion.omega("CD"))) == pytest.approx(25.0, rel=1e-12)
    assert float(motion.omega("BC")) == pytest.approx(0.0, abs=1e-12)
    plans = draw_plans(exercise)
    assert abs(plans.readings["omega_CD"]) == pytest.approx(25.0, rel=1e-9)


def test_published_piston_velocity_within_one_percent():
    """bissoy.com MCQ 375606: crank 0.3 m, rod 1.5 m, 150 r.p.m. clockwise, 40° from the inner
    dead centre; printed answer v = 3.49 m/s from the approximate formula
    ωr(sin θ + sin 2θ/(2n)). The exact value lies within 1 % of it."""
    omega = -150 * 2 * math.pi / 60
    # piston to the left of the crank centre: the inner dead centre is at 180°
    data = slider_crank(crank=0.3, rod=1.5, angle=180.0 - 40.0, omega=omega)
    data["sketch"] = {"C": [-1.8, 0.0]}
    motion = solve(exercise_from_dict(data).mechanism).at(0)
    speed = float(np.hypot(*motion.velocity("C")))
    assert speed == pytest.approx(3.49, rel=0.01)
