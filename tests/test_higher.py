"""Class III groups: seed 000's conveyor (REFERENCE_CASES S0), Newton and continuation, branch
choice, error paths, Assur's special point on the plans and in the force analysis."""

from __future__ import annotations

import copy
import dataclasses
import tomllib
from pathlib import Path

import numpy as np
import pytest

from planmethod.errors import AssemblyError, BranchJumpError, ConvergenceError, ToggleError
from planmethod.forces import solve_forces
from planmethod.kinematics import Branch, choose_branches, solve
from planmethod.kinematics.groups import higher
from planmethod.kinematics.program import model
from planmethod.plans import draw_plans
from planmethod.plans.groups.triad import SPECIAL
from planmethod.render.plan_words import step_text
from planmethod.report import analyse, report_dict
from planmethod.spec import exercise_from_dict
from planmethod.structure import analyse_structure
from planmethod.testing import reference_motion
from planmethod.words import render

CONVEYOR = Path("exercises/conveyor_sixbar.toml")
S0 = {"A": (-0.042426, 0.042426), "B": (-0.346622, -0.261489), "C": (-0.346839, -0.186490),
      "E": (-0.906837, -0.188109), "D": (0.793156, -0.183194)}


def conveyor(**changes) -> dict:
    data = tomllib.loads(CONVEYOR.read_text())
    data = copy.deepcopy(data)
    for key, value in changes.items():
        if value is None:
            data.pop(key, None)
        else:
            data[key] = value
    return data


@pytest.fixture(scope="module")
def exercise():
    return exercise_from_dict(conveyor(), file=str(CONVEYOR))


def test_structure_is_a_triad(exercise):
    structure = analyse_structure(exercise.mechanism)
    assert (structure.n, structure.p5, structure.mobility) == (5, 7, 1)
    [group] = structure.groups
    assert (group.kind, group.group_class, group.links[0]) == ("triad", 3, "tray")


def test_positions_at_135_match_s0(exercise):
    motion = solve(exercise.mechanism, 135.0, stage="position")
    here = motion.at(0)
    for point, expected in S0.items():
        assert np.allclose(here.position(point), expected, atol=1e-6), point
    assert np.degrees(here.theta("tray")) == pytest.approx(0.16565, abs=1e-5)
    assert np.degrees(here.theta("rocker_EF")) == pytest.approx(-18.29342, abs=1e-5)
    # the paper's branch: E and D below their pivots F and G
    assert here.position("E")[1] < -0.05 and here.position("D")[1] < -0.05
    branch = motion.branches[0]
    assert branch.reason == "sketch" and branch.count >= 2
    assert isinstance(branch, higher.HigherBranch)


def test_pairs_close_to_machine_precision_over_a_turn(exercise):
    motion = solve(exercise.mechanism, np.arange(0.0, 360.0, 1.0))
    mechanism = exercise.mechanism
    for point in "BED":
        owners = mechanism.links_with_point(point)
        places = [motion.links[o].place(mechanism.local(o, point)) for o in owners]
        assert np.abs(places[0] - places[1]).max() < 1e-13
    assert np.all(motion.groups[0].line_sine > 1e-3)   # well conditioned all the way round


def test_velocities_and_accelerations_against_finite_differences(exercise):
    mechanism = exercise.mechanism
    omega = mechanism.drive.omega
    angles = np.array([0.0, 77.0, 135.0, 250.0, 333.0])
    h = 1e-3  # deg
    exact = solve(mechanism, angles)
    ahead, behind = solve(mechanism, angles + h), solve(mechanism, angles - h)
    step = np.radians(h) / omega  # s
    for point in "BCED":
        fd_v = (ahead.position(point) - behind.position(point)) / (2 * step)
        assert np.allclose(fd_v, exact.velocity(point), atol=1e-9, rtol=0), point
        fd_a = (ahead.velocity(point) - behind.velocity(point)) / (2 * step)
        assert np.allclose(fd_a, exact.acceleration(point), atol=1e-7, rtol=0), point
    for link in ("tray", "rod", "rocker_EF", "rocker_DG"):
        fd_omega = np.angle(np.exp(1j * (ahead.theta(link) - behind.theta(link)))) / (2 * step)
        assert np.allclose(fd_omega, exact.omega(link), atol=1e-9, rtol=0)
        fd_epsilon = (ahead.omega(link) - behind.omega(link)) / (2 * step)
        assert np.allclose(fd_epsilon, exact.epsilon(link), atol=1e-7, rtol=0)


def test_continuation_is_periodic_and_order_free(exercise):
    mechanism = exercise.mechanism
    turn = solve(mechanism, np.arange(0.0, 361.0, 1.0), stage="position")
    for point in "BCED":
        path = turn.position(point)
        assert np.abs(np.diff(path, axis=0)).max() < 0.01       # no jump between degrees
        assert np.allclose(path[0], path[-1], atol=1e-12)       # back to itself after a turn
    scattered = solve(mechanism, [300.0, 10.0, 135.0, -200.0], stage="position")
    for angle, index in ((300.0, 0), (10.0, 1), (135.0, 2)):
        single = solve(mechanism, angle, stage="position").at(0)
        assert np.allclose(scattered.position("D")[index], single.position("D"), atol=1e-12)
    assert np.allclose(scattered.position("D")[3], turn.position("D")[160], atol=1e-12)


def test_default_branch_without_a_sketch_and_a_plain_branch():
    exercise = exercise_from_dict(conveyor(sketch=None))
    motion = solve(exercise.mechanism, 135.0, stage="position")
    assert motion.branches[0].reason == "default" and motion.branches[0].sign == 1
    sketched = exercise_from_dict(conveyor())
    chosen = choose_branches(sketched.mechanism)[0]
    plain = {0: Branch(chosen.sign, "given")}
    again = solve(sketched.mechanism, 200.0, stage="position", branches=plain)
    assert np.allclose(again.position("D"), solve(sketched.mechanism, 200.0,
                                                  stage="position").position("D"), atol=1e-12)


def test_a_group_that_cannot_be_assembled():
    data = conveyor()
    data["links"]["rocker_EF"]["E"] = [0.05, 0.0]   # far too short to reach the tray
    with pytest.raises(AssemblyError, match="cannot be assembled") as caught:
        solve(exercise_from_dict(data).mechanism, 135.0, stage="position")
    assert caught.value.angle == 135.0 and "tray" in caught.value.link


def _fresh(mechanism, title: str):
    """An equal mechanism but for its title: a model of its own (nothing cached yet)."""
    return dataclasses.replace(mechanism, title=title)


def test_newton_that_does_not_converge_says_where_and_how_far(exercise, monkeypatch):
    mechanism = _fresh(exercise.mechanism, "no convergence")
    branches = choose_branches(mechanism)
    monkeypatch.setattr(higher, "RESIDUAL", -1.0)   # nothing ever counts as converged
    with pytest.raises(ConvergenceError, match="Newton did not converge: residual") as caught:
        solve(mechanism, 140.0, stage="position", branches=branches)
    assert caught.value.angle is not None and caught.value.residual >= 0
    assert "tray" in str(caught.value)


def test_a_branch_jump_is_an_error_not_a_flip(exercise, monkeypatch):
    mechanism = _fresh(exercise.mechanism, "jump")
    branches = choose_branches(mechanism)
    # every correction counts as moving too far from its prediction
    monkeypatch.setattr(higher, "accept", lambda length, q, converged, *rest: (
        converged & False, np.ones(len(q))))
    monkeypatch.setattr(higher, "allowed", lambda length, expected: -1.0)
    with pytest.raises(BranchJumpError, match="jump to another branch") as caught:
        solve(mechanism, 150.0, stage="position", branches=branches)
    # where, as every refusal says it: the group's links and the crank angle
    assert "tray" in (caught.value.link or "") and "tray" in str(caught.value)
    assert caught.value.angle is not None


def test_an_unreachable_angle_in_a_sweep_is_a_named_error():
    """A crank too long for the rockers: the group exists at 135° but folds at a limit position
    further on; the sweep stops there with a named error, never a wrong assembly."""
    data = conveyor()
    data["links"]["crank"]["A"] = [0.3, 0.0]
    mechanism = exercise_from_dict(data).mechanism
    solve(mechanism, 135.0, stage="position")
    with pytest.raises(ToggleError, match="limit \\(toggle\\) position") as caught:
        solve(mechanism, np.arange(135.0, 360.0, 5.0), stage="position")
    assert caught.value.angle == pytest.approx(287.494, abs=0.01)
    assert caught.value.link == "tray+rod+rocker_EF+rocker_DG"


# -- plans by Assur's special point -------------------------------------------------------------
@pytest.mark.parametrize("angle", [0.0, 60.0, 135.0, 225.0, 300.0])
def test_triad_plans_equal_exact_vectors(exercise, angle):
    plans = draw_plans(exercise, angle)
    motion = solve(exercise.mechanism, angle).at(0)
    for point in "ABCDEO":
        assert np.allclose(plans.velocity.vector(point.lower()), motion.velocity(point),
                           atol=1e-12), point
        assert np.allclose(plans.acceleration.vector(point.lower()), motion.acceleration(point),
                           atol=1e-11), point
    for link in ("tray", "rod", "rocker_EF", "rocker_DG"):
        assert plans.readings[f"omega_{link}"] == pytest.approx(float(motion.omega(link)),
                                                                abs=1e-12)
        assert plans.readings[f"epsilon_{link}"] == pytest.approx(float(motion.epsilon(link)),
                                                                  abs=1e-11)
    assert SPECIAL in plans.velocity.points_mm and SPECIAL in plans.acceleration.points_mm
    intersections = [s for s in plans.velocity.steps if s.action == "intersect"]
    assert [s.end for s in intersections] == [SPECIAL, intersections[1].end]


def test_points_on_the_triads_side_links_are_placed_by_similarity_and_exact():
    """A point of each side link off the line of its pins (M on the rod, K and L on the
    rockers) is placed on both plans by similarity from that link's images, which the triad
    fixes once it has read the link's ω and ε: each equals the exact vector."""
    data = conveyor()
    data["links"]["rod"]["M"] = [0.2, 0.05]
    data["links"]["rocker_EF"]["K"] = [0.3, -0.04]
    data["links"]["rocker_DG"]["L"] = [0.25, 0.06]
    exercise = exercise_from_dict(data)
    for angle in (60.0, 225.0):
        plans = draw_plans(exercise, angle)
        motion = solve(exercise.mechanism, angle).at(0)
        for point in "MKL":
            assert np.allclose(plans.velocity.vector(point.lower()), motion.velocity(point),
                               atol=1e-12), (angle, point)
            assert np.allclose(plans.acceleration.vector(point.lower()),
                               motion.acceleration(point), atol=1e-11), (angle, point)


def test_triad_plan_at_drafting_precision_is_close(exercise):
    plans = draw_plans(exercise, 135.0, settings=exercise.plan.__class__(
        crank_mm=6, velocity_mm=40, acceleration_mm=40, precision_mm=0.5))
    motion = solve(exercise.mechanism, 135.0).at(0)
    speed = float(np.hypot(*motion.velocity("D")))
    assert np.hypot(*(plans.velocity.vector("d") - motion.velocity("D"))) < 0.05 * speed


def test_special_point_lies_on_two_side_lines(exercise):
    plans = draw_plans(exercise, 135.0)
    text = next(step_text(s, plans.velocity) for s in plans.velocity.steps if s.end == SPECIAL)
    numbers = text.split("S* = (")[1].split(")")[0].split(", ")
    special = np.array([float(x) for x in numbers])
    motion = solve(exercise.mechanism, 135.0, stage="position").at(0)
    on_lines = 0
    for p, q in (("A", "B"), ("F", "E"), ("G", "D")):
        a, b = motion.position(p), motion.position(q)
        u, w = b - a, special - a
        distance = abs(u[0] * w[1] - u[1] * w[0]) / np.hypot(*u)
        on_lines += distance < 1e-6
    assert on_lines == 2


# -- forces -------------------------------------------------------------------------------------
def test_triad_forces_by_special_point_match_the_whole_system(exercise):
    motion = solve(exercise.mechanism, np.arange(0.0, 360.0, 10.0))
    solution = solve_forces(motion)
    assert not solution.flags
    assert np.all(solution.agreement <= 1e-9)
    assert np.all(solution.power_residual < 1e-12)
    scale = np.abs(solution.balancing_moment).max()
    assert np.allclose(solution.lever.balancing_moment, solution.balancing_moment,
                       atol=1e-9 * scale)
    triad = next(g for g in solution.groups.groups if g.kind == "triad")
    assert "special point" in " ".join(render(step) for step in triad.steps)
    assert len(solution.reactions) == 7
    # the polygon of the group closes
    total = sum(edge.vector for edge in triad.polygon)
    assert np.abs(total).max() < 1e-9 * max(np.abs(e.vector).max() for e in triad.polygon)


def test_conveyor_report_from_the_cli_path():
    analysis = analyse(exercise_from_dict(conveyor(), file=str(CONVEYOR)))
    report = report_dict(analysis)
    forces = report["forces"]
    assert forces["whole_system"]["agrees"] and forces["whole_system"]["equations"] == 15
    assert forces["zhukovsky_moment"] == pytest.approx(forces["balancing_moment"], rel=1e-9)
    assert report["structure"]["groups"][0]["branch"]["reason"] == "sketch"
    assert "special_point" in forces["groups"][0]


def slider_triad() -> dict:
    """The conveyor with the rocker DG replaced by a block sliding on a fixed guide: a triad
    with a prismatic pair (solved by the group's linear system; drawn by the special point)."""
    data = conveyor()
    del data["links"]["rocker_DG"]
    del data["mass"]["rocker_DG"]
    data["links"]["block"] = {"D": [0.0, 0.0]}
    data["links"]["frame"]["H"] = [0.79, -0.183]
    data["slide"] = [{"link": "block", "along": "frame", "through": "H", "direction": 80.0}]
    data["mass"]["block"] = {"m": 2.0, "J": 0.001}
    return data


def test_triad_with_a_prismatic_pair():
    exercise = exercise_from_dict(slider_triad())
    [group] = analyse_structure(exercise.mechanism).groups
    assert group.kind == "triad"
    angles = [100.0, 135.0, 170.0]
    motion = solve(exercise.mechanism, angles)
    # the motion against the whole mechanism's constraint equations, solved by the oracle's
    # own Newton continuation from the sketch (the forces below only check themselves)
    for link, expected in reference_motion(exercise.mechanism, angles).items():
        state = motion.links[link]
        assert np.abs(np.angle(np.exp(1j * (state.theta - expected["theta"])))).max() < 1e-12
        for name in ("origin", "velocity", "acceleration", "omega", "epsilon"):
            scale = max(1.0, float(np.abs(expected[name]).max()))
            assert np.abs(getattr(state, name) - expected[name]).max() < 1e-12 * scale, (
                link, name)
    solution = solve_forces(motion)
    assert np.all(solution.agreement <= 1e-9)
    assert "linear system" in render(solution.groups.groups[0].steps[0])
    assert "block/frame" in solution.reactions
    analysis = analyse(exercise)
    assert analysis.plans is not None and analysis.forces is not None
    # its plans are drawn by the special point (tests/test_triad_slider.py): exact here too
    here = motion.at(1)
    plans = draw_plans(exercise, 135.0)
    for point in "ABCDE":
        assert np.allclose(plans.velocity.vector(point.lower()), here.velocity(point),
                           atol=1e-12), point
        assert np.allclose(plans.acceleration.vector(point.lower()), here.acceleration(point),
                           atol=1e-11), point


def test_a_chunk_the_straight_line_cannot_polish_is_redone_the_same(exercise, monkeypatch):
    """The compiled straight-line step guards its result (polished, no jump, not singular);
    a chunk that fails a guard is redone along the path. With no result counting as polished
    every chunk is redone, and the sweep gives the same positions and rates."""
    angles = np.arange(135.0, 200.0, 5.0)
    expected = solve(exercise.mechanism, angles, stage="velocity")
    mechanism = _fresh(exercise.mechanism, "redo every chunk")
    monkeypatch.setattr(higher, "POLISHED", 0.0)
    redone = solve(mechanism, angles, stage="velocity", branches=choose_branches(mechanism))
    for point in ("B", "C", "D", "E"):
        assert np.allclose(redone.position(point), expected.position(point), rtol=0, atol=1e-9)
        assert np.allclose(redone.velocity(point), expected.velocity(point), rtol=0, atol=1e-7)


def test_a_side_link_drawn_in_a_frame_of_its_own_moves_the_same():
    """A side link's local frame is the file's choice: rocker EF written with F at (0.1, 0.2)
    instead of at its origin (and a point M of it, moved alike) moves exactly as written the
    usual way — positions, velocities and accelerations of M through a sweep."""
    usual, shifted = conveyor(), conveyor()
    usual["links"]["rocker_EF"] = {"F": [0, 0], "E": [0.44, 0], "M": [0.22, 0.05]}
    shifted["links"]["rocker_EF"] = {"F": [0.1, 0.2], "E": [0.54, 0.2], "M": [0.32, 0.25]}
    angles = np.arange(135.0, 200.0, 5.0)
    first, second = (solve(exercise_from_dict(data).mechanism, angles, stage="acceleration")
                     for data in (usual, shifted))
    for read in ("position", "velocity", "acceleration"):
        assert np.allclose(getattr(second, read)("M"), getattr(first, read)("M"),
                           rtol=1e-9, atol=1e-12), read


def test_a_step_along_the_path_is_judged_by_the_move_its_prediction_expects(exercise,
                                                                             monkeypatch):
    """Each step of the march is accepted only if the corrected solution stays near its
    prediction, measured against the predicted move q′·Δφ: over steps of at most 1° that
    move is well under 5 % of the group's size (under 0.1 % for the conveyor, size 1.7 m)."""
    mechanism = _fresh(exercise.mechanism, "judged steps")
    seen = []
    judged = higher.allowed

    def watched(length, expected):   # the march's rule, on arrays and on floats alike
        if isinstance(expected, float | np.ndarray):     # not the traced program's
            seen.append((float(np.max(expected)), length))
        return judged(length, expected)

    monkeypatch.setattr(higher, "allowed", watched)
    solve(mechanism, np.arange(135.0, 160.0, 5.0), stage="position",
          branches=choose_branches(mechanism))
    assert seen and max(expected / length for expected, length in seen) < 0.05


def test_a_corrected_solution_may_move_half_its_predicted_step():
    """A step of the march is the continuation of its prediction if Newton moved it by at
    most half the predicted move (weighted), within 10⁻⁴ and 2 % of the group's size: a
    move of 0.49 of the predicted one is kept, 0.51 is a jump to another assembly."""
    weights = np.array([1.0, 1.0, 2.0])
    prediction = np.array([[0.3, -0.2, 0.1]])
    expected = np.array([0.01])               # the predicted move, group size 2 m
    converged = np.array([True])
    for share, kept in ((0.49, True), (0.51, False)):
        q = prediction + np.array([[share * 0.01, 0.0, 0.0]])
        ok, jump = higher.accept(2.0, q, converged, prediction, expected, weights)
        assert bool(ok[0]) is kept and float(jump[0]) == pytest.approx(share * 0.01)
    # the floor and the cap: 10⁻⁴ and 2 % of the size, whatever the prediction expects
    assert float(higher.allowed(2.0, np.array(1e-9))) == pytest.approx(2e-4)
    assert float(higher.allowed(2.0, np.array(5.0))) == pytest.approx(0.04)
    assert not bool(higher.accept(2.0, prediction, np.array([False]), prediction, expected,
                                  weights)[0][0])     # not converged: never kept


def test_the_groups_assemblies_are_found_distinct_and_without_a_warning(exercise):
    """At drive.angle the conveyor's group has four distinct assemblies; the sketch picks the
    fourth (the paper's). Finding and sorting them raises no numpy warning."""
    import warnings

    mechanism = _fresh(exercise.mechanism, "assemblies")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        chosen = choose_branches(mechanism)
    (branch,) = chosen.values()
    assert (branch.sign, branch.reason, branch.count) == (4, "sketch", 4)


@pytest.mark.parametrize(("angle", "bound"), [(287.49396896362305, 5e-5), (287.4, 0.015)])
def test_a_requested_angle_whose_pose_is_singular_is_a_toggle(monkeypatch, angle, bound):
    """The march's nodes are checked as they are made; a requested angle between them is
    checked too. Near the conveyor's limit with a 0.3 m crank (287.494°) the pose at the
    angle itself is the least healthy (its normalised determinant about 2.8e-5): with the
    singular bound set between it and the nodes', that angle alone is refused, by name —
    by the march, whose Newton from the node at 287° does not settle there. At 287.4° Newton
    settles (determinant 0.013, the node's is higher): only the last check of the solved
    pose, with the bound at 0.015, sees it."""
    data = conveyor()
    data["links"]["crank"]["A"] = [0.3, 0.0]
    monkeypatch.setattr(higher, "SINGULAR", bound)
    with pytest.raises(ToggleError, match="its motion is not determined") as caught:
        solve(exercise_from_dict(data).mechanism, angle, stage="position")
    assert caught.value.angle == angle and "tray" in (caught.value.link or "")


def test_a_group_with_one_assembly_takes_it_without_the_sketch(exercise, monkeypatch):
    """Where the search finds a single assembly at drive.angle it is the group's, 'unique',
    whatever the sketch says (the conveyor's search cut down to its first assembly)."""
    mechanism = _fresh(exercise.mechanism, "one assembly")
    found = higher.sort_assemblies
    monkeypatch.setattr(higher, "sort_assemblies",
                        lambda system, assemblies, known: found(system, assemblies, known)[:1])
    (branch,) = choose_branches(mechanism).values()
    assert (branch.sign, branch.reason, branch.count) == (1, "unique", 1)


def test_newton_stops_stepping_an_angle_whose_residual_reached_a_million_sizes():
    """Newton steps every angle but one that diverged: a residual of 1e6 times the group's
    size or more. At exactly that residual the angle is left where it is; just under it, it
    steps."""

    class Diverging:
        length = 2.0

        def __init__(self, residual):
            self.value = residual

        def at(self, q, known):
            return q

        def residual(self, pose):
            return np.array([self.value])

        def step(self, pose):
            return (np.array([1.0]),)

    for residual, moved in ((1e6 * 2.0, False), (np.nextafter(1e6 * 2.0, 0.0), True)):
        q, converged, _, _ = higher.System.newton(Diverging(residual), np.zeros((1, 1)), None,
                                                  iterations=1)
        assert bool(q[0, 0] != 0.0) is moved and not converged[0]


# -- the march on floats, the table built as far as asked ----------------------------------------
#: D's motion and the tray's ε at angles between the nodes, on both sides of drive.angle and
#: beyond a turn, as the march on arrays of one angle gave them (before the march on floats)
BEFORE_ANGLES = [-250.5, 17.3, 135.0, 222.2, 359.9, 481.7]
BEFORE = {
    "position": [[0.8014795375701249, -0.1533934869506015], [0.81199433159563, -0.089821197338342],
                 [0.7931559700747843, -0.18319373244502393],
                 [0.7691165256130332, -0.24319638862370074],
                 [0.8108165320059911, -0.10115223116792196],
                 [0.7977597488659509, -0.16772056465002153]],
    "velocity": [[-0.10170698530123347, -0.4207034478106453],
                 [0.0118671355221518, 0.13058651837867055],
                 [-0.13096121808178, -0.41232697397025303],
                 [0.004946175615054626, 0.010120815265464187],
                 [0.038731796465801785, 0.33090316851049356],
                 [-0.11744482406535299, -0.4229666945990455]],
    "acceleration": [[-0.4937903972131421, -0.23065618136323532],
                     [-0.44770706757825585, -4.494817923718961],
                     [-0.29345025192100416, 0.4812858523081479],
                     [1.303936953671056, 2.6687596252266883],
                     [-0.6751559355980195, -3.598225186821926],
                     [-0.42692801604088093, 0.09933537959165128]],
    "epsilon": [0.09699300515644382, -0.5891733920316611, 0.06247325984787903,
                0.03197161413199267, -0.07542777584034162, 0.0784701380818123]}


def _same(found, expected, scale):
    """Equal to 1e-12 of the quantity's size over the sweep (a component that is zero up to
    rounding compares sensibly)."""
    off = np.abs(np.asarray(found) - expected) / np.maximum(np.abs(expected), scale)
    assert off.max() <= 1e-12, off.max()


def _motions(motion):
    return {"position": motion.position("D"), "velocity": motion.velocity("D"),
            "acceleration": motion.acceleration("D"), "epsilon": motion.epsilon("tray")}


def test_the_conveyor_moves_as_before_between_the_nodes(exercise):
    motion = solve(_fresh(exercise.mechanism, "as before"), np.array(BEFORE_ANGLES))
    for name, found in _motions(motion).items():
        expected = np.array(BEFORE[name])
        _same(found, expected, np.abs(expected).max())


def _path(mechanism) -> higher.Path:
    (path,) = [value for key, value in model(mechanism).memo.items() if key[0] == "path"]
    return path


def test_the_march_on_floats_makes_the_nodes_the_march_on_arrays_makes(exercise, monkeypatch):
    """Every node of a turn and more either side of drive.angle is made on plain floats
    (none by the march on arrays of one angle), and equals the node the march on arrays makes
    — q, q′ and q″ — to 1e-12."""
    angles = np.arange(-100.0, 420.0, 1.0)
    made = []
    advance = higher.Path.advance
    monkeypatch.setattr(higher.Path, "advance",
                        lambda path, *args: made.append(args[1:3]) or advance(path, *args))
    floats = _fresh(exercise.mechanism, "on floats")
    on_floats = solve(floats, angles)
    assert made == []
    monkeypatch.setattr(higher.Path, "quick", lambda *args: None)
    arrays = _fresh(exercise.mechanism, "on arrays")
    on_arrays = solve(arrays, angles)
    assert len(made) == 284 + 235      # every node but drive.angle's, on each side
    for side, count in ((1, 284), (-1, 235)):
        for ours, theirs in zip(_path(floats).arrays(side, count),
                                _path(arrays).arrays(side, count), strict=True):
            assert ours.shape == (count + 1, 3)
            _same(ours, theirs, np.abs(theirs).max(axis=0))
    for name, found in _motions(on_floats).items():
        expected = _motions(on_arrays)[name]
        _same(found, expected, np.abs(expected).max())


def test_a_table_built_as_far_as_asked_answers_as_the_whole_table(exercise):
    """The path grows only as far as the angles asked; asked one by one, each further than
    the last, the answers equal those of a model whose whole table was built first."""
    angles = [150.0, 200.5, 96.25, 300.0, -20.0, 135.0, 481.7]
    grown = _fresh(exercise.mechanism, "grown")
    answers = [solve(grown, angle) for angle in angles]
    nodes = _path(grown).nodes     # drive.angle's and one a degree to the nearest of each angle
    assert (len(nodes[1]), len(nodes[-1])) == (1 + 347, 1 + 155)
    whole = _fresh(exercise.mechanism, "whole first")
    solve(whole, np.arange(-360.0, 720.0, 1.0))
    for angle, answer in zip(angles, answers, strict=True):
        for name, found in _motions(solve(whole, angle)).items():
            expected = _motions(answer)[name]
            _same(found, expected, np.abs(expected).max())


def test_the_order_of_the_angles_asked_changes_no_answer(exercise):
    """The same angles asked in ascending, descending and shuffled order, each of a model of
    its own: the same answer at each angle."""
    angles = np.arange(-200.0, 560.0, 7.3)
    orders = [angles, angles[::-1], np.random.default_rng(7).permutation(angles)]
    answers = []
    for number, order in enumerate(orders):
        motion = _motions(solve(_fresh(exercise.mechanism, f"order {number}"), order))
        back = np.argsort(order)
        answers.append({name: values[back] for name, values in motion.items()})
    for answer in answers[1:]:
        for name, found in answer.items():
            _same(found, answers[0][name], np.abs(answers[0][name]).max())
