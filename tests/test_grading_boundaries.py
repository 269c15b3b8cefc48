"""Every grading rule at its boundary: an answer 0.99 of a tolerance away is in, 1.01 is out.

The grader's main job is telling an answer just inside its tolerance from one just outside it,
so each rule is tried on both sides of its own boundary, with keys built from shipped exercises
and the answers derived from each key's own values and tolerances (never typed in):

* a numeric answer and the question's tolerance, for each kind of quantity (a speed or an
  acceleration, a signed ω or ε, ρ, a sliding s, ds/dt, d²s/dt² and aᵏ);
* an answer and each mistake's own tolerance around the mistake's answer (named or not);
* the key's rule of mistakes: a mistake is listed only when its answer lies beyond twice the
  tolerance from the right one;
* a drawn point and its tolerance disc, a point and a mistake's disc, a whole plan and the plan
  drawn with a mistake (within twice each point's radius);
* PrairieLearn's ``grade()`` (numbers and plan points) and the ``relabs`` comparison its
  number inputs are given.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from planmethod.grading.answers import grade_question
from planmethod.grading.drawings import Drawing, grade_drawing
from planmethod.grading.exports import prairielearn_questions
from planmethod.grading.keys import GradingSettings, build_key, bundle
from planmethod.grading.templates import draw_variant, load_template
from planmethod.grading.tolerances import kind_of
from planmethod.words import render

#: shipped exercises whose keys ask every kind of quantity between them
EXERCISES = ("exercises/compressor_slider_crank.toml", "exercises/slotted_lever.toml",
             "exercises/offset_slider_crank.toml")
#: the kinds of quantity the grader compares, each asked by one of :data:`EXERCISES`
KINDS = ("v", "a", "omega", "epsilon", "rho", "s", "ds", "dds", "coriolis")
INSIDE, OUTSIDE = 0.99, 1.01


@pytest.fixture(scope="module")
def keys() -> dict[str, dict]:
    return {path: build_key(draw_variant(load_template(path))) for path in EXERCISES}


def _questions(keys) -> list[dict]:
    return [question for key in keys.values() for question in key["questions"]]


def _by_kind(keys) -> dict[str, list[dict]]:
    found: dict[str, list[dict]] = {}
    for question in _questions(keys):
        found.setdefault(kind_of(question["id"]), []).append(question)
    return found


# -- a numeric answer and its tolerance ----------------------------------------------------------
@pytest.mark.parametrize("kind", KINDS)
def test_an_answer_within_its_tolerance_is_right_and_one_just_outside_is_wrong(keys, kind):
    questions = _by_kind(keys)[kind]
    assert questions, f"no shipped exercise asks a {kind} quantity"
    for question in questions:
        value, tolerance = question["value"], question["tolerance"]
        assert tolerance > 0
        for side in (1.0, -1.0):
            inside = grade_question(question, value + side * INSIDE * tolerance).as_dict()
            outside = grade_question(question, value + side * OUTSIDE * tolerance).as_dict()
            assert inside["correct"] and inside["score"] == question["points"], \
                (question["id"], side)
            assert not outside["correct"] and outside["score"] == 0.0, (question["id"], side)
            assert "wrong" in outside["feedback"] and "correct" in inside["feedback"]


def test_a_signed_answer_of_the_other_sense_is_wrong_at_any_distance(keys):
    """ω, ε and the sliding quantities are signed: their sense is part of the answer (a
    speed, ρ and aᵏ are magnitudes, and a negative magnitude is told it is one)."""
    for question in _questions(keys):
        value, tolerance = question["value"], question["tolerance"]
        if abs(value) <= 2 * tolerance:
            continue
        flipped = grade_question(question, -value).as_dict()
        assert not flipped["correct"], question["id"]
        if question["signed"]:
            assert flipped["mistake"] == "sense", question["id"]
        else:
            assert "a magnitude, never negative" in flipped["feedback"], question["id"]


# -- an answer and a mistake's tolerance ---------------------------------------------------------
def _alone(question: dict, mistake: dict) -> bool:
    """Whether ``mistake``'s disc, widened to 1.01 of its tolerance, touches neither the right
    answer's nor another mistake's (so that only its own rule decides there)."""
    reach = OUTSIDE * mistake["tolerance"]
    if abs(mistake["value"] - question["value"]) <= reach + question["tolerance"]:
        return False
    for other in question["mistakes"]:
        if other is not mistake and (abs(other["value"] - mistake["value"])
                                     <= reach + other["tolerance"]
                                     or abs(-other["value"] - mistake["value"])
                                     <= reach + other["tolerance"]):
            return False
    return True


def _mirror_alone(question: dict, mistake: dict) -> bool:
    """Whether the mirror image of ``mistake``'s disc (−its answer), widened to 1.01 of its
    tolerance, touches neither the right answer's disc, nor any mistake's disc, nor the mirror
    image of another mistake's."""
    mirrored, reach = -mistake["value"], OUTSIDE * mistake["tolerance"]
    if abs(mirrored - question["value"]) <= reach + question["tolerance"]:
        return False
    return not any(abs(other["value"] - mirrored) <= reach + other["tolerance"]
                   or (other is not mistake
                       and abs(other["value"] - mistake["value"]) <= reach + other["tolerance"])
                   for other in question["mistakes"])


def test_an_answer_within_a_mistakes_tolerance_names_it_and_one_just_outside_does_not(keys):
    tried: set[str] = set()
    for question in _questions(keys):
        for mistake in question["mistakes"]:
            if not _alone(question, mistake):
                continue
            for side in (1.0, -1.0):
                near = mistake["value"] + side * INSIDE * mistake["tolerance"]
                far = mistake["value"] + side * OUTSIDE * mistake["tolerance"]
                named = grade_question(question, near).as_dict()
                other = grade_question(question, far).as_dict()
                assert named["mistake"] == mistake["kind"], (question["id"], mistake["kind"])
                assert not named["correct"] and named["score"] == 0.0
                assert other["mistake"] != mistake["kind"], (question["id"], mistake["kind"])
                assert not other["correct"]
            tried.add(kind_of(question["id"]))
    assert tried == set(KINDS)


def test_a_signed_answer_of_a_mistake_with_the_sense_reversed_too_is_named_both(keys):
    """For ω and ε (and the sliding quantities) a mistake's answer with the sign reversed is
    named as that mistake and a reversed sense — within that mistake's tolerance only."""
    tried = 0
    for question in _questions(keys):
        if not question["signed"]:
            continue
        for mistake in question["mistakes"]:
            if mistake["kind"] == "sense" or not _mirror_alone(question, mistake):
                continue
            for factor, named in ((INSIDE, True), (OUTSIDE, False)):
                answer = -(mistake["value"] + factor * mistake["tolerance"])
                result = grade_question(question, answer).as_dict()
                assert (result["mistake"] == f"{mistake['kind']}+sense") is named, \
                    (question["id"], mistake["kind"], factor)
            tried += 1
    assert tried >= 10


# -- the key's rule: a mistake is listed beyond twice the tolerance ------------------------------
@pytest.mark.parametrize(("path", "quantity", "mistake"), [
    ("exercises/compressor_slider_crank.toml", "omega_BC", "sense"),
    ("exercises/compressor_slider_crank.toml", "v_C", "scale_ten"),
    ("exercises/compressor_slider_crank.toml", "epsilon_BC", "degrees"),
    ("exercises/slotted_lever.toml", "ds_block/lever", "sense"),
])
def test_a_mistake_is_listed_only_beyond_twice_the_tolerance(keys, path, quantity, mistake):
    """With the question's tolerance set (the [grading] table's ``abs`` override) so that the
    mistake's answer lies 1.99 tolerances from the right one, the key leaves it out (an answer
    there is just wrong); at 2.01 tolerances it is listed."""
    variant = draw_variant(load_template(path))
    question = next(q for q in keys[path]["questions"] if q["id"] == quantity)
    wrong = next(m for m in question["mistakes"] if m["kind"] == mistake)
    distance = abs(wrong["value"] - question["value"])
    for ratio, listed in ((1.99, False), (2.01, True)):
        settings = GradingSettings(overrides={quantity: ("abs", distance / ratio)})
        found = next(q for q in build_key(variant, settings=settings)["questions"]
                     if q["id"] == quantity)
        assert found["tolerance"] == pytest.approx(distance / ratio, rel=1e-15)
        kinds = [m["kind"] for m in found["mistakes"]] + [
            also for m in found["mistakes"] for also in m.get("also", ())]
        assert (mistake in kinds) is listed, (ratio, kinds)


# -- drawn points and their discs ----------------------------------------------------------------
def _plan_points(key: dict, plan: str) -> dict[str, tuple[float, float]]:
    return {label: tuple(xy) for label, xy in key["plans"][plan]["points_mm"].items()}


def _graded(key: dict, plan: str, points: dict) -> dict[str, dict]:
    result = grade_drawing(key, Drawing(points, plan), rescale=False).as_dict()
    return {point["point"]: point for point in result["points"]}


def _across(point) -> np.ndarray:
    """A unit vector across the pole's ray to ``point`` (a move that keeps its distance from
    the pole, so that no scale is read into it)."""
    x, y = point
    length = math.hypot(x, y)
    return np.array([-y / length, x / length]) if length else np.array([1.0, 0.0])


@pytest.mark.parametrize("plan", ["velocity", "acceleration"])
def test_a_drawn_point_within_its_disc_is_right_and_one_just_outside_is_wrong(keys, plan):
    tried = 0
    for key in keys.values():
        entry = key["plans"][plan]
        right = _plan_points(key, plan)
        for label in {p.point for p in grade_drawing(key, Drawing(right, plan)).points
                      if p.max_score}:
            radius = entry["tolerance_mm"][label]
            for direction in (_across(right[label]), np.array([0.6, -0.8])):
                for factor, inside in ((INSIDE, True), (OUTSIDE, False)):
                    points = dict(right)
                    points[label] = tuple(np.asarray(right[label]) + factor * radius
                                          * direction)
                    graded = _graded(key, plan, points)[label]
                    assert graded["correct"] is inside, (label, factor)
                    assert graded["score"] == (1.0 if inside else 0.0)
                    assert graded["distance_mm"] == pytest.approx(factor * radius)
            tried += 1
    assert tried >= 6


def test_a_drawn_points_disc_is_round_in_every_direction(keys):
    """The disc is a circle, not a polygon drawn round it: 0.9999 of the radius is in and
    1.0001 out in any direction (a 128-gon's edge lies 0.03 % inside the circle at its middle,
    π/128 off its corners)."""
    key = keys["exercises/compressor_slider_crank.toml"]
    right = _plan_points(key, "velocity")
    radius = key["plans"]["velocity"]["tolerance_mm"]["c"]
    for angle in np.arange(0.0, 2 * np.pi, np.pi / 128) + np.pi / 256:
        for factor, inside in ((0.9999, True), (1.0001, False)):
            points = dict(right)
            points["c"] = tuple(np.asarray(right["c"]) + factor * radius
                                * np.array([np.cos(angle), np.sin(angle)]))
            assert _graded(key, "velocity", points)["c"]["correct"] is inside, (angle, factor)


def test_a_drawn_point_within_a_mistakes_disc_is_named_and_one_just_outside_is_not(keys):
    tried = 0
    for key in keys.values():
        for plan in ("velocity", "acceleration"):
            entry = key["plans"][plan]
            right = _plan_points(key, plan)
            for label, candidates in entry["mistake_points"].items():
                radius = entry["tolerance_mm"][label]
                for mistake, x, y in candidates:
                    at = np.array([x, y])
                    if sum(math.dist((ox, oy), at) <= 2.02 * radius
                           for _, ox, oy in candidates) > 1:
                        continue        # another disc within reach: not this rule alone
                    away = at - np.asarray(right[label])
                    direction = away / np.hypot(*away)    # away from the right point
                    for factor, named in ((INSIDE, True), (OUTSIDE, False)):
                        points = dict(right)
                        points[label] = tuple(at + factor * radius * direction)
                        graded = _graded(key, plan, points)[label]
                        assert not graded["correct"]
                        assert (mistake in graded.get("mistakes", ())) is named, \
                            (label, mistake, factor)
                    tried += 1
    assert tried >= 20


def test_a_whole_plan_is_named_when_each_wrong_point_lies_within_its_radius_of_the_mistake(
        keys):
    """The velocity plan drawn turned 180° (the sense of ω₁ reversed), each point then moved
    across by 0.99 of its radius from where that mistake puts it, is named as a whole (every
    wrong point names the mistake: the page's rule too); by 1.01 neither a point nor the plan
    names it."""
    from planmethod.grading.plan_points import plan_sentence

    key = keys["exercises/compressor_slider_crank.toml"]
    entry = key["plans"]["velocity"]
    turned = {label: tuple(xy) for label, xy in entry["mistakes"]["sense"].items()}
    for factor, named in ((INSIDE, True), (OUTSIDE, False)):
        points = {label: tuple(np.asarray(xy) + factor * entry["tolerance_mm"][label]
                               * _across(xy)) if label != entry["pole"] else xy
                  for label, xy in turned.items()}
        result = grade_drawing(key, Drawing(points, "velocity"), rescale=False).as_dict()
        assert result["score"] == 0.0
        wrong = [point for point in result["points"] if not point["correct"]]
        assert len(wrong) >= 2
        assert all(("sense" in point.get("mistakes", [])) is named for point in wrong), factor
        assert result["plan_mistakes"] == (["sense"] if named else []), factor
        assert (render(plan_sentence(["sense"])) in result["feedback"]) is named, factor


# -- PrairieLearn's grade() ----------------------------------------------------------------------
def _server(key: dict) -> dict:
    files = prairielearn_questions(bundle([key]), slug="q")
    namespace: dict = {}
    exec(compile(files["q/server.py"], "server.py", "exec"), namespace)  # our own code
    return namespace


def _generated(namespace: dict) -> dict:
    data = {"params": {}, "correct_answers": {}, "variant_seed": 1}
    namespace["generate"](data)
    return data


def _relabs(answer: float, right: float, rtol: float, atol: float) -> bool:
    """PrairieLearn's pl-number-input ``comparison="relabs"``."""
    return abs(answer - right) <= atol + rtol * abs(right)


@pytest.mark.parametrize("path", EXERCISES)
def test_prairielearn_grades_numbers_at_their_tolerance(keys, path):
    key = keys[path]
    namespace = _server(key)
    data = _generated(namespace)
    params = data["params"]
    questions = {question["id"]: question for question in key["questions"]}
    for ident, right in data["correct_answers"].items():
        question = next(q for q in questions.values()
                        if q["value"] == right and params["tolerance"][ident]
                        == q["tolerance"])
        tolerance = question["tolerance"]
        for side in (1.0, -1.0):
            for factor, inside in ((INSIDE, True), (OUTSIDE, False)):
                answer = right + side * factor * tolerance
                data.update(submitted_answers={ident: answer}, partial_scores={})
                namespace["grade"](data)
                assert data["partial_scores"][ident]["score"] == (1.0 if inside else 0.0), \
                    (ident, side, factor)
                # the number input's own comparison agrees with grade()
                assert _relabs(answer, right, params["rtol"][ident],
                               params["atol"][ident]) is inside, (ident, side, factor)


@pytest.mark.parametrize("plan", ["velocity", "acceleration"])
def test_prairielearn_finds_a_plan_point_within_its_disc_only(keys, plan):
    key = keys["exercises/slotted_lever.toml"]
    namespace = _server(key)
    data = _generated(namespace)
    points = data["params"]["plans"][plan]
    radii = data["params"]["radius_px"][plan]
    for ident in points:
        for factor, inside in ((INSIDE, True), (OUTSIDE, False)):
            placed = [{"gradingName": "pl-point",
                       "left": point["x"] + (factor * radii[ident] if name == ident else 0.0),
                       "top": point["y"]} for name, point in points.items()]
            data.update(submitted_answers={f"{plan}_plan": placed}, partial_scores={})
            namespace["grade"](data)
            part = data["partial_scores"][f"{plan}_plan"]
            expected = 1.0 if inside else (len(points) - 1) / len(points)
            assert part["score"] == pytest.approx(expected), (ident, factor)


def test_prairielearn_names_a_mistake_within_its_disc_only(keys):
    key = keys["exercises/slotted_lever.toml"]
    namespace = _server(key)
    data = _generated(namespace)
    params = data["params"]
    points, radii = params["plans"]["acceleration"], params["radius_px"]["acceleration"]
    tried = 0
    for ident, candidates in params["mistakes_px"]["acceleration"].items():
        for mistake, x, y in candidates:
            if any(other != mistake and math.dist((ox, oy), (x, y)) <= 2.02 * radii[ident]
                   for other, ox, oy in candidates):
                continue
            right = (points[ident]["x"], points[ident]["y"])
            away = np.subtract((x, y), right)
            direction = away / np.hypot(*away)
            for factor, named in ((INSIDE, True), (OUTSIDE, False)):
                placed = [{"gradingName": "pl-point", "left": p["x"], "top": p["y"]}
                          for name, p in points.items() if name != ident]
                spot = np.array([x, y]) + factor * radii[ident] * direction
                placed.append({"gradingName": "pl-point", "left": spot[0], "top": spot[1]})
                data.update(submitted_answers={"acceleration_plan": placed}, partial_scores={})
                namespace["grade"](data)
                feedback = data["partial_scores"]["acceleration_plan"]["feedback"]
                text = namespace["MISTAKE_TEXTS"][mistake]
                assert (text in feedback) is named, (ident, mistake, factor)
            tried += 1
    assert tried >= 3
