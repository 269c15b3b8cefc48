"""Drawn plans: reading SVG (any editor, planmethod's blank sheet) and JSON, alignment at the
pole, tolerance discs, explanations of what is off, and junk submissions rejected cleanly."""

from __future__ import annotations

import json
import math
import re
import time
from pathlib import Path

import numpy as np
import pytest

from planmethod.grading.drawings import (
    MAX_BYTES,
    Drawing,
    SubmissionError,
    grade_drawing,
    parse_drawing_svg,
    read_drawing,
)
from planmethod.grading.keys import build_key
from planmethod.grading.sheets import plan_sheet_for_key
from planmethod.grading.templates import draw_variant, load_template
from planmethod.words import render

DATA = Path(__file__).parent / "data" / "grading"


@pytest.fixture(scope="module")
def key():
    return build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))


def key_points(key, plan="velocity"):
    return {k: tuple(v) for k, v in key["plans"][plan]["points_mm"].items()}


def by_point(result):
    return {p["point"]: p for p in result["points"]}


def test_exact_points_score_full_marks(key):
    for plan in ("velocity", "acceleration"):
        result = grade_drawing(key, Drawing(key_points(key, plan), plan)).as_dict()
        assert result["score"] == result["max_score"] > 0
    # shifted as a whole: aligned at the pole, still right
    shifted = {k: (x + 37.0, y - 12.0) for k, (x, y) in key_points(key).items()}
    assert grade_drawing(key, Drawing(shifted, "velocity")).as_dict()["score"] == 3


def test_a_point_off_along_its_construction_line_is_explained(key):
    points = dict(key_points(key))
    steps = key["plans"]["velocity"]["steps"]
    line = next(s for s in steps if s["action"] == "line" and s["start"] == "b")
    angle = math.radians(line["direction_deg"])
    direction = np.array([math.cos(angle), math.sin(angle)])
    b, c = np.array(points["b"]), np.array(points["c"])
    sign = 1.0 if float((c - b) @ direction) > 0 else -1.0
    moved = c + sign * 4.0 * direction        # 4 mm further from b along the line ⟂ BC
    points["c"] = tuple(moved)
    result = grade_drawing(key, Drawing(points, "velocity")).as_dict()
    c_result = by_point(result)["c"]
    assert not c_result["correct"] and c_result["distance_mm"] == pytest.approx(4.0)
    feedback = c_result["feedback"]
    assert "c is 4.0 mm off" in feedback
    assert "on the line v_CB ⟂ CB through b but 4.0 mm off along it" in feedback
    expected = 4.0 / float(np.hypot(*(c - b))) * 100
    assert f"ω₂ read {expected:.0f} % high" in feedback      # BC is link 2: its ω₂
    assert "omega_" not in feedback and "@" not in feedback and c_result["name"] == "c"
    assert by_point(result)["b"]["correct"] and result["score"] == 2


def test_a_point_within_its_disc_passes(key):
    points = dict(key_points(key))
    radius = key["plans"]["velocity"]["tolerance_mm"]["d"]
    x, y = points["d"]
    points["d"] = (x + 0.9 * radius, y)
    assert by_point(grade_drawing(key, Drawing(points, "velocity")).as_dict())["d"]["correct"]
    points["d"] = (x + 1.2 * radius, y)
    assert not by_point(grade_drawing(key, Drawing(points, "velocity")).as_dict())["d"]["correct"]


def test_reversed_sense_and_left_out_normal_are_recognised(key):
    turned = {k: (-x, -y) for k, (x, y) in key_points(key).items()}
    result = grade_drawing(key, Drawing(turned, "velocity")).as_dict()
    assert result["score"] < result["max_score"]
    assert any("turned 180°" in line for line in result["feedback"])
    wrong = key["plans"]["acceleration"]["mistakes"]["no_normal"]
    result = grade_drawing(key, Drawing({k: tuple(v) for k, v in wrong.items()},
                                        "acceleration")).as_dict()
    assert any("normal component aⁿ was left out" in line for line in result["feedback"])


def test_missing_points_and_wrong_scale(key):
    points = {k: v for k, v in key_points(key).items() if k != "d"}
    result = grade_drawing(key, Drawing(points, "velocity")).as_dict()
    assert by_point(result)["d"]["feedback"] == "d: not found on the drawing"
    doubled = {k: (2 * x, 2 * y) for k, (x, y) in key_points(key).items()}
    result = grade_drawing(key, Drawing(doubled, "velocity")).as_dict()
    assert result["score"] == result["max_score"] and result["scale_factor"] == 0.5
    assert any("scale is off" in line for line in result["feedback"])
    assert grade_drawing(key, Drawing(doubled, "velocity"), rescale=False).as_dict()["score"] < 3


def test_a_drawing_is_rescaled_only_beyond_its_first_vectors_own_tolerance(key):
    """The first vector laid off (pb) tells an editor's unit mix-up from a drafting error: the
    drawing is rescaled only where pb's length is off by more than pb's own tolerance disc
    (or 2 %, whichever is more). With b's disc at 6 % of pb, a drawing 4 % too large is
    graded as drawn; one 8 % too large is rescaled."""
    import copy

    wide = copy.deepcopy(key)
    right = float(np.hypot(*wide["plans"]["velocity"]["points_mm"]["b"]))
    wide["plans"]["velocity"]["tolerance_mm"]["b"] = 0.06 * right
    for stretch, rescaled in ((1.04, False), (1.08, True)):
        points = {k: (stretch * x, stretch * y) for k, (x, y) in key_points(wide).items()}
        result = grade_drawing(wide, Drawing(points, "velocity")).as_dict()
        assert any("scale is off" in line for line in result["feedback"]) is rescaled, stretch
        assert (result["scale_factor"] == pytest.approx(1 / stretch)) is rescaled


def test_an_editor_svg_with_px_units_groups_and_transforms(key):
    drawing = read_drawing(DATA / "compressor_velocity_inkscape.svg")
    assert drawing.plan == "velocity"
    result = grade_drawing(key, drawing).as_dict()
    assert result["score"] == result["max_score"] == 3, result


def test_the_blank_sheet_filled_in_is_read_back(key):
    sheet = plan_sheet_for_key(key, "acceleration")
    size = float(re.search(r'width="([\d.]+)mm"', sheet).group(1))
    centre_x, centre_y = size / 2, size / 2 + 12
    marks = []
    for label, (x, y) in key_points(key, "acceleration").items():
        if label == "π" or math.hypot(x, y) < 1e-9:
            continue
        X, Y = centre_x + x, centre_y - y
        marks.append(f'<circle cx="{X:.3f}" cy="{Y:.3f}" r="0.4"/>'
                     f'<text x="{X + 1.2:.3f}" y="{Y - 1.2:.3f}">{label}</text>')
    filled = sheet.replace("</svg>", "".join(marks) + "</svg>")
    drawing = parse_drawing_svg(filled)
    assert drawing.plan == "acceleration"
    result = grade_drawing(key, drawing).as_dict()
    assert result["score"] == result["max_score"] > 0
    assert all(p["distance_mm"] < 1e-3 for p in result["points"])   # written to 0.001 mm


def test_json_drawings(tmp_path, key):
    path = tmp_path / "plan.json"
    path.write_text(json.dumps({"plan": "velocity", "points": key_points(key)}))
    assert grade_drawing(key, read_drawing(path)).as_dict()["score"] == 3


@pytest.mark.parametrize(("name", "fragment"), [
    ("junk_entities.svg", "DOCTYPE or ENTITY"),
    ("junk_external.svg", "DOCTYPE or ENTITY"),
    ("junk_malformed.svg", "malformed XML at line 1"),
    ("junk_no_labels.svg", "no labelled points"),
])
def test_junk_svgs_are_rejected_with_one_clear_line(name, fragment):
    with pytest.raises(SubmissionError) as caught:
        read_drawing(DATA / name)
    message = str(caught.value)
    assert fragment in message and name in message and "\n" not in message


def test_scripts_and_foreign_content_are_ignored(key):
    drawing = read_drawing(DATA / "junk_script_with_labels.svg")
    notes = [render(note) for note in drawing.notes]
    assert "<script> ignored" in notes and "<foreignObject> ignored" in notes
    pole = np.array(drawing.points["p"])   # y up: SVG's y is turned
    assert tuple(np.array(drawing.points["b"]) - pole) == pytest.approx(
        (28.787 - 50, 50 - 28.787))       # from the line's end, not the foreign text
    result = grade_drawing(key, drawing).as_dict()
    assert by_point(result)["b"]["correct"]


JUNK = [
    (b"\xff\xfe<\x00s\x00v\x00g\x00", "not UTF-8"),
    (b"just some text", "no <svg> element"),
    (b"<html><body>p</body></html>", "no <svg> element"),
    (b"<svg xmlns='http://www.w3.org/2000/svg'><text>p</text>", "malformed XML"),
    (b"<?xml version='1.0'?><!doctype svg><svg/>", "DOCTYPE"),
    (b"<svg><text x='1e999' y='0'>p</text></svg>", "not a finite number"),
    (b"<svg><g transform='rotate(oops)'><text>p</text></g></svg>", "unreadable transform"),
    (b"<svg><path d='10 10 L 5 5'/><text>p</text></svg>", "does not start with a command"),
    (b"<svg><path d='M 10'/><text>p</text></svg>", "incomplete"),
    (b"<svg>" + b"<g>" * 100 + b"<text>p</text>" + b"</g>" * 100 + b"</svg>", "nested deeper"),
    (b"<svg>" + b"<circle/>" * 30_000 + b"</svg>", "more than 20000 elements"),
    (b"<svg><polyline points='" + b"1 2 " * 120_000 + b"'/><text>p</text></svg>",
     "more than 200000 coordinates"),
]


@pytest.mark.parametrize(("data", "fragment"), JUNK, ids=[f"junk{i}" for i in range(len(JUNK))])
def test_junk_bytes_never_crash(tmp_path, data, fragment):
    path = tmp_path / "plan.svg"
    path.write_bytes(data)
    with pytest.raises(SubmissionError) as caught:
        read_drawing(path)
    assert fragment in str(caught.value)


def test_huge_files_are_refused_before_reading(tmp_path):
    path = tmp_path / "huge.svg"
    with path.open("wb") as handle:
        handle.seek(MAX_BYTES + 10)
        handle.write(b"x")
    started = time.perf_counter()
    with pytest.raises(SubmissionError, match="at most"):
        read_drawing(path)
    assert time.perf_counter() - started < 1.0


@pytest.mark.parametrize(("text", "fragment"), [
    ("{", "not valid JSON"),
    ("[1]", "must be an object"),
    ('{"plan": "force"}', "plan must be"),
    ('{"plan": "velocity", "points": {}}', "no labelled points"),
    ('{"points": {"p": [0, "x"]}}', "finite numbers"),
    ('{"points": {"p": [0, NaN]}}', "finite numbers"),
    ("[" * 100_000 + "]" * 100_000, "not valid JSON"),
])
def test_junk_json_is_rejected(tmp_path, text, fragment):
    path = tmp_path / "plan.json"
    path.write_text(text)
    with pytest.raises(SubmissionError) as caught:
        read_drawing(path)
    assert fragment in str(caught.value)


def test_no_pole_or_unknown_plan(key):
    with pytest.raises(SubmissionError, match="no pole labelled p"):
        grade_drawing(key, Drawing({"b": (1.0, 2.0)}, "velocity"))
    with pytest.raises(SubmissionError, match="cannot tell which plan"):
        grade_drawing(key, Drawing({"b": (1.0, 2.0)}, None))


def test_drawing_feedback_names_points_and_quantities_as_the_course_does():
    """The slotted lever's b@lever is b₃ (link 3), its ε is ε₃, the slide block/lever the pair
    2–3: a misplaced point's feedback says so, never the key's ids."""
    from planmethod.grading.templates import draw_variant, load_template

    key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    plan = key["plans"]["acceleration"]
    points = {label: tuple(xy) for label, xy in plan["points_mm"].items()}
    x, y = points["b@lever"]
    points["b@lever"] = (x + 10.0, y)
    result = grade_drawing(key, Drawing(points, "acceleration")).as_dict()
    wrong = by_point(result)["b@lever"]
    assert not wrong["correct"] and wrong["name"] == "b₃"
    assert wrong["feedback"].startswith("b₃ is 10.0 mm off") and "ε₃ read" in wrong["feedback"]
    assert "pair 2–3" in wrong["feedback"]
    for text in [r["feedback"] for r in result["points"]] + result["feedback"]:
        assert not any(word in text for word in ("@", "omega_", "epsilon_", "block", "lever"))
