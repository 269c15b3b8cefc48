"""``planmethod animate FILE -o OUT.(svg|gif|mp4)``: the full turn as one animation.

The format is told by the suffix: ``.svg`` (the project's drawings, animated with CSS),
``.gif`` (matplotlib frames through Pillow) or ``.mp4`` (the same frames through ffmpeg, which
must be installed). An unknown suffix, or ``.mp4`` without ffmpeg, is refused before any work.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ..errors import SpecError
from ..vocabulary import shown_title

#: suffix → format
FORMATS = {".svg": "svg", ".gif": "gif", ".mp4": "mp4"}

#: default crank-angle step of an animation (deg)
DEFAULT_STEP = 5.0


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML)")
    parser.add_argument("-o", "--output", required=True, metavar="OUT",
                        help="the animation: OUT.svg, OUT.gif or OUT.mp4")
    parser.add_argument("--step", type=float, default=DEFAULT_STEP, metavar="DEG",
                        help=f"crank-angle step in degrees (default {DEFAULT_STEP:g})")
    parser.add_argument("--seconds", type=float, default=6.0, metavar="S",
                        help="duration of one full turn (default 6)")


def animation_format(path: str) -> str:
    """The format of an animation file, by its suffix.

    >>> animation_format("turn.GIF")
    'gif'
    >>> animation_format("turn.avi")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: option -o: cannot write 'turn.avi': the animation must be .svg, ...
    """
    form = FORMATS.get(Path(path).suffix.lower())
    if form is None:
        raise SpecError(f"cannot write {path!r}: the animation must be .svg, .gif or .mp4",
                        key="option -o")
    return form


def run(args: argparse.Namespace) -> int:
    import math
    import shutil

    from ..io import atomic_path, write_text_atomic
    from ..report import analyse
    from ..spec import load_exercise
    from .workbook import turn_angles, turn_order

    form = animation_format(args.output)
    ffmpeg = shutil.which("ffmpeg") if form == "mp4" else None
    if form == "mp4" and ffmpeg is None:
        raise SpecError(f"cannot write {args.output!r}: MP4 needs ffmpeg on the PATH "
                        "(write .gif or .svg instead)", key="option -o")
    if not (math.isfinite(args.seconds) and args.seconds > 0):
        raise SpecError(f"must be a positive number of seconds, got {args.seconds:g}",
                        key="option --seconds")
    exercise = load_exercise(args.file)
    drive = exercise.mechanism.drive
    angles = turn_order(turn_angles(args.step, start=drive.angle), drive.angle, drive.omega)
    analyses = [analyse(exercise, angle) for angle in angles]
    if any(analysis.plans is None for analysis in analyses):
        raise SpecError("this mechanism's plans are not drawn (a higher group): nothing to "
                        "animate", file=args.file)
    title = shown_title(exercise.mechanism.title)
    if form == "svg":
        from ..render.animation import animated_svg
        from ..render.steady import steady_views
        from ..render.svg import plan_drawing, position_drawing

        views = steady_views(exercise, angles)     # one zoom and one page per panel
        frames = []
        for analysis in analyses:
            plans = analysis.plans
            row = [position_drawing(plans.position, plans=plans, view=views["position"]),
                   plan_drawing(plans.velocity, details=False, view=views["velocity"])]
            if plans.acceleration is not None:
                row.append(plan_drawing(plans.acceleration, details=False,
                                        view=views["acceleration"]))
            frames.append(row)
        write_text_atomic(args.output, animated_svg(frames, seconds=args.seconds,
                                                    title=f"{title} — a full turn"))
    else:
        from ..render.animation import raster_frames, save_gif, save_mp4

        images = raster_frames([analysis.plans for analysis in analyses])
        with atomic_path(args.output) as temporary:
            if form == "gif":
                save_gif(images, temporary, seconds=args.seconds)
            else:
                save_mp4(images, temporary, ffmpeg, seconds=args.seconds)
    print(f"Wrote {args.output} ({len(angles)} frames, one turn in {args.seconds:g} s)")
    return 0
