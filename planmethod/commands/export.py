"""``planmethod export KEY --format gradescope|prairielearn|moodle|csv``: the keys of a run
as an LMS import (:mod:`planmethod.application.exporting` says what a folder it writes is,
and when it may be replaced)."""

from __future__ import annotations

import argparse

from ..arguments import said
from ..words import message, render

#: the formats of ``--format`` (:data:`planmethod.application.exporting.FORMATS`)
FORMATS = ("gradescope", "prairielearn", "moodle", "csv")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("key", metavar=render(message("key", context="metavar")),
                        help=said(message("keys.json (or its folder), a key.json, or an "
                                          "exercise file")))
    parser.add_argument("--format", required=True, choices=FORMATS,
                        help=said(message("gradescope: an autograder; prairielearn: a "
                                          "question; moodle: a quiz (XML); csv: a gradebook "
                                          "of --answers")))
    parser.add_argument("--out", required=True,
                        metavar=render(message("PATH", context="metavar")),
                        help=said(message("output file (moodle: quiz.xml; csv: gradebook.csv) "
                                          "or folder (gradescope, prairielearn)")))
    parser.add_argument("--answers", metavar=render(message("FILE", context="metavar")),
                        help=said(message("graded answers for csv (a gradebook) and "
                                          "gradescope (results.json of one student)")))
    parser.add_argument("--student", metavar=render(message("STUDENT", context="metavar")),
                        help=said(message("with --format gradescope --answers: the student")))
    parser.add_argument("--feedback", choices=("full", "hints", "score"), default="hints",
                        help=said(message("what students see of each question (gradescope): "
                                          "full (the right values), hints (default: the "
                                          "mistake and which way the answer is off) or score "
                                          "(points only)")))
    parser.add_argument("--slug", default="planmethod",
                        metavar=render(message("SLUG", context="metavar")),
                        help=said(message("PrairieLearn question folder name (default "
                                          "planmethod)")))


def run(args: argparse.Namespace) -> int:
    from ..application.exporting import ExportRequest, export_files, run_folder, write_export
    from ..runs import earlier_run
    from .output import note, say

    request = ExportRequest(args.key, args.format, args.out, args.answers, args.student,
                            args.feedback, args.slug)
    folder = run_folder(request)
    # before any work: refuse a folder that holds what no export wrote, or find its earlier run
    earlier = earlier_run(*folder) if folder is not None else None
    written, changed = write_export(request, export_files(request), earlier)
    if changed:
        note(changed)
    out = folder[0] if folder is not None else args.out
    say(message("Wrote {files}", files=written) if len(written) <= 4 else
        message("Wrote {count} files in {folder}", count=len(written), folder=str(out)))
    return 0
