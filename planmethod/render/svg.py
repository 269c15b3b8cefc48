"""SVG drawings of the plans, drawn from the plan data alone on the one
:class:`~planmethod.render.canvas.Canvas`.

* :func:`plan_svg` — a velocity or acceleration plan: the pole, every laid-off vector as an
  arrow styled by its component (normal, tangential, Coriolis, relative), the construction lines
  thin and dashed in the colour of their component and clipped to a margin around the plan, the
  vectors found by intersecting two lines, the images of links (similarity), the projection on
  the normal of a path, the results (pole → image of each point) bold, lower-case labels placed
  clear of lines, of each other and of other points' marks, points that coincide by
  construction merged ("p ≡ a ≡ c₀"), a Coriolis point only where the term is not zero, the
  scale printed with its units and a scale bar, the title, a legend with the plan's vector
  equations beside it (:func:`vector_equations`), an enlarged detail wherever points crowd
  (:mod:`planmethod.render.details`), and every flagged intersection ringed in red with the
  angle of its lines.
* :func:`position_svg` — the mechanism at μl: links as bars (a link with three or more points
  not on one line as a filled polygon), revolute pairs as small circles, fixed pivots with the
  hatched-ground symbol, sliders as blocks on their guides, upper-case labels, μl, the crank's
  ω₁ arrow, and for each point whose curvature was read the tangent ττ, the normal ηη, the
  centre of curvature and ρ.
* :func:`lever_svg` — the velocity plan turned 90° onto the mechanism, pole p at the drive's
  pivot, the mechanism faint underneath (Zhukovsky's lever stands on it).
* :func:`plan_content`, :func:`plan_legend`, :func:`frame` — the pieces other figures reuse
  (a force polygon is drawn as a plan; every figure has the same frame).

Labels follow the course (see :mod:`planmethod.render.labels` and docs/notation.md): links by
the numbers of the exercise's notation, ``b@lever`` printed as b₃ (B of link 3), ``c@frame``
as c₀, ``n_CB`` as n with subscript CB, ``O2`` as O₂; the crank's φ and ω carry its number.
Each label's ``<text>`` and each point's mark carry the plan labels they name in
``data-points``; each arrow of a construction step carries the step's number in
``data-step``. With a :class:`~planmethod.render.steady.SteadyView` a drawing keeps the zoom
and the page of every frame of a turn.

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

import numpy as np

from ..plans.construction import is_image
from ..plans.steps import Coincide, Intersect, LayOff, Line, Similarity
from ..vectors import dot, norm, perp, unit_or_zero
from ..vocabulary import (
    PLAN_SCALES,
    SCALES,
    PlanKind,
    link_text,
    numbered,
    point_name,
    point_text,
    scale_text,
)
from ..words import Message, message
from .canvas import (
    MARGIN,
    Canvas,
    Point,
    SvgFigure,
    arrowhead,
    fit_zoom,
    page_direction,
    page_point,
    scale_bar,
    shown_text,
)
from .details import (
    FROM_POLE,
    ON_THE_DRAWING,
    column_and_details,
    crowded_points,
    detail_regions,
    laid_out,
    one_spot,
    within_page,
)
from .labels import RunKind, label_runs, merge_runs
from .plan_words import flag_message, label_text, plan_title, scale_lines, vector_text
from .steady import SteadyView
from .style import (
    FAINT,
    FLAG,
    GROUND,
    INK,
    LEGEND_ORDER,
    LINK_FILL,
    MECHANISM_SIZE,
    PLAN_SIZE,
    SANS,
    SANS_BOLD,
    SMALL_SIZE,
    STYLES,
    TEXT_SIZE,
    TITLE_SIZE,
    text_width,
)

if TYPE_CHECKING:
    from ..plans import Plan, Plans, PositionPlan, Step

__all__ = [
    "SAME_POINT_MM",
    "SvgFigure",
    "coincident_groups",
    "crank_number",
    "frame",
    "legend_column",
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
    "vector_equations",
]

#: segments closer than this on the page (px) are one segment, drawn once
COINCIDENT = 1.0
#: points closer than this on the drawing (mm) coincide by construction: one mark, one merged
#: label (p ≡ a ≡ c₀); distinct points, however near, keep their own (a detail shows them)
SAME_POINT_MM = 1e-6


# -- geometry helpers -----------------------------------------------------------------------------
def _distances(points: Sequence[Point]) -> np.ndarray:
    """The page distance of every two points (n × n)."""
    xy = np.asarray(points, dtype=float).reshape(-1, 2)
    return norm(xy[:, None, :] - xy[None, :, :])


def coincident_groups(names, where: Mapping[str, Point], tolerance: float
                      ) -> list[list[str]]:
    """Names grouped by coincidence on the page (within ``tolerance`` px of a group's
    first member), in the order of their first members."""
    names = list(names)
    apart = _distances([where[name] for name in names]) >= tolerance
    groups: list[list[int]] = []
    for index in range(len(names)):
        for group in groups:
            if not apart[index, group[0]]:
                group.append(index)
                break
        else:
            groups.append([index])
    return [[names[index] for index in group] for group in groups]


def _snap(xy: Point) -> tuple[int, int]:
    return (round(xy[0] / COINCIDENT), round(xy[1] / COINCIDENT))


# -- plans ----------------------------------------------------------------------------------------
class _PlanPage:
    """One plan being drawn into a figure: where its points are on the page, which segments
    are drawn already, the images of links collected from the steps, and what each kind of
    step draws (:data:`_STEP_DRAWERS`)."""

    def __init__(self, figure: Canvas, points_mm: Mapping[str, Sequence[float]],
                 steps: Sequence[Step], pole: str, rotate_deg: float,
                 numbers: Mapping[str, int] | None) -> None:
        from shapely.geometry import box

        self.figure, self.pole, self.rotate_deg = figure, pole, rotate_deg
        self.points_mm, self.numbers = points_mm, numbers
        #: Coriolis points of a zero Coriolis term: neither drawn nor named
        self.hidden = {step.end for step in steps
                       if isinstance(step, LayOff | Coincide) and step.component == "coriolis"
                       and step.start in points_mm and step.end in points_mm
                       and float(norm(np.subtract(points_mm[step.end],
                                                  points_mm[step.start]))) <= SAME_POINT_MM}
        self.where = where = {label: figure.px(xy) for label, xy in points_mm.items()}
        self.by_number = {step.number: step for step in steps}
        self.origin = origin = where[pole]
        xs = [p[0] for p in where.values()]
        ys = [p[1] for p in where.values()]
        pad = max(0.16 * max(max(xs) - min(xs), max(ys) - min(ys)), 40.0)
        self.clip = box(min(xs) - pad, min(ys) - pad, max(xs) + pad, max(ys) + pad)
        self.reach = 4 * (self.clip.length + 1)
        #: pole → image arrows (results), by label: the step that lays it off, if one does
        self.results: dict[str, int | None] = {
            label: None for label in points_mm
            if is_image(label, pole) and float(norm(where[label] - origin)) >= 0.5}
        self.drawn = {(_snap(origin), _snap(where[label])) for label in self.results}
        self.images: dict[str, list[str]] = {}     # link → plan points of its image
        #: label → the step that fixes its point (playback)
        self.fixed: dict[str, int] = {}
        for step in steps:
            if step.end and step.end not in self.fixed and step.action != "read":
                self.fixed[step.end] = step.number

    def component_arrow(self, start: str, end: str, component: str, step: int | None,
                        always: bool = False) -> None:
        """An arrow unless the same segment is drawn already (a laid-off vector always)."""
        key = (_snap(self.where[start]), _snap(self.where[end]))
        if key in self.drawn and not always:
            return
        self.drawn.add(key)
        if self.figure.arrow(self.where[start], self.where[end], component, layer="components",
                             step=step):
            self.figure.used.add(component)

    # one method per kind of step
    def lay_off(self, step: Step) -> None:
        if step.start not in self.where or step.end not in self.where:
            return
        if step.start == self.pole and step.end in self.results:
            self.results[step.end] = step.number
        else:
            self.component_arrow(step.start, step.end, step.component or "relative",
                                 step.number, always=True)

    def line(self, step: Step) -> None:
        from shapely.geometry import LineString

        if step.start not in self.where:
            return
        through = self.where[step.start]
        direction = page_direction(step.direction_deg + self.rotate_deg)
        far = LineString([through - self.reach * direction, through + self.reach * direction])
        piece = far.intersection(self.clip)
        if piece.is_empty:
            return
        (ax, ay), (bx, by) = piece.coords[0], piece.coords[-1]
        style = STYLES.get(step.component or "", STYLES["construction"])
        self.figure.line((ax, ay), (bx, by), color=style.color, width=0.8, dash="5,4",
                         layer="construction", css="construction",
                         data={"data-step": str(step.number)})
        # the legend explains each colour of line drawn: "line of the … component"
        self.figure.used.add(
            f"construction:{step.component if step.component in STYLES else ''}")

    def intersect(self, step: Step) -> None:
        if step.end not in self.where:
            return
        for number in step.lines or ():
            line = self.by_number.get(number)
            if line is not None and line.start in self.where:
                self.component_arrow(line.start, step.end, line.component or "relative",
                                     step.number)
        if step.flagged:
            figure, at = self.figure, self.where[step.end]
            figure.circle(at, 11.0, fill="none", stroke=FLAG, width=1.6, layer="marks",
                          area=False, css="flagged")
            angle = shown_text(message("{angle:.2g}°", angle=step.angle_deg))
            figure.request((f"flag:{step.end}",), at, ((angle, RunKind.SEP),),
                           size=SMALL_SIZE, mark=11.0, css="flag")
            figure.used.add("flagged")

    def similarity(self, step: Similarity) -> None:
        if step.link:
            members = self.images.setdefault(step.link, [])
            members += [label for label in (*step.references, step.end) if label in self.where]

    def read(self, step: Step) -> None:
        if step.quantity and step.quantity.startswith(("omega_", "epsilon_")):
            link = step.quantity.partition("_")[2]
            self.images.setdefault(link, []).extend(
                label for label in (step.start, step.end)
                if label in self.where and is_image(label, self.pole))

    def project(self, step: Step) -> None:
        if step.start not in self.where or step.end not in self.where:
            return
        start, foot = self.where[step.start], self.where[step.end]
        style = STYLES["projection"]
        if float(norm(start - foot)) >= 0.5:
            self.figure.line(start, foot, color=style.color, width=style.width,
                             dash=style.dash, layer="similarity", css="projection",
                             data={"data-step": str(step.number)})
            self.figure.used.add("projection")
            _right_angle(self.figure, foot, start, self.origin, step.number)
        self.component_arrow(self.pole, step.end, "normal", step.number)

    # after the steps
    def link_images(self) -> None:
        for link, members in self.images.items():
            members = list(dict.fromkeys(members))
            known = [self.fixed[label] for label in members if label in self.fixed]
            if _link_image(self.figure, [self.where[label] for label in members], link,
                           max(known) if known else None):
                self.figure.used.add("similarity")

    def result_arrows(self) -> None:
        for label, number in self.results.items():
            number = number if number is not None else self.fixed.get(label)   # found
            if self.figure.arrow(self.origin, self.where[label], "result", layer="results",
                                 step=number):
                self.figure.used.add("result")

    def points(self) -> None:
        """Points and labels: coincident points share one mark and one merged label (p ≡ a);
        points the drawing cannot tell apart (nearer than its resolution,
        :func:`~planmethod.render.details.one_spot`) share one mark, their labels joined by
        ≈."""
        order = {label: index for index, label in enumerate(self.points_mm)}
        first = {label: (0 if label == self.pole else 1, order[label]) for label in order}
        shown = [label for label in self.points_mm if label not in self.hidden]
        exact = SAME_POINT_MM * self.figure.zoom
        for spot in coincident_groups(shown, self.where, max(one_spot(self.where), exact)):
            groups = [sorted(members, key=first.get)
                      for members in coincident_groups(spot, self.where, exact)]
            groups.sort(key=lambda members: first[members[0]])
            members = [label for members in groups for label in members]
            centre = self.where[members[0]]
            is_pole = members[0] == self.pole
            self.figure.circle(centre, 3.4 if is_pole else 2.4, fill=INK, layer="points",
                               css="pole" if is_pole else "point", points=members)
            self.figure.request(tuple(members), centre, merge_runs(
                (merge_runs(label_runs(label, self.numbers) for label in members)
                 for members in groups), sign="≈"), mark=3.4)


#: what each kind of construction step draws (a step of another kind draws nothing)
_STEP_DRAWERS = {"lay_off": _PlanPage.lay_off, "line": _PlanPage.line,
                 "intersect": _PlanPage.intersect, "similarity": _PlanPage.similarity,
                 "read": _PlanPage.read, "project": _PlanPage.project}


def plan_content(figure: Canvas, points_mm: Mapping[str, Sequence[float]],
                 steps: Sequence[Step], pole: str, rotate_deg: float = 0.0,
                 numbers: Mapping[str, int] | None = None) -> None:
    """Draw a plan's steps, results, points and label requests into ``figure``; ``numbers``
    (the links' numbers) name a point of a link as the course does (b₃)."""
    page = _PlanPage(figure, points_mm, steps, pole, rotate_deg, numbers)
    for step in steps:
        drawer = _STEP_DRAWERS.get(step.action)
        if drawer is not None:
            drawer(page, step)
    page.link_images()
    page.result_arrows()
    page.points()


def _link_image(figure: Canvas, points: Sequence[Point], link: str,
                step: int | None = None) -> bool:
    """The image of a link on a plan (similarity rule): a segment through its images, or a
    light polygon when they do not lie on one line, shown in playback from ``step`` (the
    step that fixes the last of its points). False if it shrinks to a point."""
    data = {"data-step": str(step)} if step is not None else None
    unique = list(dict.fromkeys((round(float(x), 2), round(float(y), 2)) for x, y in points))
    if len(unique) < 2:
        return False
    first, second = _extremes(unique)
    span = float(norm(page_point(first) - second))
    if span < 0.5:
        return False
    style = STYLES["similarity"]
    hull, area = _hull(unique)
    if len(hull) >= 3 and area > 1.5 * span:
        figure.polyline(hull, color=style.color, width=style.width, layer="similarity",
                        fill="#ececec", closed=True, css=f"image {link}", data=data)
    else:
        figure.line(first, second, color=style.color, width=style.width, layer="similarity",
                    css=f"image {link}", data=data)
    return True


def _right_angle(figure: Canvas, corner: Point, first: Point, second: Point,
                 step: int | None = None) -> None:
    """A small right-angle mark at ``corner`` between the directions to two points."""
    a, b = first - corner, second - corner
    if float(norm(a)) < 12 or float(norm(b)) < 12:
        return
    u, v = unit_or_zero(a), unit_or_zero(b)
    size = 6.0
    points = [corner + size * u, (corner + size * u) + size * v, corner + size * v]
    figure.polyline(points, color=STYLES["projection"].color, width=0.7, layer="similarity",
                    data={"data-step": str(step)} if step is not None else None,
                    obstacle=False)


def plan_legend(figure: Canvas, at: Point, kind: str) -> float:
    """The legend of the styles a figure used, top-left at ``at``: each arrow style drawn, and
    for each colour of construction line drawn, a row saying whose direction it carries.
    Returns the y (px) below its last row (``at``'s y when nothing is listed)."""
    x, y = at
    order = _legend_rows(figure.used)
    if not order:
        return y
    figure.text((x, y), message("Legend"), size=TEXT_SIZE, bold=True, css="legend",
                area=False)
    y += 8
    for key, component in order:
        y += 20
        figure.text((x + 44, y), _legend_row(figure, (x, y - 4), key, component, kind),
                    size=SMALL_SIZE, css="legend", area=False)
    return y


def _legend_rows(used: set[str]) -> list[tuple[str, str]]:
    """The rows of a legend, in :data:`LEGEND_ORDER`: (style, component of a construction
    line's colour), the construction lines before the images and projections, a flagged
    intersection last."""
    lines = sorted(key.partition(":")[2] for key in used if key.startswith("construction:"))
    order = [(key, "") for key in LEGEND_ORDER if key in used and key != "construction"]
    at_lines = next((index for index, (key, _) in enumerate(order)
                     if key in ("similarity", "projection")), len(order))
    order[at_lines:at_lines] = [("construction", component) for component in
                                sorted(lines, key=lambda c: LEGEND_ORDER.index(c)
                                       if c in LEGEND_ORDER else len(LEGEND_ORDER))]
    if "flagged" in used:
        order.append(("flagged", ""))
    return order


def _legend_row(figure: Canvas, at: Point, key: str, component: str, kind: str) -> Message:
    """A legend row's sample drawn at ``at`` (its left end, on the row's middle line), and its
    text."""
    (x, y), style = at, STYLES.get(key)
    if key == "flagged":
        figure.circle((x + 17, y), 7.0, fill="none", stroke=FLAG, width=1.6, layer="text",
                      area=False)
        return message("intersection at a small angle (flagged)")
    if key == "construction":
        colour = STYLES[component].color if component else style.color
        figure.line((x, y), (x + 34, y), color=colour, width=0.8, dash=style.dash,
                    layer="text", obstacle=False)
        if not component:
            return message("construction line")
        return message("construction line: direction of the {component}",
                       component=STYLES[component].legend(kind))
    if key in ("similarity", "projection"):
        figure.line((x, y), (x + 34, y), color=style.color, width=max(style.width, 0.9),
                    dash=style.dash, layer="text", obstacle=False)
    else:
        figure.arrow((x, y), (x + 34, y), key, layer="text", obstacle=False)
    return style.legend(kind)


def legend_column(figure: Canvas, kind: str, *, box: Sequence[float] | None = None,
                  equations: Sequence[str] = ()) -> float:
    """The column at the right of the content drawn so far (or of a fixed ``box``): the
    legend of the styles the figure used and the plan's vector ``equations``. Returns the y
    (px) under it (its top's when it is empty)."""
    _, y0, x1, _ = box if box is not None else figure.extent
    bottom = plan_legend(figure, (x1 + 34, y0 + 4), kind)
    if not equations:
        return bottom
    y = bottom + 34 if bottom > y0 + 4 else y0 + 4
    figure.text((x1 + 34, y), message("Vector equations"), size=TEXT_SIZE, bold=True,
                css="legend", area=False)
    for equation in equations:
        y += 20
        figure.text((x1 + 34, y), equation, size=TEXT_SIZE, css="equation", area=False,
                    formula=True)
    return y


def frame(figure: Canvas, title: Message | str, scale_lines: Sequence[Message | str],
          bar: tuple | None, flags: Sequence[Message | str], kind: str, *,
          box: Sequence[float] | None = None, equations: Sequence[str] = (),
          column: bool = True) -> None:
    """Title above, legend and the plan's vector ``equations`` at the right (unless drawn
    already: not ``column``, :func:`legend_column`), scales, scale bar and flags below the
    content — the content drawn so far, or a fixed ``box`` (x0, y0, x1, y1, px) that stays
    the same in every frame of a turn (:mod:`planmethod.render.steady`). The texts are
    messages (rendered as they are written) or text."""
    if column:
        legend_column(figure, kind, box=box, equations=equations)
    x0, y0, _, y1 = box if box is not None else figure.extent
    figure.text((x0, y0 - 16), title, size=TITLE_SIZE, bold=True, css="title", area=False)
    y = y1 + 26
    for line in scale_lines:
        figure.text((x0, y), line, size=TEXT_SIZE, css="scale", area=False, formula=True)
        y += 19
    if bar is not None:
        scale, unit, target = bar
        scale_bar(figure, (x0 + 8, y + 2), scale, unit, target)
        y += 40
    for flag in flags:
        figure.text((x0, y), "! " + shown_text(flag), size=SMALL_SIZE, color=FLAG, css="flag",
                    area=False)
        y += 17


def steady_page(view: SteadyView, title: Message | str, lines: int, kind: str, *,
                legend: bool = True, equations: Sequence[str] = ()
                ) -> tuple[float, float, float, float]:
    """The viewBox of a panel kept steady over a turn: its content's fixed box with room for
    the frame's furniture at every angle — the title (its angle written as wide as any), the
    widest legend the kind can have and the plan's ``equations`` beside it, ``lines`` scale
    lines, the scale bar and two flags."""
    x0, y0, x1, y1 = view.box
    if isinstance(title, Message) and "angle" in title.values:
        widest = shown_text(title.replace(angle=888.8))
    else:                                   # a title given as text: its angle found in it
        widest = re.sub(r"= -?[\d.]+°", "= 888.8°", shown_text(title))
    column = max([_legend_width(kind) if legend else 0.0]
                 + [text_width(shown_text(text), TEXT_SIZE, SANS) for text in equations])
    right = max(x1 + (34.0 + column if column else 0.0),
                x0 + text_width(widest, TITLE_SIZE, SANS_BOLD))
    top = y0 - 16.0 - TITLE_SIZE
    rows = (len(LEGEND_ORDER) + 3 if legend else 0) * 20.0 + (34.0 + 20.0 * len(equations)
                                                              if equations else 0.0)
    bottom = max(y1 + 26.0 + 19.0 * lines + 40.0 + 2 * 17.0, y0 + 20.0 + rows)
    return (x0 - MARGIN, top - MARGIN, right - x0 + 2 * MARGIN, bottom - top + 2 * MARGIN)


def _legend_width(kind: str) -> float:
    """The width (px) of the widest legend row a plan of this kind can have."""
    texts = [message("intersection at a small angle (flagged)")]
    for key in LEGEND_ORDER:
        name = STYLES[key].legend(kind)
        texts += [name, message("construction line: direction of the {component}",
                                component=name)]
    return 44.0 + max(text_width(shown_text(text), SMALL_SIZE, SANS) for text in texts)


def plan_drawing(plan: Plan, *, details: bool = True, view: SteadyView | None = None
                 ) -> SvgFigure:
    """A velocity or acceleration plan as an :class:`SvgFigure` (see the module docstring);
    with ``details``, a region too dense to read is drawn again, enlarged, below the plan;
    ``view`` keeps the zoom and the page of every frame of a turn; without it, the plan is
    drawn larger where its page would be too long for it (:func:`within_page`)."""
    if view is not None:
        return _plan_page(plan, details, view, 1.0)[1]
    return within_page(lambda growth: _plan_page(plan, details, None, growth))


def _plan_page(plan: Plan, details: bool, view: SteadyView | None, growth: float
               ) -> tuple[Canvas, SvgFigure]:
    """A plan's page (:func:`plan_drawing`) with its drawing ``growth`` times its own size:
    its canvas and the figure."""
    def content(canvas: Canvas) -> None:
        plan_content(canvas, plan.points_mm, plan.steps, plan.pole, numbers=plan.numbers)

    figure, regions = laid_out(      # a steady page holds the labels
        view.zoom if view else growth * fit_zoom(list(plan.points_mm.values()), PLAN_SIZE),
        content,
        lambda canvas: {label: canvas.px(xy) for label, xy in plan.points_mm.items()},
        details and not view, view.box if view else None)
    equations = vector_equations(plan)
    details = [] if view else column_and_details(   # the legend's column, the details
        figure, content, regions, f"detail-{plan.kind}",
        lambda _: legend_column(figure, plan.kind, equations=equations),
        crowded=[(label_text(name, plan.numbers), *plan.points_mm[name], (name,))
                 for name in crowded_points(regions)],
        title=FROM_POLE.replace(pole=plan.pole))
    scale = PLAN_SCALES[plan.kind]
    lines: list[Message | str] = [scale_text(scale, plan.scale)]   # words: vocabulary
    if plan.precision_mm:
        lines.append(message("drafting precision {precision:g} mm",
                             precision=plan.precision_mm))
    lines += details
    title = plan_title(plan)
    frame(figure, title, lines, (plan.scale, SCALES[scale].drawn, 0.3 * PLAN_SIZE),
          [flag_message(flag, plan.numbers) for flag in plan.flags], plan.kind,
          box=view.box if view else None, equations=equations, column=view is not None)
    return figure, figure.svg(title, view=steady_page(view, title, len(lines), plan.kind,
                                                      equations=equations) if view else None)


def plan_svg(plan: Plan, *, details: bool = True, view: SteadyView | None = None) -> str:
    """A velocity or acceleration plan as SVG text, drawn from the plan's data alone."""
    return plan_drawing(plan, details=details, view=view).svg


def vector_equations(plan: Plan) -> list[str]:
    """The vector equations a plan solves, as textbooks print them beside it: for each pair
    of construction lines intersected, the point's vector as the base image's vector plus the
    components laid off from it plus the line's own — ``v_C = v_B + v_CB = v_C₀ + v_CC₀``,
    ``a_B₃ = a_B + aᵏ_B₃B + aʳ_B₃B = a_O₂ + aⁿ_B₃O₂ + aᵗ_B₃O₂`` (each relative motion named
    by both its points, as the velocity equation names it). A component that is zero by
    construction (a Coriolis term on a guide that does not turn) is left out.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> from planmethod.plans import draw_plans
    >>> plans = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
    >>> vector_equations(plans.velocity), vector_equations(plans.acceleration)
    (['v_C = v_B + v_CB = v_C₀ + v_CC₀'], ['a_C = a_B + aⁿ_CB + aᵗ_CB = a_C₀ + aʳ_CC₀'])
    """
    letter = "v" if plan.kind == PlanKind.VELOCITY else "a"
    numbers = plan.numbers
    laid: dict[str, LayOff | Coincide] = {}
    for step in plan.steps:
        if isinstance(step, LayOff | Coincide) and step.end and step.end not in laid:
            laid[step.end] = step
    lines = {step.number: step for step in plan.steps if isinstance(step, Line)}

    def image(label: str) -> str:
        """The vector of a plan point's image: ``b@lever`` → v_B₃."""
        name, at, link = label.partition("@")
        return f"{letter}_{point_name(name.rstrip('′').upper() + at + link, numbers)}"

    def side(line: Line) -> str:
        terms = [vector_text(line.vector, numbers)]
        point = line.start
        while point.startswith(("n_", "k")) and "_" in point and point in laid:
            if isinstance(laid[point], LayOff):
                terms.insert(0, vector_text(laid[point].vector, numbers))
            point = laid[point].start or plan.pole
        return " + ".join([image(point), *terms])

    out = []
    for step in plan.steps:
        if isinstance(step, Intersect) and step.end and all(
                number in lines and lines[number].start for number in step.lines):
            first, second = step.lines
            out.append(f"{image(step.end)} = {side(lines[first])} = {side(lines[second])}")
    return out


# -- the mechanism --------------------------------------------------------------------------------
#: a slider block's length along its guide and its width (px)
BLOCK = (36.0, 18.0)


class _MechanismPage:
    """A position plan being drawn into a figure: where its points are on the page, and
    one method per kind of part (guides, links, slider blocks, fixed pivots, pairs)."""

    def __init__(self, figure: Canvas, position: PositionPlan, faint: bool) -> None:
        self.figure, self.position, self.faint = figure, position, faint
        self.ink = FAINT if faint else INK
        self.fill = "#f2f2f2" if faint else LINK_FILL
        self.where = {name: figure.px(xy) for name, xy in position.points_mm.items()}
        self.links = dict(position.links)
        self.moving = {name: points for name, points in self.links.items() if name != "frame"}
        self.count: dict[str, int] = {}
        for points in self.links.values():
            for point in points:
                self.count[point] = self.count.get(point, 0) + 1
        where = self.where
        self.centroid = np.array((sum(p[0] for p in where.values()) / len(where),
                                  sum(p[1] for p in where.values()) / len(where)))

    def guides(self) -> None:
        """The guide of each prismatic pair: a dash-dotted line hatched on the side away
        from the mechanism on the frame, a bar on a moving link."""
        block_w, block_h = BLOCK
        figure, ink = self.figure, self.ink
        for slide in self.position.slides:
            point = slide.get("point")
            if point not in self.where:
                continue
            through = figure.px(slide["through_mm"])
            u = page_direction(slide["direction_deg"])
            n = perp(u)
            at = self.where[point]
            s = float(dot(at - through, u))
            on_frame = slide.get("along") == "frame"
            if on_frame:
                low, high = min(0.0, s) - block_w, max(0.0, s) + block_w
            else:               # on a moving guide: from its mark to just beyond the block
                low, high = (0.0, s + block_w) if s >= 0 else (s - block_w, 0.0)
            axis = [through + low * u, through + high * u]
            if not on_frame:    # the guide is material of the moving link: a bar
                figure.line(axis[0], axis[1], color=ink, width=3.0, layer="links", cap="round",
                            css=f"guide {slide.get('along', '')}")
                continue
            figure.line(axis[0], axis[1], color=ink, width=0.7, dash="14,3,2,3",
                        layer="ground", css="guide")
            lean = float(dot(self.centroid - at, n))
            if abs(lean) < 1.0:         # the mechanism lies on the guide: hatch below/right
                lean = -(n[1] if abs(n[1]) > 1e-9 else n[0])
            away = -n if lean > 0 else n
            base = at + block_h / 2 * away
            _hatch(figure, base - 1.7 * block_w * u, base + 1.7 * block_w * u, away, ink)

    def bars(self) -> None:
        """Each moving link: a bar, or a filled polygon when its points span an area."""
        figure, ink = self.figure, self.ink
        for name, points in self.moving.items():
            placed = [self.where[p] for p in points if p in self.where]
            unique = list(dict.fromkeys((round(float(x), 3), round(float(y), 3))
                                        for x, y in placed))
            if len(unique) < 2:
                continue
            hull, area = _hull(unique)
            a, b = _extremes(unique)
            if len(hull) >= 3 and area > 2.0 * float(norm(page_point(a) - b)):
                # under the bars, so that a ternary link never hides a bar drawn across it
                figure.polyline(hull, color=ink, width=2.0, layer="ground", fill=self.fill,
                                closed=True, css=f"link {name}")
            else:
                figure.line(a, b, color=ink, width=3.0, layer="links", cap="round",
                            css=f"link {name}")

    def blocks(self) -> None:
        """A slider block on each prismatic pair's point."""
        block_w, block_h = BLOCK
        for slide in self.position.slides:
            point = slide.get("point")
            if point not in self.where:
                continue
            u = page_direction(slide["direction_deg"])
            n = perp(u)
            at = self.where[point]
            corners = [(at + sx * block_w / 2 * u) + sy * block_h / 2 * n
                       for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
            self.figure.polyline(corners, color=self.ink, width=1.8, layer="links",
                                 fill="#ffffff", closed=True,
                                 css=f"slider {slide.get('link', '')}")

    def pivots(self) -> None:
        """Each fixed pivot: a triangle on the hatched ground, on the side no link takes."""
        figure, ink = self.figure, self.ink
        for pivot in self.position.pivots:
            if pivot not in self.where:
                continue
            at = self.where[pivot]
            spokes = [unit_or_zero(self.where[other] - at) for points in self.moving.values()
                      if pivot in points for other in points
                      if other != pivot and other in self.where]
            away = page_point(_support_direction(spokes))
            n = perp(away)
            base = at + 18.0 * away
            figure.polyline([at, base + 9.0 * n, base - 9.0 * n], color=ink, width=1.4,
                            layer="ground", fill="#ffffff", closed=True, css="support")
            _hatch(figure, base - 16.0 * n, base + 16.0 * n, away, ink)

    def pairs(self) -> None:
        """Revolute pairs as rings, other points of links as dots, frame points that join
        nothing as crosses; then the labels (coincident points share one)."""
        figure, ink = self.figure, self.ink
        for name, at in self.where.items():
            marks = () if self.faint else (name,)     # a faint mechanism only underlies
            if self.count.get(name, 0) >= 2:
                figure.circle(at, 4.5, fill="#ffffff", stroke=ink, width=1.5, layer="points",
                              css="pair", points=marks)
            elif self.count.get(name, 0) == 1 and name not in self.links.get("frame", ()):
                figure.circle(at, 2.6, fill=ink, layer="points", css="point", points=marks)
            else:
                for corner in ((4.0, 4.0), (4.0, -4.0)):
                    figure.line(at - corner, at + corner, color=ink, width=1.0,
                                layer="points", obstacle=False)
        for members in coincident_groups(self.position.points_mm, self.where,
                                 SAME_POINT_MM * figure.zoom):
            figure.request(tuple(members), self.where[members[0]],
                           merge_runs(label_runs(name) for name in members), mark=4.5,
                           css="faint" if self.faint else "label")


def mechanism_content(figure: Canvas, position: PositionPlan, *, faint: bool = False) -> None:
    """Links, pairs, pivots, sliders and guides of a position plan, with label requests."""
    page = _MechanismPage(figure, position, faint)
    page.guides()
    page.bars()
    page.blocks()
    page.pivots()
    page.pairs()


def _hatch(figure: Canvas, start: Point, end: Point, away: Point, ink: str) -> None:
    """A ground line from ``start`` to ``end`` hatched on the side ``away``."""
    color = GROUND if ink == INK else ink
    figure.line(start, end, color=color, width=1.6, layer="ground", css="ground")
    length = float(norm(end - start))
    u = unit_or_zero(end - start, length)
    count = max(2, int(length // 7))
    for index in range(count + 1):
        foot = start + index * length / count * u
        figure.line(foot, (foot + 6.0 * away) - 5.0 * u, color=color, width=0.9,
                    layer="ground", css="hatch")


def _support_direction(spokes: Sequence[Point]) -> Point:
    """Where a pivot's ground symbol goes: below it, unless a link points that way; then
    up, left or right, whichever is clear (the least crowded if none is)."""
    options = ((0.0, 1.0), (0.0, -1.0), (-1.0, 0.0), (1.0, 0.0))   # page: down, up, left, right

    def conflict(direction: Point) -> float:
        return max((float(dot(d, page_point(direction))) for d in spokes), default=-1.0)

    for option in options:
        if conflict(option) < 0.64:                                  # no link within 50°
            return option
    return min(options, key=conflict)


def _extremes(points: Sequence[Point]) -> tuple[Point, Point]:
    """The two points furthest apart (the first such pair)."""
    distances = _distances(points)
    first, second = divmod(int(np.argmax(np.triu(distances, 1))), len(points))
    return points[first], points[second]


def _hull(points: Sequence[Point]) -> tuple[list[Point], float]:
    """The convex hull (shapely) of distinct points, counter-clockwise from the lowest
    (x, y), and its area; fewer than three corners where the points lie on one line (two
    points always do: most links, asked for no hull)."""
    if len(points) < 3:
        return [], 0.0
    from shapely.geometry import MultiPoint
    from shapely.geometry.polygon import orient

    hull = MultiPoint(points).convex_hull
    if hull.geom_type != "Polygon":
        return [], 0.0
    corners = list(orient(hull, sign=1.0).exterior.coords)[:-1]
    first = corners.index(min(corners))
    return corners[first:] + corners[:first], float(hull.area)


def turning_arrow(figure: Canvas, centre_mm: Sequence[float], radius_px: float,
                  start_rad: float, sense: float, color: str, key: str,
                  runs: tuple, *, css: str = "omega", sweep_deg: float = 70.0) -> None:
    """A curved arrow round ``centre_mm`` (an angular velocity, a moment): ``radius_px`` on the
    page, from ``start_rad`` (counter-clockwise from +x) through ``sweep_deg`` in the
    ``sense`` (+1 counter-clockwise), labelled ``runs`` at its middle (a crowded label's
    leader may start anywhere on its arc before the head: the label's span)."""
    radius = radius_px / figure.zoom
    count = 21
    angles = [start_rad + sense * math.radians(22 + sweep_deg * k / (count - 1))
              for k in range(count)]
    arc = [figure.px((centre_mm[0] + radius * math.cos(a), centre_mm[1] + radius * math.sin(a)))
           for a in angles]
    tip = arc[-1]
    direction = unit_or_zero(tip - arc[-2])
    shaft = [*arc[:-1], tip - 7.0 * direction]
    figure.polyline(shaft, color=color, width=1.4, layer="marks", css=f"arrow {css}",
                    vector=True)
    arrowhead(figure, tip, direction, 10.0, color, "marks", css=f"arrow {css}")
    figure.request((key,), arc[len(arc) // 2], runs, mark=1.0, span=shaft)


def crank_number(position: PositionPlan) -> int:
    """The crank's number in the course's notation (1 by default): the drive's symbols
    φ, ω, ε carry it."""
    return position.numbers.get(position.drive[0], 1)


def _omega_arrow(figure: Canvas, position: PositionPlan, ink: str = INK) -> None:
    """The crank's ω₁ as a curved arrow round the drive pivot."""
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
                  1.0 if omega > 0 else -1.0, ink, f"ω{crank_number(position)}",
                  (("ω", RunKind.MAIN), (str(crank_number(position)), RunKind.UPRIGHT)))


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
                            dash="2,3", closed=True, css="path")
        half = 60.0
        ends = (at - half * tangent, at + half * tangent)
        figure.line(*ends, color=color, width=1.0, dash="10,3,2,3", layer="marks", css="tangent")
        for end in ends:
            figure.request(("τ",), end, (("τ", RunKind.MAIN),), size=TEXT_SIZE, mark=0.0)
        on_sheet = rho_px <= 1.6 * extent_px
        shown = rho_px if on_sheet else 0.5 * extent_px
        ends = (at - 40.0 * normal, at + (shown + 24.0) * normal)
        figure.line(*ends, color=color, width=1.0, dash="10,3,2,3", layer="marks", css="normal")
        for end in ends:
            figure.request(("η",), end, (("η", RunKind.MAIN),), size=TEXT_SIZE, mark=0.0)
        rho_m = float(data["rho_mm"]) * position.mu_l
        text = (("ρ", RunKind.MAIN), (name, RunKind.SUB),
                (" " + shown_text(message("= {rho:.4g} m", rho=rho_m)), RunKind.SEP))
        if on_sheet:
            centre = at + rho_px * normal
            figure.arrow(at, centre, "normal", layer="marks", color=color, css="rho")
            figure.circle(centre, 3.0, fill="#ffffff", stroke=color, width=1.4,
                          layer="points", css="centre")
            figure.request((f"O_{name}",), centre, (("O", RunKind.MAIN), (name, RunKind.SUB)),
                           mark=3.0)
        else:
            text = (*text[:-1], (" " + shown_text(message("= {rho:.4g} m (centre off the sheet)",
                                                      rho=rho_m)), RunKind.SEP))
        figure.request((f"rho_{name}",), at + 0.5 * shown * normal, text, size=TEXT_SIZE,
                       mark=1.0)


def position_zoom(position: PositionPlan, extra: Sequence[Sequence[float]] = ()) -> float:
    points = list(position.points_mm.values()) + [tuple(s["through_mm"])
                                                   for s in position.slides] + list(extra)
    return fit_zoom(points, MECHANISM_SIZE)


def position_drawing(position_plan: PositionPlan, *, plans: Plans | None = None,
                     notes: Sequence[Message | str] = (), view: SteadyView | None = None,
                     details: bool = True, formulas: bool = False) -> SvgFigure:
    """The mechanism at μl as an :class:`SvgFigure` (see the module docstring).

    ``notes`` are lines of text printed under the figure (a task sheet's text); a line that
    starts with two spaces is a table row and is set in a monospaced font. With ``formulas``
    the symbols in them are set as a course writes them (``l_AB`` → l with AB below, a name in
    square brackets kept as it is). ``view`` keeps the
    zoom and the page of every frame of a turn (the fixed pivots stay where they are). With
    ``details`` (and no ``view``), points nearer each other than the readable distance are
    drawn again, enlarged, below the mechanism.
    """
    position = position_plan
    centres = []
    base_zoom = position_zoom(position)
    extent_mm = MECHANISM_SIZE / base_zoom
    for data in position.curvature.values():
        if float(data["rho_mm"]) <= 1.6 * extent_mm:
            centres.append(tuple(data["center_mm"]))
        centres += [tuple(xy) for xy in data.get("path_mm") or ()]
    figure = Canvas(view.zoom if view else position_zoom(position, centres))

    def content(canvas: Canvas) -> None:
        mechanism_content(canvas, position)
        _omega_arrow(canvas, position)
        _curvature_content(canvas, position, MECHANISM_SIZE)

    content(figure)
    regions = detail_regions(figure, {name: figure.px(xy) for name, xy in
                                      position.points_mm.items()}, draw=details and not view)
    figure.place(bounds=view.box if view else None)
    inserted = [] if view else column_and_details(
        figure, content, regions, "detail-position",
        lambda _: legend_column(figure, PlanKind.POSITION),
        crowded=[(label_text(name), *position.points_mm[name], (name,))
                 for name in crowded_points(regions)], title=ON_THE_DRAWING)
    lines = [*_position_lines(position, plans), *inserted]
    phi = numbered("φ", crank_number(position))
    title = (message("{title} — position plan, {phi} = {angle:g}°", title=position.title,
                     phi=phi, angle=position.angle) if position.title else
             message("position plan, {phi} = {angle:g}°", phi=phi, angle=position.angle))
    frame(figure, title, lines, (position.mu_l, SCALES["mu_l"].drawn, 0.25 * MECHANISM_SIZE),
          [flag_message(flag, plans.velocity.numbers) for flag in plans.flags]
          if plans is not None else (), PlanKind.POSITION,
          box=view.box if view else None, column=view is not None)
    y = figure.extent[3] + 24
    for line in map(shown_text, notes):
        if line.strip():
            figure.text((figure.extent[0], y), line, size=TEXT_SIZE, css="task", area=False,
                        monospace=line.startswith("  "), formula=formulas)
        y += 17
    return figure.svg(title, view=steady_page(view, title, len(lines), PlanKind.POSITION,
                                              legend=False) if view else None)


def _position_lines(position: PositionPlan, plans: Plans | None) -> list[Message | str]:
    """The lines under the mechanism: μl, the crank's ω, the plans' scales."""
    lines: list[Message | str] = [scale_text("mu_l", position.mu_l)]   # words: vocabulary
    link, _pivot, omega = position.drive
    if omega:
        lines.append(message("{omega} = {value:.6g} rad/s, {link}",
                             omega=numbered("ω", crank_number(position)), value=omega,
                             link=link_text(link, position.numbers, "drive link")))
    if plans is not None:
        lines += scale_lines(plans.scales)[1:3]
    return lines


def position_svg(position_plan: PositionPlan, *, plans: Plans | None = None,
                 view: SteadyView | None = None, details: bool = True) -> str:
    """The mechanism at μl as SVG text (``plans`` adds the plans' scales and flags)."""
    return position_drawing(position_plan, plans=plans, view=view, details=details).svg


# -- the rotated velocity plan --------------------------------------------------------------------
def lever_drawing(plans: Plans, *, view: SteadyView | None = None, details: bool = True
                  ) -> SvgFigure:
    """The velocity plan turned 90° onto the faint mechanism, pole p at the drive's pivot
    (``view``: the zoom and page of every frame of a turn; ``details``: where the plan's
    points crowd, an enlarged detail, unless a ``view`` is given)."""
    position, plan = plans.position, plans.velocity
    rotated = plans.rotated_velocity_plan()
    figure = Canvas(view.zoom if view else position_zoom(position, list(rotated.values())))

    def content(canvas: Canvas) -> None:
        mechanism_content(canvas, position, faint=True)
        plan_content(canvas, rotated, plan.steps, plan.pole, rotate_deg=-90.0,
                     numbers=plan.numbers)

    content(figure)
    regions = detail_regions(figure, {label: figure.px(xy) for label, xy in rotated.items()},
                             draw=details and not view)
    figure.place(bounds=view.box if view else None)
    pole = np.asarray(rotated[plan.pole], float)
    inserted = [] if view else column_and_details(
        figure, content, regions, "detail-lever",
        lambda _: legend_column(figure, PlanKind.VELOCITY),
        crowded=[(label_text(name, plan.numbers), *(np.asarray(rotated[name], float) - pole),
                  (name,)) for name in crowded_points(regions)],
        title=FROM_POLE.replace(pole=plan.pole))
    lines = [scale_text("mu_l", position.mu_l), scale_text("mu_v", plan.scale),  # vocabulary
             message("the velocity plan turned 90° clockwise, pole {pole} at {pivot} "
                     "(Zhukovsky's lever)", pole=plan.pole, pivot=point_text(position.drive[1])),
             *inserted]
    phi = numbered("φ", crank_number(position))
    title = (message("{title} — rotated velocity plan, {phi} = {angle:g}°", title=position.title,
                     phi=phi, angle=position.angle) if position.title else
             message("rotated velocity plan, {phi} = {angle:g}°", phi=phi, angle=position.angle))
    frame(figure, title, lines, (plan.scale, SCALES["mu_v"].drawn, 0.25 * MECHANISM_SIZE),
          [flag_message(flag, plan.numbers) for flag in plan.flags], PlanKind.VELOCITY,
          box=view.box if view else None, column=view is not None)
    return figure.svg(title, view=steady_page(view, title, len(lines), PlanKind.VELOCITY)
                      if view else None)


def lever_svg(plans: Plans, *, view: SteadyView | None = None, details: bool = True) -> str:
    """The rotated velocity plan on the mechanism as SVG text."""
    return lever_drawing(plans, view=view, details=details).svg
