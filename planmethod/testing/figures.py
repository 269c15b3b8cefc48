"""The figure check: what a lecture slide or a printed sheet must not show, read from the SVG.

:func:`figure_problems` parses an SVG written by planmethod (with ``defusedxml``, like any file
it did not write itself) and lists, one line each:

* **code words** in any text: a ``name[index]`` or a ``snake_case`` identifier (two or more
  letters, an underscore, more: ``rocker_EF``, ``load[1]``, ``F_u,rocker_EF``); course notation
  such as ``M_b`` or ``a_S`` in a note is not one;
* **overlapping text**: two text boxes (labels, notes, legends, titles) that overlap by more
  than a hair — boxes are computed from the fonts' advance widths (the same table the labels are
  placed with) and each element's position, size and anchor, independently of the placer;
* **outside the viewBox**: a text box, line, polyline, polygon or circle that leaves the
  figure's viewBox;
* **legend items not drawn**: a legend's sample (its stroke colour, dash and width, or its
  fill) that no element of the figure itself has;
* **marks too near each other**: marks (circles with ``data-points``) of distinct points
  nearer each other than the figure's readable distance — :data:`READABLE_EM` of its point
  labels' size, 30 px at 15 px (docs/notation.md, "Legible figures") — neither in a region
  the figure draws again as an enlarged detail (a ``detail region`` frame; a detail's own
  marks are held to it too, unless a region of the detail is drawn again);
* **a label too near another point**: a point's label (``data-points``) whose text comes
  nearer than its clearance (:data:`CLEARANCE_EM` of the readable distance) to the mark of
  another point outside such a region — the reader could take it for that point's — and any
  other label (a force's, an arm's) on a point's mark;
* **a label crossed by a line**: a drawn line, polyline, polygon outline (an arrowhead too) or
  stroked rectangle, other than the label's own leader, running more than a hair through a
  label's text;
* **leaders crossing**: a leader (``class="leader"``, its label's ``data-points``) that crosses
  another leader or a vector's arrow (``class="arrow …"``: a straight or a curved one) away
  from the point it starts at.

A figure drawn without enlarged details by design (``details=False``: a workbook frame) is not
held to the readable distance, the clearance or leaders clear of arrows, but its point labels
keep :data:`TOUCH_PX` from other points' marks.

:func:`steady_problems` checks the frames of a turn: one viewBox per panel.
:func:`page_ratio` measures how much larger a figure's page is than what it draws, and
:func:`detail_depth` how deep its enlarged details nest.
:func:`numbering_problems` checks that a figure names links as a course's numbering does.

Examples
--------
>>> svg = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 100">'
...        '<g class="labels"><text x="10" y="50" font-size="12">rocker_EF</text>'
...        '<text x="12" y="52" font-size="12">B</text></g></svg>')
>>> for problem in figure_problems(svg):
...     print(problem)
code word 'rocker_EF' in text 'rocker_EF'
text 'rocker_EF' overlaps text 'B'
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable
from dataclasses import dataclass, field

from ..render.style import (
    LABEL,
    LABEL_SIZE,
    READABLE_EM,
    READABLE_PX,
    SANS,
    SANS_BOLD,
    TOUCH_PX,
    text_width,
)

__all__ = ["CLEARANCE_EM", "CODE_WORD", "READABLE_EM", "READABLE_PX", "TOUCH_PX", "TextBox",
           "detail_depth", "drawn_extent", "figure_problems", "numbering_problems",
           "page_ratio", "readable_px", "steady_problems", "text_boxes"]

#: a point's label keeps this fraction of the readable distance (0.5 em) from another
#: point's mark, so that it reads as its own point's
CLEARANCE_EM = 0.25
#: the length (px) of a drawn line inside a label's text that counts as crossing it
_CROSS_PX = 1.5
#: marks nearer than this (px) are at one place: SVG coordinates are written to 0.01 px
_SAME = 0.015

#: a code identifier in text: ``name[1]`` or a snake_case name with two or more letters first
CODE_WORD = re.compile(r"\b[A-Za-z_]\w*\[\d+\]|\b[A-Za-z]{2,}_\w+|\b\w+_\w+_\w+")

_SVG = "{http://www.w3.org/2000/svg}"
#: overlap (px) tolerated between two boxes: the fonts' side bearings
_HAIR = 0.6
#: how far (px) anything may reach past the viewBox: a stroke's half width
_EDGE = 1.5


@dataclass(frozen=True)
class TextBox:
    """One ``<text>`` element: its whole text, its class, its box (x0, y0, x1, y1) and the
    points it labels (``data-points``)."""

    text: str
    css: str
    box: tuple[float, float, float, float]
    points: tuple[str, ...] = ()
    size: float = 0.0


def _number(value: str | None, default: float = 0.0) -> float:
    try:
        return float(value) if value not in (None, "") else default
    except ValueError:
        return default


def _local(tag: str) -> str:
    return tag.rpartition("}")[2]


def _text_box(element, css: str) -> TextBox:
    size = _number(element.get("font-size"), 12.0)
    family = element.get("font-family") or ""
    italic = element.get("font-style") == "italic"
    font = LABEL if ("Serif" in family or italic) else (
        SANS_BOLD if element.get("font-weight") == "bold" else SANS)
    monospace = "Mono" in family
    x, y = _number(element.get("x")), _number(element.get("y"))
    width, ascent, descent = 0.0, 0.8 * size, 0.25 * size
    parts: list[str] = []
    runs = [(element.text or "", size, 0.0)]
    shift = 0.0
    for child in element:
        if _local(child.tag) != "tspan":
            continue
        child_size = _number(child.get("font-size"), size)
        shift += _number(child.get("dy"))
        runs.append((child.text or "", child_size, shift))
        if child.tail:
            runs.append((child.tail, size, shift))
    for text, run_size, run_shift in runs:
        if not text:
            continue
        parts.append(text)
        width += 0.6 * run_size * len(text) if monospace else text_width(text, run_size, font)
        ascent = max(ascent, 0.8 * run_size - run_shift)
        descent = max(descent, 0.25 * run_size + run_shift)
    anchor = element.get("text-anchor") or "start"
    left = x - (width if anchor == "end" else width / 2 if anchor == "middle" else 0.0)
    return TextBox("".join(parts), css, (left, y - ascent, left + width, y + descent),
                   tuple((element.get("data-points") or "").split()), size)


_TRANSLATE = re.compile(r"^\s*translate\(\s*(-?[\d.e-]+)[\s,]+(-?[\d.e-]+)\s*\)\s*$")


def _walk(element, classes: tuple[str, ...] = (), offset=(0.0, 0.0), clip=None, clips=None):
    """(element, the classes of it and its ancestors, its translation, its clip box in page
    coordinates or None) in document order. Only ``translate`` transforms and clip paths
    made of one rectangle are understood (what planmethod writes); any other transform is
    reported by :func:`figure_problems`."""
    own = tuple((element.get("class") or "").split())
    transform = element.get("transform")
    if transform:
        match = _TRANSLATE.match(transform)
        if match:
            offset = (offset[0] + float(match.group(1)), offset[1] + float(match.group(2)))
        else:
            classes = (*classes, "unknown-transform")
    reference = element.get("clip-path")
    if reference and clips is not None:
        box = clips.get(reference.strip()[5:-1]) if reference.startswith("url(#") else None
        if box is not None:
            box = (box[0] + offset[0], box[1] + offset[1], box[2] + offset[0],
                   box[3] + offset[1])
            clip = box if clip is None else (max(clip[0], box[0]), max(clip[1], box[1]),
                                             min(clip[2], box[2]), min(clip[3], box[3]))
    yield element, classes + own, offset, clip
    for child in element:
        yield from _walk(child, classes + own, offset, clip, clips)


def _owner(element, parents: dict) -> str:
    """What a drawn element is, for a message: its own class, else its nearest classed
    ancestor's (an arrow's shaft is the arrow's)."""
    while element is not None:
        if element.get("class"):
            return element.get("class")
        element = parents.get(id(element))
    return "a line"


def _clip_boxes(root) -> dict[str, tuple[float, float, float, float]]:
    """id → box of each ``<clipPath>`` that is one rectangle."""
    out = {}
    for element in root.iter():
        if _local(element.tag) != "clipPath" or not element.get("id"):
            continue
        rects = [child for child in element if _local(child.tag) == "rect"]
        if len(rects) == 1:
            x, y = _number(rects[0].get("x")), _number(rects[0].get("y"))
            out[element.get("id")] = (x, y, x + _number(rects[0].get("width")),
                                      y + _number(rects[0].get("height")))
    return out


def _moved(box, offset):
    return (box[0] + offset[0], box[1] + offset[1], box[2] + offset[0], box[3] + offset[1])


def text_boxes(svg: str) -> list[TextBox]:
    """Every ``<text>`` element's box (see the module docstring)."""
    from defusedxml import ElementTree

    root = ElementTree.fromstring(svg.encode("utf-8"))
    out = []
    for element, classes, offset, _ in _walk(root, clips=_clip_boxes(root)):
        if _local(element.tag) == "text":
            box = _text_box(element, " ".join(classes))
            out.append(TextBox(box.text, box.css, _moved(box.box, offset), box.points, box.size))
    return out


def _overlap(a, b) -> float:
    width = min(a[2], b[2]) - max(a[0], b[0])
    height = min(a[3], b[3]) - max(a[1], b[1])
    return min(width, height)


def _points(element) -> list[tuple[float, float]]:
    tag = _local(element.tag)
    if tag == "line":
        return [(_number(element.get("x1")), _number(element.get("y1"))),
                (_number(element.get("x2")), _number(element.get("y2")))]
    if tag in ("polyline", "polygon"):
        numbers = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?",
                                                element.get("points") or "")]
        return list(zip(numbers[::2], numbers[1::2], strict=False))
    if tag == "circle":
        cx, cy, r = (_number(element.get(k)) for k in ("cx", "cy", "r"))
        return [(cx - r, cy - r), (cx + r, cy + r)]
    return []


def _look(element) -> tuple[str, ...]:
    """What a legend sample shows: stroke, dash and width, or the fill of a filled shape."""
    if element.get("stroke") not in (None, "none"):
        return ("stroke", element.get("stroke").lower(), element.get("stroke-dasharray") or "",
                element.get("stroke-width") or "")
    return ("fill", (element.get("fill") or "").lower())


def figure_problems(svg: str, *, allowed: Iterable[str] = (), details: bool = True
                    ) -> list[str]:
    """Everything wrong with one figure, one line each (empty: nothing). ``allowed`` are
    names a figure must print as they are (a task sheet's answer-file column names,
    ``[omega_BC]``): not code words there. A figure drawn without enlarged details by design
    (``details=False``: a frame of a workbook page) is not held to what only a detail can
    give — the readable distance between marks, a point label's clearance, leaders clear of
    the arrows of a crowded point — but its labels still never touch another point's mark
    (:data:`TOUCH_PX`).

    Raises
    ------
    defusedxml.DefusedXmlException, xml.etree.ElementTree.ParseError
        If ``svg`` is not well-formed (or declares entities).
    """
    from defusedxml import ElementTree

    root = ElementTree.fromstring(svg.encode("utf-8"))
    seen = _Seen(tuple(allowed))
    seen.walk(root)
    problems = seen.problems + _overlapping(seen.boxes) + _outside_view(root, seen)
    readable = readable_px(seen.boxes)
    # points the figure lists in a table of the points too close to read (no third level of
    # detail) are readable there: their marks are held to no distance
    listed = {name for box in seen.boxes if "crowded" in box.css.split()
              for name in (box.text, *box.points)}
    marks = [mark for mark in seen.marks
             if not any(_listed(point, listed) for point in mark[0])]
    problems += _crowding(seen.boxes, marks, seen.regions, readable if details else None)
    problems += _crossings(seen.boxes, seen.strokes, arrows=details)
    if details:
        problems += _spacing(marks, seen.regions, readable)
    for sample in seen.legend_samples:
        if sample[0] == "fill" and sample[1] in ("", "none", "#ffffff", "white"):
            continue
        if not any(sample[:3] == look[:3] for look in seen.drawn):     # any width
            problems.append(f"legend item {' '.join(sample)} is not drawn in the figure")
    return list(dict.fromkeys(problems))


@dataclass
class _Seen:
    """What a walk of a figure's elements sees: texts, shapes' points, point marks, detail
    regions, strokes, legend samples and drawn looks, and the problems found on the way."""

    allowed: tuple[str, ...]
    problems: list[str] = field(default_factory=list)
    boxes: list[TextBox] = field(default_factory=list)
    shapes: list[tuple[str, tuple[float, float], tuple[str, ...]]] = field(default_factory=list)
    legend_samples: list[tuple[str, ...]] = field(default_factory=list)
    drawn: set[tuple[str, ...]] = field(default_factory=set)
    marks: list[tuple[set[str], float, float, float]] = field(default_factory=list)
    regions: list[tuple[float, float, float, float]] = field(default_factory=list)
    strokes: list[_Stroke] = field(default_factory=list)

    def walk(self, root) -> None:
        """See every drawn element of ``root`` (not definitions, clip paths' own shapes)."""
        clip_shapes = {id(child) for clip in root.iter() if _local(clip.tag) == "clipPath"
                       for child in clip}      # a clip path's own shapes are not drawn
        parents = {id(child): parent for parent in root.iter() for child in parent}
        defined = {id(item) for defs in root.iter() if _local(defs.tag) == "defs"
                   for item in defs.iter()}      # patterns, clip paths: not drawn themselves
        for element, classes, offset, clip in _walk(root, clips=_clip_boxes(root)):
            tag = _local(element.tag)
            if tag in ("title", "desc", "clipPath") or id(element) in defined:
                continue
            if "unknown-transform" in classes:
                if tag in ("text", "line", "polyline", "polygon", "circle", "rect"):
                    self.problems.append(f"a {tag} under a transform other than translate")
            elif tag == "text":
                self.text(element, classes, offset, clip)
            elif tag in ("line", "polyline", "polygon", "circle", "path", "rect") and \
                    "background" not in classes and id(element) not in clip_shapes:
                self.shape(element, tag, classes, offset, clip, _owner(element, parents))

    def text(self, element, classes, offset, clip) -> None:
        """A text's box as seen (what a clip path hides is not), and its code words."""
        box = _text_box(element, " ".join(classes))
        box = TextBox(box.text, box.css, _moved(box.box, offset), box.points, box.size)
        if clip is not None:
            visible = (max(box.box[0], clip[0]), max(box.box[1], clip[1]),
                       min(box.box[2], clip[2]), min(box.box[3], clip[3]))
            if visible[0] >= visible[2] or visible[1] >= visible[3]:
                return
            box = TextBox(box.text, box.css, visible, box.points, box.size)
        self.boxes.append(box)
        for word in CODE_WORD.findall(box.text):
            if not any(f"[{name}]" in box.text and word in name for name in self.allowed):
                self.problems.append(f"code word {word!r} in text {box.text!r}")

    def shape(self, element, tag, classes, offset, clip, owner) -> None:
        """A shape's points, point marks, detail regions, strokes and look."""
        if tag == "circle" and element.get("data-points"):
            cx, cy = _number(element.get("cx")) + offset[0], _number(element.get("cy")) + offset[1]
            if clip is None or (clip[0] <= cx <= clip[2] and clip[1] <= cy <= clip[3]):
                self.marks.append((set(element.get("data-points").split()), cx, cy,
                                   _number(element.get("r"))))
        if tag == "rect" and "region" in classes and "detail" in classes:
            x, y = _number(element.get("x")) + offset[0], _number(element.get("y")) + offset[1]
            self.regions.append((x, y, x + _number(element.get("width")),
                                 y + _number(element.get("height"))))
        for x, y in _points(element):
            x, y = x + offset[0], y + offset[1]
            if clip is not None:          # clipped: only what lies inside the clip is seen
                x, y = min(max(x, clip[0]), clip[2]), min(max(y, clip[1]), clip[3])
            self.shapes.append((tag, (x, y), classes))
        if "text" not in classes:      # drawn lines (not a legend's samples, a scale bar)
            self.strokes += _strokes(element, owner, offset, clip)
            self.drawn.add(_look(element))
        elif tag in ("line", "polyline", "circle", "rect", "polygon") and not \
                {"bar", "scale", "rule"} & set(classes):   # the text layer: legends' samples
            self.legend_samples.append(_look(element))


def _overlapping(boxes: list[TextBox]) -> list[str]:
    """Every pair of texts that overlap."""
    problems = []
    for index, first in enumerate(boxes):
        for second in boxes[index + 1:]:
            if not first.text.strip() or not second.text.strip():
                continue
            if _overlap(first.box, second.box) > _HAIR:
                problems.append(f"text {first.text!r} overlaps text {second.text!r}")
    return problems


def _outside_view(root, seen: _Seen) -> list[str]:
    """Texts and kinds of shapes that leave the figure's viewBox."""
    view = [float(v) for v in (root.get("viewBox") or "").replace(",", " ").split()]
    if len(view) != 4:
        return []
    problems = []
    x0, y0, x1, y1 = view[0], view[1], view[0] + view[2], view[1] + view[3]
    for box in seen.boxes:
        bx0, by0, bx1, by1 = box.box
        if bx0 < x0 - _EDGE or by0 < y0 - _EDGE or bx1 > x1 + _EDGE or by1 > y1 + _EDGE:
            problems.append(f"text {box.text!r} leaves the viewBox")
    outside = {tag for tag, (x, y), _ in seen.shapes
               if not (x0 - _EDGE <= x <= x1 + _EDGE and y0 - _EDGE <= y <= y1 + _EDGE)}
    return problems + [f"a {tag} leaves the viewBox" for tag in sorted(outside)]


def _inside(x: float, y: float, box) -> bool:
    return box[0] <= x <= box[2] and box[1] <= y <= box[3]


def readable_px(boxes: Iterable[TextBox]) -> float:
    """The readable distance of a figure (px): :data:`READABLE_EM` times the size of its
    point labels (the commonest size among the texts that name points; :data:`LABEL_SIZE`
    when none does).

    >>> readable_px([TextBox("b", "label", (0, 0, 9, 15), ("b",), 15.0)])
    30.0
    """
    sizes = [box.size for box in boxes if box.points and "label" in box.css.split()
             and box.size > 0]
    size = max(set(sizes), key=sizes.count) if sizes else LABEL_SIZE
    return READABLE_EM * size


def _listed(point: str, listed: set[str]) -> bool:
    """Whether a mark's point is named in a table of crowded points (as the course writes
    it: its underscores and digits set as the figure sets them)."""
    return bool(listed) and any(name in listed for name in (
        point, point.replace("_", ""), point.translate(_SUBSCRIPT_DIGITS)))


#: digits as a figure sets them in a name (o2 → o₂)
_SUBSCRIPT_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _crowding(boxes, marks, regions, readable: float) -> list[str]:
    """Each point's label nearer than the clearance (:data:`CLEARANCE_EM` of the readable
    distance) to another point's mark, and any other label (a force's, an arm's) on a point's
    mark, where neither that mark nor the label's own point lies in a region drawn as a
    detail."""
    own = {}
    for points, cx, cy, _ in marks:
        for point in points:
            own.setdefault(point, (cx, cy))
    problems = []
    for box in boxes:
        if not box.points or "label" not in box.css.split():
            continue
        mine = set(box.points)
        x0, y0, x1, y1 = box.box
        home = next((own[point] for point in box.points if point in own), None)
        clearance = (0.0 if home is None else TOUCH_PX if readable is None
                     else CLEARANCE_EM * readable)
        if home is not None and any(_inside(*home, region) for region in regions):
            continue
        for points, cx, cy, radius in marks:
            if points & mine or any(_inside(cx, cy, region) for region in regions):
                continue
            if home is not None and abs(home[0] - cx) + abs(home[1] - cy) <= _SAME:
                continue                      # a point at the label's own place
            dx = max(x0 - cx, 0.0, cx - x1)
            dy = max(y0 - cy, 0.0, cy - y1)
            gap = (dx * dx + dy * dy) ** 0.5 - radius
            if gap < clearance:
                problems.append(f"label {box.text!r} is {max(gap, 0.0):.1f} px from the mark "
                                f"of {' '.join(sorted(points))} (no detail)")
    return problems


def _spacing(marks, regions, readable: float) -> list[str]:
    """Marks of distinct points nearer each other than the readable distance, neither in a
    region drawn again as an enlarged detail: their labels cannot both sit clear. Marks at
    one place (to the figure's two decimals) mark points that coincide."""
    problems = []
    for index, (first, x0, y0, _) in enumerate(marks):
        for second, x1, y1, _ in marks[index + 1:]:
            if first & second:
                continue
            gap = ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
            if _SAME < gap < readable and not any(_inside(x, y, region) for region in regions
                                          for x, y in ((x0, y0), (x1, y1))):
                problems.append(f"marks of {' '.join(sorted(first))} and "
                                f"{' '.join(sorted(second))} are {gap:.1f} px apart, nearer "
                                f"than the readable {readable:g} px (no detail)")
    return problems


@dataclass(frozen=True)
class _Stroke:
    """A visible straight piece of a drawn line (x0, y0, x1, y1), what it belongs to, and
    for a leader the points its label names."""

    piece: tuple[float, float, float, float]
    owner: str
    points: tuple[str, ...] = ()

    @property
    def leader(self) -> bool:
        return "leader" in self.owner.split()


def _dark(paint: str | None) -> bool:
    return paint not in (None, "", "none", "#ffffff", "white") and not paint.startswith("url(")


def _strokes(element, owner: str, offset, clip) -> list[_Stroke]:
    """The visible straight pieces of a line, a polyline, a polygon (its outline, also of a
    filled one: an arrowhead) or a stroked rectangle."""
    tag = _local(element.tag)
    stroked = _dark(element.get("stroke"))
    if tag in ("line", "polyline") and stroked:
        corners = _points(element)
    elif tag == "polygon" and (stroked or _dark(element.get("fill"))):
        corners = _points(element)
        corners = corners + corners[:1]
    elif tag == "rect" and stroked:
        x, y = _number(element.get("x")), _number(element.get("y"))
        w, h = _number(element.get("width")), _number(element.get("height"))
        corners = [(x, y), (x + w, y), (x + w, y + h), (x, y + h), (x, y)]
    else:
        return []
    points = tuple((element.get("data-points") or "").split())
    out = []
    for (ax, ay), (bx, by) in itertools.pairwise(corners):
        piece = (ax + offset[0], ay + offset[1], bx + offset[0], by + offset[1])
        if clip is not None:
            piece = _clip(piece, clip)
        if piece is not None and (piece[0] != piece[2] or piece[1] != piece[3]):
            out.append(_Stroke(piece, owner, points))
    return out


def _clip(piece, box):
    """The part of a segment inside a box (Liang–Barsky), or None.

    >>> _clip((-5.0, 0.0, 5.0, 0.0), (0.0, -1.0, 2.0, 1.0))
    (0.0, 0.0, 2.0, 0.0)
    """
    x0, y0, x1, y1 = piece
    dx, dy = x1 - x0, y1 - y0
    low, high = 0.0, 1.0
    for p, q in ((-dx, x0 - box[0]), (dx, box[2] - x0), (-dy, y0 - box[1]), (dy, box[3] - y0)):
        if p == 0:
            if q < 0:
                return None
            continue
        t = q / p
        if p < 0:
            low = max(low, t)
        else:
            high = min(high, t)
    if low > high:
        return None
    return (x0 + low * dx, y0 + low * dy, x0 + high * dx, y0 + high * dy)


def _length_inside(piece, box) -> float:
    inside = _clip(piece, box)
    return 0.0 if inside is None else ((inside[2] - inside[0]) ** 2
                                       + (inside[3] - inside[1]) ** 2) ** 0.5


def _meet(first, second) -> tuple[float, float] | None:
    """Where two segments cross (each at a parameter in [0, 1]), or None (parallel too)."""
    ax, ay, bx, by = first
    cx, cy, dx, dy = second
    rx, ry, sx, sy = bx - ax, by - ay, dx - cx, dy - cy
    denominator = rx * sy - ry * sx
    if abs(denominator) < 1e-12:
        return None
    t = ((cx - ax) * sy - (cy - ay) * sx) / denominator
    u = ((cx - ax) * ry - (cy - ay) * rx) / denominator
    if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0:
        return (ax + t * rx, ay + t * ry)
    return None


def _crossings(boxes, strokes, *, arrows: bool = True) -> list[str]:
    """Point labels crossed by a drawn line that is not their own leader, and leaders that
    cross another leader or (with ``arrows``) a vector's arrow, away from the point they
    start at."""
    labels = [box for box in boxes if box.points and box.text.strip()]
    text_of = {box.points: box.text for box in labels}
    problems = []
    for box in labels:
        inner = (box.box[0] + _HAIR, box.box[1] + _HAIR, box.box[2] - _HAIR,
                 box.box[3] - _HAIR)
        for stroke in strokes:
            if stroke.leader and stroke.points == box.points:
                continue
            if _length_inside(stroke.piece, inner) > _CROSS_PX:
                what = (f"the leader of {text_of.get(stroke.points, 'a label')!r}"
                        if stroke.leader else f"a line ({stroke.owner})")
                problems.append(f"label {box.text!r} is crossed by {what}")
    leaders = [stroke for stroke in strokes if stroke.leader]
    for index, leader in enumerate(leaders):
        name = text_of.get(leader.points, "a label")
        start = leader.piece[:2]
        for other in leaders[index + 1:] + [stroke for stroke in strokes if arrows
                                             and stroke.owner.startswith("arrow")]:
            if other is leader:
                continue
            at = _meet(leader.piece, other.piece)
            if at is None or (at[0] - start[0]) ** 2 + (at[1] - start[1]) ** 2 < _CROSS_PX ** 2:
                continue
            if other.leader:
                if (at[0] - other.piece[0]) ** 2 + (at[1] - other.piece[1]) ** 2 < \
                        _CROSS_PX ** 2:
                    continue                    # two leaders from one point
                what = f"the leader of {text_of.get(other.points, 'a label')!r}"
            else:
                what = f"an arrow ({other.owner})"
            problems.append(f"the leader of {name!r} crosses {what}")
    return problems


def steady_problems(frames: Iterable[str], panel: str = "panel") -> list[str]:
    """The frames of one panel over a turn drawn on more than one page (viewBox): the
    drawing would jump as the crank turns.

    >>> steady_problems(['<svg viewBox="0 0 9 9"/>', '<svg viewBox="0 0 9 9"/>'])
    []
    >>> steady_problems(['<svg viewBox="0 0 9 9"/>', '<svg viewBox="0 0 8 9"/>'], "plan")
    ['plan: 2 viewBoxes over the turn (0 0 9 9, 0 0 8 9)']
    """
    from defusedxml import ElementTree

    boxes = list(dict.fromkeys(ElementTree.fromstring(svg.encode("utf-8")).get("viewBox")
                               or "none" for svg in frames))
    if len(boxes) <= 1:
        return []
    return [f"{panel}: {len(boxes)} viewBoxes over the turn ({', '.join(boxes[:3])})"]


#: a drive symbol with its subscript, a force or a reaction with its link numbers
_DRIVE = re.compile(r"([φω])([₀-₉]+)")
_SUBSCRIPTS = str.maketrans("₀₁₂₃₄₅₆₇₈₉‚", "0123456789,")


def numbering_problems(svg: str, numbers: dict[str, int], crank: str) -> list[str]:
    """Where a figure does not name links as the numbering ``numbers`` (link → number) does:
    the drive's φ or ω with another number than the crank's, a label of a point or a force
    whose subscript names a link (b lever) or is no link's number (G₇ of a four-bar),
    a reaction whose subscript is no pair of link numbers.

    >>> svg = ('<svg xmlns="http://www.w3.org/2000/svg"><text>plan, φ₂ = 30°</text>'
    ...        '<text class="label" data-points="b@lever">b<tspan>lever</tspan></text></svg>')
    >>> numbering_problems(svg, {"frame": 0, "crank": 1, "lever": 3}, "crank")
    ["'φ₂': the crank is link 1", "label 'blever' names link lever, not its number"]
    """
    from defusedxml import ElementTree

    root = ElementTree.fromstring(svg.encode("utf-8"))
    valid = {str(number) for number in numbers.values()}
    names = {name for name in numbers if not name.isupper()}
    problems = []
    for element in root.iter():
        if _local(element.tag) != "text":
            continue
        whole = "".join(element.itertext())
        for letter, digits in _DRIVE.findall(whole):
            if digits.translate(_SUBSCRIPTS) != str(numbers[crank]):
                problems.append(f"'{letter}{digits}': the crank is link {numbers[crank]}")
        if not element.get("data-points"):
            continue
        runs = [run for run in [element.text or ""] + [
            child.text or "" for child in element if _local(child.tag) == "tspan"] if run]
        if not runs:
            continue
        head, subscripts = runs[0], [run.strip(", ") for run in runs[1:]]
        for sub in subscripts:
            if sub in names:
                problems.append(f"label {whole!r} names link {sub}, not its number")
            elif head in ("G", "Fᵘ", "Mᵘ") and sub.isdigit() and sub not in valid:
                problems.append(f"label {whole!r}: {sub} is no link's number")
            elif head in ("R", "Rⁿ", "Rᵗ", "N") and sub.replace(",", "").isdigit() and \
                    not _pair_of(sub, valid):
                problems.append(f"label {whole!r}: {sub} is no pair of link numbers")
    return list(dict.fromkeys(problems))


def _pair_of(text: str, valid: set[str]) -> bool:
    if "," in text:
        first, _, second = text.partition(",")
        return first in valid and second in valid
    return any(text[:cut] in valid and text[cut:] in valid for cut in range(1, len(text)))


#: the layers of what a figure draws (its mechanism, its plan, its polygon), not its
#: construction lines, labels, legends or notes (as :data:`planmethod.render.canvas.DRAWN_LAYERS`)
_DRAWN = frozenset(("links", "components", "results", "points"))


def drawn_extent(svg: str) -> tuple[float, float, float, float] | None:
    """The box (x0, y0, x1, y1) of what a figure draws — the corners of its links, its pairs'
    and points' centres, its vectors' ends (the layers links, points, components, results),
    not in an enlarged detail — or None if it draws none of these.

    >>> drawn_extent('<svg xmlns="http://www.w3.org/2000/svg"><g class="points">'
    ...              '<circle cx="10" cy="5" r="3"/><circle cx="40" cy="25" r="3"/></g></svg>')
    (10.0, 5.0, 40.0, 25.0)
    """
    from defusedxml import ElementTree

    root = ElementTree.fromstring(svg.encode("utf-8"))
    xs: list[float] = []
    ys: list[float] = []
    for element, classes, offset, _ in _walk(root):
        if "detail" in classes or not _DRAWN & set(classes) or "text" in classes:
            continue
        tag = _local(element.tag)
        corners = ([(_number(element.get("cx")), _number(element.get("cy")))]
                   if tag == "circle" else _points(element))
        xs += [x + offset[0] for x, _ in corners]
        ys += [y + offset[1] for _, y in corners]
    return (min(xs), min(ys), max(xs), max(ys)) if xs else None


def page_ratio(svg: str) -> float:
    """How many times the longer side of a figure's viewBox is the longer side of what it
    draws (:func:`drawn_extent`): a page framed on its mechanism or plan stays near 2–3.

    >>> page_ratio('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 90 40">'
    ...            '<g class="points"><circle cx="10" cy="5" r="3"/>'
    ...            '<circle cx="40" cy="25" r="3"/></g></svg>')
    3.0
    """
    from defusedxml import ElementTree

    view = [float(v) for v in (ElementTree.fromstring(svg.encode("utf-8")).get("viewBox")
                               or "").replace(",", " ").split()]
    box = drawn_extent(svg)
    if len(view) != 4 or box is None:
        return 0.0
    return max(view[2], view[3]) / max(box[2] - box[0], box[3] - box[1], 1e-9)


#: the line under a figure that says a detail is drawn from a region marked in another
_MARKED_IN = re.compile(r"detail ([IVX]+): the region marked in detail ([IVX]+)")
_DETAIL = re.compile(r"detail ([IVX]+): the (?:marked )?region")


def detail_depth(svg: str) -> int:
    """How deep a figure's enlarged details nest, read from the lines under it: 0 without
    details, 1 for details of the figure, 2 where one is marked in another, and so on.

    >>> detail_depth('<text>detail I: the marked region drawn 4 times larger</text>'
    ...              '<text>detail II: the region marked in detail I, drawn 40 times</text>')
    2
    """
    parents = dict(_MARKED_IN.findall(svg))
    depths = []
    for letter in _DETAIL.findall(svg):
        depth, seen = 1, {letter}
        while letter in parents and parents[letter] not in seen:
            letter = parents[letter]
            seen.add(letter)
            depth += 1
        depths.append(depth)
    return max(depths, default=0)
