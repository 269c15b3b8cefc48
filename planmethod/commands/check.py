"""``planmethod check FILE COORDS.csv``: test printed point coordinates against the mechanism
(:mod:`planmethod.application.checking` says how). Exit status: 0 when every row passes, 1
when something is flagged, 2 for bad input."""

from __future__ import annotations

import argparse

from ..arguments import EXERCISE_FILE, said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(EXERCISE_FILE))
    parser.add_argument("coordinates", metavar=render(message("coordinates",
                                                              context="metavar")),
                        help=said(message("CSV of point coordinates per crank angle")))
    parser.add_argument("--tolerance", type=float, default=2.0,
                        metavar=render(message("MM", context="metavar")),
                        help=said(message("allowed error of a length or a position, mm "
                                          "(default 2)")))
    parser.add_argument("--json", action="store_true",
                        help=said(message("print the findings as JSON")))


def run(args: argparse.Namespace) -> int:
    import json
    import sys

    from ..application.checking import check_table, check_tolerance, text_report
    from ..spec import load_exercise
    from .output import say

    check_tolerance(args.tolerance)   # before any work
    exercise = load_exercise(args.file)
    checked = check_table(exercise, args.coordinates, args.tolerance)
    if args.json:
        json.dump(checked.as_dict(), sys.stdout, ensure_ascii=False, indent=2, allow_nan=False)
        print()
    else:
        from ..numbering import course_numbers

        numbers = course_numbers(exercise.mechanism)
        say(text_report(checked.title, list(checked.rows), numbers,
                        numbers[exercise.mechanism.drive.link]))
    return 1 if checked.flagged else 0
