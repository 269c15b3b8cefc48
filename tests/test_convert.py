"""The exercise written as drawn, and ``planmethod convert`` between the two forms.

* every shipped exercise, and variants of every shipped template, written as drawn and back
  solves the same: every number of the JSON report agrees to 1e-12 (relative; see
  :mod:`planmethod.testing.reports`), and the round trip drawn → frames → drawn writes the
  same bytes;
* the as-drawn form's own rules: the crank drawn at ``drive.angle``, a slide's point on its
  guide, the assembly the one drawn, one-line errors;
* templates accept the as-drawn form with expressions.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import pytest

from planmethod.convert import convert_tables, convert_text
from planmethod.errors import SpecError
from planmethod.grading.templates import draw_variant, load_template, parse_template
from planmethod.report import analyse, report_dict
from planmethod.spec import exercise_from_dict, parse_exercise, parse_toml, read_text
from planmethod.testing import slider_crank
from planmethod.testing.reports import report_differences

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = sorted((ROOT / "exercises").glob("*.toml"))
TEMPLATES = sorted((ROOT / "exercises" / "templates").glob("*.toml"))
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"

#: links whose frame in the shipped file is not "+x from the first point toward the second"
#: (the conveyor's tray: +x from C toward D, E listed second): as drawn, their θ turns by this
#: much (rad) and a centre of mass in their frame turns with it; everything else agrees
TURNED_FRAMES = {"conveyor_sixbar": {"tray": math.pi}}


def shipped_tables():
    """(name, tables) of every shipped exercise, and three variants of every template."""
    for path in EXERCISES:
        yield path.stem, parse_toml(read_text(path))
    for path in TEMPLATES:
        template = load_template(path)
        for seed in range(3):
            yield f"{path.stem}#{seed}", dict(draw_variant(template, seed=seed, student="s").data)


SHIPPED = list(shipped_tables())


def report(tables) -> dict:
    return report_dict(analyse(exercise_from_dict(tables)))


def turned(report_: dict, name: str) -> dict:
    """The report with the frames of :data:`TURNED_FRAMES` turned back (θ and S)."""
    for link, angle in TURNED_FRAMES.get(name, {}).items():
        entry = report_.get("links", {}).get(link)
        if entry is not None:
            entry["theta"] = math.remainder(entry["theta"] + angle, 2 * math.pi)
        inertia = report_.get("forces", {}).get("inertia", {}).get(link)
        if inertia is not None:
            x, y = inertia["S"]
            c, s = math.cos(angle), math.sin(angle)
            inertia["S"] = [c * x - s * y, s * x + c * y]
    return report_


@pytest.mark.parametrize(("name", "tables"), SHIPPED, ids=[name for name, _ in SHIPPED])
def test_both_forms_solve_alike(name, tables):
    drawn = convert_tables(tables, to="drawn")
    assert "points" in drawn and "sketch" not in drawn
    original = report(tables)
    as_drawn = turned(report(drawn), name)
    assert report_differences(original, as_drawn, rel=1e-12) == []
    # and back in link frames: the drawing's own frames, the same numbers again
    frames = convert_tables(drawn, to="frames")
    assert report_differences(report(drawn), report(frames), rel=1e-12) == []


def test_a_turned_frame_is_only_a_turn():
    """The one exception above is what it says: without turning the tray back, θ differs."""
    tables = dict(SHIPPED)["conveyor_sixbar"]
    differences = report_differences(report(tables), report(convert_tables(tables, to="drawn")))
    assert {line.split(":")[0] for line in differences} == {"links.tray.theta",
                                                             "forces.inertia.tray.S"}


@pytest.mark.parametrize(("name", "tables"), SHIPPED, ids=[name for name, _ in SHIPPED])
def test_round_trip_is_byte_stable(name, tables):
    from planmethod.grading.templates import to_toml

    drawn = convert_text(to_toml(tables), to="drawn")
    frames = convert_text(drawn)
    assert "[sketch]" in frames and "[points]" not in frames
    again = convert_text(frames)
    assert again == drawn
    assert convert_text(again) == frames
    # the same form asked again writes it as this module writes it, stably
    assert convert_text(drawn, to="drawn") == drawn
    assert convert_text(frames, to="frames") == frames


def test_the_file_keeps_its_leading_comments_and_its_paragraphs():
    text = read_text(COMPRESSOR)
    drawn = convert_text(text)
    assert drawn.startswith("# Exactly as stated in U. A. Abduvaliev")
    assert "description = '''\nConstruct the position plan" in drawn
    assert parse_toml(drawn)["description"] == parse_toml(text)["description"]


# -- the as-drawn form ---------------------------------------------------------------------------
#: the slider's guide: the line through A along x
SLIDER_ON_FRAME = """
[[slide]]
link = "slider"
along = "frame"
through = "A"
direction = 0
"""

ISSUE_EXAMPLE = """
title = "Compressor slider-crank, as drawn"
[drive]
link = "AB"
pivot = "A"
angle = 45
omega = 100
[points]            # m, at drive.angle; they fix every length and the assembly
A = [0, 0]
B = [0.0424264, 0.0424264]
C = [0.217355, 0]
D = [0.129891, 0.0212132]
[links]
frame = ["A"]
AB = ["A", "B"]
BC = ["B", "C", "D"]
slider = ["C"]
""" + SLIDER_ON_FRAME


def test_the_issue_example_is_the_compressor_to_its_drawn_digits():
    drawn = analyse(parse_exercise(ISSUE_EXAMPLE, file="drawn.toml"))
    exact = analyse(exercise_from_dict(slider_crank()))
    values = {check.quantity: check.analytic for check in exact.checks}
    for check in drawn.checks:
        if check.quantity in values:   # six digits drawn: the values to about 1e-5
            assert check.analytic == pytest.approx(values[check.quantity], rel=2e-5)


def test_the_assembly_is_the_one_drawn():
    """The four-bar drawn with C below AD is assembled with C below AD (the other branch of
    the shipped exercise), and every point stands where it was drawn."""
    tables = convert_tables(parse_toml(read_text(ROOT / "exercises" / "fourbar_forces.toml")),
                            to="drawn")
    above = tables["points"]["C"]
    b, d = tables["points"]["B"], tables["points"]["D"]
    # mirror C in the line BD: the other assembly of the dyad BC–CD
    ux, uy = d[0] - b[0], d[1] - b[1]
    t = ((above[0] - b[0]) * ux + (above[1] - b[1]) * uy) / (ux * ux + uy * uy)
    foot = (b[0] + t * ux, b[1] + t * uy)
    below = [2 * foot[0] - above[0], 2 * foot[1] - above[1]]
    tables["points"]["C"] = below
    for name, xy in (("C", below), ("B", b)):
        position = analyse(exercise_from_dict(tables)).motion.at(0).position(name)
        assert position == pytest.approx(xy, abs=1e-12)
    assert below[1] < 0 < above[1]


def drawn_error(text: str) -> str:
    with pytest.raises(SpecError) as caught:
        parse_exercise(text, file="drawn.toml")
    message = str(caught.value)
    assert "\n" not in message
    return message


def test_a_crank_not_drawn_at_the_drive_angle_names_both_angles():
    message = drawn_error(ISSUE_EXAMPLE.replace("angle = 45", "angle = 50"))
    assert message == ("drawn.toml: drive.angle: the crank AB is drawn at 45°, but drive.angle "
                       "is 50°")
    nearly = drawn_error(ISSUE_EXAMPLE.replace("B = [0.0424264, 0.0424264]",
                                               "B = [0.0424264, 0.0424364]"))
    assert "drawn at 45.01°" in nearly and "drive.angle is 45°" in nearly


def test_a_slide_point_off_its_guide_gives_the_distance():
    message = drawn_error(ISSUE_EXAMPLE.replace("C = [0.217355, 0]", "C = [0.217355, 0.002]"))
    assert message.startswith("drawn.toml: slide[1].point: C is drawn 0.002 m off its guide, "
                              "the line through A at 0°")


@pytest.mark.parametrize(("change", "expected"), [
    (("slider = [\"C\"]", "slider = [\"E\"]"), "links.slider[0]: 'E' is not drawn in [points]"),
    (("D = [0.129891, 0.0212132]", "D = [0.129891, 0.0212132]\nE = [1, 1]"),
     "points.E: is not a point of any link"),
    (("BC = [\"B\", \"C\", \"D\"]", "BC = [\"B\", \"C\", \"C\"]"),
     "links.BC[2]: 'C' is listed twice"),
    (("[[slide]]", "[sketch]\nC = [0.2, 0]\n[[slide]]"), "sketch: an exercise written as drawn"),
    (("AB = [\"A\", \"B\"]", "AB = { A = [0, 0], B = [0.06, 0] }"),
     "links.AB: with [points] (the exercise written as drawn) a link is the list of its points"),
    (("B = [0.0424264, 0.0424264]", "B = [0.0424264, nan]"),
     "points.B[1]: must be a finite number, got nan"),
    (("B = [0.0424264, 0.0424264]", "B = [0, 0]"), "points.B: the crank pin B is drawn on the "
                                                   "pivot A"),
    (("A = [0, 0]", "A = [0, 0]\nZ = [0, 0]"), "points.Z: is not a point of any link"),
    (("C = [0.217355, 0]", "C = [1e300, 0]"), "points.C[0]: must be at most 1e+06 in magnitude"),
    (('slider = ["C"]', "slider = []"), "links.slider: a link needs at least one point"),
    (('link = "slider"', 'link = ["slider"]'), "slide[1].link: must be a non-empty string"),
])
def test_as_drawn_mistakes_are_one_line(change, expected):
    assert expected in drawn_error(ISSUE_EXAMPLE.replace(*change))


def test_a_list_of_points_without_the_points_table_says_what_is_missing():
    text = read_text(COMPRESSOR).replace("AB = { A = [0, 0], B = [0.06, 0] }", 'AB = ["A", "B"]')
    assert "links.AB: a list of point names needs the [points] table" in drawn_error(text)


def test_a_guide_on_a_moving_link_is_global_as_drawn():
    """The slotted lever's slot runs along the lever (0° in its frame): as drawn, its direction
    is the lever's global angle, and the frames form gets 0° back."""
    tables = parse_toml(read_text(ROOT / "exercises" / "slotted_lever.toml"))
    drawn = convert_tables(tables, to="drawn")
    o2, c = drawn["points"]["O2"], drawn["points"]["C"]
    lever = math.degrees(math.atan2(c[1] - o2[1], c[0] - o2[0]))
    assert drawn["slide"][0]["direction"] == pytest.approx(lever, abs=1e-12)
    assert convert_tables(drawn, to="frames")["slide"][0]["direction"] == pytest.approx(
        0.0, abs=1e-12)


# -- templates -----------------------------------------------------------------------------------
DRAWN_TEMPLATE = """
title = "Slider-crank, as drawn"
description = "AB = {l_AB:.3f} m, BC = {l_BC:.3f} m at {phi:g}°."
[vars]
l_AB = { range = [0.05, 0.08], step = 0.005 }
l_BC = { range = [0.18, 0.24], step = 0.01 }
phi = { range = [30, 150], step = 5 }
[template]
max_tolerance = 1
[drive]
link = "AB"
pivot = "A"
angle = "= phi"
omega = 100
[points]
A = [0, 0]
B = ["= l_AB * cos(phi)", "= l_AB * sin(phi)"]
C = ["= l_AB * cos(phi) + sqrt(l_BC ^ 2 - (l_AB * sin(phi)) ^ 2)", 0]
[links]
frame = ["A"]
AB = ["A", "B"]
BC = ["B", "C"]
slider = ["C"]
""" + SLIDER_ON_FRAME + """
[ask]
velocity = ["C"]
acceleration = ["C"]
omega = ["BC"]
"""


@pytest.mark.parametrize("seed", range(4))
def test_templates_accept_the_as_drawn_form_with_expressions(seed):
    template = parse_template(DRAWN_TEMPLATE, file="drawn_template.toml")
    variant = draw_variant(template, seed=seed, student="s1")
    values = variant.values
    mechanism = variant.exercise.mechanism
    assert mechanism.links["BC"].length("B", "C") == pytest.approx(values["l_BC"], rel=1e-12)
    expected = analyse(exercise_from_dict(slider_crank(crank=values["l_AB"], rod=values["l_BC"],
                                                       angle=values["phi"])))
    got = analyse(variant.exercise)
    exact = {check.quantity: check.analytic for check in expected.checks}
    for check in got.checks:
        assert check.analytic == pytest.approx(exact[check.quantity], rel=1e-12)
    assert f"AB = {values['l_AB']:.3f} m" in variant.description


def test_a_template_is_converted_variant_by_variant():
    with pytest.raises(SpecError, match="vars: a template"):
        convert_text(DRAWN_TEMPLATE)


# -- the command ---------------------------------------------------------------------------------
def cli(*argv: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "planmethod", *argv], cwd=ROOT,
                          capture_output=True, text=True)


def test_convert_writes_the_other_form_and_back(tmp_path):
    drawn, frames, again = tmp_path / "drawn.toml", tmp_path / "frames.toml", tmp_path / "x.toml"
    assert cli("convert", str(COMPRESSOR), "-o", str(drawn)).returncode == 0
    assert cli("convert", str(drawn), "-o", str(frames), "--to", "frames").returncode == 0
    assert cli("convert", str(frames), "-o", str(again)).returncode == 0
    assert again.read_bytes() == drawn.read_bytes()
    solved = cli("solve", str(drawn), "--json")
    assert solved.returncode == 0, solved.stderr
    printed = cli("convert", str(frames))
    assert printed.stdout == drawn.read_text(encoding="utf-8")


def test_convert_refuses_bad_input_in_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(ISSUE_EXAMPLE.replace("angle = 45", "angle = 46"), encoding="utf-8")
    out = tmp_path / "out.toml"
    done = cli("convert", str(bad), "-o", str(out))
    assert done.returncode == 2 and not out.exists()
    assert done.stderr == (f"planmethod: error: {bad}: drive.angle: the crank AB is drawn at "
                           "45°, but drive.angle is 46°\n")
    template = cli("convert", str(TEMPLATES[0]))
    assert template.returncode == 2 and template.stderr.count("\n") == 1
