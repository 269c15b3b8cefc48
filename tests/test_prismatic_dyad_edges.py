"""The prismatic dyad kinds (RPR, PRP, RPP) at their edges.

What the random cases of tests/test_group_kinds.py and tests/test_forces.py rarely meet: an RPR
slot that only just reaches the pin (the rounding rule that tells a toggle from a miss, on
exactly representable numbers), slides written the other way round (the group's link carries
the guide), a pin at (1, 0) or (0, 1) of its link, loads along a guide and blocks that touch
their slot away from their pin, and the steps of each kind's reaction sequence as the report
lists them. Every expected value comes from the mechanism's own geometry or from the
whole-system force solve, which shares nothing with the kinds' formulas.
"""

from __future__ import annotations

import numpy as np
import pytest

from planmethod.errors import AssemblyError, ToggleError
from planmethod.forces import solve_forces
from planmethod.kinematics import solve
from planmethod.report import analyse, report_dict
from planmethod.spec import exercise_from_dict
from planmethod.testing import reference_motion, scotch_yoke, slotted_lever, two_guides

#: the spacing of floats in [1, 2) (one unit in the last place of 1.5)
ULP = 2.0 ** -52
PATHS = [pytest.param(False, id="program"), pytest.param(True, id="reference")]


# -- helpers ---------------------------------------------------------------------------------
def _wrapped(angle) -> np.ndarray:
    """An angle (rad) brought into (−π, π]."""
    return np.angle(np.exp(1j * np.asarray(angle)))


def _pairs_hold(mechanism, motion, tolerance: float = 1e-12) -> None:
    """Every pair's own equations at the solved positions: a point shared by two links is at
    one place on both, and a slide's ``link`` keeps its +x axis at ``direction`` in
    ``along``'s frame with its ``point`` on the line through ``through`` along that
    direction (docs/exercise-file.md, "Prismatic pairs")."""
    links = mechanism.links
    for point in {p for link in links.values() for p in link.points}:
        carriers = [name for name, link in links.items() if point in link.points]
        places = [motion.place(name, mechanism.local(name, point)) for name in carriers]
        for other in places[1:]:
            assert np.abs(other - places[0]).max() <= tolerance, point
    for slide in mechanism.slides:
        guide = motion.theta(slide.along) + slide.direction_rad
        turn = _wrapped(motion.theta(slide.link) - guide)
        assert np.abs(turn).max() <= tolerance, slide.key
        point = motion.place(slide.link, mechanism.local(slide.link, slide.point))
        through = motion.place(slide.along, mechanism.local(slide.along, slide.through))
        gap = point - through
        across = gap[..., 1] * np.cos(guide) - gap[..., 0] * np.sin(guide)
        assert np.abs(across).max() <= tolerance, slide.key


def _axes_are_theta(motion, links) -> None:
    """A link's θ is the angle of its own +x axis: the axes it is placed with."""
    for link in links:
        state = motion.links[link]
        axes = np.stack((np.cos(state.theta), np.sin(state.theta)), axis=-1)
        assert np.abs(state.basis - axes).max() <= 1e-12, link


def _motion_is_the_linear_solves(mechanism, motion, angles) -> None:
    """ω, ε and each origin's velocity and acceleration against one exact linear solve of the
    whole mechanism's constraint equations (:func:`planmethod.testing.reference_motion`)."""
    near = {point: tuple(float(v) for v in motion.position(point)[0])
            for link in motion.solved if link != "frame"
            for point in mechanism.links[link].points}
    reference = reference_motion(mechanism, angles, near=near)
    drive = motion.links[mechanism.drive.link]
    pin = drive.place(mechanism.local(mechanism.drive.link, "B"))
    # relative to the crank's own motion (a yoke does not turn: its ω is 0)
    floors = {"omega": drive.omega, "epsilon": drive.omega ** 2 + np.abs(drive.epsilon),
              "velocity": drive.velocity_at(pin), "acceleration": drive.acceleration_at(pin)}
    for quantity in ("omega", "epsilon", "velocity", "acceleration"):
        scale = max(max(float(np.abs(expected[quantity]).max())
                        for expected in reference.values()),
                    float(np.abs(floors[quantity]).max()))
        for link, expected in reference.items():
            got = getattr(motion.links[link], quantity)
            assert np.abs(got - expected[quantity]).max() <= 1e-10 * scale, (link, quantity)


def _reactions_are_the_whole_systems(exercise, angles) -> None:
    """The group method's reactions — forces and the couples of the slides — equal the one
    linear solve of the whole mechanism (docs/kinetostatics.md, "Checks")."""
    solution = solve_forces(solve(exercise.mechanism, angles))
    assert not solution.flags
    scale = max(float(np.abs(r.force).max()) for r in solution.system.reactions.values())
    for key, found in solution.reactions.items():
        expected = solution.system.reactions[key].oriented(found.source, found.target)
        assert np.abs(found.force - expected.force).max() <= 1e-9 * scale, key
        # a prismatic pair's reaction has its couple, a revolute pair's none
        assert (found.moment is not None) == (found.kind == "P"), key
        if found.moment is not None:
            assert np.abs(found.moment - expected.moment).max() <= 1e-9 * scale, key


# -- RPR: a slot that only just reaches the pin --------------------------------------------------
def _lever_tangent(aside: float) -> dict:
    """A slotted lever whose slot passes ``aside`` from the pivot O2; at crank angle 0 the pin
    B = (0.5, 0) is exactly 1.5 m straight above O2 = (0.5, −1.5), its nearest to O2 nearby
    (B comes closer at small negative angles)."""
    data = slotted_lever(crank=0.5, centres=1.5, angle=90.0)
    data["links"]["frame"]["O2"] = [0.5, -1.5]
    data["links"]["lever"]["T"] = [0.1, aside]
    data["slide"][0]["through"] = "T"
    return data


@pytest.mark.parametrize("stage", ["position", "acceleration"])
@pytest.mark.parametrize("reference", PATHS)
@pytest.mark.parametrize("units", [0, 30, -30, 60, -60])
def test_rpr_slot_within_rounding_of_the_pins_reach_is_a_toggle(units, reference, stage):
    """|O2B| − |offset| within 16ε of the size of its terms (|O2B| = |offset| = 1.5 and
    O2B's largest component 1.5: 72 units of 1.5's last place; docs/accuracy.md, "Singular
    positions", and the comment at rpr.place's guard) is the group's toggle position, refused
    by the position solve itself, on both sides of zero and on both paths, at the first crank
    angle where it holds."""
    mechanism = exercise_from_dict(_lever_tangent(1.5 + units * ULP)).mechanism
    with pytest.raises(ToggleError) as caught:   # no other angle near the limit
        solve(mechanism, np.array([90.0, 45.0, 0.0]), stage=stage, reference=reference)
    assert (caught.value.link, caught.value.angle) == ("block+lever", 0.0)
    assert caught.value.line_angle_deg == 0.0
    assert str(caught.value) == (
        "link block+lever, crank angle 0°: toggle position: the group's links are stretched "
        "out or folded in line, its two construction lines are parallel and its motion is not "
        "determined")


@pytest.mark.parametrize("reference", PATHS)
@pytest.mark.parametrize("units", [100, 400])
def test_rpr_slot_beyond_rounding_of_the_pins_reach_is_short_by_the_exact_gap(units,
                                                                                reference):
    """Past that tolerance the slot misses the pin: an AssemblyError at crank angle 0 whose
    shortfall is the exact gap |offset| − |O2B| = units · 2⁻⁵², also printed."""
    mechanism = exercise_from_dict(_lever_tangent(1.5 + units * ULP)).mechanism
    with pytest.raises(AssemblyError) as caught:
        solve(mechanism, np.array([90.0, 45.0, 0.0, -30.0]), reference=reference)
    gap = units * ULP
    assert (caught.value.link, caught.value.angle) == ("block+lever", 0.0)
    assert caught.value.shortfall == gap
    assert str(caught.value) == (
        "link block+lever, crank angle 0°: the guide of lever passes 1.5 m from its pivot O2; "
        f"it cannot reach B: short by {gap:.6g} m")


@pytest.mark.parametrize("reference", PATHS)
def test_rpr_slot_one_metre_from_the_pivot_is_checked_too(reference):
    """A slot exactly 1 m from the pivot (an offset of +1 in the lever's frame) that the pin
    cannot reach at 270° (|O2B| = 1.2 − 0.5 = 0.7) is refused there, short by 0.3 m."""
    data = slotted_lever(crank=0.5, centres=1.2, angle=90.0)
    data["links"]["lever"]["T"] = [0.1, -1.0]
    data["slide"][0]["through"] = "T"
    mechanism = exercise_from_dict(data).mechanism
    with pytest.raises(AssemblyError) as caught:
        solve(mechanism, np.array([90.0, 180.0, 270.0]), reference=reference)
    assert (caught.value.link, caught.value.angle) == ("block+lever", 270.0)
    assert caught.value.shortfall == pytest.approx(0.3, rel=1e-12)
    assert str(caught.value) == (
        "link block+lever, crank angle 270°: the guide of lever passes 1 m from its pivot "
        "O2; it cannot reach B: short by 0.3 m")


@pytest.mark.parametrize("reference", PATHS)
def test_rpr_slot_just_inside_the_tolerance_solves(reference):
    """Well inside reach (600 units of 2⁻⁵²) the position solves at crank angle 0, with B on
    the slot 1.5 m from O2 and the slot at the given offset from the pivot."""
    aside = 1.5 - 600 * ULP
    mechanism = exercise_from_dict(_lever_tangent(aside)).mechanism
    motion = solve(mechanism, np.array([90.0, 0.0]), stage="position", reference=reference)
    _pairs_hold(mechanism, motion)
    b, o2 = motion.position("B")[-1], motion.position("O2")[-1]
    assert np.hypot(*(b - o2)) == pytest.approx(1.5, abs=1e-15)


@pytest.mark.parametrize("reference", PATHS)
def test_rpr_pin_on_the_pivot_is_no_shortfall(reference):
    """The pin B on the pivot O2 (crank 0.5, O2 at (0, −0.5), crank angle 270°: |O2B| = 0 to
    rounding) with the slot beside the pivot: refused there as two points that coincide, with
    no shortfall said."""
    data = _lever_tangent(0.2)
    data["links"]["frame"]["O2"] = [0.0, -0.5]
    mechanism = exercise_from_dict(data).mechanism
    with pytest.raises(AssemblyError) as caught:
        solve(mechanism, np.array([90.0, 180.0, 270.0]), reference=reference)
    assert (caught.value.link, caught.value.angle, caught.value.shortfall) == (
        "block+lever", 270.0, 0.0)
    assert str(caught.value) == ("link block+lever, crank angle 270°: B and O2 coincide: the "
                                 "group has no definite position")


# -- RPR: offsets everywhere ----------------------------------------------------------------------
def _lever_offsets(slot: float = 25.0) -> dict:
    """A slotted lever with its frame turned and moved off O2, its slot at ``slot``° through T
    beside the pivot, and the block touching the slot at S, away from its pin B."""
    data = slotted_lever(crank=0.1, centres=0.3, omega=7.0, epsilon=-3.0)
    data["links"]["lever"] = {"O2": [0.03, -0.02], "C": [0.5, 0.04], "T": [0.12, 0.015]}
    data["links"]["block"] = {"B": [0.02, 0.01], "S": [0.035, -0.006]}
    data["slide"][0].update(through="T", point="S", direction=slot)
    return data


@pytest.mark.parametrize("reference", PATHS)
@pytest.mark.parametrize("sign", [1, -1])
def test_rpr_positions_and_angles_keep_every_pair(sign, reference):
    """On both assemblies: B at one place on crank and block, S on the slot line through T,
    the block turned by the slot's direction from the lever, and each link's θ its axes."""
    from planmethod.kinematics.program import model

    mechanism = exercise_from_dict(_lever_offsets()).mechanism
    group = model(mechanism).structure.groups[0]
    chosen = dict(model(mechanism).branches())
    chosen[group.index] = type(chosen[group.index])(sign, "given")
    angles = np.arange(0.0, 360.0, 30.0) + 7.0
    motion = solve(mechanism, angles, branches=chosen, reference=reference)
    _pairs_hold(mechanism, motion)
    _axes_are_theta(motion, ("block", "lever"))
    assert np.abs(_wrapped(motion.theta("block") - motion.theta("lever")
                           - np.radians(25.0))).max() <= 1e-12
    if sign == 1:
        _motion_is_the_linear_solves(mechanism, motion, angles)


def test_rpr_branch_plus_one_takes_the_larger_travel():
    """Branch +1 of an RPR dyad is the assembly with the larger travel s of the block in the
    slot (docs/exercise-file.md, "Branches"): at every angle it exceeds branch −1's."""
    from planmethod.kinematics.program import model

    mechanism = exercise_from_dict(_lever_offsets()).mechanism
    group = model(mechanism).structure.groups[0]
    travel = {}
    for sign in (1, -1):
        chosen = dict(model(mechanism).branches())
        chosen[group.index] = type(chosen[group.index])(sign, "given")
        motion = solve(mechanism, np.arange(0.0, 360.0, 30.0), branches=chosen,
                       stage="position")
        travel[sign] = motion.sliding("block/lever").s
    assert np.all(travel[1] > travel[-1])


def test_rpr_reactions_with_a_load_along_the_slot_and_the_block_off_its_pin():
    """A force on the block along the slot (the R∥ of the pin) and a block touching the slot
    away from its pin (the slide's couple has an arm): the reactions and couples equal the
    whole-system solve's."""
    data = _lever_offsets()
    data["mass"] = {"crank": {"m": 1.0, "J": 0.002}, "block": {"m": 0.5, "J": 1e-4},
                    "lever": {"m": 2.0, "J": 0.02, "S": [0.2, 0.01]}}
    data["gravity"] = {"g": 9.81}
    data["load"] = [{"link": "block", "point": "B", "force": [30.0, -12.0]},
                    {"link": "lever", "point": "C", "force": [-15.0, 8.0]}]
    exercise = exercise_from_dict(data)
    _reactions_are_the_whole_systems(exercise, np.arange(0.0, 360.0, 40.0) + 5.0)


# -- PRP -----------------------------------------------------------------------------------------
def _guides(first: dict | None = None, q1=(0.01, -0.02), q2=(-0.015, 0.01)) -> dict:
    """Two guides with Q off both sliders' origins; ``first`` replaces the first slide."""
    data = two_guides(omega=6.0, epsilon=-2.5)
    data["links"]["s1"] = {"Q": list(q1), "K": [0.04, 0.03]}
    data["links"]["s2"] = {"Q": list(q2), "M": [-0.03, 0.02]}
    data["slide"][0]["point"] = "Q"
    data["slide"][1]["point"] = "Q"
    if first is not None:
        data["slide"][0] = first
    return data


#: the slot carried by the group's block the other way round: the crank's point H slides in a
#: guide of s1 through Q (s1's +x axis then at −70° from the crank's)
REVERSED_PRP = {"link": "crank", "along": "s1", "through": "Q", "direction": 70, "point": "H"}


@pytest.mark.parametrize("reference", PATHS)
@pytest.mark.parametrize("case", [
    pytest.param({}, id="Q off both origins"),
    pytest.param({"q1": (1.0, 0.0), "q2": (0.0, 1.0)}, id="Q at (1, 0) and (0, 1)"),
    pytest.param({"q1": (0.0, 1.0), "q2": (1.0, 0.0)}, id="Q at (0, 1) and (1, 0)"),
    pytest.param({"q1": (0.0, 0.0), "q2": (0.0, 0.0)}, id="Q at both origins"),
    pytest.param({"first": REVERSED_PRP}, id="guide carried by the block"),
])
def test_prp_positions_angles_and_motion_keep_every_pair(case, reference):
    """Q at one place on s1 and s2, each slider on its guide and turned by its slide's
    direction (θ(link) = θ(along) + direction, so a guide carried by the group's link turns
    that link the other way), and the motion equal to the whole-system linear solve."""
    data = _guides(**case)
    mechanism = exercise_from_dict(data).mechanism
    angles = np.array([0.0, 30.0, 60.0, 90.0, 150.0, 200.0, 250.0])
    motion = solve(mechanism, angles, reference=reference)
    _pairs_hold(mechanism, motion)
    _axes_are_theta(motion, ("s1", "s2"))
    _motion_is_the_linear_solves(mechanism, motion, angles)


@pytest.mark.parametrize("first", [pytest.param(None, id="as drawn"),
                                   pytest.param(REVERSED_PRP, id="guide on the block")])
def test_prp_reactions_with_the_sliders_off_their_pin(first):
    """Reactions and couples equal the whole-system solve's with loads on both sliders, Q off
    their origins, each slider touching its guide away from Q (K on s1, M on s2: the couples
    have an arm), and the first guide also carried by the group's block."""
    data = _guides(first=first)
    data["slide"][1]["point"] = "M"
    if first is None:
        data["slide"][0]["point"] = "K"
    data["mass"] = {"crank": {"m": 1.0, "J": 0.002}, "s1": {"m": 0.5, "J": 1e-4},
                    "s2": {"m": 0.8, "J": 2e-4}}
    data["gravity"] = {"g": 9.81}
    data["load"] = [{"link": "s1", "point": "K", "force": [20.0, -7.0]},
                    {"link": "s2", "point": "M", "force": [-9.0, 14.0]}]
    exercise = exercise_from_dict(data)
    _reactions_are_the_whole_systems(exercise, np.array([0.0, 30.0, 60.0, 90.0, 150.0, 250.0]))


# -- RPP -----------------------------------------------------------------------------------------
def _yoke(inner: bool = False, outer: bool = False) -> dict:
    """A Scotch yoke with the block's pin and the yoke's points off their origins; ``inner``:
    the slot the other way round (the yoke's point Y slides in a guide of the block through
    B); ``outer``: the frame's point G slides in a guide of the yoke through Y."""
    data = scotch_yoke(omega=8.0, epsilon=3.0)
    data["links"]["block"] = {"B": [0.01, -0.02], "U": [0.03, 0.01]}
    data["links"]["yoke"] = {"Y": [0.02, 0.015], "Z": [0.22, 0.1]}
    data["slide"][0]["point"] = "U"
    if inner:
        data["slide"][0] = {"link": "yoke", "along": "block", "through": "B", "direction": 80,
                            "point": "Y"}
    if outer:
        data["slide"][1] = {"link": "frame", "along": "yoke", "through": "Y", "direction": 10,
                            "point": "G"}
    return data


@pytest.mark.parametrize("reference", PATHS)
@pytest.mark.parametrize("inner, outer", [
    pytest.param(False, False, id="as drawn"),
    pytest.param(False, True, id="outer guide on the yoke"),
    pytest.param(True, True, id="both guides on the group's links"),
])
def test_rpp_positions_angles_and_motion_keep_every_pair(inner, outer, reference):
    """B at one place on crank and block, each slide's point on its guide and its link turned
    by the slide's direction (the other way for a guide carried by the group's link), and the
    motion equal to the whole-system linear solve."""
    mechanism = exercise_from_dict(_yoke(inner, outer)).mechanism
    angles = np.arange(0.0, 360.0, 30.0) + 4.0
    motion = solve(mechanism, angles, reference=reference)
    _pairs_hold(mechanism, motion)
    _axes_are_theta(motion, ("block", "yoke"))
    _motion_is_the_linear_solves(mechanism, motion, angles)


@pytest.mark.parametrize("inner, outer", [(False, False), (False, True), (True, True)])
def test_rpp_reactions_with_the_block_off_its_pin(inner, outer):
    """Reactions and the couples of both slides equal the whole-system solve's, with the block
    touching its slot away from its pin and loads along both guides."""
    data = _yoke(inner, outer)
    data["mass"] = {"crank": {"m": 1.0, "J": 0.002}, "block": {"m": 0.4, "J": 1e-4},
                    "yoke": {"m": 1.5, "J": 0.01, "S": [0.1, 0.05]}}
    data["gravity"] = {"g": 9.81}
    data["load"] = [{"link": "block", "point": "B", "force": [10.0, 25.0]},
                    {"link": "yoke", "point": "Z", "force": [-30.0, 6.0]}]
    exercise = exercise_from_dict(data)
    _reactions_are_the_whole_systems(exercise, np.arange(0.0, 360.0, 40.0) + 5.0)


# -- the steps the report lists -----------------------------------------------------------------
@pytest.mark.parametrize("data, kind, steps", [
    pytest.param(_lever_offsets(), "RPR", [
        "R_B along the guide from link block's projection on the guide",
        "R_B ⟂ the guide from ΣM_O2 of the group = 0",
        "the normal force and couple of pair block/lever from link block",
        "R_O2 from the force polygon of link lever"], id="RPR"),
    pytest.param(_guides(), "PRP", [
        "force polygon of the group: ΣF + N2 + N1 = 0, each N ⟂ its guide",
        "R_Q from the equilibrium of link s2",
        "each reaction couple from its link's moments about its slide point"], id="PRP"),
    pytest.param(_yoke(), "RPP", [
        "N of pair yoke/frame from link yoke's projection on the guide of pair block/yoke",
        "R_B from the force polygon of the group",
        "the normal force and couple of pair block/yoke from link block",
        "the couple of pair yoke/frame from ΣM(yoke) = 0"], id="RPP"),
])
def test_reaction_steps_as_the_report_lists_them(data, kind, steps):
    """Each prismatic dyad's textbook sequence (docs/kinetostatics.md, "Group by group": the
    normal forces ⟂ the guides, projections on the guide, moments about the outer pin, each
    slide's couple from its link's moments), as the JSON report's ``groups`` lists it."""
    data = dict(data, mass={link: {"m": 1.0, "J": 0.01} for link in data["links"]
                            if link != "frame"})
    report = report_dict(analyse(exercise_from_dict(data)))
    groups = [group for group in report["forces"]["groups"] if group["kind"] == kind]
    assert [group["steps"] for group in groups] == [steps]


@pytest.mark.parametrize("data, kind, edges", [
    pytest.param(_lever_offsets(), "RPR", [("R∥_B", "component", "block"),
                                           ("R⊥_B", "component", "block"),
                                           ("R_O2", "reaction", "lever")], id="RPR"),
    pytest.param(_guides(), "PRP", [("N_s2/frame", "component", "s2"),
                                    ("N_s1/crank", "component", "s1")], id="PRP"),
    pytest.param(_yoke(), "RPP", [("N_yoke/frame", "component", "yoke"),
                                  ("R_B", "reaction", "block")], id="RPP"),
])
def test_force_polygon_edges_found_by_each_kind(data, kind, edges):
    """The edges a prismatic dyad adds to its force polygon (the known forces aside), in the
    order they are drawn: each named as the course writes it, of its kind, on its link."""
    from planmethod.vocabulary import EdgeKind

    data = dict(data, mass={link: {"m": 1.0, "J": 0.01} for link in data["links"]
                            if link != "frame"}, gravity={"g": 9.81})
    exercise = exercise_from_dict(data)
    solution = solve_forces(solve(exercise.mechanism, [30.0, 100.0]))
    group = next(group for group in solution.groups.groups if group.kind == kind)
    found = [(edge.label, edge.kind, edge.link) for edge in group.polygon
             if edge.kind is not EdgeKind.KNOWN]
    assert found == [(label, EdgeKind(name), link) for label, name, link in edges]


# -- parallel guides ------------------------------------------------------------------------------
def _yoke_slot_along_its_guide(aside: float = 0.0) -> dict:
    """The outer guide carried by the yoke (see :func:`_yoke`) at the slot's own angle (plus
    ``aside``°): the yoke turns by −80° and the frame's guide lies along the frame's +x axis,
    as the slot does."""
    data = _yoke(outer=True)
    data["slide"][1]["direction"] = 80 + aside
    return data


RPP_PARALLEL = ("link block+yoke, crank angle 30°: the guides of block/yoke and frame/yoke are "
                "parallel: yoke has no definite position")


PRP_PARALLEL = ("link s1+s2, crank angle 10°: the guides of crank/s1 and s2/frame are "
                "parallel: Q has no definite position")


@pytest.mark.parametrize("reference", PATHS)
@pytest.mark.parametrize("data, angles, told, first", [
    pytest.param(_guides(first=REVERSED_PRP), [0.0, 5.0, 10.0, 20.0], PRP_PARALLEL, 10.0,
                 id="PRP, guide on the block"),
    # 2e-9° from parallel: |sin| = 3.5e-11, below TOGGLE_SINE = 1e-10
    pytest.param(_guides(first=REVERSED_PRP), [0.0, 5.0, 10.0 + 2e-9, 20.0], PRP_PARALLEL,
                 10.0 + 2e-9, id="PRP, within TOGGLE_SINE of parallel"),
    pytest.param(_yoke_slot_along_its_guide(), [30.0, 40.0], RPP_PARALLEL, 30.0,
                 id="RPP, guide on the yoke"),
    pytest.param(_yoke_slot_along_its_guide(2e-9), [30.0, 40.0], RPP_PARALLEL, 30.0,
                 id="RPP, within TOGGLE_SINE of parallel"),
])
def test_parallel_guides_are_refused_with_their_names(data, angles, told, first, reference):
    """Two guides that are parallel, or within |sin| < TOGGLE_SINE of it (the crank's +x axis
    along the fixed guide at 10°; a slot always along the yoke's guide), leave the group no
    position: a ToggleError naming the group, both guides and the first crank angle where
    they are, on both paths."""
    mechanism = exercise_from_dict(data).mechanism
    with pytest.raises(ToggleError) as caught:
        solve(mechanism, np.array(angles), reference=reference)
    assert str(caught.value) == told
    assert (caught.value.link, caught.value.angle, caught.value.line_angle_deg) == (
        told.split()[1].rstrip(","), first, 0.0)
