"""The full turn of an exercise (or the angles a crank that cannot turn fully reaches) as one
animation: ``.svg`` (the project's drawings, animated with CSS), ``.gif`` (the same drawings
through CairoSVG and Pillow; matplotlib's plainer frames without CairoSVG) or ``.mp4`` (the same
frames through ffmpeg, which must be installed). An unknown suffix, or ``.mp4`` without ffmpeg,
is refused before any work (:func:`check_animation`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import SpecError
from ..words import message, render
from .workbook import FULL_TURN

__all__ = ["DEFAULT_STEP", "FORMATS", "AnimationRequest", "animate", "animation_format",
           "check_animation"]

#: suffix → format
FORMATS = {".svg": "svg", ".gif": "gif", ".mp4": "mp4"}

#: default crank-angle step of an animation (deg)
DEFAULT_STEP = 5.0


@dataclass(frozen=True, slots=True)
class AnimationRequest:
    """An animation: the file to write (its suffix tells the format), the crank-angle step
    (deg), how long one full turn lasts (s) and the crank angles it shows (``span``: from the
    first up to, not including, the second; deg)."""

    output: str
    step: float = DEFAULT_STEP
    seconds: float = 6.0
    span: tuple[float, float] = FULL_TURN


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
        raise SpecError(message("cannot write {path!r}: the animation must be .svg, .gif or "
                                ".mp4", path=path), key="option -o")
    return form


def check_animation(request: AnimationRequest) -> str | None:
    """Refuse what cannot be written (an unknown suffix, MP4 without ffmpeg, a duration
    that is no positive number of seconds) before any work; ffmpeg's path for an MP4."""
    import shutil

    form = animation_format(request.output)
    ffmpeg = shutil.which("ffmpeg") if form == "mp4" else None
    if form == "mp4" and ffmpeg is None:
        raise SpecError(message("cannot write {path!r}: MP4 needs ffmpeg on the PATH (write "
                                ".gif or .svg instead)", path=request.output), key="option -o")
    if not (math.isfinite(request.seconds) and request.seconds > 0):
        raise SpecError(message("must be a positive number of seconds, got {seconds:g}",
                                seconds=request.seconds), key="option --seconds")
    return ffmpeg


def _drawings(exercise, angles, analyses) -> list[list]:
    """One row of drawings per angle: the position, velocity and acceleration plans, each
    panel at one zoom over the turn (the frames of every form of the animation)."""
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
    return frames


def _animated_svg(exercise, angles, analyses, request: AnimationRequest) -> None:
    """The animation as SVG: the frames of :func:`_drawings`, one at a time."""
    from ..io import write_text_atomic
    from ..render.animation import animated_svg
    from ..vocabulary import shown_title

    title = render(message("{title} — a full turn",
                           title=shown_title(exercise.mechanism.title)))
    write_text_atomic(request.output, animated_svg(_drawings(exercise, angles, analyses),
                                                   seconds=request.seconds, title=title))


def _images(exercise, angles, analyses) -> list:
    """The frames as images: the drawings of :func:`_drawings` where CairoSVG is installed,
    else the mechanism and plans drawn by matplotlib."""
    import importlib.util

    from ..render.animation import raster_frames, rendered_frames

    if importlib.util.find_spec("cairosvg") is not None:
        return rendered_frames(_drawings(exercise, angles, analyses))
    return raster_frames([analysis.plans for analysis in analyses])


def animate(exercise, request: AnimationRequest) -> int:
    """Write the animation ``request`` asks for; the number of frames."""
    from ..io import atomic_path
    from ..report import analyse
    from .workbook import limits_noted, turn_angles, turn_order

    ffmpeg = check_animation(request)
    form = animation_format(request.output)
    drive = exercise.mechanism.drive
    angles = turn_order(turn_angles(request.step, start=drive.angle, span=request.span),
                        drive.angle, drive.omega)
    with limits_noted():
        analyses = [analyse(exercise, angle) for angle in angles]
    if any(analysis.plans is None for analysis in analyses):
        raise SpecError(message("this mechanism's plans are not drawn (a higher group): "
                                "nothing to animate"), file=exercise.source)
    if form == "svg":
        _animated_svg(exercise, angles, analyses, request)
        return len(angles)
    from ..render.animation import save_gif, save_mp4

    images = _images(exercise, angles, analyses)
    with atomic_path(request.output) as temporary:
        if form == "gif":
            save_gif(images, temporary, seconds=request.seconds)
        else:
            save_mp4(images, temporary, ffmpeg, seconds=request.seconds)
    return len(angles)
