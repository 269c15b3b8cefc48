"""``planmethod grade KEY ANSWERS``: score numeric answers (CSV or JSON, one row per student),
drawn plans (``--drawing`` SVG or JSON) and phone photos of plan sheets (``--photo``) against a
key, with feedback (:mod:`planmethod.application.grades`).

A photo that cannot be read is refused in one line on the standard error, after the others are
graded and written: the command then ends with exit status 2."""

from __future__ import annotations

import argparse

from ..arguments import said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    file = render(message("FILE", context="metavar"))
    parser.add_argument("key", nargs="?", metavar=render(message("key", context="metavar")),
                        help=said(message("key.json, keys.json (or its folder), or an "
                                          "exercise file")))
    parser.add_argument("answers", nargs="?",
                        metavar=render(message("answers", context="metavar")),
                        help=said(message("answers: CSV or JSON, one row per student")))
    parser.add_argument("--key", dest="key_file", metavar=file,
                        help=said(message("the key, as KEY (then a file given after the "
                                          "options is ANSWERS)")))
    parser.add_argument("--photo", nargs="+", action="extend", default=[],
                        metavar=render(message("IMAGE", context="metavar")),
                        help=said(message("phone photos of plan sheets printed by `planmethod "
                                          "booklet`: each is graded against its student's key "
                                          "(the sheet's QR code says whose); a photo that "
                                          "cannot be read is refused in one line")))
    parser.add_argument("--marked", metavar=render(message("DIR", context="metavar")),
                        help=said(message("write each graded photo into DIR, its points marked "
                                          "green or red, with the sentences under it (for the "
                                          "student)")))
    parser.add_argument("--jobs", type=int, metavar=render(message("N", context="metavar")),
                        help=said(message("grade the photos in N worker processes (default: by "
                                          "their number, at most the CPUs this process may "
                                          "use)")))
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
    from ..errors import SpecError

    if args.key_file is not None:
        if args.answers is not None:
            raise SpecError(message("give the key once: as KEY or as --key FILE"))
        args.key, args.answers = args.key_file, args.key
    if args.key is None:
        raise SpecError(message("give the key: KEY or --key FILE"))
    request = GradeRequest(args.key, args.answers, tuple(args.drawing), args.plan,
                           args.student, tuple(args.photo), args.jobs, bool(args.marked))
    graded = grade(request)
    lines = graded_lines(graded, feedback=args.feedback or "full", quiet=args.quiet)
    write_grades(graded, GradeOutputs(args.json, args.csv, args.report, args.gradescope,
                                      args.feedback, args.marked), request)
    if lines:
        sys.stdout.write("\n".join(lines) + "\n")
    for refused in graded.refused:
        print(render(message("planmethod: error: {problem}", problem=refused.reason)),
              file=sys.stderr)
    return 2 if graded.refused else 0
