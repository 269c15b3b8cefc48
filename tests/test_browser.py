"""The workbook page in a real browser: headless Chromium driven by Playwright.

The slider is moved to several angles and the readings shown must equal ``planmethod solve
--angle A --json`` to 1e-9; the page must log no console error and record how long each frame
switch took; construction playback must show the report's step sentences; practice mode must
grade a right and a wrong answer as ``planmethod grade`` does.

Skipped, with the reason, where Playwright or the system Chromium is missing (CI installs both:
.ci/run). Leave them out with ``pytest -m "not browser"``.
"""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import chromium
import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parent.parent
COMPRESSOR = ROOT / "exercises" / "compressor_slider_crank.toml"
CONVEYOR = ROOT / "exercises" / "conveyor_sixbar.toml"

sync_api, CHROMIUM = chromium.require()


def cli(*argv) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "planmethod", *map(str, argv)], cwd=ROOT,
                          capture_output=True, text=True, check=True)


@pytest.fixture(scope="module")
def browser():
    with sync_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        yield browser
        browser.close()


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


def move_slider(page, angle: float) -> None:
    page.eval_on_selector("#angle", """(slider, angle) => {
        slider.value = angle;
        slider.dispatchEvent(new Event("input", {bubbles: true}));
    }""", angle)


def shown_readings(page) -> dict[str, float]:
    return {quantity: float(value) for quantity, value in page.eval_on_selector_all(
        "[data-quantity]", "cells => cells.map(c => [c.dataset.quantity, c.dataset.value])")}


@pytest.fixture(scope="module")
def compressor_page(tmp_path_factory):
    path = tmp_path_factory.mktemp("browser") / "compressor.html"
    cli("workbook", COMPRESSOR, "-o", path, "--step", "15")
    return path


@pytest.fixture(scope="module")
def conveyor_page(tmp_path_factory):
    path = tmp_path_factory.mktemp("browser") / "conveyor.html"
    cli("workbook", CONVEYOR, "-o", path, "--step", "30")
    return path


@pytest.mark.parametrize("which, angles", [
    ("compressor", (0.0, 45.0, 135.0, 270.0, 345.0)),
    ("conveyor", (0.0, 90.0, 210.0)),
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
    assert page.text_content("#switch-time").endswith(" ms")
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
        assert page.text_content("#step-text") == step["text"]
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
    page.click("#step-all")
    assert page.eval_on_selector_all("#panel-velocity .step-hidden", "nodes => nodes.length") == 0
    assert errors == []
    page.close()


def test_practice_mode_grades_as_the_cli(browser, compressor_page, tmp_path):
    report = json.loads(cli("solve", COMPRESSOR, "--json").stdout)
    exact = {check["quantity"]: check["analytic"] for check in report["checks"]}
    answers = {"v_C": exact["v_C"],                   # right
               "a_C": exact["a_C"] * 1.5,             # wrong
               "omega_BC": -exact["omega_BC"]}        # sense reversed
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
    for name, value in answers.items():
        page.fill(f'input[data-answer="{name}"]', repr(value))
    page.click("#check")
    results = page.evaluate("workbook.results")
    for name in answers:
        assert results[name]["correct"] == graded[name]["correct"]
        assert results[name]["mistake"] == graded[name]["mistake"]
        assert results[name]["feedback"] == graded[name]["feedback"]
        tolerance = page.text_content(f'[data-tolerance-for="{name}"]')
        assert tolerance.startswith("± ") and f"{graded[name]['tolerance']:.3g}" in tolerance
    assert graded["v_C"]["correct"] and not graded["a_C"]["correct"]
    assert errors == []
    page.close()
