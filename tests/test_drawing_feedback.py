"""Drawn plans in detail: every refusal of a submission is one exact line naming the file and
the entry; every SVG path command is read to its end point; labels are normalised; what a
misplaced point is told, word for word; the result's fields; when a drawing is rescaled."""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

from planmethod.grading.drawings import (
    MAX_BYTES,
    Drawing,
    SubmissionError,
    _path_vertices,
    grade_drawing,
    parse_drawing_json,
    parse_drawing_svg,
)
from planmethod.grading.keys import build_key
from planmethod.grading.templates import draw_variant, load_template
from planmethod.words import render


@pytest.fixture(scope="module")
def key():
    return build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))


def _points(key, plan="velocity") -> dict[str, tuple[float, float]]:
    return {label: tuple(xy) for label, xy in key["plans"][plan]["points_mm"].items()}


def _refusal(parse, data) -> str:
    """The one-line refusal of ``data``, which raises no warning on its way (a numpy
    overflow in a student's transform is a refusal, never a RuntimeWarning)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(SubmissionError) as caught:
            parse(data, source="plan.json" if parse is parse_drawing_json else "plan.svg")
    return str(caught.value)


# -- JSON ----------------------------------------------------------------------------------------
@pytest.mark.parametrize(("data", "message"), [
    (b"\xff\xfe{}", "plan.json: not UTF-8 text"),
    ("[1]", 'plan.json: must be an object {"plan": …, "points": {…}}'),
    ('{"plan": "force", "points": {"p": [0, 0]}}',
     "plan.json: plan: plan must be 'velocity' or 'acceleration', got 'force'"),
    ('{"plan": "velocity"}',
     'plan.json: points: no labelled points (give "points": {"p": [0, 0], …})'),
    ('{"points": {}}', 'plan.json: points: no labelled points (give "points": {"p": [0, 0], …})'),
    (json.dumps({"points": {f"q{i}": [0, 0] for i in range(1001)}}),
     "plan.json: points: more than 1000 points"),
    ('{"points": {"p": [0, "x"]}}',
     "plan.json: points.p: must be [x, y] in mm with finite numbers, got [0, 'x']"),
    ('{"points": {"p": [0, 0], "b": [1, 1e999]}}',
     "plan.json: points.b: must be [x, y] in mm with finite numbers, got [1, inf]"),
    ('{"points": {"p": [0, 0, 0]}}',
     "plan.json: points.p: must be [x, y] in mm with finite numbers, got [0, 0, 0]"),
    ('{"format": "planmethod-drawing", "points": {"p": [0, 0]}, "angle": 45}',
     "plan.json: title: must be the exercise's title, got null"),
    ('{"format": "planmethod-drawing", "points": {"p": [0, 0]}, "title": "T", "angle": "45"}',
     "plan.json: angle: must be the crank angle in degrees, within ±36000°, got '45'"),
    ('{"format": "planmethod-drawing", "points": {"p": [0, 0]}, "title": "T", "angle": true}',
     "plan.json: angle: must be the crank angle in degrees, within ±36000°, got true"),
    ('{"format": "planmethod-drawing", "points": {"p": [0, 0]}, "title": "T", "angle": 1e6}',
     "plan.json: angle: must be the crank angle in degrees, within ±36000°, got 1000000.0"),
    ('{"points": {"p": [0, 0], "b": [1, 1e308]}}',
     "plan.json: points.b: is at (1, 1e+308) mm, beyond ±1e+06 mm of the origin: a drawn "
     "plan fits on a sheet"),
    ('{"points": {"p": [0, 0], "c": [1, 2], "c": [3, 4]}}',
     "plan.json: c: the key is given twice in one object"),
    ('{"points": {"p": [0, 0], "c": [1, 2], " c": [3, 4]}}',
     "plan.json: points: point 'c' and point ' c' are one point, labels compared without "
     "spaces, pi for π; keep one"),
    ('{"plan": "acceleration", "points": {"π": [0, 0], "pi": [3, 4]}}',
     "plan.json: points: point 'π' and point 'pi' are one point, labels compared without "
     "spaces, pi for π; keep one"),
    ("{", "plan.json: not valid JSON: Expecting property name enclosed in double quotes: line 1 "
          "column 2 (char 1)"),
])
def test_every_refusal_of_a_json_drawing_is_one_exact_line(data, message):
    assert _refusal(parse_drawing_json, data) == message


def test_a_long_junk_value_is_cut_to_one_short_line():
    for data, where in (({"points": {"b": ["y" * 300, 1]}}, "points.b"),
                        ({"points": {"p": [0, 0]}, "plan": "z" * 300}, "plan"),
                        ({"format": "planmethod-drawing", "points": {"p": [0, 0]},
                          "title": ["t" * 300], "angle": 0}, "title")):
        message = _refusal(parse_drawing_json, json.dumps(data))
        prefix = f"plan.json: {where}: "
        assert message.startswith(prefix) and len(message) <= len(prefix) + 120
        assert message.endswith("…")      # the value is cut, and says so


def test_a_json_drawing_is_read_up_to_its_size_and_point_limits():
    at_most = b" " * (MAX_BYTES - 26) + b'{"points": {"p": [0, 0]}}'
    assert len(at_most) == MAX_BYTES - 1
    assert parse_drawing_json(at_most + b" ", source="x").points == {"p": (0.0, 0.0)}
    assert _refusal(parse_drawing_json, at_most + b"  ") == \
        f"plan.json: larger than {MAX_BYTES} bytes"
    many = {f"q{i}": [i, 0] for i in range(1000)}
    assert len(parse_drawing_json(json.dumps({"points": many})).points) == 1000


def test_a_json_drawing_keeps_its_labels_plan_source_and_page_data():
    drawing = parse_drawing_json(
        '{"plan": "acceleration", "points": {"pi": [1, 2], "plan": [9, 9], "P\'": [3, 4], '
        '" n C B ": [5, 6]}}', source="plan.json")
    assert drawing == Drawing({"π": (1.0, 2.0), "p′": (3.0, 4.0), "nCB": (5.0, 6.0)},
                              "acceleration", (), "plan.json")
    assert parse_drawing_json('{"p": [0, 0], "b": [1, 2]}', source="s.json") == Drawing(
        {"p": (0.0, 0.0), "b": (1.0, 2.0)}, None, (), "s.json")
    page = parse_drawing_json('{"format": "planmethod-drawing", "title": "T", "angle": 45, '
                              '"plan": "velocity", "points": {"p": [0, 0]}}', source="p.json")
    assert page == Drawing({"p": (0.0, 0.0)}, "velocity", (), "p.json", title="T", angle=45.0,
                           exact_scale=True)


@pytest.mark.parametrize(("text", "label"), [
    ("pi", "π"), ("PI", "π"), ("Pi", "π"), ("p'", "p′"), ("P'", "p′"), (" n C B ", "nCB"),
    ("b", "b"), ("B", "B"),
])
def test_labels_are_normalised_as_a_plan_writes_them(text, label):
    assert list(parse_drawing_json(json.dumps({"points": {text: [1, 2]}})).points) == [label]


# -- SVG -----------------------------------------------------------------------------------------
def test_every_path_command_is_read_to_its_end_point():
    budget = [10 ** 6]
    assert _path_vertices("M 10 20 L 30 40 H 50 V 60 C 1 2 3 4 70 80 S 5 6 90 100 "
                          "Q 7 8 110 120 T 130 140 A 5 5 0 0 1 150 160 Z", budget) == [
        (10, 20), (30, 40), (50, 40), (50, 60), (70, 80), (90, 100), (110, 120), (130, 140),
        (150, 160)]
    # relative: each from the last end point; after z the current point is the subpath's start
    assert _path_vertices("m 10 20 l 30 40 h 50 v 60 c 1 2 3 4 70 80 s 5 6 90 100 "
                          "q 7 8 110 120 t 130 140 a 5 5 0 0 1 150 160 z m 1 1 2 2", budget) == [
        (10, 20), (40, 60), (90, 60), (90, 120), (160, 200), (250, 300), (360, 420),
        (490, 560), (640, 720), (11, 21), (13, 23)]
    # numbers after a move-to are line-tos, absolute after M and relative after m
    assert _path_vertices("M 1 2 3 4 5 6 m 1 1 2 2 Z L 0 0", budget) == [
        (1, 2), (3, 4), (5, 6), (6, 7), (8, 9), (0, 0)]
    assert _path_vertices("", budget) == [] and budget == [10 ** 6 - 39 - 44 - 16]  # tokens


def test_a_path_counts_against_the_coordinate_budget():
    budget = [5]
    with pytest.raises(SubmissionError, match="more than 200000 coordinates"):
        _path_vertices("M 1 2 L 3 4", budget)       # 6 tokens, 5 left
    budget = [6]
    assert _path_vertices("M 1 2 L 3 4", budget) == [(1, 2), (3, 4)] and budget == [0]


@pytest.mark.parametrize(("svg", "message"), [
    ("<svg><text x='1e999' y='0'>p</text></svg>",
     "plan.svg: <text> 'p': x='1e999' is not a finite number"),
    ("<svg><circle id='c1' cx='nan' cy='0'/><text>p</text></svg>",
     "plan.svg: <circle id=\"c1\">: cx='nan' is not a finite number"),
    ("<svg><circle id='" + "k" * 60 + "' cx='nan' cy='0'/><text>p</text></svg>",
     "plan.svg: <circle id=\"" + "k" * 40 + "\">: cx='nan' is not a finite number"),
    ("<svg><line x1='inf' y1='0' x2='1' y2='1'/><text>p</text></svg>",
     "plan.svg: <line>: x1='inf' is not a finite number"),
    ("<svg><path d='M 0 0 Z 5'/><text>p</text></svg>", "plan.svg: a path has numbers after Z"),
    ("<svg><path d='M 0 0 L'/><text>p</text></svg>", "plan.svg: a path's data is incomplete"),
    ("<svg><path d='5 5'/><text>p</text></svg>",
     "plan.svg: a path's data does not start with a command"),
    ("<svg><polyline points='1 2 x 4'/><text>p</text></svg>",
     "plan.svg: <polyline>: points='1 2 x 4' holds something that is not a finite number"),
    ("<svg><g transform='scale(0)'><text>p</text></g></svg>",
     "plan.svg: the transform 'scale(0)' is singular (it flattens the drawing onto a line or a "
     "point)"),
    ("<svg><g transform='translate(1,2) junk'><text>p</text></g></svg>",
     "plan.svg: unreadable transform 'translate(1,2) junk'"),
    ("<html><svg/></html>", "plan.svg: the root element is <html>, not <svg>"),
    ("<svg><g transform='scale(1e200)'><text x='1' y='0'>p</text></g></svg>",
     "plan.svg: the transform 'scale(1e200)' scales the drawing beyond any finite size"),
    ("<svg><g transform='scale(1e150)'><g transform='scale(1e150)'><g transform='scale(1e150)'>"
     "<text x='1' y='0'>p</text></g></g></g></svg>",
     "plan.svg: <text> 'p': a coordinate is not a finite number"),
    ("<svg><g transform='scale(1e150)'><text x='1e200' y='0'>p</text></g></svg>",
     "plan.svg: <text> 'p': a coordinate is not a finite number"),
    # an entry overflowed to inf, then times a 0 of the next step: nan, and no warning
    ("<svg><g transform='matrix(1e200 0 0 1e-200 0 0) matrix(1e200 0 0 1e-200 0 0) "
     "translate(0)'><text x='1' y='0'>p</text></g></svg>",
     "plan.svg: <text> 'p': a coordinate is not a finite number"),
    ("<svg width='-3mm' viewBox='0 0 10 10'><text>p</text></svg>",
     "plan.svg: the drawing's width is '-3mm': a drawing has a positive size"),
    ("<svg width='10mm' height='0' viewBox='0 0 10 10'><text>p</text></svg>",
     "plan.svg: the drawing's height is '0': a drawing has a positive size"),
    ("<svg viewBox='0 0 0 10'><text>p</text></svg>",
     "plan.svg: the viewBox '0 0 0 10' has no positive, finite size"),
    ("<svg><rect/></svg>", "plan.svg: no labelled points: label the plan's points with text (p "
                           "or π for the pole, b, c, …) next to them"),
])
def test_every_refusal_of_an_svg_drawing_is_one_exact_line(svg, message):
    assert _refusal(parse_drawing_svg, svg) == message


def test_an_svg_drawing_is_read_up_to_its_size_limit():
    svg = b"<svg><text>p</text></svg>"
    assert _refusal(parse_drawing_svg, svg + b" " * (MAX_BYTES - len(svg) + 1)) == \
        f"plan.svg: larger than {MAX_BYTES} bytes"
    assert parse_drawing_svg(svg + b" " * (MAX_BYTES - len(svg)), source="x").points


# -- grading: the exercise, the pole, the result -------------------------------------------------
def test_a_drawing_of_the_same_angle_a_turn_later_is_of_the_same_exercise(key):
    points = _points(key)
    title, angle = key["title"], key["angle"]
    for turned in (angle + 360.0, angle - 720.0, angle + 1e-9):
        drawing = Drawing(points, "velocity", title=title, angle=turned, exact_scale=True)
        assert grade_drawing(key, drawing).as_dict()["score"] == 3
    for other, says in ((Drawing(points, "velocity", source="d.json", title=title,
                                 angle=angle + 0.5, exact_scale=True),
                         f"d.json: the drawing is of {title!r} at φ₁ = {angle + 0.5:g}°, the "
                         f"key of {title!r} at φ₁ = {angle:g}°: grade it against the key of its "
                         "own exercise and angle"),
                        (Drawing(points, "velocity", source="d.json", title="Other",
                                 angle=angle, exact_scale=True),
                         f"d.json: the drawing is of 'Other' at φ₁ = {angle:g}°, the key of "
                         f"{title!r} at φ₁ = {angle:g}°: grade it against the key of its own "
                         "exercise and angle")):
        with pytest.raises(SubmissionError) as caught:
            grade_drawing(key, other)
        assert str(caught.value) == says


def test_the_plan_and_the_pole_are_required_in_one_exact_line(key):
    cases = [(Drawing({"b": (1.0, 2.0)}, None, source="d.svg"), None,
              "d.svg: cannot tell which plan this is: label the pole p (velocity) or π "
              "(acceleration), or say which"),
             (Drawing({"b": (1.0, 2.0)}, "velocity", source="d.svg"), None,
              "d.svg: no pole labelled p: cannot align the plan"),
             (Drawing({"b": (1.0, 2.0)}, "acceleration", source="d.svg"), None,
              "d.svg: no pole labelled π: cannot align the plan")]
    velocity_only = dict(key, plans={"velocity": key["plans"]["velocity"]})
    for drawing, _, message in cases:
        with pytest.raises(SubmissionError) as caught:
            grade_drawing(key, drawing)
        assert str(caught.value) == message
    with pytest.raises(SubmissionError) as caught:
        grade_drawing(velocity_only, Drawing({"π": (0.0, 0.0)}, "acceleration", source="d.svg"))
    assert str(caught.value) == "d.svg: the key has no acceleration plan"


def test_an_acceleration_plan_with_its_pole_labelled_p_or_its_points_in_capitals(key):
    shifted = {("p" if label == "π" else label.upper()): (x + 5.0, y - 7.0)
               for label, (x, y) in _points(key, "acceleration").items()}
    result = grade_drawing(key, Drawing(shifted, "acceleration")).as_dict()
    assert result["score"] == result["max_score"] == 3


def test_the_result_of_a_drawing_field_by_field(key):
    points = {label: xy for label, xy in _points(key).items() if label != "d"}
    result = grade_drawing(key, Drawing(points, "velocity")).as_dict()
    radius = key["plans"]["velocity"]["tolerance_mm"]
    assert result == {
        "plan": "velocity", "student": key["student"], "score": 2.0, "max_score": 3.0,
        "scale_factor": 1.0, "plan_mistakes": [], "feedback": [], "revealed": [],
        "points": [{"point": label, "found": True, "correct": True, "distance_mm": 0.0,
                    "tolerance_mm": radius[label], "score": 1.0, "max_score": 1.0,
                    "feedback": f"{label}: within {radius[label]:.2g} mm (0 mm off)",
                    "name": label} for label in ("b", "c")]
        + [{"point": "d", "found": False, "correct": False, "score": 0.0, "max_score": 1.0,
            "feedback": "d: not found on the drawing", "name": "d"}]}


def test_a_helper_point_is_checked_when_drawn_and_never_scored(key):
    points = _points(key, "acceleration")
    x, y = points["n_CB"]
    points["n_CB"] = (x + 5.0, y)
    checked = {p["point"]: p for p in grade_drawing(key, Drawing(points, "acceleration")).as_dict()[
        "points"]}["n_CB"]
    assert not checked["correct"] and checked["score"] == checked["max_score"] == 0.0
    del points["n_CB"]
    assert "n_CB" not in {p["point"] for p in grade_drawing(
        key, Drawing(points, "acceleration")).as_dict()["points"]}


# -- what a misplaced point is told --------------------------------------------------------------
def _told(key, label, move, plan="velocity", **options) -> str:
    points = _points(key, plan)
    points[label] = tuple(np.asarray(points[label]) + np.asarray(move))
    result = grade_drawing(key, Drawing(points, plan), **options).as_dict()
    return next(p["feedback"] for p in result["points"] if p["point"] == label)


def test_a_point_placed_by_the_similarity_rule_is_told_so(key):
    assert _told(key, "d", (3.0, 0.0)) == ("d is 3.0 mm off (tolerance 0.62 mm) (placed by the "
                                           "similarity rule from b): v_D read 10 % low")


def test_a_laid_off_point_is_told_its_length_and_direction(key):
    b = np.asarray(_points(key)["b"])
    assert _told(key, "b", b * (32 / 30) - b, rescale=False) == (
        "b is 2.0 mm off (tolerance 0.25 mm): (pb) should be 30.0 mm at 135°, it is 32.0 mm: "
        "ω₂ read 5 % high")


def test_an_intersection_is_told_how_far_it_is_off_each_line(key):
    assert _told(key, "c", (0.0, 3.0)) == (
        "c is 3.0 mm off: it is 0.7 mm off the line v_CB ⟂ CB through b; it is 3.0 mm off the "
        "line v_CC₀ along the guide of pair 3–0 through c₀: ω₂ read 13 % low, v_C read 1 % high")
    # on the first line, off along it: the line's own words, and off the second one
    angle = math.radians(76.3669777746336)
    assert _told(key, "c", (2.0 * math.cos(angle), 2.0 * math.sin(angle))).startswith(
        "c is 2.0 mm off: it lies on the line v_CB ⟂ CB through b but 2.0 mm off along it; it is "
        "1.9 mm off the line v_CC₀")


def test_an_intersection_is_measured_from_the_lines_through_the_students_own_points(key):
    """b drawn 2 mm off and c on the line ⟂ CB through that b: c is told it lies on the
    line through (the student's) b, off along it — not off the line through the right b."""
    points = _points(key)
    for label in ("b", "c"):
        points[label] = tuple(np.asarray(points[label]) + np.array([0.0, 2.0]))
    result = grade_drawing(key, Drawing(points, "velocity"), rescale=False).as_dict()
    told = next(p["feedback"] for p in result["points"] if p["point"] == "c")
    assert told.startswith("c is 2.0 mm off: it lies on the line v_CB ⟂ CB through b but "), told


def test_a_reading_changed_by_less_than_half_a_percent_is_not_named(key):
    """c moved 1 mm across pc (out of its disc) and along it so that |pc| is 0.49 % or 0.51 %
    long: v_C is named as read high only in the second case."""
    c = np.asarray(_points(key)["c"])
    length = float(np.hypot(*c))
    for change, named in ((0.0049, False), (0.0051, True)):
        along = math.sqrt((length * (1 + change)) ** 2 - 1.0) / length - 1.0
        told = _told(key, "c", c * along + np.array([0.0, 1.0]))
        assert told.startswith("c is 1.0 mm off")
        assert ("v_C read 1 % high" in told) is named, change


# -- rescaling a drawing drawn at another scale --------------------------------------------------
def test_a_drawing_is_rescaled_only_beyond_two_percent_of_its_first_vector(key):
    """The first laid-off vector (pb) off by 1.9 % is a drafting error, graded as drawn; by
    2.1 % it is an editor's change of units: the drawing is scaled back, and told so."""
    for factor, rescaled in ((1.019, False), (1.021, True), (0.979, True), (0.981, False)):
        drawn = {label: (x * factor, y * factor) for label, (x, y) in _points(key).items()}
        result = grade_drawing(key, Drawing(drawn, "velocity")).as_dict()
        assert (result["scale_factor"] != 1.0) is rescaled, factor
        if rescaled:
            assert result["scale_factor"] == pytest.approx(1 / factor)
            assert result["score"] == 3
            assert result["feedback"] == [
                f"the drawing's scale is off: (pb) measures {30 * factor:.1f} mm instead of "
                f"30.0 mm; it was graded after scaling by {1 / factor:.4g}"]
        else:
            assert result["feedback"] == []


# -- SVG: transforms, units, what marks a point --------------------------------------------------
def _svg(inner: str, root: str = 'width="100mm" height="100mm" viewBox="0 0 100 100"',
         pole: str = '<text x="0" y="0">p</text>') -> str:
    return f'<svg xmlns="http://www.w3.org/2000/svg" {root}>{pole}{inner}</svg>'


@pytest.mark.parametrize(("transform", "local", "mm"), [
    ("translate(5,7)", (10, 0), (15, -7)), ("translate(5)", (10, 0), (15, 0)),
    ("scale(2)", (10, 0), (20, 0)), ("scale(2,3)", (10, 10), (20, -30)),
    ("rotate(90)", (10, 0), (0, -10)), ("rotate(90, 10, 10)", (10, 0), (20, -10)),
    ("skewX(45)", (10, 10), (20, -10)), ("skewY(45)", (10, 0), (10, -10)),
    ("matrix(1,2,3,4,5,6)", (10, 0), (15, -26)),
    ("translate(100,0) scale(2)", (10, 0), (120, 0)),
    ("translate(100 0), scale(2)", (10, 0), (120, 0)),
])
def test_every_svg_transform_moves_a_point_as_svg_says(transform, local, mm):
    x, y = local
    drawing = parse_drawing_svg(_svg(f'<g transform="{transform}"><circle cx="{x}" cy="{y}" '
                                     f'r="0.3"/><text x="{x + 0.5}" y="{y + 0.5}">b</text></g>'))
    assert drawing.points["b"] == pytest.approx(mm, abs=1e-12)       # mm, y up


@pytest.mark.parametrize(("root", "mm"), [
    ('width="10cm" height="10cm" viewBox="0 0 100 100"', (10, -10)),
    ('width="4in" height="4in" viewBox="0 0 101.6 101.6"', (10, -10)),
    ('width="72pt" height="72pt" viewBox="0 0 25.4 25.4"', (10, -10)),
    ('width="6pc" height="6pc" viewBox="0 0 25.4 25.4"', (10, -10)),
    ('width="96px" height="96px" viewBox="0 0 25.4 25.4"', (10, -10)),
    ('width="96" height="96" viewBox="0 0 25.4 25.4"', (10, -10)),
    ('width="100mm" height="50mm" viewBox="0 0 100 100"', (10, -5)),
    ('width="100mm" viewBox="0 0 100 100"', (10, -10)),
    ("", (10 * 25.4 / 96, -10 * 25.4 / 96)), ('width="100mm"', (10 * 25.4 / 96, -10 * 25.4 / 96)),
])
def test_the_root_size_and_view_box_fix_the_millimetre(root, mm):
    drawing = parse_drawing_svg(_svg('<circle cx="10" cy="10" r="0.3"/><text x="10" y="10">b'
                                     "</text>", root))
    assert drawing.points["b"] == pytest.approx(mm, rel=1e-12)


def test_what_marks_a_point_and_what_is_passed_over():
    """A label marks the nearest drawn point within 8 mm — a line's end, a polyline's or
    polygon's vertex, an ellipse's centre, a path's end point — or else its own anchor (a
    tspan's when the text has none); of two labels alike the first gives the point, and both
    are kept with their places (grading refuses a graded point marked at two places); labels
    longer than 12 characters, definitions and metadata are passed over, scripts and other
    outside content are ignored and said to be."""
    drawing = parse_drawing_svg(_svg(
        '<line x1="30" y1="0" x2="40" y2="5"/><text x="41" y="6">b</text>'
        '<polyline points="50,0 60,10 70,0"/><text x="61" y="11">c</text>'
        '<polygon points="0,50 10,60"/><text x="11" y="61">d</text>'
        '<ellipse cx="80" cy="80" rx="2" ry="1"/><text x="81" y="81">e</text>'
        '<path d="M 20 90 L 25 95"/><text x="26" y="96">f</text>'
        '<text x="0" y="30">g</text><text x="0" y="40">far too long a label</text>'
        '<text><tspan x="12" y="30">h</tspan></text><text x="31" y="1">b</text>'
        '<defs><circle cx="0" cy="20"/></defs><text x="1" y="21">k</text>'
        "<script>x</script><image/><use/><style/><a/><iframe/><foreignObject/>"
        + "".join(f'<{tag}><circle cx="0" cy="30"/><text x="5" y="5">q</text></{tag}>'
                  for tag in ("metadata", "title", "desc", "clipPath", "mask", "marker",
                              "pattern", "symbol"))), source="plan.svg")
    assert replace(drawing, notes=tuple(render(note) for note in drawing.notes)) == Drawing(
        {"p": (0.0, 0.0), "b": (40.0, -5.0), "c": (60.0, -10.0), "d": (10.0, -60.0),
         "e": (80.0, -80.0), "f": (25.0, -95.0), "g": (0.0, -30.0), "h": (12.0, -30.0),
         "k": (1.0, -21.0)}, "velocity",
        ("<a> ignored", "<foreignObject> ignored", "<iframe> ignored", "<image> ignored",
         "<script> ignored", "<style> ignored", "<use> ignored"), "plan.svg",
        labels=(("p", "p", (0.0, 0.0)), ("b", "b", (40.0, -5.0)), ("c", "c", (60.0, -10.0)),
                ("d", "d", (10.0, -60.0)), ("e", "e", (80.0, -80.0)), ("f", "f", (25.0, -95.0)),
                ("g", "g", (0.0, -30.0)), ("h", "h", (12.0, -30.0)), ("b", "b", (30.0, 0.0)),
                ("k", "k", (1.0, -21.0))))


@pytest.mark.parametrize(("svg", "plan"), [
    (_svg("", pole='<text x="0" y="0">π</text>'), "acceleration"),
    (_svg("", pole='<text x="0" y="0">pi</text>'), "acceleration"),
    (_svg("", pole='<text x="0" y="0">p</text>'), "velocity"),
    (_svg("", pole='<text x="0" y="0">π</text><text x="5" y="5">p</text>'), None),
    ('<svg><text>b</text></svg>', None),
    ('<svg data-planmethod-plan="acceleration"><text>p</text></svg>', "acceleration"),
])
def test_the_plan_is_told_by_its_pole_or_said(svg, plan):
    assert parse_drawing_svg(svg).plan == plan


def test_a_label_marks_a_drawn_point_up_to_8_mm_away_and_has_up_to_12_characters():
    for dx, snapped in ((7.99, True), (8.01, False)):
        drawing = parse_drawing_svg(_svg(f'<circle cx="20" cy="20"/><text x="{20 + dx}" '
                                         'y="20">b</text>'))
        assert drawing.points["b"] == ((20.0, -20.0) if snapped else (20 + dx, -20.0))
    for label, read in (("b" * 12, True), ("b" * 13, False)):
        assert (label in parse_drawing_svg(_svg(f"<text>{label}</text>")).points) is read


def test_an_svg_is_read_up_to_its_element_and_depth_limits():
    from planmethod.grading.drawings import MAX_DEPTH, MAX_ELEMENTS

    def nested(depth):       # the root and the text at depth 0 and 1; groups to ``depth``
        return ("<svg>" + "<g>" * (depth - 1) + "<text>p</text>" + "</g>" * (depth - 1)
                + "</svg>")

    assert parse_drawing_svg(nested(MAX_DEPTH)).points == {"p": (0.0, 0.0)}
    assert _refusal(parse_drawing_svg, nested(MAX_DEPTH + 1)) == \
        f"plan.svg: elements nested deeper than {MAX_DEPTH}"

    def many(count):         # the root, the text and circles: ``count`` elements in all
        return "<svg><text>p</text>" + "<circle/>" * (count - 2) + "</svg>"

    assert parse_drawing_svg(many(MAX_ELEMENTS)).points == {"p": (0.0, 0.0)}
    assert _refusal(parse_drawing_svg, many(MAX_ELEMENTS + 1)) == \
        f"plan.svg: more than {MAX_ELEMENTS} elements"
