"""Point labels in textbook style, and their placement without overlaps (shapely).

Label text
----------
A plan label is written the way a textbook prints it: the letter in italics and what follows
it as a subscript — ``c4`` → c₄, ``n_CB`` → n with subscript CB, ``b@lever`` → b with the link
name *lever* as an upright subscript (the image of B taken as a point of the lever),
``k_C@lever`` → k with subscript "C, lever". Digits and link names are upright, point names
italic. Labels of points that coincide on the drawing are merged into one label joined by "≡"
(``p ≡ a ≡ c_frame``), the pole first.

Placement
---------
Each label is tried at 16 directions around its point and at growing distances; a candidate
box may not overlap a label already placed, and among the rest the one with the least length of
drawn lines inside it, the least area of point marks and other text under it and the smallest
distance wins (ties: the first direction tried, up-right first). Labels are placed in a fixed
order, so the result is deterministic. A label pushed far from its point gets a thin leader.

Examples
--------
>>> def show(runs):
...     return " ".join(f"{text!r}:{kind}" for text, kind in runs)
>>> show(label_runs("b@lever"))
"'b':main 'lever':upright"
>>> show(label_runs("n_CB"))
"'n':main 'CB':sub"
>>> show(label_runs("O2"))
"'O':main '2':upright"
>>> show(label_runs("k_C@lever"))
"'k':main 'C':sub ', lever':upright"
>>> plain(merge_runs([label_runs("p"), label_runs("c@frame")]))
'p ≡ c frame'
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from enum import StrEnum

from .style import LABEL, NBSP, SUB_SCALE, SUB_SHIFT, text_width

__all__ = [
    "LabelRequest",
    "PlacedLabel",
    "RunKind",
    "label_runs",
    "merge_runs",
    "place_labels",
    "plain",
    "runs_extent",
]


class RunKind(StrEnum):
    """How a run of label text is set: ``main`` (italic), ``sub`` (italic subscript),
    ``upright`` (upright subscript: digits, link names) or ``sep`` (upright, on the
    baseline)."""

    MAIN = "main"
    SUB = "sub"
    UPRIGHT = "upright"
    SEP = "sep"


#: the runs set small and lowered, and the runs set upright
SMALL_RUNS = frozenset({RunKind.SUB, RunKind.UPRIGHT})
UPRIGHT_RUNS = frozenset({RunKind.UPRIGHT, RunKind.SEP})

#: a run of label text: (text, its RunKind)
Run = tuple[str, RunKind]

#: gap (px) kept around a label's text
PADDING = 2.0
#: further gap (px) between two labels, so that neighbours never read as one
LABEL_GAP = 7.0
#: directions tried, degrees counter-clockwise from +x on the page (up-right first)
DIRECTIONS = (45, 135, -45, -135, 0, 90, 180, -90,
              22.5, 67.5, 112.5, 157.5, -22.5, -67.5, -112.5, -157.5)
#: distances (px) tried beyond the point's mark
DISTANCES = (2.0, 6.0, 11.0, 17.0, 25.0, 35.0, 48.0, 64.0, 84.0)
#: beyond this distance (px) a label gets a leader line to its point
LEADER_DISTANCE = 14.0
#: cost of one px of a drawn line under a label, relative to one px of distance
LINE_COST = 30.0
#: cost of one px² of a point mark or fixed text under a label
AREA_COST = 2.0


def _split_digits(name: str) -> tuple[str, str]:
    head = name.rstrip("0123456789")
    return (head, name[len(head):]) if head else (name, "")


def label_runs(label: str) -> tuple[Run, ...]:
    """The runs of a label in textbook style (see the module docstring)."""
    name, at, link = label.partition("@")
    main, _, rest = name.partition("_")
    main, digits = _split_digits(main)
    parts: list[Run] = []
    if digits:
        parts.append((digits, RunKind.UPRIGHT))
    if rest:
        # point names (C, CB, O2) are italic; link and pair names (lever, block/lever) upright
        parts.append((rest, RunKind.UPRIGHT if any(ch.islower() for ch in rest) else RunKind.SUB))
    if at:
        parts.append((link, RunKind.UPRIGHT))
    runs: list[Run] = [(main, RunKind.MAIN)]
    for index, (text, kind) in enumerate(parts):
        runs.append(((", " if index else "") + text, kind))
    return tuple(runs)


def merge_runs(labels: Iterable[Sequence[Run]]) -> tuple[Run, ...]:
    """Join the runs of coincident points with " ≡ "."""
    out: list[Run] = []
    for index, runs in enumerate(labels):
        if index:
            out.append((f"{NBSP}≡{NBSP}", RunKind.SEP))
        out.extend(runs)
    return tuple(out)


def plain(runs: Sequence[Run]) -> str:
    """The runs as plain text (subscripts after a space), e.g. for tests and titles."""
    out = ""
    for text, kind in runs:
        out += (" " + text) if kind == RunKind.UPRIGHT and text[0].isalpha() else text
    return out.replace(NBSP, " ")


def runs_extent(runs: Sequence[Run], size: float) -> tuple[float, float, float]:
    """(width, ascent, descent) of the runs at ``size`` px, from the baseline."""
    width = 0.0
    descent = 0.24 * size
    for text, kind in runs:
        if kind in SMALL_RUNS:
            width += text_width(text, size * SUB_SCALE, LABEL)
            descent = max(descent, SUB_SHIFT * size + 0.24 * size * SUB_SCALE)
        else:
            width += text_width(text, size, LABEL)
    return width, 0.76 * size, descent


@dataclass(frozen=True, slots=True)
class LabelRequest:
    """A label to place: the points it names, its anchor (px, y down), its runs, its size,
    the radius of the point's mark, and a style class (``label``, ``faint``, ``flag``)."""

    points: tuple[str, ...]
    anchor: tuple[float, float]
    runs: tuple[Run, ...]
    size: float
    mark_radius: float = 3.0
    css: str = "label"


@dataclass(frozen=True, slots=True)
class PlacedLabel:
    """A placed label: its request's data, the baseline start (px), the box it covers
    ``(x0, y0, x1, y1)`` (padding included) and whether a leader line joins it to the point."""

    points: tuple[str, ...]
    anchor: tuple[float, float]
    runs: tuple[Run, ...]
    size: float
    baseline: tuple[float, float]
    box: tuple[float, float, float, float]
    leader: bool
    css: str

    @property
    def text(self) -> str:
        return plain(self.runs)


def _candidate(anchor, direction_deg, distance, width, ascent, descent):
    """Baseline and box of a label placed ``distance`` beyond the anchor in a direction."""
    ux = math.cos(math.radians(direction_deg))
    uy = -math.sin(math.radians(direction_deg))          # page y points down
    half_w, half_h = width / 2 + PADDING, (ascent + descent) / 2 + PADDING
    # the box sits beyond the point: its edge (axis directions) or its corner (diagonals)
    # nearest to the point lies `distance` away along the direction
    sx = max(-1.0, min(1.0, ux * math.sqrt(2)))
    sy = max(-1.0, min(1.0, uy * math.sqrt(2)))
    cx = anchor[0] + ux * distance + sx * half_w
    cy = anchor[1] + uy * distance + sy * half_h
    box = (cx - half_w, cy - half_h, cx + half_w, cy + half_h)
    baseline = (box[0] + PADDING, box[1] + PADDING + ascent)
    return baseline, box


def _overlaps(bounds, taken) -> bool:
    """Whether a label's box, widened by the gap kept between labels, touches a placed one
    (plain rectangle arithmetic: boundaries touching count, as for shapely's intersects)."""
    x0, y0 = bounds[0] - LABEL_GAP, bounds[1] - LABEL_GAP / 2
    x1, y1 = bounds[2] + LABEL_GAP, bounds[3] + LABEL_GAP / 2
    return any(x0 <= b[2] and b[0] <= x1 and y0 <= b[3] and b[1] <= y1 for b in taken)


def place_labels(requests: Sequence[LabelRequest], lines: Sequence, areas: Sequence
                 ) -> tuple[PlacedLabel, ...]:
    """Place labels so that no two overlap and as few drawn lines as possible run under them.

    Parameters
    ----------
    requests
        The labels, placed in this order.
    lines
        Shapely geometries of drawn lines (their length under a label counts).
    areas
        Shapely geometries of point marks, symbols and fixed text (their area counts).

    Examples
    --------
    >>> from shapely.geometry import LineString
    >>> request = LabelRequest(("b",), (0.0, 0.0), label_runs("b"), 15.0)
    >>> placed = place_labels([request, request], [LineString([(-50, 0), (50, 0)])], [])
    >>> len(placed), placed[0].box[2] < placed[1].box[0] or placed[1].box[2] < placed[0].box[0]
    (2, True)
    """
    import numpy as np
    import shapely
    from shapely import unary_union
    from shapely.geometry import Point

    line_union = unary_union(list(lines)) if lines else None
    area_union = unary_union(list(areas)) if areas else None
    placed: list[PlacedLabel] = []
    taken: list[tuple[float, float, float, float]] = []     # placed boxes (x0, y0, x1, y1)
    for request in requests:
        width, ascent, descent = runs_extent(request.runs, request.size)
        own_mark = Point(request.anchor).buffer(request.mark_radius + 1.0, quad_segs=4)
        # what lies near this label only: every candidate box lies inside this window, so a
        # box meets the clipped lines exactly where it meets them all (and far faster)
        reach = request.mark_radius + DISTANCES[-1] + width + ascent + descent + 4 * PADDING
        window = (request.anchor[0] - reach, request.anchor[1] - reach,
                  request.anchor[0] + reach, request.anchor[1] + reach)
        near_lines = near_areas = None
        if line_union is not None:
            near_lines = shapely.clip_by_rect(line_union, *window)
            shapely.prepare(near_lines)
        if area_union is not None:
            near_areas = shapely.clip_by_rect(area_union, *window)
            shapely.prepare(near_areas)
        best = None
        for distance in DISTANCES:
            reach = request.mark_radius + distance
            # the 16 candidates of this distance, free of placed labels, tested in bulk
            spots = []
            for order, direction in enumerate(DIRECTIONS):
                baseline, bounds = _candidate(request.anchor, direction, reach, width,
                                              ascent, descent)
                if not _overlaps(bounds, taken):
                    spots.append((order, baseline, bounds))
            if spots:
                corners = np.array([bounds for _, _, bounds in spots])
                shapes = shapely.box(corners[:, 0], corners[:, 1], corners[:, 2], corners[:, 3])
                costs = np.array([distance + 0.05 * order for order, _, _ in spots])
                if near_lines is not None:
                    hit = shapely.intersects(near_lines, shapes)
                    for index in np.flatnonzero(hit):   # the lines inside the box
                        costs[index] += LINE_COST * shapely.length(
                            shapely.clip_by_rect(near_lines, *corners[index]))
                if near_areas is not None:
                    hit = shapely.intersects(near_areas, shapes)
                    for index in np.flatnonzero(hit):   # marks and text under it, not its own
                        under = shapely.clip_by_rect(near_areas, *corners[index])
                        costs[index] += AREA_COST * (shapely.area(under) - shapely.area(
                            shapely.intersection(under, own_mark)))
                for cost, (_, baseline, bounds) in zip(costs.tolist(), spots, strict=True):
                    if best is None or cost < best[0] - 1e-9:
                        best = (cost, baseline, bounds, distance)
            if best is not None and best[0] <= distance + 1.0:
                break                       # a clean spot at this distance: nearer is none
        if best is None:                    # every spot overlaps: put it below everything
            bottom = max((b[3] for b in taken), default=request.anchor[1])
            baseline, bounds = _candidate((request.anchor[0], bottom + 4), -90, 0.0, width,
                                          ascent, descent)
            best = (math.inf, baseline, bounds, LEADER_DISTANCE + 1)
        _, baseline, bounds, distance = best
        taken.append(tuple(bounds))
        placed.append(PlacedLabel(request.points, request.anchor, request.runs, request.size,
                                  (round(baseline[0], 2), round(baseline[1], 2)),
                                  tuple(round(v, 2) for v in bounds),
                                  distance > LEADER_DISTANCE, request.css))
    return tuple(placed)
