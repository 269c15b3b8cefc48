"""Point labels in textbook style, and their placement without overlaps.

Label text
----------
A plan label is written the way a textbook prints it: the letter in italics and what follows
it as a subscript — ``c4`` → c₄, ``n_CB`` → n with subscript CB, ``b@lever`` → b with the link
name *lever* as an upright subscript (the image of B taken as a point of the lever),
``k_C@lever`` → k with subscript "C, lever"; with the links' numbers (the course's notation) a
point of link 3 is b₃ and k_B₃ instead. Digits and link names are upright, point names
italic; a point named like a force's symbol (``G1``, beside the weight G₁ of link 1) is set
upright as it is written, G1 (:func:`planmethod.vocabulary.reads_as_symbol`). Labels of
points that coincide on the drawing are merged into one label joined by "≡" (``p ≡ a ≡
c_frame``), the pole first.

Placement
---------
Each label is tried at 16 directions around its point and at growing distances; a candidate
box may not overlap a label already placed, and among the rest the one with the least length of
drawn lines inside it, the least area of point marks and other text under it and the smallest
distance wins (ties: the first direction tried, up-right first). The costs are plain array
arithmetic, every candidate of the first three distances at once (then the rest): the drawn
lines as straight pieces clipped to each box, the marks and text as rectangles (a round mark
as the square of its area). The first three distances need no leader, so what their spots
cost before the labels placed come in is costed for all labels together, up front. Labels
are placed in a fixed order, so the result is deterministic. A label pushed far from its
point gets a thin leader. Where the cheapest spot is one a reader sees crowded — a line
through its text, its leader across an arrow (or by a hair past an arrow's end), another
leader or a label — the label takes the cheapest spot that is not, among twice the
directions, its leader starting anywhere along the force, the arm or the curved arrow it names
(its ``span``), if there is one — but not within :func:`near_only` (the frames of a turn drawn
without enlarged details, where the time counts).

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
>>> show(label_runs("b@lever", {"lever": 3})), show(label_runs("k_B@lever", {"lever": 3}))
("'b':main '3':upright", "'k':main 'B':sub '3':upright")
>>> show(label_runs("k1_Q")), show(label_runs("k2_Q"))
("'k':main 'Q':sub", "'k′':main 'Q':sub")
>>> show(label_runs("G1"))                  # upright as written: never the weight G₁
"'G1':sep"
>>> plain(merge_runs([label_runs("p"), label_runs("c@frame")]))
'p ≡ c frame'
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from contextvars import ContextVar
from dataclasses import dataclass, replace
from enum import StrEnum

import numpy as np

from ..vocabulary import coriolis_letter, reads_as_symbol
from .style import CLEARANCE_PX, LABEL, NBSP, SUB_SCALE, SUB_SHIFT, TOUCH_PX, text_width

__all__ = [
    "LabelRequest",
    "PlacedLabel",
    "RunKind",
    "drafted",
    "drawn_length",
    "label_runs",
    "merge_runs",
    "near_only",
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
DISTANCES = (2.0, 6.0, 11.0, 17.0, 25.0, 35.0, 48.0, 64.0, 84.0, 110.0, 140.0, 180.0, 230.0)
#: beyond this distance (px) a label gets a leader line to its point
LEADER_DISTANCE = 14.0
#: a leader may cross the lines through its own point within this distance (px) of it
LEADER_START = 1.5
#: cost of a leader crossing a vector's arrow (px of distance)
VECTOR_CROSSING_COST = 250.0
#: cost of a leader crossing another label or leader: a spot taken only where no other is
CLASH_COST = 2000.0
#: cost of one px of a drawn line under a label, relative to one px of distance
LINE_COST = 30.0
#: cost of one px² of a point mark or fixed text under a label
AREA_COST = 2.0
#: cost (px) of a spot on the side opposite a label's ``lean``, half of it at right angles
LEAN_COST = 1.5
#: cost (px) of a spot that leaves the bounds the labels keep within
OUTSIDE_COST = 60.0
#: a spot is clean if it costs no more than this (px) beyond its distance, side and leader's
#: thin crossings: a hair of a line in its padding
CLEAN_SLACK = 1.0
#: a label may come this near (px) its own point's mark: the room other labels keep from a
#: point's mark (``planmethod.render.canvas.KEEP_CLEAR``) is not held against its own label
OWN_ROOM = CLEARANCE_PX
#: a crowded label on a leader (no details) keeps its box, padding included, this far (px)
#: from every mark and fixed text: the touching distance of a figure without details and
#: one px more, for a round mark counted as the square of its area
CROWDED_ROOM = TOUCH_PX + 1.0
#: what an arrow crossed by a crowded label's leader costs (px of distance): a leader may
#: cross arrows in a figure without details, but a spot a little farther that crosses none
#: is taken first
CROWDED_CROSSING_COST = 20.0
#: a label's text less its padding and the figure check's hair: what a line must not cross
_INNER = np.array([PADDING + 0.6, PADDING + 0.6, -PADDING - 0.6, -PADDING - 0.6])
#: the length (px) of a line through a label's text that a reader sees as crossing it
TROUBLE_PX = 1.5
#: a label's text less its padding: what a spot found for a crowded label keeps lines out of
_TEXT = np.array([PADDING, PADDING, -PADDING, -PADDING])
#: the length (px) of lines in that text such a spot may have: a margin under
#: :data:`TROUBLE_PX` for the fonts' metrics, which the figure check reads otherwise
CLEAR_PX = 0.5
#: the places along the vector a label names (fractions of its length) that its leader may
#: start from where its cheapest spot is crowded (:func:`_rescued`): its middle first, none
#: on the last 15 % (an arrow's head)
RESCUE_ALONG = (0.5, 0.75, 0.3, 0.2, 0.85, 0.1, 0.6, 0.4)
#: what a px of a rescued label's leader start moved along its vector costs (px of distance)
SHIFT_COST = 0.5
#: how far (px) past its ends an arrow's piece counts as crossed where a crowded label's
#: leader is looked at: the figure is written to 0.01 px, where a leader that passes a
#: head's corner by a hair may touch it
GRAZE_PX = 0.05
#: the directions tried for a crowded label on a leader: those of every label, then the
#: ones halfway between them
CROWDED_DIRECTIONS = np.concatenate((DIRECTIONS, np.asarray(DIRECTIONS[8:]) + 11.25,
                                     np.asarray(DIRECTIONS[8:]) - 11.25))


def _split_digits(name: str) -> tuple[str, str]:
    head = name.rstrip("0123456789")
    return (head, name[len(head):]) if head else (name, "")


def label_runs(label: str, numbers: Mapping[str, int] | None = None) -> tuple[Run, ...]:
    """The runs of a label in textbook style (see the module docstring). With the links'
    ``numbers`` a point taken as a point of a link carries the link's number: ``b@lever`` is
    b₃, ``k_B@lever`` is k with subscript B₃."""
    name, at, link = label.partition("@")
    main, _, rest = name.partition("_")
    if not rest and reads_as_symbol(main):  # G1 upright as written: never the weight G₁
        return ((main, RunKind.SEP), *_link_runs(link if at else "", numbers, False))
    main, digits = _split_digits(main)
    if main == "k" and digits and rest:     # a Coriolis point's side index: k1_Q is k_Q
        main, digits = coriolis_letter(digits), ""
    parts: list[Run] = []
    if digits:
        parts.append((digits, RunKind.UPRIGHT))
    if rest:
        # point names (C, CB, O2) are italic; link and pair names (lever, block/lever) upright
        parts.append((rest, RunKind.UPRIGHT if any(ch.islower() for ch in rest) else RunKind.SUB))
    runs: list[Run] = [(main, RunKind.MAIN)]
    for index, (text, kind) in enumerate(parts):
        runs.append(((", " if index else "") + text, kind))
    return tuple(runs) + _link_runs(link if at else "", numbers, bool(parts))


def _link_runs(link: str, numbers: Mapping[str, int] | None, comma: bool) -> tuple[Run, ...]:
    """The run of the link a point is taken as a point of: its number (b₃, k_B₃: no comma),
    else its name."""
    if not link:
        return ()
    if numbers and link in numbers:
        return ((str(numbers[link]), RunKind.UPRIGHT),)
    return (((", " if comma else "") + link, RunKind.UPRIGHT),)


def merge_runs(labels: Iterable[Sequence[Run]], sign: str = "≡") -> tuple[Run, ...]:
    """Join the runs of coincident points with " ≡ " (or another ``sign``: " ≈ " for points
    that only the drawing cannot tell apart)."""
    out: list[Run] = []
    for index, runs in enumerate(labels):
        if index:
            out.append((f"{NBSP}{sign}{NBSP}", RunKind.SEP))
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
    the radius of the point's mark, a style class (``label``, ``faint``, ``flag``) and the
    vector it names, if any."""

    points: tuple[str, ...]
    anchor: tuple[float, float]
    runs: tuple[Run, ...]
    size: float
    mark_radius: float = 3.0
    css: str = "label"
    #: the vector a label names, (start, end) px, where it names one (or the dimension line
    #: of an arm's h; a curved arrow's arc as a polyline of more points): an enlarged detail
    #: that shows part of it anchors the label on that part, and a crowded label's leader
    #: may start anywhere along it
    span: tuple[tuple[float, float], ...] | None = None
    #: the side (a page direction) a label prefers, among spots as clean and as near: a
    #: dimension's label above its line
    lean: tuple[float, float] | None = None
    #: a label shown elsewhere too (in an enlarged detail): left out where it finds no clean
    #: spot (one with no line, label or leader in the way)
    optional: bool = False
    #: a crowded point's label in a figure drawn without details: where it finds no clean
    #: spot, it goes after the others to the nearest spot with nothing in its box, on a
    #: leader (see :func:`place_labels`), and is left out only where there is none
    crowded: bool = False


@dataclass(frozen=True, slots=True)
class PlacedLabel:
    """A placed label: its request's data, the baseline start (px), the box it covers
    ``(x0, y0, x1, y1)`` (padding included), whether a leader line joins it to the point and
    whether its spot is clean (no line, label or leader in the way). Its ``anchor`` is where
    its leader starts: for a crowded label of a force or an arm, a place along what it names
    other than the anchor asked for (:attr:`requested`)."""

    points: tuple[str, ...]
    anchor: tuple[float, float]
    runs: tuple[Run, ...]
    size: float
    baseline: tuple[float, float]
    box: tuple[float, float, float, float]
    leader: bool
    css: str
    clean: bool = True
    #: the anchor asked for, where the leader starts elsewhere (None: at it)
    named: tuple[float, float] | None = None

    @property
    def text(self) -> str:
        return plain(self.runs)

    @property
    def requested(self) -> tuple[float, float]:
        """The anchor the label was asked for (what a detail watches)."""
        return self.anchor if self.named is None else self.named


def _directions(degrees) -> tuple:
    """The unit vector (page y down) of each direction, and the signs that put a label's box
    beyond its point: its edge (axis directions) or its corner (diagonals) nearest to the point
    lies the distance away along the direction."""
    ux = np.cos(np.radians(degrees))
    uy = -np.sin(np.radians(degrees))
    return ux, uy, np.clip(ux * math.sqrt(2), -1.0, 1.0), np.clip(uy * math.sqrt(2), -1.0, 1.0)


def _boxes(anchor, directions, distance, half_w: float, half_h: float) -> np.ndarray:
    """The boxes (x0, y0, x1, y1) of a label ``distance`` beyond the anchor in each of the
    ``directions`` (see :func:`_directions`)."""
    ux, uy, sx, sy = directions
    cx = anchor[0] + ux * distance + sx * half_w
    cy = anchor[1] + uy * distance + sy * half_h
    return np.array((cx - half_w, cy - half_h, cx + half_w, cy + half_h)).T


#: the distances costed together (a label mostly settles within the first batch), and per
#: batch: each candidate's distance and direction terms and its cost before obstacles
_BATCHES = ((0, 1, 2), tuple(range(3, len(DISTANCES))))
_CANDIDATES = []
for _batch in _BATCHES:
    _steps = np.repeat(np.asarray(_batch), len(DIRECTIONS))
    _order = np.tile(np.arange(len(DIRECTIONS)), len(_batch))
    _CANDIDATES.append((_batch, np.asarray(DISTANCES)[_steps],
                        _directions(np.asarray(DIRECTIONS)[_order]),
                        np.asarray(DISTANCES)[_steps] + 0.05 * _order))
#: the spots a crowded label is tried at (:func:`_rescued`), batch by batch of distances:
#: each spot's distance, its direction's number and its direction (see :func:`_directions`)
_RESCUE_BATCHES = []
for _batch in (range(0, 5), range(5, 9), range(9, len(DISTANCES))):
    _steps = np.repeat(np.asarray(_batch), len(CROWDED_DIRECTIONS))
    _order = np.tile(np.arange(len(CROWDED_DIRECTIONS)), len(_batch))
    _RESCUE_BATCHES.append((np.asarray(DISTANCES)[_steps], _order,
                            _directions(CROWDED_DIRECTIONS[_order])))
#: where a label goes when every spot overlaps: straight below
_BELOW = _directions(np.array([-90.0]))
#: how far the gap kept between labels widens a box (x0, y0, x1, y1), touching counting
_GAP_LOW = np.array([-LABEL_GAP, -LABEL_GAP / 2])
_GAP_HIGH = np.array([LABEL_GAP, LABEL_GAP / 2])


def _segments(lines: Sequence[Sequence[tuple[float, float]]]) -> np.ndarray:
    """The straight pieces (x0, y0, x1, y1) of the drawn lines (point sequences); a piece
    drawn twice (a construction line along a vector) counts once.

    >>> _segments([((0, 0), (1, 0), (1, 1)), ((1, 0), (0, 0))]).tolist()
    [[0.0, 0.0, 1.0, 0.0], [1.0, 0.0, 1.0, 1.0]]
    """
    pieces = set()      # (a few dozen pieces: plain tuples are quicker than np.unique)
    for line in lines:
        for k in range(len(line) - 1):
            start = (float(line[k][0]), float(line[k][1]))
            end = (float(line[k + 1][0]), float(line[k + 1][1]))
            if end < start:     # each piece from its lower end (x, then y): drawn both ways,
                start, end = end, start                                     # it is one
            if start != end:                                   # no zero-length pieces
                pieces.add(start + end)
    if not pieces:
        return np.empty((0, 4))
    return np.array(sorted(pieces), dtype=float)


def _lengthened(segments: np.ndarray, by: float) -> np.ndarray:
    """The segments (x0, y0, x1, y1) each ``by`` px longer at both ends.

    >>> _lengthened(np.array([[0.0, 0.0, 4.0, 0.0]]), 0.5).tolist()
    [[-0.5, 0.0, 4.5, 0.0]]
    """
    along = segments[:, 2:] - segments[:, :2]
    along = by * along / np.maximum(np.hypot(*along.T), 1e-12)[:, None]
    return np.concatenate((segments[:, :2] - along, segments[:, 2:] + along), axis=1)


def _bounds(items: np.ndarray) -> np.ndarray:
    """The bounds (x0, y0, x1, y1), low corner first, of segments or rectangles given by two
    corners (x0, y0, x1, y1).

    >>> _bounds(np.array([[3.0, 0, 1, 2]])).tolist()
    [[1.0, 0.0, 3.0, 2.0]]
    """
    return np.concatenate((np.minimum(items[:, :2], items[:, 2:]),
                           np.maximum(items[:, :2], items[:, 2:])), axis=1)


def _lengths(segments: np.ndarray) -> np.ndarray:
    """The length of each segment (x0, y0, x1, y1).

    >>> _lengths(np.array([[0.0, 0, 3, 4]])).tolist()
    [5.0]
    """
    return np.hypot(segments[:, 2] - segments[:, 0], segments[:, 3] - segments[:, 1])


def _meeting(bounds: np.ndarray, region) -> np.ndarray:
    """Which of the segments' or rectangles' ``bounds`` (see :func:`_bounds`) meet the region
    (x0, y0, x1, y1)."""
    return ((bounds[:, 0] <= region[2]) & (bounds[:, 2] >= region[0])
            & (bounds[:, 1] <= region[3]) & (bounds[:, 3] >= region[1]))


def _clipped_lengths(segments: np.ndarray, boxes: np.ndarray, split: int | None = None,
                     bounds: np.ndarray | None = None) -> np.ndarray:
    """For each box (x0, y0, x1, y1), the length of the segments inside it (Liang–Barsky
    clipping of every segment against every box at once); with ``split``, that of the
    segments before it and that of the rest, as two rows. ``bounds`` are the segments'
    (see :func:`_bounds`), where known.

    >>> _clipped_lengths(np.array([[-5.0, 0.0, 5.0, 0.0]]), np.array([[0.0, -1, 2, 1],
    ...                                                               [3, 3, 4, 4]]))
    array([2., 0.])
    """
    piece, which, share = _inside(segments, boxes, bounds)
    if not len(piece):
        return np.zeros(len(boxes)) if split is None else np.zeros((2, len(boxes)))
    inside = share * _lengths(segments)[piece]
    if split is None:
        return np.bincount(which, weights=inside, minlength=len(boxes))
    # the segments from ``split`` on count in a second row: bins len(boxes) onwards
    return np.bincount(which + len(boxes) * (piece >= split), weights=inside,
                       minlength=2 * len(boxes)).reshape(2, len(boxes))


def _inside(segments: np.ndarray, boxes: np.ndarray, bounds: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Liang–Barsky clipping of every segment (x0, y0, x1, y1) against every box (x0, y0,
    x1, y1) at once, on the pairs whose bounds meet: the segment and the box of each such
    pair, and the share (0 to 1) of the segment inside the box. ``bounds`` are the segments'
    (see :func:`_bounds`), where known.

    >>> _inside(np.array([[0.0, 0, 10, 0]]), np.array([[4.0, -1, 6, 1], [20, 0, 30, 1]]))
    (array([0]), array([0]), array([0.2]))
    """
    if bounds is None:
        bounds = _bounds(segments)
    low_x, low_y, high_x, high_y = np.ascontiguousarray(bounds.T)
    left, top, right, bottom = np.ascontiguousarray(boxes.T)
    if len(segments) >= len(boxes):         # the longer of the two along the rows
        meet = low_x <= right[:, None]
        meet &= high_x >= left[:, None]
        meet &= low_y <= bottom[:, None]
        meet &= high_y >= top[:, None]
        which, piece = np.nonzero(meet)
    else:
        meet = low_x[:, None] <= right
        meet &= high_x[:, None] >= left
        meet &= low_y[:, None] <= bottom
        meet &= high_y[:, None] >= top
        piece, which = np.nonzero(meet)
    if not len(piece):
        return piece, which, np.zeros(0)
    return piece, which, _shares(segments, boxes, piece, which)


def _shares(segments: np.ndarray, boxes: np.ndarray, piece: np.ndarray, which: np.ndarray
            ) -> np.ndarray:
    """The share (0 to 1) of each segment ``piece`` inside its box ``which`` (Liang–Barsky
    clipping of the pairs given, which must not be empty).

    >>> _shares(np.array([[0.0, 0, 10, 0]]), np.array([[4.0, -1, 6, 1]]), np.array([0]),
    ...         np.array([0]))
    array([0.2])
    """
    # the pairs' coordinates as contiguous rows (x, y), so that every step runs on whole rows
    ends = np.take(np.ascontiguousarray(segments.T), piece, axis=1)
    box = np.take(np.ascontiguousarray(boxes.T), which, axis=1)
    start = ends[:2]
    delta = ends[2:] - start
    # along each axis the t (0 to 1 along the segment) where it meets the box's low edge and
    # its high edge; the nearer bounds t from below, the farther from above. A segment
    # parallel to an axis gives ±inf or nan there: nan bounds nothing (fmax and fmin pass
    # over it), and beyond an edge both are +inf (or both -inf), so nothing of it is inside
    before = start - box[:2]
    after = box[2:] - start
    with np.errstate(divide="ignore", invalid="ignore"):
        at_low = before / -delta
        at_high = after / delta
    low = np.fmax(np.minimum(at_low, at_high), 0.0)
    high = np.fmin(np.maximum(at_low, at_high), 1.0)
    share = np.fmin(high[0], high[1]) - np.fmax(low[0], low[1])
    return np.maximum(share, 0.0)


def drawn_length(lines: Sequence, boxes: Sequence) -> np.ndarray:
    """For each box (x0, y0, x1, y1), the length of the drawn lines (point sequences) inside
    it: how cluttered a place is.

    >>> drawn_length([((-5, 0), (5, 0))], [(0, -1, 2, 1), (3, 3, 4, 4)]).round(9).tolist()
    [2.0, 0.0]
    """
    segments = _segments(lines)
    boxes = np.asarray(boxes, dtype=float).reshape(-1, 4)
    return _clipped_lengths(segments, boxes) if len(segments) else np.zeros(len(boxes))


def _overlap_areas(rectangles: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """For each box, the area of the rectangles under it, added up in the rectangles' order
    (as a sum down the columns is; one over a single column would be taken pairwise)."""
    width = (np.minimum(rectangles[:, 2, None], boxes[:, 2])
             - np.maximum(rectangles[:, 0, None], boxes[:, 0]))
    height = (np.minimum(rectangles[:, 3, None], boxes[:, 3])
              - np.maximum(rectangles[:, 1, None], boxes[:, 1]))
    areas = np.maximum(width, 0.0) * np.maximum(height, 0.0)
    return areas.sum(axis=0) if len(boxes) > 1 else np.cumsum(areas, axis=0)[-1]


def _leaders(anchor, boxes: np.ndarray) -> np.ndarray:
    """The leader (x0, y0, x1, y1) of a label in each box: from its point to the nearest
    point of the box (as :meth:`planmethod.render.canvas.Canvas.place` draws it)."""
    ax, ay = anchor
    return np.array((np.full(len(boxes), ax), np.full(len(boxes), ay),
                     np.clip(ax, boxes[:, 0], boxes[:, 2]),
                     np.clip(ay, boxes[:, 1], boxes[:, 3]))).T


def _crossing(leaders: np.ndarray, segments: np.ndarray, bounds: np.ndarray | None = None,
              start: float = LEADER_START) -> np.ndarray:
    """(leaders × segments): whether each leader crosses each segment, more than ``start``
    px away from the point it starts at (a leader may leave its point across the lines
    through it). ``bounds`` are the segments' (see :func:`_bounds`), where known.

    >>> _crossing(np.array([[0.0, 0, 10, 0], [0, 0, 0, 10]]),
    ...           np.array([[5.0, -5, 5, 5], [0, 0, 3, 3]])).tolist()
    [[True, False], [False, False]]
    """
    if not len(segments) or not len(leaders):
        return np.zeros((len(leaders), len(segments)), dtype=bool)
    if bounds is None:
        bounds = _bounds(segments)
    low = np.minimum(leaders[:, :2], leaders[:, 2:]).min(axis=0)
    high = np.maximum(leaders[:, :2], leaders[:, 2:]).max(axis=0)
    meeting = _meeting(bounds, (low[0], low[1], high[0], high[1]))
    if not meeting.all():                 # only the segments near the leaders can cross
        out = np.zeros((len(leaders), len(segments)), dtype=bool)
        out[:, meeting] = _crossing(leaders, segments[meeting], bounds[meeting], start)
        return out
    ax, ay = leaders[:, 0, None], leaders[:, 1, None]
    rx, ry = leaders[:, 2, None] - ax, leaders[:, 3, None] - ay
    if (ax == ax[0]).all() and (ay == ay[0]).all():   # from one point: one row does for all
        ax, ay = ax[:1], ay[:1]
    cx, cy = segments[:, 0], segments[:, 1]
    sx, sy = segments[:, 2] - cx, segments[:, 3] - cy
    away_x, away_y = cx - ax, cy - ay
    denominator = rx * sy - ry * sx
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (away_x * sy - away_y * sx) / denominator
        u = (away_x * ry - away_y * rx) / denominator
    length = np.hypot(rx, ry)
    near = start / np.maximum(length, 1e-9)             # where it leaves its point
    return (np.abs(denominator) > 1e-12) & (t > near) & (t <= 1.0) & (u >= 0.0) & (u <= 1.0)


def _leaving(left, top, right, bottom, bounds: Sequence[float]) -> np.ndarray:
    """Where a box, given by its edges (arrays of one shape), leaves ``bounds`` (x0, y0, x1,
    y1).

    >>> _leaving(np.array([0.0, -1]), np.array([0.0, 0]), np.array([5.0, 5]),
    ...          np.array([5.0, 5]), (0, 0, 10, 10)).tolist()
    [False, True]
    """
    return (left < bounds[0]) | (top < bounds[1]) | (right > bounds[2]) | (bottom > bounds[3])


def _clear(boxes: np.ndarray, taken: np.ndarray) -> np.ndarray:
    """Which boxes (x0, y0, x1, y1) are clear of the labels placed in ``taken``: their boxes
    widened by the gap kept between labels, touching counting.

    >>> _clear(np.array([[0.0, 0, 10, 10], [30, 0, 40, 10]]), np.array([[12.0, 0, 20, 10]]))
    array([False,  True])
    """
    if not len(taken):
        return np.ones(len(boxes), dtype=bool)
    low = boxes[:, :2] + _GAP_LOW
    high = boxes[:, 2:] + _GAP_HIGH
    left, top, right, bottom = taken.T
    meet = low[:, 0, None] <= right                  # (box, label placed), in place
    meet &= left <= high[:, 0, None]
    meet &= low[:, 1, None] <= bottom
    meet &= top <= high[:, 1, None]
    return ~meet.any(axis=1)


def _near_spots(anchors: np.ndarray, reaches: np.ndarray, halves: np.ndarray,
                leans: np.ndarray, segments: np.ndarray, segment_bounds: np.ndarray,
                rectangles: np.ndarray, bounds: Sequence[float] | None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The spots of the first batch of distances (no leader there) for every label at once,
    with what each costs before the labels and leaders placed come in.

    Parameters
    ----------
    anchors
        Each label's point (x, y), one row a label.
    reaches
        Each label's mark radius (px), where its distances start.
    halves
        Each label's box half width and half height, padding included.
    leans
        Each label's preferred side (x, y), or nan where it has none.
    segments, segment_bounds
        The drawn lines' straight pieces and their bounds (see :func:`_bounds`).
    rectangles
        The marks and text (x0, y0, x1, y1) whose area under a spot counts.
    bounds
        The box the labels keep within where they can, if any.

    Returns
    -------
    boxes, clean, cost
        Per label (first axis) and candidate: the box (x0, y0, x1, y1), what a clean spot
        there costs and what the spot costs, each the same float as when costed alone.
    """
    _, distance, (ux, uy, sx, sy), base = _CANDIDATES[0]
    count, per_label = len(anchors), len(distance)
    half_w, half_h = halves[:, 0, None], halves[:, 1, None]
    reach = reaches[:, None] + distance
    cx = anchors[:, 0, None] + ux * reach + sx * half_w
    cy = anchors[:, 1, None] + uy * reach + sy * half_h
    # each edge of every box as one contiguous (label, spot) block
    corners = np.array((cx - half_w, cy - half_h, cx + half_w, cy + half_h))
    clean = np.broadcast_to(base + CLEAN_SLACK, (count, per_label))
    leaning = ~np.isnan(leans[:, 0])
    if leaning.any():                   # the preferred side first, among equals
        clean = np.where(leaning[:, None], clean + LEAN_COST * (
            1.0 - ux * leans[:, 0, None] - uy * leans[:, 1, None]), clean)
    cost = clean - CLEAN_SLACK
    if len(segments):  # the lines under each spot
        cost = cost + LINE_COST * _near_line_lengths(corners, segments, segment_bounds)
    if len(rectangles):
        cost = cost + AREA_COST * _near_areas(corners, anchors, reaches, rectangles)
    if bounds is not None:
        cost = cost + OUTSIDE_COST * _leaving(*corners, bounds)
    return np.moveaxis(corners, 0, -1), clean, cost


def _near_line_lengths(corners: np.ndarray, segments: np.ndarray, segment_bounds: np.ndarray
                       ) -> np.ndarray:
    """The length of the drawn lines under each spot of the first batch (label, spot), the
    spots given by their edges ``corners`` (left, top, right, bottom: each label × spot): the
    pieces near a label found first, then per spot."""
    left, top, right, bottom = corners
    count, per_label = left.shape
    flat = corners.reshape(4, -1).T
    label, piece = np.nonzero((segment_bounds[:, 0] <= right.max(axis=1)[:, None])
                              & (segment_bounds[:, 2] >= left.min(axis=1)[:, None])
                              & (segment_bounds[:, 1] <= bottom.max(axis=1)[:, None])
                              & (segment_bounds[:, 3] >= top.min(axis=1)[:, None]))
    # pairs by label, piece, then spot: each spot's pieces in their order
    near = np.take(np.ascontiguousarray(segment_bounds.T), piece, axis=1)[:, :, None]
    meet = near[0] <= np.take(right, label, axis=0)
    meet &= near[2] >= np.take(left, label, axis=0)
    meet &= near[1] <= np.take(bottom, label, axis=0)
    meet &= near[3] >= np.take(top, label, axis=0)
    rows, spots = np.nonzero(meet)
    piece, which = piece[rows], label[rows] * per_label + spots
    lengths = np.zeros(len(flat))
    if len(piece):
        inside = _shares(segments, flat, piece, which) * _lengths(segments)[piece]
        lengths = np.bincount(which, weights=inside, minlength=len(flat))
    return lengths.reshape(count, per_label)


def _near_areas(corners: np.ndarray, anchors: np.ndarray, reaches: np.ndarray,
                rectangles: np.ndarray) -> np.ndarray:
    """The area of the marks and text under each spot of the first batch (label, spot), but
    the label's own round mark (with the room kept round it), which it may touch."""
    left, top, right, bottom = corners
    count, per_label = left.shape
    own = (reaches + 1.0) * math.sqrt(math.pi) / 2 + OWN_ROOM
    own_low = anchors - own[:, None]
    own_high = anchors + own[:, None]
    width = (np.minimum(own_high[:, 0, None], right)
             - np.maximum(own_low[:, 0, None], left))
    height = (np.minimum(own_high[:, 1, None], bottom)
              - np.maximum(own_low[:, 1, None], top))
    mine = np.maximum(width, 0.0) * np.maximum(height, 0.0)
    under = _overlap_areas(rectangles, corners.reshape(4, -1).T).reshape(count, per_label)
    return np.maximum(under - mine, 0.0)


class _Drawing:
    """What labels are placed on: the drawn lines' pieces, the vectors' arrows, the marks
    and text as rectangles, the points' round marks and the bounds to keep within (each
    with the bounds of its items, see :func:`_bounds`); and what is placed so far — the
    labels' boxes and the leaders, in arrays made once for at most ``capacity`` labels."""

    def __init__(self, lines: Sequence, areas: Sequence, vectors: Sequence, marks: Sequence,
                 bounds: Sequence[float] | None, capacity: int) -> None:
        self.segments = _segments(lines)
        self.segment_bounds = _bounds(self.segments)
        self.arrows = _segments(vectors)
        self.arrow_bounds = _bounds(self.arrows)
        #: the arrows' pieces a crowded label's leader keeps off (:func:`_troubling`)
        self.grazed = _lengthened(self.arrows, GRAZE_PX)
        self.rectangles = np.asarray(areas, dtype=float).reshape(-1, 4)
        self.rectangle_bounds = _bounds(self.rectangles)
        self.marks = np.asarray(marks, dtype=float).reshape(-1, 4)
        self.bounds = bounds
        self._boxes = np.empty((capacity, 4))       # placed boxes (x0, y0, x1, y1)
        self._leaders = np.empty((capacity, 4))     # placed leaders (x0, y0, x1, y1)
        self._leader_bounds = np.empty((capacity, 4))   # and their bounds
        self._placed = self._led = self._bounded = 0

    @property
    def taken(self) -> np.ndarray:
        """The boxes of the labels placed."""
        return self._boxes[:self._placed]

    @property
    def leaders(self) -> np.ndarray:
        """The leaders drawn."""
        return self._leaders[:self._led]

    @property
    def leader_bounds(self) -> np.ndarray:
        """The bounds of the leaders drawn before the crowded labels' (which no later
        label's costing reads)."""
        return self._leader_bounds[:self._bounded]

    def take(self, box: np.ndarray, leader: np.ndarray | None = None,
             bounded: bool = True) -> None:
        """A label placed in ``box``, on ``leader`` (x0, y0, x1, y1) if it has one
        (``bounded``: its bounds kept for the labels placed after)."""
        self._boxes[self._placed] = box
        self._placed += 1
        if leader is not None:
            self._leaders[self._led] = leader[0]
            self._led += 1
            if bounded:
                self._leader_bounds[self._bounded] = _bounds(leader)[0]
                self._bounded += 1


#: set within :func:`drafted`: labels placed quickly, for a picture shown only for a moment
_DRAFT: ContextVar[bool] = ContextVar("planmethod_labels_drafted", default=False)


@contextlib.contextmanager
def drafted() -> Iterator[None]:
    """Within it, :func:`place_labels` places each label at the first spot near its point that
    no label placed before takes, blind to the drawn lines (a fraction of the time): for the
    pictures of a drag's intermediate steps, redrawn in full when the drag rests. Outside it,
    placement is as it always is.

    >>> request = LabelRequest(("b",), (0.0, 0.0), label_runs("b"), 15.0)
    >>> with drafted():
    ...     quick = place_labels([request, request], [((-50, 0), (50, 0))], [])
    >>> len(quick), quick[0].box != quick[1].box
    (2, True)
    """
    token = _DRAFT.set(True)
    try:
        yield
    finally:
        _DRAFT.reset(token)


#: set within :func:`near_only`: a crowded label does not look farther afield
_NEAR_ONLY: ContextVar[bool] = ContextVar("planmethod_labels_near_only", default=False)


@contextlib.contextmanager
def near_only() -> Iterator[None]:
    """Within it, :func:`place_labels` leaves a label at its cheapest spot even where a
    reader sees it crowded, without looking farther afield for a clear one (see the module
    docstring): for the many frames of a turn drawn without enlarged details, where the
    time counts and a leader across an arrow is allowed.

    >>> request = LabelRequest(("b",), (0.0, 0.0), label_runs("b"), 15.0)
    >>> with near_only():
    ...     placed = place_labels([request], [((-50, 0), (50, 0))], [])
    >>> len(placed)
    1
    """
    token = _NEAR_ONLY.set(True)
    try:
        yield
    finally:
        _NEAR_ONLY.reset(token)


def _drafted_labels(requests: Sequence[LabelRequest]) -> tuple[PlacedLabel, ...]:
    """Each label at the first of its nearest spots clear of the labels placed before (the
    first spot where none is), no leader; an optional label with no clear spot left out.
    Plain floats: a few boxes per label, where arrays cost more than they save."""
    _, distances, (ux, uy, sx, sy), _ = _CANDIDATES[0]
    spots = list(zip(distances.tolist(), ux.tolist(), uy.tolist(), sx.tolist(), sy.tolist(),
                     strict=True))
    taken: list[tuple[float, float, float, float]] = []
    placed: list[PlacedLabel] = []
    for request in requests:
        width, ascent, descent = runs_extent(request.runs, request.size)
        half_w, half_h = width / 2 + PADDING, (ascent + descent) / 2 + PADDING
        ax, ay = request.anchor
        first = chosen = None
        for distance, dx, dy, side_x, side_y in spots:
            reach = request.mark_radius + distance
            cx, cy = ax + dx * reach + side_x * half_w, ay + dy * reach + side_y * half_h
            box = (cx - half_w, cy - half_h, cx + half_w, cy + half_h)
            first = first or box
            if not any(box[0] - LABEL_GAP <= right and left <= box[2] + LABEL_GAP
                       and box[1] - LABEL_GAP / 2 <= bottom and top <= box[3] + LABEL_GAP / 2
                       for left, top, right, bottom in taken):
                chosen = box
                break
        if request.optional and chosen is None:
            continue
        box = chosen or first
        taken.append(box)
        placed.append(_placed(request, np.array(box), ascent, False, chosen is not None))
    return tuple(placed)


def place_labels(requests: Sequence[LabelRequest], lines: Sequence, areas: Sequence, *,
                 vectors: Sequence = (), marks: Sequence = (),
                 bounds: Sequence[float] | None = None) -> tuple[PlacedLabel, ...]:
    """Place labels so that no two overlap and as few drawn lines as possible run under them
    (within :func:`drafted`, quickly: a drag's intermediate pictures). Long: its documentation.

    A label shown elsewhere too (``optional``: in an enlarged detail) is left out where it
    finds no clean spot; a crowded point's label of a figure without details (``crowded``)
    then goes, after all the others, on a leader (:func:`_crowded_spot`).

    A label pushed far from its point gets a leader: a label's box never takes a leader drawn
    before, and a leader crosses a label placed before or another leader only where no other
    spot is free (:data:`CLASH_COST`); crossing a vector's arrow costs a leader
    :data:`VECTOR_CROSSING_COST` (other drawn lines it may cross).

    Parameters
    ----------
    requests
        The labels, placed in this order.
    lines
        The drawn lines as sequences of points (their length under a label counts).
    areas
        Point marks, symbols and fixed text as rectangles (x0, y0, x1, y1) (their area
        counts).
    vectors
        The vectors' arrows among the lines, as sequences of points: a leader keeps off them.
    marks
        The points' round marks (x, y, radius, i): each one's area, with the room other
        labels keep from it, is ``areas[i]``; a crowded label keeps only
        :data:`CROWDED_ROOM` from them.
    bounds
        A box (x0, y0, x1, y1) the labels keep within where they can (an enlarged detail's
        frame): a spot that leaves it costs :data:`OUTSIDE_COST`.

    Examples
    --------
    >>> request = LabelRequest(("b",), (0.0, 0.0), label_runs("b"), 15.0)
    >>> placed = place_labels([request, request], [((-50, 0), (50, 0))], [])
    >>> len(placed), placed[0].box[2] < placed[1].box[0] or placed[1].box[2] < placed[0].box[0]
    (2, True)
    """
    if _DRAFT.get():
        return _drafted_labels(requests)
    drawing = _Drawing(lines, areas, vectors, marks, bounds, len(requests))
    extents = [runs_extent(request.runs, request.size) for request in requests]
    halves = [(width / 2 + PADDING, (ascent + descent) / 2 + PADDING)
              for width, ascent, descent in extents]
    near = _near_of(requests, halves, drawing)
    placed: list[PlacedLabel] = []
    crowded: list[int] = []                 # crowded labels with no clean spot: placed last
    for number, request in enumerate(requests):
        label = _place_near(request, halves[number], extents[number][1],
                            (near[0][number], near[1][number], near[2][number]), drawing)
        if label is not None:
            placed.append(label)
        elif request.crowded:
            crowded.append(number)
    for number in crowded:                  # on a leader, after every other label
        label = _place_crowded(requests[number], halves[number], extents[number][1], drawing)
        if label is not None:               # (else nowhere free: left out)
            placed.append(label)
    return tuple(placed)


def _place_crowded(request: LabelRequest, half: tuple[float, float], ascent: float,
                   drawing: _Drawing) -> PlacedLabel | None:
    """A crowded label that found no clean spot, on a leader (:func:`_crowded_spot`), or
    None where nothing is free."""
    found = _crowded_spot(request, half, drawing.segments, drawing.segment_bounds,
                          drawing.arrows, drawing.rectangles, drawing.marks, drawing.taken,
                          drawing.leaders, drawing.bounds)
    if found is None:
        return None
    drawing.take(found, _leaders(request.anchor, found[None, :]), bounded=False)
    return _placed(request, found, ascent, True, False)


def _near_of(requests: Sequence[LabelRequest], halves: list[tuple[float, float]],
             drawing: _Drawing) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The first distances need no leader, so what their spots cost before the labels placed
    come in is costed for every label at once (:func:`_near_spots`)."""
    return _near_spots(
        np.array([request.anchor for request in requests], dtype=float).reshape(-1, 2),
        np.array([request.mark_radius for request in requests], dtype=float),
        np.array(halves, dtype=float).reshape(-1, 2),
        np.array([request.lean if request.lean is not None else (np.nan, np.nan)
                  for request in requests], dtype=float).reshape(-1, 2),
        drawing.segments, drawing.segment_bounds, drawing.rectangles, drawing.bounds)


def _place_near(request: LabelRequest, half: tuple[float, float], ascent: float,
                near: tuple[np.ndarray, np.ndarray, np.ndarray], drawing: _Drawing
                ) -> PlacedLabel | None:
    """A label placed at its cheapest spot (on a leader where far), or below everything where
    every spot is taken; None for an optional label with no clean spot (shown in a
    detail)."""
    best = _cheapest(request, half, near, drawing)
    tidy = best is not None and best[0] <= best[3]
    if request.optional and not tidy:
        return None
    ax, ay = request.anchor
    if best is None:                    # every spot overlaps: put it below everything
        bottom = float(drawing.taken[:, 3].max()) if len(drawing.taken) else ay
        best = (math.inf, _boxes((ax, bottom + 4), _BELOW, 0.0, *half)[0], math.inf, 0.0)
    far = best[2] > LEADER_DISTANCE
    # (a spot costed clean may be on a leader that grazes an arrow: looked at too)
    if (not tidy or far) and math.isfinite(best[0]) and not _NEAR_ONLY.get() and _troubling(
            request.anchor, best[1], far, drawing):
        rescued = _rescued(request, half, drawing)
        if rescued is not None:          # a spot a reader sees clear, found farther afield
            shifted, box, far = rescued
            drawing.take(box, _leaders(shifted.anchor, box[None, :]) if far else None)
            return _placed(shifted, box, ascent, far, tidy, named=request.anchor)
    drawing.take(best[1], _leaders(request.anchor, best[1][None, :]) if far else None)
    return _placed(request, best[1], ascent, far, tidy)


def _troubling(anchor: tuple[float, float], box: np.ndarray, leader: bool, drawing: _Drawing
               ) -> bool:
    """Whether a label in ``box`` is what a reader sees as crowded (as the figure check
    counts it): a drawn line or leader more than a hair (:data:`TROUBLE_PX`) through its
    text, or (with a ``leader`` from ``anchor``) its leader across a vector's arrow (or by a
    hair past a piece's end, :data:`GRAZE_PX`) or another leader away from its point, or
    through a label placed.

    >>> drawing = _Drawing([((0, -20), (0, 20))], [], [((0, -20), (0, 20))], [], None, 1)
    >>> _troubling((30.0, 0.0), np.array([-10.0, -5, 10, 5]), False, drawing)
    True
    >>> _troubling((-40.0, 0.0), np.array([-60.0, -5, -45, 5]), True, drawing)
    False
    """
    lines = np.concatenate((drawing.segments, drawing.leaders))
    inner = box + _INNER
    if len(lines) and _clipped_lengths(lines, inner[None, :])[0] > TROUBLE_PX:
        return True
    if not leader:
        return False
    crossed = np.concatenate((drawing.grazed, drawing.leaders))
    leader_line = _leaders(anchor, box[None, :])
    return bool(_crossing(leader_line, crossed).any()) or bool(
        len(drawing.taken) and _through(leader_line, drawing.taken)[0])


def _along(request: LabelRequest) -> list[tuple[float, float]]:
    """Where a label's leader may start: its anchor, and where it names a vector or a curved
    arrow (its ``span``), the places along it at :data:`RESCUE_ALONG` — the leader of a
    force's or a moment's label ends on its arrow anywhere.

    >>> _along(LabelRequest(("F",), (6.0, 0.0), (), 15.0, span=((0.0, 0.0), (10.0, 0.0))))
    [(6.0, 0.0), (5.0, 0.0), (7.5, 0.0), (3.0, 0.0), (2.0, 0.0), (8.5, 0.0), (1.0, 0.0), (4.0, 0.0)]
    """
    out = [request.anchor]
    if request.span is not None:
        out += [point_along(request.span, fraction) for fraction in RESCUE_ALONG]
    return list(dict.fromkeys(out))


def point_along(path: Sequence[tuple[float, float]], fraction: float) -> tuple[float, float]:
    """The point ``fraction`` of the way along the polyline ``path`` (of its length; a
    curved arrow's arc, or a straight vector's start and end).

    >>> point_along(((0.0, 0.0), (10.0, 0.0)), 0.25)
    (2.5, 0.0)
    >>> point_along(((0.0, 0.0), (10.0, 0.0), (10.0, 10.0)), 0.75)
    (10.0, 5.0)
    """
    if len(path) == 2:
        (sx, sy), (ex, ey) = path
        return (sx + fraction * (ex - sx), sy + fraction * (ey - sy))
    points = np.asarray(path, dtype=float)
    reached = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))))
    x, y = (np.interp(fraction * reached[-1], reached, points[:, axis]) for axis in (0, 1))
    return (float(x), float(y))


def _rescued(request: LabelRequest, half: tuple[float, float], drawing: _Drawing
             ) -> tuple[LabelRequest, np.ndarray, bool] | None:
    """A label whose cheapest spot a reader sees crowded (:func:`_troubling`) at the
    cheapest spot that is not: among :data:`CROWDED_DIRECTIONS` at every distance, from its
    anchor or another place along the vector it names (:func:`_along`, each px of the move
    costing :data:`SHIFT_COST`), the nearer distances first (:data:`_RESCUE_BATCHES`: a
    farther one only while it could still be cheaper). Returns the request with that anchor,
    the box and whether it needs a leader; None where every such spot is crowded too."""
    lines = np.concatenate((drawing.segments, drawing.leaders))
    around = (lines, _bounds(lines), np.concatenate((drawing.grazed, drawing.leaders)))
    anchors = np.asarray(_along(request), dtype=float)
    moved = SHIFT_COST * np.hypot(*(anchors - anchors[0]).T)
    found: tuple | None = None
    for candidates in _RESCUE_BATCHES:
        if found is not None and candidates[0][0] >= found[0]:
            break                   # no spot of a farther batch can be cheaper
        found = _rescue_batch(request, anchors, moved, half, candidates, around, drawing,
                              found)
    return None if found is None else found[1:]


def _rescue_batch(request: LabelRequest, anchors: np.ndarray, moved: np.ndarray,
                  half: tuple[float, float], candidates: tuple, around: tuple,
                  drawing: _Drawing, found: tuple | None) -> tuple | None:
    """The cheapest clear spot of :func:`_rescued` among ``candidates`` (distances, direction
    numbers, directions) round each of the ``anchors`` (what moving there costs: ``moved``)
    — (cost, request, box, leader) — where it is cheaper than the one ``found`` so far; else
    ``found``. ``around`` are the lines no text may lie on, their bounds, and the lines no
    leader may cross."""
    distance, order, directions = candidates
    lines, line_bounds, crossed = around
    which = np.repeat(np.arange(len(anchors)), len(distance))     # each spot's anchor
    boxes = np.concatenate([_boxes(anchor, directions, request.mark_radius + distance, *half)
                            for anchor in anchors])
    cost = np.tile(distance + 0.05 * order, len(anchors)) + moved[which]
    leading = np.tile(distance > LEADER_DISTANCE, len(anchors))
    spots = np.flatnonzero(cost < found[0]) if found is not None else np.arange(len(cost))
    spots = spots[_clear(boxes[spots], drawing.taken)]
    if len(lines) and len(spots):         # (the whole text: no hair of a line near it)
        spots = spots[_clipped_lengths(lines, boxes[spots] + _TEXT,
                                       bounds=line_bounds) <= CLEAR_PX]
    far = spots[leading[spots]]
    if len(far):           # no leader across an arrow, another leader or a label
        ends = np.clip(anchors[which[far]], boxes[far, :2], boxes[far, 2:])
        leaders = np.column_stack((anchors[which[far]], ends))
        blocked = _crossing(leaders, crossed).any(axis=1)
        if len(drawing.taken):
            blocked |= _through(leaders, drawing.taken) > 0
        spots = np.setdiff1d(spots, far[blocked])
    for index in np.unique(which[spots]).tolist():
        chosen = spots[which[spots] == index]
        shifted = replace(request, anchor=tuple(anchors[index].tolist()))
        table = _spot_costs(shifted, boxes[chosen], cost[chosen],
                            np.zeros(len(chosen), bool), None, drawing)
        best = int(np.argmin(table))
        if math.isfinite(table[best]) and (found is None or table[best] < found[0]):
            found = (float(table[best]), shifted, boxes[chosen[best]],
                     bool(leading[chosen[best]]))
    return found


#: the cheapest spot found for a label: (its cost, its box, its distance, what a clean spot
#: there costs)
_Best = tuple[float, np.ndarray, float, float]


def _cheapest(request: LabelRequest, half: tuple[float, float],
              near: tuple[np.ndarray, np.ndarray, np.ndarray], drawing: _Drawing
              ) -> _Best | None:
    """The cheapest spot for a label among the candidates of :data:`_CANDIDATES`, batch by
    batch: the nearest distance with a clean spot wins; ``near`` are its spots of the first
    batch and what they cost before the labels placed come in (:func:`_near_spots`). None
    where every spot is taken."""
    best: _Best | None = None
    for batch, distance, directions, base in _CANDIDATES:
        if batch is _BATCHES[0]:
            boxes, clean, table = _near_costs(near, drawing)
        else:
            boxes, clean, table = _far_costs(request, half, (distance, directions, base),
                                             best, drawing)
        best, settled = _pick(table, batch, boxes, clean, best)
        if settled:
            break
    return best


def _near_costs(near: tuple[np.ndarray, np.ndarray, np.ndarray], drawing: _Drawing
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A label's spots of the first batch, what a clean one costs and what each costs: as
    costed up front, only the labels and leaders placed since come in (no label on a
    leader)."""
    boxes, clean, cost = near
    contending = _clear(boxes, drawing.taken)
    if len(drawing.leaders):
        low = boxes[:, :2].min(axis=0)
        high = boxes[:, 2:].max(axis=0)
        meeting = _meeting(drawing.leader_bounds, (low[0], low[1], high[0], high[1]))
        if meeting.any():
            contending &= _clipped_lengths(drawing.leaders[meeting], boxes,
                                           bounds=drawing.leader_bounds[meeting]) <= 0.0
    return boxes, clean, np.where(contending, cost, np.inf)


def _far_costs(request: LabelRequest, half: tuple[float, float], candidates: tuple,
               best: _Best | None, drawing: _Drawing
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A label's spots at the distances of a later batch (``candidates``: their distances,
    directions and cost before obstacles, see :data:`_CANDIDATES`), what a clean one costs
    and what each costs (inf where it cannot be taken). Only the spots that can win are
    costed: those clear of the labels placed and, once a spot is found (``best``), cheaper
    than it before any obstacle's cost is added."""
    distance, directions, base = candidates
    boxes = _boxes(request.anchor, directions, request.mark_radius + distance, *half)
    # what a clean spot costs: its distance and its side; anything in the way makes a spot
    # not clean (a leader may cross thin lines: construction lines, links)
    clean = base + CLEAN_SLACK
    if request.lean is not None:      # the preferred side first, among equals
        ux, uy = directions[0], directions[1]
        clean = clean + LEAN_COST * (1.0 - ux * request.lean[0] - uy * request.lean[1])
    cost = clean - CLEAN_SLACK
    contending = _clear(boxes, drawing.taken)
    if best is not None:
        contending &= cost < best[0]
    chosen = np.flatnonzero(contending)
    table = np.full(len(boxes), np.inf)
    if len(chosen):
        table[chosen] = _spot_costs(request, boxes[chosen], cost[chosen],
                                    distance[chosen] > LEADER_DISTANCE, best, drawing)
    return boxes, clean, table


def _spot_costs(request: LabelRequest, spots: np.ndarray, cost: np.ndarray,
                leading: np.ndarray, best: _Best | None, drawing: _Drawing) -> np.ndarray:
    """What each of a label's spots costs (inf where a leader drawn before runs through it):
    the drawn lines and the areas under it, leaving the bounds, and for a spot far enough to
    need a leader (``leading``) the leader's crossings of leaders drawn before, of arrows and
    of labels placed."""
    ax, ay = request.anchor
    free = np.ones(len(spots), dtype=bool)
    # the region of the spots costed and of the leaders they would need
    low = spots[:, :2].min(axis=0)
    high = spots[:, 2:].max(axis=0)
    region = (min(low[0], ax), min(low[1], ay), max(high[0], ax), max(high[1], ay))
    meeting = _meeting(drawing.leader_bounds, region)
    before, before_bounds = drawing.leaders[meeting], drawing.leader_bounds[meeting]
    meeting = _meeting(drawing.segment_bounds, region)
    near = drawing.segments[meeting]
    if len(near) or len(before):  # the lines under each spot; no label on a leader
        lengths = _clipped_lengths(np.concatenate((near, before)), spots, len(near),
                                   np.concatenate((drawing.segment_bounds[meeting],
                                                   before_bounds)))
        cost = cost + LINE_COST * lengths[0]
        free &= lengths[1] <= 0.0
    under = drawing.rectangles[_meeting(drawing.rectangle_bounds, region)]
    if len(under):
        # the label's own round mark, which it may touch: as the square of its area
        own = (request.mark_radius + 1.0) * math.sqrt(math.pi) / 2 + OWN_ROOM
        own_mark = np.array([[ax - own, ay - own, ax + own, ay + own]])
        cost = cost + AREA_COST * np.maximum(
            _overlap_areas(under, spots) - _overlap_areas(own_mark, spots), 0.0)
    if drawing.bounds is not None:
        cost = cost + OUTSIDE_COST * _leaving(*spots.T, drawing.bounds)
    far = leading & free     # the leaders the spots that could still win would need
    if best is not None:
        far &= cost < best[0]
    if far.any():
        cost = cost + _leader_costs(request.anchor, spots, far, region, before,
                                    before_bounds, drawing)
    return np.where(free, cost, np.inf)


def _leader_costs(anchor, spots: np.ndarray, far: np.ndarray, region, before: np.ndarray,
                  before_bounds: np.ndarray, drawing: _Drawing) -> np.ndarray:
    """What the leaders to the ``far`` spots cost: the leaders drawn before (``before``, in
    the region) and the arrows they cross, and the labels they run through."""
    leaders = _leaders(anchor, spots[far])
    extra = np.zeros(len(spots))
    meeting = _meeting(drawing.arrow_bounds, region)
    close = drawing.arrows[meeting]
    weights = np.concatenate((np.full(len(before), CLASH_COST),
                              np.full(len(close), VECTOR_CROSSING_COST)))
    extra[far] = _crossing(leaders, np.concatenate((before, close)),
                           np.concatenate((before_bounds,
                                           drawing.arrow_bounds[meeting]))) @ weights
    others = drawing.taken[_meeting(drawing.taken, region)]
    if len(others):          # through another label: only where nothing else
        extra[far] += CLASH_COST * _through(leaders, others)
    return extra


def _pick(table: np.ndarray, batch: tuple[int, ...], boxes: np.ndarray, clean: np.ndarray,
          best: _Best | None) -> tuple[_Best | None, bool]:
    """The cheapest spot so far after a batch (per distance of the batch its cheapest free
    candidate, the first of equals; a nearer one kept unless a farther is cheaper), and
    whether it is settled: clean, so that no farther distance is tried."""
    table = table.reshape(len(batch), len(DIRECTIONS))
    picks = table.argmin(axis=1)
    lowest = np.minimum.reduce(table, axis=1).tolist()     # the values at the picks
    for row, step in enumerate(batch):   # the nearest distance with a clean spot wins
        index = row * len(DIRECTIONS) + picks[row]
        if lowest[row] < math.inf and (best is None or lowest[row] < best[0] - 1e-9):
            best = (lowest[row], boxes[index], DISTANCES[step], float(clean[index]))
        if best is not None and best[0] <= best[3]:
            return best, True
    return best, False


def _placed(request: LabelRequest, box: np.ndarray, ascent: float, leader: bool, clean: bool,
            named: tuple[float, float] | None = None) -> PlacedLabel:
    """The label of ``request`` placed in ``box`` (x0, y0, x1, y1, padding included): its
    baseline starts inside the padding, ``ascent`` below the box's top edge; ``named`` is
    the anchor asked for where the request's is another (a crowded label's, moved)."""
    corners = box.tolist()
    x0, y0 = corners[0], corners[1]
    return PlacedLabel(request.points, request.anchor, request.runs, request.size,
                       (round(x0 + PADDING, 2), round(y0 + PADDING + ascent, 2)),
                       tuple([round(v, 2) for v in corners]), leader, request.css, clean,
                       named if named != request.anchor else None)


def _crowded_spot(request: LabelRequest, half: tuple[float, float], segments: np.ndarray,
                  segment_bounds: np.ndarray, arrows: np.ndarray, rectangles: np.ndarray,
                  marks: np.ndarray, taken: np.ndarray, drawn_leaders: np.ndarray,
                  bounds: Sequence[float] | None) -> np.ndarray | None:
    """The box (x0, y0, x1, y1) of a crowded label that found no clean spot, on a leader:
    among the spots beyond :data:`LEADER_DISTANCE` in :data:`CROWDED_DIRECTIONS`, the
    nearest (an arrow its leader crosses counting :data:`CROWDED_CROSSING_COST`) whose box
    has no drawn line, label or leader in it, keeps :data:`CROWDED_ROOM` from every point's
    mark (``marks``: x, y, radius, the index of its room among the ``rectangles``) and
    overlaps no other area, whose leader crosses no other leader and runs through no label,
    no area and no other point's mark, and which stays within ``bounds``, if given; None where
    there is none. The room other labels keep round a point's mark is not held against it: a
    crowded point has no such room to give.

    >>> request = LabelRequest(("b",), (0.0, 0.0), label_runs("b"), 15.0, crowded=True)
    >>> lines = np.array([[-40.0, 0, 40, 0], [0, -40, 0, 40]])
    >>> marks = np.array([[0.0, 0, 3, 0], [5, 5, 3, 1]])
    >>> rooms = np.array([[-7.0, -7, 7, 7], [-2, -2, 12, 12]])
    >>> box = _crowded_spot(request, (6.0, 9.0), lines, _bounds(lines), np.empty((0, 4)),
    ...                     rooms, marks, np.empty((0, 4)), np.empty((0, 4)), None)
    >>> box.round(1).tolist()            # up and to the right, clear of both lines
    [14.1, -32.1, 26.1, -14.1]
    """
    # the marks as their bounding squares, and the areas that are not a mark's room
    radius = marks[:, 2:3]
    squares = np.column_stack((marks[:, :2] - radius, marks[:, :2] + radius))
    areas = np.delete(rectangles, marks[:, 3].astype(int), axis=0)
    boxes, cost = _crowded_boxes(request, half, np.concatenate((segments, drawn_leaders)),
                                 np.concatenate((segment_bounds, _bounds(drawn_leaders))),
                                 np.concatenate((squares, areas)), taken, bounds)
    if not len(boxes):
        return None
    leaders = _leaders(request.anchor, boxes)
    free = np.ones(len(boxes), dtype=bool)
    if len(drawn_leaders):      # (a crowded point's neighbour may start its leader a px off)
        free &= ~_crossing(leaders, drawn_leaders, start=LEADER_START / 3).any(axis=1)
    # labels, areas and other points' marks the leader runs through (not a mark that touches
    # its own point's: it cannot leave its point without)
    ax, ay = request.anchor
    reach = marks[:, 2] + request.mark_radius
    others = squares[(np.abs(marks[:, 0] - ax) > reach) | (np.abs(marks[:, 1] - ay) > reach)]
    crossed = np.concatenate((taken, areas, others))
    if len(crossed):
        free &= _through(leaders, crossed) == 0
    if len(arrows):
        cost = cost + CROWDED_CROSSING_COST * _crossing(leaders, arrows).sum(axis=1)
    if not free.any():
        return None
    return boxes[int(np.argmin(np.where(free, cost, np.inf)))]


def _crowded_boxes(request: LabelRequest, half: tuple[float, float], lines: np.ndarray,
                   line_bounds: np.ndarray, obstacles: np.ndarray, taken: np.ndarray,
                   bounds: Sequence[float] | None) -> tuple[np.ndarray, np.ndarray]:
    """A crowded label's spots on a leader whose box is free — of the labels placed, of the
    drawn ``lines`` and leaders, of the ``obstacles`` (marks and areas) by
    :data:`CROWDED_ROOM`, within ``bounds`` — and what each costs (its distance and
    direction)."""
    far = [distance for distance in DISTANCES if distance > LEADER_DISTANCE]
    distance = np.repeat(np.asarray(far), len(CROWDED_DIRECTIONS))
    order = np.tile(np.arange(len(CROWDED_DIRECTIONS)), len(far))
    boxes = _boxes(request.anchor, _directions(CROWDED_DIRECTIONS[order]),
                   request.mark_radius + distance, half[0], half[1])
    free = _clear(boxes, taken)
    if bounds is not None:
        free &= ~_leaving(*boxes.T, bounds)
    if len(lines):
        free &= _clipped_lengths(lines, boxes, bounds=line_bounds) <= 0.0
    if len(obstacles):
        grown = boxes + np.array([-CROWDED_ROOM, -CROWDED_ROOM, CROWDED_ROOM, CROWDED_ROOM])
        free &= _overlap_areas(obstacles, grown) <= 0.0
    return boxes[free], (distance + 0.05 * order)[free]


def _through(leaders: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """For each leader, how many of the boxes it runs through (Liang–Barsky, on the pairs
    whose bounds meet).

    >>> _through(np.array([[0.0, 0, 10, 0], [0, 5, 0, 9]]), np.array([[4.0, -1, 6, 1]]))
    array([1, 0])
    """
    piece, _, share = _inside(leaders, boxes)
    return np.bincount(piece[share > 1e-9], minlength=len(leaders))
