"""The one SVG canvas every figure of planmethod is drawn on (written as svgwrite would).

A :class:`Canvas` collects primitives in page coordinates (px, y down) in fixed layers — lines,
polylines, circles, arrows, fixed text, rectangles — remembers what labels must not cover
(drawn lines and areas), places the requested labels clear of them
(:func:`planmethod.render.labels.place_labels`) and writes the SVG. Plans, the mechanism, the
lever, force polygons, task sheets and blank plan sheets are all drawn on it, so a change in how
an arrow, a label or a scale bar looks is made once, here.

Output is deterministic: no ids unless asked for, no dates, coordinates written with two
decimals, elements in a fixed order, one element a line — the same input gives the same bytes.

Examples
--------
>>> from planmethod.render.labels import RunKind
>>> canvas = Canvas(zoom=2.0)
>>> canvas.line(canvas.px((0, 0)), canvas.px((50, 0)), color="#000000", width=1.0)
>>> canvas.request(("B",), canvas.px((50, 0)), (("B", RunKind.MAIN),))
>>> canvas.place()
>>> figure = canvas.svg("a bar")
>>> figure.svg.startswith("<?xml") and "<title>a bar</title>" in figure.svg
True
>>> [label.text for label in figure.labels]
['B']
"""

from __future__ import annotations

import functools
import html
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..vectors import norm, perp, unit_angle, unit_or_zero
from ..vocabulary import unit_words, xml_characters
from ..words import Message, message, render
from ..words.language import catalogue, current
from .labels import (
    SMALL_RUNS,
    UPRIGHT_RUNS,
    LabelRequest,
    PlacedLabel,
    Run,
    place_labels,
)
from .style import (
    CLEARANCE_PX,
    FAINT,
    FLAG,
    INK,
    LABEL_FAMILY,
    LABEL_SIZE,
    SANS,
    SANS_BOLD,
    SMALL_SIZE,
    STYLES,
    SUB_SCALE,
    SUB_SHIFT,
    TEXT_FAMILY,
    TEXT_SIZE,
    num,
    text_width,
)

__all__ = [
    "Canvas",
    "Point",
    "SvgFigure",
    "arrowhead",
    "fit_zoom",
    "formula_grammar",
    "formula_runs",
    "page_direction",
    "page_point",
    "points_attribute",
    "round_scale_value",
    "scale_bar",
    "shown_text",
]

#: the family of monospaced text (tables on task sheets)
MONO_FAMILY = "DejaVu Sans Mono, monospace"

#: margin (px) round the whole figure
MARGIN = 14.0

#: a point on the page (px, y down): a pair of numbers, or an array (2,) for vector arithmetic
Point = Sequence[float]

#: one element a line (diff-friendly), never inside a <text>: its tspans stay together (the
#: tag a lookahead, so that the line break is a literal replacement: no template per match)
_ONE_PER_LINE = re.compile(r"><(?=/?g\b|line\b|polygon\b|polyline\b|circle\b|text\b|rect\b|"
                           r"title\b|defs\b|/?svg\b|style\b)")


def shown_text(text: Message | str) -> str:
    """``text`` as a figure shows it: a message rendered in the language spoken now (the
    same message in the same language and catalogue rendered once: a figure's legend rows,
    headings and units recur in every figure of a turn), text as it is.

    >>> shown_text(message("{value:g} {unit}", value=0.5, unit="m/s")), shown_text("p")
    ('0.5 m/s', 'p')
    """
    if not isinstance(text, Message):
        return text
    language = current()
    try:
        return _rendered(text, language, catalogue(language))
    except TypeError:           # a field that cannot be a key (a list): rendered each time
        return render(text, language)


@functools.lru_cache(maxsize=2048)
def _rendered(text: Message, language: str, translations: object) -> str:
    """A message rendered in ``language`` with its catalogue ``translations`` (a key only:
    a catalogue read again renders again)."""
    return render(text, language)


@dataclass(frozen=True)
class SvgFigure:
    """A figure written as SVG: its text, its size (px), the placed labels, the numbers of the
    construction steps drawn as arrows, and what it is made of — its viewBox and its elements
    (definitions, then the layers) — so that another figure can hold it whole
    (:meth:`Canvas.nest`)."""

    svg: str
    width: float
    height: float
    labels: tuple[PlacedLabel, ...]
    arrow_steps: tuple[int, ...]
    view: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    elements: tuple = ()


def page_direction(degrees: float) -> np.ndarray:
    """A direction given in degrees counter-clockwise from +x, on the page (y down)."""
    return unit_angle(-math.radians(degrees))


def page_point(xy: Sequence[float]) -> np.ndarray:
    """A point or a direction on the page as an array (for the vector arithmetic of
    :mod:`planmethod.vectors`)."""
    return np.asarray(xy, dtype=float)


def _pair(xy: Point) -> tuple[float, float]:
    """A point as two Python floats (an array's numbers cost more to write)."""
    return (float(xy[0]), float(xy[1]))


def points_attribute(points: Sequence[Point]) -> list[tuple[float, float]]:
    """Points rounded as written (svgwrite formats the list)."""
    return [(float(num(x)), float(num(y))) for x, y in points]


def round_scale_value(value: float) -> float:
    """The largest 1, 2 or 5 × 10ⁿ not above ``value``."""
    exponent = math.floor(math.log10(value))
    for mantissa in (5.0, 2.0, 1.0):
        if mantissa * 10.0 ** exponent <= value * (1 + 1e-12):
            return mantissa * 10.0 ** exponent
    return 10.0 ** exponent  # pragma: no cover


#: the room (px) other labels keep from a point's mark, so that no label reads as another
#: point's (where points crowd closer than the readable distance, an enlarged detail shows
#: them)
KEEP_CLEAR = CLEARANCE_PX

#: the side of the square whose area is a round mark's (its 16-gon's), per unit of radius
_ROUND_MARK = math.sqrt(8.0 * math.sin(math.pi / 8.0))

_LAYERS = ("ground", "construction", "similarity", "links", "components", "results",
           "marks", "points", "leaders", "labels", "text")
#: the layers of what a figure draws (its mechanism's links and pairs, its plan's vectors and
#: points), not of its construction lines, marks, labels or notes: :attr:`Canvas.drawn`
DRAWN_LAYERS = frozenset(("links", "components", "results", "points"))


def _widen(extent: list[float], points) -> None:
    """Widen a box [x0, y0, x1, y1] to hold ``points``."""
    for x, y in points:
        if x < extent[0]:
            extent[0] = x
        if x > extent[2]:
            extent[2] = x
        if y < extent[1]:
            extent[1] = y
        if y > extent[3]:
            extent[3] = y


class Canvas:
    """Primitives in page coordinates (px, y down), layered; labels placed at the end."""

    def __init__(self, zoom: float = 1.0) -> None:
        self.zoom = zoom
        self.layers: dict[str, list] = {name: [] for name in _LAYERS}
        self.definitions: list = []
        #: what labels keep clear of: drawn lines as point sequences, marks and fixed text as
        #: rectangles (x0, y0, x1, y1)
        self.obstacle_lines: list[tuple[Point, ...]] = []
        self.obstacle_areas: list[tuple[float, float, float, float]] = []
        #: the points' marks (x, y, radius, i): each one's area is ``obstacle_areas[i]``
        self.point_marks: list[tuple[float, float, float, int]] = []
        #: the vectors' arrows among the obstacle lines: leaders keep off them
        self.vector_lines: list[tuple[Point, ...]] = []
        self.requests: list[LabelRequest] = []
        self.used: set[str] = set()
        self.arrow_steps: list[int] = []
        self.extent = [math.inf, math.inf, -math.inf, -math.inf]
        #: the extent of what the figure draws (:data:`DRAWN_LAYERS`): its page is framed on it
        self.drawn = [math.inf, math.inf, -math.inf, -math.inf]
        self.labels: tuple[PlacedLabel, ...] = ()

    # coordinates
    def px(self, xy: Sequence[float]) -> np.ndarray:
        """A drawing's point (mm, y up) on the page (px, y down)."""
        return np.array((float(xy[0]) * self.zoom, -float(xy[1]) * self.zoom))

    def grow(self, *points: Point, layer: str = "") -> None:
        """Widen the extent to hold ``points`` (and the drawn extent, for an element of one of
        :data:`DRAWN_LAYERS`)."""
        if layer in DRAWN_LAYERS:
            _widen(self.drawn, points)
        _widen(self.extent, points)

    # primitives
    def add(self, layer: str, tag: str, attrs: dict[str, Any], children: list | None = None
            ) -> None:
        self.layers[layer].append((tag, attrs, children or []))

    def line(self, p: Point, q: Point, *, color: str, width: float, dash: str | None = None,
             layer: str = "construction", obstacle: bool = True, cap: str = "butt",
             css: str | None = None, data: dict | None = None) -> None:
        p, q = _pair(p), _pair(q)
        attrs = {"x1": num(p[0]), "y1": num(p[1]), "x2": num(q[0]), "y2": num(q[1]),
                 "stroke": color, "stroke-width": num(width)}
        if dash:
            attrs["stroke-dasharray"] = dash
        if cap != "butt":
            attrs["stroke-linecap"] = cap
        if css:
            attrs["class"] = css
        attrs.update(data or {})
        self.add(layer, "line", attrs)
        self.grow(p, q, layer=layer)
        if obstacle and (p[0] != q[0] or p[1] != q[1]):
            self.obstacle_lines.append((p, q))

    def polyline(self, points: Sequence[Point], *, color: str, width: float,
                 dash: str | None = None, layer: str = "marks", obstacle: bool = True,
                 fill: str = "none", closed: bool = False, css: str | None = None,
                 data: dict | None = None, vector: bool = False) -> None:
        """A polyline (a polygon if ``closed``); labels keep clear of it if an ``obstacle``,
        and leaders keep off it if it draws a ``vector`` (a curved arrow)."""
        points = [_pair(point) for point in points]
        attrs = {"points": points_attribute(points), "fill": fill, "stroke": color,
                 "stroke-width": num(width), "stroke-linejoin": "round"}
        if dash:
            attrs["stroke-dasharray"] = dash
        if css:
            attrs["class"] = css
        attrs.update(data or {})
        self.add(layer, "polygon" if closed else "polyline", attrs)
        self.grow(*points, layer=layer)
        if obstacle:
            self.obstacle_lines.append(tuple(points) + ((points[0],) if closed else ()))
        if vector:
            self.vector_lines.append(tuple(points))

    def circle(self, centre: Point, radius: float, *, fill: str, stroke: str = "none",
               width: float = 0.0, layer: str = "points", area: bool = True,
               css: str | None = None, points: Sequence[str] = ()) -> None:
        """A circle; the mark of the named ``points`` if any (written in ``data-points``):
        other points' labels then keep :data:`KEEP_CLEAR` px from it."""
        centre = _pair(centre)
        attrs = {"cx": num(centre[0]), "cy": num(centre[1]), "r": num(radius), "fill": fill}
        if stroke != "none":
            attrs |= {"stroke": stroke, "stroke-width": num(width)}
        if css:
            attrs["class"] = css
        if points:
            attrs["data-points"] = " ".join(points)
        self.add(layer, "circle", attrs)
        self.grow((centre[0] - radius, centre[1] - radius),
                  (centre[0] + radius, centre[1] + radius))
        if layer in DRAWN_LAYERS:
            _widen(self.drawn, (centre,))
        if area:
            # a round mark as the square of the area of its 16-gon (a point's, with room)
            half = _ROUND_MARK * radius / 2 + (KEEP_CLEAR if points else 0.0)
            self.obstacle_areas.append((centre[0] - half, centre[1] - half, centre[0] + half,
                                        centre[1] + half))
            if points:
                self.point_marks.append((centre[0], centre[1], float(radius),
                                         len(self.obstacle_areas) - 1))

    def arrow(self, p: Point, q: Point, style_key: str, *, layer: str, step: int | None = None,
              color: str | None = None, css: str | None = None, obstacle: bool = True
              ) -> bool:
        """A vector from p to q with its head at q; False if too short to draw. Labels keep
        clear of it, and leaders keep off it (unless not an ``obstacle``: a legend's
        sample)."""
        style = STYLES[style_key]
        p, q = page_point(p), page_point(q)
        length = float(norm(q - p))
        if length < 0.5:
            return False
        color = color or style.color
        u = unit_or_zero(q - p, length)
        n = perp(u)
        head = min(style.head, 0.55 * length)
        half = head * 0.36
        base = q - head * u
        shaft_end = _pair(q - 0.75 * head * u)
        wings = [_pair(base + half * n), _pair(base - half * n)]
        p, q = _pair(p), _pair(q)
        line = {"x1": num(p[0]), "y1": num(p[1]), "x2": num(shaft_end[0]),
                "y2": num(shaft_end[1]), "stroke": color, "stroke-width": num(style.width)}
        if style.dash:
            line["stroke-dasharray"] = style.dash
        tip = {"points": points_attribute([q, *wings]), "fill": color}
        group = {"class": f"arrow {css or style_key}"}
        if step is not None:
            group["data-step"] = str(step)
            self.arrow_steps.append(step)
        self.add(layer, "g", group, [("line", line, []), ("polygon", tip, [])])
        self.grow(p, q, layer=layer)
        if obstacle:                   # the shaft, and the head's outline
            self.obstacle_lines += [(p, q), (q, wings[0], wings[1], q)]
            self.vector_lines += [(p, q), (q, wings[0], wings[1], q)]
        return True

    def rectangle(self, corner: Point, size: Point, *, fill: str, stroke: str = "none",
                  width: float = 0.0, layer: str = "ground", css: str | None = None,
                  obstacle: bool = False) -> None:
        """An axis-aligned rectangle, top-left at ``corner`` (page px); with ``obstacle``
        labels keep clear of its outline."""
        attrs = {"x": num(corner[0]), "y": num(corner[1]), "width": num(size[0]),
                 "height": num(size[1]), "fill": fill}
        if stroke != "none":
            attrs |= {"stroke": stroke, "stroke-width": num(width)}
        if css:
            attrs["class"] = css
        self.add(layer, "rect", attrs)
        far = (corner[0] + size[0], corner[1] + size[1])
        self.grow(corner, far)
        if obstacle:
            self.obstacle_lines.append(((corner[0], corner[1]), (far[0], corner[1]), far,
                                        (corner[0], far[1]), (corner[0], corner[1])))

    def define(self, tag: str, attrs: dict[str, Any], children: list | None = None) -> None:
        """An element of ``<defs>`` (a pattern, a marker), written before the layers."""
        self.definitions.append((tag, attrs, children or []))

    def grid_pattern(self, ident: str, step: float, *, color: str, width: float) -> str:
        """A square grid of ``step`` as a pattern of ``<defs>``; returns the fill that paints
        with it (``url(#ident)``)."""
        self.define("pattern", {"id": ident, "width": num(step), "height": num(step),
                                "patternUnits": "userSpaceOnUse"},
                    [("path", {"d": f"M {num(step)} 0 L 0 0 0 {num(step)}", "fill": "none",
                               "stroke": color, "stroke-width": num(width)}, [])])
        return f"url(#{ident})"

    def cells(self, corner: Point, cell: float, rows: Sequence[Sequence[bool]], *,
              color: str = INK, layer: str = "marks", css: str) -> None:
        """Square cells of side ``cell``, the top-left one at ``corner``, those true in
        ``rows`` filled — a QR code's modules, a fiducial marker's bits — as one path, each
        row's runs of filled cells one rectangle (no seam between neighbours)."""
        x0, y0 = _pair(corner)
        parts = []
        for row, values in enumerate(rows):
            column = 0
            while column < len(values):
                if not values[column]:
                    column += 1
                    continue
                end = column
                while end < len(values) and values[end]:
                    end += 1
                parts.append(f"M{num(x0 + column * cell)} {num(y0 + row * cell)}"
                             f"h{num((end - column) * cell)}v{num(cell)}"
                             f"h{num(-(end - column) * cell)}z")
                column = end
        if parts:
            self.add(layer, "path", {"d": "".join(parts), "fill": color, "class": css})
        self.grow((x0, y0), (x0 + cell * max((len(row) for row in rows), default=0),
                             y0 + cell * len(rows)))

    def rules(self, box: Sequence[float], *, xs: Sequence[float] = (),
              ys: Sequence[float] = (), color: str, width: float, css: str,
              layer: str = "ground") -> None:
        """Ruled lines across ``box`` (x0, y0, x1, y1): vertical ones at ``xs``, horizontal
        ones at ``ys`` — a sheet's grid — as one path."""
        x0, y0, x1, y1 = (float(value) for value in box)
        parts = [f"M{num(x)} {num(y0)}V{num(y1)}" for x in xs]
        parts += [f"M{num(x0)} {num(y)}H{num(x1)}" for y in ys]
        if parts:
            self.add(layer, "path", {"d": "".join(parts), "fill": "none", "stroke": color,
                                     "stroke-width": num(width), "class": css})
        self.grow((x0, y0), (x1, y1))

    def style_sheet(self, css: str) -> None:
        """A ``<style>`` sheet of the figure (an animation's keyframes), in ``<defs>``."""
        self.definitions.append(("style", {}, [css]))

    def nest(self, figures: Sequence[tuple[SvgFigure, Point, Point]], *, layer: str = "ground",
             css: str, style: str | None = None) -> None:
        """A group of whole figures (each with its own viewBox, its background and its
        elements), each in the box ``(figure, corner, size)`` of this page."""
        cells = []
        for figure, corner, size in figures:
            x0, y0, width, height = figure.view
            cells.append(("svg", {"x": num(corner[0]), "y": num(corner[1]),
                                  "width": num(size[0]), "height": num(size[1]),
                                  "viewBox": f"{num(x0)} {num(y0)} {num(width)} {num(height)}"},
                          list(figure.elements)))
            self.grow(corner, (corner[0] + size[0], corner[1] + size[1]))
        attrs = {"class": css}
        if style:
            attrs["style"] = style
        self.add(layer, "g", attrs, cells)

    def clipped(self, other: Canvas, box: Sequence[float], offset: Point, *,
                layers: Sequence[str], css: str, ident: str) -> None:
        """Another canvas's ``layers`` drawn on this one, moved by ``offset`` and clipped to
        ``box`` (x0, y0, x1, y1 in the other canvas's px) — an enlarged detail."""
        x0, y0, x1, y1 = box
        self.define("clipPath", {"id": ident}, [
            ("rect", {"x": num(x0), "y": num(y0), "width": num(x1 - x0),
                      "height": num(y1 - y0)}, [])])
        seen = (x0 - _CULL, y0 - _CULL, x1 + _CULL, y1 + _CULL)
        drawing = [("g", {"class": name}, shown) for name, items in other.layers.items()
                   if name in layers
                   for shown in [[item for item in items if _meets(_bounds(item), seen)]]
                   if shown]             # what the clip hides entirely is not written
        self.add("points", "g", {"class": css, "clip-path": f"url(#{ident})",
                                 "transform": _move(offset)}, drawing)

    def moved(self, items: Mapping[str, Sequence], offset: Point, *, css: str) -> None:
        """Elements of another canvas (``{layer name: its elements}``) drawn on this one's
        labels, moved by ``offset`` and not clipped (labels kept whole)."""
        self.add("labels", "g", {"class": css, "transform": _move(offset)},
                 [("g", {"class": name}, list(elements)) for name, elements in items.items()])

    def text(self, xy: Point, text: Message | str, *, size: float = TEXT_SIZE,
             color: str = INK, anchor: str = "start", bold: bool = False, css: str = "note",
             layer: str = "text", area: bool = True, family: str = TEXT_FAMILY,
             italic: bool = False, monospace: bool = False, formula: bool = False,
             points: Sequence[str] = ()) -> float:
        """Fixed text (sans, or monospaced with its spaces kept); returns its width. A message
        is rendered in the language spoken now. A ``formula`` sets what follows an underscore
        as a subscript (``a_B₃`` → a with B₃ below, :func:`formula_runs`); ``points`` are the
        points it names (``data-points``: a table's row of a point)."""
        text = shown_text(text)
        font = SANS_BOLD if bold else SANS
        runs = formula_runs(text) if formula else [(text, False)]
        if monospace:
            family = MONO_FAMILY
            width = 0.6 * size * len(text)
        else:
            width = sum(text_width(part, size * SUB_SCALE if small else size, font)
                        for part, small in runs)
        attrs = {"x": num(xy[0]), "y": num(xy[1]), "font-family": family,
                 "font-size": num(size), "fill": color, "class": css}
        if bold:
            attrs["font-weight"] = "bold"
        if italic:
            attrs["font-style"] = "italic"
        if anchor != "start":
            attrs["text-anchor"] = anchor
        if monospace:
            attrs["xml:space"] = "preserve"
        if points:
            attrs["data-points"] = " ".join(points)
        if len(runs) > 1:
            self.add(layer, "text", attrs, _formula_spans(runs, size, monospace))
        else:
            self.add(layer, "text", attrs, [text])
        left = xy[0] - (width if anchor == "end" else width / 2 if anchor == "middle" else 0)
        self.grow((left, xy[1] - 0.8 * size), (left + width, xy[1] + 0.25 * size))
        if area:
            self.obstacle_areas.append((left, xy[1] - 0.8 * size, left + width,
                                        xy[1] + 0.25 * size))
        return width

    def table(self, at: Point, rows: Sequence[Sequence[Message | str]], *,
              header: Sequence[Message | str], right: Sequence[bool] = (),
              size: float = TEXT_SIZE, css: str = "table", title: Message | str = "",
              points: Sequence[Sequence[str]] = ()) -> float:
        """A table set at ``size`` (the figure's normal text), top-left at ``at``: an
        optional bold ``title``, a bold header, a rule, one row a line; the columns flagged
        in ``right`` (numbers) are aligned right. Cells are formulas (``F_b`` → F with b
        below), messages rendered; a row's first cell names the ``points`` given for it, if
        any. Returns the y (px) under its last row."""
        x, y = at
        columns = len(header)
        cells = [[shown_text(cell) for cell in header]] + [
            [shown_text(cell) for cell in row] + [""] * (columns - len(row)) for row in rows]
        widths = [max(sum(text_width(part, size * SUB_SCALE if small else size,
                                     SANS_BOLD if index == 0 else SANS)
                          for part, small in formula_runs(row[column]))
                      for index, row in enumerate(cells)) for column in range(columns)]
        gap = 1.2 * size
        if title:
            self.text((x, y), title, size=size, bold=True, css=css, area=False, formula=True)
            y += 1.6 * size
        for index, row in enumerate(cells):
            left = x
            for column, cell in enumerate(row):
                aligned = column < len(right) and right[column]
                named = points[index - 1] if 0 < index <= len(points) and not column else ()
                self.text((left + widths[column] if aligned else left, y), cell, size=size,
                          bold=index == 0, css=css, anchor="end" if aligned else "start",
                          area=False, formula=True, points=named)
                left += widths[column] + gap
            if index == 0:
                self.line((x, y + 0.45 * size), (left - gap, y + 0.45 * size), color=INK,
                          width=0.6, layer="text", obstacle=False, css="rule")
            y += 1.5 * size
        return y

    def request(self, points: tuple[str, ...], anchor: Point, runs: tuple[Run, ...], *,
                size: float = LABEL_SIZE, mark: float = 3.0, css: str = "label",
                span: Sequence[Point] | None = None, lean: Point | None = None) -> None:
        """A label to place at ``anchor``; ``span`` is the vector (start, end) it names, if
        it names one, or the points of a curved arrow's arc (an enlarged detail anchors it on
        the part it shows; a crowded label's leader may start anywhere along it); ``lean``
        the side (a unit page direction) it prefers among equally clean spots."""
        self.requests.append(LabelRequest(points, (float(anchor[0]), float(anchor[1])), runs,
                                          size, mark, css,
                                          tuple(_pair(point) for point in span) if span
                                          else None,
                                          _pair(lean) if lean is not None else None))

    # labels
    def trial(self, bounds: Sequence[float] | None = None) -> tuple[PlacedLabel, ...]:
        """Where the requested labels would go (within ``bounds`` where they can, as
        :meth:`place` puts them), without drawing them."""
        return place_labels(self.requests, self.obstacle_lines, self.obstacle_areas,
                            vectors=self.vector_lines, marks=self.point_marks, bounds=bounds)

    def place(self, bounds: Sequence[float] | None = None,
              labels: tuple[PlacedLabel, ...] | None = None) -> None:
        """Place the requested labels (within ``bounds``, x0, y0, x1, y1, where they can) and
        draw them with their leaders — or draw the ``labels`` a :meth:`trial` placed."""
        self.labels = self.trial(bounds) if labels is None else labels
        for label in self.labels:
            x0, y0, x1, y1 = label.box
            self.grow((x0, y0), (x1, y1))
            color = {"faint": FAINT, "flag": FLAG}.get(label.css, INK)
            if label.leader:
                ax, ay = label.anchor
                cx = min(max(ax, x0), x1)
                cy = min(max(ay, y0), y1)
                self.add("leaders", "line", {"x1": num(ax), "y1": num(ay), "x2": num(cx),
                                             "y2": num(cy), "stroke": color,
                                             "stroke-width": "0.6", "class": "leader",
                                             "data-points": " ".join(label.points)})
            self.add("labels", "text", _label_attrs(label, color), _label_spans(label))

    # output
    def svg(self, title: Message | str, *,
            view: tuple[float, float, float, float] | None = None,
            unit: str = "", attributes: Mapping[str, str] | None = None) -> SvgFigure:
        """The SVG text of everything drawn, as an :class:`SvgFigure`.

        ``view`` fixes the viewBox ``(x, y, width, height)`` (default: what was drawn plus a
        margin); ``unit`` is appended to the width and height (``"mm"`` prints at scale);
        ``attributes`` are added to the root element (e.g. ``data-…`` markers a reader looks
        for).
        """
        if view is None:
            x0, y0, x1, y1 = self.extent
            x0, y0, x1, y1 = x0 - MARGIN, y0 - MARGIN, x1 + MARGIN, y1 + MARGIN
            width, height = x1 - x0, y1 - y0
        else:
            x0, y0, width, height = view
        # the document's shell (its root, title, definitions, background) and the drawn
        # elements are written as ElementTree writes svgwrite's elements of them (attributes
        # sorted, svgwrite's defaults first; :func:`_shell`), at a fraction of the time
        shell = _shell(width, height, unit, (x0, y0), attributes or {}, shown_text(title))
        if self.definitions:
            definitions = ["<defs>"]
            for item in self.definitions:
                _write(item, definitions)
            shell = shell.replace("<defs />", "".join(definitions) + "</defs>", 1)
        drawn: list[str] = []
        for name in _LAYERS:
            if self.layers[name]:
                drawn.append(f'<g class="{name}">')
                for item in self.layers[name]:
                    _write(item, drawn)
                drawn.append("</g>")
        body = _ONE_PER_LINE.sub(">\n<", shell[:-len("</svg>")] + "".join(drawn) + "</svg>")
        text = '<?xml version="1.0" encoding="utf-8"?>\n' + body + "\n"
        background = ("rect", {"x": num(x0), "y": num(y0), "width": num(width),
                               "height": num(height), "fill": "#ffffff",
                               "class": "background"}, [])
        elements = ((("defs", {}, list(self.definitions)),) if self.definitions else ()) + (
            background,) + tuple(("g", {"class": name}, self.layers[name])
                                 for name in _LAYERS if self.layers[name])
        return SvgFigure(text, float(num(width)), float(num(height)), self.labels,
                         tuple(self.arrow_steps), (float(x0), float(y0), float(width),
                                                   float(height)), elements)


#: the root element's attributes svgwrite writes for a full-profile drawing
_SVG_ROOT = {"baseProfile": "full", "version": "1.1", "xmlns": "http://www.w3.org/2000/svg",
             "xmlns:ev": "http://www.w3.org/2001/xml-events",
             "xmlns:xlink": "http://www.w3.org/1999/xlink"}


def _shell(width: float, height: float, unit: str, corner: tuple[float, float],
           attributes: Mapping[str, str], title: str) -> str:
    """An SVG document with nothing drawn, as ElementTree writes svgwrite's full-profile
    ``Drawing`` of that size (``unit`` appended), its viewBox from ``corner``, the root's
    extra ``attributes``, the ``title`` and a white background (the test holds it to
    svgwrite's).

    >>> _shell(10, 5, "", (0, -1), {"data-kind": "plan"}, "a & b")[:62]
    '<svg baseProfile="full" data-kind="plan" height="5" version="1'
    """
    x, y = num(corner[0]), num(corner[1])
    root = {**_SVG_ROOT, "width": num(width) + unit, "height": num(height) + unit,
            "viewBox": f"{x} {y} {num(width)} {num(height)}",
            **{key: xml_characters(value) for key, value in attributes.items()}}
    head: list[str] = []
    _write(("svg", root, []), head)
    background: list[str] = []
    _write(("rect", {"x": x, "y": y, "width": num(width), "height": num(height),
                     "fill": "#ffffff", "class": "background"}, []), background)
    return (head[0][:-len(" />")] + f"><title>{_escape_text(title)}</title><defs />"
            + background[0] + "</svg>")


#: how far (px) beyond a clip box an element may reach and still be written: a stroke's width
_CULL = 4.0


def _bounds(item) -> tuple[float, float, float, float] | None:
    """The box (x0, y0, x1, y1) an element ``(tag, attributes, children)`` covers, None if
    unknown (a path, text: always written).

    >>> _bounds(("g", {}, [("line", {"x1": "0", "y1": "0", "x2": "5", "y2": "2"}, []),
    ...                    ("circle", {"cx": "9", "cy": "1", "r": "1"}, [])]))
    (0.0, 0.0, 10.0, 2.0)
    """
    tag, attrs, children = item
    if tag == "line":
        xs, ys = (float(attrs["x1"]), float(attrs["x2"])), (float(attrs["y1"]), float(attrs["y2"]))
    elif tag in ("polyline", "polygon"):
        xs, ys = tuple(x for x, _ in attrs["points"]), tuple(y for _, y in attrs["points"])
    elif tag == "circle":
        cx, cy, r = (float(attrs[key]) for key in ("cx", "cy", "r"))
        xs, ys = (cx - r, cx + r), (cy - r, cy + r)
    elif tag == "rect":
        x, y = float(attrs["x"]), float(attrs["y"])
        xs, ys = (x, x + float(attrs["width"])), (y, y + float(attrs["height"]))
    elif tag == "g" and children:
        parts = [_bounds(child) for child in children if not isinstance(child, str)]
        if not parts or any(part is None for part in parts):
            return None
        return (min(p[0] for p in parts), min(p[1] for p in parts),
                max(p[2] for p in parts), max(p[3] for p in parts))
    else:
        return None
    return (min(xs), min(ys), max(xs), max(ys))


def _meets(bounds, box) -> bool:
    return bounds is None or (bounds[0] <= box[2] and box[0] <= bounds[2]
                              and bounds[1] <= box[3] and box[1] <= bounds[3])


def _move(offset: Point) -> str:
    return f"translate({num(offset[0])},{num(offset[1])})"


#: the attributes svgwrite gives an element of these tags before its own
_SVGWRITE_DEFAULTS = {"line": {"x1": "0", "y1": "0", "x2": "0", "y2": "0"},
                      "circle": {"cx": "0", "cy": "0", "r": "1"},
                      "rect": {"x": "0", "y": "0", "width": "1", "height": "1"},
                      "ellipse": {"cx": "0", "cy": "0", "rx": "1", "ry": "1"}}


#: a character ElementTree escapes in an attribute's value, or one XML cannot hold (most
#: values have none)
_ATTRIBUTE_SPECIAL = re.compile('[&<>"\r\n\t\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]')


def _escape_text(text: str) -> str:
    """Text as XML character data (what ElementTree escapes in it; a character XML cannot
    hold, a control character from a file, as U+FFFD: :func:`~planmethod.vocabulary.
    xml_characters`).

    >>> _escape_text("a<b & c>d")
    'a&lt;b &amp; c&gt;d'
    """
    return xml_characters(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _escape_attribute(text: str) -> str:
    """An attribute's value as ElementTree writes it.

    >>> _escape_attribute('x="1" & 2')
    'x=&quot;1&quot; &amp; 2'
    """
    if _ATTRIBUTE_SPECIAL.search(text) is None:
        return text
    return (_escape_text(text).replace('"', "&quot;").replace("\r", "&#13;")
            .replace("\n", "&#10;").replace("\t", "&#09;"))


def _write(item, out: list[str]) -> None:
    """Write ``(tag, attributes, children)`` into ``out`` as ElementTree writes svgwrite's
    element of it: attributes sorted and as strings (empty ones left out), a polygon's points
    as ``x,y`` pairs, strings among the children as the element's text, an element with
    neither text nor children as ``<tag … />``.

    >>> out = []
    >>> _write(("text", {"x": 1, "class": "a&b"}, ["p<", ("tspan", {"dy": "2"}, ["1"])]), out)
    >>> "".join(out)
    '<text class="a&amp;b" x="1">p&lt;<tspan dy="2">1</tspan></text>'
    """
    tag, attrs, children = item
    defaults = _SVGWRITE_DEFAULTS.get(tag)
    if defaults is not None:
        attrs = {**defaults, **attrs}
    if tag in _POINTS_TAGS:
        attrs = {**attrs, "points": " ".join(["%s,%s" % point  # noqa: UP031
                                              for point in attrs["points"]])}
    keys, values = [], []
    for key in sorted(attrs):
        value = attrs[key]
        if value is None:
            continue
        if value.__class__ is not str:
            value = str(value)
        if value:
            keys.append(key)
            values.append(value)
    # one search over the values joined (most are numbers, with nothing to escape)
    if _ATTRIBUTE_SPECIAL.search("".join(values)) is not None:
        values = [_escape_attribute(value) for value in values]
    head = "".join([f' {key}="{value}"' for key, value in zip(keys, values, strict=True)])
    if not children:
        out.append(f"<{tag}{head} />")
        return
    text = ("".join([child for child in children if isinstance(child, str)])
            if tag in _TEXT_TAGS else "")
    elements = [child for child in children if not isinstance(child, str)]
    if not text and not elements:
        out.append(f"<{tag}{head} />")
        return
    out.append(f"<{tag}{head}>{_escape_text(text)}")
    for child in elements:
        _write(child, out)
    out.append(f"</{tag}>")


#: the tags whose ``points`` are a list of pairs, and those whose strings are their text
_POINTS_TAGS = frozenset(("polygon", "polyline"))
_TEXT_TAGS = frozenset(("text", "tspan", "style"))


#: subscript digits inside a subscript are set as plain digits (the run is set small)
_PLAIN_DIGITS = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")
#: a subscript in a formula: what follows an underscore up to a space, a sign or a bracket; a
#: name in square brackets (an answer column, ``[v_C]``) is kept as it is
_SUBSCRIPT_RUN = re.compile(r"\[[^\]]*\]|_([^\s=+−·×,;:()/|\[\]]+)")


def formula_runs(text: str) -> list[tuple[str, bool]]:
    """A formula's runs: (text, set as a subscript).

    >>> formula_runs("a_B₃ = a_B + aᵏ_B₃")
    [('a', False), ('B3', True), (' = a', False), ('B', True), (' + aᵏ', False), ('B3', True)]
    >>> formula_runs("|v_C|   [v_C]")
    [('|v', False), ('C', True), ('|   [v_C]', False)]
    """
    runs: list[tuple[str, bool]] = []
    at = 0
    for match in _SUBSCRIPT_RUN.finditer(text):
        if match.group(1) is None:       # a bracketed name: part of the plain run
            continue
        if match.start() > at:
            runs.append((text[at:match.start()], False))
        runs.append((match.group(1).translate(_PLAIN_DIGITS), True))   # already set small
        at = match.end()
    if at < len(text):
        runs.append((text[at:], False))
    return runs


def formula_grammar() -> dict[str, str]:
    """The grammar of :func:`formula_runs` as data, for a page's script to set the
    subscripts of the sentences it fills (``page_words.js``: ``formula``): the pattern of a
    subscript run (group 1: the subscript) and the subscript digits it sets as plain digits.

    >>> grammar = formula_grammar()
    >>> re.findall(grammar["pattern"], "v_C = v_B₃ [v_C]"), grammar["digits"][:3]
    (['C', 'B₃', ''], '₀₁₂')
    """
    return {"pattern": _SUBSCRIPT_RUN.pattern,
            "digits": "".join(chr(code) for code in sorted(_PLAIN_DIGITS))}


def _formula_spans(runs: Sequence[tuple[str, bool]], size: float, monospace: bool) -> list:
    """The children of a formula's ``<text>``: its first plain run, then a ``<tspan>`` a run,
    a subscript lowered and set small. In a monospaced line (a table row aligned by its
    spaces) what a subscript's smaller letters and its underscore leave of their characters'
    cells is made up where the line next has a gap of spaces, so that its columns stay
    aligned and the symbol stays whole (v_C, m/s)."""
    children: list = [runs[0][0]] if not runs[0][1] else []
    shift = owed = 0.0
    for part, small in runs[1 if children else 0:]:
        target = SUB_SHIFT * size if small else 0.0
        span: dict[str, str] = {"dy": num(target - shift)} if target != shift else {}
        shift = target
        if small:
            span["font-size"] = num(size * SUB_SCALE)
            owed += 0.6 * size * ((1.0 - SUB_SCALE) * len(part) + 1) if monospace else 0.0
        gap = part.find("  ") if owed and not small else -1
        if gap < 0:
            children.append(("tspan", span, [part]))
            continue
        if gap:
            children.append(("tspan", span, [part[:gap]]))
            span = {}
        children.append(("tspan", {**span, "dx": num(owed)}, [part[gap:]]))
        owed = 0.0
    return children


def _label_attrs(label: PlacedLabel, color: str) -> dict[str, str]:
    return {"x": num(label.baseline[0]), "y": num(label.baseline[1]),
            "font-family": LABEL_FAMILY, "font-size": num(label.size), "font-style": "italic",
            "fill": color, "class": label.css, "data-points": " ".join(label.points)}


def _label_spans(label: PlacedLabel) -> list:
    spans = []
    shift = 0.0
    for text, kind in label.runs:
        small = kind in SMALL_RUNS
        target = SUB_SHIFT * label.size if small else 0.0
        attrs: dict[str, str] = {}
        if target != shift:
            attrs["dy"] = num(target - shift)
            shift = target
        if small:
            attrs["font-size"] = num(label.size * SUB_SCALE)
        if kind in UPRIGHT_RUNS:
            attrs["font-style"] = "normal"
        spans.append(("tspan", attrs, [text]))
    return spans



def arrowhead(figure: Canvas, tip: Point, direction: Point, size: float, color: str,
              layer: str, css: str | None = None) -> None:
    """A filled arrowhead at ``tip`` pointing along the page direction ``direction`` (of a
    curved arrow: labels keep clear of it, leaders keep off it)."""
    tip, direction = page_point(tip), page_point(direction)
    n = perp(direction)
    base = tip - size * direction
    corners = [_pair(tip), _pair(base + 0.36 * size * n), _pair(base - 0.36 * size * n)]
    attrs = {"points": points_attribute(corners), "fill": color}
    if css:
        attrs["class"] = css
    figure.add(layer, "polygon", attrs)
    figure.obstacle_lines.append((*corners, corners[0]))
    figure.vector_lines.append((*corners, corners[0]))



def scale_bar(figure: Canvas, at: Point, scale: float, unit: str, target_px: float) -> None:
    """A scale bar: a nice value whose drawn length is near ``target_px``, labelled with its
    ``unit``."""
    if not (scale > 0 and math.isfinite(scale)):
        return
    value = round_scale_value(target_px / figure.zoom * scale)
    length = value / scale * figure.zoom
    x, y = at
    color = INK
    figure.line((x, y), (x + length, y), color=color, width=1.4, layer="text", obstacle=False,
                css="scale bar")
    for t in (0.0, 0.5, 1.0):
        tick = 5.0 if t != 0.5 else 3.0
        figure.line((x + t * length, y - tick), (x + t * length, y + tick), color=color,
                    width=1.0, layer="text", obstacle=False, css="scale bar")
    figure.text((x, y + 17), "0", size=SMALL_SIZE, anchor="middle", area=False, css="scale")
    figure.text((x + length, y + 17), message("{value:g} {unit}", value=value,
                                              unit=unit_words(unit)),
                size=SMALL_SIZE, anchor="middle", area=False, css="scale")



def fit_zoom(points: Sequence[Sequence[float]], size: float) -> float:
    xs = [float(p[0]) for p in points]
    ys = [float(p[1]) for p in points]
    extent = max(max(xs) - min(xs), max(ys) - min(ys)) if points else 0.0
    return size / extent if extent > 1e-9 else 10.0


def empty_svg(attributes: Mapping[str, str]) -> str:
    """An empty inline ``<svg>`` element for an HTML page whose script draws into it (the
    workbook's drawing sheets), its attribute values escaped.

    >>> empty_svg({"data-draw": "velocity", "aria-label": 'a "plan"'})
    '<svg data-draw="velocity" aria-label="a &quot;plan&quot;"></svg>'
    """
    written = " ".join(f'{name}="{html.escape(str(value))}"'
                       for name, value in attributes.items())
    return f"<svg {written}></svg>"
