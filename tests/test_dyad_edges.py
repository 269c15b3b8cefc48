"""Where the revolute dyads stop, and the rounding rules that tell a toggle from a miss.

A four-bar's coupler and rocker (RRR) and a slider-crank's rod and slider (RRP) are placed in
closed form; at the positions where the closed form has no answer the kind refuses, naming
the group, the crank angle and what is wrong (docs/accuracy.md):

- the links cannot reach: an AssemblyError saying by how much (m);
- the vanishing factor of the closed form (a + b − |P1P2| or |P1P2| − |a − b| for RRR,
  a − |h| for RRP) lies within 16 ε of the size of the terms it was computed from: its sign
  is lost in rounding, the two assemblies coincide — a ToggleError;
- the two pins coincide (closer than 1e-15 of the links' length): no definite position.

The positions here are built from exactly representable numbers (at crank angle 0° the crank
pin is exactly at (r, 0)), so a vanishing factor of k·ε is exactly k·ε and the boundary of
the rule can be stepped over by one rounding unit. Every case runs on both paths: the compiled
program (its guard, then the exact check) and the kind's formulas run directly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from planmethod.errors import AssemblyError, ToggleError
from planmethod.kinematics import solve
from planmethod.kinematics.groups import kind_module
from planmethod.kinematics.groups.base import GroupInputs
from planmethod.spec import exercise_from_dict
from planmethod.structure import analyse_structure
from planmethod.testing import fourbar, slider_crank

EPS = float(np.finfo(float).eps)
#: a toggle's vanishing factor is within this many ε of its terms' size (docs/accuracy.md)
UNITS = 16.0


def _refusal(data: dict, angles, stage: str = "acceleration"):
    """The error both paths raise (they must agree on its type, text and angle)."""
    mechanism = exercise_from_dict(data).mechanism
    caught = []
    for reference in (False, True):
        with pytest.raises((AssemblyError, ToggleError)) as error:
            solve(mechanism, np.array(angles, dtype=float), stage=stage, reference=reference)
        caught.append(error.value)
    compiled, direct = caught
    assert (type(compiled), str(compiled), compiled.angle) == (type(direct), str(direct),
                                                               direct.angle)
    return compiled


def _placed(data: dict, angles):
    """A solved motion and the dyad's closed-form placement at its positions."""
    mechanism = exercise_from_dict(data).mechanism
    motion = solve(mechanism, np.array(angles, dtype=float), stage="position")
    group = next(g for g in analyse_structure(mechanism).groups if g.is_dyad)
    index = group.index
    bodies = {link: motion.body(link) for link in motion.solved if link not in group.links}
    context = GroupInputs(mechanism, group, bodies, motion.branches[index].sign,
                          motion.angles, {})
    return motion, index, kind_module(group).place(context)


# -- RRR: the coupler and the rocker of a four-bar ---------------------------------------------
def _four_bar(ground: float, crank: float, coupler: float, rocker: float,
              angle: float = 0.0, lift: float = 0.0) -> dict:
    """A four-bar A = (0, 0), D = (ground, ``lift``), driven from ``angle`` (where it must
    close)."""
    data = fourbar(ground=ground, crank=crank, coupler=coupler, rocker=rocker, angle=angle)
    data["links"]["frame"]["D"] = [ground, lift]
    return data


@pytest.mark.parametrize("coupler, rocker", [(0.2, 0.15), (0.15, 0.2)])
def test_a_four_bar_too_short_to_close_says_by_how_much(coupler, rocker):
    """Stretched out: the coupler and the rocker fall short of B→D by |BD| − (a + b), first
    at the first angle in the order given (B and D off the frame's x-axis there: 100°)."""
    crank, ground, lift = 0.1, 0.31, -0.05
    angles = [0.0, 100.0, 180.0]
    error = _refusal(_four_bar(ground, crank, coupler, rocker, lift=lift), angles)
    assert isinstance(error, AssemblyError) and not isinstance(error, ToggleError)
    b = crank * np.array([math.cos(math.radians(100.0)), math.sin(math.radians(100.0))])
    short = math.dist(b, (ground, lift)) - coupler - rocker
    assert error.angle == 100.0 and error.link == "BC+CD"
    assert error.shortfall == pytest.approx(short, rel=1e-12)
    assert str(error) == (f"link BC+CD, crank angle 100°: BC (BC = {coupler:g} m) and CD (CD = "
                          f"{rocker:g} m) cannot join B and D: short by {short:.6g} m")


@pytest.mark.parametrize("coupler, rocker", [(0.5, 0.1), (0.1, 0.5)])
def test_a_four_bar_folded_too_far_says_by_how_much(coupler, rocker):
    """Folded in: B comes closer to D than |a − b|, short by |a − b| − |BD|."""
    crank, ground = 0.1, 0.35
    angles = [180.0, 60.0, 0.0]
    error = _refusal(_four_bar(ground, crank, coupler, rocker, 180.0), angles)
    assert isinstance(error, AssemblyError)
    b = crank * np.array([math.cos(math.radians(60.0)), math.sin(math.radians(60.0))])
    short = abs(coupler - rocker) - math.dist(b, (ground, 0.0))
    assert error.angle == 60.0
    assert error.shortfall == pytest.approx(short, rel=1e-12)
    assert str(error).endswith(f"cannot join B and D: short by {short:.6g} m")


@pytest.mark.parametrize("units, toggle", [(80, True), (96, True), (98, False), (112, False)])
def test_stretched_out_by_rounding_units_is_a_toggle_beyond_them_a_miss(units, toggle):
    """B = (1, 0), D = (3 + kε, 0), a = b = 1: the factor a + b − |BD| is exactly −kε; the
    terms' size is a + b + |BD| + max|BD's components| = 6 + 2kε, so k ≤ 96 is a toggle and
    beyond it the links miss by kε."""
    error = _refusal(_four_bar(3.0 + units * EPS, 1.0, 1.0, 1.0), [0.0])
    if toggle:
        assert isinstance(error, ToggleError)
        assert "toggle position" in str(error) and error.angle == 0.0
    else:
        assert isinstance(error, AssemblyError)
        assert error.shortfall == units * EPS


@pytest.mark.parametrize("units, toggle", [(100, True), (142, True), (146, False)])
@pytest.mark.parametrize("size", [1.0, 0.125])
def test_stretched_short_of_its_reach_by_rounding_units_is_a_toggle(units, toggle, size):
    """From inside: a = b = 1.5, |BD| = 3 − kε (the group does close): the factor kε is lost
    in rounding up to 16ε·(a + b + 2|BD|) ≈ 144ε — a toggle, refused before any number is taken
    from it (the compiled program's guard must let the exact check see it, for links longer
    and shorter than 1 m: the same mechanism at 1/8 size, exactly); beyond, the dyad's
    position is solved."""
    data = _four_bar((4.0 - units * EPS) * size, size, 1.5 * size, 1.5 * size)
    if toggle:
        assert isinstance(_refusal(data, [0.0], stage="position"), ToggleError)
    else:
        for reference in (False, True):
            motion = solve(exercise_from_dict(data).mechanism, np.array([0.0]),
                           stage="position", reference=reference)
            assert np.all(np.isfinite(motion.position("C")))


@pytest.mark.parametrize("coupler, rocker, units, toggle", [
    (2.0, 1.0, 40, True), (2.0, 1.0, 78, True), (2.0, 1.0, 82, False),
    (1.0, 2.0, 40, True)])
def test_folded_in_by_rounding_units_is_a_toggle(coupler, rocker, units, toggle):
    """Folded: a − b = ±1, B = (1, 0), D = (2 + kε, 0): the factor |BD| − |a − b| = kε is
    lost in rounding up to 16ε·(a + b + |BD| + |BD|) ≈ 80ε; it is the factor nearer zero of
    the two, which the check takes."""
    data = _four_bar(2.0 + units * EPS, 1.0, coupler, rocker)
    if toggle:
        assert isinstance(_refusal(data, [0.0], stage="position"), ToggleError)
    else:
        solve(exercise_from_dict(data).mechanism, np.array([0.0]), stage="position")


def test_pins_closer_than_a_rounding_of_the_links_coincide():
    """B and D 1e-15 m apart under links of 5 m: below 1e-15 of the links' length (10 m),
    they coincide — no definite position, no shortfall."""
    error = _refusal(_four_bar(0.5 + 1e-15, 0.5, 5.0, 5.0), [0.0], stage="position")
    assert isinstance(error, AssemblyError)
    assert str(error) == ("link BC+CD, crank angle 0°: B and D coincide: the group has no "
                          "definite position")
    assert error.shortfall == 0.0


def _random_four_bar(rng: np.random.Generator, scale: float) -> dict:
    crank = rng.uniform(0.03, 0.06) * scale
    coupler, rocker = rng.uniform(0.15, 0.3, size=2) * scale
    return fourbar(ground=(coupler + rocker) * 0.85, crank=crank, coupler=coupler,
                   rocker=rocker, angle=0.0)


def _random_slider_crank(rng: np.random.Generator, scale: float) -> dict:
    crank = rng.uniform(0.03, 0.06) * scale
    return slider_crank(crank=crank, rod=rng.uniform(1.2, 3.0) * crank,
                        offset=rng.uniform(-0.1, 0.1) * crank, angle=0.0)


@pytest.mark.parametrize("build", [_random_four_bar, _random_slider_crank])
@pytest.mark.parametrize("scale", [1.0, 10.0])
def test_the_size_ratio_bound_holds_at_every_position(build, scale):
    """The compiled program checks a stage's digits only where the line sine is small for the
    bound R̂ of the size ratio R = L/l it was given (docs/accuracy.md): R̂ must be at least R at
    every assembled position, for links of centimetres and of metres. It is the largest R the
    kind can reach (2(a + b)/min(a, b) with the links stretched out, 2 for a rod and its
    slider), so on a mechanism driven near the stretched position R comes within 10 % of it."""
    rng = np.random.default_rng(5)
    for _ in range(4):
        motion, index, placed = _placed(build(rng, scale), np.linspace(0.0, 360.0, 73))
        ratio = motion.groups[index].construction.size_ratio()
        assert np.all(ratio <= placed.ratio_bound)
        assert np.max(ratio) > 0.9 * placed.ratio_bound


# -- RRP: the rod and the slider of a slider-crank -----------------------------------------------
def _slider(crank: float, rod: float, offset: float, direction: float = 0.0,
            pin=(0.0, 0.0), angle: float = 90.0) -> dict:
    """A slider-crank A = (0, 0) whose guide runs through G = (0, −``offset``) at
    ``direction`` (°), the slider's pin C at ``pin`` on it, driven from ``angle``."""
    data = slider_crank(crank=crank, rod=rod, offset=offset, angle=angle)
    data["slide"][0]["direction"] = direction
    # the slider touches the guide at S, its origin; its pin C sits at ``pin`` beside it
    data["links"]["slider"] = {"C": list(pin), "S": [0.0, 0.0]}
    data["slide"][0]["point"] = "S"
    data["sketch"] = {}
    return data


@pytest.mark.parametrize("direction, pin", [(0.0, (0.0, 0.0)), (15.0, (0.01, -0.02))])
def test_a_rod_too_short_for_its_guide_says_by_how_much(direction, pin):
    """The rod cannot reach the line the slider's pin C runs on: short by the distance from B
    to that line less the rod's length, at the first angle that fails (here 90°: B straight
    above A, the guide 0.2 m below A, tilted, the pin off the slider's origin)."""
    crank, rod, offset = 0.1, 0.15, 0.2
    error = _refusal(_slider(crank, rod, offset, direction, pin, 270.0), [270.0, 90.0, 0.0])
    u = math.radians(direction)
    along, normal = np.array([math.cos(u), math.sin(u)]), np.array([-math.sin(u), math.cos(u)])
    # the line of C: through G = (0, −offset) on the frame, C at `pin` on the slider, whose
    # axes are the guide's
    c_line = np.array([0.0, -offset]) + pin[0] * along + pin[1] * normal
    b = crank * np.array([math.cos(math.radians(90.0)), math.sin(math.radians(90.0))])
    short = abs(float(np.dot(b - c_line, normal))) - rod
    assert isinstance(error, AssemblyError) and error.angle == 90.0
    assert error.shortfall == pytest.approx(short, rel=1e-12)
    assert str(error) == (f"link BC+slider, crank angle 90°: BC (BC = {rod:g} m) cannot reach "
                          f"the line of C along frame's guide: short by {short:.6g} m")


@pytest.mark.parametrize("crank, units, toggle", [
    (1.0, 60, True), (1.0, 94, True), (1.0, 98, False), (2.0, 126, True), (2.0, 130, False)])
def test_a_rod_across_its_guide_by_rounding_units_is_a_toggle(crank, units, toggle):
    """The rod (a = 2) just reaches the guide y = r + 2 − kε from B = (≈0, r) at 90°: the
    factor a − |h| = kε is lost in rounding up to 16ε·(a + |line| + |B|) ≈ 16ε·(4 + 2r) — a
    toggle (the rod across the guide), for a crank r of 1 m and of 2 m (the guard's bound
    grows with it); beyond it the slider's position is solved."""
    data = _slider(crank, 2.0, -(crank + 2.0 - units * EPS))
    if toggle:
        error = _refusal(data, [90.0], stage="position")
        assert isinstance(error, ToggleError) and error.angle == 90.0
    else:
        for reference in (False, True):
            motion = solve(exercise_from_dict(data).mechanism, np.array([90.0]),
                           stage="position", reference=reference)
            assert motion.position("C")[0, 1] == crank + 2.0 - units * EPS


@pytest.mark.parametrize("units, toggle", [(90, True), (100, False)])
def test_a_rod_missing_its_guide_by_rounding_units(units, toggle):
    """From outside: the guide at y = 3 + kε, beyond the rod's reach by kε: a toggle while kε
    is lost in rounding, beyond it a miss by exactly kε."""
    error = _refusal(_slider(1.0, 2.0, -(3.0 + units * EPS)), [90.0], stage="position")
    if toggle:
        assert isinstance(error, ToggleError)
    else:
        assert isinstance(error, AssemblyError) and error.shortfall == units * EPS


@pytest.mark.parametrize("pin", [(1.0, 0.0), (0.0, 1.0), (0.0, 0.0)])
def test_a_slider_whose_pin_is_off_its_origin_keeps_its_origin_on_the_guide(pin):
    """The slider's frame at its origin S, which runs on the guide through G = (0, −0.3) at
    20°; its pin C at ``pin`` in that frame (1 m along or across it, or at S): on both paths,
    S stays on the guide, C sits at ``pin`` turned by the guide's angle from S, and the rod
    keeps its length."""
    direction = 20.0
    data = _slider(0.2, 1.5, 0.3, direction, pin, angle=30.0)
    u = math.radians(direction)
    along, normal = np.array([math.cos(u), math.sin(u)]), np.array([-math.sin(u), math.cos(u)])
    angles = np.array([30.0, 75.0, 160.0, 250.0])
    for reference in (False, True):
        motion = solve(exercise_from_dict(data).mechanism, angles, reference=reference)
        s, c, b = motion.position("S"), motion.position("C"), motion.position("B")
        assert np.allclose((s - [0.0, -0.3]) @ normal, 0.0, atol=1e-12)
        assert np.allclose(c - s, pin[0] * along + pin[1] * normal, atol=1e-12)
        assert np.allclose(np.hypot(*(c - b).T), 1.5, rtol=1e-12)


@pytest.mark.parametrize("reversed_slide", [False, True])
def test_the_rod_and_the_slider_turn_as_their_frames_say(reversed_slide):
    """θ of a link is the angle of its own +x axis: the rod's frame turned and moved off its
    pins (B at (0.02, 0.01), C beyond it at 37°), so θ_rod = angle(BC) − 37°; the slider turned
    by the guide's 25° against the frame — written either way round (the slider along the
    frame's guide, or the frame along the slider's), so θ_slider = ±25° as the pair says."""
    data = _slider(0.2, 0.6, 0.1, 25.0, angle=40.0)
    turn = math.radians(37.0)
    b_local = (0.02, 0.01)
    data["links"]["BC"] = {"B": list(b_local),
                           "C": [b_local[0] + 0.6 * math.cos(turn),
                                 b_local[1] + 0.6 * math.sin(turn)]}
    if reversed_slide:      # the guide is the slider's, and the frame's point G runs on it
        data["slide"][0] = {"link": "frame", "along": "slider", "through": "S", "point": "G",
                            "direction": -25.0}
    angles = np.array([40.0, 130.0, 220.0, 310.0])
    for reference in (False, True):
        motion = solve(exercise_from_dict(data).mechanism, angles, reference=reference)
        rod = motion.position("C") - motion.position("B")
        assert np.allclose(motion.theta("BC"), np.arctan2(rod[:, 1], rod[:, 0]) - turn,
                           atol=1e-12)
        assert np.allclose(motion.theta("slider"), math.radians(25.0), atol=1e-12)
