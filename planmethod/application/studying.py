"""The parameter study of a four-bar's reactions (M. A. Jobborova, M. O'. Xakimova and Sh. A.
Kulturayeva, "Study of the load on kinematic pairs of a four-bar linkage mechanism"): the
rocker weight G4, the crank speed ω1 and the resisting moment Mc stepped one at a time
around a base case, the largest reaction of each pair over a full turn tabulated, the paper's
conclusions checked against the numbers (:mod:`planmethod.forces.study` computes them).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from ..errors import SpecError
from ..words import message, number_text, render

__all__ = ["MAX_GRID", "StudyRequest", "StudyResult", "check_study", "csv_text", "study",
           "table_text"]

#: the most values a study takes per parameter (each is a full-turn force analysis)
MAX_GRID = 200


@dataclass(frozen=True, slots=True)
class StudyRequest:
    """A study: the values of each parameter (N, rad/s, N·m), the base case (default the
    file's), the rocker (default the link of the first ``[[load]]`` moment), the crank-angle
    step of each turn, and the CSV and plot to write if given."""

    weights: tuple[float, ...] = (20.0, 40.0, 60.0, 80.0, 100.0)
    omegas: tuple[float, ...] = (10.0, 20.0, 30.0, 40.0, 50.0)
    moments: tuple[float, ...] = (80.0, 100.0, 120.0, 140.0, 160.0)
    base_weight: float | None = None
    base_omega: float | None = None
    base_moment: float | None = None
    rocker: str | None = None
    step: float = 2.0
    csv: str | None = None
    plot: str | None = None


@dataclass(frozen=True, slots=True)
class StudyResult:
    """A study done: its tables as a course prints them, and the files written."""

    table: str
    written: tuple[str, ...]


def check_study(request: StudyRequest) -> None:
    """Refuse a step that is no number of degrees in (0, 90], or a plot in a format that
    cannot be written, before any work."""
    if not (math.isfinite(request.step) and 0 < request.step <= 90):
        raise SpecError(message("--step must be a number of degrees in (0, 90], got {step}",
                                step=request.step))
    if request.plot:
        from ..render.plots import plot_format

        plot_format(request.plot)


def table_text(study, names: Mapping[str, str] | None = None,
               rocker: str | None = None) -> str:
    """The study as a course prints it: one table per parameter, then the conclusions;
    ``names`` are the pairs' reactions as the course writes them (R₀₁ for the pair A),
    ``rocker`` the rocker in words (link 3 (CD)); in the language spoken."""
    from ..vocabulary import shown_title

    names = names or {}
    lines = [render(message("{title} — largest reactions over a full turn (N) and |M_b| "
                            "(N·m)", title=shown_title(study.title))),
             render(message("base case: {base}; the rocker is {rocker}",
                            base=study.base_text(), rocker=rocker or study.rocker)), ""]
    header = "".join(f"{names.get(pair, 'R_' + pair):>11}" for pair in study.pairs)
    header += f"{'|M_b|':>11}"
    for parameter in study.parameters:
        lines.append(f"{parameter.label} ({parameter.unit})".ljust(28) + header)
        for i, value in enumerate(parameter.values):
            row = "".join(number_text(study.maxima[parameter.name][pair][i], ">11.1f")
                          for pair in study.pairs)
            row += number_text(study.balancing[parameter.name][i], ">11.2f")
            lines.append(f"  {number_text(value, '<26g')}" + row)
        change = "".join(number_text(100 * study.relative_change(parameter.name, pair),
                                     ">10.1f") + "%" for pair in study.pairs)
        lines.append(("  " + render(message("change over the range"))).ljust(28) + change)
        lines.append("")
    lines.append(render(message("The conclusions of Jobborova et al. against these numbers:")))
    for number, (statement, confirmed, evidence) in enumerate(study.conclusions(names),
                                                              start=1):
        verdict = (message("the data support it") if confirmed
                   else message("the data do not support it"))
        lines.append("  " + render(message("{number}. \"{statement}\": {verdict} — {evidence}",
                                           number=number, statement=statement,
                                           verdict=verdict, evidence=evidence)))
    lines.append("  " + render(message("(the tables above are the figures that show it; "
                                       "--plot draws them)")))
    return "\n".join(lines)


def _printed_names(exercise, study) -> tuple[dict[str, str], str]:
    """Each pair's reaction as the course writes it (R₀₁) and the rocker in words (link 3
    (CD)), from the exercise's own solution at its angle."""
    from ..render.notation import ForceNotation
    from ..report import analyse

    notation = ForceNotation(analyse(exercise, plans=False).forces.solution)
    return ({pair: notation.plain(f"R_{pair}") for pair in study.pairs},
            notation.link_name(study.rocker))


def csv_text(study) -> str:
    """The study as CSV: one line per parameter value, the largest reaction of each pair and
    |M_b| (full precision)."""
    from ..io import csv_text as spreadsheet_csv

    rows: list[list] = [["parameter", "value", *(f"R_{p}_max" for p in study.pairs),
                         "M_b_max"]]
    for parameter in study.parameters:
        for i, value in enumerate(parameter.values):
            rows.append([parameter.name, float(value),
                         *(float(study.maxima[parameter.name][p][i]) for p in study.pairs),
                         float(study.balancing[parameter.name][i])])
    return spreadsheet_csv(rows)


def _based(exercise, request: StudyRequest):
    """The exercise with the request's base case (weight, ω1, Mc) where it gives one."""
    from ..forces.study import moment_load, study_variant

    if all(value is None for value in (request.base_weight, request.base_omega,
                                       request.base_moment)):
        return exercise
    index, load = moment_load(exercise, request.rocker)
    mechanism = exercise.mechanism
    if load.link not in mechanism.masses or not mechanism.gravity:
        raise SpecError(message("the study needs [gravity] and a mass on the rocker"),
                        file=exercise.source)
    base = {"weight": request.base_weight or mechanism.masses[load.link].m * mechanism.gravity,
            "omega": request.base_omega or mechanism.drive.omega,
            "moment": request.base_moment or abs(load.moment)}
    if any(not (math.isfinite(v) and v > 0) for v in base.values()):
        raise SpecError(message("base values must be positive, got {base}", base=str(base)))
    return study_variant(exercise, load.link, index, **base)


def study(exercise, request: StudyRequest) -> StudyResult:
    """Run the study ``request`` describes on ``exercise``; the plot and the CSV are written
    together, or neither."""
    from ..forces.study import run_study
    from ..io import output_set

    check_study(request)
    exercise = _based(exercise, request)
    found = run_study(exercise, rocker=request.rocker, weights=request.weights,
                      omegas=request.omegas, moments=request.moments, step=request.step)
    with output_set() as outputs:   # the plot and the CSV together, or neither
        if request.plot:
            from ..render.plots import save_study_plot

            with outputs.writing(request.plot) as temporary:
                save_study_plot(found, temporary)
        if request.csv:
            outputs.text(request.csv, csv_text(found))
    written = tuple(path for path in (request.plot, request.csv) if path)
    return StudyResult(table_text(found, *_printed_names(exercise, found)), written)
