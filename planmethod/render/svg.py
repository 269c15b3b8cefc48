"""SVG drawings of the plans, drawn from the plan data alone on the one
:class:`~planmethod.render.canvas.Canvas`.

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
* :func:`plan_content`, :func:`plan_legend`, :func:`frame` — the pieces other figures reuse
  (a force polygon is drawn as a plan; every figure has the same frame).

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
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from ..vocabulary import PlanKind
from .canvas import (
    Canvas,
    Drawing,
    Point,
    arrowhead,
    difference,
    fit_zoom,
    page_direction,
    scale_bar,
    translate,
    unit_vector,
    vector_length,
)
from .labels import RunKind, label_runs, merge_runs
from .style import (
    FAINT,
    FLAG,
    GROUND,
    INK,
    LEGEND_ORDER,
    LINK_FILL,
    SMALL_SIZE,
    STYLES,
    TEXT_SIZE,
    TITLE_SIZE,
    num,
    quantity,
)

if TYPE_CHECKING:
    from ..plans import Plan, Plans, PositionPlan, Step

__all__ = [
    "Drawing",
    "dense_regions",
    "frame",
    "lever_drawing",
    "lever_svg",
    "mechanism_content",
    "plan_content",
    "plan_drawing",
    "plan_legend",
    "plan_svg",
    "position_drawing",
    "position_svg",
    "position_zoom",
    "turning_arrow",
]

#: the longest side of a plan's points is drawn this long (px); a scale bar keeps it honest
PLAN_SIZE = 440.0
#: the longest side of the mechanism is drawn this long (px)
MECHANISM_SIZE = 600.0
#: points closer than this on the page (px) are one point, and their labels are merged
COINCIDENT = 1.0
_SYMBOLS = {"velocity": "μv", "acceleration": "μa", "force": "μF"}

#: one element a line (diff-friendly), never inside a <text>: its tspans stay together
_ONE_PER_LINE = re.compile(r"><(/?g\b|line\b|polygon\b|polyline\b|circle\b|text\b|rect\b|"
                           r"title\b|defs\b|/svg\b)")


# -- geometry helpers -----------------------------------------------------------------------------
def _unit_of(unit: str) -> str:
    """The unit a plan's segment stands for: ``(m/s)/mm`` → ``m/s``."""
    if unit.endswith("/mm"):
        unit = unit[:-3].strip()
        if unit.startswith("(") and unit.endswith(")"):
            unit = unit[1:-1]
    return unit


def _clusters(names, where: Mapping[str, Point]) -> list[list[str]]:
    """Names grouped by coincidence on the page (within ``COINCIDENT`` px of a group's
    first member), in the order of their first members."""
    groups: list[list[str]] = []
    for name in names:
        for group in groups:
            if vector_length(difference(where[name], where[group[0]])) < COINCIDENT:
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


# -- plans ----------------------------------------------------------------------------------------
def _is_image(label: str, pole: str) -> bool:
    """A plan point that is the image of a mechanism point (not n_…, k_… or the pole)."""
    return "_" not in label and label != pole


def _order_key(label: str, pole: str, order: Mapping[str, int]) -> tuple[int, int]:
    return (0 if label == pole else 1, order[label])


def plan_content(figure: Canvas, points_mm: Mapping[str, Sequence[float]],
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
                                      and vector_length(difference(where[label], origin)) >= 0.5}
    result_keys = {(_snap(origin), _snap(where[label])) for label in results}
    drawn = set(result_keys)
    images: dict[str, list[str]] = {}      # link → plan points of its image
    fixed: dict[str, int] = {}             # label → the step that fixes its point (playback)
    for step in steps:
        if step.end and step.end not in fixed and step.action != "read":
            fixed[step.end] = step.number

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
            direction = page_direction(step.direction_deg + rotate_deg)
            far = LineString([translate(through, direction, -reach),
                              translate(through, direction, reach)])
            piece = far.intersection(clip)
            if piece.is_empty:
                continue
            (ax, ay), (bx, by) = piece.coords[0], piece.coords[-1]
            style = STYLES.get(step.component or "", STYLES["construction"])
            figure.line((ax, ay), (bx, by), color=style.color, width=0.8, dash="5,4",
                        layer="construction", css="construction",
                        data={"data-step": str(step.number)})
            # the legend explains each colour of line drawn: "line of the … component"
            figure.used.add(f"construction:{step.component if step.component in STYLES else ''}")
        elif step.action == "intersect" and step.end in where:
            for number in step.lines or ():
                line = by_number.get(number)
                if line is not None and line.start in where:
                    component_arrow(line.start, step.end, line.component or "relative",
                                    step.number)
            if step.flagged:
                figure.circle(where[step.end], 11.0, fill="none", stroke=FLAG, width=1.6,
                              layer="marks", area=False, css="flagged")
                figure.request((f"flag:{step.end}",), where[step.end],
                               ((f"{step.angle_deg:.2g}°", RunKind.SEP),), size=SMALL_SIZE,
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
            if vector_length(difference(start, foot)) >= 0.5:
                figure.line(start, foot, color=style.color, width=style.width,
                            dash=style.dash, layer="similarity", css="projection",
                            data={"data-step": str(step.number)})
                figure.used.add("projection")
                _right_angle(figure, foot, start, origin, step.number)
            component_arrow(pole, step.end, "normal", step.number)
    for link, members in images.items():
        members = list(dict.fromkeys(members))
        known = [fixed[label] for label in members if label in fixed]
        if _link_image(figure, [where[label] for label in members], link,
                       max(known) if known else None):
            figure.used.add("similarity")
    for label, number in results.items():
        number = number if number is not None else fixed.get(label)   # found, not laid off
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


def _link_image(figure: Canvas, points: Sequence[Point], link: str,
                step: int | None = None) -> bool:
    """The image of a link on a plan (similarity rule): a segment through its images, or a
    light polygon when they do not lie on one line, shown in playback from ``step`` (the
    step that fixes the last of its points). False if it shrinks to a point."""
    data = {"data-step": str(step)} if step is not None else None
    unique = list(dict.fromkeys((round(x, 2), round(y, 2)) for x, y in points))
    if len(unique) < 2:
        return False
    first, second = _extremes(unique)
    span = vector_length(difference(first, second))
    if span < 0.5:
        return False
    style = STYLES["similarity"]
    hull = _hull(unique)
    if len(hull) >= 3 and _area(hull) > 1.5 * span:
        figure.polyline(hull, color=style.color, width=style.width, layer="similarity",
                        fill="#ececec", closed=True, css=f"image {link}", data=data)
    else:
        figure.line(first, second, color=style.color, width=style.width, layer="similarity",
                    css=f"image {link}", data=data)
    return True


def _right_angle(figure: Canvas, corner: Point, first: Point, second: Point,
                 step: int | None = None) -> None:
    """A small right-angle mark at ``corner`` between the directions to two points."""
    a, b = difference(first, corner), difference(second, corner)
    if vector_length(a) < 12 or vector_length(b) < 12:
        return
    u, v = unit_vector(a), unit_vector(b)
    size = 6.0
    points = [translate(corner, u, size), translate(translate(corner, u, size), v, size),
              translate(corner, v, size)]
    figure.polyline(points, color=STYLES["projection"].color, width=0.7, layer="similarity",
                    data={"data-step": str(step)} if step is not None else None,
                    obstacle=False)


def plan_legend(figure: Canvas, at: Point, kind: str) -> float:
    """The legend of the styles a figure used, top-left at ``at``: each arrow style drawn, and
    for each colour of construction line drawn, a row saying whose direction it carries.
    Returns the y (px) below its last row (``at``'s y when nothing is listed)."""
    x, y = at
    lines = sorted(key.partition(":")[2] for key in figure.used
                   if key.startswith("construction:"))
    order = [(key, "") for key in LEGEND_ORDER if key in figure.used and key != "construction"]
    at_lines = next((index for index, (key, _) in enumerate(order)
                     if key in ("similarity", "projection")), len(order))
    order[at_lines:at_lines] = [("construction", component) for component in
                                sorted(lines, key=lambda c: LEGEND_ORDER.index(c)
                                       if c in LEGEND_ORDER else len(LEGEND_ORDER))]
    if "flagged" in figure.used:
        order.append(("flagged", ""))
    if not order:
        return y
    figure.text((x, y), "Legend", size=TEXT_SIZE, bold=True, css="legend", area=False)
    y += 8
    for key, component in order:
        y += 20
        if key == "flagged":
            figure.circle((x + 17, y - 4), 7.0, fill="none", stroke=FLAG, width=1.6,
                          layer="text", area=False)
            text = "intersection at a small angle (flagged)"
        elif key == "construction":
            style = STYLES[key]
            colour = STYLES[component].color if component else style.color
            figure.line((x, y - 4), (x + 34, y - 4), color=colour, width=0.8,
                        dash=style.dash, layer="text", obstacle=False)
            if component:
                own = STYLES[component]
                name = own.legend_velocity if kind == PlanKind.VELOCITY else own.legend_acceleration
                text = f"construction line: direction of the {name}"
            else:
                text = "construction line"
        elif key in ("similarity", "projection"):
            style = STYLES[key]
            figure.line((x, y - 4), (x + 34, y - 4), color=style.color,
                        width=max(style.width, 0.9), dash=style.dash, layer="text",
                        obstacle=False)
            text = style.legend_velocity if kind == PlanKind.VELOCITY else style.legend_acceleration
        else:
            style = STYLES[key]
            figure.arrow((x, y - 4), (x + 34, y - 4), key, layer="text")
            figure.obstacle_lines.pop()
            text = style.legend_velocity if kind == PlanKind.VELOCITY else style.legend_acceleration
        figure.text((x + 44, y), text, size=SMALL_SIZE, css="legend", area=False)
    return y


def frame(figure: Canvas, title: str, scale_lines: Sequence[str], bar: tuple | None,
           flags: Sequence[str], kind: str) -> None:
    """Title above, legend at the right, scales, scale bar and flags below the content."""
    x0, y0, x1, y1 = figure.extent
    plan_legend(figure, (x1 + 34, y0 + 4), kind)
    x0, y0, x1, y1 = figure.extent
    figure.text((x0, y0 - 16), title, size=TITLE_SIZE, bold=True, css="title", area=False)
    y = y1 + 26
    for line in scale_lines:
        figure.text((x0, y), line, size=TEXT_SIZE, css="scale", area=False)
        y += 19
    if bar is not None:
        scale, unit, target = bar
        scale_bar(figure, (x0 + 8, y + 2), scale, unit, target)
        y += 40
    for flag in flags:
        figure.text((x0, y), "! " + flag, size=SMALL_SIZE, color=FLAG, css="flag", area=False)
        y += 17


#: points of a plan nearer than this (px) to a neighbour crowd each other: three or more such
#: (distinct) points make a region that gets an enlarged detail
DENSE_PX = 16.0
#: the longest side of a detail inset (px), and the least and most enlargement worth drawing
DETAIL_SIZE = 300.0
DETAIL_ZOOM = (2.5, 12.0)


def dense_regions(where: Mapping[str, Point], *, gap: float = DENSE_PX,
                  least: int = 3) -> list[tuple[float, float, float, float]]:
    """Boxes (x0, y0, x1, y1, page px) round the groups of at least ``least`` distinct points
    (coincident ones count once) each within ``gap`` of another of the group — the regions of
    a plan too dense to read, largest group first.

    Examples
    --------
    >>> dense_regions({"a": (0, 0), "b": (5, 0), "c": (5, 6), "d": (200, 0)})
    [(0.0, 0.0, 5.0, 6.0)]
    """
    spots: list[Point] = []
    for xy in where.values():
        if all(vector_length(difference(xy, other)) >= COINCIDENT for other in spots):
            spots.append((float(xy[0]), float(xy[1])))
    group = list(range(len(spots)))

    def root(index: int) -> int:
        while group[index] != index:
            group[index] = group[group[index]]
            index = group[index]
        return index

    for i, first in enumerate(spots):
        for j in range(i + 1, len(spots)):
            if vector_length(difference(first, spots[j])) < gap:
                group[root(i)] = root(j)
    members: dict[int, list[Point]] = {}
    for index, xy in enumerate(spots):
        members.setdefault(root(index), []).append(xy)
    found = [points for points in members.values() if len(points) >= least]
    found.sort(key=lambda points: (-len(points), points[0]))
    return [(min(p[0] for p in points), min(p[1] for p in points),
             max(p[0] for p in points), max(p[1] for p in points)) for points in found]


def _detail_regions(figure: Canvas, plan: Plan) -> list[tuple[str, tuple, float]]:
    """The plan's dense regions worth an enlarged detail: (letter, box in page px,
    enlargement), each marked on the plan with a frame and its letter (placed with the
    labels: call before :meth:`Canvas.place`)."""
    where = {label: figure.px(xy) for label, xy in plan.points_mm.items()}
    out = []
    for x0, y0, x1, y1 in dense_regions(where)[:2]:
        margin = max(10.0, 0.2 * max(x1 - x0, y1 - y0))
        box = (x0 - margin, y0 - margin, x1 + margin, y1 + margin)
        zoom = min(DETAIL_SIZE / max(box[2] - box[0], box[3] - box[1]), DETAIL_ZOOM[1])
        if zoom < DETAIL_ZOOM[0]:
            continue
        letter = "ABCD"[len(out)]
        figure.rectangle((box[0], box[1]), (box[2] - box[0], box[3] - box[1]), fill="none",
                         stroke=INK, width=0.8, layer="marks", css="detail region")
        figure.request((f"detail:{letter}",), (box[2], box[1]), ((letter, RunKind.SEP),),
                       mark=0.0)
        out.append((letter, box, float(math.floor(zoom))))     # a whole enlargement: ×6
    return out


def _detail_insets(figure: Canvas, plan: Plan, regions) -> list[str]:
    """Each marked region drawn again, enlarged, below the plan: the drawing clipped to the
    region, the labels of the points inside it kept whole. Returns the lines that say so."""
    lines = []
    x = figure.extent[0]
    top = figure.extent[3] + 30.0
    for letter, (x0, y0, x1, y1), zoom in regions:
        detail = Canvas(figure.zoom * zoom)
        plan_content(detail, plan.points_mm, plan.steps, plan.pole)
        reach = 60.0               # labels are placed for the points in and near the region
        detail.requests = [request for request in detail.requests
                           if x0 * zoom - reach <= request.anchor[0] <= x1 * zoom + reach
                           and y0 * zoom - reach <= request.anchor[1] <= y1 * zoom + reach]
        detail.place()
        width, height = (x1 - x0) * zoom, (y1 - y0) * zoom
        inside = {" ".join(label.points) for label in detail.labels
                  if x0 * zoom <= label.anchor[0] <= x1 * zoom
                  and y0 * zoom <= label.anchor[1] <= y1 * zoom}
        ident = f"detail-{plan.kind}-{letter}"
        figure.define("clipPath", {"id": ident}, [
            ("rect", {"x": num(x0 * zoom), "y": num(y0 * zoom), "width": num(width),
                      "height": num(height)}, [])])
        drawing = [("g", {"class": name}, items) for name, items in detail.layers.items()
                   if items and name not in ("labels", "leaders")]
        texts = [item for item in detail.layers["labels"]
                 if item[1].get("data-points") in inside]
        leaders = [item for item in detail.layers["leaders"]
                   if x0 * zoom <= float(item[1]["x1"]) <= x1 * zoom
                   and y0 * zoom <= float(item[1]["y1"]) <= y1 * zoom]
        move = f"translate({num(x - x0 * zoom)},{num(top - y0 * zoom)})"
        figure.add("points", "g", {"class": "detail", "clip-path": f"url(#{ident})",
                                   "transform": move}, drawing)
        figure.add("labels", "g", {"class": "detail labels", "transform": move},
                   [("g", {"class": "leaders"}, leaders), ("g", {"class": "labels"}, texts)])
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


def plan_drawing(plan: Plan, *, details: bool = True) -> Drawing:
    """A velocity or acceleration plan as an SVG :class:`Drawing` (see the module docstring);
    with ``details``, a region too dense to read is drawn again, enlarged, below the plan."""
    figure = Canvas(fit_zoom(list(plan.points_mm.values()), PLAN_SIZE))
    plan_content(figure, plan.points_mm, plan.steps, plan.pole)
    regions = _detail_regions(figure, plan) if details else []
    figure.place()
    details = _detail_insets(figure, plan, regions)
    symbol = _SYMBOLS.get(plan.kind, "μ")
    lines = [f"{symbol} = {quantity(plan.scale, 6)} {plan.unit}"]
    if plan.precision_mm:
        lines.append(f"drafting precision {plan.precision_mm:g} mm")
    lines += details
    frame(figure, plan.title or f"{plan.kind} plan", lines,
           (plan.scale, _unit_of(plan.unit), 0.3 * PLAN_SIZE), plan.flags, plan.kind)
    return figure.svg(plan.title or f"{plan.kind} plan")


def plan_svg(plan: Plan, *, details: bool = True) -> str:
    """A velocity or acceleration plan as SVG text, drawn from the plan's data alone."""
    return plan_drawing(plan, details=details).svg


# -- the mechanism --------------------------------------------------------------------------------
def mechanism_content(figure: Canvas, position: PositionPlan, *, faint: bool = False) -> None:
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
        u = page_direction(slide["direction_deg"])
        n = (-u[1], u[0])
        at = where[point]
        s = (at[0] - through[0]) * u[0] + (at[1] - through[1]) * u[1]
        if slide.get("along") == "frame":
            low, high = min(0.0, s) - block_w, max(0.0, s) + block_w
        else:                   # on a moving guide: from its mark to just beyond the block
            low, high = (0.0, s + block_w) if s >= 0 else (s - block_w, 0.0)
        axis = [translate(through, u, low), translate(through, u, high)]
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
            base = translate(at, away, block_h / 2)
            ends = [translate(base, u, -1.7 * block_w), translate(base, u, 1.7 * block_w)]
            _hatch(figure, ends[0], ends[1], away, ink)

    # links
    for name, points in moving.items():
        placed = [where[p] for p in points if p in where]
        unique = list(dict.fromkeys((round(x, 3), round(y, 3)) for x, y in placed))
        if len(unique) < 2:
            continue
        hull = _hull(unique)
        if len(hull) >= 3 and _area(hull) > 2.0 * max(
                vector_length(difference(a, b)) for a in unique for b in unique):
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
        u = page_direction(slide["direction_deg"])
        n = (-u[1], u[0])
        at = where[point]
        corners = [translate(translate(at, u, sx * block_w / 2), n, sy * block_h / 2)
                   for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        figure.polyline(corners, color=ink, width=1.8, layer="links", fill="#ffffff",
                        closed=True, css=f"slider {slide.get('link', '')}")

    # fixed pivots with the hatched ground
    for pivot in position.pivots:
        if pivot not in where:
            continue
        at = where[pivot]
        spokes = [unit_vector(difference(where[other], at)) for name, points in moving.items()
                  if pivot in points for other in points if other != pivot and other in where]
        away = _support_direction(spokes)
        n = (-away[1], away[0])
        base = translate(at, away, 18.0)
        figure.polyline([at, translate(base, n, 9.0), translate(base, n, -9.0)], color=ink,
                        width=1.4, layer="ground", fill="#ffffff", closed=True, css="support")
        _hatch(figure, translate(base, n, -16.0), translate(base, n, 16.0), away, ink)

    # pairs and points
    for name, at in where.items():
        if count.get(name, 0) >= 2:
            figure.circle(at, 4.5, fill="#ffffff", stroke=ink, width=1.5, layer="points",
                          css="pair")
        elif count.get(name, 0) == 1 and name not in links.get("frame", ()):
            figure.circle(at, 2.6, fill=ink, layer="points", css="point")
        else:
            figure.line(translate(at, (-4, -4)), translate(at, (4, 4)), color=ink, width=1.0,
                        layer="points", obstacle=False)
            figure.line(translate(at, (-4, 4)), translate(at, (4, -4)), color=ink, width=1.0,
                        layer="points", obstacle=False)
    for members in _clusters(position.points_mm, where):
        figure.request(tuple(members), where[members[0]],
                       merge_runs(label_runs(name) for name in members), mark=4.5,
                       css="faint" if faint else "label")


def _hatch(figure: Canvas, start: Point, end: Point, away: Point, ink: str) -> None:
    """A ground line from ``start`` to ``end`` hatched on the side ``away``."""
    figure.line(start, end, color=GROUND if ink == INK else ink, width=1.6, layer="ground",
                css="ground")
    u = unit_vector(difference(end, start))
    length = vector_length(difference(end, start))
    count = max(2, int(length // 7))
    for index in range(count + 1):
        foot = translate(start, u, index * length / count)
        tip = translate(translate(foot, away, 6.0), u, -5.0)
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
            if vector_length(difference(a, b)) > vector_length(difference(*best)):
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


def turning_arrow(figure: Canvas, centre_mm: Sequence[float], radius_px: float,
                  start_rad: float, sense: float, color: str, key: str,
                  runs: tuple, *, css: str = "omega", sweep_deg: float = 70.0) -> None:
    """A curved arrow round ``centre_mm`` (an angular velocity, a moment): ``radius_px`` on the
    page, from ``start_rad`` (counter-clockwise from +x) through ``sweep_deg`` in the
    ``sense`` (+1 counter-clockwise), labelled ``runs`` at its middle."""
    radius = radius_px / figure.zoom
    count = 21
    angles = [start_rad + sense * math.radians(22 + sweep_deg * k / (count - 1))
              for k in range(count)]
    arc = [figure.px((centre_mm[0] + radius * math.cos(a), centre_mm[1] + radius * math.sin(a)))
           for a in angles]
    tip = arc[-1]
    direction = unit_vector(difference(tip, arc[-2]))
    figure.polyline([*arc[:-1], translate(tip, direction, -7.0)], color=color, width=1.4,
                    layer="marks", css=css)
    arrowhead(figure, tip, direction, 10.0, color, "marks")
    figure.request((key,), arc[len(arc) // 2], runs, mark=1.0)


def _omega_arrow(figure: Canvas, position: PositionPlan, ink: str = INK) -> None:
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
    turning_arrow(figure, centre_mm, min(max(0.42 * crank_px, 20.0), 44.0), start,
                  1.0 if omega > 0 else -1.0, ink, "ω1",
                  (("ω", RunKind.MAIN), ("1", RunKind.UPRIGHT)))


def _curvature_content(figure: Canvas, position: PositionPlan, extent_px: float) -> None:
    """Tangent ττ, normal ηη, centre of curvature and ρ of every point whose ρ was read."""
    for name, data in position.curvature.items():
        if name not in position.points_mm:
            continue
        at = figure.px(position.points_mm[name])
        tangent = page_direction(float(data["tangent_deg"]))
        normal = page_direction(float(data["normal_deg"]))
        rho_px = float(data["rho_mm"]) * figure.zoom
        color = "#8a5a00"
        if data.get("path_mm"):
            figure.polyline([figure.px(xy) for xy in data["path_mm"]], color=color, width=0.8,
                            dash="2,3", closed=True, obstacle=False, css="path")
        half = 60.0
        ends = (translate(at, tangent, -half), translate(at, tangent, half))
        figure.line(*ends, color=color, width=1.0, dash="10,3,2,3", layer="marks", css="tangent")
        for end in ends:
            figure.request(("τ",), end, (("τ", RunKind.MAIN),), size=TEXT_SIZE, mark=0.0)
        on_sheet = rho_px <= 1.6 * extent_px
        shown = rho_px if on_sheet else 0.5 * extent_px
        ends = (translate(at, normal, -40.0), translate(at, normal, shown + 24.0))
        figure.line(*ends, color=color, width=1.0, dash="10,3,2,3", layer="marks", css="normal")
        for end in ends:
            figure.request(("η",), end, (("η", RunKind.MAIN),), size=TEXT_SIZE, mark=0.0)
        rho_m = float(data["rho_mm"]) * position.mu_l
        text = (("ρ", RunKind.MAIN), (name, RunKind.SUB), (f" = {quantity(rho_m)} m", RunKind.SEP))
        if on_sheet:
            centre = translate(at, normal, rho_px)
            figure.arrow(at, centre, "normal", layer="marks", color=color, css="rho")
            figure.circle(centre, 3.0, fill="#ffffff", stroke=color, width=1.4,
                          layer="points", css="centre")
            figure.request((f"O_{name}",), centre, (("O", RunKind.MAIN), (name, RunKind.SUB)),
                           mark=3.0)
        else:
            text = (*text[:-1], (f" = {quantity(rho_m)} m (centre off the sheet)", RunKind.SEP))
        figure.request((f"rho_{name}",), translate(at, normal, 0.5 * shown), text, size=TEXT_SIZE,
                       mark=1.0)


def position_zoom(position: PositionPlan, extra: Sequence[Sequence[float]] = ()) -> float:
    points = list(position.points_mm.values()) + [tuple(s["through_mm"])
                                                   for s in position.slides] + list(extra)
    return fit_zoom(points, MECHANISM_SIZE)


def position_drawing(position_plan: PositionPlan, *, plans: Plans | None = None,
                     notes: Sequence[str] = ()) -> Drawing:
    """The mechanism at μl as an SVG :class:`Drawing` (see the module docstring).

    ``notes`` are lines of text printed under the figure (a task sheet's text); a line that
    starts with two spaces is a table row and is set in a monospaced font.
    """
    position = position_plan
    centres = []
    base_zoom = position_zoom(position)
    extent_mm = MECHANISM_SIZE / base_zoom
    for data in position.curvature.values():
        if float(data["rho_mm"]) <= 1.6 * extent_mm:
            centres.append(tuple(data["center_mm"]))
        centres += [tuple(xy) for xy in data.get("path_mm") or ()]
    figure = Canvas(position_zoom(position, centres))
    mechanism_content(figure, position)
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
    frame(figure, title, lines, (position.mu_l, "m", 0.25 * MECHANISM_SIZE),
           plans.flags if plans is not None else (), PlanKind.POSITION)
    y = figure.extent[3] + 24
    for line in notes:
        if line.strip():
            figure.text((figure.extent[0], y), line, size=TEXT_SIZE, css="task", area=False,
                        monospace=line.startswith("  "))
        y += 17
    return figure.svg(title)


def position_svg(position_plan: PositionPlan, *, plans: Plans | None = None) -> str:
    """The mechanism at μl as SVG text (``plans`` adds the plans' scales and flags)."""
    return position_drawing(position_plan, plans=plans).svg


# -- the rotated velocity plan --------------------------------------------------------------------
def lever_drawing(plans: Plans) -> Drawing:
    """The velocity plan turned 90° onto the faint mechanism, pole p at the drive's pivot."""
    position, plan = plans.position, plans.velocity
    rotated = plans.rotated_velocity_plan()
    figure = Canvas(position_zoom(position, list(rotated.values())))
    mechanism_content(figure, position, faint=True)
    plan_content(figure, rotated, plan.steps, plan.pole, rotate_deg=-90.0)
    figure.place()
    lines = [f"μl = {quantity(position.mu_l, 6)} m/mm",
             f"μv = {quantity(plan.scale, 6)} {plan.unit}",
             f"the velocity plan turned 90° clockwise, pole {plan.pole} at "
             f"{_sans_name(position.drive[1])} (Zhukovsky's lever)"]
    title = (f"{position.title} — rotated velocity plan, φ₁ = {position.angle:g}°"
             .lstrip(" —"))
    frame(figure, title, lines, (plan.scale, _unit_of(plan.unit), 0.25 * MECHANISM_SIZE),
           plan.flags, PlanKind.VELOCITY)
    return figure.svg(title)


def lever_svg(plans: Plans) -> str:
    """The rotated velocity plan on the mechanism as SVG text."""
    return lever_drawing(plans).svg
