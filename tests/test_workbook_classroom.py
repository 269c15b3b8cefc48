"""The workbook in a classroom, in headless Chromium through Playwright (issue 39): the mode
bar (watch, practise, draw) in the first viewport on a laptop and a phone and in view when
scrolled; drawing brought into view; what comes after a right velocity plan; a reload that
restores the mode, the angle, the drawing with its verdicts and what was revealed; no asked
value shown while practising or drawing with nothing typed; a point placed by a tap on a phone
and graded.

Skipped, with the reason, where Playwright or the system Chromium is missing.
"""

from __future__ import annotations

import json
from pathlib import Path

import chromium
import pytest
from browser_tools import (
    flat,
    move_slider,
    run_axe,
    sheet_point,
    start_drawing,
    violations_text,
)
from commands import cli

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"
SLOTTED = ROOT / "exercises" / "slotted_lever.toml"

sync_api, CHROMIUM = chromium.require()

LAPTOP = {"viewport": {"width": 1280, "height": 720}}
PHONE = {"viewport": {"width": 390, "height": 844}, "has_touch": True, "is_mobile": True,
         "device_scale_factor": 3}




@pytest.fixture(scope="module")
def browser():
    yield from chromium.launched(sync_api, CHROMIUM)


@pytest.fixture(scope="module")
def slotted_page(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("classroom") / "slotted.html"
    cli("workbook", SLOTTED, "-o", path, "--step", 15)
    return path


@pytest.fixture(scope="module")
def compressor_page(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("classroom") / "compressor.html"
    cli("workbook", COMPRESSOR, "-o", path, "--step", 15)
    return path


@pytest.fixture(scope="module")
def slotted_report() -> dict:
    return json.loads(cli("solve", SLOTTED, "--json").stdout)


def ready(page) -> None:
    page.wait_for_function("window.workbook && window.workbook.ready", timeout=30_000)


def open_page(browser, path: Path, device: dict):
    """A new browser context (its own storage) of ``device`` with the page open, and the
    console errors it logs."""
    context = browser.new_context(**device)
    page = context.new_page()
    errors: list[str] = []
    page.on("console", lambda message: errors.append(message.text)
            if message.type == "error" else None)
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.goto(path.as_uri())
    ready(page)
    return page, errors


def box(page, selector: str) -> dict:
    return page.eval_on_selector(selector, "e => e.getBoundingClientRect().toJSON()")


def in_view(page, selector: str) -> bool:
    """Whether the element lies wholly inside the viewport."""
    rect, (width, height) = box(page, selector), page.evaluate("[innerWidth, innerHeight]")
    return rect["top"] >= 0 and rect["left"] >= 0 and rect["bottom"] <= height and \
        rect["right"] <= width and rect["width"] > 0


def words(page, name: str, **fields) -> str:
    """A sentence of the page's words, as the page says it."""
    return page.evaluate("([name, fields]) => workbook.rules.words.say(name, fields)",
                         [name, fields])


def place_all(page, plan: str, points: dict, tap: bool = False) -> list[str]:
    labels = [place.partition(":")[2] for place in page.eval_on_selector_all(
        f'[data-place^="{plan}:"]', "buttons => buttons.map(b => b.dataset.place)")]
    for label in labels:
        if tap:
            page.tap(f'[data-place="{plan}:{label}"]')
            page.touchscreen.tap(*sheet_point(page, plan, *points[label]))
        else:
            page.click(f'[data-place="{plan}:{label}"]')
            page.mouse.click(*sheet_point(page, plan, *points[label]))
    return labels


@pytest.mark.parametrize("device", [LAPTOP, PHONE], ids=["1280x720", "390x844-touch"])
def test_the_mode_bar_is_in_the_first_viewport_and_stays_in_view(browser, slotted_page,
                                                                  device):
    page, errors = open_page(browser, slotted_page, device)
    assert page.eval_on_selector_all('#modes input[name="mode"]',
                                     "inputs => inputs.map(i => i.value)") == \
        ["watch", "practise", "draw"]
    assert in_view(page, "#modes")
    for label in page.query_selector_all("#modes label"):
        size = label.bounding_box()
        assert size["width"] >= 44 and size["height"] >= 44
    # no horizontal scroll of the page
    assert page.evaluate("document.documentElement.scrollWidth <= innerWidth")
    page.evaluate("window.scrollTo(0, document.body.scrollHeight)")
    assert page.evaluate("scrollY") > 0 and in_view(page, "#modes")
    # switching to draw brings the velocity plan's sheet into view, below the bar
    page.evaluate("window.scrollTo(0, 0)")
    page.check("#draw-mode")
    heading = box(page, '.draw-plan[data-plan="velocity"] h3')
    assert heading["top"] >= box(page, "#controls")["bottom"] - 1
    sheet = box(page, 'svg[data-draw="velocity"]')
    assert sheet["top"] < page.evaluate("innerHeight") - 100
    assert in_view(page, "#modes")
    assert page.evaluate("document.documentElement.scrollWidth <= innerWidth")
    assert errors == []
    page.context.close()


def test_a_right_velocity_plan_says_the_acceleration_plan_comes_next(browser, slotted_page,
                                                                     slotted_report):
    page, errors = open_page(browser, slotted_page, LAPTOP)
    start_drawing(page, 30)
    assert page.text_content("#draw-status") == ""
    place_all(page, "velocity", slotted_report["plans"]["velocity"]["points_mm"])
    page.click('[data-check="velocity"]')
    said = words(page, "next_acceleration")
    assert said == "the velocity plan is right: now draw the acceleration plan"
    assert page.text_content("#draw-status") == said
    place_all(page, "acceleration", slotted_report["plans"]["acceleration"]["points_mm"])
    page.click('[data-check="acceleration"]')
    assert page.text_content("#draw-status") == words(page, "plans_right", phi="φ₁", angle=30)
    assert errors == []
    page.context.close()


def test_a_reload_restores_the_drawing_its_verdicts_and_what_was_revealed(
        browser, slotted_page, slotted_report):
    page, errors = open_page(browser, slotted_page, LAPTOP)
    move_slider(page, 45)
    page.check("#practice")
    page.click('button[data-reveal="v_B@lever"]')
    start_drawing(page, 30)
    points = slotted_report["plans"]["velocity"]["points_mm"]
    place_all(page, "velocity", points)
    page.click('[data-check="velocity"]')
    shown = {cell: text for cell, text in page.eval_on_selector_all(
        '[data-verdict-for^="velocity:"]',
        "cells => cells.map(c => [c.dataset.verdictFor, c.textContent])")}
    assert shown and all(shown.values())
    page.click('[data-show-step="acceleration"]')
    page.click('[data-show-step="acceleration"]')
    step = page.text_content('.draw-plan[data-plan="acceleration"] .draw-step')
    assert step
    page.reload()
    ready(page)
    # the mode, the angle, the drawing and its verdicts, the construction's steps shown
    assert page.is_checked("#draw-mode") and page.input_value("#angle") == "30"
    assert page.text_content("#draw-kept") == words(page, "kept_restored", phi="φ₁", angle=30)
    assert "30°" in page.text_content("#draw-kept")
    assert {cell: text for cell, text in page.eval_on_selector_all(
        '[data-verdict-for^="velocity:"]',
        "cells => cells.map(c => [c.dataset.verdictFor, c.textContent])")} == shown
    assert page.text_content("#draw-status") == words(page, "next_acceleration")
    assert page.text_content('.draw-plan[data-plan="acceleration"] .draw-step') == step
    assert page.evaluate("workbook.draw.exported('acceleration').revealed") == \
        ["construction:acceleration"]
    # what was revealed while practising, at its angle
    assert page.evaluate("workbook.revealed") == {"45": ["v_B@lever"]}
    page.check("#practice")
    move_slider(page, 45)
    assert page.is_visible('td.reading[data-quantity="v_B@lever"]')
    assert not page.is_visible('td.reading[data-quantity="omega_lever"]')
    assert errors == []
    page.context.close()


@pytest.mark.parametrize("mode", ["practice", "draw-mode"])
def test_nothing_typed_shows_no_asked_value(browser, compressor_page, mode):
    """Practising or drawing, *check* with nothing typed shows no right value of an asked
    quantity anywhere in the page's visible text."""
    report = json.loads(cli("solve", COMPRESSOR, "--angle", 45, "--json").stdout)
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    page, errors = open_page(browser, compressor_page, LAPTOP)
    move_slider(page, 45)
    page.check(f"#{mode}")
    page.click("#check")
    results = page.evaluate("workbook.results")
    asked = set(results)
    assert asked and not any(result["correct"] for result in results.values())
    text = page.evaluate("document.body.innerText")
    given = {name: shown for name, value in exact.items() if name in asked and abs(value) > 1e-9
             for shown in (f"{value:.4g}", f"{value:.6g}") if shown in text}
    assert given == {}
    assert errors == []
    page.context.close()


def test_a_point_is_placed_by_a_tap_on_a_phone_and_graded(browser, slotted_page,
                                                          slotted_report):
    page, errors = open_page(browser, slotted_page, PHONE)
    start_drawing(page, 30)
    assert in_view(page, "#modes")
    points = slotted_report["plans"]["velocity"]["points_mm"]
    labels = place_all(page, "velocity", points, tap=True)
    for label in labels:
        placed = page.evaluate(f"workbook.draw.drawing('velocity').points[{label!r}]")
        assert placed == pytest.approx(points[label], abs=0.2)
    page.tap('[data-check="velocity"]')
    oks = page.eval_on_selector_all('[data-verdict-for^="velocity:"]',
                                    "cells => cells.map(c => c.dataset.ok)")
    assert oks and all(ok == "true" for ok in oks)
    # point buttons and the plan's controls are at least 44 × 44 CSS px
    for selector in ('.draw-plan[data-plan="velocity"] button', "#controls button"):
        for button in page.query_selector_all(selector):
            size = button.bounding_box()
            if size:
                assert size["width"] >= 44 and size["height"] >= 44, selector
    assert page.evaluate("document.documentElement.scrollWidth <= innerWidth")
    assert errors == []
    page.context.close()


def test_a_practice_hint_says_about_how_far_off_and_which_way(browser, compressor_page,
                                                               tmp_path):
    """A wrong answer's hint tells which way it is off and about how far (to one significant
    digit, never the right value), the same sentence as ``grade --feedback hints``."""
    report = json.loads(cli("solve", COMPRESSOR, "--json").stdout)   # at its own angle
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    answers = {"v_C": 1.12 * exact["v_C"], "v_D": 0.7 * exact["v_D"],
               "a_C": 30 * exact["a_C"]}
    sheet = tmp_path / "answers.json"
    sheet.write_text(json.dumps({"s1": answers}))
    cli("grade", COMPRESSOR, sheet, "--json", tmp_path / "graded.json")
    graded = {q["id"]: q for q in json.loads(
        (tmp_path / "graded.json").read_text())["answers"][0]["questions"]}
    page, errors = open_page(browser, compressor_page, LAPTOP)
    page.check("#practice")
    for name, value in answers.items():
        page.fill(f'input[data-answer="{name}"]', repr(value))
    page.click("#check")
    for name in answers:
        shown = page.text_content(f'td.verdict[data-verdict-for="{name}"]')
        assert flat(shown) == flat(graded[name]["hint"]) and "_" not in shown
        assert f"{exact[name]:.4g}" not in shown
    hint = graded["v_C"]["hint"]
    assert hint.endswith("(about 10 % too high)") or \
        hint.endswith("(about 10 % too large in magnitude)")
    assert "about 30 % too" in graded["v_D"]["hint"]
    assert "about 30 times what it should be" in graded["a_C"]["hint"]
    assert errors == []
    page.context.close()


def touch(client, kind: str, *points: tuple[float, float]) -> None:
    """A touch event through the browser's input (the fingers at ``points``, CSS px)."""
    client.send("Input.dispatchTouchEvent", {
        "type": kind, "touchPoints": [{"x": x, "y": y, "id": number}
                                      for number, (x, y) in enumerate(points)]})


def test_a_finger_sees_its_point_magnified_above_it_and_two_fingers_zoom(
        browser, slotted_page):
    """A finger's point shows in a loupe above the finger while it moves (the finger hides
    the point itself) and is placed where the finger leaves the sheet; two fingers zoom the
    sheet and place nothing; the zoom reaches a size where every tolerance disc of the page is
    6 px across or more."""
    page, errors = open_page(browser, slotted_page, PHONE)
    assert page.get_attribute('meta[name="viewport"]', "content") == \
        "width=device-width, initial-scale=1"
    page.check("#draw-mode")
    client = page.context.new_cdp_session(page)
    x, y = sheet_point(page, "velocity", 0, 10)
    zoom = page.evaluate("workbook.draw.zoom")
    touch(client, "touchStart", (x, y))
    touch(client, "touchMove", (x + 2 * zoom, y))
    loupe = box(page, ".draw-loupe")
    assert page.is_visible(".draw-loupe") and loupe["bottom"] < y - 20     # above the finger
    assert page.eval_on_selector(".draw-loupe svg", "v => v.querySelectorAll('circle').length")
    touch(client, "touchEnd")
    assert not page.is_visible(".draw-loupe")
    first = page.evaluate("Object.keys(workbook.draw.drawing('velocity').points)")
    assert len(first) == 1
    placed = page.evaluate(f"workbook.draw.drawing('velocity').points[{first[0]!r}]")
    assert placed == pytest.approx([2, 10], abs=0.5)
    # two fingers spread apart: the sheet zooms in, the chosen point stays unplaced
    before = page.evaluate("workbook.draw.drawing('velocity').points")
    touch(client, "touchStart", (x - 20, y + 40), (x + 20, y + 40))
    for step in range(1, 6):
        touch(client, "touchMove", (x - 20 - 15 * step, y + 40), (x + 20 + 15 * step, y + 40))
    touch(client, "touchEnd")
    assert page.evaluate("workbook.draw.zoom") > zoom
    assert page.evaluate("workbook.draw.drawing('velocity').points") == before
    smallest, zooms = page.evaluate("[workbook.draw.smallestRadius, workbook.draw.zooms]")
    assert smallest > 0 and max(zooms) * 2 * smallest >= 6
    for _ in zooms:
        page.click('[data-zoom="1"]')
    assert page.evaluate("workbook.draw.zoom") == max(zooms)
    assert page.evaluate("document.documentElement.scrollWidth <= innerWidth")
    assert errors == []
    page.context.close()


def test_the_keyboard_places_a_point_on_a_chosen_sheet(browser, slotted_page, slotted_report):
    """Enter on a focused sheet places the chosen point at the middle of the sheet in view;
    Control + an arrow key moves it 5 mm, an arrow key 0.5 mm; + zooms."""
    page, errors = open_page(browser, slotted_page, LAPTOP)
    start_drawing(page, 30)
    page.focus('[data-place="velocity:b"]')
    page.keyboard.press("Enter")                      # the point's button chooses it
    page.focus('svg[data-draw="velocity"]')
    page.keyboard.press("Enter")
    start = page.evaluate("workbook.draw.drawing('velocity').points.b")
    page.keyboard.press("Control+ArrowRight")
    page.keyboard.press("ArrowUp")
    moved = page.evaluate("workbook.draw.drawing('velocity').points.b")
    assert moved == pytest.approx([start[0] + 5, start[1] + 0.5], abs=1e-9)
    zoom = page.evaluate("workbook.draw.zoom")
    page.keyboard.press("+")
    assert page.evaluate("workbook.draw.zoom") > zoom
    assert errors == []
    page.context.close()


@pytest.mark.parametrize("device", [LAPTOP, PHONE], ids=["1280x720", "390x844-touch"])
def test_axe_finds_no_serious_or_critical_violation(browser, slotted_page, slotted_report,
                                                   device):
    """axe-core on the workbook in each mode: watching, practising with every verdict shown,
    drawing with a plan checked and its right plan shown."""
    page, errors = open_page(browser, slotted_page, device)
    assert run_axe(page) == [], violations_text(run_axe(page))
    page.check("#practice")
    page.click("#check")
    page.click('button[data-reveal="v_C"]')
    found = run_axe(page)
    assert found == [], violations_text(found)
    start_drawing(page, 30)
    place_all(page, "velocity", slotted_report["plans"]["velocity"]["points_mm"])
    page.click('[data-check="velocity"]')
    page.click('[data-show-plan="acceleration"]')
    found = run_axe(page)
    assert found == [], violations_text(found)
    assert errors == []
    page.context.close()


def test_controls_are_named_in_course_words(browser, slotted_page):
    """Each answer's field is named by its quantity's course symbol as the table shows it
    (ω₃, v_B₃), never by its id (omega_lever, v_B@lever); no control is named by an id."""
    page, errors = open_page(browser, slotted_page, LAPTOP)
    page.check("#practice")
    ids = page.eval_on_selector_all("input.answer", "inputs => inputs.map(i => i.dataset.answer)")
    names = page.eval_on_selector_all("input.answer", """inputs => inputs.map(input =>
        document.getElementById(input.getAttribute("aria-labelledby")).textContent)""")
    assert "ω3" in names and "vB₃" in names
    for name, id_ in zip(names, ids, strict=True):
        assert name and "_" not in name and "@" not in name and name != id_
        assert page.get_by_label(name, exact=True).first.get_attribute("data-answer") == id_
    labels = page.eval_on_selector_all("[aria-label]", "nodes => nodes.map(n => n.ariaLabel)")
    assert not [label for label in labels if any(id_ in label for id_ in ids)]
    assert errors == []
    page.context.close()


def test_every_action_works_from_the_keyboard(browser, slotted_page, slotted_report):
    """The modes by the arrow keys, an answer typed, checked and shown, the angle by the
    arrow keys, a point chosen and placed, a construction line drawn and turned, a plan
    checked — without the mouse."""
    page, errors = open_page(browser, slotted_page, LAPTOP)
    page.focus("#watch")
    page.keyboard.press("ArrowRight")
    assert page.is_checked("#practice")
    page.focus('input[data-answer="v_C"]')
    page.keyboard.type("1")
    page.focus("#check")
    page.keyboard.press("Enter")
    assert page.text_content('td.verdict[data-verdict-for="v_C"]').startswith("vC = 1")
    page.focus('button[data-reveal="v_C"]')
    page.keyboard.press("Enter")
    assert page.evaluate("workbook.revealedAt(workbook.data.angles[workbook.frame])") == ["v_C"]
    page.focus("#angle")
    angle = page.evaluate("workbook.data.angles[workbook.frame]")
    page.keyboard.press("ArrowRight")
    assert page.evaluate("workbook.data.angles[workbook.frame]") == angle + 15
    page.keyboard.press("ArrowLeft")
    page.focus("#practice")
    page.keyboard.press("ArrowRight")
    assert page.is_checked("#draw-mode")
    points = slotted_report["plans"]["velocity"]["points_mm"]
    page.focus('[data-place="velocity:b"]')
    page.keyboard.press("Enter")
    page.focus('svg[data-draw="velocity"]')
    page.keyboard.press("Enter")
    start = page.evaluate("workbook.draw.drawing('velocity').points.b")
    # to the right place in 5 mm, 0.5 mm and 0.1 mm steps
    for axis, (key_up, key_down) in enumerate((("ArrowRight", "ArrowLeft"),
                                               ("ArrowUp", "ArrowDown"))):
        for step, modifier in ((5, "Control+"), (0.5, ""), (0.1, "Shift+")):
            for _ in range(int(abs(points["b"][axis] - page.evaluate(
                    "workbook.draw.drawing('velocity').points.b")[axis]) / step + 1e-9)):
                current = page.evaluate("workbook.draw.drawing('velocity').points.b")[axis]
                page.keyboard.press(modifier + (key_up if points["b"][axis] > current
                                                else key_down))
    placed = page.evaluate("workbook.draw.drawing('velocity').points.b")
    assert placed != start and placed == pytest.approx(points["b"], abs=0.11)
    page.focus('.draw-plan[data-plan="velocity"] [data-tool="line"]')
    page.keyboard.press("Enter")
    page.focus('svg[data-draw="velocity"]')
    page.keyboard.press("Enter")
    page.keyboard.press("Control+ArrowUp")
    page.keyboard.press("ArrowUp")
    assert page.evaluate("workbook.draw.drawing('velocity').lines") == [
        {"through": "b", "at": placed, "direction_deg": 16}]
    page.focus('[data-check="velocity"]')
    page.keyboard.press("Enter")
    assert page.get_attribute('[data-verdict-for="velocity:b"]', "data-ok") == "true"
    assert errors == []
    page.context.close()


def test_downloaded_answers_say_what_was_revealed_and_grade_reports_it(
        browser, slotted_page, tmp_path):
    """Practising at 45°, one answer shown and another typed: the answers downloaded name the
    exercise and the angle, are graded at that angle, and ``grade`` reports the one shown (in
    its text and in the JSON's ``revealed``)."""
    page, errors = open_page(browser, slotted_page, LAPTOP)
    move_slider(page, 45)
    page.check("#practice")
    page.click('button[data-reveal="v_B@lever"]')
    right = page.get_attribute('td.reading[data-quantity="omega_lever"]', "data-value")
    page.fill('input[data-answer="omega_lever"]', right)
    with page.expect_download() as download:
        page.click("#download-answers")
    sheet = tmp_path / download.value.suggested_filename
    download.value.save_as(sheet)
    assert sheet.name.endswith("-answers-45deg.json")
    written = json.loads(sheet.read_text())
    assert written["angle"] == 45 and written["revealed"] == ["v_B@lever"]
    assert written["answers"] == {"omega_lever": right} and len(written["exercise"]) == 16
    graded_json = tmp_path / "graded.json"
    shown = cli("grade", SLOTTED, sheet, "--json", graded_json).stdout
    graded = json.loads(graded_json.read_text())["answers"][0]
    assert graded["revealed"] == ["v_B@lever"]
    assert next(q for q in graded["questions"] if q["id"] == "omega_lever")["correct"]
    note = next(line for line in shown.splitlines() if line.startswith("  !  "))
    assert "the page showed the right values" in note and note.endswith(": v_B₃")
    assert errors == []
    page.context.close()
