"""Figures over a full turn (issue 37): every figure of the loaded press and of an unseen-style
mechanism (the rocking block of the lever's terms), drawn at every 15° of the crank, as
``solve --svg`` writes them. A cluster crowded by points or by the labels round them is drawn
again as an enlarged detail (two levels at most) or, where it still cannot be read, listed in
the table of crowded points beside the figure — never left crowded on the figure."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from planmethod.render.figures import plan_files
from planmethod.report import analyse
from planmethod.spec import exercise_from_dict, load_exercise
from planmethod.testing.figures import detail_depth, figure_problems, page_ratio

ROOT = Path(__file__).resolve().parent.parent
#: every 15° of the crank: 24 positions of each mechanism
ANGLES = tuple(float(angle) for angle in range(0, 360, 15))


def _exercise(name: str):
    if name == "press":
        return load_exercise(ROOT / "exercises" / "loaded_press_sixbar.toml")
    from test_lever_terms import ROCKING

    return exercise_from_dict(tomllib.loads(ROCKING))


@pytest.fixture(scope="module", params=["press", "rocking block"])
def turn(request) -> dict[float, dict[str, str]]:
    """Every figure of the mechanism at each of :data:`ANGLES` (angle → file → SVG)."""
    exercise = _exercise(request.param)
    drawn = {}
    for angle in ANGLES:
        analysis = analyse(exercise, angle)
        drawn[angle] = plan_files(analysis.plans, analysis.forces)
    return drawn


def _found(turn, check, names=None) -> list[str]:
    return [f"{angle:g}° {name}: {problem}" for angle, files in turn.items()
            for name, svg in files.items() if names is None or name in names
            for problem in check(svg)]


def test_every_crowded_cluster_is_a_detail_or_a_table_over_the_turn(turn):
    """No figure at any angle leaves marks nearer than the readable distance, or a label on
    another point's mark, outside a detail and out of its table of crowded points."""
    found = _found(turn, lambda svg: [problem for problem in figure_problems(svg)
                                      if problem.endswith("(no detail)")])
    assert not found, "\n".join(found[:20])


def test_details_nest_two_levels_at_most_over_the_turn(turn):
    found = _found(turn, lambda svg: [f"{detail_depth(svg)} levels"] if detail_depth(svg) > 2
                   else [])
    assert not found, "\n".join(found[:20])


PLANS = ("position.svg", "velocity.svg", "acceleration.svg")


def test_the_plans_pass_the_figure_check_over_the_turn(turn):
    """The position, velocity and acceleration plans: no figure problem at any angle, each
    page within 3× of what it draws."""
    found = _found(turn, figure_problems, PLANS)
    found += _found(turn, lambda svg: [f"page {page_ratio(svg):.2f}× what it draws"]
                    if page_ratio(svg) > 3.0 else [], PLANS)
    assert not found, "\n".join(found[:20])


def _over_three(turn) -> list[str]:
    return [f"{angle:g}° {name}: page {page_ratio(svg):.2f}× what it draws"
            for angle, files in turn.items() for name, svg in files.items()
            if page_ratio(svg) > 3.0]


def test_every_page_keeps_within_three_times_what_it_draws_over_the_turn(turn):
    """Every figure's page (its legend's column, its tables and details beside the drawing)
    within 3× of what it draws — the press's lever with its eight details and its table of
    21 forces too: where they would make the page longer, the lever is drawn larger."""
    found = _over_three(turn)
    assert not found, "\n".join(found[:20])


def test_every_page_of_the_conveyor_keeps_within_three_times_what_it_draws_over_the_turn():
    """The conveyor, whose lever's page reached 3.9× what it draws at 225° (eight details
    under a table of 19 forces), keeps every page within 3× at every 15° of the crank."""
    exercise = load_exercise(ROOT / "exercises" / "conveyor_sixbar.toml")
    turn = {}
    for angle in ANGLES:
        analysis = analyse(exercise, angle)
        turn[angle] = plan_files(analysis.plans, analysis.forces)
    found = _over_three(turn)
    assert not found, "\n".join(found[:20])


def test_the_press_lever_at_45_draws_its_crowd_as_details():
    """At φ₁ = 45° the labels round p, b, c, d of the press's lever made a region too wide
    for one detail, and none was drawn (42 figure problems): now the crowd is a detail, the
    points its detail of a detail cannot set apart are in the table beside the lever, and no
    mark or label is crowded outside them."""
    analysis = analyse(_exercise("press"), 45.0)
    lever = plan_files(analysis.plans, analysis.forces)["lever.svg"]
    assert "detail I:" in lever and detail_depth(lever) == 2
    rows = re.findall(r'<text class="table crowded"[^>]*>([^<]*)</text>', lever)
    assert {"b", "c", "d"} <= set(rows)
    problems = figure_problems(lever)
    assert not [problem for problem in problems if "(no detail)" in problem], problems
    assert not [problem for problem in problems if "overlaps" in problem], problems
    assert page_ratio(lever) <= 3.0
