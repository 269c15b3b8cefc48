"""A class III triad with a prismatic pair drawn by Assur's special point (issue 37): the
vibrating screen of exercises/screen_sixbar.toml (a block on a fixed guide at the screen's end)
and a variant whose screen slides on a block pinned to the frame (a slot, with a Coriolis
component). Every plan point, ω, ε and sliding reading is checked against exact values from
the whole mechanism's constraint equations (planmethod.testing.reference_motion: Newton and
exact linear solves, nothing of the triad's own solution or of the plans), with every choice
of the special point's two sides."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from planmethod.cli import main
from planmethod.kinematics import solve
from planmethod.plans import draw_plans
from planmethod.plans.groups import triad
from planmethod.plans.groups.triad import SPECIAL
from planmethod.render.plan_words import step_text
from planmethod.report import analyse
from planmethod.spec import exercise_from_dict
from planmethod.testing import reference_motion
from planmethod.vectors import cross, perp

SCREEN = Path("exercises/screen_sixbar.toml")
ANGLES = (0.0, 75.0, 90.0, 160.0, 240.0, 315.0)


def screen() -> dict:
    return tomllib.loads(SCREEN.read_text())


def slot() -> dict:
    """The screen sliding along its line BD on a block pinned to the frame at H: the side's
    inner pair is prismatic, its carrier turns with the screen (aᵏ ≠ 0)."""
    data = screen()
    data["links"]["block"] = {"H": [0, 0]}
    data["links"]["frame"]["H"] = [0.62, 0.02]
    data["slide"] = [{"link": "block", "along": "screen", "through": "D", "direction": 0,
                      "point": "H"}]
    data["ask"]["sliding"] = ["block/screen"]
    return data


def exact(mechanism, angle: float) -> dict:
    """Each point's exact (position, velocity, acceleration) and each link's (ω, ε), from the
    reference motion."""
    reference = reference_motion(mechanism, [angle])
    points, rates = {}, {}
    for link, state in reference.items():
        theta, origin = state["theta"][0], state["origin"][0]
        omega, epsilon = state["omega"][0], state["epsilon"][0]
        rates[link] = (omega, epsilon)
        turn = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
        for name, local in mechanism.links[link].points.items():
            r = turn @ np.asarray(local, dtype=float)
            points.setdefault(name, (origin + r, state["velocity"][0] + omega * perp(r),
                                     state["acceleration"][0] + epsilon * perp(r)
                                     - omega ** 2 * r))
    return {"points": points, "rates": rates}


def with_special_sides(exercise, angle: float, third: int):
    """The plans drawn with the special point on the lines of the two sides other than
    ``third`` (the drawing's own choice replaced: every choice must give the same plans)."""
    motion = solve(exercise.mechanism, angle, stage="position")
    mechanism = exercise.mechanism

    class Probe:             # what the sides are measured from: the position plan
        def where(self, link, point):
            return motion.links[link].place(mechanism.local(link, point))[0]

    probe = Probe()
    probe.motion = motion
    [group] = motion.structure.groups
    sides = triad._sides(probe, group)
    j, k = [m for m in range(3) if m != third]
    (pj, ej), (pk, ek) = sides[j].line, sides[k].line
    special = pj + cross(pk - pj, ek) / cross(ej, ek) * ej
    with triad._GEOMETRY_LOCK:
        triad._GEOMETRY.setdefault(motion, {})[group.index] = (sides, third, j, k, special)
    return draw_plans(exercise, angle, motion=motion), sides[third]


def assert_exact(plans, expected: dict, links) -> None:
    for name, (_, velocity, acceleration) in expected["points"].items():
        label = name.lower()
        if label in plans.velocity.points_mm:
            assert np.allclose(plans.velocity.vector(label), velocity, atol=1e-12), name
            assert np.allclose(plans.acceleration.vector(label), acceleration,
                               atol=1e-11), name
    for link in links:
        omega, epsilon = expected["rates"][link]
        assert plans.omega(link) == pytest.approx(omega, abs=1e-12), link
        assert plans.epsilon(link) == pytest.approx(epsilon, abs=1e-11), link


@pytest.mark.parametrize("angle", ANGLES)
@pytest.mark.parametrize("third", [0, 1, 2])
def test_the_screens_plans_equal_the_exact_vectors_whichever_sides_meet_in_s(angle, third):
    exercise = exercise_from_dict(screen())
    plans, side = with_special_sides(exercise, angle, third)
    expected = exact(exercise.mechanism, angle)
    assert_exact(plans, expected, ("rod", "screen", "rocker", "block"))
    for label in "abedm":
        assert label in plans.velocity.points_mm and label in plans.acceleration.points_mm
    # the block slides along the fixed guide at 30°: s' = v_D·u, s'' = a_D·u, no Coriolis
    guide = np.array([np.cos(np.radians(30.0)), np.sin(np.radians(30.0))])
    _, v_d, a_d = expected["points"]["D"]
    assert plans.readings["ds_block/frame"] == pytest.approx(v_d @ guide, abs=1e-12)
    assert plans.readings["dds_block/frame"] == pytest.approx(a_d @ guide, abs=1e-11)
    assert plans.readings["coriolis_block/frame"] == 0.0
    assert (side.slide is not None) == (third == 2)


@pytest.mark.parametrize("angle", ANGLES)
@pytest.mark.parametrize("third", [0, 1, 2])
def test_a_screen_sliding_on_a_pinned_block_has_its_coriolis_component(angle, third):
    exercise = exercise_from_dict(slot())
    plans, _ = with_special_sides(exercise, angle, third)
    expected = exact(exercise.mechanism, angle)
    assert_exact(plans, expected, ("rod", "screen", "rocker", "block"))
    # s = (H − D)·d along the screen's line BD (d turns at ω: ḋ = ω·Jd, d̈ = ε·Jd − ω²·d),
    # H fixed: s' = −v_D·d, s'' = −a_D·d − 2ω·v_D·Jd − ω²·s
    position_d, v_d, a_d = expected["points"]["D"]
    position_b = expected["points"]["B"][0]
    d = (position_d - position_b) / np.linalg.norm(position_d - position_b)
    omega = expected["rates"]["screen"][0]
    travel = (np.array([0.62, 0.02]) - position_d) @ d
    sliding = -v_d @ d
    assert plans.readings["ds_block/screen"] == pytest.approx(sliding, abs=1e-12)
    assert plans.readings["dds_block/screen"] == pytest.approx(
        -a_d @ d - 2 * omega * v_d @ perp(d) - omega ** 2 * travel, abs=1e-11)
    assert plans.readings["coriolis_block/screen"] == pytest.approx(abs(2 * omega * sliding),
                                                                     abs=1e-11)
    assert "k_H@screen" in plans.acceleration.points_mm


def test_the_drawing_chooses_a_special_point_and_says_how_it_is_found():
    exercise = exercise_from_dict(screen())
    plans = draw_plans(exercise)
    velocity = [step_text(step, plans.velocity) for step in plans.velocity.steps]
    acceleration = [step_text(step, plans.acceleration) for step in plans.acceleration.steps]
    assert SPECIAL in plans.velocity.points_mm and SPECIAL in plans.acceleration.points_mm
    assert "through d₀: v_DD₀ along the guide of pair 5–0" in velocity
    assert "through k_D: aʳ_DD₀ (relative) along the guide of pair 5–0" in acceleration
    assert any(text.startswith("aᵏ = 0: frame does not turn") for text in acceleration)
    at_250 = draw_plans(exercise, 250.0)
    lines = [step_text(step, at_250.velocity) for step in at_250.velocity.steps]
    assert ("through d₀: v_S*D₀ along the guide of pair 5–0 (S* lies on the normal to the "
            "guide through D)") in lines
    acceleration = [step_text(step, at_250.acceleration) for step in at_250.acceleration.steps]
    assert "through n_S*D: aʳ + aᵗ_S*D along the guide of pair 5–0" in acceleration


def test_the_screen_is_solved_with_every_figure(tmp_path, capsys):
    analysis = analyse(exercise_from_dict(screen()))
    assert analysis.plans is not None
    assert all(check.plan == pytest.approx(check.analytic, abs=1e-9 * max(
        1.0, abs(check.analytic))) for check in analysis.checks)
    assert main(["solve", str(SCREEN), "--svg", str(tmp_path / "screen")]) == 0
    assert sorted(path.name for path in (tmp_path / "screen").iterdir()) == [
        "acceleration.svg", "lever.svg", "position.svg", "velocity.svg"]


def test_a_group_whose_plans_are_not_drawn_says_so_and_writes_the_rest(tmp_path, capsys,
                                                                      monkeypatch):
    path = tmp_path / "screen.toml"
    path.write_text(SCREEN.read_text().replace(
        'sliding = ["block/frame"]', 'sliding = ["block/frame"]\nforces = true') + """
[mass.screen]
m = 20.0
J = 0.25

[mass.rod]
m = 2.0
J = 0.0096
""")
    monkeypatch.setattr(triad, "drawable", lambda group: False)   # as for a tetrad
    capsys.readouterr()
    assert main(["solve", str(path), "--svg", str(tmp_path / "out")]) == 0
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    notes = [line for line in out.out.splitlines() if line.startswith("only the position")]
    assert notes == [
        "only the position plan is drawn: the velocity, acceleration and lever plans of link "
        "screen+rod+rocker+block are not — plans are drawn for class III triads whose side "
        "links have at most one prismatic pair each; this triad is not one — its exact "
        "kinematics is reported (planmethod solve --json)"]
    written = sorted(path.name for path in (tmp_path / "out").iterdir())
    assert written == ["forces_1_screen+rod+rocker+block.svg", "forces_2_crank.svg",
                       "position.svg"]
