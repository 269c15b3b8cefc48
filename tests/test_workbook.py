"""The workbook page and the animations, without a browser: what the page holds (the same
readings, steps and keys as `solve` and `grade`), that it names no address, and the error paths
(one line, exit 2, nothing written). The page in a real browser: tests/test_browser.py."""

from __future__ import annotations

import base64
import gzip
import json
import re
from pathlib import Path

import pytest

from planmethod.cli import main
from planmethod.render.workbook import formula_html
from planmethod.report import analyse, report_dict
from planmethod.spec import load_exercise

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"
CONVEYOR = ROOT / "exercises" / "conveyor_sixbar.toml"


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def page_data(text: str) -> dict:
    packed = re.search(r'<script type="application/octet-stream" id="workbook-data">'
                       r'([^<]*)</script>', text).group(1)
    return json.loads(gzip.decompress(base64.b64decode(packed)))


@pytest.fixture(scope="module")
def compressor_page(tmp_path_factory):
    path = tmp_path_factory.mktemp("workbook") / "compressor.html"
    assert main(["workbook", str(COMPRESSOR), "-o", str(path), "--step", "15"]) == 0
    return path.read_text(encoding="utf-8")


def test_page_names_no_address_and_has_the_controls(compressor_page):
    data = page_data(compressor_page)
    everything = compressor_page + json.dumps(data, ensure_ascii=False)
    assert not re.search(r"https?:|//www\.|\bsrc=|@import|url\(", everything)
    assert '<input type="range" id="angle" min="0" max="345" step="15"' in compressor_page
    assert data["angles"] == [15.0 * k for k in range(24)]
    assert data["panels"][:3] == ["position", "velocity", "acceleration"]


def test_frames_hold_the_reports_checks_and_the_keys(compressor_page):
    data = page_data(compressor_page)
    exercise = load_exercise(COMPRESSOR)
    from planmethod.grading.keys import build_key
    from planmethod.grading.templates import draw_variant, load_template

    names = [q["name"] for q in data["quantities"]]
    for number in (0, 5, 7):
        angle = data["angles"][number]
        report = report_dict(analyse(exercise, angle))
        assert names == [check["quantity"] for check in report["checks"]]
        readings = data["frames"][number]["readings"]
        for check, (exact, plan) in zip(report["checks"], readings, strict=True):
            assert exact == check["analytic"] and plan == check["plan"]
        steps = data["frames"][number]["steps"]["velocity"]
        assert [data["strings"][text] for _, text, *_ in steps] == [
            formula_html(step["text"]) for step in report["plans"]["velocity"]["steps"]]
    # at the file's own angle the page's key is `planmethod grade`'s key
    key = build_key(draw_variant(load_template(COMPRESSOR)))
    frame = data["frames"][data["angles"].index(exercise.mechanism.drive.angle)]
    for mine, theirs in zip(frame["questions"], key["questions"], strict=True):
        assert mine["id"] == theirs["id"]
        assert mine["value"] == theirs["value"] and mine["tolerance"] == theirs["tolerance"]
        assert mine["mistakes"] == theirs["mistakes"]


def test_drawings_are_the_ones_solve_writes(compressor_page):
    """Each frame's drawings are ``solve --svg``'s, drawn steady: at the turn's one zoom and
    page per panel."""
    from planmethod.render.figures import plan_files
    from planmethod.render.steady import steady_views
    from planmethod.render.workbook import inline_svg

    data = page_data(compressor_page)
    exercise = load_exercise(COMPRESSOR)
    analysis = analyse(exercise, data["angles"][3])
    files = plan_files(analysis.plans, details=False,
                       views=steady_views(exercise, data["angles"]))
    for panel, lines in zip(data["panels"], data["frames"][3]["drawings"], strict=True):
        assert "\n".join(data["strings"][k] for k in lines) == inline_svg(files[panel + ".svg"])


def test_every_panel_keeps_one_page_over_the_turn(compressor_page):
    """One viewBox per panel for the whole turn: the pivots and poles stay put, the scale
    does not change; and the page opens at the exercise's own angle."""
    import re

    data = page_data(compressor_page)
    for index, panel in enumerate(data["panels"]):
        boxes = {re.search(r'viewBox="([^"]+)"', data["strings"][frame["drawings"][index][0]])
                 .group(1) for frame in data["frames"]}
        assert len(boxes) == 1, (panel, boxes)
    opening = float(re.search(r'id="angle"[^>]* value="([^"]+)"', compressor_page).group(1))
    drive = load_exercise(COMPRESSOR).mechanism.drive.angle
    assert opening == drive and drive in data["angles"]


def test_the_notebooks_page_holds_and_opens_at_the_exercises_own_angle():
    """Jupyter shows the workbook every 10°: the compressor's own angle is 45°, so its frames
    are 5°, 15° … 355° and the page opens at 45°, not at 40°."""
    import html

    from planmethod.notebook import NOTEBOOK_STEP, _exercise_html

    exercise = load_exercise(COMPRESSOR)
    assert exercise.mechanism.drive.angle == 45 and NOTEBOOK_STEP == 10
    frame = _exercise_html(exercise)
    page = html.unescape(re.search(r'srcdoc="([^"]*)"', frame).group(1))
    data = page_data(page)
    assert data["angles"] == [5.0 + 10 * k for k in range(36)]
    assert re.search(r'id="angle"[^>]* min="5" max="355" step="10" value="45"', page)


def test_identical_svg_lines_are_stored_once(compressor_page):
    data = page_data(compressor_page)
    used = [k for frame in data["frames"] for lines in frame["drawings"] for k in lines]
    assert len(data["strings"]) == len(set(data["strings"]))
    assert len(set(used)) < 0.7 * len(used)


@pytest.mark.parametrize("argv, words", [
    (["--step", "0"], "option --step"),
    (["--step", "nan"], "option --step"),
    (["--step", "400"], "option --step"),
    (["--from", "100", "--to", "50"], "option --to"),
    (["--from", "0", "--to", "400"], "option --to"),
    (["--from", "inf"], "option --from"),
])
def test_workbook_bad_step_or_range_exits_2_and_writes_nothing(capsys, tmp_path, argv, words):
    out_path = tmp_path / "page.html"
    code, _, err = run(capsys, "workbook", COMPRESSOR, "-o", out_path, *argv)
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1
    assert "Traceback" not in err and not out_path.exists()


SLOTTED_CROSSHEAD = ROOT / "exercises" / "slotted_crank_crosshead.toml"


def test_a_crank_that_cannot_turn_fully_gets_a_page_of_the_angles_it_reaches(capsys,
                                                                           tmp_path):
    """The slot carried by the crank turns parallel to the crosshead's guide at 120° (and
    300°): no full turn, and the refusal says what makes a page; --from and --to give one,
    its frames on the exercise's own angle's grid, and its note says the range."""
    path = tmp_path / "page.html"
    code, _, err = run(capsys, "workbook", SLOTTED_CROSSHEAD, "-o", path, "--step", "30")
    assert code == 2 and not path.exists() and len(err.strip().splitlines()) == 1
    assert "crank angle 120°" in err and err.rstrip().endswith("with --from and --to")
    code, _, err = run(capsys, "workbook", SLOTTED_CROSSHEAD, "-o", path, "--step", "30",
                       "--from", "-50", "--to", "100")
    assert code == 0 and not err
    text = path.read_text(encoding="utf-8")
    assert page_data(text)["angles"] == [-30.0, 0.0, 30.0, 60.0, 90.0]
    assert "5 positions from -30° to 90°, every 30°" in text


def test_an_animation_of_a_crank_that_cannot_turn_fully_takes_its_angles(capsys, tmp_path):
    """As the workbook: a full turn meets the limit and says what makes an animation; the
    range gives one frame per angle of it."""
    path = tmp_path / "turn.svg"
    code, _, err = run(capsys, "animate", SLOTTED_CROSSHEAD, "-o", path, "--step", "30")
    assert code == 2 and not path.exists() and err.rstrip().endswith("with --from and --to")
    code, out, _ = run(capsys, "animate", SLOTTED_CROSSHEAD, "-o", path, "--step", "30",
                       "--from", "-50", "--to", "100")
    assert code == 0 and "(5 frames," in out
    assert path.read_text(encoding="utf-8").count('class="frame"') == 5


def test_workbook_wants_an_html_file(capsys, tmp_path):
    code, _, err = run(capsys, "workbook", COMPRESSOR, "-o", tmp_path / "page.pdf")
    assert code == 2 and "option -o" in err and not (tmp_path / "page.pdf").exists()


def test_animate_unknown_suffix_exits_2_before_any_work(capsys, tmp_path):
    code, _, err = run(capsys, "animate", tmp_path / "missing.toml", "-o", tmp_path / "a.avi")
    assert code == 2 and ".svg, .gif or .mp4" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "a.avi").exists()


def test_animate_mp4_without_ffmpeg_exits_2(capsys, tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))  # no ffmpeg here
    code, _, err = run(capsys, "animate", COMPRESSOR, "-o", tmp_path / "a.mp4")
    assert code == 2 and "ffmpeg" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "a.mp4").exists()


def test_animated_svg_shows_each_frame_once_per_turn(capsys, tmp_path):
    path = tmp_path / "turn.svg"
    code, _, err = run(capsys, "animate", COMPRESSOR, "-o", path, "--step", "45",
                       "--seconds", "4")
    assert code == 0 and not err
    text = path.read_text(encoding="utf-8")
    delays = [float(d) for d in re.findall(r'class="frame" style="animation-delay:([0-9.]+)s"',
                                           text)]
    assert delays == pytest.approx([0.5 * k for k in range(8)])
    assert "animation:planmethod-turn 4s step-end infinite" in text
    assert text.count("position plan, φ₁ = 135°") == 1


def test_animated_gif_has_one_frame_per_angle(capsys, tmp_path):
    from PIL import Image

    path = tmp_path / "turn.gif"
    code, _, _ = run(capsys, "animate", COMPRESSOR, "-o", path, "--step", "60")
    assert code == 0
    with Image.open(path) as image:
        assert image.n_frames == 6 and image.info["loop"] == 0


def test_notebook_shows_an_exercise_as_its_workbook():
    from planmethod.notebook import register

    class Formatter:
        def __init__(self):
            self.types = {}

        def for_type_by_name(self, module, name, function):
            self.types[module, name] = function

    from types import SimpleNamespace

    formatters = {"image/svg+xml": Formatter(), "text/html": Formatter()}
    register(SimpleNamespace(display_formatter=SimpleNamespace(formatters=formatters)))
    shown = formatters["text/html"].types[
        "planmethod.model", "Exercise"]
    html = shown(load_exercise(COMPRESSOR))
    assert html.startswith("<iframe") and "srcdoc=" in html and "id=&quot;angle&quot;" in html
    # the same drawing mode inline
    for plan in ("velocity", "acceleration"):
        assert f"svg data-draw=&quot;{plan}&quot;" in html
        assert f"data-check=&quot;{plan}&quot;" in html


def test_the_drawing_mode_holds_each_angles_key_points_and_mistakes(tmp_path):
    """The drawing mode's data are the answer key's at each angle (points, tolerance radii,
    mistakes' positions on the sheet), the markup is the documented one, and the page grades
    against them without computing mechanics."""
    from dataclasses import replace

    from planmethod.application.workbook import exercise_variant
    from planmethod.grading.keys import build_key, key_numbers
    from planmethod.grading.plan_points import DRAWN_MISTAKES, drawing_frame

    slotted = ROOT / "exercises" / "slotted_lever.toml"
    path = tmp_path / "slotted.html"
    assert main(["workbook", str(slotted), "-o", str(path), "--step", "60"]) == 0
    text = path.read_text(encoding="utf-8")
    for plan in ("velocity", "acceleration"):
        for attribute in ("svg data-draw", "data-check", "data-download"):
            assert f'{attribute}="{plan}"' in text
    data = page_data(text)
    draw = data["draw"]
    assert draw["title"] == "Crank and slotted lever" and draw["format"] == "planmethod-drawing"
    assert draw["names"]["b@lever"] == "b₃" and draw["names"]["c"] == "c"
    assert [mistake for mistake, _ in draw["mistakes"]] == list(DRAWN_MISTAKES)
    exercise = load_exercise(slotted)
    variant = exercise_variant(exercise)
    for number in (0, 3):
        angle = data["angles"][number]
        key = build_key(replace(variant, exercise=analyse(exercise, angle).exercise))
        expected = drawing_frame(key, key_numbers(key))
        frame = data["frames"][number]["draw"]
        for plan, entry in expected.items():
            left, bottom, right, top = draw["extents"][plan]
            # and what grade --drawing's sentences tell of a point: its lines, its step, the
            # readings off it, the other points they name (by their course names)
            for field in ("points", "required", "helpers", "lines", "placed", "reads",
                          "others"):
                assert frame[plan][field] == entry[field], field
            assert set(entry["others"]) <= set(draw["names"])
            for x, y, _ in entry["points"].values():     # one sheet holds every angle's plan
                assert left < x < right and bottom < y < top
            for label, candidates in entry["mistakes"].items():
                on_sheet = [c for c in candidates
                            if left <= c[1] <= right and bottom <= c[2] <= top]
                assert frame[plan]["mistakes"].get(label, []) == on_sheet
    assert data["frames"][1]["draw"]["acceleration"]["mistakes"]["b@lever"]
    assert [line[0] for line in data["frames"][1]["draw"]["acceleration"]["lines"]["b@lever"]
            ] == ["k_B@lever", "n_B@lever"]


def test_readings_name_every_quantity_in_the_course_notation(tmp_path):
    """The readings table writes each quantity as the course does: a link's by its number
    (ω₃), a point of a link by that link's number (v_B₃), a slide by the numbers of its two
    links (s₂₃) — never a link's name from the file (``block/lever``)."""
    path = tmp_path / "slotted.html"
    assert main(["workbook", str(ROOT / "exercises" / "slotted_lever.toml"), "-o", str(path),
                 "--step", "90"]) == 0
    shown = {q["name"]: q["symbol"] + "_" + q["subscript"]
             for q in page_data(path.read_text(encoding="utf-8"))["quantities"]}
    assert shown["omega_lever"] == "ω_3" and shown["v_B@lever"] == "v_B₃"
    assert shown["s_block/lever"] == "s_23" and shown["ds_block/lever"] == "ds/dt_23"
    assert not any("block" in text or "lever" in text for text in shown.values()), shown


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_page_draws_its_exercises_variant_once(monkeypatch, jobs):
    """The variant a frame keys at its own angle is the exercise file's, the same for every
    frame: a page draws it once (in one process it was drawn again for each of 360 frames,
    about a fifth of the page's time), and hands it to its workers."""
    from planmethod.application import workbook

    calls = []
    drawn = workbook.exercise_variant

    def counted(exercise):
        calls.append(exercise.mechanism.title)
        return drawn(exercise)

    monkeypatch.setattr(workbook, "exercise_variant", counted)
    exercise = load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml")
    page = workbook.build_workbook(exercise, 60.0, jobs=jobs)
    assert len(calls) == 1 and page.count('data-quantity="') == 7


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_page_packed_as_its_frames_come_is_the_page_packed_at_once(monkeypatch, jobs):
    """The page's data is packed while the workers solve the frames that follow (its string
    table grown and gzipped chunk by chunk): the page is byte for byte the one packed at
    once from the same frames."""
    from planmethod.application import workbook
    from planmethod.application.workers import usable_cpus
    from planmethod.render import workbook as page_module

    if jobs > usable_cpus():
        pytest.skip("one CPU: no second worker")
    made = {}
    write = page_module.workbook_html

    def kept(page, rules=None, data=None):
        made.update(page=page, rules=rules, held=data is not None and data.holds(page))
        return write(page, rules, data)

    monkeypatch.setattr(page_module, "workbook_html", kept)
    text = workbook.build_workbook(load_exercise(COMPRESSOR), 10.0, jobs=jobs)
    assert made["held"] and len(made["page"].frames) == 36
    assert text == write(made["page"], made["rules"])      # packed at once
    assert len(page_data(text)["frames"]) == 36
