"""``planmethod study FILE``: the parameter study of a four-bar's reactions of M. A. Jobborova,
M. O'. Xakimova and Sh. A. Kulturayeva, "Study of the load on kinematic pairs of a four-bar linkage
mechanism".

The rocker weight G4, the crank speed ω1 and the resisting moment Mc on the rocker are stepped
one at a time over their ranges (default: the paper's 20…100 N, 10…50 rad/s, 80…160 N·m, step
20, 10, 20) around the base case of the exercise file (or ``--base-*``); for each value the full
turn is solved and the largest reaction of each pair is tabulated; the paper's two conclusions
are checked against the numbers. ``--plot`` draws the table, ``--csv`` writes it.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Mapping

from ..vocabulary import shown_title

#: the most values a study takes per parameter (each is a full-turn force analysis)
MAX_GRID = 200


def _range(text: str, limit: float = math.inf, unit: str = "") -> tuple[float, ...]:
    """``20:100:20`` (first:last:step, inclusive) or ``20,40,60``; each value finite and at
    most ``limit`` in magnitude."""
    try:
        if ":" in text:
            first, last, step = (float(part) for part in text.split(":"))
            if not (step > 0 and last >= first and math.isfinite(last - first)):
                raise ValueError
            count = round((last - first) / step)
            if count + 1 > MAX_GRID:
                raise argparse.ArgumentTypeError(
                    f"{text!r} gives {count + 1:.3g} values; at most {MAX_GRID} per parameter")
            values = tuple(first + step * i for i in range(count + 1))
        else:
            values = tuple(float(part) for part in text.split(",")[:MAX_GRID + 1])
            if len(values) > MAX_GRID:
                raise argparse.ArgumentTypeError(f"more than {MAX_GRID} values in {text[:40]!r}")
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected first:last:step or a comma list of numbers, got {text!r}") from None
    if not values or any(not math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected finite numbers, got {text!r}")
    largest = max(values, key=abs)
    if abs(largest) > limit:
        raise argparse.ArgumentTypeError(f"{largest:g} is beyond the limit: at most {limit:g} "
                                         f"{unit}in magnitude (as in an exercise file)")
    return values


def _within(limit_name: str, unit: str, *, grid: bool):
    """An argparse type: a range (``grid``) or one number, at most the exercise file's limit
    ``limit_name`` (:mod:`planmethod.spec`) in magnitude — the same table as the file's."""
    def parse(text: str):
        from .. import spec

        limit = getattr(spec, limit_name)
        if grid:
            return _range(text, limit, unit)
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
        if not math.isfinite(value) or abs(value) > limit:
            raise argparse.ArgumentTypeError(f"must be a finite number at most {limit:g} "
                                             f"{unit}in magnitude (as in an exercise file), "
                                             f"got {text!r}")
        return value
    parse.__name__ = "number" if not grid else "range"
    return parse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML) of the four-bar (base case)")
    parser.add_argument("--rocker", metavar="LINK",
                        help="the link carrying the resisting moment (default: the link of the "
                             "first [[load]] moment)")
    parser.add_argument("--weights", type=_within("MAX_MAGNITUDE", "N ", grid=True),
                        default="20:100:20", metavar="N",
                        help="rocker weights G4, N (default 20:100:20)")
    parser.add_argument("--omegas", type=_within("MAX_OMEGA", "rad/s ", grid=True),
                        default="10:50:10", metavar="RAD/S",
                        help="crank speeds ω1, rad/s (default 10:50:10)")
    parser.add_argument("--moments", type=_within("MAX_MAGNITUDE", "N·m ", grid=True),
                        default="80:160:20", metavar="N·M",
                        help="resisting moments Mc, N·m (default 80:160:20)")
    parser.add_argument("--base-weight", type=_within("MAX_MAGNITUDE", "N ", grid=False),
                        metavar="N",
                        help="base rocker weight (default: the file's)")
    parser.add_argument("--base-omega", type=_within("MAX_OMEGA", "rad/s ", grid=False),
                        metavar="RAD/S",
                        help="base crank speed (default: the file's)")
    parser.add_argument("--base-moment", type=_within("MAX_MAGNITUDE", "N·m ", grid=False),
                        metavar="N·M",
                        help="base resisting moment (default: the file's)")
    parser.add_argument("--step", type=float, default=2.0, metavar="DEG",
                        help="crank-angle step of each full turn (default 2)")
    parser.add_argument("--csv", metavar="FILE", help="write the table as CSV")
    parser.add_argument("--plot", metavar="FILE", help="write the plots (PNG/SVG/PDF)")


def table_text(study, names: Mapping[str, str] | None = None,
               rocker: str | None = None) -> str:
    """The study as a course prints it: one table per parameter, then the conclusions;
    ``names`` are the pairs' reactions as the course writes them (R₀₁ for the pair A),
    ``rocker`` the rocker in words (link 3 (CD))."""
    from ..words import render

    names = names or {}
    base = ", ".join(render(value) for value in study.base_values())
    lines = [f"{shown_title(study.title)} — largest reactions over a full turn (N) and |M_b| (N·m)",
             f"base case: {base}; the rocker is {rocker or study.rocker}", ""]
    header = "".join(f"{names.get(pair, 'R_' + pair):>11}" for pair in study.pairs)
    header += f"{'|M_b|':>11}"
    for parameter in study.parameters:
        lines.append(f"{render(parameter.label)} ({render(parameter.unit)})".ljust(28) + header)
        for i, value in enumerate(parameter.values):
            row = "".join(f"{study.maxima[parameter.name][pair][i]:>11.1f}"
                          for pair in study.pairs)
            row += f"{study.balancing[parameter.name][i]:>11.2f}"
            lines.append(f"  {value:<26g}" + row)
        change = "".join(f"{100 * study.relative_change(parameter.name, pair):>10.1f}%"
                         for pair in study.pairs)
        lines.append("  change over the range".ljust(28) + change)
        lines.append("")
    lines.append("The conclusions of Jobborova et al. against these numbers:")
    for number, (statement, confirmed, evidence) in enumerate(study.conclusions(names),
                                                              start=1):
        verdict = ("the data support it" if confirmed
                   else "the data do not support it")
        lines.append(f"  {number}. \"{render(statement)}\": {verdict} — {render(evidence)}")
    lines.append("  (the tables above are the figures that show it; --plot draws them)")
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


def run(args: argparse.Namespace) -> int:
    from ..errors import SpecError
    from ..forces.study import moment_load, run_study, study_variant
    from ..io import output_set
    from ..spec import load_exercise

    if not (math.isfinite(args.step) and 0 < args.step <= 90):
        raise SpecError(f"--step must be a number of degrees in (0, 90], got {args.step}")
    if args.plot:  # before any work: an unsupported format is refused at once
        from ..render.plots import plot_format

        plot_format(args.plot)
    exercise = load_exercise(args.file)
    if any(value is not None for value in (args.base_weight, args.base_omega,
                                           args.base_moment)):
        index, load = moment_load(exercise, args.rocker)
        mechanism = exercise.mechanism
        if load.link not in mechanism.masses or not mechanism.gravity:
            raise SpecError("the study needs [gravity] and a mass on the rocker",
                            file=exercise.source)
        base = {"weight": args.base_weight or mechanism.masses[load.link].m * mechanism.gravity,
                "omega": args.base_omega or mechanism.drive.omega,
                "moment": args.base_moment or abs(load.moment)}
        if any(not (math.isfinite(v) and v > 0) for v in base.values()):
            raise SpecError(f"base values must be positive, got {base}")
        exercise = study_variant(exercise, load.link, index, **base)
    study = run_study(exercise, rocker=args.rocker, weights=args.weights, omegas=args.omegas,
                      moments=args.moments, step=args.step)
    with output_set() as outputs:   # the plot and the CSV together, or neither
        if args.plot:
            from ..render.plots import save_study_plot

            with outputs.writing(args.plot) as temporary:
                save_study_plot(study, temporary)
        if args.csv:
            outputs.text(args.csv, csv_text(study))
    written = [path for path in (args.plot, args.csv) if path]
    print(table_text(study, *_printed_names(exercise, study)))
    if written:
        print("\nWrote " + ", ".join(written))
    return 0
