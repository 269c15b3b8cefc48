"""Enlarged details wherever points crowd: any figure, drawn again larger, clipped to a region.

Where two or more distinct points of a figure lie nearer each other than the readable distance
(:data:`DENSE_PX`, :data:`planmethod.render.style.READABLE_PX`: 2 em of the labels), the region
round them is framed and numbered on the figure (I, II, …) and drawn again below it, enlarged
by a whole factor, clipped to the region, with the labels of the points inside it kept whole.
The enlargement is the largest that keeps the detail within :data:`DETAIL_SIZE`; where the
closest pair of the region is still nearer than the readable distance at it, the region round
them is marked inside the detail and drawn again, larger still (a detail of a detail: two
levels at most, :data:`DEPTH`), down to :data:`RESOLUTION` of the figure: points nearer than
that are one spot of the drawing (their labels are joined by ≈). Where a detail of a detail
still crowds points, they are its ``crowded`` points: the figure lists them in a table of their
coordinates (:func:`crowded_points`) rather than nesting a third detail. Any figure can have
details: it hands over the points to watch and a function that draws its content on a canvas of
any zoom (a plan, the lever with its forces, the loaded mechanism, a force polygon), and the
detail is that same drawing at a larger zoom — never a picture of a picture. A label that names
a vector (a force) is anchored, in a detail, on the part of the vector the detail shows.

Examples
--------
>>> dense_regions({"a": (0, 0), "b": (5, 0), "c": (5, 6), "d": (200, 0)})
[(0.0, 0.0, 5.0, 6.0)]
>>> dense_regions({"a": (0, 0), "b": (5, 0), "d": (200, 0)}, least=3)
[]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

import numpy as np

from ..vectors import norm
from ..words import Message, message
from .canvas import Canvas, Point, page_point, shown_text
from .labels import RunKind, drawn_length
from .style import INK, READABLE_PX, TEXT_SIZE

__all__ = ["DENSE_PX", "DEPTH", "DETAIL_SIZE", "DETAIL_ZOOM", "NESTED", "RESOLUTION", "Detail",
           "crowded_points", "dense_regions", "detail_insets", "detail_regions", "one_spot"]

#: distinct points nearer than this (px) to a neighbour crowd each other: two or more such make
#: a region that gets an enlarged detail (the readable distance)
DENSE_PX = READABLE_PX
#: the longest side of a detail inset (px), and the least and most enlargement of one step
DETAIL_SIZE = 300.0
DETAIL_ZOOM = (2.5, 12.0)
#: details of details go this deep at most in a plan (a figure, its detail, a detail of that;
#: the plan lists the points still crowded): :func:`detail_regions`'s ``depth``
DEPTH = 2
#: how deep a figure that lists no crowded points nests its details (the force figures, the
#: lever and the position plan, for now)
NESTED = 3
#: points of a figure nearer each other than this fraction of its extent are one spot of the
#: drawing: no detail two steps deep (×144) would set them the readable distance apart
RESOLUTION = 1.0 / 2000.0
#: how far (px) round a region's corner its numeral looks for room
NUMERAL_ROOM = 30.0
#: at most this many details a figure, named by Roman numerals (no point is named so)
ROMAN = ("I", "II", "III", "IV", "V", "VI", "VII", "VIII")
MOST = len(ROMAN)


@dataclass(frozen=True)
class Detail:
    """An enlarged detail: its numeral, its region (x0, y0, x1, y1) in the figure's px, its
    enlargement of the figure, the detail it is marked in (None: the figure), and the points
    still too close to read in it where no deeper detail is drawn (``crowded``)."""

    letter: str
    box: tuple[float, float, float, float]
    zoom: float
    parent: str | None = None
    crowded: tuple[str, ...] = ()


def crowded_points(regions: list[Detail]) -> list[str]:
    """The points no detail sets apart (each once, in the details' order): a figure lists
    them with their coordinates.

    >>> crowded_points([Detail("I", (0, 0, 9, 9), 4.0), Detail("II", (1, 1, 2, 2), 40.0,
    ...                 "I", ("b", "c"))])
    ['b', 'c']
    """
    return list(dict.fromkeys(name for region in regions for name in region.crowded))


def one_spot(where: Mapping[str, Point]) -> float:
    """How near (px) two of the points ``where`` may lie and still be one spot of the
    drawing: :data:`RESOLUTION` of their extent.

    >>> one_spot({"a": (0, 0), "b": (400, 100)})
    0.2
    """
    if not where:
        return 0.0
    xy = np.asarray([page_point(p) for p in where.values()], dtype=float)
    extent = float(max(np.ptp(xy[:, 0]), np.ptp(xy[:, 1])))
    return RESOLUTION * extent


def dense_regions(where: Mapping[str, Point], *, gap: float = DENSE_PX, least: int = 2,
                  same: float = 1e-6) -> list[tuple[float, float, float, float]]:
    """Boxes (x0, y0, x1, y1, page px) round the groups of at least ``least`` distinct points
    (points within ``same`` px of one another count once) each within ``gap`` of another of
    the group — the regions of a figure too dense to read, largest group first."""
    spots: list[np.ndarray] = []
    for xy in where.values():
        xy = page_point(xy)
        if not spots or bool(np.all(norm(np.asarray(spots) - xy) > same)):
            spots.append(xy)
    if not spots:
        return []
    array = np.asarray(spots)
    near = norm(array[:, None, :] - array[None, :, :]) < gap
    group = np.arange(len(spots))
    for _ in range(len(spots)):          # join neighbours until the groups stop growing
        joined = np.array([group[near[index]].min() for index in range(len(spots))])
        joined = np.minimum(joined, joined[joined])
        if np.array_equal(joined, group):
            break
        group = joined
    members: dict[int, list[tuple[float, float]]] = {}
    for index, xy in enumerate(spots):
        members.setdefault(int(group[index]), []).append((float(xy[0]), float(xy[1])))
    found = [points for points in members.values() if len(points) >= least]
    found.sort(key=lambda points: (-len(points), points[0]))
    return [(min(p[0] for p in points), min(p[1] for p in points),
             max(p[0] for p in points), max(p[1] for p in points)) for points in found]


def detail_regions(figure: Canvas, where: Mapping[str, Point], *, draw: bool = True,
                   depth: int = NESTED) -> list[Detail]:
    """The figure's dense regions worth an enlarged detail, and the regions of those details
    still too dense at their enlargement (details of details), in the order they are drawn;
    each region of the figure is marked on it with a frame and its numeral (placed with the
    labels: call before :meth:`Canvas.place`), each region of a detail is marked on that
    detail by :func:`detail_insets`. The labels of what a region holds go on the figure only
    where they find a clean spot. A figure drawn without details (not ``draw``: a frame of a
    workbook page, the studio) gets no region; the labels of its crowded points that find no
    clean spot go on leaders, after the others (``crowded``, see
    :func:`planmethod.render.labels.place_labels`). Details nest ``depth`` levels at most; the
    points the deepest still crowds are its ``crowded`` ones (:func:`crowded_points`)."""
    same = one_spot(where)
    if not draw:
        for box in _regions(where, 1.0, same):
            figure.requests = [replace(request, optional=True, crowded=True)
                               if _within(request, box)
                               else request for request in figure.requests]
        return []
    out: list[Detail] = []
    queue: list[tuple[tuple[float, float, float, float], float, str | None, int]] = [
        (box, 1.0, None, 1) for box in _regions(where, 1.0, same)]
    while queue and len(out) < MOST:
        box, base, parent, level = queue.pop(0)
        step = math.floor(min(DETAIL_SIZE / (max(box[2] - box[0], box[3] - box[1]) * base),
                              DETAIL_ZOOM[1]))
        if step < DETAIL_ZOOM[0]:
            continue
        inside = {name: xy for name, xy in where.items()
                  if box[0] <= xy[0] <= box[2] and box[1] <= xy[1] <= box[3]}
        detail = Detail(ROMAN[len(out)], box, base * step, parent)
        inner = _regions(inside, detail.zoom, same)
        if level >= depth and inner:     # no deeper level: its crowded points are listed
            detail = replace(detail, crowded=tuple(
                name for name, xy in inside.items()
                if any(x0 <= xy[0] <= x1 and y0 <= xy[1] <= y1 for x0, y0, x1, y1 in inner)))
        out.append(detail)
        if parent is None:
            _mark(figure, detail, 1.0)
            # the labels of what the detail shows go on the figure only where they find a
            # clean spot (the detail names it anyway)
            figure.requests = [replace(request, optional=True) if _within(request, box)
                               else request for request in figure.requests]
        if level < depth:
            queue += [(region, detail.zoom, detail.letter, level + 1) for region in inner]
    return out


def _regions(where: Mapping[str, Point], zoom: float, same: float
             ) -> list[tuple[float, float, float, float]]:
    """The framed dense regions (figure px) of the points ``where`` seen ``zoom`` times
    larger, overlapping ones joined."""
    scaled = {name: page_point(xy) * zoom for name, xy in where.items()}
    boxes = [_framed(region) for region in dense_regions(scaled, same=same * zoom)]
    return [tuple(value / zoom for value in box) for box in _merged(boxes)]


def _within(request, box) -> bool:
    """Whether a label request names something in ``box``: its anchor lies in it (not a
    detail's own numeral)."""
    x0, y0, x1, y1 = box
    return (x0 <= request.anchor[0] <= x1 and y0 <= request.anchor[1] <= y1
            and not request.points[0].startswith("detail:"))


def _mark(canvas: Canvas, detail: Detail, zoom: float) -> None:
    """A detail's region framed on ``canvas`` (drawn ``zoom`` times the figure's size) with
    its numeral, at the corner with the least drawn round it outside the frame."""
    x0, y0, x1, y1 = (value * zoom for value in detail.box)
    corners = [(x1, y0, 1, -1), (x0, y0, -1, -1), (x1, y1, 1, 1), (x0, y1, -1, 1)]
    reach = NUMERAL_ROOM
    outside = [(min(x, x + sx * reach), min(y, y + sy * reach), max(x, x + sx * reach),
                max(y, y + sy * reach)) for x, y, sx, sy in corners]
    clutter = drawn_length(canvas.obstacle_lines, outside)
    x, y, _, _ = corners[int(np.argmin(clutter))]       # the first of equals: top right
    canvas.rectangle((x0, y0), (x1 - x0, y1 - y0), fill="none", stroke=INK, width=0.8,
                     layer="marks", css="detail region", obstacle=True)
    canvas.request((f"detail:{detail.letter}",), (x, y), ((detail.letter, RunKind.SEP),),
                   mark=0.0)
    canvas.requests.insert(0, canvas.requests.pop())    # placed first: it names the detail


def _framed(region: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """A dense region with the margin its detail shows round it."""
    x0, y0, x1, y1 = region
    margin = max(10.0, 0.2 * max(x1 - x0, y1 - y0))
    return (x0 - margin, y0 - margin, x1 + margin, y1 + margin)


def _merged(boxes: list[tuple[float, float, float, float]]
            ) -> list[tuple[float, float, float, float]]:
    """Boxes that overlap joined into one (in the order of their first members), so that
    one crowded place gets one detail.

    >>> _merged([(0, 0, 10, 10), (50, 0, 60, 10), (8, 8, 20, 20)])
    [(0, 0, 20, 20), (50, 0, 60, 10)]
    """
    boxes = list(boxes)
    joined = True
    while joined:
        joined = False
        for i, first in enumerate(boxes):
            for j in range(i + 1, len(boxes)):
                second = boxes[j]
                if first[0] <= second[2] and second[0] <= first[2] and first[1] <= second[3] \
                        and second[1] <= first[3]:
                    boxes[i] = (min(first[0], second[0]), min(first[1], second[1]),
                                max(first[2], second[2]), max(first[3], second[3]))
                    del boxes[j]
                    joined = True
                    break
            if joined:
                break
    return boxes


def _anchored(request, box):
    """A label request of a vector anchored on the part of it inside ``box`` (the middle of
    that part), when its own anchor lies outside; else the request unchanged."""
    x0, y0, x1, y1 = box
    ax, ay = request.anchor
    if request.span is None or (x0 <= ax <= x1 and y0 <= ay <= y1):
        return request
    (sx, sy), (ex, ey) = request.span
    dx, dy = ex - sx, ey - sy
    low, high = 0.0, 1.0
    for p, q in ((-dx, sx - x0), (dx, x1 - sx), (-dy, sy - y0), (dy, y1 - sy)):
        if p == 0:
            if q < 0:
                return request
            continue
        if p < 0:
            low = max(low, q / p)
        else:
            high = min(high, q / p)
    if high - low <= 0 or (high - low) * math.hypot(dx, dy) < 8.0:
        return request                     # not shown, or too little of it to name
    middle = 0.5 * (low + high)
    return replace(request, anchor=(sx + middle * dx, sy + middle * dy))


def detail_insets(figure: Canvas, draw: Callable[[Canvas], None], regions: list[Detail],
                  ident: str, *, beside: bool = False) -> list[str]:
    """Each marked region drawn again, enlarged, below the figure (in rows as wide as the
    figure) — or, ``beside`` it where it is taller than wide, in rows two details wide (the
    page's room beside a tall plan): ``draw`` draws the figure's content on a canvas of the
    detail's zoom, clipped to the region, the regions of the details within it marked, the
    labels of the points inside it placed inside it where they can and kept whole (a
    force's label on the part of its arrow the detail shows; the frame widened to hold a
    label that reaches past the region).
    Returns the lines that say so."""
    lines = []
    x0, y0, x1, y1 = figure.extent
    if beside and y1 - y0 > x1 - x0:      # a tall figure: its details beside it
        left = x = x1 + 40.0
        row_width, top = 2 * DETAIL_SIZE + 40.0, y0
    else:                      # a wide one: in rows below it, as wide as it
        left = x = x0
        row_width, top = max(x1 - x0, 2 * DETAIL_SIZE + 40.0), y1 + 30.0
    row_bottom = top
    for region in regions:
        detail, view, inside = _detail(draw, regions, region, figure.zoom)
        width, height = view[2] - view[0], view[3] - view[1]
        if x > left and x + width > left + row_width:      # a new row
            x, top = left, row_bottom + 40.0
        texts = [item for item in detail.layers["labels"]
                 if item[1].get("data-points") in inside]
        leaders = [item for item in detail.layers["leaders"]
                   if item[1].get("data-points") in inside]
        move = (x - view[0], top - view[1])
        figure.clipped(detail, view, move,
                       layers=[name for name in detail.layers if name not in ("labels",
                                                                              "leaders")],
                       css="detail", ident=f"{ident}-{region.letter}")
        figure.moved({"leaders": leaders, "labels": texts}, move, css="detail labels")
        figure.rectangle((x, top), (width, height), fill="none", stroke=INK, width=0.8,
                         layer="marks", css="detail frame")
        right, bottom = x + width, top + height
        caption = figure.text((x, bottom + 18), _caption(region), size=TEXT_SIZE, bold=True,
                              css="detail", area=False)
        right = max(right, x + caption)
        lines.append(shown_text(_said(region)))   # text: a figure's line (force_svg edits them)
        row_bottom = max(row_bottom, bottom + 18)
        x = right + 40.0
    return lines


def _detail(draw: Callable[[Canvas], None], regions: list[Detail], region: Detail,
            zoom: float) -> tuple[Canvas, list[float], set[str]]:
    """One detail drawn: the content at its zoom (the figure's ``zoom`` times its own), the
    regions of the details within it marked, the labels of what it shows placed inside its
    frame where they can. Returns the canvas, the box it shows (px of that canvas: the region,
    widened to hold a label kept whole that reaches past it) and the labels kept (by the
    points they name)."""
    (x0, y0, x1, y1), scale = region.box, region.zoom
    detail = Canvas(zoom * scale)
    draw(detail)
    for inner in regions:
        if inner.parent == region.letter:
            _mark(detail, inner, scale)
            inner_box = tuple(value * scale for value in inner.box)
            detail.requests = [replace(request, optional=True)
                               if _within(request, inner_box) else request
                               for request in detail.requests]
    box = (x0 * scale, y0 * scale, x1 * scale, y1 * scale)
    reach = 60.0               # labels are placed for the points in and near the region
    detail.requests = [_anchored(request, box) for request in detail.requests]
    detail.requests = [request for request in detail.requests
                       if box[0] - reach <= request.anchor[0] <= box[2] + reach
                       and box[1] - reach <= request.anchor[1] <= box[3] + reach]
    detail.place(bounds=box)           # inside the frame where they can
    inside = {" ".join(label.points) for label in detail.labels
              if box[0] <= label.anchor[0] <= box[2] and box[1] <= label.anchor[1] <= box[3]}
    # the frame holds the labels kept whole: where one reaches past the region, the detail
    # shows that much more of the drawing
    view = list(box)
    for label in detail.labels:
        if " ".join(label.points) in inside:
            view = [min(view[0], label.box[0] - 2.0), min(view[1], label.box[1] - 2.0),
                    max(view[2], label.box[2] + 2.0), max(view[3], label.box[3] + 2.0)]
    return detail, view, inside


def _caption(region: Detail) -> Message:
    """The caption under a detail: its numeral, its enlargement, the detail it is marked in."""
    if region.parent:
        return message("{letter}: detail ×{zoom:g} (marked in detail {parent})",
                       letter=region.letter, zoom=region.zoom, parent=region.parent)
    return message("{letter}: detail ×{zoom:g}", letter=region.letter, zoom=region.zoom)


def _said(region: Detail) -> Message:
    """The line under a figure that says what a detail is."""
    if region.parent:
        return message("detail {letter}: the region marked in detail {parent}, drawn {zoom:g} "
                       "times larger than the figure", letter=region.letter,
                       parent=region.parent, zoom=region.zoom)
    return message("detail {letter}: the marked region drawn {zoom:g} times larger",
                   letter=region.letter, zoom=region.zoom)
