"""The kinetostatics, the report and the sweeps speak through the catalogue: under the
pseudo-language ``qps`` (every template marked ⟦…⟧, planmethod.testing.pseudo) no English word
of the messages shows outside the marks in the force figures and Zhukovsky's lever, the text
report of ``solve``, the sweep's table and its plots — names, symbols and numbers aside.

Text that other areas make and that is not converted yet is left out by name, each with the
module it comes from:

* the plans' own legend and the enlarged details' captions in a figure (render/svg.py
  ``plan_legend``, render/details.py): runs that the plans' figures show too, and the runs
  ``detail I: …``;
* a link named in words, ``link 2 (BC)`` (vocabulary.link_text, where ``# words:
  vocabulary`` marks the call);
* the units of a sweep's plot and of the check table
  (vocabulary.QUANTITY_KINDS);
* the lines of ``solve``'s report before the check table (the application's own headers,
  structure.describe, Scales.describe).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("babel", reason="the pseudo catalogue is written with Babel (test extra)")

from planmethod.testing.pseudo import PSEUDO, message_words, pseudo_catalogue, unmarked_words
from planmethod.vocabulary import QUANTITY_KINDS
from planmethod.words import language, render, speaking

ROOT = Path(__file__).resolve().parent.parent
EXERCISES = ("fourbar_forces", "combined_force_slider_crank")
#: captions of other areas in a figure (see the module docstring)
FOREIGN_RUNS = re.compile(r"^(detail [IVXLC]+: |link \d+ \()")
#: the units the vocabulary gives, shown in tables and on axes (front-words converts them)
UNITS = sorted({kind.unit for kind in QUANTITY_KINDS.values()}, key=len, reverse=True)
#: the derivatives' symbols (ds/dt, d²s/dt²): notation, not words, though a template's words
#: name them too (only these: a one-letter symbol taken out would cut words of the text)
SYMBOLS = sorted({kind.symbol for kind in QUANTITY_KINDS.values() if "/" in kind.symbol},
                 key=len, reverse=True)


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    found = tmp_path_factory.mktemp("pseudo")
    pseudo_catalogue(found)
    return found


@pytest.fixture
def qps(folder, monkeypatch):
    """Speak the pseudo-language in this process."""
    monkeypatch.setenv(language.LOCALE_ENVIRONMENT, str(folder))
    language.catalogue.cache_clear()
    try:
        with speaking(PSEUDO):
            yield
    finally:
        language.catalogue.cache_clear()


def _names(exercise) -> list[str]:
    """What is no word of the messages: the exercise's title, points and links."""
    mechanism = exercise.mechanism
    points = {point for link in mechanism.links.values() for point in link.points}
    return [mechanism.title, *mechanism.links, *points]


def _texts(svg: str) -> list[str]:
    """Each text element of an SVG as a person reads it: its runs (a subscript's tspan
    among them) joined."""
    from defusedxml import ElementTree

    return ["".join(element.itertext()).strip()
            for element in ElementTree.fromstring(svg).iter()
            if element.tag.rpartition("}")[2] in ("text", "title")
            and "".join(element.itertext()).strip()]


def _unmarked(texts, names, foreign=frozenset()) -> list[tuple[str, list[str]]]:
    words = message_words()
    return [(text, found) for text in texts
            if text not in foreign and not FOREIGN_RUNS.match(text)
            and (found := unmarked_words(text, words, names))]


@pytest.mark.parametrize("name", EXERCISES)
def test_force_figures_are_marked(qps, name):
    """The force polygons, the combined force, Zhukovsky's lever and the loaded mechanism:
    titles, legends, notes, the lever's table, the loaded mechanism's table."""
    from planmethod.render.figures import plan_files
    from planmethod.render.force_svg import force_files
    from planmethod.report import analyse
    from planmethod.spec import load_exercise

    exercise = load_exercise(ROOT / "exercises" / f"{name}.toml")
    analysis = analyse(exercise)
    files = force_files(analysis.forces, analysis.plans)
    assert "lever.svg" in files and "loaded.svg" in files
    assert ("combined_force.svg" in files) == bool(exercise.mechanism.gravity)
    plans = plan_files(analysis.plans)            # the plans' own figures: another area's
    foreign = {text for svg in plans.values() for text in _texts(svg)}
    for file, svg in files.items():
        texts = _texts(svg)
        assert any("⟦" in text for text in texts), file
        assert not _unmarked(texts, _names(exercise), foreign), file


@pytest.mark.parametrize("name", [*EXERCISES, "compressor_slider_crank"])
def test_the_solve_report_is_marked(qps, name):
    """The check table, the book's values, the flags and the kinetostatics of ``solve``."""
    from planmethod.application.solving import report_text
    from planmethod.render.report_text import (
        check_lines,
        flag_lines,
        force_lines,
        published_lines,
    )
    from planmethod.report import analyse
    from planmethod.spec import load_exercise

    exercise = load_exercise(ROOT / "exercises" / f"{name}.toml")
    analysis = analyse(exercise)
    lines = [*check_lines(analysis), *published_lines(analysis), *flag_lines(analysis.flags)]
    if analysis.forces is not None:
        lines += force_lines(analysis.forces)
    report = report_text(analysis)
    assert "\n".join(check_lines(analysis)[1:]) in report
    if analysis.forces is not None:
        assert "\n".join(force_lines(analysis.forces)) in report
    if exercise.published:
        assert any("⟦Published values" in line for line in lines)
    assert not _unmarked(lines, [*_names(exercise), *UNITS, *SYMBOLS])


def _environment(folder: Path) -> dict[str, str]:
    return {**os.environ, language.LOCALE_ENVIRONMENT: str(folder),
            language.ENVIRONMENT: PSEUDO}


def test_the_force_sweep_and_its_plot_are_marked(folder, tmp_path):
    """``sweep --forces --plot``: the printed table (its headings, the balancing moment's and
    the friction's columns) and the plot's titles, axes, legends and notes (its text kept as
    SVG text)."""
    from planmethod.spec import load_exercise

    exercise = load_exercise(ROOT / "exercises" / "conveyor_sixbar.toml")
    plot = tmp_path / "forces.svg"
    shown = subprocess.run([sys.executable, "-m", "planmethod", "sweep",
                            "exercises/conveyor_sixbar.toml", "--forces", "--step", "30",
                            "--plot", str(plot)], cwd=ROOT, env=_environment(folder),
                           capture_output=True, text=True, check=True).stdout
    table = shown.split("\nWrote ")[0].splitlines()
    assert "⟦friction iterations⟧" in shown
    assert not _unmarked(table, _names(exercise))
    texts = _texts(plot.read_text(encoding="utf-8"))
    assert any("⟦" in text for text in texts)
    assert not _unmarked(texts, [*_names(exercise), "Rx", "Ry"])


def test_the_sweep_plot_is_marked(qps, monkeypatch):
    """``sweep --plot``: the plot's text as matplotlib draws it (its Text artists: the file
    keeps them as paths), the panels' units aside (vocabulary.QUANTITY_KINDS); the panels'
    titles are rendered when drawn, in the language spoken then."""
    from matplotlib.text import Text

    from planmethod.numbering import course_numbers
    from planmethod.render import plots
    from planmethod.spec import load_exercise
    from planmethod.sweep import sweep_table

    drawn = []
    monkeypatch.setattr(plots, "_save", lambda figure, path, form: drawn.append(figure))
    exercise = load_exercise(ROOT / "exercises" / "offset_slider_crank.toml")
    table = sweep_table(exercise, 30.0)
    table["M_extra"] = np.ones_like(table["angle"])          # a column of no panel's
    plots.save_sweep_plot(table, "curves.png", title=exercise.mechanism.title,
                          numbers=course_numbers(exercise.mechanism))
    texts = [text.get_text() for figure in drawn for text in figure.findobj(Text)
             if text.get_text().strip()]
    panels = [render(title) for title, _, _ in plots.panels(table)]
    assert "⟦other columns⟧" in panels
    assert any(text.startswith("⟦crank angle") for text in texts)
    assert "⟦speed of points |v|⟧" in texts          # a panel's title, rendered when drawn
    assert not _unmarked(texts, [*_names(exercise), *UNITS, *SYMBOLS, "M_extra"])
