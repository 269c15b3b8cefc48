"""The plans' figures and sentences under the pseudo language: every word of them comes from
the catalogue (planmethod.testing.pseudo marks each translated template ⟦…⟧; an English word
of the templates outside the marks is a sentence that bypassed them)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod.plans import draw_plans
from planmethod.render.figures import plan_files
from planmethod.render.plan_words import plan_dict, scale_lines
from planmethod.spec import load_exercise
from planmethod.testing.pseudo import (
    PSEUDO,
    message_words,
    pseudo_catalogue,
    texts_of_svg,
    unmarked_words,
)
from planmethod.words import language, render, speaking

ROOT = Path(__file__).resolve().parent.parent
#: two shipped exercises whose figures hold every kind of the plans' words: guides, Coriolis
#: points and enlarged details (the shaper), a path's radius of curvature (the offset slider
#: crank); each drawn at a drafting precision, its intersections flagged
EXERCISES = ("shaper_sixbar", "offset_slider_crank")


@pytest.fixture(scope="module")
def words() -> set[str]:
    """The English words of the package's templates."""
    return message_words()


@pytest.fixture(scope="module")
def pseudo(tmp_path_factory):
    """Speak the pseudo language (its catalogue written for the package's templates)."""
    folder = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(folder)
    patch = pytest.MonkeyPatch()
    patch.setenv(language.LOCALE_ENVIRONMENT, str(folder))
    language.catalogue.cache_clear()
    with speaking(PSEUDO):
        yield
    patch.undo()
    language.catalogue.cache_clear()


def _plans(name: str):
    exercise = load_exercise(ROOT / "exercises" / f"{name}.toml")
    settings = dataclasses.replace(exercise.plan, precision_mm=0.5, min_angle_deg=89.9)
    return exercise, draw_plans(exercise, settings=settings)


def _names(exercise) -> list[str]:
    """What is no word of the messages: the exercise's points, links and title."""
    mechanism = exercise.mechanism
    points = {point for link in mechanism.links.values() for point in link.points}
    return [*points, *mechanism.links, mechanism.title]


@pytest.mark.parametrize("name", EXERCISES)
def test_every_figure_of_the_plans_says_only_catalogue_words(pseudo, words, name):
    """The position plan, the velocity and acceleration plans and the lever: titles, legends,
    scales, notes, details' captions, flags and the labels' words, every one marked."""
    exercise, plans = _plans(name)
    assert plans.flags                       # the flags are drawn (and said) too
    names = _names(exercise)
    for file, svg in plan_files(plans).items():
        shown = texts_of_svg(svg)
        assert any("⟦" in text for text in shown), file
        found = [(text, unmarked_words(text, words, names)) for text in shown]
        assert [pair for pair in found if pair[1]] == [], file


@pytest.mark.parametrize("name", EXERCISES)
def test_every_step_flag_and_scale_line_says_only_catalogue_words(pseudo, words, name):
    """The JSON report's step sentences and flags, and the scale lines, under the pseudo
    language: each one marked whole."""
    exercise, plans = _plans(name)
    names = _names(exercise)
    for plan in (plans.velocity, plans.acceleration):
        written = plan_dict(plan)
        for text in [step["text"] for step in written["steps"]] + written["flags"]:
            assert text.startswith("⟦") and text.endswith("⟧"), text
            assert unmarked_words(text, words, names) == [], text
    lines = [render(line) for line in scale_lines(plans.scales)]
    assert any(line.startswith("⟦μφv") for line in lines)
