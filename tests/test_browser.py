"""The workbook page in a real browser: headless Chromium driven by Playwright.

The slider is moved to several angles and the readings shown must equal ``planmethod solve
--angle A --json`` to 1e-9; the page must log no console error and record how long each frame
switch took; construction playback must show the report's step sentences; practice mode must
grade a right and a wrong answer as ``planmethod grade`` does.

Drawing mode, on the crank and slotted lever (a Coriolis component): the plans drawn by clicks
where ``planmethod solve --json`` puts their points are right point by point; a point where the
construction without the Coriolis component puts it is named with that mistake; the drawing
downloaded from the page is graded by ``planmethod grade --drawing`` with every point scored;
a reload keeps the drawing, and a kept drawing of another exercise is ignored with a notice.

Skipped, with the reason, where Playwright or the system Chromium is missing (CI installs both:
.ci/run). Leave them out with ``pytest -m "not browser"``.
"""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import chromium
import pytest
from browser_tools import flat, move_slider, sheet_point, start_drawing
from commands import cli

from planmethod.render.workbook import formula_html

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"
CONVEYOR = ROOT / "exercises" / "conveyor_sixbar.toml"
SLOTTED = ROOT / "exercises" / "slotted_lever.toml"

sync_api, CHROMIUM = chromium.require()




@pytest.fixture(scope="module")
def browser():
    yield from chromium.launched(sync_api, CHROMIUM)


def open_page(browser, path: Path):
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    errors: list[str] = []
    page.on("console", lambda message: errors.append(message.text)
            if message.type == "error" else None)
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.on("request", lambda request: errors.append(f"request to {request.url}")
            if not request.url.startswith(("file:", "data:", "about:")) else None)
    page.goto(path.as_uri())
    page.wait_for_function("window.workbook && window.workbook.ready", timeout=30_000)
    return page, errors


def practise(page, answers: dict[str, float]) -> dict:
    """Type ``answers`` into practice mode's fields, check them, and return the page's
    verdicts by question id."""
    for name, value in answers.items():
        page.fill(f'input[data-answer="{name}"]', repr(value))
    page.click("#check")
    return page.evaluate("workbook.results")


def shown_readings(page) -> dict[str, float]:
    return {quantity: float(value) for quantity, value in page.eval_on_selector_all(
        "[data-quantity]", "cells => cells.map(c => [c.dataset.quantity, c.dataset.value])")}


def workbook_page(tmp_path_factory, exercise: Path, step: float) -> Path:
    """The workbook page of ``exercise`` every ``step`` degrees, written by the command."""
    path = tmp_path_factory.mktemp("browser") / f"{exercise.stem}.html"
    cli("workbook", exercise, "-o", path, "--step", step)
    return path


@pytest.fixture(scope="module")
def compressor_page(tmp_path_factory):
    return workbook_page(tmp_path_factory, COMPRESSOR, 15)


@pytest.fixture(scope="module")
def conveyor_page(tmp_path_factory):
    return workbook_page(tmp_path_factory, CONVEYOR, 30)


@pytest.mark.parametrize("which, angles", [
    ("compressor", (0.0, 45.0, 135.0, 270.0, 345.0)),
    ("conveyor", (15.0, 105.0, 225.0)),     # its own angle is 135°: its frames 15° + 30°·k
])
def test_readings_follow_the_slider_and_equal_solve(browser, request, which, angles):
    path = request.getfixturevalue(f"{which}_page")
    exercise = COMPRESSOR if which == "compressor" else CONVEYOR
    page, errors = open_page(browser, path)
    for angle in angles:
        move_slider(page, angle)
        assert page.text_content("#angle-value") == f"{angle:g}°"
        report = json.loads(cli("solve", exercise, "--angle", angle, "--json").stdout)
        shown = shown_readings(page)
        assert list(shown) == [check["quantity"] for check in report["checks"]]
        for check in report["checks"]:
            assert shown[check["quantity"]] == pytest.approx(check["analytic"], rel=1e-9,
                                                              abs=1e-9)
        title = page.text_content("#panel-position title")
        assert f"φ₁ = {angle:g}°" in title
    times = page.evaluate("workbook.switchTimes")
    assert len(times) == len(angles) + 1 and all(t >= 0 for t in times)
    assert page.text_content("#switch-time").endswith(" ms")   # kept for the benchmark,
    assert not page.is_visible("#switch-time")                  # never shown to a student
    assert errors == []
    page.close()


@pytest.mark.parametrize("omega", [100, -100])
def test_play_turns_the_crank_the_way_omega_says(browser, tmp_path_factory, omega):
    """*play* steps φ up when the crank turns counter-clockwise (ω₁ > 0), down when it turns
    clockwise, starting at the exercise's own angle (45°)."""
    folder = tmp_path_factory.mktemp("sense")
    exercise = folder / "compressor.toml"
    exercise.write_text(COMPRESSOR.read_text(encoding="utf-8").replace(
        "omega = 100\n", f"omega = {omega}\n", 1), encoding="utf-8")
    path = workbook_page(tmp_path_factory, exercise, 15)
    page, errors = open_page(browser, path)
    assert page.text_content("#angle-value") == "45°"
    # every angle shown while playing, in order (however many steps a busy machine lets by)
    page.evaluate("""() => {
        window.seen = [];
        const shown = document.querySelector('#angle-value');
        new MutationObserver(() => window.seen.push(shown.textContent))
            .observe(shown, {childList: true, characterData: true, subtree: true});
    }""")
    page.click("#play")
    page.wait_for_function("window.seen.length > 0", timeout=30_000)
    page.click("#play")
    seen = page.evaluate("window.seen")
    assert seen[0] == ("60°" if omega > 0 else "30°"), seen       # one step, the crank's way
    assert errors == []
    page.close()


def test_arrow_keys_step_one_frame(browser, compressor_page):
    page, errors = open_page(browser, compressor_page)
    move_slider(page, 90)
    page.focus("#angle")
    page.keyboard.press("ArrowRight")
    assert page.text_content("#angle-value") == "105°"
    page.keyboard.press("ArrowLeft")
    page.keyboard.press("ArrowLeft")
    assert page.text_content("#angle-value") == "75°"
    assert errors == []
    page.close()


def test_construction_playback_shows_the_reports_steps(browser, compressor_page):
    page, errors = open_page(browser, compressor_page)
    move_slider(page, 45)
    steps = json.loads(cli("solve", COMPRESSOR, "--json").stdout)["plans"]["velocity"]["steps"]
    page.select_option("#step-plan", "velocity")
    for number, step in enumerate(steps[:4]):
        page.click("#step-next")
        # the report's sentence, its subscripts set (n_CB: CB below the n)
        assert page.inner_html("#step-text") == formula_html(step["text"])
        assert "_" not in page.text_content("#step-text")
        assert page.text_content("#step-number") == f"step {number + 1} of {len(steps)}"
        hidden = page.eval_on_selector_all(
            "#panel-velocity [data-step]",
            "nodes => nodes.filter(n => n.classList.contains('step-hidden'))"
            ".map(n => Number(n.dataset.step))")
        assert all(shown > step["number"] for shown in hidden)
        named = {point for earlier in steps[:number + 1]
                 for point in (earlier.get("start"), earlier.get("end")) if point}
        labels = page.eval_on_selector_all(
            "#panel-velocity text.label:not(.step-hidden)",
            "nodes => nodes.map(n => n.dataset.points.split(' '))")
        assert labels and all(named.intersection(points) for points in labels)
        # a point not yet found has no mark (nor a leader) on the plan either
        marks = page.eval_on_selector_all(
            "#panel-velocity circle[data-points]:not(.step-hidden), "
            "#panel-velocity line.leader[data-points]:not(.step-hidden)",
            "nodes => nodes.map(n => n.dataset.points.split(' '))")
        assert marks and all(named.intersection(points) for points in marks)
        if number == 0:
            assert page.eval_on_selector_all("#panel-velocity circle.step-hidden",
                                             "nodes => nodes.length") > 0
    page.click("#step-all")
    assert page.eval_on_selector_all("#panel-velocity .step-hidden", "nodes => nodes.length") == 0
    assert errors == []
    page.close()


def test_practice_mode_grades_as_the_cli(browser, compressor_page, tmp_path):
    report = json.loads(cli("solve", COMPRESSOR, "--json").stdout)
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    answers = {"v_C": exact["v_C"],                   # right
               "a_C": exact["a_C"] * 1.5,             # wrong
               "omega_BC": -exact["omega_BC"],        # sense reversed
               "v_D": -exact["v_D"]}                  # a magnitude with a sign
    sheet = tmp_path / "answers.csv"
    with sheet.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["student", *answers])
        writer.writerow(["s1", *(repr(value) for value in answers.values())])
    cli("grade", COMPRESSOR, sheet, "--json", tmp_path / "graded.json")
    graded = {q["id"]: q for q in json.loads(
        (tmp_path / "graded.json").read_text())["answers"][0]["questions"]}

    page, errors = open_page(browser, compressor_page)
    move_slider(page, 45)
    page.check("#practice")
    assert page.eval_on_selector("td.reading", "c => getComputedStyle(c).visibility") == \
        "hidden"
    results = practise(page, answers)
    for name in answers:
        assert results[name]["correct"] == graded[name]["correct"]
        assert results[name]["mistake"] == graded[name]["mistake"]
        assert results[name]["feedback"] == graded[name]["feedback"]
        tolerance = page.text_content(f'[data-tolerance-for="{name}"]')
        assert tolerance.startswith("± ") and f"{graded[name]['tolerance']:.3g}" in tolerance
    assert graded["v_C"]["correct"] and not graded["a_C"]["correct"]
    assert "a magnitude, never negative" in results["v_D"]["feedback"]
    assert errors == []
    page.close()


def test_practice_gives_no_answer_away_until_asked(browser, compressor_page):
    """Practising with nothing typed, *check* names every answer missing and shows no right
    value anywhere in the page's visible text — not in the verdicts, the readings, the curves,
    the construction's sentences nor the radius of curvature on the mechanism; *show the
    answer* shows one quantity's right value (its verdict and readings), only that one, and the
    page remembers it at that angle."""
    report = json.loads(cli("solve", COMPRESSOR, "--angle", 45, "--json").stdout)
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    page, errors = open_page(browser, compressor_page)
    move_slider(page, 45)
    rho = '#panel-position [data-points="rho_D"]'
    assert page.is_visible(rho)

    def given_away() -> dict[str, list[str]]:
        text = page.evaluate("document.body.innerText")
        return {name: [shown for shown in (f"{value:.4g}", f"{value:.6g}") if shown in text]
                for name, value in exact.items() if abs(value) > 1e-9}

    page.check("#practice")
    page.click("#check")
    results = page.evaluate("workbook.results")
    assert set(results) == set(exact) and not any(r["correct"] for r in results.values())
    for name in exact:
        verdict = page.text_content(f'td.verdict[data-verdict-for="{name}"]')
        assert flat(verdict) == flat(results[name]["hint"]) and verdict.endswith("no answer")
        assert "_" not in verdict          # v_C set as v with C below, never with "_"
    assert not any(given_away().values()), given_away()
    assert not page.is_visible(rho)
    page.fill('input[data-answer="a_C"]', repr(1.3 * exact["a_C"]))
    page.click("#check")
    told = page.evaluate("workbook.results.a_C")
    assert flat(page.text_content('td.verdict[data-verdict-for="a_C"]')) == flat(told["hint"])
    assert page.inner_html('td.verdict[data-verdict-for="a_C"]').startswith("a<sub>C</sub>")
    assert "wrong (" in told["hint"] and f"{exact['a_C']:.6g}" in told["feedback"]
    assert not any(given_away().values()), given_away()

    page.click('button[data-reveal="v_C"]')
    assert flat(page.text_content('td.verdict[data-verdict-for="v_C"]')) == flat(
        results["v_C"]["feedback"])
    assert f"{exact['v_C']:.6g}" in results["v_C"]["feedback"]
    shown = {name: found for name, found in given_away().items() if found}
    assert list(shown) == ["v_C"]
    assert page.is_visible('td.reading[data-quantity="v_C"]')
    assert not page.is_visible(rho)
    assert page.evaluate("workbook.revealed") == {"45": ["v_C"]}
    page.click("#check")   # checked again, the answer shown stays shown, the others hidden
    assert flat(page.text_content('td.verdict[data-verdict-for="v_C"]')) == flat(
        results["v_C"]["feedback"])
    assert list({name for name, found in given_away().items() if found}) == ["v_C"]
    # the radius of curvature on the mechanism shows once its answer is asked for
    page.click('button[data-reveal="rho_D"]')
    assert page.is_visible(rho)
    # another angle: nothing shown there; back at 45°, v_C is remembered
    move_slider(page, 90)
    page.click("#check")
    assert not page.is_visible(rho)
    assert page.text_content('td.verdict[data-verdict-for="v_C"]').endswith("no answer")
    move_slider(page, 45)
    page.click("#check")
    assert flat(page.text_content('td.verdict[data-verdict-for="v_C"]')) == flat(
        results["v_C"]["feedback"])
    page.check("#watch")
    assert page.is_visible(rho) and page.is_visible("#charts")
    assert errors == []
    page.close()


# -- drawing mode -------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def slotted_page(tmp_path_factory):
    return workbook_page(tmp_path_factory, SLOTTED, 15)


def test_practice_mode_tells_magnitudes_and_slides_as_the_cli(browser, slotted_page, tmp_path):
    """A negative Coriolis magnitude and speed of B₃ are told they are magnitudes, in the
    course's names (never v_B@lever, block/lever); a slide's travel with the wrong sign is
    along or against its guide, not clockwise — the same sentences as ``planmethod grade``."""
    report = json.loads(cli("solve", SLOTTED, "--json").stdout)
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    answers = {"coriolis_block/lever": -exact["coriolis_block/lever"],
               "v_B@lever": -exact["v_B@lever"],
               "s_block/lever": -0.8 * exact["s_block/lever"],
               "dds_block/lever": -0.5 * exact["dds_block/lever"]}
    sheet = tmp_path / "answers.json"
    sheet.write_text(json.dumps({"s1": answers}))
    cli("grade", SLOTTED, sheet, "--json", tmp_path / "graded.json")
    graded = {q["id"]: q for q in json.loads(
        (tmp_path / "graded.json").read_text())["answers"][0]["questions"]}
    page, errors = open_page(browser, slotted_page)
    page.check("#practice")
    results = practise(page, answers)
    for name in answers:
        assert results[name]["feedback"] == graded[name]["feedback"]
        assert "@" not in results[name]["feedback"] and "block/" not in results[name]["feedback"]
    assert "aᵏ₂₃ is the magnitude" in results["coriolis_block/lever"]["feedback"]
    assert "v_B₃ is the speed of B₃" in results["v_B@lever"]["feedback"]
    assert "positive, along the guide" in results["s_block/lever"]["feedback"]
    assert "negative, against the guide" in results["dds_block/lever"]["feedback"]
    assert errors == []
    page.close()


@pytest.fixture(scope="module")
def slotted_report():
    return json.loads(cli("solve", SLOTTED, "--json").stdout)


@pytest.fixture
def drawing(browser, slotted_page):
    """The slotted lever's page in drawing mode at its own angle (30°), and the console errors
    it logs."""
    page, errors = open_page(browser, slotted_page)
    start_drawing(page, 30)
    yield page, errors
    page.close()


def click_plan_point(page, plan: str, x: float, y: float) -> None:
    """Click the drawing sheet of ``plan`` where the plan point (x, y) in mm (y up) is: at
    user coordinates (x, −y), scrolled into view first."""
    page.mouse.click(*sheet_point(page, plan, x, y))


def draw_and_download(page, plan: str, report: dict, folder: Path) -> Path:
    """Place the right points of ``plan`` (from a solve report) by clicks and save the drawing
    the page downloads as ``folder/PLAN.json``."""
    place_by_clicks(page, plan, report["plans"][plan]["points_mm"])
    with page.expect_download() as download:
        page.click(f'[data-download="{plan}"]')
    path = folder / f"{plan}.json"
    download.value.save_as(path)
    return path


def place_by_clicks(page, plan: str, points: dict) -> list[str]:
    """Choose every point the page offers for ``plan`` and click where ``points`` (mm) put
    it; returns the points placed."""
    places = page.eval_on_selector_all(f'[data-place^="{plan}:"]',
                                       "buttons => buttons.map(b => b.dataset.place)")
    labels = [place.partition(":")[2] for place in places]
    for label in labels:
        page.click(f'[data-place="{plan}:{label}"]')
        click_plan_point(page, plan, *points[label])
    return labels


def verdicts(page, plan: str) -> dict[str, tuple[str | None, str]]:
    return {cell[0].partition(":")[2]: (cell[1], cell[2]) for cell in page.eval_on_selector_all(
        f'[data-verdict-for^="{plan}:"]',
        "cells => cells.map(c => [c.dataset.verdictFor, c.dataset.ok ?? null, c.textContent])")}


def test_the_right_plans_placed_by_clicks_are_right_point_by_point(drawing, slotted_report):
    page, errors = drawing
    names = page.evaluate("workbook.data.draw.names")
    assert names["b@lever"] == "b₃"          # the course's name, shown on the button
    for plan in ("velocity", "acceleration"):
        points = slotted_report["plans"][plan]["points_mm"]
        labels = place_by_clicks(page, plan, points)
        assert "b@lever" in labels and page.text_content(
            f'[data-place="{plan}:b@lever"]') == "b₃"
        # the sheet's user units are the plan's mm, the pole at (0, 0): each point where
        # solve --json puts it, to the click's precision
        for label in labels:
            placed = page.get_attribute(f'[data-point="{plan}:{label}"]', "data-x"), \
                page.get_attribute(f'[data-point="{plan}:{label}"]', "data-y")
            assert [float(v) for v in placed] == pytest.approx(points[label], abs=0.05)
        page.click(f'[data-check="{plan}"]')
        shown = verdicts(page, plan)
        assert set(shown) == set(labels)
        for label, (ok, sentence) in shown.items():
            assert ok == "true", (label, sentence)
            # the verdict opens with the point's name as its button sets it (b₃, k with B₃)
            assert sentence.startswith(page.text_content(f'[data-place="{plan}:{label}"]') +
                                       ": within ")   # grade --drawing's sentence
    # each check is timed by the page for the benchmark (benchmarks/workbook.py): one time a
    # check, no target here (speed lives in the benchmark)
    times = page.evaluate("workbook.draw.checkTimes")
    assert len(times) == 2 and all(time > 0 for time in times)
    assert errors == []


def test_a_point_where_the_coriolis_term_is_left_out_is_named(drawing, slotted_report,
                                                             tmp_path):
    from planmethod.grading.mistakes import mistaken_plans
    from planmethod.spec import load_exercise

    wrong = mistaken_plans(load_exercise(SLOTTED), "no_coriolis")
    assert wrong is not None
    points = dict(slotted_report["plans"]["acceleration"]["points_mm"])
    page, errors = drawing
    place_by_clicks(page, "acceleration", points)
    page.click('[data-place="acceleration:b@lever"]')
    click_plan_point(page, "acceleration", *wrong.acceleration.points_mm["b@lever"])
    page.click('[data-check="acceleration"]')
    shown = verdicts(page, "acceleration")
    ok, sentence = shown["b@lever"]
    assert ok == "false"
    assert sentence.startswith("b₃ is ") and "mm off" in sentence
    assert "Coriolis component aᵏ was left out" in sentence
    assert all(shown[label][0] == "true" for label in ("b", "c"))
    # hints only: the right position is never told
    x, y = points["b@lever"]
    assert f"{x:.1f}" not in sentence and f"{y:.1f}" not in sentence
    # the instructor grading the handed-in drawing names the same mistake
    with page.expect_download() as download:
        page.click('[data-download="acceleration"]')
    path = tmp_path / "acceleration.json"
    download.value.save_as(path)
    cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
    graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
    point = next(p for p in graded["points"] if p["point"] == "b@lever")
    assert not point["correct"] and point["mistakes"] == ["no_coriolis"]
    assert errors == []


def test_a_point_of_the_wrong_link_is_told_as_grade_tells_it(drawing, slotted_report,
                                                            tmp_path):
    """b₃ placed at b (a point of the wrong link) lies on the line v_B₃B along the guide: the
    page says so, in the very sentence ``grade --drawing`` gives the downloaded drawing."""
    page, errors = drawing
    points = dict(slotted_report["plans"]["velocity"]["points_mm"])
    place_by_clicks(page, "velocity", points)
    page.click('[data-place="velocity:b@lever"]')
    click_plan_point(page, "velocity", *points["b"])
    page.click('[data-check="velocity"]')
    ok, sentence = verdicts(page, "velocity")["b@lever"]
    assert ok == "false"
    assert sentence.startswith("b₃ is ") and " lies on the line " in sentence
    assert " through b but " in sentence and " mm off along it" in sentence
    with page.expect_download() as download:
        page.click('[data-download="velocity"]')
    path = tmp_path / "velocity.json"
    download.value.save_as(path)
    cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
    graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
    told = {point["point"]: point["feedback"] for point in graded["points"]}
    shown = verdicts(page, "velocity")
    assert {label: flat(shown[label][1]) for label in told} == {
        label: flat(sentence) for label, sentence in told.items()}
    assert not [text for _, text in shown.values() if "_" in text]
    assert errors == []


def test_the_downloaded_drawing_is_graded_by_the_cli(drawing, slotted_report, tmp_path):
    page, errors = drawing
    for plan in ("velocity", "acceleration"):
        path = draw_and_download(page, plan, slotted_report, tmp_path)
        drawing = json.loads(path.read_text())
        assert drawing["title"] == slotted_report["title"] and drawing["angle"] == 30
        assert drawing["plan"] == plan
        done = cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
        assert f"({plan} plan): " in done.stdout
        graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
        assert graded["max_score"] >= 3 and graded["score"] == graded["max_score"]
        assert all(p["correct"] for p in graded["points"])
    assert errors == []


def test_a_reload_keeps_the_drawing_and_ignores_another_exercises(drawing, slotted_report):
    page, errors = drawing
    points = slotted_report["plans"]["velocity"]["points_mm"]
    labels = place_by_clicks(page, "velocity", points)
    # drag b₃ 5 mm to the right, then nudge it back with the arrow keys (0.5 mm each)
    x, y = points["b@lever"]
    page.click('[data-place="velocity:b@lever"]')
    page.eval_on_selector('svg[data-draw="velocity"]', "svg => svg.scrollIntoView()")
    start = page.eval_on_selector('[data-point="velocity:b@lever"] circle',
                                  "c => { const b = c.getBoundingClientRect(); "
                                  "return [b.x + b.width / 2, b.y + b.height / 2]; }")
    zoom = page.evaluate("workbook.draw.zoom")
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(start[0] + 5 * zoom, start[1], steps=5)
    page.mouse.up()
    moved = page.evaluate("workbook.draw.drawing('velocity').points['b@lever']")
    assert moved == pytest.approx([x + 5, y], abs=0.1)
    for _ in range(10):
        page.keyboard.press("ArrowLeft")
    back = page.evaluate("workbook.draw.drawing('velocity').points['b@lever']")
    assert back == pytest.approx([moved[0] - 5, moved[1]], abs=1e-9)
    kept = page.evaluate("workbook.draw.drawing('velocity').points")
    page.reload()
    page.wait_for_function("window.workbook && window.workbook.ready", timeout=30_000)
    start_drawing(page, 30)
    assert page.evaluate("workbook.draw.drawing('velocity').points") == kept
    assert sorted(kept) == sorted(labels)
    for label, (u, v) in kept.items():
        assert page.get_attribute(f'[data-point="velocity:{label}"]', "data-x") == f"{u:g}"
        assert page.get_attribute(f'[data-point="velocity:{label}"]', "data-y") == f"{v:g}"
    assert page.text_content("#draw-notice") == ""
    # a drawing kept under this title and angle by another exercise's page is ignored
    page.evaluate("""() => {
        const key = Object.keys(localStorage).find(k => k.endsWith(":30"));
        const record = JSON.parse(localStorage.getItem(key));
        record.exercise = "another exercise";
        localStorage.setItem(key, JSON.stringify(record));
    }""")
    page.reload()
    page.wait_for_function("window.workbook && window.workbook.ready", timeout=30_000)
    start_drawing(page, 30)
    assert page.evaluate("workbook.draw.drawing('velocity').points") == {}
    assert "belongs to another exercise" in page.text_content("#draw-notice")
    assert errors == []


def test_show_the_construction_reveals_one_step_at_a_time(drawing, slotted_report):
    page, errors = drawing
    assert not page.is_visible("#panel-acceleration")       # the answer stays hidden
    steps = slotted_report["plans"]["acceleration"]["steps"]
    for number in range(4):
        page.click('[data-show-step="acceleration"]')
        assert page.is_visible("#panel-acceleration")
        assert page.inner_html('.draw-plan[data-plan="acceleration"] .draw-step') == \
            f"step {number + 1} of {len(steps)}: {formula_html(steps[number]['text'])}"
        hidden = page.eval_on_selector_all(
            "#panel-acceleration [data-step].step-hidden", "nodes => nodes.length")
        assert hidden > 0
    assert page.eval_on_selector_all('svg[data-draw="acceleration"] .right-point',
                                     "nodes => nodes.length") == 0
    page.click('[data-show-plan="acceleration"]')
    assert page.eval_on_selector_all('svg[data-draw="acceleration"] .right-point',
                                     "nodes => nodes.length") == 5
    assert errors == []


def test_the_page_and_grade_give_the_same_verdicts_and_mistakes(drawing, slotted_report,
                                                                tmp_path):
    """Drawings of the acceleration plan — right, drawn without the Coriolis term, c alone
    3 mm off at 45°, b₃ 2 mm off — get the same verdict and the same named mistakes for
    every point, and the same whole-plan sentence (or none), in the page and from
    ``planmethod grade --drawing`` on the downloaded drawing."""
    import math

    from planmethod.grading.mistakes import mistaken_plans
    from planmethod.spec import load_exercise

    right = slotted_report["plans"]["acceleration"]["points_mm"]
    wrong = mistaken_plans(load_exercise(SLOTTED), "no_coriolis").acceleration.points_mm
    shift = 3 / math.sqrt(2)
    drawings = {"right": dict(right), "no Coriolis": dict(wrong),
                "c off": {**right, "c": [right["c"][0] + shift, right["c"][1] + shift]},
                "b₃ off": {**right, "b@lever": [right["b@lever"][0], right["b@lever"][1] + 2]}}
    page, errors = drawing
    labels = [place.partition(":")[2] for place in page.eval_on_selector_all(
        '[data-place^="acceleration:"]', "buttons => buttons.map(b => b.dataset.place)")]
    for number, (name, points) in enumerate(drawings.items()):
        for label in labels:
            page.evaluate("([label, x, y]) => workbook.draw.place('acceleration', label, x, y)",
                          [label, *points[label]])
        page.click('[data-check="acceleration"]')
        results = page.evaluate("workbook.draw.results.acceleration")
        summary = page.text_content('.draw-plan[data-plan="acceleration"] .draw-summary')
        with page.expect_download() as download:
            page.click('[data-download="acceleration"]')
        path = tmp_path / f"drawing{number}.json"
        download.value.save_as(path)
        cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
        graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
        for point in graded["points"]:
            mine = results[point["point"]]
            assert mine["ok"] == point["correct"], (name, point)
            assert mine["mistakes"] == point.get("mistakes", []), (name, point)
        plan_lines = [line for line in graded["feedback"] if line.startswith("the wrong points")]
        assert [flat(line) for line in plan_lines] == [
            flat(line) for line in [summary.partition("; ")[2]] if line], name
        assert not re.search(r"_[A-Za-z]", summary), summary
        if name == "no Coriolis":
            assert plan_lines and "Coriolis component aᵏ was left out" in plan_lines[0]
        else:
            assert plan_lines == [], name
    assert errors == []


def test_a_drawing_at_another_angle_is_graded_at_that_angle(drawing, tmp_path):
    """The slotted lever's own angle is 30°: its plans drawn on the page at 45° download with
    that angle and are graded by ``planmethod grade --drawing`` against the exercise file at
    45°, every point scored."""
    page, errors = drawing
    move_slider(page, 45)
    report = json.loads(cli("solve", SLOTTED, "--angle", 45, "--json").stdout)
    for plan in ("velocity", "acceleration"):
        path = draw_and_download(page, plan, report, tmp_path)
        assert json.loads(path.read_text())["angle"] == 45
        cli("grade", SLOTTED, "--drawing", path, "--json", tmp_path / "graded.json")
        graded = json.loads((tmp_path / "graded.json").read_text())["drawings"][0]
        assert graded["max_score"] >= 3 and graded["score"] == graded["max_score"], graded
    assert errors == []


def test_two_exercises_with_one_title_keep_their_own_drawings(browser, slotted_page,
                                                              slotted_report, tmp_path):
    """Two pages of exercises with the same title (a template's variants; here the lever
    10 cm longer) keep their drawings apart: drawing on one leaves the other's kept drawing
    as it was, and a page with no drawing of its own says that the other's is kept."""
    longer = tmp_path / "slotted_longer.toml"
    longer.write_text(SLOTTED.read_text().replace("C = [0.45, 0]", "C = [0.55, 0]"))
    other = tmp_path / "slotted_longer.html"
    cli("workbook", longer, "-o", other, "--step", 15)
    context = browser.new_context(viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))

    def open_at_30(path):
        page.goto(path.as_uri())
        page.wait_for_function("window.workbook && window.workbook.ready", timeout=30_000)
        start_drawing(page, 30)

    open_at_30(slotted_page)
    labels = place_by_clicks(page, "velocity", slotted_report["plans"]["velocity"]["points_mm"])
    kept = page.evaluate("workbook.draw.drawing('velocity').points")
    assert sorted(kept) == sorted(labels)
    open_at_30(other)
    assert page.evaluate("workbook.draw.drawing('velocity').points") == {}
    assert "another exercise with this title" in page.text_content("#draw-notice")
    page.evaluate("([label, x, y]) => workbook.draw.place('velocity', label, x, y)",
                  ["b", 1.0, 2.0])
    open_at_30(slotted_page)
    assert page.evaluate("workbook.draw.drawing('velocity').points") == kept
    assert page.text_content("#draw-notice") == ""
    assert errors == []
    context.close()


def test_drawing_hides_every_value_read_off_a_plan(browser, compressor_page, tmp_path):
    """While drawing, nothing gives a right position away: the readings (exact and read off
    the plan), the curves, the radius of curvature on the mechanism, and the right value in a
    typed answer's verdict (the hint instead, as ``grade --feedback hints``) stay hidden
    until the student asks to see the plan they are read off; then that plan's show."""
    report = json.loads(cli("solve", COMPRESSOR, "--json").stdout)
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    sheet = tmp_path / "answers.json"
    sheet.write_text(json.dumps({"s1": {"v_C": 1.2 * exact["v_C"],
                                        "a_C": 1.2 * exact["a_C"]}}))
    cli("grade", COMPRESSOR, sheet, "--json", tmp_path / "graded.json")
    graded = {q["id"]: q for q in json.loads(
        (tmp_path / "graded.json").read_text())["answers"][0]["questions"]}
    page, errors = open_page(browser, compressor_page)

    def hidden_readings():
        return {row: page.eval_on_selector(
            f'td.reading[data-quantity="{row}"]',
            "cell => getComputedStyle(cell).visibility === 'hidden' && getComputedStyle("
            "cell.nextElementSibling).visibility === 'hidden'") for row in exact}

    def shown_charts():
        return page.eval_on_selector_all(
            "#charts .chart", "charts => charts.filter(c => c.offsetParent !== null)"
            ".map(c => c.querySelector('title').textContent)")

    rho = '#panel-position [data-points="rho_D"]'
    assert not any(hidden_readings().values()) and len(shown_charts()) == 4
    assert page.is_visible(rho)
    page.check("#draw-mode")
    assert all(hidden_readings().values())
    assert shown_charts() == [] and not page.is_visible(rho)
    # drawing, the answers are typed and graded too (the hint, as while practising)
    for name in ("v_C", "a_C"):
        page.fill(f'input[data-answer="{name}"]', repr(1.2 * exact[name]))
    page.click("#check")
    for name in ("v_C", "a_C"):
        verdict = page.text_content(f'td.verdict[data-verdict-for="{name}"]')
        assert flat(verdict) == flat(graded[name]["hint"]) and f"{exact[name]:.4g}" not in verdict
    # the right velocity plan asked for: its values show, the acceleration plan's do not
    page.click('[data-show-plan="velocity"]')
    page.click("#check")
    for name, told in (("v_C", "feedback"), ("a_C", "hint")):
        verdict = page.text_content(f'td.verdict[data-verdict-for="{name}"]')
        assert flat(verdict) == flat(graded[name][told]) and "_" not in verdict
    shown = {name for name, hidden in hidden_readings().items() if not hidden}
    assert shown == {"v_C", "v_D", "omega_BC"}
    assert [title.partition(" over")[0] for title in shown_charts()] == \
        ["velocities", "angular velocities"]
    page.check("#watch")
    assert not any(hidden_readings().values()) and len(shown_charts()) == 4
    assert page.is_visible(rho)
    assert errors == []
    page.close()


def test_points_are_placed_anywhere_nudged_finely_and_named_as_the_course(drawing,
                                                                         slotted_report):
    """A chosen point is placed where the student clicks, even on another point (two points
    may coincide); Shift + an arrow key nudges it 0.1 mm; moving a point clears the plan's
    summary of the last check; every button and mark names its point with real subscripts
    (k with B₃ below, never k_B₃), and so does the playback's vector equation."""
    page, errors = drawing
    points = slotted_report["plans"]["acceleration"]["points_mm"]
    page.click('[data-place="acceleration:b"]')
    click_plan_point(page, "acceleration", *points["b"])
    page.click('[data-place="acceleration:k_B@lever"]')
    click_plan_point(page, "acceleration", *points["b"])     # on b's mark: k is placed
    placed = page.evaluate("workbook.draw.drawing('acceleration').points")
    assert placed["k_B@lever"] == pytest.approx(placed["b"], abs=0.05)
    assert placed["b"] == pytest.approx(points["b"], abs=0.05)
    page.click('[data-check="acceleration"]')
    summary = '.draw-plan[data-plan="acceleration"] .draw-summary'
    assert page.text_content(summary).startswith("1 of 3 points")
    page.click('[data-place="acceleration:k_B@lever"]')       # chosen again: the keys move it
    page.focus('svg[data-draw="acceleration"]')
    start = placed["k_B@lever"]
    for _ in range(3):
        page.keyboard.press("Shift+ArrowRight")
    page.keyboard.press("ArrowUp")
    moved = page.evaluate("workbook.draw.drawing('acceleration').points['k_B@lever']")
    assert moved == pytest.approx([start[0] + 0.3, start[1] + 0.5], abs=1e-9)
    assert "check again" in page.text_content(summary)
    assert page.get_attribute('[data-verdict-for="acceleration:k_B@lever"]', "data-ok") is None
    # course names with real subscripts, on the buttons, the marks and in the verdicts
    texts = page.eval_on_selector_all(
        "[data-place], [data-point] text, .draw-verdict", "nodes => nodes.map(n => n.textContent)")
    assert texts and not any("_" in text for text in texts)
    button = page.inner_html('[data-place="acceleration:k_B@lever"]')
    assert "k<sub>B</sub>" in button and ">3</sub>" in button
    assert page.text_content('[data-place="acceleration:k_B@lever"]') == "kB3"
    assert page.text_content('[data-place="acceleration:b@lever"]') == "b₃"
    assert page.eval_on_selector('[data-point="acceleration:k_B@lever"] text',
                                 "t => t.querySelectorAll('tspan[font-size]').length") == 2
    page.click('[data-show-step="acceleration"]')
    equation = page.inner_html("#equations")
    assert "<sub>" in equation and "_" not in page.text_content("#equations")
    assert page.text_content("#equations").startswith("aB3 = aB + aᵏB3")
    assert errors == []


@pytest.mark.parametrize("which", ["compressor", "conveyor"])
def test_panel_text_is_readable_in_a_1400_px_window(browser, request, which):
    """Every drawing of the page shows at its own size in a 1400 px wide window: no text of
    a panel (labels, legends, scales; subscripts aside) is smaller than 11 CSS px, as the
    drawings set it; the small side-by-side view stays available."""
    page, errors = open_page(browser, request.getfixturevalue(f"{which}_page"))
    sizes = page.evaluate("""() => Array.from(document.querySelectorAll('.panel svg')).map(
        svg => [svg.closest('.panel').id, Math.min(...Array.from(svg.querySelectorAll('text'))
            .map(text => parseFloat(getComputedStyle(text).fontSize) * svg.getScreenCTM().a))])""")
    assert len(sizes) >= 4
    for panel, smallest in sizes:
        assert smallest >= 11 - 0.05, (panel, smallest)
    page.check("#compact")
    widths = page.eval_on_selector_all(".panel", "panels => panels.map(p => p.offsetWidth)")
    assert max(widths) < 700
    # two to a row, each panel keeps its drawing's aspect ratio: no empty band around it
    for panel, drawn, shown in page.evaluate("""() => Array.from(
            document.querySelectorAll('.panel svg')).map(svg => {
        const box = svg.viewBox.baseVal, panel = svg.closest('.panel');
        return [panel.id, box.height / box.width, panel.clientHeight / panel.clientWidth];
    })"""):
        assert shown == pytest.approx(drawn, rel=0.02), panel
    assert errors == []
    page.close()


# -- one rulebook: the page and planmethod grade ------------------------------------------------
def test_the_page_grades_the_golden_file_as_python_does(browser, compressor_page,
                                                        tmp_path_factory):
    """The workbook page's own scripts and rules (the data embedded in a page the command
    wrote) give every case of the golden file Python's verdict: each typed answer
    ``grade``'s feedback and hint, each drawn point ``grade --drawing``'s sentence, each plan
    summary Python's, each number Python's writing (tests/page_golden.py; the same file runs
    under Node in tests/test_page_rules.py)."""
    import page_golden

    golden = json.loads(page_golden.golden_file(tmp_path_factory).read_text(encoding="utf-8"))
    page, errors = open_page(browser, compressor_page)
    assert page.evaluate("workbook.data.rules") == golden["rules"]
    wrong = page.evaluate("""golden => {
        const rules = workbook.rules, out = [];
        const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
        golden.answers.forEach(item => {
            const {question, quantity} = golden.questions[item.question];
            const mine = rules.answerVerdict(question, item.raw, quantity);
            const got = {correct: mine.correct, mistake: mine.mistake, feedback: mine.feedback,
                         hint: mine.hint, answer: mine.answer};
            const expected = item.expected;
            if (!same(got, {correct: expected.correct, mistake: expected.mistake,
                            feedback: expected.feedback, hint: expected.hint,
                            answer: expected.answer})) out.push([item.raw, got, expected]);
        });
        golden.drawings.forEach(item => {
            const plan = golden.plans[item.plan];
            const verdict = rules.sheet(plan.data, item.drawn, plan.names, golden.texts);
            Object.entries(item.expected).forEach(([label, expected]) => {
                const mine = verdict(label);
                if (!same({ok: mine.ok, mistakes: mine.mistakes, sentence: mine.sentence},
                          expected)) out.push([item, label, mine]);
            });
            const got = rules.planSummary(plan.plan, item.right, plan.data.required.length,
                                          item.common, golden.texts);
            if (got !== item.summary) out.push([item, got]);
        });
        golden.numbers.forEach(([value, specification, expected]) => {
            const got = planmethodWords.formatNumber(value, specification);
            if (got !== expected) out.push([value, specification, expected, got]);
        });
        return {wrong: out.slice(0, 5), count: out.length, answers: golden.answers.length};
    }""", golden)
    assert wrong == {"wrong": [], "count": 0, "answers": len(golden["answers"])}
    assert errors == []
    page.close()
