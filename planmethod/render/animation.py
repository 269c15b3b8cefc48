"""The full turn as one animation for slides: an animated SVG, a GIF or an MP4.

* :func:`animated_svg` puts the project's own drawings of every frame side by side and shows
  one frame at a time with a CSS animation (no script; it plays in browsers and in slide
  programs that show SVG). It is drawn on the one canvas (:mod:`planmethod.render.canvas`),
  which nests each drawing whole.
* :func:`raster_frames` draws the mechanism and its plans from the plans' data with matplotlib
  (``Figure`` and ``FigureCanvasAgg``, never pyplot), with axes fixed over the whole turn so that
  nothing jumps; :func:`save_gif` writes them through Pillow and :func:`save_mp4` through
  ffmpeg.

Examples
--------
>>> from planmethod.render.canvas import Canvas
>>> def disc(radius):
...     canvas = Canvas()
...     canvas.circle((0.0, 0.0), radius, fill="#000000")
...     return canvas.svg("a disc")
>>> svg = animated_svg([[disc(1.0)], [disc(2.0)]], seconds=2)
>>> svg.count('class="frame"'), "@keyframes" in svg
(2, True)
"""

from __future__ import annotations

import subprocess
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import PlanmethodError
from ..vocabulary import PlanKind, numbered
from ..words import message, render
from .canvas import Canvas, SvgFigure
from .style import num

__all__ = ["animated_svg", "raster_frames", "save_gif", "save_mp4"]

#: the size (px) of one drawing in an animated SVG
CELL_WIDTH, CELL_HEIGHT = 520.0, 480.0
#: the title of each plan's panel in a raster frame
_PLAN_TITLES = {PlanKind.VELOCITY: message("velocity plan"),
                PlanKind.ACCELERATION: message("acceleration plan")}


def animated_svg(frames: Sequence[Sequence[SvgFigure]], *, seconds: float = 6.0,
                 title: str = "") -> str:
    """One SVG that shows ``frames`` (each a row of drawings) in turn, looping, one full
    turn in ``seconds``."""
    count = len(frames)
    columns = max(len(row) for row in frames)
    width, height = CELL_WIDTH * columns, CELL_HEIGHT
    share = 100.0 / count
    duration = seconds / count
    page = Canvas()
    page.style_sheet(f".frame{{visibility:hidden;animation:planmethod-turn {num(seconds)}s "
                     f"step-end infinite}}@keyframes planmethod-turn{{0%{{visibility:visible}}"
                     f"{share:.6g}%{{visibility:hidden}}100%{{visibility:hidden}}}}")
    for number, row in enumerate(frames):
        page.nest([(figure, (CELL_WIDTH * column, 0.0), (CELL_WIDTH, CELL_HEIGHT))
                   for column, figure in enumerate(row)],
                  css="frame", style=f"animation-delay:{number * duration:.6g}s")
    return page.svg(title, view=(0.0, 0.0, width, height)).svg


def _limits(points: Sequence[Sequence[float]]) -> tuple[float, float, float, float]:
    xs = [p[0] for p in points] or [0.0]
    ys = [p[1] for p in points] or [0.0]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    pad = 0.08 * max(x1 - x0, y1 - y0, 1.0)
    return x0 - pad, x1 + pad, y0 - pad, y1 + pad


def _plan_points(plan) -> dict[str, tuple[float, float]]:
    return {name: (float(xy[0]), float(xy[1])) for name, xy in plan.points_mm.items()}


def raster_frames(plans_of_frames: Sequence[Any], *, dpi: int = 100) -> list[Any]:
    """The frames as RGB images (``PIL.Image``): the mechanism, the velocity plan and the
    acceleration plan of each frame's :class:`~planmethod.plans.Plans`, axes fixed over the
    turn."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from PIL import Image

    kinds = [PlanKind.POSITION, PlanKind.VELOCITY] + ([PlanKind.ACCELERATION] if all(
        plans.acceleration is not None for plans in plans_of_frames) else [])
    every: dict[str, list] = {kind: [] for kind in kinds}
    for plans in plans_of_frames:
        every["position"] += list(_plan_points(plans.position).values())
        for kind in kinds[1:]:
            every[kind] += list(_plan_points(getattr(plans, kind)).values())
    limits = {kind: _limits(points) for kind, points in every.items()}
    figure = Figure(figsize=(4.0 * len(kinds), 4.0), dpi=dpi)
    canvas = FigureCanvasAgg(figure)
    axes = figure.subplots(1, len(kinds))
    figure.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.92, wspace=0.04)
    images = []
    for plans in plans_of_frames:
        for ax, kind in zip(axes, kinds, strict=True):
            ax.clear()
            x0, x1, y0, y1 = limits[kind]
            ax.set_xlim(x0, x1)
            ax.set_ylim(y0, y1)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            if kind == PlanKind.POSITION:
                _draw_mechanism(ax, plans.position)
                crank = plans.position.numbers.get(plans.position.drive[0], 1)
                ax.set_title(render(message("{phi} = {angle:g}°", phi=numbered("φ", crank),
                                            angle=plans.position.angle)), fontsize=10)
            else:
                _draw_plan(ax, getattr(plans, kind))
                ax.set_title(render(_PLAN_TITLES[kind]), fontsize=10)
        canvas.draw()
        images.append(Image.frombuffer("RGBA", canvas.get_width_height(),
                                       canvas.buffer_rgba(), "raw", "RGBA", 0, 1)
                      .convert("RGB"))
    return images


def _draw_mechanism(ax, position) -> None:
    where = _plan_points(position)
    for names in position.links.values():
        points = [where[name] for name in names if name in where]
        if len(points) >= 2:
            ax.plot([p[0] for p in points], [p[1] for p in points], color="#1f5fbf", lw=2.4,
                    solid_capstyle="round")
    for name, (x, y) in where.items():
        marker = "^" if name in position.pivots else "o"
        ax.plot([x], [y], marker=marker, color="#000000", ms=5 if marker == "o" else 8)
        ax.annotate(name, (x, y), xytext=(4, 4), textcoords="offset points", fontsize=9,
                    style="italic")


def _draw_plan(ax, plan) -> None:
    where = _plan_points(plan)
    pole = where.get(plan.pole, (0.0, 0.0))
    for name, (x, y) in where.items():
        if name == plan.pole:
            continue
        image = name.isalnum() and name[:1].islower()
        if image and (abs(x - pole[0]) + abs(y - pole[1])) > 1e-9:
            ax.annotate("", xy=(x, y), xytext=pole,
                        arrowprops={"arrowstyle": "-|>", "color": "#000000", "lw": 1.4})
            ax.annotate(name, (x, y), xytext=(4, 4), textcoords="offset points", fontsize=9,
                        style="italic")
        else:
            ax.plot([x], [y], marker=".", color="#7b3fa0", ms=4)
    ax.plot([pole[0]], [pole[1]], marker="o", color="#000000", ms=5)
    ax.annotate(plan.pole, pole, xytext=(4, -10), textcoords="offset points", fontsize=9,
                style="italic")


def save_gif(images: Sequence[Any], path: str | Path, *, seconds: float = 6.0) -> None:
    """Write the images as a looping GIF (Pillow), one turn in ``seconds``."""
    frame_ms = max(20, round(1000.0 * seconds / len(images)))
    first, *rest = images
    first.save(path, format="GIF", save_all=True, append_images=rest, duration=frame_ms,
               loop=0, optimize=True)


def save_mp4(images: Sequence[Any], path: str | Path, ffmpeg: str, *,
             seconds: float = 6.0) -> None:
    """Write the images as an H.264 MP4 by piping raw frames to ``ffmpeg``."""
    width, height = images[0].size
    rate = max(1.0, len(images) / seconds)
    command = [ffmpeg, "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24",
               "-s", f"{width}x{height}", "-r", f"{rate:g}", "-i", "-",
               "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p",
               "-f", "mp4", str(path)]
    data = b"".join(image.tobytes() for image in images)
    done = subprocess.run(command, input=data, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, check=False)
    if done.returncode != 0:   # a full disk, a file too large: ffmpeg's last line, one line
        said = done.stderr.decode("utf-8", "replace").strip().splitlines()
        if said:
            raise PlanmethodError(message("ffmpeg could not write the animation ({said})",
                                          said=said[-1][:200]), file=str(path))
        raise PlanmethodError(message("ffmpeg could not write the animation (exit status "
                                      "{status})", status=done.returncode), file=str(path))
