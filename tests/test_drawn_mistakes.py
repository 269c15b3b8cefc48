"""Where the known mistakes put each point of a drawn plan — carried by the answer key,
computed from the mistake registry's own rules — and the drawing graders naming a misplaced
point by them (``planmethod grade --drawing``; the workbook page's drawing mode and
PrairieLearn's grade() read the same data: tests/test_browser.py, test_grading_exports.py).
A drawing downloaded from the page carries its exercise and angle."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from planmethod.cli import main
from planmethod.grading.drawings import Drawing, grade_drawing, parse_drawing_json
from planmethod.grading.keys import build_key
from planmethod.grading.mistakes import MISTAKES, REGISTRY, mistaken_plans
from planmethod.grading.plan_points import (
    DRAWN_MISTAKES,
    drawing_frame,
    drawn_labels,
    named_mistakes,
)
from planmethod.grading.templates import draw_variant, load_template
from planmethod.kinematics import solve
from planmethod.words import render

ROOT = Path(__file__).resolve().parent.parent
SLOTTED = "exercises/slotted_lever.toml"
COMPRESSOR = "exercises/compressor_slider_crank.toml"


def _key_and_variant(path: str):
    variant = draw_variant(load_template(path))
    return build_key(variant), variant


@pytest.fixture(scope="module")
def slotted():
    return _key_and_variant(SLOTTED)


@pytest.fixture(scope="module")
def compressor():
    return _key_and_variant(COMPRESSOR)


def _points(key, plan):
    return {label: tuple(xy) for label, xy in key["plans"][plan]["points_mm"].items()}


def _candidates(key, plan, label, mistake):
    return [(x, y) for kind, x, y in key["plans"][plan]["mistake_points"].get(label, ())
            if kind == mistake]


def test_the_key_puts_a_construction_mistakes_points_where_its_redrawn_plan_does(slotted):
    key, variant = slotted
    mechanism = variant.exercise.mechanism
    motion = solve(mechanism, mechanism.drive.angle)
    redrawn = mistaken_plans(variant.exercise, "no_coriolis", motion=motion)
    for label in ("b@lever", "c"):
        x, y = redrawn.acceleration.points_mm[label]
        assert _candidates(key, "acceleration", label, "no_coriolis") == [
            (round(x, 2), round(y, 2))]
    # the reversed Coriolis component puts b₃ on the other side
    assert _candidates(key, "acceleration", "b@lever", "coriolis_reversed")


def test_listed_positions_are_told_apart_from_the_right_point_and_the_pole(slotted,
                                                                           compressor):
    for key, _ in (slotted, compressor):
        for plan in ("velocity", "acceleration"):
            entry = key["plans"][plan]
            assert set(entry["mistake_points"]) <= set(drawn_labels(entry))
            for label, found in entry["mistake_points"].items():
                right_x, right_y = entry["points_mm"][label]
                radius = entry["tolerance_mm"][label]
                for mistake, x, y in found:
                    assert mistake in REGISTRY
                    assert math.hypot(x - right_x, y - right_y) > radius
                    assert math.hypot(x, y) > radius
                    assert (round(x, 2), round(y, 2)) == (x, y)


def test_relative_for_absolute_and_a_wrong_scale_are_placed_from_the_right_plan(compressor):
    key, _ = compressor
    points = _points(key, "velocity")
    (c_x, c_y), (b_x, b_y) = points["c"], points["b"]
    # v_CB laid off from the pole: c − b
    assert (round(c_x - b_x, 2), round(c_y - b_y, 2)) in _candidates(
        key, "velocity", "c", "relative_for_absolute")
    # a scale misread ten times too large: every length ten times too short
    assert _candidates(key, "velocity", "c", "scale_ten") == [
        (round(c_x / 10, 2), round(c_y / 10, 2))]
    # with the drive's scale applied twice (v_B/μv²) the plan is 1/μv times too long
    mu_v = key["scales"]["mu_v"]
    assert _candidates(key, "velocity", "b", "scale_twice") == [
        (round(b_x / mu_v, 2), round(b_y / mu_v, 2))]


def test_named_mistakes_is_the_one_comparison():
    candidates = [["no_coriolis", 1.0, 1.0], ["scale_ten", 1.2, 1.0], ["no_coriolis", 1.0, 1.1]]
    assert named_mistakes(candidates, 1.05, 1.0, 0.2) == ["no_coriolis", "scale_ten"]
    assert named_mistakes(candidates, 5.0, 5.0, 0.2) == []


def test_grade_drawing_names_the_mistake_a_misplaced_point_lies_at(slotted):
    key, _ = slotted
    points = _points(key, "acceleration")
    points["b@lever"] = _candidates(key, "acceleration", "b@lever", "no_coriolis")[0]
    result = grade_drawing(key, Drawing(points, "acceleration")).as_dict()
    verdicts = {p["point"]: p for p in result["points"]}
    assert not verdicts["b@lever"]["correct"]
    assert verdicts["b@lever"]["mistakes"] == ["no_coriolis"]
    assert render(MISTAKES["no_coriolis"]) in verdicts["b@lever"]["feedback"]
    assert "Coriolis" in verdicts["b@lever"]["feedback"]
    assert verdicts["c"]["correct"] and "mistakes" not in verdicts["c"]


def test_a_velocity_plan_turned_180_degrees_names_the_reversed_sense_on_every_point(slotted):
    key, _ = slotted
    right = _points(key, "velocity")
    pole = key["plans"]["velocity"]["pole"]
    turned = {label: (-x, -y) for label, (x, y) in right.items()}
    result = grade_drawing(key, Drawing(turned, "velocity")).as_dict()
    wrong = [p for p in result["points"] if p["point"] != pole and not p["correct"]]
    assert wrong and all(p["mistakes"] == ["sense"] for p in wrong), wrong
    assert all("turned 180°" in p["feedback"] for p in wrong)


def test_the_page_frame_refers_to_mistakes_by_their_registry_index(slotted):
    key, _ = slotted
    frame = drawing_frame(key)["acceleration"]
    assert frame["required"] == ["b", "b@lever", "c"]
    assert set(frame["points"]) == {"b", "k_B@lever", "n_B@lever", "b@lever", "c"}
    for label, (x, y, radius) in frame["points"].items():
        right = key["plans"]["acceleration"]["points_mm"][label]
        assert (x, y) == pytest.approx(right, abs=5e-4)
        assert radius == pytest.approx(key["plans"]["acceleration"]["tolerance_mm"][label],
                                       abs=5e-4)
    listed = {(DRAWN_MISTAKES[index], x, y)
              for index, x, y in frame["mistakes"]["b@lever"]}
    assert listed == {tuple(entry) for entry in
                      key["plans"]["acceleration"]["mistake_points"]["b@lever"]}


def _page_drawing(key, plan, points, **changes) -> dict:
    from planmethod.grading.drawings import exercise_digest
    from planmethod.grading.keys import key_exercise

    drawing = {"format": "planmethod-drawing", "version": 1, "title": key["title"],
               "exercise": exercise_digest(key_exercise(key)), "angle": key["angle"],
               "plan": plan,
               "points": {key["plans"][plan]["pole"]: [0, 0], **points}, "lines": []}
    drawing.update(changes)
    return drawing


def test_a_page_drawing_is_graded_at_its_own_scale(compressor):
    """A drawing made on the page's millimetre grid is never rescaled: a plan drawn ten
    times too small is wrong, each point named with the wrong scale."""
    key, _ = compressor
    small = {label: [x / 10, y / 10] for label, (x, y) in _points(key, "velocity").items()
             if label in drawn_labels(key["plans"]["velocity"])}
    drawing = parse_drawing_json(json.dumps(_page_drawing(key, "velocity", small)))
    assert drawing.title == key["title"] and drawing.angle == key["angle"]
    result = grade_drawing(key, drawing).as_dict()
    assert result["scale_factor"] == 1.0 and result["score"] == 0
    for point in result["points"]:
        assert point["mistakes"] == ["scale_ten"], point
        assert "wrong scale" in point["feedback"]
    # the same points without the page's format: an editor's unit slip, scaled back
    plain = parse_drawing_json(json.dumps({"plan": "velocity",
                                           "points": {"p": [0, 0], **small}}))
    assert grade_drawing(key, plain).score == grade_drawing(key, plain).max_score


@pytest.mark.parametrize(("changes", "words"), [
    ({"exercise": "0123456789abcdef"}, "the drawing was made on the page of another version "
                                       "of 'Crank and slotted lever' (exercise digest "
                                       "0123456789abcdef, the key's exercise "),
    ({"title": "Another mechanism"}, "the drawing is of 'Another mechanism', the key of "
                                     "'Crank and slotted lever'"),
])
def test_grade_drawing_refuses_a_page_drawing_of_another_exercise_in_one_line(
        tmp_path, capsys, slotted, changes, words):
    key, _ = slotted
    path = tmp_path / "drawing.json"
    points = {label: list(xy) for label, xy in _points(key, "velocity").items()}
    path.write_text(json.dumps(_page_drawing(key, "velocity", points, **changes)))
    code = main(["grade", str(ROOT / SLOTTED), "--drawing", str(path)])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("planmethod: error: ")
    assert words in err


@pytest.mark.parametrize(("changes", "key_name"), [
    ({"angle": "thirty"}, "angle"), ({"angle": float("inf")}, "angle"), ({"title": 7}, "title"),
    ({"exercise": 7}, "exercise"), ({"exercise": "not a digest"}, "exercise"),
])
def test_a_page_drawing_with_a_bad_title_or_angle_names_the_key(tmp_path, capsys, slotted,
                                                                changes, key_name):
    key, _ = slotted
    path = tmp_path / "drawing.json"
    text = json.dumps(_page_drawing(key, "velocity", {"b": [1, 2]}, **changes))
    path.write_text(text.replace("Infinity", "1e999"))
    code = main(["grade", str(ROOT / SLOTTED), "--drawing", str(path)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and f": {key_name}: " in err


def test_every_drawn_mistake_has_what_the_student_is_told():
    from planmethod.grading.mistakes import drawn_explanation

    for mistake in DRAWN_MISTAKES:
        assert render(drawn_explanation(mistake))
    assert "turned 180°" in render(drawn_explanation("sense"))
    assert "wrong scale" in render(drawn_explanation("scale_none"))


@pytest.mark.parametrize(("path", "offered", "not_offered"), [
    (COMPRESSOR, {"b", "n_CB", "c", "d", "n_D"}, {"k_C", "c@frame"}),   # slider on the frame
    ("exercises/shaper_sixbar.toml", {"k_B@lever", "b@lever"}, {"k_D", "d@frame"}),
    ("exercises/scotch_yoke.toml", {"b@yoke"}, {"k1_B@yoke", "k2_B@yoke", "b@frame"}),
])
def test_the_page_offers_only_the_points_the_construction_draws(path, offered, not_offered):
    """A Coriolis point whose term is zero (it coincides with the point it would be laid off
    from) and a frame point's image at the pole are neither drawn nor named: a student is
    not asked to place them."""
    key, _ = _key_and_variant(path)
    labels = set(drawing_frame(key)["acceleration"]["points"])
    assert offered <= labels and not labels & not_offered, labels


def test_one_misplaced_point_is_no_whole_plan_mistake(slotted):
    """c alone 3 mm off at 45° lies where no mistake puts it: neither its verdict nor the
    plan's names one (grade --drawing once said the wrong points 'fit the plan drawn when
    the normal component aⁿ was left out', judged at twice the tolerance, which the page
    never said); a plan drawn wholly without the Coriolis term is named so, point by point
    and as a whole, by the rule the page applies (common_mistakes)."""
    from planmethod.grading.plan_points import common_mistakes, plan_sentence

    key, _ = slotted
    points = _points(key, "acceleration")
    x, y = points["c"]
    points["c"] = (x + 3 * math.cos(math.pi / 4), y + 3 * math.sin(math.pi / 4))
    result = grade_drawing(key, Drawing(points, "acceleration", exact_scale=True)).as_dict()
    assert [p["point"] for p in result["points"] if not p["correct"]] == ["c"]
    assert result["feedback"] == [] and result["plan_mistakes"] == []
    entry = key["plans"]["acceleration"]
    wrong = {label: tuple(xy) for label, xy in entry["mistakes"]["no_coriolis"].items()
             if label in drawn_labels(entry) or label == entry["pole"]}
    result = grade_drawing(key, Drawing(wrong, "acceleration", exact_scale=True)).as_dict()
    named = [p["mistakes"] for p in result["points"] if not p["correct"]]
    assert len(named) >= 2 and common_mistakes(named) == ["no_coriolis"]
    assert result["plan_mistakes"] == ["no_coriolis"]
    assert result["feedback"] == [render(plan_sentence(["no_coriolis"]))]


def test_a_page_drawing_at_another_angle_is_graded_at_that_angle(tmp_path, capsys, slotted):
    """A drawing made on the page at 45° (the exercise's drive.angle is 30°) is graded
    against the key of 45° — the assembly chosen at 30° followed there, as solve --angle
    and the page pose it — from the exercise file and from its key.json alike; the same
    drawing said to be of 30° is wrong point by point."""
    from planmethod.grading.drawings import key_at_angle

    key, _ = slotted
    at45 = key_at_angle(key, 45.0)
    assert at45["angle"] == 45.0 and at45["title"] == key["title"]
    points = {label: list(xy) for label, xy in _points(at45, "acceleration").items()
              if label in drawn_labels(at45["plans"]["acceleration"])}
    path = tmp_path / "drawing.json"
    path.write_text(json.dumps(_page_drawing(at45, "acceleration", points)))
    (tmp_path / "key.json").write_text(json.dumps(key))
    for graded_against in (ROOT / SLOTTED, tmp_path / "key.json"):
        code = main(["grade", str(graded_against), "--drawing", str(path), "--json",
                     str(tmp_path / "graded.json")])
        assert code == 0, capsys.readouterr().err
        graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
        assert graded["max_score"] == 3 and graded["score"] == 3, graded
    path.write_text(json.dumps(_page_drawing(key, "acceleration", points)))
    assert main(["grade", str(ROOT / SLOTTED), "--drawing", str(path), "--json",
                 str(tmp_path / "graded.json")]) == 0
    assert json.loads((tmp_path / "graded.json").read_text())["drawings"][0]["score"] == 0
    capsys.readouterr()


def test_the_page_frame_of_a_small_plan_whole():
    """A plan's frame for the workbook page: its pole, scale (6 digits) and unit; every point a
    student places (not the pole, not a fixed point at it) with its disc, as the key has them
    (grade --drawing compares the same numbers), never −0.0; those scored, and the helpers
    checked when placed; the mistakes' positions by registry index; what grade --drawing's
    sentences tell of a point (the lines of an intersection, the step that places each point,
    the readings off a length that is not zero, the other points these name); no acceleration
    plan, no entry."""
    from math import copysign

    from planmethod.grading.plan_points import DRAWN_MISTAKES, drawing_frame

    key = {"plans": {"velocity": {
        "pole": "p", "scale": 0.123456789, "unit": "(m/s)/mm",
        "points_mm": {"p": [0, 0], "a": [0, 0], "b": [10.00049, -0.0], "c": [-0.0001, -20.0],
                      "n_CB": [1.0, 1.0]},
        "tolerance_mm": {"p": 0.0, "a": 0.25, "b": 0.25, "c": 0.7549, "n_CB": 0.3},
        "steps": [{"action": "coincide", "start": "p", "end": "a"},
                  {"number": 1, "action": "lay_off", "start": "p", "end": "b",
                   "length_mm": 10.0, "direction_deg": 0.0},
                  {"number": 2, "action": "line", "start": "b", "direction_deg": 90.0,
                   "text": "through b: v_CB ⟂ CB"},
                  {"number": 3, "action": "line", "start": "a", "direction_deg": 0.0,
                   "text": "through a: v_C ∥ guide"},
                  {"number": 4, "action": "intersect", "end": "c", "lines": [2, 3]},
                  {"number": 5, "action": "read", "quantity": "v_C", "start": "p", "end": "c",
                   "length_mm": 20.0},
                  {"number": 6, "action": "read", "quantity": "v_B", "start": "p", "end": "b",
                   "length_mm": 1e-15}],
        "mistake_points": {"c": [["sense", 0.0, 20.0], ["scale_ten", 0.0, -2.0]], "b": []}}},
        "questions": [{"id": "v_C"}, {"id": "v_B"}]}
    frame = drawing_frame(key)
    sense, ten = DRAWN_MISTAKES.index("sense"), DRAWN_MISTAKES.index("scale_ten")
    assert frame == {"velocity": {
        "pole": "p", "scale": "0.123457", "unit": "(m/s)/mm",
        "points": {"b": [10.00049, 0.0, 0.25], "c": [-0.0001, -20.0, 0.7549],
                   "n_CB": [1.0, 1.0, 0.3]},
        "required": ["b", "c"], "helpers": ["n_CB"],
        "mistakes": {"c": [[sense, 0.0, 20.0], [ten, 0.0, -2.0]]},
        "lines": {"c": [["b", 90.0, "v_CB ⟂ CB"], ["a", 0.0, "v_C ∥ guide"]]},
        "placed": {"b": ["lay_off", "p", 10.0, 0.0], "c": ["intersect"]},
        "reads": [["v_C", "p", "c", 20.0]], "others": {"a": [0.0, 0.0], "p": [0.0, 0.0]}}}
    assert copysign(1.0, frame["velocity"]["points"]["b"][1]) == 1.0


def test_the_sheet_of_a_turn_holds_every_frames_plan_and_the_pole():
    """(left, bottom, right, top): the extreme points of all frames and the pole, widened by
    the margin (15 mm by default) and rounded out to 10 mm."""
    from planmethod.grading.plan_points import plan_extent

    frames = [{"velocity": {"points": {"b": [12.0, -3.0, 0.5]}}},
              {"velocity": {"points": {"b": [31.0, 4.0, 0.5], "c": [-6.0, 22.0, 0.5]}}},
              {"acceleration": {"points": {"b": [99.0, 99.0, 0.5]}}}, {}]
    assert plan_extent(frames, "velocity") == (-30.0, -20.0, 50.0, 40.0)
    assert plan_extent(frames, "velocity", margin=0.0) == (-10.0, -10.0, 40.0, 30.0)
    assert plan_extent([{"velocity": {"points": {"b": [-41.0, -52.0, 0.5]}}}], "velocity",
                       margin=5.0) == (-50.0, -60.0, 10.0, 10.0)
    assert plan_extent([], "velocity") == (-20.0, -20.0, 20.0, 20.0)


def test_the_points_scored_on_a_plan_are_the_images_off_the_pole():
    from planmethod.grading.plan_points import graded_labels

    plan = {"pole": "π", "points_mm": {"π": [0, 0], "b": [0, 30], "n_CB": [1, 2],
                                       "c@frame": [0, 0], "d@frame": [3, 4], "a": [0, 0],
                                       "e": [5e-10, 0.0], "f": [2e-9, 0.0], "p": [5, 5]}}
    assert graded_labels(plan) == ["b", "f", "p"]


def test_a_plan_drawn_at_a_wrong_scale_is_its_own_plans_points_scaled():
    """The wrong-scale mistakes place each point of a plan at its right place times that
    plan's own scale factor: without the scale (× μ), the scale applied twice (÷ μ) — μv on
    the velocity plan, μa on the acceleration plan (the compressor: 0.2 and 20)."""
    key = build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))
    for plan, mu in (("velocity", key["scales"]["mu_v"]), ("acceleration", key["scales"]["mu_a"])):
        entry = key["plans"][plan]
        x, y = entry["points_mm"]["c"]
        placed = {mistake: (px, py) for mistake, px, py in entry["mistake_points"]["c"]}
        assert placed["scale_none"] == pytest.approx((round(x * mu, 2), round(y * mu, 2)),
                                                     abs=0.006), plan
        assert placed["scale_twice"] == pytest.approx((round(x / mu, 2), round(y / mu, 2)),
                                                      abs=0.006), plan


def test_a_short_vector_laid_off_is_drawn_and_a_zero_one_is_not():
    """A vector laid off 0.5 mm long is drawn (its end is a point to place); only one of zero
    length (to 1e-9 mm) leaves nothing to draw."""
    entry = {"pole": "π", "points_mm": {"π": [0, 0], "b": [0.5, 0], "k_B": [0.5, 0],
                                        "c": [0.5, 1e-12]},
             "steps": [{"action": "lay_off", "start": "π", "end": "b", "length_mm": 0.5},
                       {"action": "lay_off", "start": "b", "end": "k_B", "length_mm": 1e-10},
                       {"action": "lay_off", "start": "b", "end": "c", "length_mm": 2e-9}]}
    assert drawn_labels(entry) == ["b", "c"]
