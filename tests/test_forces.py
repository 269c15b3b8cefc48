"""Kinetostatics: REFERENCE_CASES case A, every dyad kind against the whole-system solve,
Zhukovsky's lever, the power balance, inertia, loads, friction, and bad input."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from planmethod import testing
from planmethod.errors import ConvergenceError, ForceError, SpecError
from planmethod.forces import solve_forces
from planmethod.forces.applied import Wrench, applied_loads
from planmethod.forces.group_method import solve_by_groups
from planmethod.forces.system import solve_whole_system
from planmethod.kinematics import solve
from planmethod.kinematics.state import LinkState
from planmethod.model import Load
from planmethod.report import analyse, report_dict
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.vectors import cross, perp
from planmethod.words import render

CASE_A = "exercises/fourbar_forces.toml"
BALANCING_A = {0.0: -0.910965, 60.0: 0.642055, 150.0: -0.577299}
REACTIONS_A_60 = {"A": ("frame", "AB", (-17.95286, -15.04389)),
                  "B": ("AB", "BC", (-15.95286, -11.57979)),
                  "C": ("BC", "CD", (-4.48865, -0.67895)),
                  "D": ("frame", "CD", (-1.10951, -2.30054))}


@pytest.fixture(scope="module")
def case_a():
    exercise = load_exercise(CASE_A)
    motion = solve(exercise.mechanism, list(BALANCING_A))
    return exercise, motion, solve_forces(motion)


def test_case_a_balancing_moment_by_every_method(case_a):
    _, _, solution = case_a
    expected = np.array(list(BALANCING_A.values()))
    assert np.allclose(solution.balancing_moment, expected, atol=1e-6, rtol=0)
    assert np.allclose(solution.system.balancing_moment, expected, atol=1e-6, rtol=0)
    assert np.allclose(solution.lever.balancing_moment, expected, atol=1e-6, rtol=0)
    assert np.allclose(solution.power_moment, expected, atol=1e-6, rtol=0)
    assert np.all(solution.power_residual < 1e-12)
    assert np.all(solution.agreement < 1e-12)


def test_case_a_reactions_at_60(case_a):
    _, _, solution = case_a
    for key, (source, target, force) in REACTIONS_A_60.items():
        for found in (solution.reactions[key], solution.system.reactions[key]):
            assert (found.source, found.target) == (source, target)
            assert np.allclose(found.force[1], force, atol=1e-5, rtol=0), key
    # the reference prints five decimals; the two solves agree far below that
    for key in REACTIONS_A_60:
        assert np.allclose(solution.reactions[key].force, solution.system.reactions[key].force,
                           atol=1e-12, rtol=0)


def test_case_a_report_block_and_plans():
    analysis = analyse(load_exercise(CASE_A))
    report = report_dict(analysis)
    forces = report["forces"]
    json.dumps(report, allow_nan=False)
    assert forces["balancing_moment"] == pytest.approx(0.642055, abs=1e-6)
    assert forces["zhukovsky_moment"] == pytest.approx(0.642055, abs=1e-6)
    assert forces["zhukovsky"]["source"] == "velocity plan"
    assert forces["power_residual"] < 1e-12
    assert forces["power_balance_moment"] == pytest.approx(0.642055, abs=1e-6)
    assert forces["whole_system"]["agrees"] and forces["whole_system"]["equations"] == 9
    assert list(forces["reactions"]) == ["A", "B", "C", "D"]
    for key, (source, target, force) in REACTIONS_A_60.items():
        entry = forces["reactions"][key]
        assert (entry["from"], entry["on"]) == (source, target)
        assert entry["force"] == pytest.approx(force, abs=1e-5)
        assert "moment" not in entry
    assert {g["kind"] for g in forces["groups"]} == {"RRR", "drive"}


def test_drawn_lever_shows_the_drafting_error():
    exercise = load_exercise(CASE_A)
    exact = analyse(exercise).forces.zhukovsky_moment
    rough = analyse(exercise, precision_mm=0.5).forces
    assert rough.balancing_moment == pytest.approx(0.642055, abs=1e-6)  # exact solve
    assert rough.zhukovsky_moment != pytest.approx(exact, abs=1e-9)    # read off the drawing
    assert rough.zhukovsky_moment == pytest.approx(exact, rel=0.02)


# -- every dyad kind: the group method against the whole-system solve -----------------------------
KINDS = {
    "fourbar": (testing.fourbar, np.arange(0, 360, 15.0), ["RRR"]),
    "slider_crank": (testing.slider_crank, np.arange(0, 360, 15.0), ["RRP"]),
    "offset_slider": (lambda: testing.slider_crank(offset=0.02), np.arange(5, 360, 20.0),
                      ["RRP"]),
    "slotted_lever": (testing.slotted_lever, np.arange(0, 360, 15.0), ["RPR"]),
    "scotch_yoke": (testing.scotch_yoke, np.arange(0, 360, 15.0), ["RPP"]),
    "two_guides": (testing.two_guides, np.array([0, 30, 60, 90, 150, 200, 250.0]), ["PRP"]),
    "shaper": (testing.shaper, np.arange(0, 360, 15.0), ["RPR", "RRP"]),
    # sliders that touch their guide at a point of their own away from the pin: the
    # reaction's couple about that point has an arm
    "slider_off_its_pin": (lambda: _off_the_pin(testing.slider_crank(), {"slider": "C"}),
                           np.arange(0, 360, 15.0), ["RRP"]),
    "two_guides_off_their_pin": (lambda: _off_the_pin(testing.two_guides(),
                                                      {"s1": "Q", "s2": "Q"}),
                                 np.array([0, 30, 60, 90, 150, 200, 250.0]), ["PRP"]),
    "slotted_lever_off_its_pin": (lambda: _off_the_pin(testing.slotted_lever(),
                                                       {"block": "B"}),
                                  np.arange(0, 360, 15.0), ["RPR"]),
    "scotch_yoke_off_its_pin": (lambda: _off_the_pin(testing.scotch_yoke(), {"block": "B"}),
                                np.arange(0, 360, 15.0), ["RPP"]),
}


def _off_the_pin(data: dict, pins: dict[str, str]) -> dict:
    """Each slider of ``pins`` touches its guide at a point T of its own, 20 mm along and
    8 mm across from its pin; the guide passes through the same fixed point as before."""
    for number, (link, pin) in enumerate(pins.items()):
        x, y = data["links"][link][pin]
        data["links"][link][f"T{number}"] = [x + 0.02, y + 0.008]
        slide = next(slide for slide in data["slide"] if slide["link"] == link)
        slide["point"] = f"T{number}"
    return data


def loaded(data: dict, seed: int = 3) -> dict:
    """Masses off the link lines, gravity, a force at a point and a moment."""
    rng = np.random.default_rng(seed)
    data = dict(data)
    data["mass"] = {}
    for link, points in data["links"].items():
        if link == "frame":
            continue
        offset = ([float(rng.uniform(-0.03, 0.08)), float(rng.uniform(-0.03, 0.03))]
                  if len(points) > 1 else [0.0, 0.0])
        data["mass"][link] = {"m": float(rng.uniform(0.5, 3.0)),
                              "J": float(rng.uniform(1e-3, 2e-2)), "S": offset}
    data["gravity"] = {"g": 9.81}
    links = [link for link in data["links"] if link != "frame"]
    data["load"] = [{"link": links[-1], "point": next(iter(data["links"][links[-1]])),
                     "force": [-40.0, 15.0]},
                    {"link": links[-2], "moment": -6.0}]
    return data


def equilibrium_residual(mechanism, solution, applied) -> float:
    """Largest unbalanced force (and moment / crank length) on any link with the reactions
    found — an independent check of both solves."""
    wrenches = applied.wrenches(mechanism.moving_links)
    for reaction in solution.reactions.values():
        if reaction.target in wrenches:
            wrenches[reaction.target] = wrenches[reaction.target] + reaction.wrench()
        if reaction.source in wrenches:
            wrenches[reaction.source] = wrenches[reaction.source] - reaction.wrench()
    drive = mechanism.drive.link
    count = solution.balancing_moment.shape[0]
    wrenches[drive] = wrenches[drive] + Wrench(np.zeros((count, 2)), solution.balancing_moment)
    scale = max(float(np.abs(r.force).max()) for r in solution.reactions.values())
    worst = 0.0
    for wrench in wrenches.values():
        worst = max(worst, float(np.abs(wrench.force).max()),
                    float(np.abs(wrench.moment).max()) / 0.1)
    return worst / scale


@pytest.mark.parametrize("name", list(KINDS))
def test_each_groups_force_polygon_closes_edge_by_named_edge(name):
    """Each group's polygon, as its force plan draws it: every edge named, of a kind, on one
    of the group's links, and the edges closing to zero (the group is in equilibrium), edge by
    edge — a component or a reaction of the wrong size or sign leaves it open."""
    from planmethod.vocabulary import EdgeKind

    build, angles, _ = KINDS[name]
    exercise = exercise_from_dict(loaded(build()))
    solution = solve_forces(solve(exercise.mechanism, angles))
    for group in solution.groups.groups:
        assert group.polygon, group.name
        total = np.zeros((len(angles), 2))
        for edge in group.polygon:
            assert isinstance(edge.label, str) and edge.label.strip(), (group.name, edge)
            assert isinstance(edge.kind, EdgeKind), (group.name, edge.label)
            assert edge.link in group.links, (group.name, edge.label, edge.link)
            total = total + edge.vector
        scale = max(float(np.abs(edge.vector).max()) for edge in group.polygon)
        assert np.abs(total).max() <= 1e-9 * scale, (name, group.name)
        kinds = {edge.kind for edge in group.polygon}
        assert EdgeKind.KNOWN in kinds, (name, group.name)


@pytest.mark.parametrize("name", list(KINDS))
def test_group_method_matches_whole_system(name):
    build, angles, kinds = KINDS[name]
    exercise = exercise_from_dict(loaded(build()))
    motion = solve(exercise.mechanism, angles)
    assert [g.kind for g in motion.structure.groups] == kinds
    solution = solve_forces(motion)
    assert not solution.flags
    assert np.all(solution.agreement <= 1e-9)
    assert set(solution.reactions) == set(solution.system.reactions)
    scale = np.abs(solution.balancing_moment).max()
    assert np.allclose(solution.lever.balancing_moment, solution.balancing_moment,
                       atol=1e-9 * scale, rtol=0)
    assert np.all(solution.power_residual < 1e-12)
    assert equilibrium_residual(exercise.mechanism, solution.groups, solution.applied) < 1e-12
    assert equilibrium_residual(exercise.mechanism, solution.system, solution.applied) < 1e-12
    for reaction in solution.reactions.values():
        assert (reaction.moment is not None) == (reaction.kind == "P")
        if reaction.kind == "P":
            guide = motion.links[reaction.slide.along].theta + reaction.slide.direction_rad
            along = reaction.force[:, 0] * np.cos(guide) + reaction.force[:, 1] * np.sin(guide)
            assert np.abs(along).max() <= 1e-9 * scale  # no friction: ⟂ the guide


def test_prismatic_pair_keys_and_orientation():
    exercise = exercise_from_dict(loaded(testing.shaper()))
    solution = solve_forces(solve(exercise.mechanism, 60.0))
    block = solution.reactions["block/lever"]
    assert (block.source, block.target) == ("lever", "block")
    ram = solution.reactions["ram/frame"]
    assert (ram.source, ram.target) == ("frame", "ram")


def test_three_links_at_one_point_are_keyed_per_pair():
    data = testing.fourbar()
    data["links"]["frame"]["G"] = [0.0, 0.35]
    data["links"]["rod"] = {"C": [0.0, 0.0], "F": [0.25, 0.0]}
    data["links"]["slider"] = {"F": [0.0, 0.0]}
    data["slide"] = [{"link": "slider", "along": "frame", "through": "G", "direction": 0}]
    data["sketch"] = {"C": [0.24, 0.17], "F": [0.41, 0.35]}
    exercise = exercise_from_dict(loaded(data))
    solution = solve_forces(solve(exercise.mechanism, [40.0, 60.0, 90.0]))
    assert {key for key in solution.reactions if key.startswith("C")} == {"C:BC/CD",
                                                                         "C:BC/rod"}
    assert solution.reactions["C:BC/rod"].target == "rod"
    assert np.all(solution.agreement <= 1e-9)
    assert equilibrium_residual(exercise.mechanism, solution.groups, solution.applied) < 1e-12


# -- inertia and loads ----------------------------------------------------------------------------
def test_inertia_force_moment_and_equivalent_single_force(case_a):
    _, motion, solution = case_a
    inertia = solution.applied.inertia["BC"]
    state = motion.links["BC"]
    a_s = state.acceleration_at(state.place((0.11, 0.0)))
    assert np.allclose(inertia.force, -2.0 * a_s, rtol=1e-14)
    assert np.allclose(inertia.moment, -1e-2 * state.epsilon, rtol=1e-14)
    # the single force −m·a_S on the line through S + h·J·F̂_u has the moment M_u about S
    unit = inertia.force / np.hypot(*inertia.force.T)[:, None]
    shifted = perp(unit) * inertia.offset[:, None]
    assert np.allclose(cross(shifted, inertia.force), inertia.moment, rtol=1e-12, atol=1e-15)


def test_oppose_velocity_load_and_rest_flag():
    data = testing.slider_crank()
    data["load"] = [{"link": "slider", "point": "C", "force": [300.0, 0.0],
                     "oppose_velocity": True}]
    exercise = exercise_from_dict(data)
    motion = solve(exercise.mechanism, [0.0, 45.0, 90.0, 200.0])
    applied = applied_loads(exercise.mechanism, motion.links, angles=motion.angles)
    force = applied.items[0].force
    velocity = motion.velocity("C")
    assert np.allclose(force[1:], -300.0 * velocity[1:] / np.hypot(*velocity[1:].T)[:, None])
    assert np.allclose(force[0], [300.0, 0.0])   # at rest (dead centre): as given, flagged
    assert applied.flags and "0°" in render(applied.flags[0])


def test_a_moment_can_oppose_the_angular_velocity():
    """A resisting torque on a rocker: |M| against the rocker's ω at every angle, so its power
    M·ω is never positive; where the rocker turns back, the moment turns with it."""
    data = testing.fourbar()
    data["load"] = [{"link": "CD", "moment": 50.0, "oppose_velocity": True}]
    exercise = exercise_from_dict(data)
    angles = np.arange(0.0, 360.0, 7.5)
    motion = solve(exercise.mechanism, angles)
    applied = applied_loads(exercise.mechanism, motion.links, angles=motion.angles)
    (item,) = [i for i in applied.items if i.kind == "load"]
    omega = motion.omega("CD")
    assert np.all(np.abs(item.moment) == 50.0)
    assert np.all(item.moment * omega <= 0.0)
    assert np.any(omega > 0) and np.any(omega < 0)     # the rocker does turn back
    as_given = applied_loads(replace(exercise.mechanism, loads=(Load("CD", moment=50.0),)),
                             motion.links, angles=motion.angles)
    (plain,) = [i for i in as_given.items if i.kind == "load"]
    assert np.all(plain.moment == 50.0)


def test_load_on_a_point_not_in_its_link():
    exercise = exercise_from_dict(testing.fourbar())
    mechanism = replace(exercise.mechanism, loads=(Load("BC", "D", (1.0, 0.0)),))
    motion = solve(mechanism, 60.0)
    with pytest.raises(SpecError, match="'D' is not a point of 'BC'"):
        applied_loads(mechanism, motion.links)
    with pytest.raises(SpecError, match=r"load\[1\]\.point"):
        exercise_from_dict(testing.with_changes(
            testing.fourbar(), load=[{"link": "BC", "point": "D", "force": [1.0, 0.0]}]))


@pytest.mark.parametrize(("table", "message"), [
    ({"BC": {"m": 0.0}}, "mass.BC.m: must be positive"),
    ({"BC": {"m": -1.0}}, "mass.BC.m: must be positive"),
    ({"BC": {"m": 1.0, "J": -1e-3}}, "mass.BC.J: must not be negative"),
    ({"BC": {"m": 1.0, "S": [50.0, 0.0]}}, "mass.BC.S: centre of mass"),
])
def test_bad_mass_properties(table, message):
    with pytest.raises(SpecError, match=message):
        exercise_from_dict(testing.with_changes(testing.fourbar(), mass=table))


def test_singular_force_system_is_a_named_error():
    """BC and CD in line (the four-bar's toggle): both solves refuse, naming the group."""
    exercise = exercise_from_dict(loaded(testing.fourbar()))
    mechanism = exercise.mechanism
    motion = solve(mechanism, 60.0)
    states = dict(motion.links)
    # put C on the line BD: rotate CD about D so that B, C, D are collinear
    b = states["BC"].place((0.0, 0.0))
    d = np.array([[0.30, 0.0]])
    direction = (b - d) / np.hypot(*(b - d).T)[:, None]
    c = d + 0.18 * direction
    theta_cd = np.arctan2(direction[:, 1], direction[:, 0])
    theta_bc = np.arctan2(*(c - b)[:, ::-1].T)
    cd, bc = states["CD"], states["BC"]
    states["CD"] = LinkState(theta_cd, d, cd.omega, cd.velocity, cd.epsilon, cd.acceleration)
    states["BC"] = LinkState(theta_bc, b, bc.omega, bc.velocity, bc.epsilon, bc.acceleration)
    applied = applied_loads(mechanism, states)
    with pytest.raises(ForceError, match="BC and CD are in line") as caught:
        solve_by_groups(mechanism, motion.structure, states, applied, angles=np.array([60.0]))
    assert caught.value.angle == 60.0 and caught.value.link == "BC+CD"
    with pytest.raises(ForceError, match="singular"):
        solve_whole_system(mechanism, motion.structure, states, applied,
                           angles=np.array([60.0]))


# -- friction -------------------------------------------------------------------------------------
def with_friction(data: dict, **table) -> dict:
    data = loaded(data)
    data["friction"] = {"f": 0.12, "pin_radius": 0.01, **table}
    return data


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "slotted_lever", "shaper"])
def test_friction_iteration_converges_and_balances_power(name):
    build, angles, _ = KINDS[name]
    exercise = exercise_from_dict(with_friction(build()))
    motion = solve(exercise.mechanism, angles[1::2])
    solution = solve_forces(motion)
    friction = solution.friction
    assert friction is not None and np.all(friction.iterations >= 2)
    assert friction.history[-1] <= 1e-9
    assert np.all(solution.agreement <= 1e-9)        # the system solve with the same loads
    assert np.all(solution.power_residual < 1e-12)   # friction losses included
    total_loss = sum(friction.losses.values())
    assert np.all(total_loss <= 1e-12)               # friction only takes power out
    for key, reaction in solution.reactions.items():
        moments = [i for i in friction.items if i.name == f"M_f,{key}"
                   and i.link == reaction.target]
        if reaction.kind == "R" and moments:
            relative = motion.links[reaction.target].omega - motion.links[reaction.source].omega
            expected = -0.12 * 0.01 * reaction.magnitude * np.sign(relative)
            # the loads of the last iteration came from the reactions one step before
            assert np.allclose(moments[0].moment, expected, rtol=1e-8, atol=1e-9)


def test_friction_sense_changes_where_the_relative_rotation_turns(tmp_path):
    """The sweep's sense columns, and the angles the force plot marks, are where the relative
    angular velocity of a revolute pair's links (from the kinematics) changes sign."""
    from planmethod.forces import force_columns
    from planmethod.forces.applied import REST_SPEED
    from planmethod.render.plots import save_force_plot, sense_changes
    from planmethod.sweep import sweep_table

    exercise = exercise_from_dict(with_friction(testing.fourbar()))
    table = sweep_table(exercise, 1.0, extra=force_columns(exercise), progress=False)
    solution = solve_forces(solve(exercise.mechanism, np.array([30.0])))
    found = sense_changes(table)
    checked = 0
    for key, reaction in solution.reactions.items():
        omega = {name: table.get(f"omega_{name}", np.zeros_like(table["angle"]))
                 for name in (reaction.target, reaction.source)}
        if reaction.target == exercise.mechanism.drive.link:
            omega[reaction.target] = np.full_like(table["angle"], exercise.mechanism.drive.omega)
        if reaction.source == exercise.mechanism.drive.link:
            omega[reaction.source] = np.full_like(table["angle"], exercise.mechanism.drive.omega)
        relative = omega[reaction.target] - omega[reaction.source]
        moving = np.flatnonzero(np.abs(relative) > REST_SPEED * abs(exercise.mechanism.drive.omega))
        turns = table["angle"][moving[1:][np.diff(np.sign(relative[moving])) != 0]]
        assert found.get(key, []) == pytest.approx(list(turns)), key
        checked += len(turns)
    assert checked >= 2                  # the four-bar's rocker turns back twice a turn
    path = tmp_path / "forces.svg"
    save_force_plot(table, path, title="four-bar", marks=[(30.0, 1.0)])
    text = path.read_text(encoding="utf-8")
    assert "friction changes sense" in text and "M_b = 1 N·m" in text


def test_friction_raises_the_driving_moment_on_average():
    exercise = exercise_from_dict(with_friction(testing.fourbar()))
    plain = exercise_from_dict(loaded(testing.fourbar()))
    angles = np.arange(0, 360, 5.0)
    work = solve_forces(solve(exercise.mechanism, angles)).balancing_moment.mean()
    plain_work = solve_forces(solve(plain.mechanism, angles)).balancing_moment.mean()
    assert work > plain_work  # ω1 > 0: the motor supplies the friction losses


def test_zero_friction_changes_nothing():
    exercise = exercise_from_dict(with_friction(testing.slider_crank(), f=0.0))
    plain = exercise_from_dict(loaded(testing.slider_crank()))
    solution = solve_forces(solve(exercise.mechanism, 30.0))
    assert solution.balancing_moment == pytest.approx(
        solve_forces(solve(plain.mechanism, 30.0)).balancing_moment, rel=1e-15)


def test_friction_that_does_not_converge_says_so():
    exercise = exercise_from_dict(with_friction(testing.fourbar(), max_iterations=2,
                                                tolerance=1e-15))
    with pytest.raises(ConvergenceError, match="did not converge in 2 iterations") as caught:
        solve_forces(solve(exercise.mechanism, [30.0, 60.0]))
    assert caught.value.residual > 1e-15 and caught.value.angle == 30.0


def test_per_pair_friction_override():
    data = with_friction(testing.fourbar(), f=0.0)
    data["friction"]["pairs"] = {"B": {"f": 0.2, "pin_radius": 0.02}}
    solution = solve_forces(solve(exercise_from_dict(data).mechanism, 60.0))
    names = {item.name for item in solution.friction.items}
    assert names == {"M_f,B"}
    reaction = solution.reactions["B"]
    moment = next(i.moment for i in solution.friction.items if i.link == reaction.target)
    assert abs(float(moment[0])) == pytest.approx(0.2 * 0.02 * float(reaction.magnitude[0]),
                                                  rel=1e-8)


def test_report_never_holds_nan_when_the_crank_stands_still():
    data = loaded(testing.fourbar(omega=0.0, epsilon=5.0))
    exercise = exercise_from_dict(data)
    analysis = analyse(exercise, plans=False)
    report = report_dict(analysis)
    json.dumps(report, allow_nan=False)
    assert report["forces"]["zhukovsky_moment"] is None
    assert report["forces"]["power_balance_moment"] is None
    assert any("ω₁ = 0" in flag for flag in report["forces"]["flags"])


# -- properties ------------------------------------------------------------------------------------
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_mass = st.fixed_dictionaries({
    "m": st.floats(0.1, 20.0), "J": st.floats(0.0, 0.5),
    "S": st.tuples(st.floats(-0.1, 0.3), st.floats(-0.1, 0.1)).map(list)})


@settings(max_examples=25, deadline=None)
@given(kind=st.sampled_from(["fourbar", "slider_crank", "slotted_lever"]),
       angle=st.floats(0.0, 359.0), omega=st.floats(-30.0, 30.0).filter(lambda w: abs(w) > 0.1),
       epsilon=st.floats(-50.0, 50.0), masses=st.lists(_mass, min_size=3, max_size=3),
       force=st.tuples(st.floats(-500, 500), st.floats(-500, 500)),
       moment=st.floats(-50.0, 50.0), gravity=st.booleans())
def test_every_method_gives_the_same_balancing_moment(kind, angle, omega, epsilon, masses, force,
                                                      moment, gravity):
    """Group method = whole-system solve = Zhukovsky's lever = power balance, for any masses,
    loads and motion (positions away from toggles)."""
    build = {"fourbar": testing.fourbar, "slider_crank": testing.slider_crank,
             "slotted_lever": testing.slotted_lever}[kind]
    data = build(angle=angle, omega=omega, epsilon=epsilon)
    links = [name for name in data["links"] if name != "frame"]
    data["mass"] = {}
    for link, props in zip(links, masses, strict=False):
        props = dict(props)
        if len(data["links"][link]) == 1:
            props["S"] = [0.0, 0.0]
        data["mass"][link] = props
    if gravity:
        data["gravity"] = {"g": 9.81}
    data["load"] = [{"link": links[-1], "point": next(iter(data["links"][links[-1]])),
                     "force": list(force)}, {"link": links[-2], "moment": moment}]
    exercise = exercise_from_dict(data)
    motion = solve(exercise.mechanism, angle)
    if float(np.min(np.abs(next(iter(motion.groups.values())).line_sine))) < 1e-3:
        return  # too near the toggle for a 1e-9 comparison
    solution = solve_forces(motion)
    crank = exercise.mechanism.links[exercise.mechanism.drive.link]
    arm = max(crank.length(exercise.mechanism.drive.pivot, p) for p in crank.points)
    largest = max(float(r.magnitude[0]) for r in solution.reactions.values())
    scale = max(float(np.max(np.abs(solution.balancing_moment))), largest * arm)
    assert solution.agreement[0] <= 1e-9
    for other in (solution.lever.balancing_moment, solution.power_moment,
                  solution.system.balancing_moment):
        assert abs(float(other[0] - solution.balancing_moment[0])) <= 1e-9 * scale + 1e-12
