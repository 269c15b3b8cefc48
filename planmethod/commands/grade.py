"""``planmethod grade KEY ANSWERS``: score numeric answers (CSV or JSON, one row per student)
and drawn plans (``--drawing`` SVG or JSON) against a key, with feedback
(:mod:`planmethod.application.grades`)."""

from __future__ import annotations

import argparse

from ..arguments import said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    file = render(message("FILE", context="metavar"))
    parser.add_argument("key", metavar=render(message("key", context="metavar")),
                        help=said(message("key.json, keys.json (or its folder), or an "
                                          "exercise file")))
    parser.add_argument("answers", nargs="?",
                        metavar=render(message("answers", context="metavar")),
                        help=said(message("answers: CSV or JSON, one row per student")))
    parser.add_argument("--drawing", action="append", default=[], metavar=file,
                        help=said(message("a drawn plan (SVG or JSON of points in mm); may be "
                                          "repeated; one downloaded from the workbook page is "
                                          "graded at its own crank angle")))
    parser.add_argument("--plan", choices=("velocity", "acceleration"),
                        help=said(message("which plan the drawing is (default: told by its "
                                          "pole label)")))
    parser.add_argument("--student", metavar=render(message("STUDENT", context="metavar")),
                        help=said(message("grade as this student (picks the variant's key; "
                                          "for a single submission)")))
    parser.add_argument("--json", metavar=file,
                        help=said(message("write every result as JSON")))
    parser.add_argument("--csv", metavar=file, help=said(message("write a CSV gradebook")))
    parser.add_argument("--gradescope", metavar=file,
                        help=said(message("write Gradescope's results.json (one student)")))
    parser.add_argument("--feedback", choices=("full", "hints", "score"),
                        help=said(message("what each question's feedback shows: full (the "
                                          "right values), hints (the mistake and which way the "
                                          "answer is off, never the right value) or score "
                                          "(points only); default: full on the screen and in "
                                          "--json, hints in --gradescope (the student sees "
                                          "it)")))
    parser.add_argument("--report", metavar=render(message("DIR", context="metavar")),
                        help=said(message("write the class report into DIR: questions.csv "
                                          "(mean score, share right, most common mistake per "
                                          "question), mistakes.csv and class_report.png "
                                          "(which step the class gets wrong)")))
    parser.add_argument("--quiet", action="store_true",
                        help=said(message("print the totals only")))


def run(args: argparse.Namespace) -> int:
    import sys

    from ..application.grades import (
        GradeOutputs,
        GradeRequest,
        grade,
        graded_lines,
        write_grades,
    )

    request = GradeRequest(args.key, args.answers, tuple(args.drawing), args.plan,
                           args.student)
    graded = grade(request)
    lines = graded_lines(graded, feedback=args.feedback or "full", quiet=args.quiet)
    write_grades(graded, GradeOutputs(args.json, args.csv, args.report, args.gradescope,
                                      args.feedback), request)
    sys.stdout.write("\n".join(lines) + "\n")
    return 0
