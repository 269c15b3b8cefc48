"""Hypothesis properties of the exact kinematics over full turns of random mechanisms."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from planmethod.errors import AssemblyError, ToggleError
from planmethod.kinematics import solve
from planmethod.spec import exercise_from_dict
from planmethod.testing import (
    fourbar,
    reference_motion,
    scotch_yoke,
    slider_crank,
    slotted_lever,
    two_guides,
)

ANGLES = np.arange(0.0, 360.0, 2.5)


@st.composite
def crank_rockers(draw):
    """Grashof crank-rockers: the crank is the shortest link and s + l < p + q."""
    ground = draw(st.floats(0.2, 1.0))
    coupler = draw(st.floats(0.2, 1.0))
    rocker = draw(st.floats(0.2, 1.0))
    crank = draw(st.floats(0.02, 0.19))
    lengths = sorted([ground, coupler, rocker, crank])
    assume(lengths[0] == crank and lengths[0] + lengths[3] < 0.97 * (lengths[1] + lengths[2]))
    return fourbar(ground=ground, crank=crank, coupler=coupler, rocker=rocker,
                   omega=draw(st.floats(-30, 30).filter(lambda w: abs(w) > 0.5)),
                   epsilon=draw(st.floats(-50, 50)),
                   point=(draw(st.floats(-0.3, 0.3)), draw(st.floats(-0.3, 0.3))))


@st.composite
def slider_cranks(draw):
    crank = draw(st.floats(0.01, 0.2))
    rod = draw(st.floats(1.5, 6.0)) * crank
    offset = draw(st.floats(-0.4, 0.4)) * (rod - crank)
    return slider_crank(crank=crank, rod=rod, offset=offset,
                        omega=draw(st.floats(-300, 300).filter(lambda w: abs(w) > 1)),
                        epsilon=draw(st.floats(-500, 500)))


@st.composite
def slotted_levers(draw):
    crank = draw(st.floats(0.02, 0.2))
    return slotted_lever(crank=crank, centres=crank * draw(st.floats(1.3, 5.0)),
                         omega=draw(st.floats(-20, 20).filter(lambda w: abs(w) > 0.5)),
                         epsilon=draw(st.floats(-20, 20)))


MECHANISMS = st.one_of(crank_rockers(), slider_cranks(), slotted_levers())


def _solve(data, angles=ANGLES):
    mechanism = exercise_from_dict(data).mechanism
    try:
        return mechanism, solve(mechanism, angles)
    except (AssemblyError, ToggleError):
        assume(False)


@settings(max_examples=30, deadline=None)
@given(MECHANISMS)
def test_closed_form_agrees_with_the_whole_mechanism_linear_solve(data):
    mechanism, motion = _solve(data)
    reference = reference_motion(mechanism, ANGLES)
    for link, expected in reference.items():
        state = motion.links[link]
        turn = np.angle(np.exp(1j * (state.theta - expected["theta"])))
        assert np.abs(turn).max() <= 1e-9, (link, "theta")
        for name in ("origin", "omega", "velocity", "epsilon", "acceleration"):
            got, want = getattr(state, name), expected[name]
            scale = max(1.0, float(np.abs(want).max()))
            assert np.allclose(got, want, rtol=0, atol=1e-9 * scale), (link, name)


@settings(max_examples=20, deadline=None)
@given(MECHANISMS)
def test_finite_differences_of_exact_positions_converge_to_exact_velocities(data):
    mechanism, motion = _solve(data)
    omega = mechanism.drive.omega
    errors = []
    for step_deg in (0.2, 0.1):
        ahead, behind = _solve(data, ANGLES + step_deg)[1], _solve(data, ANGLES - step_deg)[1]
        dt = np.radians(step_deg) / omega
        # with ε ≠ 0 the sweep is of instantaneous states, so compare positions only (ω const)
        for point in ("C",):
            fd = (ahead.position(point) - behind.position(point)) / (2 * dt)
            errors.append(float(np.abs(fd - motion.velocity(point)).max()))
    scale = float(np.abs(motion.velocity("C")).max())
    assert errors[1] <= 1e-3 * scale + 1e-12
    # second order: halving the step cuts the error by about four
    assert errors[1] <= errors[0] / 3.0 + 1e-9 * scale


@settings(max_examples=30, deadline=None)
@given(MECHANISMS)
def test_rigid_body_conditions(data):
    """Two points of a link: (v_P − v_Q) ⟂ PQ and (a_P − a_Q)·PQ = −ω²|PQ|²."""
    mechanism, motion = _solve(data)
    for name in mechanism.moving_links:
        points = list(mechanism.links[name].points.values())
        if len(points) < 2:
            continue
        p, q = points[0], points[1]
        r = motion.place(name, p) - motion.place(name, q)
        dv = motion.velocity_of(name, p) - motion.velocity_of(name, q)
        da = motion.acceleration_of(name, p) - motion.acceleration_of(name, q)
        scale = float(np.abs(dv).max() * np.abs(r).max()) + 1e-12
        assert np.abs(np.einsum("ij,ij->i", dv, r)).max() <= 1e-9 * scale
        expected = -(motion.omega(name) ** 2) * np.einsum("ij,ij->i", r, r)
        assert np.allclose(np.einsum("ij,ij->i", da, r), expected,
                           atol=1e-9 * (float(np.abs(da).max() * np.abs(r).max()) + 1e-12))


@settings(max_examples=20, deadline=None)
@given(MECHANISMS)
def test_branch_is_continuous_over_the_turn(data):
    """Consecutive positions differ by no more than the path the velocity allows."""
    mechanism, motion = _solve(data, np.arange(0.0, 360.0, 0.5))
    dt = np.radians(0.5) / abs(mechanism.drive.omega)
    for link, state in motion.links.items():
        steps = np.hypot(*np.diff(state.origin, axis=0).T)
        speed = np.hypot(*state.velocity.T)
        bound = (np.maximum(speed[:-1], speed[1:]) * dt * 1.5
                 + 1e-9 * (1 + float(np.abs(state.origin).max())))
        assert np.all(steps <= bound + 0.5 * np.hypot(*state.acceleration.T)[:-1] * dt ** 2
                      * 4), link


@pytest.mark.parametrize("data", [scotch_yoke(), two_guides()], ids=["RPP", "PRP"])
def test_prismatic_dyads_agree_with_the_linear_solve(data):
    # the two-guides dyad is in its toggle where the crank's guide turns parallel to the fixed
    # one (crank at 120° and 300°): stay 5° away from those
    angles = ANGLES[np.abs(((ANGLES - 120.0 + 90.0) % 180.0) - 90.0) > 5.0]
    mechanism = exercise_from_dict(data).mechanism
    motion = solve(mechanism, angles)
    reference = reference_motion(mechanism, angles)
    for link, expected in reference.items():
        for name in ("origin", "omega", "velocity", "epsilon", "acceleration"):
            want = expected[name]
            assert np.allclose(getattr(motion.links[link], name), want,
                               atol=1e-9 * max(1.0, float(np.abs(want).max())))
