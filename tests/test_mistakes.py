"""Each known mistake, made by a student from the exercise itself, is named by the grader on
every quantity it affects and on no other: construction mistakes by drawing the plans again
with the mistake (every downstream quantity follows), value mistakes from the right value."""

from __future__ import annotations

import pytest

from planmethod.grading.answers import grade_answers
from planmethod.grading.keys import build_key
from planmethod.grading.mistakes import CONSTRUCTION_MISTAKES, MISTAKES, mistaken_plans
from planmethod.grading.templates import draw_variant, load_template
from planmethod.kinematics import solve

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
    result = grade_answers(key, answers)
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
        assert MISTAKES[mistake] in question["feedback"]          # gives the same answer


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
