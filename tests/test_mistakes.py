"""Each known mistake, made by a student from the exercise itself, is named by the grader on
every quantity it affects and on no other: construction mistakes by drawing the plans again
with the mistake (every downstream quantity follows), value mistakes from the right value."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from planmethod.grading.answers import grade_answers
from planmethod.grading.keys import build_key
from planmethod.grading.mistakes import CONSTRUCTION_MISTAKES, MISTAKES, mistaken_plans
from planmethod.grading.templates import draw_variant, load_template
from planmethod.kinematics import solve
from planmethod.plans import draw_plans
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.words import render

#: exercises where each construction mistake can be made (Coriolis: a slide on a turning link)
WHERE = {"no_normal": "exercises/compressor_slider_crank.toml",
         "tangential_along": "exercises/templates/four_bar.toml",
         "no_coriolis": "exercises/slotted_lever.toml",
         "coriolis_reversed": "exercises/slotted_lever.toml",
         # a coupler point off the coupler's line: its images can be turned over
         "mirrored_similarity": "exercises/fourbar_coupler_point.toml"}


def _key_and_variant(path: str):
    variant = draw_variant(load_template(path))
    return variant, build_key(variant)


def _graded(key: dict, answers: dict) -> dict[str, dict]:
    result = grade_answers(key, answers).as_dict()
    return {question["id"]: question for question in result["questions"]}


@pytest.mark.parametrize("mistake", CONSTRUCTION_MISTAKES)
def test_a_construction_mistake_is_named_on_every_quantity_it_changes(mistake):
    variant, key = _key_and_variant(WHERE[mistake])
    mechanism = variant.exercise.mechanism
    motion = solve(mechanism, mechanism.drive.angle)
    plans = mistaken_plans(variant.exercise, mistake, motion=motion)
    assert plans is not None, f"{WHERE[mistake]} has no component for {mistake}"
    answers, affected = {}, set()
    for question in key["questions"]:
        name = question["id"]
        wrong = plans.readings.get(name)
        if wrong is None:
            continue
        answers[name] = wrong
        if abs(wrong - question["value"]) > 2 * question["tolerance"]:
            affected.add(name)
    assert len(affected) >= 2, (mistake, affected)      # it corrupts more than one quantity
    for name, question in _graded(key, answers).items():
        if name in affected:
            assert question["mistake"] == mistake, (name, question["feedback"])
            assert not question["correct"]
        elif name in answers:
            assert question["correct"], (name, question["feedback"])


VALUE_MISTAKES = {"scale_ten": 10.0, "scale_tenth": 0.1}


@pytest.mark.parametrize("mistake", sorted(VALUE_MISTAKES))
@pytest.mark.parametrize("path", ["exercises/compressor_slider_crank.toml",
                                  "exercises/slotted_lever.toml"])
def test_a_scale_misread_by_ten_is_named_on_every_quantity_read_at_a_scale(mistake, path):
    _, key = _key_and_variant(path)
    factor = VALUE_MISTAKES[mistake]
    answers = {q["id"]: q["value"] * factor for q in key["questions"]}
    graded = _graded(key, answers)
    assert graded
    for name, question in graded.items():
        named = [question["mistake"], *question.get("also", ())]
        assert mistake in named, (name, question["feedback"])     # alone, or with one that
        assert render(MISTAKES[mistake]) in question["feedback"]  # gives the same answer


@pytest.mark.parametrize("path", ["exercises/compressor_slider_crank.toml",
                                  "exercises/slotted_lever.toml"])
def test_a_drawn_length_divided_by_the_scale_is_named(path):
    """(pc) = v/μv read, then divided by μv again: v/μv² (ω: the length's μl as well)."""
    from planmethod.grading.tolerances import scale_factor

    _, key = _key_and_variant(path)
    scales = key["scales"]
    answers = {}
    for question in key["questions"]:
        factor = scale_factor(question["id"], scales["mu_l"], scales["mu_v"], scales["mu_a"])
        if factor and factor != 1.0:
            answers[question["id"]] = question["value"] / factor ** 2
    graded = _graded(key, answers)
    assert len(graded) >= 3
    for name, question in graded.items():
        named = [question["mistake"], *question.get("also", ())]
        assert "scale_inverted" in named, (name, question["feedback"])
        assert not question["correct"]


def test_a_mistake_outside_the_key_is_not_named():
    _, key = _key_and_variant("exercises/compressor_slider_crank.toml")
    answers = {q["id"]: q["value"] * 3.7 for q in key["questions"]}
    for name, question in _graded(key, answers).items():
        assert question["mistake"] is None and not question["correct"], name


def test_an_angular_velocity_read_with_the_other_links_length_is_named():
    from planmethod.grading.mistakes import other_lengths

    variant, key = _key_and_variant("exercises/templates/four_bar.toml")
    mechanism = variant.exercise.mechanism
    motion = solve(mechanism, mechanism.drive.angle)
    answers, expected = {}, set()
    for question in key["questions"]:
        kind, _, link = question["id"].partition("_")
        if kind in ("omega", "epsilon"):
            ((_, ratio),) = other_lengths(motion, link)       # the dyad's other link
            answers[question["id"]] = question["value"] * ratio
            # named where the key can tell it from a right answer (its 2× rule)
            if abs(answers[question["id"]] - question["value"]) > 2 * question["tolerance"]:
                expected.add(question["id"])
    assert len(expected) >= 2
    for name, question in _graded(key, answers).items():
        if name not in expected:
            continue
        named = [question["mistake"], *question.get("also", ())]
        assert "wrong_length" in named, (name, question["feedback"])


def test_a_relative_velocity_read_for_the_absolute_one_is_named():
    import numpy as np

    variant, key = _key_and_variant("exercises/templates/four_bar.toml")
    mechanism = variant.exercise.mechanism
    motion = solve(mechanism, mechanism.drive.angle)
    # v_CB and a_CB: the segment bc (or its acceleration twin) read instead of pc
    def size(vector) -> float:
        return float(np.hypot(*np.reshape(vector, (-1, 2))[0]))

    answers = {"v_C": size(motion.velocity("C") - motion.velocity("B")),
               "a_C": size(motion.acceleration("C") - motion.acceleration("B"))}
    graded = _graded(key, answers)
    for name in answers:
        named = [graded[name]["mistake"], *graded[name].get("also", ())]
        assert "relative_for_absolute" in named, (name, graded[name]["feedback"])


# -- the value rules, each against the plan or the mechanism itself --------------------------
def test_the_full_acceleration_for_the_normal_one_gives_v_squared_over_a():
    """ρ = v²/aⁿ read with the full acceleration: v²/|a|, from the exact vectors."""
    import numpy as np

    variant, key = _key_and_variant("exercises/compressor_slider_crank.toml")
    mechanism = variant.exercise.mechanism
    motion = solve(mechanism, mechanism.drive.angle)
    found = {}
    for question in key["questions"]:
        values = {m["kind"]: m["value"] for m in question["mistakes"]}
        if question["id"].startswith("rho_"):
            point = question["id"].removeprefix("rho_")
            speed = float(np.hypot(*np.ravel(motion.velocity(point))[:2]))
            accel = float(np.hypot(*np.ravel(motion.acceleration(point))[:2]))
            found[point] = values["full_acceleration"]
            assert values["full_acceleration"] == pytest.approx(speed ** 2 / accel, rel=1e-12)
        else:
            assert "full_acceleration" not in values, question["id"]
    assert found


def test_a_point_without_acceleration_has_no_full_acceleration_mistake(monkeypatch):
    """a = 0: no radius is read with it (not a division by zero)."""
    import planmethod.report
    from planmethod.grading.mistakes import REGISTRY

    monkeypatch.setattr(planmethod.report, "exact_value",
                        lambda motion, name: 0.0 if name.startswith("a_") else 3.0)
    from types import SimpleNamespace

    rule = REGISTRY["full_acceleration"].value
    motion = SimpleNamespace(at=lambda index: None)     # read at its one angle: by the above
    assert rule("rho_D", 0.07, 0.001, SimpleNamespace(motion=motion)) == []


def test_the_other_links_length_ratio_comes_from_the_links_themselves():
    """In each dyad of a six-bar (a second RRR dyad on the coupler point), ω read with the
    other link's length is scaled by l_link / l_other."""
    from planmethod.grading.mistakes import other_lengths
    from planmethod.testing import fourbar

    data = fourbar()
    data["links"]["frame"]["E"] = [0.35, 0.25]
    data["links"]["PQ"] = {"P": [0, 0], "Q": [0.2, 0]}
    data["links"]["QE"] = {"Q": [0, 0], "E": [0.15, 0]}
    data["sketch"]["Q"] = [0.25, 0.38]
    mechanism = exercise_from_dict(data).mechanism
    motion = solve(mechanism, mechanism.drive.angle)
    assert [group.links for group in motion.structure.groups] == [("BC", "CD"), ("PQ", "QE")]
    lengths = {"BC": 0.22, "CD": 0.18, "PQ": 0.2, "QE": 0.15}
    for link, other in (("BC", "CD"), ("CD", "BC"), ("PQ", "QE"), ("QE", "PQ")):
        ((name, ratio),) = other_lengths(motion, link)
        assert name == other and ratio == pytest.approx(lengths[link] / lengths[other],
                                                        rel=1e-12)
    assert other_lengths(motion, "AB") == [] and other_lengths(motion, "nowhere") == []


def test_links_of_one_length_give_no_wrong_length_at_any_size():
    """The other link of the same length (to 1e-10 of it, at 1 mm or at 1 km) reads ω the
    same: no mistake to name."""
    from planmethod.grading.mistakes import other_lengths
    from planmethod.testing import fourbar

    for size in (0.001, 1000.0):
        mechanism = exercise_from_dict(fourbar(
            ground=0.30 * size, crank=0.08 * size, coupler=0.2 * size,
            rocker=0.2 * size * (1 + 1e-10), point=(0.1 * size, 0.05 * size))).mechanism
        motion = solve(mechanism, mechanism.drive.angle)
        coupler = next(link for link in motion.structure.groups[0].links)
        assert other_lengths(motion, coupler) == [], size


# -- the construction rules, on the plans drawn again ------------------------------------------
def test_the_tangential_component_along_the_link_turns_that_line_only():
    """The slider's relative acceleration still runs along its guide (the pole's horizontal):
    only the rod's tangential line is turned."""
    import numpy as np

    from planmethod.report import analyse

    analysis = analyse(load_exercise("exercises/compressor_slider_crank.toml"))
    right = analysis.plans.acceleration.points_mm
    wrong = mistaken_plans(analysis.exercise, "tangential_along").acceleration.points_mm
    assert right["c"][1] == pytest.approx(0.0, abs=1e-9)
    assert wrong["c"][1] == pytest.approx(0.0, abs=1e-9)
    assert abs(wrong["c"][0] - right["c"][0]) > 10.0       # along the guide, elsewhere
    assert np.allclose(wrong["b"], right["b"])


@pytest.mark.parametrize("mistake, moved", [("no_coriolis", 1.0), ("coriolis_reversed", 2.0)])
def test_a_coriolis_component_drawn_under_a_millimetre_is_still_left_out_or_reversed(
        mistake, moved):
    """At 88° the slotted lever's aᵏ is drawn 0.52 mm long: left out it moves b₃ by that
    length, reversed by twice it."""
    import numpy as np

    from planmethod.report import analyse

    analysis = analyse(load_exercise("exercises/slotted_lever.toml"), 88.0)
    right = analysis.plans.acceleration.points_mm
    coriolis = float(np.hypot(*(np.asarray(right["k_B@lever"]) - np.asarray(right["b"]))))
    assert 0.1 < coriolis < 1.0
    wrong = mistaken_plans(analysis.exercise, mistake).acceleration.points_mm
    away = float(np.hypot(*(np.asarray(wrong["b@lever"]) - np.asarray(right["b@lever"]))))
    assert away == pytest.approx(moved * coriolis, rel=1e-6)


@pytest.mark.parametrize("name", ["compressor_slider_crank", "slotted_lever", "shaper_sixbar"])
def test_a_mistake_that_changes_no_length_of_the_exact_drawing_is_not_drawn(name, monkeypatch):
    """Given the exact drawing's lengths (as a key has them from the tolerance analysis), a
    mistake made only in the lengths laid off that changes none of them gives None without
    drawing the plans again (the compressor's Coriolis components are all 0: no_coriolis and
    coriolis_reversed); every other answer is the one drawn without them."""
    import planmethod.plans as plans_module
    from planmethod.grading.tolerances import propagate

    exercise = load_exercise(f"exercises/{name}.toml")
    motion = solve(exercise.mechanism, exercise.mechanism.drive.angle, stage="acceleration")
    found = propagate(exercise, 0.5, motion=motion)
    drawn = tuple(zip(found.lengths, found.segments, strict=True))
    assert [segment for _, segment in drawn] == list(found.segments)
    draws = []
    original = plans_module.draw_plans

    def counted(*args, **kwargs):
        draws.append(1)
        return original(*args, **kwargs)

    for mistake in CONSTRUCTION_MISTAKES:
        alone = mistaken_plans(exercise, mistake, motion=motion)
        monkeypatch.setattr(plans_module, "draw_plans", counted)
        draws.clear()
        given = mistaken_plans(exercise, mistake, motion=motion, drawn=drawn)
        monkeypatch.setattr(plans_module, "draw_plans", original)
        assert (given is None) == (alone is None)
        if given is not None:
            assert given.readings == alone.readings and draws == [1]
        skipped = (name == "compressor_slider_crank"
                   and mistake in ("no_coriolis", "coriolis_reversed"))
        assert (draws == []) == skipped, mistake


def test_a_mirrored_similarity_puts_the_image_at_its_mirror_image_across_the_links_line():
    """The coupler point's image placed by the similarity rule with its triangle turned over
    lands at the right image reflected across the line of the link's other images (b, c), on
    both plans; the images that rule does not place stay where they are."""
    exercise = load_exercise(WHERE["mirrored_similarity"])
    wrong = mistaken_plans(exercise, "mirrored_similarity")
    right = draw_plans(exercise, settings=replace(exercise.plan, precision_mm=0.0))
    for plan in ("velocity", "acceleration"):
        drawn = getattr(wrong, plan).points_mm
        exact = getattr(right, plan).points_mm
        b, c, e = (np.asarray(exact[label]) for label in "bce")
        along = (c - b) / np.linalg.norm(c - b)
        foot = b + along * np.dot(e - b, along)
        assert np.allclose(drawn["e"], 2.0 * foot - e, rtol=0, atol=1e-9), plan
        assert not np.allclose(drawn["e"], e, atol=1.0)         # off the line: it moved
        assert np.allclose(drawn["b"], b) and np.allclose(drawn["c"], c)


def test_a_similarity_model_is_shown_each_image_by_its_label_and_link():
    """draw_plans shows a ``mirror`` model each image the similarity rule places off its link's
    line as a segment naming the image's label and the link (as draw_plans documents it)."""
    exercise = load_exercise(WHERE["mirrored_similarity"])
    seen = []

    def watch(segment) -> bool:
        seen.append((str(segment.plan), segment.action, segment.name, segment.vector))
        return False

    draw_plans(exercise, mirror=watch)
    assert ("velocity", "similarity", "e", "BC") in seen
    assert ("acceleration", "similarity", "e", "BC") in seen
