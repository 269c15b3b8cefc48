"""SVG drawings of the plans, drawn from the plan data alone (svgwrite, shapely).

* :func:`plan_svg` — a velocity or acceleration plan: the pole, every laid-off vector as an
  arrow styled by its component (normal, tangential, Coriolis, relative), the construction lines
  thin and dashed in the colour of their component and clipped to a margin around the plan, the
  vectors found by intersecting two lines, the images of links (similarity), the projection on
  the normal of a path, the results (pole → image of each point) bold, lower-case labels placed
  clear of lines and of each other, coincident points merged ("p ≡ a ≡ c₄"), the scale printed
  with its units and a scale bar, the title, a legend, and every flagged intersection ringed in
  red with the angle of its lines.
* :func:`position_svg` — the mechanism at μl: links as bars (a link with three or more points
  not on one line as a filled polygon), revolute pairs as small circles, fixed pivots with the
  hatched-ground symbol, sliders as blocks on their guides, upper-case labels, μl, the crank's
  ω1 arrow, and for each point whose curvature was read the tangent ττ, the normal ηη, the
  centre of curvature and ρ.
* :func:`lever_svg` — the velocity plan turned 90° onto the mechanism, pole p at the drive's
  pivot, the mechanism faint underneath (Zhukovsky's lever stands on it).
* :func:`plan_files` — all of them as ``{file name: SVG text}``.

Labels follow the textbook (see :mod:`planmethod.render.labels`): ``b@lever`` is printed as b
with the link's name *lever* as an upright subscript, ``n_CB`` as n with subscript CB, ``O2``
as O₂. Each label's ``<text>`` carries the plan labels it names in ``data-points``; each arrow
of a construction step carries the step's number in ``data-step``.

Output is deterministic: no ids, no dates, coordinates written with two decimals, elements in a
fixed order — the same input gives the same bytes. The ``*_drawing`` functions return the SVG
together with the placed labels (for tests and for other drawings that add to a figure).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.plans import draw_plans
>>> plans = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
>>> svg = plan_svg(plans.velocity)
>>> svg.startswith("<?xml") and "μv = 0.2 (m/s)/mm" in svg
True
>>> svg == plan_svg(plans.velocity)
True
>>> sorted(plan_files(plans))
['acceleration.svg', 'lever.svg', 'position.svg', 'velocity.svg']
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .labels import (
    LabelRequest,
    PlacedLabel,
    Run,
    label_runs,
    merge_runs,
    place_labels,
)
from .style import (
    FAINT,
    FLAG,
    GROUND,
    INK,
    LABEL_FAMILY,
    LABEL_SIZE,
    LEGEND_ORDER,
    LINK_FILL,
    SANS,
    SANS_BOLD,
    SMALL_SIZE,
    STYLES,
    SUB_SCALE,
    SUB_SHIFT,
    TEXT_FAMILY,
    TEXT_SIZE,
    TITLE_SIZE,
    num,
    quantity,
    text_width,
)

if TYPE_CHECKING:
    from ..plans import Plan, Plans, PositionPlan, Step

__all__ = [
    "Drawing",
    "lever_drawing",
    "lever_svg",
    "plan_drawing",
    "plan_files",
    "plan_svg",
    "position_drawing",
    "position_svg",
]

#: the longest side of a plan's points is drawn this long (px); a scale bar keeps it honest
PLAN_SIZE = 440.0
#: the longest side of the mechanism is drawn this long (px)
MECHANISM_SIZE = 600.0
#: points closer than this on the page (px) are one point, and their labels are merged
COINCIDENT = 1.0
#: margin (px) round the whole figure
MARGIN = 14.0

Point = tuple[float, float]

_SYMBOLS = {"velocity": "μv", "acceleration": "μa", "force": "μF"}

#: one element a line (diff-friendly), never inside a <text>: its tspans stay together
_ONE_PER_LINE = re.compile(r"><(/?g\b|line\b|polygon\b|polyline\b|circle\b|text\b|rect\b|"
                           r"title\b|defs\b|/svg\b)")


@dataclass(frozen=True)
class Drawing:
    """An SVG figure and its layout: the text, its size (px), the placed labels and the
    numbers of the construction steps drawn as arrows."""

    svg: str
    width: float
    height: float
    labels: tuple[PlacedLabel, ...]
    arrow_steps: tuple[int, ...]


# -- geometry helpers -----------------------------------------------------------------------------
def _sub(p: Point, q: Point) -> Point:
    return (p[0] - q[0], p[1] - q[1])


def _add(p: Point, q: Point, factor: float = 1.0) -> Point:
    return (p[0] + factor * q[0], p[1] + factor * q[1])


def _length(v: Point) -> float:
    return math.hypot(v[0], v[1])


def _unit(v: Point) -> Point:
    length = _length(v)
    return (v[0] / length, v[1] / length) if length else (0.0, 0.0)


def _page_direction(degrees: float) -> Point:
    """A direction given in degrees counter-clockwise from +x, on the page (y down)."""
    return (math.cos(math.radians(degrees)), -math.sin(math.radians(degrees)))


def _points_attr(points: Sequence[Point]) -> list[tuple[float, float]]:
    """Points rounded as written (svgwrite formats the list)."""
    return [(float(num(x)), float(num(y))) for x, y in points]


def _unit_of(unit: str) -> str:
    """The unit a plan's segment stands for: ``(m/s)/mm`` → ``m/s``."""
    if unit.endswith("/mm"):
        unit = unit[:-3].strip()
        if unit.startswith("(") and unit.endswith(")"):
            unit = unit[1:-1]
    return unit


def _nice(value: float) -> float:
    """The largest 1, 2 or 5 × 10ⁿ not above ``value``."""
    exponent = math.floor(math.log10(value))
    for mantissa in (5.0, 2.0, 1.0):
        if mantissa * 10.0 ** exponent <= value * (1 + 1e-12):
            return mantissa * 10.0 ** exponent
    return 10.0 ** exponent  # pragma: no cover


def _clusters(names, where: Mapping[str, Point]) -> list[list[str]]:
    """Names grouped by coincidence on the page (within ``COINCIDENT`` px of a group's
    first member), in the order of their first members."""
    groups: list[list[str]] = []
    for name in names:
        for group in groups:
            if _length(_sub(where[name], where[group[0]])) < COINCIDENT:
                group.append(name)
                break
        else:
            groups.append([name])
    return groups


def _sans_name(name: str) -> str:
    """A point name for plain text, its digits as subscripts (``O1`` → ``O₁``)."""
    head = name.rstrip("0123456789")
    return head + name[len(head):].translate(str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉"))


def _snap(xy: Point) -> tuple[int, int]:
    return (round(xy[0] / COINCIDENT), round(xy[1] / COINCIDENT))


# -- the figure being drawn -----------------------------------------------------------------------
_LAYERS = ("ground", "construction", "similarity", "links", "components", "results",
           "marks", "points", "leaders", "labels", "text")


class _Figure:
    """Primitives in page coordinates (px, y down), layered; labels placed at the end."""

    def __init__(self, zoom: float) -> None:
        self.zoom = zoom
        self.layers: dict[str, list] = {name: [] for name in _LAYERS}
        self.obstacle_lines: list = []
        self.obstacle_areas: list = []
        self.requests: list[LabelRequest] = []
        self.used: set[str] = set()
        self.arrow_steps: list[int] = []
        self.extent = [math.inf, math.inf, -math.inf, -math.inf]
        self.labels: tuple[PlacedLabel, ...] = ()

    # coordinates
    def px(self, xy: Sequence[float]) -> Point:
        return (float(xy[0]) * self.zoom, -float(xy[1]) * self.zoom)

    def grow(self, *points: Point) -> None:
        for x, y in points:
            self.extent = [min(self.extent[0], x), min(self.extent[1], y),
                           max(self.extent[2], x), max(self.extent[3], y)]

    # primitives
    def add(self, layer: str, tag: str, attrs: dict[str, Any], children: list | None = None
            ) -> None:
        self.layers[layer].append((tag, attrs, children or []))

    def line(self, p: Point, q: Point, *, color: str, width: float, dash: str | None = None,
             layer: str = "construction", obstacle: bool = True, cap: str = "butt",
             css: str | None = None, data: dict | None = None) -> None:
        from shapely.geometry import LineString

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
        self.grow(p, q)
        if obstacle and _length(_sub(q, p)) > 0:
            self.obstacle_lines.append(LineString([p, q]))

    def polyline(self, points: Sequence[Point], *, color: str, width: float,
                 dash: str | None = None, layer: str = "marks", obstacle: bool = True,
                 fill: str = "none", closed: bool = False, css: str | None = None) -> None:
        from shapely.geometry import LineString

        attrs = {"points": _points_attr(points), "fill": fill, "stroke": color,
                 "stroke-width": num(width), "stroke-linejoin": "round"}
        if dash:
            attrs["stroke-dasharray"] = dash
        if css:
            attrs["class"] = css
        self.add(layer, "polygon" if closed else "polyline", attrs)
        self.grow(*points)
        if obstacle:
            ring = list(points) + ([points[0]] if closed else [])
            self.obstacle_lines.append(LineString(ring))

    def circle(self, centre: Point, radius: float, *, fill: str, stroke: str = "none",
               width: float = 0.0, layer: str = "points", area: bool = True,
               css: str | None = None) -> None:
        from shapely.geometry import Point as ShapelyPoint

        attrs = {"cx": num(centre[0]), "cy": num(centre[1]), "r": num(radius), "fill": fill}
        if stroke != "none":
            attrs |= {"stroke": stroke, "stroke-width": num(width)}
        if css:
            attrs["class"] = css
        self.add(layer, "circle", attrs)
        self.grow((centre[0] - radius, centre[1] - radius),
                  (centre[0] + radius, centre[1] + radius))
        if area:
            self.obstacle_areas.append(ShapelyPoint(centre).buffer(radius, quad_segs=4))

    def arrow(self, p: Point, q: Point, style_key: str, *, layer: str, step: int | None = None,
              color: str | None = None, css: str | None = None) -> bool:
        """A vector from p to q with its head at q; False if too short to draw."""
        from shapely.geometry import LineString

        style = STYLES[style_key]
        vector = _sub(q, p)
        length = _length(vector)
        if length < 0.5:
            return False
        color = color or style.color
        u = _unit(vector)
        n = (-u[1], u[0])
        head = min(style.head, 0.55 * length)
        half = head * 0.36
        base = _add(q, u, -head)
        shaft_end = _add(q, u, -0.75 * head)
        line = {"x1": num(p[0]), "y1": num(p[1]), "x2": num(shaft_end[0]),
                "y2": num(shaft_end[1]), "stroke": color, "stroke-width": num(style.width)}
        if style.dash:
            line["stroke-dasharray"] = style.dash
        tip = {"points": _points_attr([q, _add(base, n, half), _add(base, n, -half)]),
               "fill": color}
        group = {"class": f"arrow {css or style_key}"}
        if step is not None:
            group["data-step"] = str(step)
            self.arrow_steps.append(step)
        self.add(layer, "g", group, [("line", line, []), ("polygon", tip, [])])
        self.grow(p, q)
        self.obstacle_lines.append(LineString([p, q]))
        return True

    def text(self, xy: Point, text: str, *, size: float = TEXT_SIZE, color: str = INK,
             anchor: str = "start", bold: bool = False, css: str = "note",
             layer: str = "text", area: bool = True) -> float:
        """Fixed text (sans); returns its width."""
        from shapely.geometry import box

        width = text_width(text, size, SANS_BOLD if bold else SANS)
        attrs = {"x": num(xy[0]), "y": num(xy[1]), "font-family": TEXT_FAMILY,
                 "font-size": num(size), "fill": color, "class": css}
        if bold:
            attrs["font-weight"] = "bold"
        if anchor != "start":
            attrs["text-anchor"] = anchor
        self.add(layer, "text", attrs, [text])
        left = xy[0] - (width if anchor == "end" else width / 2 if anchor == "middle" else 0)
        self.grow((left, xy[1] - 0.8 * size), (left + width, xy[1] + 0.25 * size))
        if area:
            self.obstacle_areas.append(box(left, xy[1] - 0.8 * size, left + width,
                                           xy[1] + 0.25 * size))
        return width

    def request(self, points: tuple[str, ...], anchor: Point, runs: tuple[Run, ...], *,
                size: float = LABEL_SIZE, mark: float = 3.0, css: str = "label") -> None:
        self.requests.append(LabelRequest(points, anchor, runs, size, mark, css))

    # labels
    def place(self) -> None:
        self.labels = place_labels(self.requests, self.obstacle_lines, self.obstacle_areas)
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
                                             "stroke-width": "0.6", "class": "leader"})
            self.add("labels", "text", _label_attrs(label, color), _label_spans(label))

    # output
    def svg(self, title: str) -> Drawing:
        import svgwrite

        x0, y0, x1, y1 = self.extent
        x0, y0, x1, y1 = x0 - MARGIN, y0 - MARGIN, x1 + MARGIN, y1 + MARGIN
        width, height = x1 - x0, y1 - y0
        drawing = svgwrite.Drawing(size=(num(width), num(height)), profile="full",
                                   debug=False)
        drawing["viewBox"] = f"{num(x0)} {num(y0)} {num(width)} {num(height)}"
        drawing.set_desc(title=title)
        drawing.add(drawing.rect(insert=(num(x0), num(y0)), size=(num(width), num(height)),
                                 fill="#ffffff", class_="background"))
        for name in _LAYERS:
            if self.layers[name]:
                group = drawing.g(class_=name)
                for item in self.layers[name]:
                    group.add(_element(drawing, item))
                drawing.add(group)
        body = _ONE_PER_LINE.sub(r">\n<\1", drawing.tostring())
        text = '<?xml version="1.0" encoding="utf-8"?>\n' + body + "\n"
        return Drawing(text, float(num(width)), float(num(height)), self.labels,
                       tuple(self.arrow_steps))


def _element(drawing, item):
    """An svgwrite element from ``(tag, attributes, children)``; strings are text content."""
    tag, attrs, children = item
    if tag in ("text", "tspan"):
        element = getattr(drawing, tag)("".join(c for c in children if isinstance(c, str)))
    elif tag in ("polygon", "polyline"):       # svgwrite writes `points` itself
        attrs = dict(attrs)
        element = getattr(drawing, tag)(points=attrs.pop("points"))
    else:
        element = getattr(drawing, tag)()
    for key, value in attrs.items():
        element[key] = value
    for child in children:
        if not isinstance(child, str):
            element.add(_element(drawing, child))
    return element


def _label_attrs(label: PlacedLabel, color: str) -> dict[str, str]:
    return {"x": num(label.baseline[0]), "y": num(label.baseline[1]),
            "font-family": LABEL_FAMILY, "font-size": num(label.size), "font-style": "italic",
            "fill": color, "class": label.css, "data-points": " ".join(label.points)}


def _label_spans(label: PlacedLabel) -> list:
    spans = []
    shift = 0.0
    for text, kind in label.runs:
        small = kind in ("sub", "upright")
        target = SUB_SHIFT * label.size if small else 0.0
        attrs: dict[str, str] = {}
        if target != shift:
            attrs["dy"] = num(target - shift)
            shift = target
        if small:
            attrs["font-size"] = num(label.size * SUB_SCALE)
        if kind in ("upright", "sep"):
            attrs["font-style"] = "normal"
        spans.append(("tspan", attrs, [text]))
    return spans


# -- plans ----------------------------------------------------------------------------------------
def _is_image(label: str, pole: str) -> bool:
    """A plan point that is the image of a mechanism point (not n_…, k_… or the pole)."""
    return "_" not in label and label != pole


def _order_key(label: str, pole: str, order: Mapping[str, int]) -> tuple[int, int]:
    return (0 if label == pole else 1, order[label])


def _plan_content(figure: _Figure, points_mm: Mapping[str, Sequence[float]],
                  steps: Sequence[Step], pole: str, rotate_deg: float = 0.0) -> None:
    """Draw a plan's steps, results, points and label requests into ``figure``."""
    from shapely.geometry import LineString, box

    where = {label: figure.px(xy) for label, xy in points_mm.items()}
    order = {label: index for index, label in enumerate(points_mm)}
    by_number = {step.number: step for step in steps}
    origin = where[pole]
    xs = [p[0] for p in where.values()]
    ys = [p[1] for p in where.values()]
    pad = max(0.16 * max(max(xs) - min(xs), max(ys) - min(ys)), 40.0)
    clip = box(min(xs) - pad, min(ys) - pad, max(xs) + pad, max(ys) + pad)
    reach = 4 * (clip.length + 1)

    results: dict[str, int | None] = {label: None for label in points_mm
                                      if _is_image(label, pole)
                                      and _length(_sub(where[label], origin)) >= 0.5}
    result_keys = {(_snap(origin), _snap(where[label])) for label in results}
    drawn = set(result_keys)
    images: dict[str, list[str]] = {}      # link → plan points of its image

    def component_arrow(start: str, end: str, component: str, step: int | None,
                        always: bool = False) -> None:
        """An arrow unless the same segment is drawn already (a laid-off vector always)."""
        key = (_snap(where[start]), _snap(where[end]))
        if key in drawn and not always:
            return
        drawn.add(key)
        if figure.arrow(where[start], where[end], component, layer="components", step=step):
            figure.used.add(component)

    for step in steps:
        if step.action == "lay_off" and step.start in where and step.end in where:
            if step.start == pole and step.end in results:
                results[step.end] = step.number
            else:
                component_arrow(step.start, step.end, step.component or "relative",
                                step.number, always=True)
        elif step.action == "line" and step.start in where:
            through = where[step.start]
            direction = _page_direction(step.direction_deg + rotate_deg)
            far = LineString([_add(through, direction, -reach), _add(through, direction, reach)])
            piece = far.intersection(clip)
            if piece.is_empty:
                continue
            (ax, ay), (bx, by) = piece.coords[0], piece.coords[-1]
            style = STYLES.get(step.component or "", STYLES["construction"])
            figure.line((ax, ay), (bx, by), color=style.color, width=0.8, dash="5,4",
                        layer="construction", css="construction",
                        data={"data-step": str(step.number)})
            figure.used.add("construction")
            if step.component in STYLES:    # the legend explains the line's colour
                figure.used.add(step.component)
        elif step.action == "intersect" and step.end in where:
            for number in step.lines or ():
                line = by_number.get(number)
                if line is not None and line.start in where:
                    component_arrow(line.start, step.end, line.component or "relative", None)
            if step.flagged:
                figure.circle(where[step.end], 11.0, fill="none", stroke=FLAG, width=1.6,
                              layer="marks", area=False, css="flagged")
                figure.request((f"flag:{step.end}",), where[step.end],
                               ((f"{step.angle_deg:.2g}°", "sep"),), size=SMALL_SIZE,
                               mark=11.0, css="flag")
                figure.used.add("flagged")
        elif step.action == "similarity" and step.vector:
            members = images.setdefault(step.vector, [])
            members += [label for label in (*step.references, step.end) if label in where]
        elif (step.action == "read" and step.quantity
              and step.quantity.startswith(("omega_", "epsilon_"))):
            link = step.quantity.partition("_")[2]
            images.setdefault(link, []).extend(
                label for label in (step.start, step.end)
                if label in where and _is_image(label, pole))
        elif step.action == "project" and step.start in where and step.end in where:
            start, foot = where[step.start], where[step.end]
            style = STYLES["projection"]
            if _length(_sub(start, foot)) >= 0.5:
                figure.line(start, foot, color=style.color, width=style.width,
                            dash=style.dash, layer="similarity", css="projection",
                            data={"data-step": str(step.number)})
                figure.used.add("projection")
                _right_angle(figure, foot, start, origin)
            component_arrow(pole, step.end, "normal", step.number)
    for link, members in images.items():
        if _link_image(figure, [where[label] for label in dict.fromkeys(members)], link):
            figure.used.add("similarity")
    for label, number in results.items():
        if figure.arrow(origin, where[label], "result", layer="results", step=number):
            figure.used.add("result")
    # points and labels: coincident points share one mark and one merged label
    for members in _clusters(points_mm, where):
        members.sort(key=lambda label: _order_key(label, pole, order))
        centre = where[members[0]]
        is_pole = members[0] == pole
        figure.circle(centre, 3.4 if is_pole else 2.4, fill=INK, layer="points",
                      css="pole" if is_pole else "point")
        figure.request(tuple(members), centre,
                       merge_runs(label_runs(label) for label in members), mark=3.4)


def _link_image(figure: _Figure, points: Sequence[Point], link: str) -> bool:
    """The image of a link on a plan (similarity rule): a segment through its images, or a
    light polygon when they do not lie on one line. False if it shrinks to a point."""
    unique = list(dict.fromkeys((round(x, 2), round(y, 2)) for x, y in points))
    if len(unique) < 2:
        return False
    first, second = _extremes(unique)
    span = _length(_sub(first, second))
    if span < 0.5:
        return False
    style = STYLES["similarity"]
    hull = _hull(unique)
    if len(hull) >= 3 and _area(hull) > 1.5 * span:
        figure.polyline(hull, color=style.color, width=style.width, layer="similarity",
                        fill="#ececec", closed=True, css=f"image {link}")
    else:
        figure.line(first, second, color=style.color, width=style.width, layer="similarity",
                    css=f"image {link}")
    return True


def _right_angle(figure: _Figure, corner: Point, first: Point, second: Point) -> None:
    """A small right-angle mark at ``corner`` between the directions to two points."""
    a, b = _sub(first, corner), _sub(second, corner)
    if _length(a) < 12 or _length(b) < 12:
        return
    u, v = _unit(a), _unit(b)
    size = 6.0
    points = [_add(corner, u, size), _add(_add(corner, u, size), v, size), _add(corner, v, size)]
    figure.polyline(points, color=STYLES["projection"].color, width=0.7, layer="similarity",
                    obstacle=False)


def _legend(figure: _Figure, at: Point, kind: str) -> None:
    """The legend of the styles a figure used, top-left at ``at``."""
    x, y = at
    keys = [key for key in (*LEGEND_ORDER, "flagged") if key in figure.used]
    if not keys:
        return
    figure.text((x, y), "Legend", size=TEXT_SIZE, bold=True, css="legend", area=False)
    y += 8
    for key in keys:
        y += 20
        if key == "flagged":
            figure.circle((x + 17, y - 4), 7.0, fill="none", stroke=FLAG, width=1.6,
                          layer="text", area=False)
            text = "intersection at a small angle (flagged)"
        elif key in ("construction", "similarity", "projection"):
            style = STYLES[key]
            figure.line((x, y - 4), (x + 34, y - 4), color=style.color,
                        width=max(style.width, 0.9), dash=style.dash, layer="text",
                        obstacle=False)
            text = style.legend_velocity if kind == "velocity" else style.legend_acceleration
        else:
            style = STYLES[key]
            figure.arrow((x, y - 4), (x + 34, y - 4), key, layer="text")
            figure.obstacle_lines.pop()
            text = style.legend_velocity if kind == "velocity" else style.legend_acceleration
        figure.text((x + 44, y), text, size=SMALL_SIZE, css="legend", area=False)


def _scale_bar(figure: _Figure, at: Point, scale: float, unit: str, target_px: float) -> None:
    """A scale bar: a nice value whose drawn length is near ``target_px``."""
    if not (scale > 0 and math.isfinite(scale)):
        return
    value = _nice(target_px / figure.zoom * scale)
    length = value / scale * figure.zoom
    x, y = at
    color = INK
    figure.line((x, y), (x + length, y), color=color, width=1.4, layer="text", obstacle=False)
    for t in (0.0, 0.5, 1.0):
        tick = 5.0 if t != 0.5 else 3.0
        figure.line((x + t * length, y - tick), (x + t * length, y + tick), color=color,
                    width=1.0, layer="text", obstacle=False)
    figure.text((x, y + 17), "0", size=SMALL_SIZE, anchor="middle", area=False, css="scale")
    figure.text((x + length, y + 17), f"{value:g} {unit}", size=SMALL_SIZE, anchor="middle",
                area=False, css="scale")


def _frame(figure: _Figure, title: str, scale_lines: Sequence[str], bar: tuple | None,
           flags: Sequence[str], kind: str) -> None:
    """Title above, legend at the right, scales, scale bar and flags below the content."""
    x0, y0, x1, y1 = figure.extent
    _legend(figure, (x1 + 34, y0 + 4), kind)
    x0, y0, x1, y1 = figure.extent
    figure.text((x0, y0 - 16), title, size=TITLE_SIZE, bold=True, css="title", area=False)
    y = y1 + 26
    for line in scale_lines:
        figure.text((x0, y), line, size=TEXT_SIZE, css="scale", area=False)
        y += 19
    if bar is not None:
        scale, unit, target = bar
        _scale_bar(figure, (x0 + 8, y + 2), scale, unit, target)
        y += 40
    for flag in flags:
        figure.text((x0, y), "! " + flag, size=SMALL_SIZE, color=FLAG, css="flag", area=False)
        y += 17


def _zoom(points: Sequence[Sequence[float]], size: float) -> float:
    xs = [float(p[0]) for p in points]
    ys = [float(p[1]) for p in points]
    extent = max(max(xs) - min(xs), max(ys) - min(ys)) if points else 0.0
    return size / extent if extent > 1e-9 else 10.0


def plan_drawing(plan: Plan) -> Drawing:
    """A velocity or acceleration plan as an SVG :class:`Drawing` (see the module docstring)."""
    figure = _Figure(_zoom(list(plan.points_mm.values()), PLAN_SIZE))
    _plan_content(figure, plan.points_mm, plan.steps, plan.pole)
    figure.place()
    symbol = _SYMBOLS.get(plan.kind, "μ")
    lines = [f"{symbol} = {quantity(plan.scale, 6)} {plan.unit}"]
    if plan.precision_mm:
        lines.append(f"drafting precision {plan.precision_mm:g} mm")
    _frame(figure, plan.title or f"{plan.kind} plan", lines,
           (plan.scale, _unit_of(plan.unit), 0.3 * PLAN_SIZE), plan.flags, plan.kind)
    return figure.svg(plan.title or f"{plan.kind} plan")


def plan_svg(plan: Plan) -> str:
    """A velocity or acceleration plan as SVG text, drawn from the plan's data alone."""
    return plan_drawing(plan).svg


# -- the mechanism --------------------------------------------------------------------------------
def _mechanism_content(figure: _Figure, position: PositionPlan, *, faint: bool = False) -> None:
    """Links, pairs, pivots, sliders and guides of a position plan, with label requests."""
    ink = FAINT if faint else INK
    fill = "#f2f2f2" if faint else LINK_FILL
    where = {name: figure.px(xy) for name, xy in position.points_mm.items()}
    links = {name: points for name, points in position.links.items()}
    moving = {name: points for name, points in links.items() if name != "frame"}
    count: dict[str, int] = {}
    for points in links.values():
        for point in points:
            count[point] = count.get(point, 0) + 1
    centroid = (sum(p[0] for p in where.values()) / len(where),
                sum(p[1] for p in where.values()) / len(where))
    block_w, block_h = 36.0, 18.0

    # guides of the prismatic pairs
    for slide in position.slides:
        point = slide.get("point")
        if point not in where:
            continue
        through = figure.px(slide["through_mm"])
        u = _page_direction(slide["direction_deg"])
        n = (-u[1], u[0])
        at = where[point]
        s = (at[0] - through[0]) * u[0] + (at[1] - through[1]) * u[1]
        if slide.get("along") == "frame":
            low, high = min(0.0, s) - block_w, max(0.0, s) + block_w
        else:                   # on a moving guide: from its mark to just beyond the block
            low, high = (0.0, s + block_w) if s >= 0 else (s - block_w, 0.0)
        axis = [_add(through, u, low), _add(through, u, high)]
        if slide.get("along") == "frame":
            figure.line(axis[0], axis[1], color=ink, width=0.7, dash="14,3,2,3",
                        layer="ground", css="guide")
        else:                   # the guide is material of the moving link: a bar
            figure.line(axis[0], axis[1], color=ink, width=3.0, layer="links", cap="round",
                        css=f"guide {slide.get('along', '')}")
        if slide.get("along") == "frame":
            lean = (centroid[0] - at[0]) * n[0] + (centroid[1] - at[1]) * n[1]
            if abs(lean) < 1.0:         # the mechanism lies on the guide: hatch below/right
                lean = -(n[1] if abs(n[1]) > 1e-9 else n[0])
            away = (-n[0], -n[1]) if lean > 0 else n
            base = _add(at, away, block_h / 2)
            ends = [_add(base, u, -1.7 * block_w), _add(base, u, 1.7 * block_w)]
            _hatch(figure, ends[0], ends[1], away, ink)

    # links
    for name, points in moving.items():
        placed = [where[p] for p in points if p in where]
        unique = list(dict.fromkeys((round(x, 3), round(y, 3)) for x, y in placed))
        if len(unique) < 2:
            continue
        hull = _hull(unique)
        if len(hull) >= 3 and _area(hull) > 2.0 * max(
                _length(_sub(a, b)) for a in unique for b in unique):
            # under the bars, so that a ternary link never hides a bar drawn across it
            figure.polyline(hull, color=ink, width=2.0, layer="ground", fill=fill, closed=True,
                            css=f"link {name}")
        else:
            a, b = _extremes(unique)
            figure.line(a, b, color=ink, width=3.0, layer="links", cap="round",
                        css=f"link {name}")

    # slider blocks
    for slide in position.slides:
        point = slide.get("point")
        if point not in where:
            continue
        u = _page_direction(slide["direction_deg"])
        n = (-u[1], u[0])
        at = where[point]
        corners = [_add(_add(at, u, sx * block_w / 2), n, sy * block_h / 2)
                   for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        figure.polyline(corners, color=ink, width=1.8, layer="links", fill="#ffffff",
                        closed=True, css=f"slider {slide.get('link', '')}")

    # fixed pivots with the hatched ground
    for pivot in position.pivots:
        if pivot not in where:
            continue
        at = where[pivot]
        spokes = [_unit(_sub(where[other], at)) for name, points in moving.items()
                  if pivot in points for other in points if other != pivot and other in where]
        away = _support_direction(spokes)
        n = (-away[1], away[0])
        base = _add(at, away, 18.0)
        figure.polyline([at, _add(base, n, 9.0), _add(base, n, -9.0)], color=ink, width=1.4,
                        layer="ground", fill="#ffffff", closed=True, css="support")
        _hatch(figure, _add(base, n, -16.0), _add(base, n, 16.0), away, ink)

    # pairs and points
    for name, at in where.items():
        if count.get(name, 0) >= 2:
            figure.circle(at, 4.5, fill="#ffffff", stroke=ink, width=1.5, layer="points",
                          css="pair")
        elif count.get(name, 0) == 1 and name not in links.get("frame", ()):
            figure.circle(at, 2.6, fill=ink, layer="points", css="point")
        else:
            figure.line(_add(at, (-4, -4)), _add(at, (4, 4)), color=ink, width=1.0,
                        layer="points", obstacle=False)
            figure.line(_add(at, (-4, 4)), _add(at, (4, -4)), color=ink, width=1.0,
                        layer="points", obstacle=False)
    for members in _clusters(position.points_mm, where):
        figure.request(tuple(members), where[members[0]],
                       merge_runs(label_runs(name) for name in members), mark=4.5,
                       css="faint" if faint else "label")


def _hatch(figure: _Figure, start: Point, end: Point, away: Point, ink: str) -> None:
    """A ground line from ``start`` to ``end`` hatched on the side ``away``."""
    figure.line(start, end, color=GROUND if ink == INK else ink, width=1.6, layer="ground",
                css="ground")
    u = _unit(_sub(end, start))
    length = _length(_sub(end, start))
    count = max(2, int(length // 7))
    for index in range(count + 1):
        foot = _add(start, u, index * length / count)
        tip = _add(_add(foot, away, 6.0), u, -5.0)
        figure.line(foot, tip, color=GROUND if ink == INK else ink, width=0.9, layer="ground",
                    css="hatch")


def _support_direction(spokes: Sequence[Point]) -> Point:
    """Where a pivot's ground symbol goes: below it, unless a link points that way; then
    up, left or right, whichever is clear (the least crowded if none is)."""
    options = ((0.0, 1.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 0.0))   # page: down, up, left, right

    def conflict(direction: Point) -> float:
        return max((d[0] * direction[0] + d[1] * direction[1] for d in spokes), default=-1.0)

    for option in options:
        if conflict(option) < 0.64:                                  # no link within 50°
            return option
    return min(options, key=conflict)


def _extremes(points: Sequence[Point]) -> tuple[Point, Point]:
    """The two points furthest apart."""
    best = (points[0], points[1])
    for i, a in enumerate(points):
        for b in points[i + 1:]:
            if _length(_sub(a, b)) > _length(_sub(*best)):
                best = (a, b)
    return best


def _hull(points: Sequence[Point]) -> list[Point]:
    """Convex hull (monotone chain), counter-clockwise on the page."""
    pts = sorted(set(points))
    if len(pts) < 3:
        return list(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[Point] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list[Point] = []
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def _area(polygon: Sequence[Point]) -> float:
    return abs(sum(a[0] * b[1] - b[0] * a[1]
                   for a, b in zip(polygon, [*polygon[1:], polygon[0]], strict=True))) / 2


def _omega_arrow(figure: _Figure, position: PositionPlan, ink: str = INK) -> None:
    """The crank's ω1 as a curved arrow round the drive pivot."""
    link, pivot, omega = position.drive
    if not omega or pivot not in position.points_mm:
        return
    others = [p for p in position.links.get(link, ()) if p != pivot and p in position.points_mm]
    if not others:
        return
    centre_mm = position.points_mm[pivot]
    tip_mm = position.points_mm[others[0]]
    start = math.atan2(tip_mm[1] - centre_mm[1], tip_mm[0] - centre_mm[0])
    crank_px = math.hypot(tip_mm[0] - centre_mm[0], tip_mm[1] - centre_mm[1]) * figure.zoom
    radius = min(max(0.42 * crank_px, 20.0), 44.0) / figure.zoom
    sense = 1.0 if omega > 0 else -1.0
    angles = [start + sense * math.radians(22 + 3.5 * k) for k in range(21)]
    arc = [figure.px((centre_mm[0] + radius * math.cos(a), centre_mm[1] + radius * math.sin(a)))
           for a in angles]
    tip = arc[-1]
    direction = _unit(_sub(tip, arc[-2]))
    figure.polyline([*arc[:-1], _add(tip, direction, -7.0)], color=ink, width=1.4,
                    layer="marks", css="omega")
    _arrowhead(figure, tip, direction, 10.0, ink, "marks")
    middle = arc[len(arc) // 2]
    figure.request(("ω1",), middle, (("ω", "main"), ("1", "upright")), mark=1.0)


def _arrowhead(figure: _Figure, tip: Point, direction: Point, size: float, color: str,
               layer: str) -> None:
    """A filled arrowhead at ``tip`` pointing along the page direction ``direction``."""
    n = (-direction[1], direction[0])
    base = _add(tip, direction, -size)
    figure.add(layer, "polygon", {"points": _points_attr(
        [tip, _add(base, n, 0.36 * size), _add(base, n, -0.36 * size)]), "fill": color})


def _curvature_content(figure: _Figure, position: PositionPlan, extent_px: float) -> None:
    """Tangent ττ, normal ηη, centre of curvature and ρ of every point whose ρ was read."""
    for name, data in position.curvature.items():
        if name not in position.points_mm:
            continue
        at = figure.px(position.points_mm[name])
        tangent = _page_direction(float(data["tangent_deg"]))
        normal = _page_direction(float(data["normal_deg"]))
        rho_px = float(data["rho_mm"]) * figure.zoom
        color = "#8a5a00"
        if data.get("path_mm"):
            figure.polyline([figure.px(xy) for xy in data["path_mm"]], color=color, width=0.8,
                            dash="2,3", closed=True, obstacle=False, css="path")
        half = 60.0
        ends = (_add(at, tangent, -half), _add(at, tangent, half))
        figure.line(*ends, color=color, width=1.0, dash="10,3,2,3", layer="marks", css="tangent")
        for end in ends:
            figure.request(("τ",), end, (("τ", "main"),), size=TEXT_SIZE, mark=0.0)
        on_sheet = rho_px <= 1.6 * extent_px
        shown = rho_px if on_sheet else 0.5 * extent_px
        ends = (_add(at, normal, -40.0), _add(at, normal, shown + 24.0))
        figure.line(*ends, color=color, width=1.0, dash="10,3,2,3", layer="marks", css="normal")
        for end in ends:
            figure.request(("η",), end, (("η", "main"),), size=TEXT_SIZE, mark=0.0)
        rho_m = float(data["rho_mm"]) * position.mu_l
        text = (("ρ", "main"), (name, "sub"), (f" = {quantity(rho_m)} m", "sep"))
        if on_sheet:
            centre = _add(at, normal, rho_px)
            figure.arrow(at, centre, "normal", layer="marks", color=color, css="rho")
            figure.circle(centre, 3.0, fill="#ffffff", stroke=color, width=1.4,
                          layer="points", css="centre")
            figure.request((f"O_{name}",), centre, (("O", "main"), (name, "sub")), mark=3.0)
        else:
            text = (*text[:-1], (f" = {quantity(rho_m)} m (centre off the sheet)", "sep"))
        figure.request((f"rho_{name}",), _add(at, normal, 0.5 * shown), text, size=TEXT_SIZE,
                       mark=1.0)


def _position_zoom(position: PositionPlan, extra: Sequence[Sequence[float]] = ()) -> float:
    points = list(position.points_mm.values()) + [tuple(s["through_mm"])
                                                   for s in position.slides] + list(extra)
    return _zoom(points, MECHANISM_SIZE)


def position_drawing(position_plan: PositionPlan, *, plans: Plans | None = None) -> Drawing:
    """The mechanism at μl as an SVG :class:`Drawing` (see the module docstring)."""
    position = position_plan
    centres = []
    base_zoom = _position_zoom(position)
    extent_mm = MECHANISM_SIZE / base_zoom
    for data in position.curvature.values():
        if float(data["rho_mm"]) <= 1.6 * extent_mm:
            centres.append(tuple(data["center_mm"]))
        centres += [tuple(xy) for xy in data.get("path_mm") or ()]
    figure = _Figure(_position_zoom(position, centres))
    _mechanism_content(figure, position)
    _omega_arrow(figure, position)
    _curvature_content(figure, position, MECHANISM_SIZE)
    figure.place()
    lines = [f"μl = {quantity(position.mu_l, 6)} m/mm"]
    link, _pivot, omega = position.drive
    if omega:
        lines.append(f"ω₁ = {quantity(omega, 6)} rad/s (link {link})")
    if plans is not None:
        lines += [line for line in plans.scales.describe()[1:3]]
    title = f"{position.title} — position plan, φ₁ = {position.angle:g}°".lstrip(" —")
    _frame(figure, title, lines, (position.mu_l, "m", 0.25 * MECHANISM_SIZE),
           plans.flags if plans is not None else (), "position")
    return figure.svg(title)


def position_svg(position_plan: PositionPlan, *, plans: Plans | None = None) -> str:
    """The mechanism at μl as SVG text (``plans`` adds the plans' scales and flags)."""
    return position_drawing(position_plan, plans=plans).svg


# -- the rotated velocity plan --------------------------------------------------------------------
def lever_drawing(plans: Plans) -> Drawing:
    """The velocity plan turned 90° onto the faint mechanism, pole p at the drive's pivot."""
    position, plan = plans.position, plans.velocity
    rotated = plans.rotated_velocity_plan()
    figure = _Figure(_position_zoom(position, list(rotated.values())))
    _mechanism_content(figure, position, faint=True)
    _plan_content(figure, rotated, plan.steps, plan.pole, rotate_deg=-90.0)
    figure.place()
    lines = [f"μl = {quantity(position.mu_l, 6)} m/mm",
             f"μv = {quantity(plan.scale, 6)} {plan.unit}",
             f"the velocity plan turned 90° clockwise, pole {plan.pole} at "
             f"{_sans_name(position.drive[1])} (Zhukovsky's lever)"]
    title = (f"{position.title} — rotated velocity plan, φ₁ = {position.angle:g}°"
             .lstrip(" —"))
    _frame(figure, title, lines, (plan.scale, _unit_of(plan.unit), 0.25 * MECHANISM_SIZE),
           plan.flags, "velocity")
    return figure.svg(title)


def lever_svg(plans: Plans) -> str:
    """The rotated velocity plan on the mechanism as SVG text."""
    return lever_drawing(plans).svg


def plan_files(plans: Plans, forces: Any = None) -> dict[str, str]:
    """Every drawing of one crank angle: ``{"position.svg": …, "velocity.svg": …,
    "acceleration.svg": … (if drawn), "lever.svg": …}`` plus the force drawings if
    ``forces`` is given."""
    files = {"position.svg": position_svg(plans.position, plans=plans),
             "velocity.svg": plan_svg(plans.velocity)}
    if plans.acceleration is not None:
        files["acceleration.svg"] = plan_svg(plans.acceleration)
    files["lever.svg"] = lever_svg(plans)
    if forces is not None:
        from .force_svg import force_files

        files.update(force_files(forces, plans))
    return files
