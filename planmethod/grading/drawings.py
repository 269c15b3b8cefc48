"""Grading drawn plans: read a student's plan (SVG or JSON), align it at the pole, check every
plan point against its tolerance disc and the construction lines, and explain what is off.

A submission is untrusted input. SVG is read with the standard library's expat parser after
these checks: at most :data:`MAX_BYTES` bytes, UTF-8, no ``<!DOCTYPE`` or ``<!ENTITY`` at all
(so no entity expansion and no external resolution), at most :data:`MAX_ELEMENTS` elements,
nesting at most :data:`MAX_DEPTH`, at most :data:`MAX_NUMBERS` coordinates. Scripts, images and
links are never followed (they are ignored). Any failure is a :class:`SubmissionError` with
one clear line.

Points are found in the SVG as the plan's labels (``<text>`` with ``p``, ``π``/``pi``, ``b``,
``c``, ``n_CB``…): each label marks the nearest drawn point (a line or path end, a vertex, a
circle's centre) within :data:`LABEL_REACH_MM`, or its own anchor if nothing is drawn near it —
so labelled dots, text near line ends, and planmethod's blank plan sheet all work. Units: a
root ``width`` in mm/cm/in/pt/px with a ``viewBox`` fixes the user unit; otherwise a user unit
is a CSS px (25.4/96 mm). SVG's y axis points down; plans are graded with y up.

JSON submissions are ``{"plan": "velocity", "points": {"p": [0, 0], "b": [x, y], …}}`` in mm,
y up (or just the points object). A drawing downloaded from the workbook page
(``"format": "planmethod-drawing"``, see docs/workbook-drawing.md) also names its exercise's
``title`` and crank ``angle``: grading it against a key of another exercise or angle is refused
in one line. It is drawn on a millimetre grid, so it is never rescaled. It also lists what the
student asked the page to show before downloading it (``revealed``: the answers shown, by
question id, ``construction:<plan>``, ``plan:<plan>``): the grade reports it
(:attr:`GradedDrawing.revealed`, and a note on the drawing naming it in course words).

Examples
--------
>>> drawing = parse_drawing_json('{"plan": "velocity", "points": {"p": [0, 0], "b": [1, 2]}}')
>>> drawing.plan, drawing.points["b"]
('velocity', (1.0, 2.0))
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SpecError, about, value_text
from ..io import read_bytes_bounded
from ..render.plan_words import label_text
from ..spec import MAX_ANGLE_DEG, parse_json
from ..vectors import cross
from ..vocabulary import numbered, symbol
from ..words import Message, message, plural, template
from .answers import refuse_twice
from .keys import key_numbers
from .plan_points import (
    ConstructionLine,
    common_mistakes,
    graded_labels,
    helper_labels,
    mistake_sentence,
    named_mistakes,
    placing_steps,
    plan_sentence,
    point_lines,
    read_steps,
)
from .results import GradedDrawing, GradedPoint
from .verdicts import POINT_PARTS, POINTS, PointPart, PointVerdict

__all__ = [
    "Drawing",
    "SubmissionError",
    "exercise_digest",
    "grade_drawing",
    "key_at_angle",
    "key_for_drawing",
    "page_drawing",
    "parse_drawing_json",
    "parse_drawing_svg",
    "read_drawing",
    "revealed_notes",
]

MAX_BYTES = 2_000_000
MAX_ELEMENTS = 20_000
MAX_DEPTH = 64
MAX_NUMBERS = 200_000
LABEL_REACH_MM = 8.0
#: a drawn point further than this from the origin (mm) is on no sheet: refused, naming it
MAX_COORDINATE_MM = 1e6
#: a drawing whose first vector is more than this many times too long or too short is graded
#: as drawn, not rescaled (a slip of the scale is 10 times, or 1000 for mm as m)
MAX_RESCALE = 1e4
#: how labels that name one point are compared: without spaces, ``pi`` for π, ``p'`` for p′
LABELS_COMPARED = message("labels compared without spaces, pi for π")
#: the ``format`` of a drawing downloaded from the workbook page
DRAWING_FORMAT = "planmethod-drawing"
PX_MM = 25.4 / 96.0
SVG_NAMESPACE = "{http://www.w3.org/2000/svg}"
UNITS_MM = {"mm": 1.0, "cm": 10.0, "in": 25.4, "pt": 25.4 / 72, "pc": 25.4 / 6, "px": PX_MM,
            "": PX_MM}


class SubmissionError(SpecError):
    """A submitted drawing cannot be read (too large, malformed, unsafe, no labels…)."""


@dataclass(frozen=True)
class Drawing:
    """A student's plan: labelled points in mm (y up, as drawn: not yet aligned), the plan
    it claims to be (``velocity``/``acceleration`` or None), and notes on what was skipped."""

    points: Mapping[str, tuple[float, float]]
    plan: str | None = None
    notes: tuple[Message, ...] = ()
    source: str | None = None
    lines: tuple = field(default=())
    #: the exercise's title and the crank angle (deg) the drawing says it is of (a drawing
    #: from the workbook page), else None
    title: str | None = None
    angle: float | None = None
    #: drawn on a millimetre grid (the workbook page): its scale is never corrected
    exact_scale: bool = False
    #: the digest of the exercise the page was made from (:func:`exercise_digest`), else None
    exercise: str | None = None
    #: every label an SVG drawing holds: (its text as written, the point it names, where it
    #: marks in mm); two that name one point at two places are refused when it is graded
    labels: tuple[tuple[str, str, tuple[float, float]], ...] = ()
    #: what the workbook page showed the student before the drawing was downloaded: answers
    #: by question id, ``construction:<plan>`` (steps shown), ``plan:<plan>`` (the right plan)
    revealed: tuple[str, ...] = ()


def read_drawing(path: str | Path) -> Drawing:
    """Read a drawn plan from an SVG or JSON file (see the module notes).

    Raises
    ------
    SubmissionError
        For anything that is not a readable, safe drawing with labelled points.
    """
    path = Path(path)
    data = read_bytes_bounded(path, MAX_BYTES, error=SubmissionError)
    head = data.lstrip()[:1]
    if path.suffix.lower() == ".json" or head in (b"{", b"["):
        return parse_drawing_json(data, source=str(path))
    return parse_drawing_svg(data, source=str(path))


def _finite_pair(value: Any, where: str, source: str | None) -> tuple[float, float]:
    if (not isinstance(value, list | tuple) or len(value) != 2
            or not all(isinstance(v, int | float) and not isinstance(v, bool)
                       and math.isfinite(v) for v in value)):
        raise SubmissionError(message("must be [x, y] in mm with finite numbers, got {given}",
                                      given=value_text(value)), file=source, key=where)
    return _on_a_sheet((float(value[0]), float(value[1])), where, source)


def _on_a_sheet(xy: tuple[float, float], where: str, source: str | None
                ) -> tuple[float, float]:
    """``xy`` (mm), or a :class:`SubmissionError` naming ``where`` if it lies beyond
    :data:`MAX_COORDINATE_MM` of the origin: on no sheet, and too large to grade with."""
    if max(abs(xy[0]), abs(xy[1])) > MAX_COORDINATE_MM:
        raise SubmissionError(message("is at ({x:.6g}, {y:.6g}) mm, beyond ±{limit:g} mm of "
                                      "the origin: a drawn plan fits on a sheet", x=xy[0],
                                      y=xy[1], limit=MAX_COORDINATE_MM),
                              file=source, key=where)
    return xy


def _too_large(source: str | None) -> SubmissionError:
    return SubmissionError(plural("larger than {count} byte", "larger than {count} bytes",
                                  count=MAX_BYTES), file=source)


def _json_problem(error: SpecError) -> Message | str:
    """What is wrong with a drawing's JSON, as :func:`~planmethod.spec.parse_json` said it: a
    key's problem as it is, anything else said to be invalid JSON."""
    said = error.message
    opening = said.template if isinstance(said, Message) else str(said)
    if error.key or opening.startswith("not valid JSON"):
        return said
    return message("not valid JSON: {problem}", problem=said)


def _json_points(parsed: Mapping[str, Any], plan: Any, source: str | None
                 ) -> dict[str, tuple[float, float]]:
    """The labelled points of a drawing's JSON (mm), each label once."""
    points = parsed.get("points", parsed if plan is None else None)
    if not isinstance(points, Mapping) or not points:
        raise SubmissionError(message("no labelled points (give \"points\": {{\"p\": [0, 0], "
                                      "…}})"), file=source, key="points")
    if len(points) > 1000:
        raise SubmissionError(plural("more than {count} point", "more than {count} points",
                                     count=1000), file=source, key="points")
    names = [str(label) for label in points if label != "plan"]
    refuse_twice(names, _normal_label, "point", file=source, key="points",
                 compared=LABELS_COMPARED, error=SubmissionError)
    return {_normal_label(label): _finite_pair(points[label], f"points.{label}", source)
            for label in names}


def page_drawing(parsed: Mapping[str, Any], points, plan, source: str | None) -> Drawing:
    """A drawing downloaded from the workbook page: its points, and the exercise's title,
    digest and crank angle it names, and what the page showed (``revealed``); the answers
    the page downloads name them alike (:mod:`planmethod.grading.page_answers`).

    >>> page_drawing({"title": "T", "angle": 45, "revealed": ["v_C"]}, {}, None, None).angle
    45.0

    Raises
    ------
    SubmissionError
        In one line, naming the field, for a title, digest, angle or ``revealed`` that is not
        what the page writes.
    """
    title, angle = parsed.get("title"), parsed.get("angle")
    digest = parsed.get("exercise")
    if not isinstance(title, str):
        raise SubmissionError(message("must be the exercise's title, got {given}",
                                      given=value_text(title)), file=source, key="title")
    if digest is not None and (not isinstance(digest, str)
                               or not re.fullmatch(r"[0-9a-f]{16}", digest)):
        raise SubmissionError(message("must be the exercise's digest (16 hexadecimal digits), "
                                      "got {given}", given=value_text(digest)),
                              file=source, key="exercise")
    if (isinstance(angle, bool) or not isinstance(angle, int | float)
            or not math.isfinite(angle) or abs(angle) > MAX_ANGLE_DEG):
        raise SubmissionError(message("must be the crank angle in degrees, within ±{limit:g}°, "
                                      "got {given}", limit=MAX_ANGLE_DEG,
                                      given=value_text(angle)), file=source, key="angle")
    return Drawing(points, plan, (), source, title=title, angle=float(angle), exact_scale=True,
                   exercise=digest, revealed=_revealed(parsed.get("revealed", []), source))


#: at most this many things revealed, each named in at most this many characters
MAX_REVEALED, MAX_REVEALED_CHARACTERS = 1000, 200


def _revealed(given: Any, source: str | None) -> tuple[str, ...]:
    """What a page's drawing says was shown: a list of names (each once, in order)."""
    if (not isinstance(given, list) or len(given) > MAX_REVEALED
            or not all(isinstance(name, str) and 0 < len(name) <= MAX_REVEALED_CHARACTERS
                       for name in given)):
        raise SubmissionError(message("must be a list of what the page showed (at most "
                                      "{count} names), got {given}", count=MAX_REVEALED,
                                      given=value_text(given)), file=source, key="revealed")
    return tuple(dict.fromkeys(given))


#: what a drawing's note says the page showed, by what ``revealed`` names of a plan
_REVEALED_PLAN = {
    "construction:velocity": template("the page showed the construction of the velocity plan "
                                      "before the drawing was downloaded"),
    "construction:acceleration": template("the page showed the construction of the "
                                          "acceleration plan before the drawing was "
                                          "downloaded"),
    "plan:velocity": template("the page showed the right velocity plan before the drawing "
                              "was downloaded"),
    "plan:acceleration": template("the page showed the right acceleration plan before the "
                                  "drawing was downloaded"),
}


def revealed_notes(revealed: Sequence[str], key: Mapping[str, Any]) -> list[Message]:
    """The notes on a drawing that say what the page showed before it was downloaded: the
    plans' help (:data:`_REVEALED_PLAN`), and the answers shown by their course symbols (a
    name the key does not ask is given as written).

    >>> from planmethod.words import render
    >>> key = {"questions": [{"id": "omega_BC", "symbol": "ω₂"}]}
    >>> [render(note) for note in revealed_notes(["omega_BC", "plan:velocity"], key)]
    ['the page showed the right velocity plan before the drawing was downloaded', \
'the page showed the right values of these before the drawing was downloaded: ω₂']
    """
    symbols = {question.get("id"): question.get("symbol") or question.get("id")
               for question in key.get("questions", []) if isinstance(question, Mapping)}
    notes = [_REVEALED_PLAN[name] for name in revealed if name in _REVEALED_PLAN]
    answers = [str(symbols.get(name, name)) for name in revealed if name not in _REVEALED_PLAN]
    if answers:
        notes.append(message("the page showed the right values of these before the drawing "
                             "was downloaded: {symbols}", symbols=", ".join(answers)))
    return notes


def parse_drawing_json(data: bytes | str, *, source: str | None = None) -> Drawing:
    """A drawing from JSON point coordinates (mm, y up)."""
    if isinstance(data, bytes):
        if len(data) > MAX_BYTES:
            raise _too_large(source)
        try:
            data = data.decode("utf-8-sig")
        except UnicodeDecodeError:
            raise SubmissionError(message("not UTF-8 text"), file=source) from None
    try:   # a key given twice would keep one of two points without a word
        parsed = parse_json(data, file=source, unique_keys=True)
    except SpecError as error:    # too deep, not JSON, a key twice, or a number beyond 64 bits
        raise SubmissionError(_json_problem(error), file=source, key=error.key) from None
    if not isinstance(parsed, Mapping):
        raise SubmissionError(message("must be an object {{\"plan\": …, \"points\": {{…}}}}"),
                              file=source)
    plan = parsed.get("plan")
    if plan is not None and plan not in ("velocity", "acceleration"):
        raise SubmissionError(message("plan must be 'velocity' or 'acceleration', got {given}",
                                      given=value_text(plan)), file=source, key="plan")
    points = _json_points(parsed, plan, source)
    if parsed.get("format") != DRAWING_FORMAT:
        return Drawing(points, plan, (), source)
    return page_drawing(parsed, points, plan, source)


# -- SVG -------------------------------------------------------------------------------------
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_TRANSFORM = re.compile(r"\s*(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)\s*,?")
_LENGTH = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(mm|cm|in|pt|pc|px)?"
                     r"\s*$")


def _too_many_numbers() -> SubmissionError:
    return SubmissionError(plural("more than {count} coordinate", "more than {count} coordinates",
                                  count=MAX_NUMBERS))


def _numbers(text: str, budget: list[int]) -> list[float]:
    values = [float(v) for v in _NUMBER.findall(text or "")]
    budget[0] -= len(values)
    if budget[0] < 0:
        raise _too_many_numbers()
    return values


def _unreadable(text: str) -> SubmissionError:
    return SubmissionError(message("unreadable transform {transform!r}", transform=text[:60]))


def _transform(text: str | None, budget) -> np.ndarray:
    matrix = np.eye(3)
    if not text:
        return matrix
    position = 0
    for match in _TRANSFORM.finditer(text):
        if match.start() != position:
            raise _unreadable(text)
        position = match.end()
        name, args = match.group(1), _numbers(match.group(2), budget)
        step = np.eye(3)
        try:
            if name == "matrix" and len(args) == 6:
                a, b, c, d, e, f = args
                step = np.array([[a, c, e], [b, d, f], [0, 0, 1]])
            elif name == "translate" and len(args) in (1, 2):
                step[0, 2], step[1, 2] = args[0], (args[1] if len(args) == 2 else 0.0)
            elif name == "scale" and len(args) in (1, 2):
                step[0, 0], step[1, 1] = args[0], (args[1] if len(args) == 2 else args[0])
            elif name == "rotate" and len(args) in (1, 3):
                angle = math.radians(args[0])
                c, s = math.cos(angle), math.sin(angle)
                rotation = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
                if len(args) == 3:
                    shift, back = np.eye(3), np.eye(3)
                    shift[:2, 2], back[:2, 2] = args[1:], [-args[1], -args[2]]
                    rotation = shift @ rotation @ back
                step = rotation
            elif name in ("skewX", "skewY") and len(args) == 1:
                step[0 if name == "skewX" else 1, 1 if name == "skewX" else 0] = math.tan(
                    math.radians(args[0]))
            else:
                raise _unreadable(text)
        except (OverflowError, ValueError) as error:
            raise _unreadable(text) from error
        # in Python floats: an overflow is inf, never a numpy warning
        determinant = (float(step[0, 0]) * float(step[1, 1])
                       - float(step[0, 1]) * float(step[1, 0]))
        if not math.isfinite(determinant):
            raise SubmissionError(message("the transform {transform!r} scales the drawing "
                                          "beyond any finite size", transform=text[:60]))
        if abs(determinant) <= 1e-12:
            raise SubmissionError(message("the transform {transform!r} is singular (it "
                                          "flattens the drawing onto a line or a point)",
                                          transform=text[:60]))
        with np.errstate(over="ignore", invalid="ignore"):     # a coordinate then says so
            matrix = matrix @ step
    if text[position:].strip():
        raise _unreadable(text)
    return matrix


def _path_vertices(d: str, budget) -> list[tuple[float, float]]:
    """The end points of every segment of an SVG path (absolute user units)."""
    tokens = re.findall(r"[MmLlHhVvCcSsQqTtAaZz]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?",
                        d or "")
    budget[0] -= len(tokens)
    if budget[0] < 0:
        raise _too_many_numbers()
    sizes = {"m": 2, "l": 2, "h": 1, "v": 1, "c": 6, "s": 4, "q": 4, "t": 2, "a": 7, "z": 0}
    out: list[tuple[float, float]] = []
    x = y = start_x = start_y = 0.0
    command, index = None, 0
    while index < len(tokens):
        token = tokens[index]
        if token.isalpha():
            command = token
            index += 1
            if command in "Zz":
                x, y = start_x, start_y
                continue
        if command is None:
            raise SubmissionError(message("a path's data does not start with a command"))
        size = sizes[command.lower()]
        if size == 0:
            raise SubmissionError(message("a path has numbers after Z"))
        args = tokens[index:index + size]
        if len(args) < size or any(a.isalpha() for a in args):
            raise SubmissionError(message("a path's data is incomplete"))
        values = [float(a) for a in args]
        index += size
        relative = command.islower()
        lower = command.lower()
        if lower == "h":
            x = values[0] + (x if relative else 0.0)
        elif lower == "v":
            y = values[0] + (y if relative else 0.0)
        else:
            nx, ny = values[-2], values[-1]
            x, y = (x + nx, y + ny) if relative else (nx, ny)
        if lower == "m":
            start_x, start_y = x, y
            command = "l" if relative else "L"  # implicit line-tos follow a move-to
        out.append((x, y))
    return out


def _length_mm(text: str | None) -> tuple[float, str] | None:
    if not text:
        return None
    match = _LENGTH.match(text)
    if not match:
        return None
    return float(match.group(1)), match.group(2) or ""


def _user_unit_mm(root) -> tuple[float, float]:
    width, height = _length_mm(root.get("width")), _length_mm(root.get("height"))
    for name, size in (("width", width), ("height", height)):
        if size is not None and not (math.isfinite(size[0]) and size[0] > 0):
            raise SubmissionError(message("the drawing's {attribute} is {given!r}: a drawing "
                                          "has a positive size", attribute=name,
                                          given=root.get(name)))
    view = root.get("viewBox")
    if view:
        numbers = [float(v) for v in _NUMBER.findall(view)]
        if len(numbers) == 4 and not (numbers[2] > 0 and numbers[3] > 0
                                      and all(math.isfinite(n) for n in numbers)):
            raise SubmissionError(message("the viewBox {view!r} has no positive, finite size",
                                          view=view[:60]))
        if len(numbers) == 4 and numbers[2] > 0 and numbers[3] > 0:
            sx = (width[0] * UNITS_MM[width[1]] / numbers[2]) if width else PX_MM
            sy = (height[0] * UNITS_MM[height[1]] / numbers[3]) if height else sx
            return sx, sy
    return PX_MM, PX_MM


def _normal_label(text: str) -> str:
    label = text.strip().replace(" ", "")
    label = {"pi": "π", "PI": "π", "Pi": "π", "p'": "p′", "P'": "p′"}.get(label, label)
    return label


def parse_drawing_svg(data: bytes | str, *, source: str | None = None) -> Drawing:
    """A drawing from SVG (see the module notes for what is read and what is refused)."""
    import xml.etree.ElementTree as ElementTree

    if isinstance(data, str):
        data = data.encode("utf-8")
    if len(data) > MAX_BYTES:
        raise _too_large(source)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise SubmissionError(message("not UTF-8 text (an SVG drawing is expected)"),
                              file=source) from None
    lowered = text.lower()
    if "<!doctype" in lowered or "<!entity" in lowered:
        raise SubmissionError(message("refused: the file declares a DOCTYPE or ENTITY (not "
                                      "accepted in submissions)"), file=source)
    if "<svg" not in lowered:
        raise SubmissionError(message("not an SVG drawing (no <svg> element)"), file=source)
    try:
        parser = ElementTree.XMLParser()
        parser.feed(text)
        root = parser.close()
    except ElementTree.ParseError as error:
        line, column = error.position
        raise SubmissionError(message("malformed XML at line {line}, column {column}",
                                      line=line, column=column + 1), file=source) from None
    if root.tag not in ("svg", f"{SVG_NAMESPACE}svg"):
        raise SubmissionError(message("the root element is <{tag}>, not <svg>", tag=root.tag),
                              file=source)
    try:
        return _read_svg(root, source)
    except SubmissionError as error:
        raise error.located(file=source) from None


def _element_name(element) -> str:
    """An element as an error names it: ``<text> 'b'``, ``<circle id="c1">``, ``<line>``."""
    tag = _local(element.tag)
    if tag == "text":
        return f"<text> {''.join(element.itertext()).strip()[:12]!r}"
    return f'<{tag} id="{element.get("id")[:40]}">' if element.get("id") else f"<{tag}>"


def _coordinate(element, name: str, budget: list[int]) -> float:
    """The number an attribute such as ``x`` or ``cx`` starts with (0 when it is absent); one
    that is not a finite number (``NaN``, ``inf``, ``1e999``) is refused, naming the element —
    never read as 0, which would put the point at the pole."""
    text = element.get(name)
    if text is None or not text.strip():
        return 0.0
    values = _numbers(text, budget)
    first = _NUMBER.match(text.strip())
    if first is None or not values or not math.isfinite(values[0]):
        raise SubmissionError(message("{attribute}={given!r} is not a finite number",
                                      attribute=name, given=text[:40]),
                              key=_element_name(element))
    return values[0]


def _local(tag: Any) -> str:
    if not isinstance(tag, str):
        return ""  # comments and processing instructions
    return tag.rpartition("}")[2]


#: elements whose content is never read (a note says so)
_IGNORED = ("script", "foreignObject", "image", "use", "style", "a", "iframe")
#: elements that draw nothing a point is read from
_UNDRAWN = ("defs", "metadata", "title", "desc", "clipPath", "mask", "marker", "pattern",
            "symbol")


class _SvgReader:
    """Walks an SVG's elements (bounded in count and depth) and collects the drawn points
    (line and path ends, vertices, circles' centres) and the labels (short texts, each with
    its anchor) in mm, y up, and the elements it ignored."""

    def __init__(self, root) -> None:
        sx, sy = _user_unit_mm(root)
        self.root, self.to_mm = root, np.diag([sx, -sy, 1.0])  # y up
        self.budget = [MAX_NUMBERS]
        self.points: list[tuple[float, float]] = []
        self.labels: list[tuple[str, tuple[float, float]]] = []   # (text as written, anchor)
        self.ignored: set[str] = set()

    def walk(self) -> None:
        count = 0
        stack = [(self.root, self.to_mm, 0)]
        while stack:
            element, matrix, depth = stack.pop()
            count += 1
            if count > MAX_ELEMENTS:
                raise SubmissionError(plural("more than {count} element",
                                             "more than {count} elements", count=MAX_ELEMENTS))
            if depth > MAX_DEPTH:
                raise SubmissionError(message("elements nested deeper than {depth}",
                                              depth=MAX_DEPTH))
            tag = _local(element.tag)
            if tag in _IGNORED:
                self.ignored.add(tag)
                continue
            if tag in _UNDRAWN:
                continue
            step = _transform(element.get("transform"), self.budget)  # its own errstate inside
            with np.errstate(over="ignore", invalid="ignore"):     # a coordinate then says so
                matrix = matrix @ step
            if self.read(element, tag, matrix):
                for child in reversed(list(element)):
                    stack.append((child, matrix, depth + 1))

    def place(self, x: float, y: float, matrix, element) -> tuple[float, float]:
        with np.errstate(invalid="ignore", over="ignore"):
            u = matrix @ np.array([x, y, 1.0])
        if not (math.isfinite(u[0]) and math.isfinite(u[1])):
            raise SubmissionError(message("a coordinate is not a finite number"),
                                  key=_element_name(element))
        return (float(u[0]), float(u[1]))

    def read(self, element, tag: str, matrix) -> bool:
        """Read one element's points or label; whether its children are read too."""
        def at(x_name: str, y_name: str) -> tuple[float, float]:
            return self.place(_coordinate(element, x_name, self.budget),
                              _coordinate(element, y_name, self.budget), matrix, element)

        if tag in ("circle", "ellipse"):
            self.points.append(at("cx", "cy"))
        elif tag == "line":
            self.points += [at("x1", "y1"), at("x2", "y2")]
        elif tag in ("polyline", "polygon"):
            listed = element.get("points", "")
            values = _numbers(listed, self.budget)
            if _NUMBER.sub("", listed).strip(" ,\t\n\r"):
                raise SubmissionError(message("points={given!r} holds something that is not a "
                                              "finite number", given=listed[:40]),
                                      key=_element_name(element))
            self.points += [self.place(values[i], values[i + 1], matrix, element)
                            for i in range(0, len(values) - 1, 2)]
        elif tag == "path":
            self.points += [self.place(x, y, matrix, element)
                            for x, y in _path_vertices(element.get("d", ""), self.budget)]
        elif tag == "text":
            content = "".join(element.itertext()).strip()
            if content and len(content) <= 12:
                x, y = (_coordinate(element, name, self.budget) for name in ("x", "y"))
                span = next((c for c in element if _local(c.tag) == "tspan" and c.get("x")),
                            None)
                if span is not None and not element.get("x"):
                    x, y = (_coordinate(span, name, self.budget) for name in ("x", "y"))
                self.labels.append((content, _on_a_sheet(self.place(x, y, matrix, element),
                                                         _element_name(element), None)))
            return False
        return True


def _marked(labels, points) -> tuple[dict[str, tuple[float, float]], list]:
    """Each label's point: the nearest drawn point within :data:`LABEL_REACH_MM` of its
    anchor, or the anchor; (the first place of each point, every label with its place)."""
    drawn = np.asarray(points, dtype=float).reshape(-1, 2)
    out: dict[str, tuple[float, float]] = {}
    marked: list[tuple[str, str, tuple[float, float]]] = []
    for written, anchor in labels:
        xy = np.asarray(anchor)
        if len(drawn):
            with np.errstate(over="ignore", invalid="ignore"):   # far geometry is just far
                distances = np.hypot(*(drawn - xy).T)
            nearest = int(np.argmin(distances))
            if distances[nearest] <= LABEL_REACH_MM:
                xy = drawn[nearest]
        label = _normal_label(written)
        marked.append((written, label, (float(xy[0]), float(xy[1]))))
        out.setdefault(label, marked[-1][2])
    return out, marked


def _read_svg(root, source: str | None) -> Drawing:
    reader = _SvgReader(root)
    reader.walk()
    if not reader.labels:
        raise SubmissionError(message("no labelled points: label the plan's points with text "
                                      "(p or π for the pole, b, c, …) next to them"))
    out, marked = _marked(reader.labels, reader.points)
    plan = root.get("data-planmethod-plan")
    if plan is None:
        if "π" in out and "p" not in out:
            plan = "acceleration"
        elif "p" in out and "π" not in out:
            plan = "velocity"
    notes = tuple(POINT_PARTS[PointPart.IGNORED].replace(tag=tag) for tag in sorted(reader.ignored))
    return Drawing(out, plan, notes, source, (), labels=tuple(marked))


# -- grading ---------------------------------------------------------------------------------
def exercise_digest(exercise) -> str:
    """A short digest of an exercise's mechanism, drawing settings and scene. The workbook
    page keeps a drawing under it and writes it into the drawing it downloads, so that a
    drawing of another exercise with the same title (a template's variant) or of an earlier
    version of the exercise is told apart, in the page and by :func:`key_for_drawing`.

    >>> from planmethod.spec import load_exercise
    >>> len(exercise_digest(load_exercise("exercises/slotted_lever.toml")))
    16
    """
    import hashlib

    text = repr((exercise.mechanism, exercise.plan, exercise.ask))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def key_at_angle(key: Mapping[str, Any], angle: float) -> Mapping[str, Any]:
    """The key of the same variant at another crank angle (deg): its exercise posed on the
    assembly chosen at ``drive.angle`` and followed to ``angle``, as ``planmethod solve
    --angle`` and each frame of the workbook page pose it; the key itself at its own angle.

    Raises
    ------
    SubmissionError
        If the key keeps no exercise to pose (a key written without its tables).
    ToggleError, AssemblyError, BranchJumpError
        As :func:`planmethod.kinematics.continuation.pose` on the way to ``angle``.

    Examples
    --------
    >>> from planmethod.grading.keys import build_key
    >>> from planmethod.grading.templates import load_template, draw_variant
    >>> key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    >>> key_at_angle(key, 45)["angle"], key_at_angle(key, 390) is key
    (45.0, True)
    """
    from dataclasses import replace

    from ..kinematics.continuation import pose
    from ..scene import plan_scene
    from .keys import build_key, key_exercise
    from .templates import Variant

    if abs((float(angle) - float(key["angle"]) + 180.0) % 360.0 - 180.0) < 1e-9:
        return key
    exercise = key_exercise(key)
    if exercise is None:
        raise SubmissionError(message("the key of {title!r} keeps no exercise tables: it "
                                      "cannot be built at {phi} = {angle:g}°",
                                      title=key.get("title"), phi=_crank_angle_symbol(key),
                                      angle=float(angle)))
    posed = pose(exercise.mechanism, float(angle), links=plan_scene(exercise).links)
    variant = Variant(str(key.get("student")), int(key.get("seed", 0)),
                      int(key.get("attempt", 0)), key["exercise"], dict(key.get("given", {})),
                      replace(exercise, mechanism=posed.mechanism))
    return build_key(variant)


def key_for_drawing(key: Mapping[str, Any], drawing: Drawing) -> Mapping[str, Any]:
    """The key a drawing is graded against: ``key``, or — for a drawing downloaded from the
    workbook page at another crank angle — the key of the same exercise at the drawing's
    angle (:func:`key_at_angle`: the page's key of that angle).

    Raises
    ------
    SubmissionError
        In one line, if the drawing names another title or another exercise digest than
        the key's exercise (made from another exercise, or from another version of it).
    """
    from .keys import key_exercise

    title = key.get("title")
    if drawing.title is not None and title is not None and drawing.title != title:
        raise SubmissionError(message("the drawing is of {drawn!r}, the key of {title!r}: "
                                      "grade it against the key of its own exercise",
                                      drawn=drawing.title, title=title), file=drawing.source)
    if drawing.exercise is None and drawing.angle is None:
        return key
    exercise = key_exercise(key)
    if drawing.exercise is not None and exercise is not None:
        digest = exercise_digest(exercise)
        if digest != drawing.exercise:
            raise SubmissionError(message(
                "the drawing was made on the page of another version of {title!r} (exercise "
                "digest {drawn}, the key's exercise {digest}): grade it against the exercise "
                "its page was made from", title=title, drawn=drawing.exercise, digest=digest),
                file=drawing.source)
    if drawing.angle is None or exercise is None:
        return key
    with about(drawing.source, key="angle"):   # e.g. cannot be assembled at that angle
        return key_at_angle(key, drawing.angle)


def _crank_angle_symbol(key: Mapping[str, Any]) -> str:
    """φ with the number the key's exercise gives its crank (φ₁ by default)."""
    drive = ((key.get("exercise") or {}).get("drive") or {}).get("link")
    return numbered("φ", key_numbers(key).get(drive, 1))


def _check_exercise(key: Mapping[str, Any], drawing: Drawing) -> None:
    """Refuse, in one line, a drawing that says it is of another exercise or angle."""
    title, angle = key.get("title"), key.get("angle")
    other_title = drawing.title is not None and title is not None and drawing.title != title
    other_angle = (drawing.angle is not None and isinstance(angle, int | float)
                   and abs((drawing.angle - angle + 180.0) % 360.0 - 180.0) > 1e-6)
    if other_title or other_angle:
        raise SubmissionError(message("the drawing is of {drawn!r} at {phi} = {drawn_angle:g}°, "
                                      "the key of {title!r} at {phi} = {angle:g}°: grade it "
                                      "against the key of its own exercise and angle",
                                      drawn=drawing.title, phi=_crank_angle_symbol(key),
                                      drawn_angle=drawing.angle, title=title, angle=angle),
                              file=drawing.source)


def _match(points: Mapping[str, tuple[float, float]], label: str):
    if label in points:
        return points[label]
    folded = {k.casefold(): v for k, v in points.items()}
    return folded.get(label.casefold())


def _one_place_each(drawing: Drawing, labels) -> None:
    """Refuse a drawing in which two labels mark two places for one of ``labels`` (the
    points a plan is graded on), matched as :func:`_match` matches them: one of the two
    would be graded and the other lost without a word. Labels that name no graded point
    (a scale's text, a mechanism's letters) are left alone."""
    for label in labels:
        marks = [mark for mark in drawing.labels if mark[1] == label] or [
            mark for mark in drawing.labels if mark[1].casefold() == label.casefold()]
        places = {(round(x, 3), round(y, 3)): mark for mark in marks for x, y in [mark[2]]}
        if len(places) > 1:
            (first, _, one), (second, _, other) = list(places.values())[:2]
            raise SubmissionError(message(   # where the SVG puts them, in mm: y points down
                "<text> {first!r} at ({x:.1f}, {y:.1f}) mm and <text> {second!r} at "
                "({other_x:.1f}, {other_y:.1f}) mm both mark the point {label} ({compared}): "
                "keep one", first=first, x=one[0], y=-one[1], second=second, other_x=other[0],
                other_y=-other[1], label=label, compared=LABELS_COMPARED), file=drawing.source)


@dataclass(frozen=True)
class _Sheet:
    """What a drawn point is graded against: the student's points (aligned at the pole,
    scaled), the right points and their discs, the step that places each point, the lines
    each intersection lies on, the read steps of the quantities asked, and the links'
    numbers its name is written with."""

    student: Mapping[str, np.ndarray]
    points: Mapping[str, np.ndarray]
    radii: Mapping[str, float]
    by_end: Mapping[str, Mapping[str, Any]]
    lines: Mapping[str, tuple[ConstructionLine, ...]]
    reads: tuple[Mapping[str, Any], ...]
    numbers: Mapping[str, int]

    def name(self, label: str) -> str:
        """A label as the course writes it (b₃)."""
        return label_text(label, self.numbers)

    def drawn(self, label: str) -> np.ndarray:
        """Where the student drew a point, or its right place if it is not drawn."""
        found = _match(self.student, label)
        return found if found is not None else self.points[label]


def _plan_entry(key: Mapping[str, Any], plan: str | None, drawing: Drawing) -> Mapping:
    """The key's table of the plan a drawing is graded as."""
    if plan not in ("velocity", "acceleration"):
        raise SubmissionError(message("cannot tell which plan this is: label the pole p "
                                      "(velocity) or π (acceleration), or say which"),
                              file=drawing.source)
    entry = key["plans"].get(plan)
    if entry is None:
        raise SubmissionError(_NO_PLAN[plan], file=drawing.source)
    return entry


#: a key without the plan a drawing is graded as
_NO_PLAN = {"velocity": message("the key has no velocity plan"),
            "acceleration": message("the key has no acceleration plan")}


def _aligned(drawing: Drawing, pole: str) -> dict[str, np.ndarray]:
    """The drawing's points moved so that its pole is at the origin."""
    origin = _match(drawing.points, pole)
    if origin is None and pole == "π":
        origin = _match(drawing.points, "p")  # a pole labelled p on an acceleration sheet
    if origin is None:
        raise SubmissionError(message("no pole labelled {pole}: cannot align the plan",
                                      pole=pole), file=drawing.source)
    return {label: np.asarray(xy, dtype=float) - np.asarray(origin)
            for label, xy in drawing.points.items()}


def _rescaled(student: dict[str, np.ndarray], entry: Mapping[str, Any],
              numbers: Mapping[str, int]) -> tuple[dict[str, np.ndarray], float, Message | None]:
    """(the points, the factor they were scaled by, the note that says so): a drawing whose
    first vector laid off (pb or πb, given data) has the wrong length is scaled to it (an
    editor's unit mix-up); one more than :data:`MAX_RESCALE` times off is graded as drawn."""
    first = next((s for s in entry["steps"] if s["action"] == "lay_off"), None)
    if first is None:
        return student, 1.0, None
    end = first["end"]
    found = _match(student, end)
    right = np.asarray(entry["points_mm"][end])
    if found is None or not np.hypot(*found) > 0:
        return student, 1.0, None
    drawn, length = float(np.hypot(*found)), float(np.hypot(*right))
    ratio = drawn / length
    tolerance = entry["tolerance_mm"].get(end, 0.5) / length
    segment = {"pole": entry["pole"], "end": label_text(end, numbers), "drawn": drawn,
               "right": length}
    if not 1 / MAX_RESCALE <= ratio <= MAX_RESCALE:
        return student, 1.0, POINT_PARTS[PointPart.SCALE_FAR].replace(limit=MAX_RESCALE,
                                                                      **segment)
    if abs(ratio - 1) <= max(tolerance, 0.02):
        return student, 1.0, None
    factor = 1.0 / ratio
    return ({label: xy * factor for label, xy in student.items()}, factor,
            POINT_PARTS[PointPart.SCALE_FIXED].replace(factor=factor, **segment))


def _sheet(key: Mapping[str, Any], entry: Mapping[str, Any], student, numbers) -> _Sheet:
    steps = entry["steps"]
    asked = {question["id"] for question in key.get("questions", ())}
    return _Sheet(student, {k: np.asarray(v, dtype=float) for k, v in entry["points_mm"].items()},
                  entry["tolerance_mm"], placing_steps(steps), point_lines(entry),
                  tuple(read_steps(entry, asked)), numbers)


def _grade_point(label: str, required: bool, sheet: _Sheet,
                 candidates: Sequence) -> GradedPoint | None:
    """One point's grade (None for a helper point not drawn): within its disc, or where it
    is off and why, named with the known mistakes that put a point there (``candidates``:
    the key's ``mistake_points`` of it)."""
    name = sheet.name(label)
    found = _match(sheet.student, label)
    if found is None:
        return GradedPoint(label, name, False, False, 0.0, 1.0,
                           POINTS[PointVerdict.MISSING].replace(point=name)) if required else None
    right = sheet.points[label]
    radius = float(sheet.radii.get(label, 0.5))
    distance = float(np.hypot(*(found - right)))
    inside = distance <= radius       # the disc itself, as the workbook page compares
    graded = {"point": label, "name": name, "found": True, "correct": bool(inside),
              "score": (1.0 if inside else 0.0) if required else 0.0,
              "max_score": 1.0 if required else 0.0, "distance_mm": distance,
              "tolerance_mm": radius}
    if inside:
        return GradedPoint(feedback=POINTS[PointVerdict.WITHIN].replace(
            point=name, radius=radius, distance=distance), **graded)
    feedback = _explain(label, found, right, distance, radius, sheet)
    named = named_mistakes(candidates, float(found[0]), float(found[1]), radius)
    if named:
        feedback = POINT_PARTS[PointPart.MISTAKES].replace(sentence=feedback,
                                                           lies=mistake_sentence(named))
    return GradedPoint(feedback=feedback, mistakes=tuple(named), **graded)


def grade_drawing(key: Mapping[str, Any], drawing: Drawing, plan: str | None = None, *,
                  rescale: bool = True) -> GradedDrawing:
    """Grade a drawn plan against a key.

    The drawing is moved so that its pole is at the key's pole; with ``rescale`` a drawing
    whose laid-off first vector (pb or πb, given data) has the wrong length is scaled to it
    first (an editor's unit mix-up), and the feedback says so. Each graded point scores if it
    lies in its tolerance disc: no further from its right place than the disc's radius. What
    a student reads names points and quantities as the course does (b₃, ω₃), never as the
    key's ids (b@lever, omega_lever); a point's ``point`` keeps the id a program matches.

    Raises
    ------
    SubmissionError
        If the plan kind cannot be told, or the pole is not labelled.
    """
    plan = plan or drawing.plan
    _check_exercise(key, drawing)
    entry = _plan_entry(key, plan, drawing)
    pole = entry["pole"]
    _one_place_each(drawing, [pole, *(["p"] if pole == "π" else []), *entry["points_mm"]])
    student = _aligned(drawing, pole)
    numbers = key_numbers(key)
    notes: list[Message] = list(drawing.notes)
    factor = 1.0
    if rescale and not drawing.exact_scale:
        student, factor, note = _rescaled(student, entry, numbers)
        notes += [note] if note is not None else []
    sheet = _sheet(key, entry, student, numbers)
    graded = graded_labels(entry)
    wrong = entry.get("mistake_points", {})
    results = [result for label in [*graded, *helper_labels(entry)]
               if (result := _grade_point(label, label in graded, sheet,
                                          wrong.get(label, ()))) is not None]
    # a whole-plan mistake only where every wrong point is named with it, by the one rule
    # the workbook page applies to the same data (plan_points.common_mistakes)
    common = common_mistakes([list(r.mistakes) for r in results if r.found and not r.correct])
    if common:
        notes.append(plan_sentence(common))
    notes += revealed_notes(drawing.revealed, key)
    return GradedDrawing(plan, key.get("student"), sum(r.score for r in results),
                         sum(r.max_score for r in results), factor, tuple(results),
                         tuple(common), tuple(notes), drawing.revealed)


def _line_part(line: ConstructionLine, found: np.ndarray, right: np.ndarray, radius: float,
               sheet: _Sheet) -> Message | None:
    """How a point is off one line it is the intersection of: off the line, or on it and off
    along it (None where it is on the line and near its right place)."""
    base = sheet.drawn(line.through)
    angle = math.radians(line.direction_deg)
    direction = np.array([math.cos(angle), math.sin(angle)])
    off_line = abs(float(cross(found - base, direction)))   # from the whole line
    along = float((found - right) @ direction)
    fields = {"line": line.name, "through": sheet.name(line.through)}
    if off_line <= radius and abs(along) > radius:
        return POINT_PARTS[PointPart.ON_THE_LINE].replace(along=abs(along), **fields)
    if off_line > radius:
        return POINT_PARTS[PointPart.OFF_THE_LINE].replace(off=off_line, **fields)
    return None


def _readings(label: str, sheet: _Sheet) -> list[Message]:
    """The quantities read off a point that it makes wrong by half a percent or more."""
    meanings = []
    for read in sheet.reads:
        if label not in (read["start"], read["end"]):
            continue
        start, end = _match(sheet.student, read["start"]), _match(sheet.student, read["end"])
        if read["start"] in ("p", "π") and start is None:
            start = np.zeros(2)
        if start is None or end is None or not read.get("length_mm"):
            continue
        change = float(np.hypot(*(end - start))) / read["length_mm"] - 1.0
        if abs(change) >= 0.005:
            part = PointPart.READ_HIGH if change > 0 else PointPart.READ_LOW
            meanings.append(POINT_PARTS[part].replace(
                quantity=symbol(read["quantity"], sheet.numbers), percent=abs(change) * 100))
    return list(dict.fromkeys(meanings))


def _explain(label: str, found: np.ndarray, right: np.ndarray, distance: float,
             radius: float, sheet: _Sheet) -> Message:
    """Where a misplaced point is off: the lines of an intersection it is off (or on and off
    along), the length and direction of a vector laid off, the similarity rule that places
    an image; and the readings it makes wrong."""
    name, step = sheet.name(label), sheet.by_end.get(label)
    sentence = POINTS[PointVerdict.OFF].replace(point=name, distance=distance, radius=radius)
    action = step["action"] if step is not None else None
    if action == "intersect":
        parts = [part for line in sheet.lines.get(label, ())
                 if (part := _line_part(line, found, right, radius, sheet)) is not None]
        if len(parts) == 1:
            sentence = POINTS[PointVerdict.OFF_LINE].replace(point=name, distance=distance,
                                                             line=parts[0])
        elif parts:
            sentence = POINTS[PointVerdict.OFF_LINES].replace(point=name, distance=distance,
                                                              line=parts[0], other=parts[1])
    elif action == "lay_off":
        drawn = float(np.hypot(*(found - sheet.drawn(step["start"]))))
        sentence = POINTS[PointVerdict.LAID_OFF].replace(
            point=name, distance=distance, radius=radius, start=sheet.name(step["start"]),
            length=step["length_mm"], direction=step["direction_deg"], drawn=drawn)
    elif action == "similarity":
        sentence = POINTS[PointVerdict.SIMILARITY].replace(
            point=name, distance=distance, radius=radius,
            references=[sheet.name(reference) for reference in step.get("references", [])])
    readings = _readings(label, sheet)
    if readings:
        sentence = POINT_PARTS[PointPart.READINGS].replace(sentence=sentence, readings=readings)
    return sentence
