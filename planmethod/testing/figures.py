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
* **a label too near another point**: a point's label (``data-points``) whose text comes
  nearer than :data:`READABLE_PX` to the mark of another point (a circle with
  ``data-points``) outside any region the figure draws again as an enlarged detail (a
  ``detail region`` frame) — the reader could take it for that point's.

:func:`steady_problems` checks the frames of a turn: one viewBox per panel.
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

import re
from collections.abc import Iterable
from dataclasses import dataclass

from ..render.style import LABEL, SANS, SANS_BOLD, text_width

__all__ = ["CODE_WORD", "READABLE_PX", "TextBox", "figure_problems", "numbering_problems",
           "steady_problems", "text_boxes"]

#: a label's text keeps at least this far (px) from another point's mark
READABLE_PX = 3.0

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
                   tuple((element.get("data-points") or "").split()))


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
            out.append(TextBox(box.text, box.css, _moved(box.box, offset), box.points))
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


def figure_problems(svg: str, *, allowed: Iterable[str] = ()) -> list[str]:
    """Everything wrong with one figure, one line each (empty: nothing). ``allowed`` are
    names a figure must print as they are (a task sheet's answer-file column names,
    ``[omega_BC]``): not code words there.

    Raises
    ------
    defusedxml.DefusedXmlException, xml.etree.ElementTree.ParseError
        If ``svg`` is not well-formed (or declares entities).
    """
    from defusedxml import ElementTree

    root = ElementTree.fromstring(svg.encode("utf-8"))
    problems: list[str] = []
    boxes: list[TextBox] = []
    shapes: list[tuple[str, tuple[float, float], tuple[str, ...]]] = []
    legend_samples: list[tuple[str, ...]] = []
    drawn: set[tuple[str, ...]] = set()
    marks: list[tuple[set[str], float, float, float]] = []
    regions: list[tuple[float, float, float, float]] = []
    clip_shapes = {id(child) for clip in root.iter() if _local(clip.tag) == "clipPath"
                   for child in clip}      # a clip path's own shapes are not drawn
    for element, classes, offset, clip in _walk(root, clips=_clip_boxes(root)):
        tag = _local(element.tag)
        if tag in ("title", "desc", "clipPath"):
            continue
        if "unknown-transform" in classes:
            if tag in ("text", "line", "polyline", "polygon", "circle", "rect"):
                problems.append(f"a {tag} under a transform other than translate")
            continue
        if tag == "text":
            box = _text_box(element, " ".join(classes))
            box = TextBox(box.text, box.css, _moved(box.box, offset), box.points)
            if clip is not None:          # what a clip path hides is not seen
                visible = (max(box.box[0], clip[0]), max(box.box[1], clip[1]),
                           min(box.box[2], clip[2]), min(box.box[3], clip[3]))
                if visible[0] >= visible[2] or visible[1] >= visible[3]:
                    continue
                box = TextBox(box.text, box.css, visible, box.points)
            boxes.append(box)
            for word in CODE_WORD.findall(box.text):
                if not any(f"[{name}]" in box.text and word in name for name in allowed):
                    problems.append(f"code word {word!r} in text {box.text!r}")
            continue
        if tag not in ("line", "polyline", "polygon", "circle", "path", "rect"):
            continue
        if "background" in classes or id(element) in clip_shapes:
            continue
        if tag == "circle" and element.get("data-points"):
            cx, cy = _number(element.get("cx")) + offset[0], _number(element.get("cy")) + offset[1]
            if clip is None or (clip[0] <= cx <= clip[2] and clip[1] <= cy <= clip[3]):
                marks.append((set(element.get("data-points").split()), cx, cy,
                              _number(element.get("r"))))
        if tag == "rect" and "region" in classes and "detail" in classes:
            x, y = _number(element.get("x")) + offset[0], _number(element.get("y")) + offset[1]
            regions.append((x, y, x + _number(element.get("width")),
                            y + _number(element.get("height"))))
        for x, y in _points(element):
            x, y = x + offset[0], y + offset[1]
            if clip is not None:          # clipped: only what lies inside the clip is seen
                x, y = min(max(x, clip[0]), clip[2]), min(max(y, clip[1]), clip[3])
            shapes.append((tag, (x, y), classes))
        if "text" in classes:          # the text layer: legends' samples and scale bars
            if tag in ("line", "polyline", "circle", "rect", "polygon") and "bar" not in \
                    classes and "scale" not in classes and "rule" not in classes:
                legend_samples.append(_look(element))
        else:
            drawn.add(_look(element))
    for index, first in enumerate(boxes):
        for second in boxes[index + 1:]:
            if not first.text.strip() or not second.text.strip():
                continue
            if _overlap(first.box, second.box) > _HAIR:
                problems.append(f"text {first.text!r} overlaps text {second.text!r}")
    view = [float(v) for v in (root.get("viewBox") or "").replace(",", " ").split()]
    if len(view) == 4:
        x0, y0, x1, y1 = view[0], view[1], view[0] + view[2], view[1] + view[3]
        for box in boxes:
            bx0, by0, bx1, by1 = box.box
            if bx0 < x0 - _EDGE or by0 < y0 - _EDGE or bx1 > x1 + _EDGE or by1 > y1 + _EDGE:
                problems.append(f"text {box.text!r} leaves the viewBox")
        outside = {tag for tag, (x, y), _ in shapes
                   if not (x0 - _EDGE <= x <= x1 + _EDGE and y0 - _EDGE <= y <= y1 + _EDGE)}
        for tag in sorted(outside):
            problems.append(f"a {tag} leaves the viewBox")
    problems += _crowding(boxes, marks, regions)
    for sample in legend_samples:
        if sample[0] == "fill" and sample[1] in ("", "none", "#ffffff", "white"):
            continue
        if not any(sample[:3] == look[:3] for look in drawn):     # any width
            problems.append(f"legend item {' '.join(sample)} is not drawn in the figure")
    return list(dict.fromkeys(problems))


def _inside(x: float, y: float, box) -> bool:
    return box[0] <= x <= box[2] and box[1] <= y <= box[3]


def _crowding(boxes, marks, regions) -> list[str]:
    """Each point's label nearer than :data:`READABLE_PX` to another point's mark, where
    neither that mark nor the label's own point lies in a region drawn as a detail."""
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
        if home is not None and any(_inside(*home, region) for region in regions):
            continue
        for points, cx, cy, radius in marks:
            if points & mine or any(_inside(cx, cy, region) for region in regions):
                continue
            dx = max(x0 - cx, 0.0, cx - x1)
            dy = max(y0 - cy, 0.0, cy - y1)
            gap = (dx * dx + dy * dy) ** 0.5 - radius
            if gap < READABLE_PX:
                problems.append(f"label {box.text!r} is {max(gap, 0.0):.1f} px from the mark "
                                f"of {' '.join(sorted(points))} (no detail)")
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
