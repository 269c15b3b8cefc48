"""Enlarged details wherever points crowd: any figure, drawn again larger, clipped to a region.

Where two or more distinct points of a figure lie nearer each other than a readable distance
(:data:`DENSE_PX`), the region round them is framed and numbered on the figure (I, II, …) and
drawn again below it, enlarged by a whole factor (×6), clipped to the region, with the labels
of the points inside it kept whole. Any figure can have details: it hands over the points to
watch and a function that draws its content on a canvas of any zoom (a plan, the lever with its
forces, the loaded mechanism, a force polygon), and the detail is that same drawing at a larger
zoom — never a picture of a picture.

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

import numpy as np

from ..vectors import norm
from .canvas import Canvas, Point, page_point
from .labels import RunKind
from .style import INK, TEXT_SIZE

__all__ = ["DENSE_PX", "DETAIL_SIZE", "DETAIL_ZOOM", "dense_regions", "detail_insets",
           "detail_regions"]

#: distinct points nearer than this (px) to a neighbour crowd each other: two or more such make
#: a region that gets an enlarged detail
DENSE_PX = 16.0
#: the longest side of a detail inset (px), and the least and most enlargement worth drawing
DETAIL_SIZE = 300.0
DETAIL_ZOOM = (2.5, 12.0)
#: at most this many details a figure, named by Roman numerals (no point is named so)
MOST = 4
ROMAN = ("I", "II", "III", "IV")


def dense_regions(where: Mapping[str, Point], *, gap: float = DENSE_PX,
                  least: int = 2) -> list[tuple[float, float, float, float]]:
    """Boxes (x0, y0, x1, y1, page px) round the groups of at least ``least`` distinct points
    (coincident ones count once) each within ``gap`` of another of the group — the regions of
    a figure too dense to read, largest group first."""
    spots: list[np.ndarray] = []
    for xy in where.values():
        xy = page_point(xy)
        if not spots or bool(np.all(norm(np.asarray(spots) - xy) > 1e-6)):
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


def detail_regions(figure: Canvas, where: Mapping[str, Point]
                   ) -> list[tuple[str, tuple[float, float, float, float], float]]:
    """The figure's dense regions worth an enlarged detail: (letter, box in page px,
    enlargement), each marked on the figure with a frame and its letter (placed with the
    labels: call before :meth:`Canvas.place`)."""
    out = []
    for box in _merged([_framed(region) for region in dense_regions(where)]):
        if len(out) == MOST:
            break
        zoom = min(DETAIL_SIZE / max(box[2] - box[0], box[3] - box[1]), DETAIL_ZOOM[1])
        if zoom < DETAIL_ZOOM[0]:
            continue
        letter = ROMAN[len(out)]
        figure.rectangle((box[0], box[1]), (box[2] - box[0], box[3] - box[1]), fill="none",
                         stroke=INK, width=0.8, layer="marks", css="detail region")
        figure.request((f"detail:{letter}",), (box[2], box[1]), ((letter, RunKind.SEP),),
                       mark=0.0)
        out.append((letter, box, float(math.floor(zoom))))     # a whole enlargement: ×6
    return out


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


def detail_insets(figure: Canvas, draw: Callable[[Canvas], None], regions, ident: str
                  ) -> list[str]:
    """Each marked region drawn again, enlarged, below the figure: ``draw`` draws the
    figure's content on a canvas of the detail's zoom, clipped to the region, the labels of
    the points inside it kept whole. Returns the lines that say so."""
    lines = []
    x = figure.extent[0]
    top = figure.extent[3] + 30.0
    for letter, (x0, y0, x1, y1), zoom in regions:
        detail = Canvas(figure.zoom * zoom)
        draw(detail)
        reach = 60.0               # labels are placed for the points in and near the region
        detail.requests = [request for request in detail.requests
                           if x0 * zoom - reach <= request.anchor[0] <= x1 * zoom + reach
                           and y0 * zoom - reach <= request.anchor[1] <= y1 * zoom + reach]
        detail.place()
        width, height = (x1 - x0) * zoom, (y1 - y0) * zoom
        inside = {" ".join(label.points) for label in detail.labels
                  if x0 * zoom <= label.anchor[0] <= x1 * zoom
                  and y0 * zoom <= label.anchor[1] <= y1 * zoom}
        texts = [item for item in detail.layers["labels"]
                 if item[1].get("data-points") in inside]
        leaders = [item for item in detail.layers["leaders"]
                   if x0 * zoom <= float(item[1]["x1"]) <= x1 * zoom
                   and y0 * zoom <= float(item[1]["y1"]) <= y1 * zoom]
        move = (x - x0 * zoom, top - y0 * zoom)
        figure.clipped(detail, (x0 * zoom, y0 * zoom, x1 * zoom, y1 * zoom), move,
                       layers=[name for name in detail.layers if name not in ("labels",
                                                                              "leaders")],
                       css="detail", ident=f"{ident}-{letter}")
        figure.moved({"leaders": leaders, "labels": texts}, move, css="detail labels")
        figure.rectangle((x, top), (width, height), fill="none", stroke=INK, width=0.8,
                         layer="marks", css="detail frame")
        right, bottom = x + width, top + height
        for label in detail.labels:           # labels kept whole may reach past the frame
            if " ".join(label.points) in inside:
                bx0, by0, bx1, by1 = label.box
                corner = (x + bx1 - x0 * zoom, top + by1 - y0 * zoom)
                figure.grow((x + bx0 - x0 * zoom, top + by0 - y0 * zoom), corner)
                right, bottom = max(right, corner[0]), max(bottom, corner[1])
        figure.text((x, bottom + 18), f"{letter}: detail ×{zoom:g}", size=TEXT_SIZE,
                    bold=True, css="detail", area=False)
        lines.append(f"detail {letter}: the marked region drawn {zoom:g} times larger")
        x = right + 40.0
    return lines
