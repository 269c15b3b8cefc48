"""Enlarged details wherever points crowd: any figure, drawn again larger, clipped to a region.

Where two or more distinct points of a figure lie nearer each other than the readable distance
(:data:`DENSE_PX`, :data:`planmethod.render.style.READABLE_PX`: 2 em of the labels), the region
round them is framed and numbered on the figure (I, II, …) and drawn again beside it, enlarged
by a whole factor, clipped to the region, with the labels of the points inside it kept whole.
The enlargement is the largest that keeps the detail within :data:`DETAIL_SIZE`; where the
closest pair of the region is still nearer than the readable distance at it, the region round
them is marked inside the detail and drawn again, larger still (a detail of a detail: two
levels at most, :data:`DEPTH`), down to :data:`RESOLUTION` of the figure: points nearer than
that are one spot of the drawing (their labels are joined by ≈). Where a detail of a detail
still crowds points, they are its ``crowded`` points: the figure lists them in a table of their
coordinates (:func:`crowded_points`, :func:`crowded_table`) rather than nesting a third detail.
The page is framed on what the figure draws: its legend's column at the right of the drawing,
the table under it, the details packed beside them (:func:`column_and_details`) on a page at
most :data:`PAGE` times as wide as the drawing — where a detail would make the page longer, at
a smaller whole enlargement that still shows its points apart, if one fits. Any figure can have
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

import itertools
import math
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TypeVar

import numpy as np

from ..vectors import cross, inside_span, norm
from ..words import Message, message, number_text, template
from .canvas import MARGIN, Canvas, Point, page_point, shown_text
from .labels import PADDING, RunKind, drawn_length, near_only, point_along
from .style import CLEARANCE_PX, INK, READABLE_PX, SANS_BOLD, TEXT_SIZE, text_width

__all__ = ["DENSE_PX", "DEPTH", "DETAIL_SIZE", "DETAIL_ZOOM", "FROM_POLE", "ON_THE_DRAWING",
           "PAGE", "RESOLUTION", "Detail",
           "Room", "column_and_details", "crowded_points", "crowded_table", "dense_regions",
           "detail_insets", "detail_regions", "laid_out", "one_spot", "page_times",
           "room_beside", "within_page"]

#: distinct points nearer than this (px) to a neighbour crowd each other: two or more such make
#: a region that gets an enlarged detail (the readable distance)
DENSE_PX = READABLE_PX
#: the figure writes coordinates to 0.01 px: two points this much farther apart than a
#: distance may be read nearer than it from the file, and count as nearer
WRITTEN_PX = 0.02
#: the longest side of a detail inset (px), and the least and most enlargement of one step
DETAIL_SIZE = 300.0
DETAIL_ZOOM = (2.0, 12.0)
#: details of details go this deep at most in any figure (a figure, its detail, a detail of
#: that; the figure lists the points still crowded): :func:`detail_regions`'s ``depth``
DEPTH = 2
#: a figure's page is at most this many times as wide as what it draws (its mechanism, its
#: plan, its polygon: :attr:`Canvas.drawn`) — the details beside it wrap into rows within it
#: (the figure check allows 3, with room for the margins and labels round the drawing)
PAGE = 2.9
#: points of a figure nearer each other than this fraction of its extent are one spot of the
#: drawing: no detail two steps deep (×144) would set them the readable distance apart
RESOLUTION = 1.0 / 2000.0
#: a detail of labels alone (no two places in it near each other) enlarges this much at
#: most: they need room round them, not the drawing larger
LONE_ZOOM = 6
#: how far (px) round a region's corner its numeral looks for room
NUMERAL_ROOM = 30.0
#: the title of the table of the points a plan's details cannot set apart (x, y from its pole)
FROM_POLE = template("points too close to read (from the pole {pole})")
#: the title of that table on a drawing of the mechanism (x, y of the drawing)
ON_THE_DRAWING = message("points too close to read (mm on the drawing)")
#: at most this many details a figure, named by Roman numerals (no point is named so)
ROMAN = ("I", "II", "III", "IV", "V", "VI", "VII", "VIII")
MOST = len(ROMAN)
#: what a figure's builder returns besides its canvas (:func:`within_page`)
_T = TypeVar("_T")


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


def crowded_table(figure: Canvas, at: Point,
                  rows: Sequence[tuple[str, float, float, tuple[str, ...]]],
                  title: Message) -> float:
    """The table of the points a figure's details cannot set apart, top-left at ``at``: each
    row a point's name as the figure prints it, its x and y (mm, as a student lays them off)
    and the points it names (the figure's marks it lists); returns the y under it (``at``'s
    without rows).

    >>> figure = Canvas()
    >>> crowded_table(figure, (0, 0), [("b₃", 1.0, 2.5, ("b@lever",))],
    ...               message("points too close to read")) > 40
    True
    """
    if not rows:
        return float(at[1])
    return figure.table(at, [[name, number_text(x, ".2f"), number_text(y, ".2f")]
                             for name, x, y, _ in rows],
                        header=[message("point", context="column"),
                                message("x, mm", context="column"),
                                message("y, mm", context="column")], right=[False, True, True],
                        css="table crowded", title=title, points=[row[3] for row in rows])


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
    the group (or :data:`WRITTEN_PX` more: as near as the written figure may show them) —
    the regions of a figure too dense to read, largest group first."""
    spots: list[np.ndarray] = []
    for xy in where.values():
        xy = page_point(xy)
        if not spots or bool(np.all(norm(np.asarray(spots) - xy) > same)):
            spots.append(xy)
    if not spots:
        return []
    array = np.asarray(spots)
    near = norm(array[:, None, :] - array[None, :, :]) < gap + WRITTEN_PX
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
                   depth: int = DEPTH, alone: Collection[str] = (),
                   same: float | None = None) -> list[Detail]:
    """The figure's dense regions worth an enlarged detail, and the regions of those details
    still too dense at their enlargement (details of details), in the order they are drawn;
    each region of the figure is marked on it with a frame and its numeral (placed with the
    labels: call before :meth:`Canvas.place`), each region of a detail is marked on that
    detail by :func:`detail_insets`. The labels of what a region holds go on the figure only
    where they find a clean spot. A figure drawn without details (not ``draw``: a frame of a
    workbook page, the studio) gets no region; the labels of its crowded points that find no
    clean spot go on leaders, after the others (``crowded``, see
    :func:`planmethod.render.labels.place_labels`). Details nest ``depth`` levels at most; the
    points the deepest still crowds are its ``crowded`` ones (:func:`crowded_points`). The
    places of the names ``alone`` (labels that found no clean spot on the figure) are
    regions by themselves where no other region holds them: a label crowded by the lines
    round it needs no second point near it to be drawn again larger. Points nearer than
    ``same`` (px; :func:`one_spot` of ``where`` unless given: that of the points the figure
    joins in one mark) are one spot."""
    same = one_spot(where) if same is None else same
    if not draw:
        for box in _regions(where, 1.0, same):
            figure.requests = [replace(request, optional=True, crowded=True)
                               if _within(request, box)
                               else request for request in figure.requests]
        return []
    out: list[Detail] = []
    dense = _regions(where, 1.0, same)
    queue: list[tuple[tuple[float, float, float, float], float, str | None, int]] = [
        (box, 1.0, None, 1) for box in dense]
    # the places of labels alone come after every crowd and its details of details
    later = [(box, 1.0, None, 1) for box in _lone(dense, [
        where[name] for name in alone if name in where])]
    while (queue or later) and len(out) < MOST:
        box, base, parent, level = (queue or later).pop(0)
        inside = {name: xy for name, xy in where.items()
                  if box[0] <= xy[0] <= box[2] and box[1] <= xy[1] <= box[3]}
        step = _step(box, base)
        if inside and set(inside) <= set(alone) and not dense_regions(
                inside, same=same):       # labels alone, no two near: room round them
            step = min(step, LONE_ZOOM)
        if step < DETAIL_ZOOM[0]:       # too wide a crowd for one detail: its tighter parts
            queue[:0] = [(part, base, parent, level) for part in _parts(inside, base, same)]
            continue
        detail = Detail(ROMAN[len(out)], box, base * step, parent)
        inner = _joined(_regions(inside, detail.zoom, same), detail.zoom)
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


def laid_out(zoom: float, content: Callable[[Canvas], None],
             where_of: Callable[[Canvas], Mapping[str, Point]], details: bool,
             bounds: tuple[float, float, float, float] | None = None,
             plan_of: Callable[[Canvas], Mapping[str, Point]] | None = None
             ) -> tuple[Canvas, list[Detail]]:
    """A figure drawn by ``content`` at ``zoom``, its enlarged details' regions marked and its
    labels placed (within ``bounds`` where they can: a steady page's box). The details watch
    the points ``where_of(figure)`` and the labels that find no clean spot — on trial, and
    again once the regions are marked (a frame may push a label off its spot: then the figure
    is drawn once more with that label watched too, up to three times). A label — of a
    force, a moment or a point — that a line crosses or whose leader crosses an arrow
    (:func:`_troubled`) is a crowded place by itself: no second point need be near it for it
    to be drawn again larger — but an arm's h, which stands a fixed step (px) beside its
    arm, is drawn larger only with what is near it (a detail of its place alone would show
    the arm elsewhere). Points one spot
    apart are as near as the plan's own points ``plan_of(figure)`` (all of ``where_of``
    unless given) are where the plan joins them in one mark.

    >>> figure, regions = laid_out(1.0, lambda canvas: None, lambda canvas: {}, True)
    >>> regions
    []
    """
    extra: dict = {}
    lone: set[str] = set()
    for _ in range(3):
        figure = Canvas(zoom)
        content(figure)
        where = where_of(figure)
        watched, unclean = _crowded(figure, where) if details else (where, set())
        watched, lone = watched | extra, lone | unclean
        regions = detail_regions(figure, watched, draw=details, alone=[
            name for name in watched if name in lone and not name.startswith("arm:")],
            same=one_spot((plan_of or where_of)(figure)))
        if not details:         # no detail to draw: nothing more to watch
            with near_only():   # (a frame of a turn: a leader may cross an arrow)
                figure.place(bounds=bounds)
            break
        figure.place(bounds=bounds)
        placed = [label for label in figure.labels
                  if not label.points[0].startswith("detail:")]
        pushed = {" ".join(label.points): label.requested for label in placed
                  if not label.clean and not set(label.points) & set(watched)}
        alone = {name for label in placed if _troubled(figure, label) for name in (
            [point for point in label.points if point in where] or [" ".join(label.points)])
                 } - lone
        if not (pushed or alone):
            break
        extra, lone = extra | pushed, lone | alone
    return figure, regions


def _crowded(figure: Canvas, where: dict) -> tuple[dict, set[str]]:
    """The points a detail watches, ``where``, and where the other labels go (of forces,
    arms, moments) that find no clean spot on the figure, placed on trial: such a label
    crowds the points near it like a point, so an enlarged detail shows it where others are
    near; and the labels (of a point: its name) that a line crosses or whose leader crosses
    an arrow there (:func:`_troubled`), each a crowded place by itself."""
    trial = [label for label in figure.trial() if not label.points[0].startswith("detail:")]
    return (where | {" ".join(label.points): label.requested for label in trial
                     if not label.clean and not set(label.points) & set(where)},
            {name for label in trial if _troubled(figure, label) for name in
             ([point for point in label.points if point in where] or [" ".join(label.points)])})


def _troubled(figure: Canvas, label) -> bool:
    """Whether a label placed on ``figure`` is crossed by a drawn line, lies on another
    point's mark (a point's label: nearer it than :data:`CLEARANCE_PX`, with a px for the
    fonts' ascent as a reader's box has it), or its leader
    crosses a vector's arrow more than a hair from its point — what a reader sees as
    crowded, not only a spot that costs more than a clean one."""
    x0, y0, x1, y1 = label.box
    inner = (x0 + PADDING + 0.6, y0 + PADDING + 0.6, x1 - PADDING - 0.6, y1 - PADDING - 0.6)
    if drawn_length(figure.obstacle_lines + figure.vector_lines, [inner])[0] > 1.5:
        return True
    ax, ay = label.anchor
    marks = [(x, y, radius) for x, y, radius, _ in figure.point_marks]
    own = any(abs(x - ax) + abs(y - ay) < 0.5 for x, y, _ in marks)   # a point's label
    text = (x0 + PADDING, y0 + PADDING, x1 - PADDING, y1 - PADDING)
    for x, y, radius in marks:         # on (a point's: near) another point's mark
        gap = math.hypot(max(text[0] - x, 0.0, x - text[2]),
                         max(text[1] - y, 0.0, y - text[3])) - radius
        if abs(x - ax) + abs(y - ay) >= 0.5 and gap < (CLEARANCE_PX + 1.0 if own else 0.0):
            return True
    if not label.leader:
        return False
    start = np.asarray(label.anchor, float)
    end = np.clip(start, (x0, y0), (x1, y1))
    for line in figure.vector_lines:
        for first, second in itertools.pairwise(line):
            first, second = np.asarray(first, float), np.asarray(second, float)
            along, other = end - start, second - first
            denominator = float(cross(along, other))
            if abs(denominator) < 1e-12:
                continue
            t = float(cross(first - start, other)) / denominator
            u = float(cross(first - start, along)) / denominator
            if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0 and t * float(norm(along)) > 1.5:
                return True
    return False


def _regions(where: Mapping[str, Point], zoom: float, same: float, gap: float = DENSE_PX
             ) -> list[tuple[float, float, float, float]]:
    """The framed dense regions (figure px) of the points ``where`` seen ``zoom`` times
    larger (each within ``gap`` of another there), overlapping ones joined."""
    scaled = {name: page_point(xy) * zoom for name, xy in where.items()}
    boxes = [_framed(region) for region in dense_regions(scaled, gap=gap, same=same * zoom)]
    return [tuple(value / zoom for value in box) for box in _merged(boxes)]


def _lone(boxes: list[tuple[float, float, float, float]], places: Sequence[Point]
          ) -> list[tuple[float, float, float, float]]:
    """A framed region round each of the ``places`` that none of the regions ``boxes``
    holds (overlapping ones joined), but those that overlap one of them: a region's detail
    shows what reaches into it.

    >>> _lone([(0, 0, 30, 30)], [(10, 10), (100, 100), (35, 35)])
    [(90.0, 90.0, 110.0, 110.0)]
    """
    out = []
    for place in places:
        x, y = (float(value) for value in page_point(place))
        if not any(box[0] <= x <= box[2] and box[1] <= y <= box[3] for box in boxes):
            out.append(_framed((x, y, x, y)))
    return [box for box in _merged(out) if not any(
        box[0] <= other[2] and other[0] <= box[2] and box[1] <= other[3]
        and other[1] <= box[3] for other in boxes)]


def _step(box: tuple[float, float, float, float], base: float) -> int:
    """The whole enlargement (of a figure seen ``base`` times larger) that draws ``box``
    within :data:`DETAIL_SIZE`, at most :data:`DETAIL_ZOOM`'s largest.

    >>> _step((0, 0, 40, 25), 1.0), _step((0, 0, 40, 25), 3.0), _step((0, 0, 4, 2), 1.0)
    (7, 2, 12)
    """
    return math.floor(min(DETAIL_SIZE / (max(box[2] - box[0], box[3] - box[1]) * base),
                          DETAIL_ZOOM[1]))


def _parts(where: Mapping[str, Point], zoom: float, same: float
           ) -> list[tuple[float, float, float, float]]:
    """A crowd too wide for one detail (of a figure seen ``zoom`` times larger) split into
    its tighter parts: the dense regions of its points at half the distance, a half again
    where one is still too wide, down to the hair that is one spot — each part one that a
    detail can draw (the labels of what falls between them find their spots on the figure).
    Many labels round a few points make such a crowd: no region is dropped for being wide."""
    gap = DENSE_PX / 2
    while gap >= 1.0:
        parts = _regions(where, zoom, same, gap)
        if all(_step(part, zoom) >= DETAIL_ZOOM[0] for part in parts):
            return parts
        gap /= 2
    return []


def _joined(boxes: list[tuple[float, float, float, float]], zoom: float
            ) -> list[tuple[float, float, float, float]]:
    """The regions of a detail (drawn ``zoom`` times the figure) joined where two fit one
    detail together (the two whose joined box is smallest first): a few details of a detail,
    not a page of small ones.

    >>> _joined([(0, 0, 10, 10), (20, 0, 30, 10), (400, 0, 410, 10)], 1.0)
    [(0, 0, 30, 10), (400, 0, 410, 10)]
    """
    boxes = list(boxes)
    while len(boxes) > 1:
        pairs = [(max(x1, b[2]) - min(x0, b[0]), max(y1, b[3]) - min(y0, b[1]), i, j)
                 for i, (x0, y0, x1, y1) in enumerate(boxes)
                 for j, b in enumerate(boxes) if j > i]
        _, _, i, j = min(pairs, key=lambda pair: max(pair[0], pair[1]))
        first, second = boxes[i], boxes[j]
        whole = (min(first[0], second[0]), min(first[1], second[1]),
                 max(first[2], second[2]), max(first[3], second[3]))
        if _step(whole, zoom) < DETAIL_ZOOM[0]:
            break
        boxes[i] = whole
        del boxes[j]
    return boxes


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
    that part), when its own anchor lies outside, and naming that part only (a crowded
    label's leader may start anywhere on what it names: only on what the detail shows); else
    the request unchanged. An arm's h stays at its arm's end (a detail of part of the arm
    does not name it).

    >>> from planmethod.render.labels import LabelRequest
    >>> request = LabelRequest(("F",), (5.0, 0.0), (), 15.0, span=((-20.0, 0.0), (20.0, 0.0)))
    >>> moved = _anchored(request, (-10.0, -5.0, 0.0, 5.0))
    >>> moved.anchor, moved.span
    ((-5.0, 0.0), ((-10.0, 0.0), (0.0, 0.0)))
    """
    x0, y0, x1, y1 = box
    ax, ay = request.anchor
    if request.span is None:
        return request
    if len(request.span) > 2:
        return _anchored_on_arc(request, box)
    (sx, sy), (ex, ey) = request.span
    dx, dy = ex - sx, ey - sy
    span = inside_span(request.span[0], request.span[1], box)
    if span is None:
        return request                     # not shown
    low, high = span
    shown = ((sx + low * dx, sy + low * dy), (sx + high * dx, sy + high * dy))
    if x0 <= ax <= x1 and y0 <= ay <= y1:
        return replace(request, span=shown)
    if (high - low) * math.hypot(dx, dy) < 8.0 or request.points[0].startswith("arm:"):
        return request                     # too little of it to name, or an arm's h
    middle = 0.5 * (low + high)
    return replace(request, anchor=(sx + middle * dx, sy + middle * dy), span=shown)


def _anchored_on_arc(request, box):
    """:func:`_anchored` for a label of a curved arrow (its span a polyline, the arc): naming
    the piece of the arc inside ``box`` that holds its anchor, or where its anchor lies
    outside, anchored on the middle of the longest piece shown (if 8 px of it are).

    >>> from planmethod.render.labels import LabelRequest
    >>> arc = ((-20.0, 0.0), (0.0, 0.0), (0.0, 20.0))
    >>> moved = _anchored_on_arc(LabelRequest(("M",), (-20.0, 0.0), (), 15.0, span=arc),
    ...                          (-5.0, -5.0, 5.0, 30.0))
    >>> moved.anchor, moved.span
    ((0.0, 7.5), ((-5.0, 0.0), (0.0, 0.0), (0.0, 20.0)))
    """
    pieces = _shown_pieces(request.span, box)
    if not pieces:
        return request                     # not shown
    x0, y0, x1, y1 = box
    ax, ay = request.anchor
    if x0 <= ax <= x1 and y0 <= ay <= y1:
        holding = min(pieces, key=lambda piece: min(math.hypot(x - ax, y - ay)
                                                     for x, y in piece))
        return replace(request, span=holding)
    longest = max(pieces, key=_path_length)
    if _path_length(longest) < 8.0:
        return request                     # too little of it to name
    return replace(request, anchor=point_along(longest, 0.5), span=longest)


def _path_length(path: Sequence[tuple[float, float]]) -> float:
    """The length of a polyline."""
    return sum(math.dist(start, end) for start, end in itertools.pairwise(path))


def _shown_pieces(path: Sequence[tuple[float, float]], box: Sequence[float]
                  ) -> list[tuple[tuple[float, float], ...]]:
    """The pieces of the polyline ``path`` inside ``box`` (x0, y0, x1, y1), each a polyline.

    >>> _shown_pieces(((-10.0, 0.0), (10.0, 0.0), (10.0, 5.0), (-10.0, 5.0)),
    ...               (0.0, -1.0, 5.0, 6.0))
    [((0.0, 0.0), (5.0, 0.0)), ((5.0, 5.0), (0.0, 5.0))]
    """
    pieces: list[tuple[tuple[float, float], ...]] = []
    current: list[tuple[float, float]] = []
    for (sx, sy), (ex, ey) in itertools.pairwise(path):
        inside = inside_span((sx, sy), (ex, ey), box)
        if inside is None:
            low, high = 1.0, 0.0                   # (none of it: the piece ends)
        else:
            low, high = inside
            first = (sx + low * (ex - sx), sy + low * (ey - sy))
            if not current or low > 0.0:           # a new piece begins here
                if current:
                    pieces.append(tuple(current))
                current = [first]
            current.append((sx + high * (ex - sx), sy + high * (ey - sy)))
        if high < 1.0 and current:
            pieces.append(tuple(current))
            current = []
    if current:
        pieces.append(tuple(current))
    return pieces


@dataclass(frozen=True)
class Room:
    """Where a figure's details go: on its page beside what is ``taken`` (boxes x0, y0, x1,
    y1 px: its drawing with its labels, the column of its legend), from ``left`` and ``top``,
    no detail reaching past ``right`` (unless one alone is wider than the page), and where
    one would reach past ``bottom``, drawn smaller if it can (:func:`_fitted`)."""

    taken: tuple[tuple[float, float, float, float], ...]
    left: float
    top: float
    right: float
    bottom: float = math.inf


#: the room (px) between two details, or a detail and what it stands beside
GAP = 40.0

#: no figure's page is more than this many times as long as what it draws (the figure check's
#: limit, issue 37), a little under it for the coordinates written to 0.01 px
PAGE_MOST = 2.99
#: how much larger than its own size a figure draws its drawing, in turn, where its page
#: (legend, tables, details, lines under it — all of a fixed size) would be longer than that
GROWTH = (1.0, 1.25, 1.5, 2.0)


def page_times(figure: Canvas) -> float:
    """How many times the longer side of a figure's page (what it holds, with its margins)
    is the longer side of what it draws (:attr:`Canvas.drawn`).

    >>> figure = Canvas()
    >>> figure.grow((0, 0), (100, 50), layer="points")
    >>> figure.grow((0, 0), (272, 50))
    >>> page_times(figure)
    3.0
    """
    x0, y0, x1, y1 = figure.extent
    drawn = figure.drawn
    return (max(x1 - x0, y1 - y0) + 2 * MARGIN) / max(drawn[2] - drawn[0],
                                                      drawn[3] - drawn[1], 1e-9)


def within_page(build: Callable[[float], tuple[Canvas, _T]]) -> _T:
    """A figure built by ``build(growth)`` (its canvas and what it returns) with its drawing
    :data:`GROWTH` times its own size in turn, the first whose page keeps within
    :data:`PAGE_MOST` of what it draws (:func:`page_times`) — the last tried if none does:
    a drawing drawn larger holds its legend, its tables and its details on a page of fewer
    times its size, and crowds fewer of its points.

    >>> within_page(lambda growth: (Canvas(growth), growth))
    1.0
    """
    for growth in GROWTH:
        figure, out = build(growth)
        if page_times(figure) <= PAGE_MOST:
            break
    return out


def room_beside(figure: Canvas, drawn: Sequence[float],
                taken: Sequence[Sequence[float]], below: float = 0.0) -> Room:
    """The room for a figure's details beside what is ``taken`` on a page at most
    :data:`PAGE` times as wide and as tall as ``drawn`` (x0, y0, x1, y1 px: what the figure
    draws, :attr:`Canvas.drawn`), less its margins and the ``below`` px of lines under it.

    >>> figure = Canvas()
    >>> figure.grow((0, 0), (100, 80))
    >>> room_beside(figure, (0, 0, 100, 80), [(0, 0, 100, 80)], below=40.0)
    Room(taken=((0.0, 0.0, 100.0, 80.0),), left=0.0, top=0.0, right=262.0, bottom=222.0)
    """
    x0, y0, _, _ = figure.extent
    side = max(drawn[2] - drawn[0], drawn[3] - drawn[1])
    return Room(tuple(tuple(float(v) for v in box) for box in taken), float(x0), float(y0),
                x0 + PAGE * side - 2 * MARGIN, y0 + PAGE * side - 2 * MARGIN - below)


#: the height (px) of the lines under a figure: the first's drop, each line, the scale bar,
#: the title over it (:func:`planmethod.render.svg.frame`)
LINES_PX = (26.0, 19.0, 40.0, 30.0)
#: the lines a figure with forces writes under it besides its details' (scales, notes)
OWN_LINES = 4


def _spot(room: Room, taken: list, width: float, height: float) -> tuple[float, float]:
    """Where a detail of ``width`` × ``height`` goes: clear of everything ``taken`` (by
    :data:`GAP`), within the page's width where it can, at the place that keeps the page
    shortest (then the highest, then the leftmost) — beside the drawing's column, under the
    drawing beside a tall column, or under everything."""
    xs = sorted({room.left} | {box[2] + GAP for box in taken})
    ys = sorted({room.top} | {box[3] + GAP for box in taken})
    floor = max(box[3] for box in taken)
    best: tuple | None = None
    for y in ys:
        for x in xs:
            if x > room.left and x + width > room.right:
                continue
            if any(x < box[2] + GAP - 1e-6 and box[0] < x + width + GAP - 1e-6
                   and y < box[3] + GAP - 1e-6 and box[1] < y + height + GAP - 1e-6
                   for box in taken):
                continue
            key = (max(floor, y + height), y, x)
            if best is None or key < best:
                best = key
    return (best[2], best[1]) if best else (room.left, floor + GAP)


def column_and_details(figure: Canvas, draw: Callable[[Canvas], None], regions: list[Detail],
                       ident: str, column: Callable[[Point], float], *,
                       crowded: Sequence[tuple[str, float, float, tuple[str, ...]]] = (),
                       title: Message | None = None) -> list[str]:
    """What goes beside a figure's drawing (its content drawn, its labels placed): the
    ``column`` at its right (``column(top_left)`` draws the legend and tables there and
    returns the y under them), under it the table of the ``crowded`` points its details
    cannot set apart (:func:`crowded_table`, with its ``title``), and its details beside
    them on a page framed on the drawing (:func:`room_beside`). Returns the details'
    lines."""
    drawn, drawing = tuple(figure.drawn), tuple(figure.extent)
    at = (drawing[2] + 34, drawing[1] + 4)
    bottom = column(at)
    if crowded and title is not None:
        bottom = crowded_table(figure, (at[0], bottom + 34 if bottom > at[1] else at[1]),
                               crowded, title)
    taken = [drawing]
    if figure.extent[2] > drawing[2]:          # the column drawn
        taken.append((at[0], drawing[1], figure.extent[2], max(bottom, at[1])))
    first, line, bar, title = LINES_PX
    below = first + line * (len(regions) + OWN_LINES) + bar + title
    return detail_insets(figure, draw, regions, ident,
                         room=room_beside(figure, drawn, taken, below=below))


def detail_insets(figure: Canvas, draw: Callable[[Canvas], None], regions: list[Detail],
                  ident: str, *, room: Room) -> list[str]:
    """Each marked region drawn again, enlarged, in the ``room`` the figure leaves
    (:func:`room_beside`): ``draw`` draws the figure's content on a canvas of the
    detail's zoom, clipped to the region, the regions of the details within it marked, the
    labels of the points inside it placed inside it where they can and kept whole (a
    force's label on the part of its arrow the detail shows; the frame widened to hold a
    label that reaches past the region), its caption under it.
    Returns the lines that say so."""
    lines = []
    taken = list(room.taken)
    for region in regions:
        region, (detail, view, inside), (x, top) = _fitted(draw, regions, region, figure.zoom,
                                                           room, taken)
        width, height = view[2] - view[0], view[3] - view[1]
        caption = _caption(region, width)
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
        right = x + max(width, figure.text((x, top + height + 18), caption, size=TEXT_SIZE,
                                           bold=True, css="detail", area=False))
        taken.append((x, top, right, top + height + 22.0))
        lines.append(shown_text(_said(region)))   # text: a figure's line (force_svg edits them)
    return lines


def _fitted(draw: Callable[[Canvas], None], regions: list[Detail], region: Detail,
            zoom: float, room: Room, taken: list) -> tuple[Detail, tuple, tuple[float, float]]:
    """A detail drawn (:func:`_detail`) and its spot in the room (:func:`_spot`): where it
    would make the page longer and no detail is marked in it, it is drawn at the largest
    smaller whole enlargement (of the figure or the detail it is marked in, down to half its
    own and :data:`DETAIL_ZOOM`'s least) that fits beside what is drawn and still shows its
    points apart; where it would reach past the page's height (``room.bottom``), marked
    details too, at the smallest such one if none fits — its labels then no more crowded
    than at its own enlargement, not all clean. Returns the region (its
    enlargement as drawn), the drawn detail and its spot."""
    floor = max(box[3] for box in taken)

    def tried(candidate: Detail):
        drawn = _detail(draw, regions, candidate, zoom)
        view = drawn[1]
        width = max(view[2] - view[0], text_width(shown_text(_caption(
            candidate, view[2] - view[0])), TEXT_SIZE, SANS_BOLD))
        return drawn, _spot(room, taken, width, view[3] - view[1] + 22.0), view[3] - view[1]

    drawn, spot, height = tried(region)
    past = spot[1] + height + 22.0 > room.bottom       # past the page's height
    if spot[1] + height + 22.0 <= floor or (not past and any(
            inner.parent == region.letter for inner in regions)):
        return region, drawn, spot
    base = next((other.zoom for other in regions if other.letter == region.parent), 1.0)
    step = round(region.zoom / base)
    least = max(DETAIL_ZOOM[0], step / 2)      # at least half its own: a detail, not a dot
    best = (region, drawn, spot)
    while step - 1 >= least:
        step -= 1
        candidate = replace(region, zoom=base * step)
        smaller, place, tall = tried(candidate)
        if not _readable(*smaller, troubles=_troubles(*drawn) if past else None):
            break                         # smaller still would crowd what it shows
        if place[1] + tall + 22.0 <= floor:
            return candidate, smaller, place
        if past:                          # the page too tall: the smallest readable
            best = (candidate, smaller, place)
    return best


def _readable(detail: Canvas, view, inside: set[str], troubles: int | None = None) -> bool:
    """Whether a detail shows its points the readable distance apart (or at one place) and
    every label of what it shows on a clean spot — or, given the ``troubles`` of the detail
    it would replace, no more of its labels crowded (:func:`_troubles`)."""
    marks = [(x, y) for x, y, _, _ in detail.point_marks
             if view[0] <= x <= view[2] and view[1] <= y <= view[3]]
    for index, (x0, y0) in enumerate(marks):
        for x1, y1 in marks[index + 1:]:
            if 0.5 < math.hypot(x1 - x0, y1 - y0) < DENSE_PX:
                return False
    if troubles is not None:
        return _troubles(detail, view, inside) <= troubles
    return all(label.clean for label in detail.labels if " ".join(label.points) in inside)


def _troubles(detail: Canvas, view, inside: set[str]) -> int:
    """How many labels of what a detail shows a reader sees crowded (:func:`_troubled`)."""
    return sum(_troubled(detail, label) for label in detail.labels
               if " ".join(label.points) in inside)


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
    if region.crowded:         # listed in the figure's table: named here where clean
        detail.requests = [replace(request, optional=True)
                           if set(request.points) & set(region.crowded) else request
                           for request in detail.requests]
    box = (x0 * scale, y0 * scale, x1 * scale, y1 * scale)
    reach = 60.0               # labels are placed for the points in and near the region
    detail.requests = [_anchored(request, box) for request in detail.requests]
    detail.requests = [request for request in detail.requests
                       if box[0] - reach <= request.anchor[0] <= box[2] + reach
                       and box[1] - reach <= request.anchor[1] <= box[3] + reach]
    detail.place(labels=_inside(detail, box))      # inside the frame where they can
    inside = {" ".join(label.points) for label in detail.labels
              if box[0] <= label.requested[0] <= box[2]
              and box[1] <= label.requested[1] <= box[3]}
    # the frame holds the labels kept whole: where one reaches past the region, the detail
    # shows that much more of the drawing
    view = list(box)
    for label in detail.labels:
        if " ".join(label.points) in inside:
            view = [min(view[0], label.box[0] - 2.0), min(view[1], label.box[1] - 2.0),
                    max(view[2], label.box[2] + 2.0), max(view[3], label.box[3] + 2.0)]
    return detail, view, inside


#: how far (px) past a detail's region its labels may go where, inside it, a leader would
#: cross an arrow or a line a label (the frame then widens to hold them)
WIDER_PX = 30.0


def _inside(detail: Canvas, box: tuple[float, float, float, float]) -> tuple:
    """A detail's labels placed (:meth:`Canvas.trial`) inside its region ``box`` where they
    can — or, where that leaves some of them crowded (:func:`_troubled`: a leader across an
    arrow, a line across a label) and :data:`WIDER_PX` more room round it leaves fewer,
    within that."""
    def troubles(labels) -> int:
        return sum(_troubled(detail, label) for label in labels     # a clean spot's
                   if (label.leader or not label.clean)              # label: on no line
                   and box[0] <= label.requested[0] <= box[2]
                   and box[1] <= label.requested[1] <= box[3])

    placed = detail.trial(box)
    first = troubles(placed)
    if not first:
        return placed
    wider = detail.trial((box[0] - WIDER_PX, box[1] - WIDER_PX, box[2] + WIDER_PX,
                          box[3] + WIDER_PX))
    return wider if troubles(wider) < first else placed


def _caption(region: Detail, width: float | None = None) -> Message:
    """The caption under a detail: its numeral, its enlargement, the detail it is marked in
    (where that fits the detail's ``width``: the line under the figure says it anyway)."""
    short = message("{letter}: detail ×{zoom:g}", letter=region.letter, zoom=region.zoom)
    if not region.parent:
        return short
    long = message("{letter}: detail ×{zoom:g} (marked in detail {parent})",
                   letter=region.letter, zoom=region.zoom, parent=region.parent)
    if width is not None and text_width(shown_text(long), TEXT_SIZE, SANS_BOLD) > width:
        return short
    return long


def _said(region: Detail) -> Message:
    """The line under a figure that says what a detail is."""
    if region.parent:
        return message("detail {letter}: the region marked in detail {parent}, drawn {zoom:g} "
                       "times larger than the figure", letter=region.letter,
                       parent=region.parent, zoom=region.zoom)
    return message("detail {letter}: the marked region drawn {zoom:g} times larger",
                   letter=region.letter, zoom=region.zoom)
