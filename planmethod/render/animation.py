"""The full turn as one animation for slides: an animated SVG, a GIF or an MP4.

* :func:`animated_svg` puts the project's own drawings of every frame side by side and shows
  one frame at a time with a CSS animation (no script; it plays in browsers and in slide
  programs that show SVG). It is drawn on the one canvas (:mod:`planmethod.render.canvas`),
  which nests each drawing whole.
* :func:`rendered_frames` draws the same drawings, frame by frame, as images through CairoSVG
  (the ``png`` extra); without it :func:`raster_frames` draws the mechanism and its plans from
  the plans' data with matplotlib (``Figure`` and ``FigureCanvasAgg``, never pyplot), with axes
  fixed over the whole turn so that nothing jumps. :func:`save_gif` writes the images through
  Pillow and :func:`save_mp4` through ffmpeg.

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

import math
import subprocess
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import PlanmethodError
from ..plans.construction import is_image
from ..vocabulary import PlanKind, numbered, point_text
from ..words import message, render
from .canvas import Canvas, SvgFigure
from .plan_words import label_text
from .style import num
from .svg import SAME_POINT_MM, coincident_groups

__all__ = ["animated_svg", "frame_svg", "raster_frames", "rendered_frames", "save_gif",
           "save_mp4"]

#: the height (px) of one drawing in an animation, and the width of one without a page size
CELL_WIDTH, CELL_HEIGHT = 520.0, 480.0
#: the title of each plan's panel in a raster frame
_PLAN_TITLES = {PlanKind.VELOCITY: message("velocity plan"),
                PlanKind.ACCELERATION: message("acceleration plan")}


def animated_svg(frames: Sequence[Sequence[SvgFigure]], *, seconds: float = 6.0,
                 title: str = "") -> str:
    """One SVG that shows ``frames`` (each a row of drawings) in turn, looping, one full
    turn in ``seconds``; each drawing as high as :data:`CELL_HEIGHT`, as wide as its page
    (:func:`_cells`: a steady page keeps its size over the turn)."""
    count = len(frames)
    cells = [_cells(row) for row in frames]
    width = max(corner[0] + size[0] for row in cells for _, corner, size in row)
    share = 100.0 / count
    duration = seconds / count
    page = Canvas()
    page.style_sheet(f".frame{{visibility:hidden;animation:planmethod-turn {num(seconds)}s "
                     f"step-end infinite}}@keyframes planmethod-turn{{0%{{visibility:visible}}"
                     f"{share:.6g}%{{visibility:hidden}}100%{{visibility:hidden}}}}")
    for number, row in enumerate(cells):
        page.nest(row, css="frame", style=f"animation-delay:{number * duration:.6g}s")
    return page.svg(title, view=(0.0, 0.0, width, CELL_HEIGHT)).svg


def _cells(row: Sequence[SvgFigure]) -> list[tuple[SvgFigure, tuple[float, float],
                                                   tuple[float, float]]]:
    """A row of drawings side by side, each :data:`CELL_HEIGHT` high and as wide as its
    page's proportions make it: (figure, corner, size) for :meth:`Canvas.nest`."""
    cells, left = [], 0.0
    for figure in row:
        _, _, width, height = figure.view
        size = (CELL_HEIGHT * width / height if height > 0 else CELL_WIDTH, CELL_HEIGHT)
        cells.append((figure, (left, 0.0), size))
        left += size[0]
    return cells


def frame_svg(row: Sequence[SvgFigure]) -> str:
    """One frame's drawings side by side as one SVG page (the cells of :func:`animated_svg`)."""
    cells = _cells(row)
    page = Canvas()
    page.nest(cells, css="frame")
    width = max(corner[0] + size[0] for _, corner, size in cells)
    return page.svg("", view=(0.0, 0.0, width, CELL_HEIGHT)).svg


def rendered_frames(frames: Sequence[Sequence[SvgFigure]]) -> list[Any]:
    """The frames (each a row of the project's own drawings, as :func:`animated_svg` shows
    them) as RGB images (``PIL.Image``), :data:`CELL_HEIGHT` px high, drawn by CairoSVG: the
    GIF and the MP4 show what the SVG shows, labels placed as every figure places them."""
    import io

    import cairosvg
    from PIL import Image

    images = []
    for row in frames:
        png = cairosvg.svg2png(bytestring=frame_svg(row).encode("utf-8"),
                               background_color="#ffffff")
        images.append(Image.open(io.BytesIO(png)).convert("RGB"))
    return images


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


#: the colours of a raster frame: links, fixed pivots and guides, construction points
_LINK, _INK, _GUIDE, _HELPER = "#1f5fbf", "#000000", "#777777", "#7b3fa0"


def _joined(where: dict[str, tuple[float, float]], text) -> list[tuple[str, tuple[float, float]]]:
    """Each place of ``where`` once, with the names of the points there joined by ≡ (a
    course writes O₂ ≡ E and p ≡ a ≡ d₀), ``text`` naming each point."""
    return [(" ≡ ".join(text(name) for name in names), where[names[0]])
            for names in coincident_groups(where, where, SAME_POINT_MM)]


def _draw_mechanism(ax, position) -> None:
    """The mechanism of a raster frame: its moving links as bars (the frame not), each guide
    as a thin line (a slot on a link through its points and the block's, a fixed guide across
    the panel), a block as a square, fixed pivots as triangles; its points named as the
    course writes them (O₁, O₂ ≡ E)."""
    where = _plan_points(position)
    frame = [link for link, number in position.numbers.items() if number == 0]
    for slide in position.slides:
        _draw_guide(ax, slide, where, position.links.get(slide["along"], ()),
                    slide["along"] in frame)
    for link, names in position.links.items():
        points = [where[name] for name in names if name in where]
        if link not in frame and len(points) >= 2:
            ax.plot([p[0] for p in points], [p[1] for p in points], color=_LINK, lw=2.4,
                    solid_capstyle="round")
    blocks = {slide["point"] for slide in position.slides}
    for name, (x, y) in where.items():
        marker = "^" if name in position.pivots else "s" if name in blocks else "o"
        ax.plot([x], [y], marker=marker, color=_INK, ms=5 if marker == "o" else 8,
                mfc="#ffffff" if marker == "s" else _INK)
    for text, xy in _joined(where, point_text):
        ax.annotate(text, xy, xytext=(4, 4), textcoords="offset points", fontsize=9,
                    style="italic")


def _draw_guide(ax, slide: dict, where: dict[str, tuple[float, float]],
                carriers: Sequence[str], fixed: bool) -> None:
    """A prismatic pair's guide: across the panel where it is fixed (a centre line), else
    along its link from the farthest of the link's points to past the block."""
    x, y = (float(value) for value in slide["through_mm"])
    angle = math.radians(float(slide["direction_deg"]))
    ux, uy = math.cos(angle), math.sin(angle)
    if fixed:
        x0, x1 = ax.get_xlim()
        y0, y1 = ax.get_ylim()
        reach = 2.0 * math.hypot(x1 - x0, y1 - y0)
        ax.plot([x - reach * ux, x + reach * ux], [y - reach * uy, y + reach * uy],
                color=_GUIDE, lw=0.8, ls="-.")
        return
    along = [(px - x) * ux + (py - y) * uy for name, (px, py) in where.items()
             if name in carriers or name == slide["point"]] + [0.0]
    start, stop = min(along), max(along)
    stop += 0.15 * max(stop - start, 1.0)          # the slot goes on past the block
    ax.plot([x + start * ux, x + stop * ux], [y + start * uy, y + stop * uy], color=_LINK,
            lw=2.4, solid_capstyle="round")


def _draw_plan(ax, plan) -> None:
    """A velocity or acceleration plan of a raster frame: an arrow from the pole to each
    image of a point, the construction points (n, k) as small dots, every point named as the
    course writes it (b₃, n_CB, p ≡ a)."""
    where = _plan_points(plan)
    pole = where.get(plan.pole, (0.0, 0.0))
    for name, (x, y) in where.items():
        if is_image(name, plan.pole) and abs(x - pole[0]) + abs(y - pole[1]) > 1e-9:
            ax.annotate("", xy=(x, y), xytext=pole,
                        arrowprops={"arrowstyle": "-|>", "color": _INK, "lw": 1.4})
        elif name != plan.pole:
            ax.plot([x], [y], marker=".", color=_HELPER, ms=4)
    ax.plot([pole[0]], [pole[1]], marker="o", color=_INK, ms=5)
    for text, xy in _joined(where, lambda name: label_text(name, plan.numbers)):
        ax.annotate(text, xy, xytext=(4, 4), textcoords="offset points", fontsize=9,
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
