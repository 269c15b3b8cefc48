"""Every group kind, fast path against reference path, on random mechanisms.

Each registered group-kind module (:mod:`planmethod.kinematics.groups`) is run two ways on the
same random mechanisms — on both assembly branches where it has two, and at crank angles next to
the dead centres — and the two must agree to 1e-12 relative: the compiled program (the kind's
formulas traced into one straight-line numpy function with a reused workspace, chunk by chunk)
and the direct evaluation (the same formulas run on numpy arrays). The positions are checked
against the pairs' constraint equations and the velocities and accelerations against one exact
linear solve of the whole mechanism (:func:`planmethod.testing.reference_motion`), which shares
nothing with the kinds' vector equations.

Adding a kind means adding its module and a case here: the first test fails for a registered
kind without one.
"""

from __future__ import annotations

import copy
import tomllib
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from planmethod.errors import ToggleError
from planmethod.kinematics import solve
from planmethod.kinematics.constraints import ConstraintSystem
from planmethod.kinematics.groups import kind_module, registered
from planmethod.kinematics.program import model
from planmethod.kinematics.tracing import CHUNK
from planmethod.spec import exercise_from_dict
from planmethod.testing import (
    fourbar,
    reference_motion,
    scotch_yoke,
    slider_crank,
    slotted_lever,
    two_guides,
)

ROOT = Path(__file__).resolve().parent.parent
RELATIVE = 1e-12
DRAWS = 6


def _fourbar(rng: np.random.Generator) -> dict:
    crank = rng.uniform(0.03, 0.08)
    coupler, rocker, ground = rng.uniform(0.15, 0.3, size=3)
    while crank + max(coupler, rocker, ground) >= sum(sorted((coupler, rocker, ground))[:2]):
        coupler, rocker, ground = rng.uniform(0.15, 0.3, size=3)   # Grashof: a crank-rocker
    data = fourbar(ground=ground, crank=crank, coupler=coupler, rocker=rocker,
                   omega=rng.uniform(-20, 20), epsilon=rng.uniform(-50, 50),
                   point=tuple(rng.uniform(-0.1, 0.2, size=2)))
    for link in ("BC", "CD"):     # each link's own frame turned and moved off its points
        turn = rng.uniform(-np.pi, np.pi)
        shift = np.array([rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)])
        rotation = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
        data["links"][link] = {point: (rotation @ np.asarray(xy, dtype=float) + shift).tolist()
                               for point, xy in data["links"][link].items()}
    return data


def _offset(rng: np.random.Generator) -> list[float]:
    """A point's place in its link's own frame, away from the frame's origin (a formula that
    forgot the offset would still hold at the origin)."""
    return [float(rng.uniform(-0.04, 0.04)), float(rng.uniform(-0.04, 0.04))]


def _slider(rng: np.random.Generator) -> dict:
    crank = rng.uniform(0.03, 0.08)
    offset = rng.uniform(-0.02, 0.02)
    data = slider_crank(crank=crank, rod=rng.uniform(2.5, 5) * crank + abs(offset),
                        offset=offset, omega=rng.uniform(-150, 150),
                        epsilon=rng.uniform(-500, 500))
    data["links"]["slider"] = {"C": _offset(rng)}     # the pin away from the slider's origin
    data["slide"][0]["direction"] = float(rng.uniform(-20, 20))    # a guide at an angle
    return data


def _lever(rng: np.random.Generator) -> dict:
    crank = rng.uniform(0.05, 0.12)
    data = slotted_lever(crank=crank, centres=rng.uniform(1.3, 3.0) * crank,
                         omega=rng.uniform(-15, 15), epsilon=rng.uniform(-40, 40))
    slot = rng.uniform(-40, 40)                 # the slot at an angle in the lever …
    data["slide"][0]["direction"] = slot
    # … and off its pivot: through T, a few mm beside the line through O2; the block's pin
    # and the lever's points away from their links' origins
    o2 = _offset(rng)
    aside, u = rng.uniform(-0.005, 0.005), np.radians(slot)
    data["links"]["lever"] = {"O2": o2, "C": [o2[0] + 1.5 * (crank + 0.3), o2[1]],
                              "T": [o2[0] + 0.1 * np.cos(u) - aside * np.sin(u),
                                    o2[1] + 0.1 * np.sin(u) + aside * np.cos(u)]}
    # the block touches the slot at S, a few mm from its pin B
    pin = _offset(rng)
    data["links"]["block"] = {"B": pin, "S": [pin[0] + 0.004, pin[1] - 0.003]}
    data["slide"][0]["through"] = "T"
    data["slide"][0]["point"] = "S"
    return data


def _yoke(rng: np.random.Generator) -> dict:
    data = scotch_yoke(crank=rng.uniform(0.05, 0.15), slot=rng.uniform(60, 120),
                       guide=rng.uniform(-20, 20), omega=rng.uniform(-15, 15),
                       epsilon=rng.uniform(-40, 40))
    y = _offset(rng)
    data["links"]["block"] = {"B": _offset(rng)}
    data["links"]["yoke"] = {"Y": y, "Z": [y[0] + 0.2, y[1] + 0.1]}
    return data


def _guides(rng: np.random.Generator) -> dict:
    data = two_guides(omega=rng.uniform(-15, 15), epsilon=rng.uniform(-40, 40))
    data["slide"][0]["direction"] = rng.uniform(40, 80)
    data["slide"][1]["direction"] = rng.uniform(-20, 20)
    data["links"]["s1"] = {"Q": _offset(rng)}
    data["links"]["s2"] = {"Q": _offset(rng)}
    return data


def _conveyor() -> dict:
    return tomllib.loads((ROOT / "exercises" / "conveyor_sixbar.toml").read_text())


def _triad(rng: np.random.Generator) -> dict:
    data = _conveyor()
    for link in ("rod", "rocker_EF", "rocker_DG"):
        for point, (x, y) in data["links"][link].items():
            data["links"][link][point] = [x * rng.uniform(0.99, 1.01), y]
    data["drive"]["omega"] = rng.uniform(-10, 10)
    data["drive"]["epsilon"] = rng.uniform(-20, 20)
    return data


def _slider_triad(rng: np.random.Generator) -> dict:
    """The conveyor with the rocker DG replaced by a block on a fixed guide: a triad with a
    prismatic pair (the general higher system)."""
    data = _conveyor()
    del data["links"]["rocker_DG"]
    del data["mass"]["rocker_DG"]
    data["links"]["block"] = {"D": [0.0, 0.0]}
    data["links"]["frame"]["H"] = [0.79, -0.183]
    data["slide"] = [{"link": "block", "along": "frame", "through": "H",
                      "direction": rng.uniform(75, 85)}]
    data["mass"]["block"] = {"m": 2.0, "J": 0.001}
    return data


#: kind module → random mechanisms whose groups include that kind
CASES: dict[str, Callable[[np.random.Generator], dict]] = {
    "rrr": _fourbar, "rrp": _slider, "rpr": _lever, "rpp": _yoke, "prp": _guides,
    "triad": _triad, "higher": _slider_triad,
}
#: dead centres are looked for on modules that have them (where the driven link reverses)
SLOW_MODULES = {"triad", "higher"}


def test_every_registered_kind_has_a_case():
    modules = {module.name for modules in registered().values() for module in modules}
    assert modules == set(CASES), f"registered kinds without a case: {modules - set(CASES)}"


def _mechanisms(name: str, sign: int | None = None):
    rng = np.random.default_rng(sum(map(ord, name)))
    for _ in range(2 if name in SLOW_MODULES else DRAWS):
        data = CASES[name](rng)
        yield exercise_from_dict(copy.deepcopy(data)).mechanism


def _dead_centres(mechanism, link: str) -> np.ndarray:
    """Crank angles where ``link``'s angular velocity (or a slider's speed) changes sign, to
    within 1e-7°."""
    grid = np.arange(0.0, 360.0, 0.5)
    motion = solve(mechanism, grid, stage="velocity")
    rate = motion.omega(link)
    if np.allclose(rate, 0.0):
        return np.array([])
    flips = np.flatnonzero(np.sign(rate[:-1]) != np.sign(rate[1:]))
    out = []
    for index in flips:
        low, high = grid[index], grid[index + 1]
        for _ in range(40):
            middle = 0.5 * (low + high)
            value = float(solve(mechanism, middle, stage="velocity").at(0).omega(link))
            if np.sign(value) == np.sign(rate[index]):
                low = middle
            else:
                high = middle
        out += [low, high, low - 1e-6, high + 1e-6]
    return np.array(out)


def _grid(mechanism) -> np.ndarray:
    """Crank angles every 7.3° — for two guides, more than 8° from where they are parallel
    (their toggle, which is refused: see tests/test_stress.py)."""
    grid = np.arange(0.0, 360.0, 7.3) + 0.123
    slides = {slide.along: slide for slide in mechanism.slides}
    if "crank" in slides and "frame" in slides:
        parallel = slides["frame"].direction - slides["crank"].direction
        gap = np.abs((grid - parallel + 90.0) % 180.0 - 90.0)
        grid = grid[gap > 8.0]
    return grid


def _angles(mechanism, group) -> np.ndarray:
    angles = [_grid(mechanism)]
    driven = [link for link in group.links if link != mechanism.drive.link]
    for link in driven[-1:]:
        angles.append(_dead_centres(mechanism, link))
    return np.concatenate(angles)


def _compare(fast, slow, mechanism, what: str) -> None:
    points = list(dict.fromkeys(p for link in mechanism.links.values() for p in link.points))
    for point in points:
        for quantity in ("position", "velocity", "acceleration"):
            a, b = getattr(fast, quantity)(point), getattr(slow, quantity)(point)
            scale = max(float(np.abs(b).max()), 1e-300)
            assert np.abs(a - b).max() <= RELATIVE * scale, (what, point, quantity)
    for link in mechanism.links:
        for quantity in ("theta", "omega", "epsilon"):
            a, b = getattr(fast, quantity)(link), getattr(slow, quantity)(link)
            scale = max(float(np.abs(b).max()), 1.0 if quantity == "theta" else 1e-300)
            assert np.abs(a - b).max() <= RELATIVE * scale, (what, link, quantity)


@pytest.mark.parametrize("name", sorted(CASES))
def test_fast_path_equals_reference_path(name):
    for mechanism in _mechanisms(name):
        groups = model(mechanism).structure.groups
        kinds = {kind_module(group).name for group in groups}
        assert name in kinds, f"the {name} case has no {name} group: {kinds}"
        group = next(g for g in groups if kind_module(g).name == name)
        signs = [1, -1] if kind_module(group).branches == 2 else [None]
        for sign in signs:
            branches = None
            if sign is not None:
                chosen = dict(model(mechanism).branches())
                chosen[group.index] = type(chosen[group.index])(sign, "given")
                branches = chosen
            angles = _angles(mechanism, group) if sign in (None, 1) else _grid(mechanism)
            fast = solve(mechanism, angles, branches=branches)
            slow = solve(mechanism, angles, branches=branches, reference=True)
            _compare(fast, slow, mechanism, f"{name} branch {sign}")


@pytest.mark.parametrize("name", sorted(CASES))
def test_against_the_whole_mechanism_linear_solve(name):
    for mechanism in _mechanisms(name):
        angles = _grid(mechanism)
        motion = solve(mechanism, angles)
        # positions close every pair …
        moving = [link for link in mechanism.moving_links if link != mechanism.drive.link]
        system = ConstraintSystem.between(mechanism, moving)
        size = max(abs(v) for link in mechanism.links.values() for p in link.points.values()
                   for v in p)
        assert np.abs(system.residual(motion.links)).max() <= 1e-13 * max(size, 1.0)
        for link, state in motion.links.items():   # each link's axes are (cos θ, sin θ)
            axes = np.stack((np.cos(state.theta), np.sin(state.theta)), axis=-1)
            assert np.abs(state.basis - axes).max() <= 1e-13, (name, link)
        # … and the velocities and accelerations are the whole mechanism's linear solve's,
        # on the assembly the solver chose at drive.angle (a link's two assemblies can put
        # its points alike and its origin apart)
        chosen = solve(mechanism, stage="position")
        near = {point: tuple(float(v) for v in chosen.at(0).position(point))
                for link in chosen.solved if link != "frame"
                for point in mechanism.links[link].points}
        reference = reference_motion(mechanism, angles, near=near)
        for quantity in ("omega", "epsilon", "velocity", "acceleration"):
            # relative to the largest such quantity of any link (a pivot's zero velocity
            # is compared with the mechanism's speeds)
            scale = max(float(np.abs(expected[quantity]).max())
                        for expected in reference.values())
            for link, expected in reference.items():
                got = getattr(motion.links[link], quantity)
                assert np.abs(got - expected[quantity]).max() <= 1e-12 * scale, (
                    name, link, quantity)


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_velocity_stage_computes_what_the_acceleration_stage_does(name):
    """Solving to the velocities only stops earlier: positions and velocities (ω included)
    are those of the solve to accelerations, for every kind of group."""
    mechanism = next(_mechanisms(name))
    angles = _grid(mechanism)
    velocity = solve(mechanism, angles, stage="velocity")
    acceleration = solve(mechanism, angles, stage="acceleration")
    for link, state in acceleration.links.items():
        fast = velocity.links[link]
        assert np.array_equal(fast.origin, state.origin), (name, link)
        assert np.allclose(fast.velocity, state.velocity, rtol=0, atol=1e-12), (name, link)
        assert np.allclose(fast.omega, state.omega, rtol=0, atol=1e-12), (name, link)


@pytest.mark.parametrize("name", ["triad", "higher"])
def test_a_higher_groups_move_is_measured_in_metres(name):
    """How far Newton moved a solution from its prediction (judged against half the predicted
    move) is measured in metres: a link's x and y as they are, its angle θ times the group's
    size; the plain triad's q is its central link's (x, y, θ), the general system's every
    group link's."""
    from planmethod.kinematics.groups.base import GroupInputs
    from planmethod.kinematics.groups.higher import GeneralSystem
    from planmethod.kinematics.groups.triad import TriadSystem
    from planmethod.structure import analyse_structure

    mechanism = exercise_from_dict(CASES[name](np.random.default_rng(7))).mechanism
    (group,) = [g for g in analyse_structure(mechanism).groups if len(g.links) == 4]
    make = TriadSystem if name == "triad" else GeneralSystem
    system = make(GroupInputs(mechanism, group, {}, 1.0, np.array([0.0]), {}))
    assert system.size == 3 * (1 if name == "triad" else len(group.links))
    for index in range(system.size):
        move = np.zeros((1, system.size))
        move[0, index] = 1e-3
        metres = 1e-3 * (system.length if index % 3 == 2 else 1.0)
        assert float(system.norm(move)[0]) == pytest.approx(metres, rel=1e-12), index


def test_a_dyad_hung_on_a_general_higher_group_closes_every_pair():
    """The general higher group (the triad with a block) with a dyad hung on its tray's point
    T: the group's equations are its own pairs and those with the links known before it,
    never the later dyad's; every pair of the mechanism closes over the turn, and the fast
    path is the reference path."""
    data = _slider_triad(np.random.default_rng(sum(map(ord, "higher"))))
    data["links"]["tray"]["T"] = [0.3, 0.0]
    data["links"]["frame"]["W"] = [0.2514386, -0.18159618]      # 0.3 m right of T at 135°
    data["links"]["arm1"] = {"T": [0, 0], "V": [0.2, 0]}
    data["links"]["arm2"] = {"V": [0, 0], "W": [0.2, 0]}
    data["sketch"]["V"] = [0.1014386, -0.05159618]
    data["mass"] |= {"arm1": {"m": 1.0, "J": 0.001}, "arm2": {"m": 1.0, "J": 0.001}}
    mechanism = exercise_from_dict(data).mechanism
    angles = np.arange(0.0, 360.0, 30.0) + 0.123
    motion = solve(mechanism, angles)
    moving = [link for link in mechanism.moving_links if link != mechanism.drive.link]
    system = ConstraintSystem.between(mechanism, moving)
    assert np.abs(system.residual(motion.links)).max() <= 1e-13
    _compare(motion, solve(mechanism, angles, reference=True), mechanism, "hung dyad")


def test_long_sweeps_run_chunk_by_chunk_with_the_same_numbers():
    mechanism = exercise_from_dict(fourbar()).mechanism
    angles = np.linspace(0.0, 720.0, 3 * CHUNK + 17)
    whole = solve(mechanism, angles)
    for start in (0, CHUNK - 3, 2 * CHUNK + 5):
        part = solve(mechanism, angles[start:start + 40])
        assert np.array_equal(part.acceleration("C"), whole.acceleration("C")[start:start + 40])


@pytest.mark.parametrize("data, angles, told", [
    pytest.param(two_guides(), [100.0, 120.0, 130.0],
                 "link s1+s2, crank angle 120°: the guides of s1/crank and s2/frame are "
                 "parallel: Q has no definite position", id="PRP"),
    pytest.param(scotch_yoke(slot=0.0), [30.0, 40.0],
                 "link block+yoke, crank angle 30°: the guides of block/yoke and yoke/frame "
                 "are parallel: yoke has no definite position", id="RPP"),
])
def test_parallel_guides_are_a_named_toggle_at_the_first_angle_they_meet(data, angles, told):
    """Both paths (the compiled program's guard and the kind's formulas) stop at the angle,
    naming the group and the guides."""
    mechanism = exercise_from_dict(data).mechanism
    for reference in (False, True):
        with pytest.raises(ToggleError) as caught:
            solve(mechanism, np.array(angles), reference=reference)
        assert str(caught.value) == told
        assert (caught.value.link, caught.value.angle) == (told.split()[1].rstrip(","),
                                                           float(told.split()[4][:-2]))


def _slot_beside_the_pivot(aside: float, **lever) -> dict:
    data = slotted_lever(**lever)
    data["links"]["lever"]["T"] = [0.1, aside]
    data["slide"][0]["through"] = "T"
    return data


@pytest.mark.parametrize("data, angles, told", [
    pytest.param(_slot_beside_the_pivot(0.25, crank=0.1, centres=0.3),
                 [30.0, 200.0, 250.0, 270.0],
                 "link block+lever, crank angle 250°: the guide of lever passes 0.25 m from "
                 "its pivot O2; it cannot reach B: short by 0.0411497 m",
                 id="slot beyond the pin's reach"),
    pytest.param(slotted_lever(crank=0.3, centres=0.3, angle=0.0), [0.0, 180.0, 270.0],
                 "link block+lever, crank angle 270°: B and O2 coincide: the group has no "
                 "definite position", id="pin on the pivot"),
    pytest.param(fourbar(ground=0.3, crank=0.3, coupler=0.2, rocker=0.2), [60.0, 30.0, 0.0],
                 "link BC+CD, crank angle 0°: B and D coincide: the group has no definite "
                 "position", id="four-bar's crank pin on the rocker's pivot"),
])
def test_a_dyad_that_cannot_be_placed_says_where_and_why(data, angles, told):
    """The refusals of the RPR and RRR kinds, on both paths, at the first angle where they
    hold: a slot passing its pivot farther than the pin can come, and a pin on the pivot (two
    points that coincide are no shortfall: nothing is said to be short)."""
    from planmethod.errors import AssemblyError

    mechanism = exercise_from_dict(data).mechanism
    for reference in (False, True):
        with pytest.raises(AssemblyError) as caught:
            solve(mechanism, np.array(angles), reference=reference)
        assert str(caught.value) == told
        assert caught.value.link == told.split()[1].rstrip(",")
    assert solve(mechanism, np.array(angles[:2])).position("B").shape == (2, 2)
