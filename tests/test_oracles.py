"""The oracles of :mod:`planmethod.testing.oracles` against each other, and their independence.

The whole-mechanism Newton solve (:func:`reference_motion`) must give the 40-digit closed forms'
positions, velocities and accelerations on the branch the sketch (or ``near``) picks, must run
none of the solver's code (only the generic constraint equations and the link-state helpers
of the kinematics), and must refuse what it cannot reach instead of jumping to another
assembly.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from planmethod.kinematics import solve
from planmethod.spec import exercise_from_dict
from planmethod.testing import (
    exact_fourbar,
    exact_slider_crank,
    fourbar,
    reference_motion,
    shaper,
    slider_crank,
    two_guides,
)
from planmethod.testing.oracles import reference_place as place
from planmethod.testing.oracles import reference_positions
from planmethod.testing.stress import exercise_of, fourbar_case, toggle_fourbar

ANGLES = np.arange(-30.0, 390.0, 7.5)
KINEMATICS = Path(__file__).resolve().parent.parent / "planmethod" / "kinematics"


def _vectors(values) -> np.ndarray:
    return np.array([[float(value[0]), float(value[1])] for value in values])


def _c_of(mechanism, reference) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """C's place, velocity and acceleration from a reference_motion result (on link BC)."""
    state = reference["BC"]
    r = place(mechanism, reference, "C") - state["origin"]
    turned = np.stack((-r[:, 1], r[:, 0]), axis=-1)
    velocity = state["velocity"] + state["omega"][:, None] * turned
    acceleration = (state["acceleration"] + state["epsilon"][:, None] * turned
                    - (state["omega"] ** 2)[:, None] * r)
    return place(mechanism, reference, "C"), velocity, acceleration


@pytest.mark.parametrize("above", [True, False])
def test_fourbar_equals_the_40_digit_closed_form_on_the_sketched_branch(above):
    case = fourbar_case(above=above, epsilon=-30.0)
    mechanism = exercise_of(case).mechanism
    got = _c_of(mechanism, reference_motion(mechanism, ANGLES))
    exact = [exact_fourbar(float(angle), above=above, **case.params) for angle in ANGLES]
    for values, key in zip(got, ("C", "v_C", "a_C"), strict=True):
        want = _vectors([e[key] for e in exact])
        assert np.abs(values - want).max() <= 1e-13 * np.abs(want).max(), key


@pytest.mark.parametrize("forward", [True, False])
def test_slider_crank_equals_the_40_digit_closed_form(forward):
    data = slider_crank(offset=0.02, epsilon=300.0)
    data["sketch"] = {"C": [0.2 if forward else -0.2, -0.02]}
    mechanism = exercise_from_dict(data).mechanism
    got = _c_of(mechanism, reference_motion(mechanism, ANGLES))
    exact = [exact_slider_crank(float(angle), offset=0.02, epsilon=300.0, forward=forward)
             for angle in ANGLES]
    for values, key in zip(got, ("C", "v_C", "a_C"), strict=True):
        want = _vectors([e[key] for e in exact])
        assert np.abs(values - want).max() <= 1e-13 * np.abs(want).max(), key


def test_near_points_pick_the_assembly_instead_of_the_sketch():
    mechanism = exercise_from_dict(fourbar()).mechanism
    sketched = place(mechanism, reference_motion(mechanism, [60.0]), "C")[0]
    lower = exact_fourbar(60.0, above=False)
    flipped = place(mechanism, reference_motion(mechanism, [60.0], near={"C": (0.3, -0.1)}),
                    "C")[0]
    assert np.hypot(*(flipped - _vectors([lower["C"]])[0])) < 1e-14
    assert np.hypot(*(flipped - sketched)) > 0.1


def test_the_shaper_agrees_with_the_solver_over_a_turn():
    """Two groups in series (RPR, then RRP) and a sketch for both."""
    mechanism = exercise_from_dict(shaper()).mechanism
    reference = reference_motion(mechanism, ANGLES)
    motion = solve(mechanism, ANGLES)
    for point in ("C", "D"):
        assert np.abs(place(mechanism, reference, point) - motion.position(point)).max() < 1e-13


def test_unique_assemblies_are_solved_past_where_they_run_off():
    """Two guides turn parallel at 120°: continuation could not pass, each angle is solved on
    its own (the assembly is unique)."""
    mechanism = exercise_from_dict(two_guides()).mechanism
    angles = np.array([30.0, 110.0, 130.0, 250.0])
    links, q = reference_positions(mechanism, angles)
    motion = solve(mechanism, angles, stage="position")
    for index, link in enumerate(links):
        assert np.abs(q[:, 3 * index:3 * index + 2] - motion.links[link].origin).max() < 1e-12


def test_a_toggle_on_the_way_is_refused_not_jumped():
    case = toggle_fourbar(120.0)   # assembled on one side of 120° only
    mechanism = exercise_of(case).mechanism
    beyond = 120.0 + (30.0 if case.drive_angle < 120.0 else -30.0)
    with pytest.raises(ValueError, match="no continuation"):
        reference_motion(mechanism, [case.drive_angle, beyond])


def test_no_code_of_the_solver_runs():
    """Only the generic constraint equations and the link-state helpers of the kinematics are
    called (every Python function call is watched)."""
    mechanism = exercise_from_dict(shaper()).mechanism
    called: set[str] = set()

    def watch(frame, event, argument):
        if event == "call":
            called.add(frame.f_code.co_filename)

    sys.setprofile(watch)
    try:
        reference_motion(mechanism, [0.0, 60.0, 200.0])
    finally:
        sys.setprofile(None)
    used = {Path(name).resolve().relative_to(KINEMATICS).as_posix() for name in called
            if Path(name).resolve().is_relative_to(KINEMATICS)}
    assert used == {"constraints.py", "state.py"}
