"""``planmethod workbook FILE -o PAGE.html``: one offline HTML page for a full turn of the crank,
or of the angles ``--from`` … ``--to`` (:mod:`planmethod.application.workbook` builds it)."""

from __future__ import annotations

import argparse

from ..application.workbook import DEFAULT_STEP
from ..arguments import EXERCISE_FILE, add_angle_range, said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(EXERCISE_FILE))
    parser.add_argument("-o", "--output", required=True,
                        metavar=render(message("PAGE.html", context="metavar")),
                        help=said(message("the HTML page to write")))
    parser.add_argument("--step", type=float, default=DEFAULT_STEP,
                        metavar=render(message("DEG", context="metavar")),
                        help=said(message("crank-angle step in degrees (default {step:g}; 1 "
                                          "gives 360 frames)", step=DEFAULT_STEP)))
    add_angle_range(parser)
    parser.add_argument("--jobs", type=int, metavar=render(message("N", context="metavar")),
                        help=said(message("worker processes, at most the CPUs this process "
                                          "may use (default: every CPU, at least 12 frames "
                                          "each)")))


def _progress(phase: str, done: int, total: int) -> None:
    """The frames solved so far, on a terminal's standard error."""
    import sys

    if sys.stderr.isatty():
        print("\r" + render(message("frame {done}/{total}", done=done, total=total)),
              end="" if done < total else "\n", file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..application.tasks import Watch
    from ..application.workbook import build_workbook, turn_angles
    from ..application.workers import worker_count
    from ..errors import SpecError
    from ..io import write_text_atomic
    from ..spec import load_exercise
    from .output import say

    if Path(args.output).suffix.lower() not in (".html", ".htm"):
        raise SpecError(message("the page must be an .html file, got {path!r}",
                                path=args.output), key="option -o")
    span = (args.start, args.stop)
    worker_count(args.jobs, len(turn_angles(args.step, span=span)))   # before any work
    exercise = load_exercise(args.file)
    page = build_workbook(exercise, args.step, jobs=args.jobs, watch=Watch(_progress),
                          span=span)
    write_text_atomic(args.output, page)
    say(message("Wrote {file} ({size:.2f} MB)", file=args.output,
                size=len(page.encode("utf-8")) / 1e6))
    return 0
