"""``planmethod workbook FILE -o PAGE.html``: one offline HTML page for a full turn of the crank.

Every frame (one crank angle every ``--step`` degrees) is solved here as ``planmethod solve
--angle A`` solves it: its drawings are the ones ``solve --svg`` writes, its readings are the
report's ``checks``, and its grading questions are those of the answer key ``planmethod
grade`` builds at that angle. The page (:mod:`planmethod.render.workbook`) only shows them.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

from ..errors import SpecError

#: default crank-angle step of a workbook (deg)
DEFAULT_STEP = 5.0

#: the drawings a frame shows, in this order, by file name of ``plan_files``
PANELS = ("position", "velocity", "acceleration", "lever")

#: what a question of the key keeps in the page (its ``text`` is not shown)
QUESTION_FIELDS = ("id", "value", "tolerance", "unit", "signed", "mistakes")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML)")
    parser.add_argument("-o", "--output", required=True, metavar="PAGE.html",
                        help="the HTML page to write")
    parser.add_argument("--step", type=float, default=DEFAULT_STEP, metavar="DEG",
                        help=f"crank-angle step in degrees (default {DEFAULT_STEP:g}; "
                             "1 gives 360 frames)")


def turn_angles(step: float, option: str = "--step") -> list[float]:
    """The crank angles of a full turn, 0 ≤ φ < 360, ``step`` degrees apart.

    >>> turn_angles(90)
    [0.0, 90.0, 180.0, 270.0]
    >>> turn_angles(0)
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: option --step: must be a number of degrees in (0, 180], got 0
    """
    if not (isinstance(step, int | float) and math.isfinite(step) and 0 < step <= 180):
        raise SpecError(f"must be a number of degrees in (0, 180], got {step:g}",
                        key=f"option {option}")
    count = math.ceil(360.0 / step - 1e-9)
    return [round(float(number * step), 9) for number in range(count)]


def exercise_variant(exercise):
    """The variant whose key ``planmethod grade`` builds for this exercise file (the file's
    own ``[grading]`` table), or a variant with default grading settings for an exercise
    that has no file."""
    from ..grading.templates import Variant, draw_variant, load_template

    if exercise.source:
        variant = draw_variant(load_template(exercise.source))
        return replace(variant, exercise=exercise)
    return Variant("1", 0, 0, {}, {}, exercise)


def frame_data(analysis, variant, files: dict[str, str]) -> dict[str, Any]:
    """One frame of the page as plain data (see :func:`planmethod.render.workbook.
    workbook_html`)."""
    from ..grading.keys import build_key

    drawings = {name.removesuffix(".svg"): text for name, text in files.items()}
    readings = [[check.analytic, check.plan] for check in analysis.checks]
    steps = {}
    if analysis.plans is not None:
        for name in ("velocity", "acceleration"):
            plan = getattr(analysis.plans, name)
            if plan is not None:
                steps[name] = [[step.number, step.text, step.action] for step in plan.steps]
    key = build_key(replace(variant, exercise=analysis.exercise))
    questions = [{field: question[field] for field in QUESTION_FIELDS}
                 for question in key["questions"]]
    return {"drawings": drawings, "readings": readings, "steps": steps,
            "questions": questions, "tolerance_source": key["precision_mm"]}


def build_workbook(exercise, step: float = DEFAULT_STEP, *,
                   progress: Callable[[int, int], None] | None = None) -> str:
    """The workbook page of ``exercise`` (an :class:`~planmethod.model.Exercise`) as HTML.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> page = build_workbook(load_exercise("exercises/compressor_slider_crank.toml"), 120)
    >>> page.count('data-quantity="'), 'id="angle"' in page
    (7, True)
    """
    from ..render.figures import plan_files
    from ..render.workbook import curve_chart, workbook_html
    from ..report import analyse
    from ..vocabulary import quantity

    angles = turn_angles(step)
    variant = exercise_variant(exercise)
    frames, analyses = [], []
    for number, angle in enumerate(angles):
        analysis = analyse(exercise, angle)
        files = plan_files(analysis.plans, forces=analysis.forces) if analysis.plans else {}
        frames.append(frame_data(analysis, variant, files))
        analyses.append(analysis)
        if progress is not None:
            progress(number + 1, len(angles))
    first = analyses[0]
    quantities = [{"name": check.quantity, "symbol": quantity(check.quantity).symbol,
                   "subscript": quantity(check.quantity).subscript, "unit": check.unit}
                  for check in first.checks]
    panels = [name for name in PANELS if name in frames[0]["drawings"]]
    panels += [name for name in frames[0]["drawings"] if name not in panels]
    charts = turn_charts(angles, analyses)
    precision = first.exercise.plan.precision_mm
    notes = [f"{len(angles)} positions, every {step:g}°; drawings by planmethod, "
             f"drafting precision {precision:g} mm" if precision else
             f"{len(angles)} positions, every {step:g}°; drawings by planmethod, exact "
             "construction",
             f"practice mode grades as `planmethod grade` does: tolerances from a drafting "
             f"precision of {frames[0]['tolerance_source']:g} mm (each tolerance is shown)"]
    return workbook_html(exercise.mechanism.title, angles, panels, frames, quantities,
                         charts=[curve_chart(angles, curves, title=title, unit=unit)
                                 for title, unit, curves in charts], notes=notes)


def turn_charts(angles: Sequence[float], analyses: Sequence) -> list[tuple[str, str, dict]]:
    """The full-turn curves: speeds, accelerations, angular velocities and accelerations of
    the checks, and the balancing moment when forces are computed."""
    import numpy as np

    from ..vocabulary import quantity

    titles = {"v": "velocities", "a": "accelerations", "omega": "angular velocities",
              "epsilon": "angular accelerations"}
    charts: dict[str, tuple[str, str, dict]] = {}
    for index, check in enumerate(analyses[0].checks):
        kind = check.quantity.partition("_")[0]
        if kind not in titles:
            continue
        curves = charts.setdefault(kind, (titles[kind], check.unit, {}))[2]
        curves[quantity(check.quantity).text] = [analysis.checks[index].analytic
                                                 for analysis in analyses]
    out = list(charts.values())
    if analyses[0].forces is not None:
        out.append(("balancing moment", "N·m", {"M_b": [
            float(np.ravel(analysis.forces.balancing_moment)[0]) for analysis in analyses]}))
    return out


def run(args: argparse.Namespace) -> int:
    import sys
    from pathlib import Path

    from ..io import write_text_atomic
    from ..spec import load_exercise

    if Path(args.output).suffix.lower() not in (".html", ".htm"):
        raise SpecError(f"the page must be an .html file, got {args.output!r}",
                        key="option -o")
    turn_angles(args.step)
    exercise = load_exercise(args.file)

    def progress(done: int, total: int) -> None:
        if sys.stderr.isatty():
            print(f"\rframe {done}/{total}", end="" if done < total else "\n",
                  file=sys.stderr)

    page = build_workbook(exercise, args.step, progress=progress)
    write_text_atomic(args.output, page)
    print(f"Wrote {args.output} ({len(page.encode('utf-8')) / 1e6:.2f} MB)")
    return 0
