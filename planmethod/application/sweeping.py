"""The full turn of an exercise: its extremes as a table, every column as CSV, its curves as
a plot — the CSV streamed chunk by chunk, so that a sweep of millions of angles runs in
bounded memory.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
>>> done = sweep(exercise, SweepRequest(step=30.0))
>>> done.summary.splitlines()[0], done.written
('Compressor slider-crank (Abduvaliev & Abduxoshimov) — 12 crank angles from 0° to 330°', ())
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass

__all__ = ["SweepRequest", "SweepResult", "check_plot", "sweep"]


@dataclass(frozen=True, slots=True)
class SweepRequest:
    """A sweep: crank angles ``start`` … ``stop`` (not included) ``step`` degrees apart, with
    the reactions and the balancing moment if ``forces``; the CSV of every column and the
    plot of the curves written to ``csv`` and ``plot`` if given."""

    step: float = 1.0
    start: float = 0.0
    stop: float = 360.0
    forces: bool = False
    csv: str | None = None
    plot: str | None = None


@dataclass(frozen=True, slots=True)
class SweepResult:
    """A sweep done: its extremes as a course prints them, and the files written."""

    summary: str
    written: tuple[str, ...]


def check_plot(request: SweepRequest) -> None:
    """Refuse a plot in a format that cannot be written, before any work."""
    if request.plot:
        from ..render.plots import plot_format

        plot_format(request.plot)


def _save_plot(exercise, table, path, *, forces: bool) -> None:
    """The sweep's curves (or, with forces, the reactions and the balancing moment) into
    ``path``."""
    import numpy as np

    from ..numbering import course_numbers
    from ..render.plots import save_sweep_plot

    numbers = course_numbers(exercise.mechanism)
    crank = numbers[exercise.mechanism.drive.link]
    if forces:
        from ..render.notation import ForceNotation
        from ..render.plots import save_force_plot
        from ..report import analyse

        solved = analyse(exercise).forces    # the position the exercise solves, marked
        marks = ([(float(solved.angle), float(np.ravel(solved.balancing_moment)[0]))]
                 if solved is not None else [])
        names = {}
        if solved is not None:   # each pair's reaction as a course writes it: R₁₂
            notation = ForceNotation(solved.solution)
            names = {key: notation.plain(f"R_{key}") for key in solved.solution.reactions}
        save_force_plot(table, path, title=exercise.mechanism.title, marks=marks,
                        names=names, crank=crank)
    else:
        save_sweep_plot(table, path, title=exercise.mechanism.title, numbers=numbers,
                        crank=crank)


def _printed_names(exercise, forces: bool) -> dict:
    """What the printed table names its columns by (the CSV's header keeps the column
    names): each quantity, reaction and link angle in the course's notation, and the crank
    angle's symbol with the crank's number."""
    from ..numbering import course_numbers
    from ..vocabulary import column_text, numbered

    numbers = course_numbers(exercise.mechanism)
    phi = numbered("φ", numbers[exercise.mechanism.drive.link])
    if forces:
        from ..render.notation import ForceNotation
        from ..report import analyse

        solved = analyse(exercise, plans=False).forces
        if solved is not None:
            return {"names": ForceNotation(solved.solution).column, "phi": phi}
    return {"names": lambda name: column_text(name, numbers), "phi": phi}


def sweep(exercise, request: SweepRequest) -> SweepResult:
    """Sweep ``exercise`` as ``request`` says; the plot and the CSV are written together, or
    neither."""
    from ..io import csv_text, output_set
    from ..sweep import Extremes, csv_rows, sweep_chunks, sweep_table
    from .workbook import limits_noted

    check_plot(request)
    extra = None
    if request.forces:
        from ..forces import force_columns

        extra = force_columns(exercise)
    turn = {"step": request.step, "start": request.start, "stop": request.stop,
            "extra": extra}
    extremes = Extremes()
    # a limit met on the way is noted (--from, --to); the plot and the CSV together, or neither
    with limits_noted(), output_set() as outputs:
        # a plot needs every column at once; otherwise the sweep streams chunk by chunk
        table = sweep_table(exercise, **turn) if request.plot else None
        chunks = [table] if table is not None else sweep_chunks(exercise, **turn)
        if request.plot:
            with outputs.writing(request.plot) as temporary:
                _save_plot(exercise, table, temporary, forces=request.forces)
        with contextlib.ExitStack() as stack:   # a failed write names the CSV, not the exercise
            handle = (stack.enter_context(stack.enter_context(outputs.writing(request.csv))
                                          .open("w", encoding="utf-8"))
                      if request.csv else None)   # streamed: a sweep of millions of rows fits
            for chunk in chunks:
                if handle is not None:
                    if not extremes.count:
                        handle.write(csv_text([list(chunk)]))   # header text; rows: numbers
                    handle.writelines(csv_rows(chunk))
                extremes.feed(chunk)
    written = tuple(path for path in (request.plot, request.csv) if path)
    summary = extremes.describe(exercise.mechanism.title,
                                **_printed_names(exercise, request.forces))
    return SweepResult(summary, written)
