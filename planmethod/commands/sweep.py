"""``planmethod sweep FILE --step DEG``: the full turn, as a table, a CSV and a plot
(:mod:`planmethod.application.sweeping`)."""

from __future__ import annotations

import argparse

from ..arguments import EXERCISE_FILE, said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    degrees = render(message("DEG", context="metavar"))
    file = render(message("FILE", context="metavar"))
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(EXERCISE_FILE))
    parser.add_argument("--step", type=float, default=1.0, metavar=degrees,
                        help=said(message("crank-angle step in degrees (default 1)")))
    parser.add_argument("--from", dest="start", type=float, default=0.0, metavar=degrees,
                        help=said(message("first crank angle (default 0)")))
    parser.add_argument("--to", dest="stop", type=float, default=360.0, metavar=degrees,
                        help=said(message("sweep up to (not including) this angle (default "
                                          "360)")))
    parser.add_argument("--csv", metavar=file,
                        help=said(message("write every column to a CSV file")))
    parser.add_argument("--plot", metavar=file,
                        help=said(message("write the curves as PNG/SVG/PDF")))
    parser.add_argument("--forces", action="store_true",
                        help=said(message("add the reactions per pair and the balancing "
                                          "moment")))


def run(args: argparse.Namespace) -> int:
    from ..application.sweeping import SweepRequest, check_plot, sweep
    from ..spec import load_exercise
    from .output import say, wrote

    request = SweepRequest(step=args.step, start=args.start, stop=args.stop,
                           forces=args.forces, csv=args.csv, plot=args.plot)
    check_plot(request)   # before any work: an unsupported format is refused at once
    done = sweep(load_exercise(args.file), request)
    say(done.summary)
    wrote(done.written)
    return 0
