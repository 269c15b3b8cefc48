"""``planmethod solve FILE``: structure, scales, plans and a check table at one crank angle
(:mod:`planmethod.application.solving`)."""

from __future__ import annotations

import argparse

from ..arguments import EXERCISE_FILE, said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(EXERCISE_FILE))
    parser.add_argument("--angle", type=float,
                        metavar=render(message("DEG", context="metavar")),
                        help=said(message("crank angle in degrees (default: drive.angle of the "
                                          "file); the assembly chosen at drive.angle is "
                                          "followed there, as a sweep follows it")))
    parser.add_argument("--svg", metavar=render(message("DIR", context="metavar")),
                        help=said(message("write the drawings into DIR as SVG: the position, "
                                          "velocity, acceleration and lever plans (and the "
                                          "force drawings with forces)")))
    parser.add_argument("--json", action="store_true",
                        help=said(message("print the JSON report")))
    parser.add_argument("--precision", type=float,
                        metavar=render(message("MM", context="metavar")),
                        help=said(message("drafting precision in mm (overrides [plan] "
                                          "precision_mm)")))
    parser.add_argument("--png", action="store_true",
                        help=said(message("with --svg, also write PNG renderings (needs "
                                          "cairosvg)")))


def run(args: argparse.Namespace) -> int:
    import json
    import sys

    from ..application.solving import (
        check_choices,
        figures,
        pngs,
        report_text,
        solve_at,
        unwritten,
    )
    from ..io import output_set
    from ..report import report_dict
    from ..spec import load_exercise
    from .output import say, wrote

    check_choices(args.angle, args.precision)   # before the file is read
    exercise = load_exercise(args.file)
    analysis = solve_at(exercise, args.angle, precision_mm=args.precision)
    files = figures(analysis) if args.svg else {}
    images = pngs(files) if args.svg and args.png else {}
    written: list[str] = []
    if args.svg:  # everything is computed: now write, every drawing or none
        with output_set() as outputs:
            written = [str(path) for path in outputs.files(args.svg, {**files, **images})]
    if args.json:
        json.dump(report_dict(analysis), sys.stdout, ensure_ascii=False, indent=2,
                  allow_nan=False)
        print()
        return 0
    say(report_text(analysis))
    wrote(written)
    for why in unwritten(analysis) if args.svg else ():
        say(why)
    return 0
