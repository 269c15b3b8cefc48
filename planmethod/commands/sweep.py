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


def run(args: argparse.Namespace) -> int:
    import contextlib

    import numpy as np

    from ..io import atomic_path
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
    if args.plot:  # first: a bad plot file name then leaves no CSV behind
        from ..numbering import course_numbers
        from ..render.plots import save_sweep_plot

        numbers = course_numbers(exercise.mechanism)

        if args.forces:
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
            save_force_plot(table, args.plot, title=exercise.mechanism.title, marks=marks,
                            names=names, crank=numbers[exercise.mechanism.drive.link])
        else:
            save_sweep_plot(table, args.plot, title=exercise.mechanism.title, numbers=numbers,
                            crank=numbers[exercise.mechanism.drive.link])
    extremes = Extremes()
    with contextlib.ExitStack() as stack:
        handle = None
        if args.csv:  # written to a temporary file, renamed into place only when complete
            temporary = stack.enter_context(atomic_path(args.csv))
            handle = stack.enter_context(temporary.open("w", encoding="utf-8"))
        for chunk in chunks:
            if handle is not None:
                if not extremes.count:
                    handle.write(",".join(chunk) + "\n")
                handle.writelines(csv_rows(chunk))
            extremes.feed(chunk)
        if handle is not None:
            handle.close()
    outputs = ([args.plot] if args.plot else []) + ([args.csv] if args.csv else [])
    print(extremes.describe(exercise.mechanism.title))
    if outputs:
        print("\nWrote " + ", ".join(outputs))
    return 0
