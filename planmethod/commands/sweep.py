"""``planmethod sweep FILE --step DEG``: the full turn, as a table, a CSV and a plot."""

from __future__ import annotations

import argparse
import io


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


def csv_text(table) -> str:
    """The sweep table as CSV text (full precision, blank for undefined values)."""
    import numpy as np

    names = list(table)
    out = io.StringIO()
    out.write(",".join(names) + "\n")
    columns = [np.asarray(table[name], dtype=float) for name in names]
    for row in zip(*columns, strict=True):
        out.write(",".join("" if not np.isfinite(v) else repr(float(v)) for v in row) + "\n")
    return out.getvalue()


def summary(table, title: str) -> str:
    import numpy as np

    angles = table["angle"]
    lines = [f"{title} — {len(angles)} crank angles from {angles[0]:g}° to {angles[-1]:g}°",
             "", "  quantity            min      at φ      max      at φ"]
    for name, values in table.items():
        if name == "angle" or name.startswith(("x_", "y_", "vx_", "vy_", "ax_", "ay_")):
            continue
        values = np.asarray(values, dtype=float)
        finite = np.isfinite(values)
        if not finite.any():
            lines.append(f"  {name:<16} (undefined)")
            continue
        low = int(np.nanargmin(np.where(finite, values, np.nan)))
        high = int(np.nanargmax(np.where(finite, values, np.nan)))
        lines.append(f"  {name:<16} {values[low]:>10.5g} {angles[low]:>7g}° "
                     f"{values[high]:>10.5g} {angles[high]:>7g}°")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    from ..io import write_text_atomic
    from ..spec import load_exercise
    from ..sweep import sweep_table

    exercise = load_exercise(args.file)
    extra = None
    if args.forces:
        from ..forces import force_columns

        extra = force_columns(exercise)
    table = sweep_table(exercise, args.step, start=args.start, stop=args.stop, extra=extra)
    outputs = []
    csv = csv_text(table) if args.csv else None
    if args.plot:
        from ..render.plots import save_sweep_plot

        if args.forces:
            from ..render.force_plots import save_force_plot as save_sweep_plot
        save_sweep_plot(table, args.plot, title=exercise.mechanism.title)
        outputs.append(args.plot)
    if csv is not None:
        write_text_atomic(args.csv, csv)
        outputs.append(args.csv)
    print(summary(table, exercise.mechanism.title))
    if outputs:
        print("\nWrote " + ", ".join(outputs))
    return 0
