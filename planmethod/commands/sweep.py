"""``planmethod sweep FILE --step DEG``: the full turn, as a table, a CSV and a plot."""

from __future__ import annotations

import argparse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML)")
    parser.add_argument("--step", type=float, default=1.0, metavar="DEG",
                        help="crank-angle step in degrees (default 1)")
    parser.add_argument("--from", dest="start", type=float, default=0.0, metavar="DEG",
                        help="first crank angle (default 0)")
    parser.add_argument("--to", dest="stop", type=float, default=360.0, metavar="DEG",
                        help="sweep up to (not including) this angle (default 360)")
    parser.add_argument("--csv", metavar="FILE", help="write every column to a CSV file")
    parser.add_argument("--plot", metavar="FILE", help="write the curves as PNG/SVG/PDF")
    parser.add_argument("--forces", action="store_true",
                        help="add the reactions per pair and the balancing moment")


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


def run(args: argparse.Namespace) -> int:
    import contextlib

    from ..io import csv_text, output_set
    from ..spec import load_exercise
    from ..sweep import Extremes, csv_rows, sweep_chunks, sweep_table

    if args.plot:  # before any work: an unsupported format is refused at once
        from ..render.plots import plot_format

        plot_format(args.plot)
    exercise = load_exercise(args.file)
    extra = None
    if args.forces:
        from ..forces import force_columns

        extra = force_columns(exercise)
    sweep = {"step": args.step, "start": args.start, "stop": args.stop, "extra": extra}
    # a plot needs every column at once; otherwise the sweep streams chunk by chunk, so a
    # sweep of millions of angles runs in bounded memory
    table = sweep_table(exercise, **sweep) if args.plot else None
    chunks = [table] if table is not None else sweep_chunks(exercise, **sweep)
    extremes = Extremes()
    with output_set() as outputs:   # the plot and the CSV together, or neither
        if args.plot:
            with outputs.writing(args.plot) as temporary:
                _save_plot(exercise, table, temporary, forces=args.forces)
        with contextlib.ExitStack() as stack:   # a failed write names the CSV, not the exercise
            handle = (stack.enter_context(stack.enter_context(outputs.writing(args.csv))
                                          .open("w", encoding="utf-8"))
                      if args.csv else None)   # streamed: a sweep of millions of rows fits
            for chunk in chunks:
                if handle is not None:
                    if not extremes.count:
                        handle.write(csv_text([list(chunk)]))   # header text; rows: numbers
                    handle.writelines(csv_rows(chunk))
                extremes.feed(chunk)
    written = ([args.plot] if args.plot else []) + ([args.csv] if args.csv else [])
    print(extremes.describe(exercise.mechanism.title, **_printed_names(exercise, args.forces)))
    if written:
        print("\nWrote " + ", ".join(written))
    return 0
