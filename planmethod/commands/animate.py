"""``planmethod animate FILE -o OUT.(svg|gif|mp4)``: the full turn (or the angles ``--from`` …
``--to``) as one animation (:mod:`planmethod.application.animating`; the format is told by the
suffix)."""

from __future__ import annotations

import argparse

from ..application.animating import DEFAULT_STEP
from ..arguments import EXERCISE_FILE, add_angle_range, said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(EXERCISE_FILE))
    parser.add_argument("-o", "--output", required=True,
                        metavar=render(message("OUT", context="metavar")),
                        help=said(message("the animation: OUT.svg, OUT.gif or OUT.mp4")))
    parser.add_argument("--step", type=float, default=DEFAULT_STEP,
                        metavar=render(message("DEG", context="metavar")),
                        help=said(message("crank-angle step in degrees (default {step:g})",
                                          step=DEFAULT_STEP)))
    add_angle_range(parser)
    parser.add_argument("--seconds", type=float, default=6.0,
                        metavar=render(message("S", context="metavar")),
                        help=said(message("duration of one full turn (default 6)")))


def run(args: argparse.Namespace) -> int:
    from ..application.animating import AnimationRequest, animate, check_animation
    from ..spec import load_exercise
    from .output import say

    request = AnimationRequest(args.output, step=args.step, seconds=args.seconds,
                               span=(args.start, args.stop))
    check_animation(request)   # before any work
    frames = animate(load_exercise(args.file), request)
    say(message("Wrote {file} ({frames} frames, one turn in {seconds:g} s)",
                file=args.output, frames=frames, seconds=args.seconds))
    return 0
