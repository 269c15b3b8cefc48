"""SVG drawings of the kinetostatics: force polygons and I. H. Aliyev's
combined-force construction.

* :func:`polygon_svg` — one group's force polygon at μF, drawn head to tail in the order the
  group's solve writes its vector equation (for an RRR dyad: Rᵗ of the first outer pin, the
  known forces of both links, Rᵗ and Rⁿ of the second outer pin, Rⁿ of the first, closing on
  the start). Known forces (weights, inertia forces, loads, friction) and the reactions of
  groups solved before are thin; the components of the unknown reactions are styled like the
  plans' normal (Rⁿ, N) and tangential (Rᵗ) components; each whole reaction R = Rⁿ + Rᵗ is bold.
* :func:`combined_svg` — the acceleration plan with the pole moved down by the image of g,
  Z_g = g/μa, to π′, and from each centre-of-mass image s the dashed segment s→π′, which
  represents the combined force Q = m·(g − a_S) at Q/(m·μa) (I. H. Aliyev,
  "Studies of the possibility of determining amplifications in kinematic pairs").
* :func:`lever_forces_svg` — Zhukovsky's lever with its forces: the turned velocity plan, each
  force at the image of its point with its arm from the pole, the balancing force and ΣM_p = 0.
* :func:`loaded_svg` — the loaded mechanism: every force and moment acting on it.
* :func:`force_files` — all of them as ``{file name: SVG text}`` for ``planmethod solve --svg``.

The figures are drawn on the one canvas (:mod:`planmethod.render.canvas`) with the plans' style,
frame and label placement (:mod:`planmethod.render.svg`), and are deterministic.

Examples
--------
>>> from planmethod.report import analyse
>>> from planmethod.spec import load_exercise
>>> analysis = analyse(load_exercise("exercises/fourbar_forces.toml"))
>>> sorted(force_files(analysis.forces, analysis.plans))      # no gravity: no combined force
['forces_1_BC+CD.svg', 'forces_2_AB.svg', 'lever.svg', 'loaded.svg']
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..forces.checks import VelocitySource
from ..forces.names import BALANCING_MOMENT, INERTIA_FORCE, INERTIA_MOMENT
from ..plans.scales import standard
from ..vectors import cross, dot, inside_span, norm, perp, unit
from ..vocabulary import (
    SCALES,
    AppliedKind,
    EdgeKind,
    PlanKind,
    numbered,
    point_text,
    scale_text,
    shown_title,
    subscript,
)
from ..words import Message, message, number_text, render
from .canvas import Canvas, arrowhead, fit_zoom
from .details import (
    FROM_POLE,
    ON_THE_DRAWING,
    column_and_details,
    crowded_points,
    laid_out,
    within_page,
)
from .labels import RunKind, label_runs
from .notation import BALANCING_FORCE, ForceNotation, symbol_runs
from .plan_words import flag_message, label_text
from .steady import SteadyView
from .style import INK, SMALL_SIZE, STYLES, TEXT_SIZE
from .svg import (
    MECHANISM_SIZE,
    PLAN_SIZE,
    crank_number,
    frame,
    mechanism_content,
    plan_content,
    plan_legend,
    position_zoom,
    steady_page,
    turning_arrow,
)

__all__ = ["combined_omitted", "combined_svg", "force_files", "lever_forces_svg",
           "loaded_svg", "polygon_svg"]

#: colour of each kind of known force in a polygon
KNOWN_COLOURS = {"G": "#8c564b", "F": "#c0392b", "l": "#7b3fa0", "R": "#666666"}
FRICTION = "#e67e22"


def _runs(name: str):
    """Label runs of a force's name: ``G_BC`` → G with subscript BC, ``F_u,BC`` → F with
    subscript u,BC, ``Rᵗ_B`` → Rᵗ with subscript B."""
    if name.startswith("load["):
        return ((name, RunKind.MAIN),)
    return label_runs(name)


#: how an edge of each kind but a known force is drawn: (style key, colour override, legend)
_EDGE_LOOKS = {
    EdgeKind.REACTION: ("result", None, message("reaction found by closing the polygon")),
    EdgeKind.TRANSMITTED: ("relative", KNOWN_COLOURS["R"],
                           message("reaction from a group solved before")),
}


def _edge_style(edge) -> tuple[str, str | None]:
    """(style key, colour override) of a polygon edge."""
    if edge.kind == EdgeKind.COMPONENT:
        return ("tangential", None) if edge.label.startswith("Rᵗ") else ("normal", None)
    if edge.kind in _EDGE_LOOKS:
        return _EDGE_LOOKS[edge.kind][:2]
    if edge.label.startswith(("M_f", "F_f")):
        return "relative", FRICTION
    return "relative", KNOWN_COLOURS.get(edge.label[:1], KNOWN_COLOURS["l"])


def _totals(edges, vectors):
    """Whole reactions R = Rⁿ + Rᵗ where the two components follow each other (cyclically):
    ``[(name, start index, end index)]``."""
    out = []
    count = len(edges)
    for i in range(count):
        j = (i + 1) % count
        first, second = edges[i].label, edges[j].label
        for a, b in (("Rⁿ_", "Rᵗ_"), ("Rᵗ_", "Rⁿ_")):
            if first.startswith(a) and second.startswith(b) and first[3:] == second[3:]:
                out.append((f"R_{first[3:]}", i, j))
    return out


def polygon_svg(group, mu_f: float, *, title: str, angle: float, index: int = 0,
                notation: ForceNotation | None = None, details: bool = True,
                view: SteadyView | None = None) -> str:
    """One group's force polygon (see the module docstring); ``index`` picks the crank angle
    of a vectorised solve; ``notation`` prints the forces as a course writes them (R₁₂, G₃),
    else by their report names. Where short forces crowd their corners, an enlarged detail
    (with ``details``). ``view`` keeps the force scale, the zoom and the page of every frame of
    a turn."""
    if view is not None and view.scale:
        mu_f = view.scale
    edges = [edge for edge in group.polygon if float(norm(edge.vector[index])) > 0]
    drawn = _Polygon(group, edges, mu_f, index, notation)
    if view is not None:
        return _polygon_page(drawn, title, details, view, 1.0)[1]
    return within_page(lambda growth: _polygon_page(drawn, title, details, None, growth))


@dataclass(frozen=True)
class _Polygon:
    """A group's force polygon to draw: its group, its edges (forces not zero), its force
    scale, the crank angle's index and the notation its forces are printed in."""

    group: Any
    edges: list
    mu_f: float
    index: int
    notation: ForceNotation | None


def _polygon_page(drawn: _Polygon, title: str, details: bool, view: SteadyView | None,
                  growth: float) -> tuple[Canvas, str]:
    """A force polygon's page (:func:`polygon_svg`) with its drawing ``growth`` times its own
    size: its canvas and SVG."""
    group, edges, mu_f, notation = drawn.group, drawn.edges, drawn.mu_f, drawn.notation
    vectors = [edge.vector[drawn.index] / mu_f for edge in edges]
    corners = [np.zeros(2)]
    for vector in vectors:
        corners.append(corners[-1] + vector)
    used: dict[Message, tuple[str, str | None]] = {}
    count = len(edges)

    def content(figure: Canvas) -> None:
        where = [figure.px(c) for c in corners]
        for number, (edge, start, end) in enumerate(zip(edges, where[:-1], where[1:],
                                                        strict=True)):
            style, colour = _edge_style(edge)
            if figure.arrow(start, end, style, layer="components", color=colour,
                            css=f"force {edge.kind}", step=number + 1):
                used.setdefault(_legend_key(edge), (style, colour))
            runs = notation.runs(edge.label, edge.link) if notation else _runs(edge.label)
            figure.request((edge.label,), start + 0.5 * (end - start), runs, mark=2.0,
                           span=(start, end))
        for name, first, _ in _totals(edges, vectors):
            on = edges[first].link
            after = first + 2  # the corner after the second component (cyclically)
            start, end = where[first], where[after if after <= count else after - count]
            if figure.arrow(start, end, "result", layer="results", css="force total"):
                used.setdefault(_WHOLE_REACTION, ("result", None))
                figure.request((name,), start + 0.5 * (end - start),
                               notation.runs(name, on) if notation else _runs(name), mark=2.0,
                               span=(start, end))
        figure.circle(where[0], 3.4, fill=INK, css="start")

    figure, regions = laid_out(
        view.zoom if view else growth * fit_zoom([tuple(c) for c in corners], PLAN_SIZE),
        content,
        lambda canvas: {f"corner {k}": canvas.px(c) for k, c in enumerate(corners[:-1])},
        details and not view, view.box if view else None)
    closure = float(norm(corners[-1] - corners[0]))
    if view:
        lines_of_details = []
        _force_legend(figure, (view.box[2] + 34, view.box[1] + 4), used)
    else:                  # the legend beside the polygon, its details beside them
        lines_of_details = column_and_details(figure, content, regions, "detail-polygon",
                                              lambda at: _force_legend(figure, at, used))
    lines = [line.replace("⟂", "⊥")               # ⊥ is in every common font
             for line in _polygon_notes(group, edges, mu_f, closure, notation)
             + lines_of_details]
    frame(figure, title, lines, (mu_f, SCALES["mu_f"].drawn, 0.3 * PLAN_SIZE), (), "force",
          box=view.box if view else None)
    return figure, figure.svg(title, view=steady_page(view, title, len(lines), "force")
                              if view else None).svg


def _polygon_notes(group, edges: list, mu_f: float, closure: float,
                   notation: ForceNotation | None) -> list[str]:
    """The lines under a force polygon: its scale, its vector equation, how near it closes
    and the group's steps (in the course's notation with ``notation``)."""
    terms = " + ".join(notation.plain(edge.label, edge.link) if notation else edge.label
                       for edge in edges)
    return [scale_text("mu_f", mu_f), f"ΣF = 0: {terms} = 0",   # words: vocabulary
            render(message("the polygon closes to {closure:.2g} mm", closure=closure)),
            *(render(notation.sentence(step, group.links) if notation else step)
              for step in group.steps)]


#: a polygon's legend entries of its known forces and its components
_FRICTION_FORCE = message("friction force")
_WEIGHT = message("weight G")
_EXTERNAL_LOAD = message("external load")
_TANGENTIAL = message("tangential component Rᵗ (⊥ the link)")
_NORMAL = message("normal component Rⁿ (along the link) or N (⊥ a guide)")
_INERTIA = message("inertia force {symbol} = −m·a_S", symbol=INERTIA_FORCE)
_WHOLE_REACTION = message("whole reaction R = Rⁿ + Rᵗ")


def _legend_key(edge) -> Message:
    if edge.kind == EdgeKind.COMPONENT:
        return _TANGENTIAL if edge.label.startswith("Rᵗ") else _NORMAL
    if edge.kind in _EDGE_LOOKS:
        return _EDGE_LOOKS[edge.kind][2]
    if edge.label.startswith(("M_f", "F_f")):
        return _FRICTION_FORCE
    if edge.label[:1] == "F":
        return _INERTIA
    return _WEIGHT if edge.label[:1] == "G" else _EXTERNAL_LOAD


def _force_legend(figure: Canvas, at, used: dict[Message, tuple[str, str | None]],
                  heading: Message | None = None) -> float:
    """The legend of the forces drawn (by their entries' messages), top-left at ``at``;
    returns the y under it."""
    x, y = at
    if not used:
        return y
    figure.text((x, y), render(heading or message("Legend")), size=TEXT_SIZE, bold=True,
                css="legend", area=False)
    y += 8
    for text, (style, colour) in used.items():
        y += 20
        figure.arrow((x, y - 4), (x + 34, y - 4), style, layer="text", color=colour,
                     obstacle=False)
        figure.text((x + 44, y), render(text), size=SMALL_SIZE, css="legend", area=False,
                    formula=True)
    return y


def combined_svg(forces, plans, *, view: SteadyView | None = None, details: bool = True
                 ) -> str | None:
    """Aliyev's combined-force construction on the acceleration plan (None without one, and
    None where no gravity acts: with g = 0 the moved pole π′ is π and the construction is the
    inertia forces alone; see :func:`combined_omitted`); ``view`` keeps the zoom and page of
    every frame of a turn; with ``details`` (and no ``view``) an enlarged detail where
    points crowd."""
    combined = forces.combined
    if combined is None or plans is None or plans.acceleration is None or not combined.g:
        return None
    if view is not None:
        return _combined_page(forces, plans, view, details, 1.0)[1]
    return within_page(lambda growth: _combined_page(forces, plans, None, details, growth))


def _combined_page(forces, plans, view: SteadyView | None, details: bool, growth: float
                   ) -> tuple[Canvas, str]:
    """The combined-force figure's page (:func:`combined_svg`) with its drawing ``growth``
    times its own size: its canvas and SVG."""
    combined = forces.combined
    plan = plans.acceleration
    points = dict(plan.points_mm)
    new_pole = combined.new_pole_mm
    notation = ForceNotation(forces.solution)

    def content(canvas: Canvas) -> None:
        plan_content(canvas, points, plan.steps, plan.pole, numbers=plan.numbers)
        _combined_content(canvas, combined, notation)

    def where(canvas: Canvas) -> dict:
        return ({label: canvas.px(xy) for label, xy in points.items()}
                | {"π′": canvas.px(new_pole)}
                | {f"s_{force.link}": canvas.px(force.image_mm) for force in combined.forces})

    extra = [new_pole] + [f.image_mm for f in combined.forces]
    figure, regions = laid_out(view.zoom if view else growth * fit_zoom(
        list(points.values()) + extra, PLAN_SIZE), content, where, details and not view,
        view.box if view else None,
        plan_of=lambda canvas: {label: canvas.px(xy) for label, xy in points.items()})
    if view:
        lines_of_details = []
        _combined_column(figure, (view.box[2] + 34, view.box[1] + 4))
    else:
        named = {f"s_{force.link}": (numbered("s", notation.number(force.link)),
                                     force.image_mm) for force in combined.forces}
        named |= {"π′": ("π′", new_pole)} | {
            label: (label_text(label, plan.numbers), xy) for label, xy in points.items()}
        lines_of_details = column_and_details(
            figure, content, regions, "detail-combined",
            lambda at: _combined_column(figure, at), crowded=_crowded_rows(named, regions),
            title=FROM_POLE.replace(pole=plan.pole))
    figure.used.clear()
    lines = _combined_notes(combined, notation) + lines_of_details
    title = render(message("{title} — Q = G + {symbol} on the acceleration plan, pole moved to "
                           "π′, {phi} = {angle:g}°", symbol=INERTIA_FORCE,
                           title=shown_title(plans.exercise.mechanism.title), phi=_phi(plans),
                           angle=plans.angle))
    frame(figure, title, lines, None, [flag_message(f, plan.numbers) for f in plan.flags],
          PlanKind.ACCELERATION,
          box=view.box if view else None)
    return figure, figure.svg(title, view=steady_page(view, title, len(lines) + 2,
                                                      PlanKind.ACCELERATION) if view else None
                              ).svg


def _combined_column(figure: Canvas, at) -> float:
    """The combined-force figure's column, top-left at ``at``: the plan's styles and the
    construction's; returns the y under it."""
    bottom = plan_legend(figure, at, PlanKind.ACCELERATION)
    return _force_legend(figure, (at[0], bottom + 34 if bottom > at[1] else at[1]), {
        message("image of g: π → π′, Z_g = g/μa"): ("normal", KNOWN_COLOURS["G"]),
        message("s → π′ = (g − a_S)/μa: Q = m·μa·(s π′)"): ("tangential", KNOWN_COLOURS["F"])},
        heading=message("Combined force (Aliyev)"))


def _crowded_rows(named: Mapping[str, tuple[str, Any]], regions: list
                  ) -> list[tuple[str, float, float, tuple[str, ...]]]:
    """The rows of the table of the points a figure's details cannot set apart, from the
    points' printed names and places (mm) by the names the details watch (a force's label
    among them is not a point: not listed)."""
    return [(named[name][0], float(named[name][1][0]), float(named[name][1][1]), (name,))
            for name in crowded_points(regions) if name in named]


def _combined_content(canvas: Canvas, combined, notation: ForceNotation) -> None:
    """Over the acceleration plan: the image of g from π to π′, each centre of mass's image
    s and the segment s→π′ of its combined force."""
    pole_px, new_px = canvas.px((0.0, 0.0)), canvas.px(combined.new_pole_mm)
    if combined.gravity_image_mm > 0:
        canvas.arrow(pole_px, new_px, "normal", layer="results", color=KNOWN_COLOURS["G"],
                     css="gravity image")
        canvas.request(("Z_g",), pole_px + 0.5 * (new_px - pole_px), _runs("Z_g"),
                       mark=2.0, span=(pole_px, new_px))
    canvas.circle(new_px, 3.4, fill=KNOWN_COLOURS["F"], css="new pole", points=("π′",))
    canvas.request(("π′",), new_px, (("π′", RunKind.MAIN),), mark=3.4)
    for force in combined.forces:
        s = canvas.px(force.image_mm)
        canvas.circle(s, 2.6, fill=KNOWN_COLOURS["F"], css="centre of mass image",
                      points=(f"s_{force.link}",))
        canvas.request((f"s_{force.link}",), s, (("s", RunKind.MAIN),
                                                 (notation.number(force.link),
                                                  RunKind.SUB)), mark=2.6)
        if float(norm(np.asarray(force.segment_mm))) * canvas.zoom >= 1.0:
            canvas.arrow(s, new_px, "tangential", layer="results",
                         color=KNOWN_COLOURS["F"], css=f"combined {force.link}")


def _combined_notes(combined, notation: ForceNotation) -> list[str]:
    """The lines under the combined-force figure: the scale and Z_g, and each link's Q read
    off the plan."""
    lines = [render(message("{scale}; g = {g:g} m/s², Z_g = g/μa = {length:.4g} mm",
                            scale=scale_text("mu_a", combined.mu_a),    # words: vocabulary
                            g=combined.g, length=combined.gravity_image_mm))]
    for force in combined.forces:
        length = float(norm(np.asarray(force.segment_mm)))
        sub = subscript(notation.number(force.link))
        lines.append(render(message(
            "{link}: (s{sub}π′) = {length:.4g} mm → Q{sub} = m{sub}·μa·(s{sub}π′) = "
            "{mass:g}·{scale:.4g}·{length:.4g} = {force:.5g} N",
            link=notation.link_name(force.link), sub=sub, length=length, mass=force.mass,
            scale=combined.mu_a, force=float(norm(np.asarray(force.from_plan))))))
    return lines


def combined_omitted(forces, plans) -> Message | None:
    """Why the combined-force figure is not drawn, in one line (None when it is, or when the
    analysis has no combined-force construction at all)."""
    combined = getattr(forces, "combined", None)
    if combined is None or plans is None or plans.acceleration is None or combined.g:
        return None
    return message("{file} is not drawn: no gravity acts (g = 0), so the moved pole π′ is π "
                   "and Q = G + {symbol} is the inertia force alone", file="combined_force.svg",
                   symbol=INERTIA_FORCE)


def _phi(plans, letter: str = "φ") -> str:
    """The crank's φ (or ω, ε) with the crank's number, as the course writes it."""
    return numbered(letter, crank_number(plans.position))


def _force_colour(name: str) -> str:
    if name.startswith(("M_f", "F_f")):
        return FRICTION
    if name.startswith("M_u"):
        return KNOWN_COLOURS["F"]
    return KNOWN_COLOURS.get(name[:1], KNOWN_COLOURS["l"])


@dataclass(frozen=True)
class _LeverForce:
    """A force on the lever, in mm of the turned plan: its image, its vector (N), its moment
    about p (N·mm), its arm h and the arm's foot; ``couple`` names the couple whose force
    pair it belongs to (Mᵘ₂ …), ``number`` the arm's index (h₁, h₂ …)."""

    name: str
    link: str | None
    image: np.ndarray
    force: np.ndarray
    moment: float
    arm: float
    foot: np.ndarray
    couple: str = ""
    number: int = 0
    #: the arm's row among the arms on one line from p (0: on its own line), and the side
    #: (+1, −1 along the force) the rows step to: arms that would lie on one another are
    #: drawn as stacked dimension lines
    row: int = 0
    side: float = 1.0
    #: the report name of the force (or couple) it carries, and a couple's force's point
    source: str = ""
    point: str | None = None


#: the legend entries of the lever's forces
_LEVER_LEGEND = {
    "known": message("known force at the image of its point, arm h from p"),
    "couple": message("inertia couple {symbol} as the force pair ±{symbol}/l the sum counts",
                      symbol=INERTIA_MOMENT),
    "balancing": message("balancing force {symbol} (⊥ the crank) at the image of the crank "
                         "pin", symbol=BALANCING_FORCE),
    "term": message("couple on a link with one point: the term {symbol}·ω/μv (its sense on "
                    "the lever)", symbol=INERTIA_MOMENT)}


@dataclass(frozen=True)
class _MomentTerm:
    """A couple on a link with one point on the plan, on the lever as its moment term
    M·ω/μv (N·mm) at the image of that point (mm of the turned plan)."""

    source: str
    link: str
    image: np.ndarray
    moment: float


def _moment_terms(solution: Any, lever: Any) -> list[_MomentTerm]:
    """The lever's moment terms whose couple is not zero (a zero ω still gives its row)."""
    given = {(item.name, item.link): item for item in solution.applied.items
             if item.moment is not None}
    terms = []
    for force in lever.forces:
        item = given.get((force.source, force.link))
        if not force.term or item is None or float(item.moment[0]) == 0.0:
            continue
        terms.append(_MomentTerm(force.source, force.link,
                                 np.asarray(force.image_mm[0], float), float(force.moment[0])))
    return terms


def _arm(image: np.ndarray, force: np.ndarray) -> tuple[float, np.ndarray]:
    """The arm h (mm) of a force at ``image`` about the pole, and the foot of the
    perpendicular from the pole to its line of action."""
    direction = unit(force)
    foot = image - float(dot(image, direction)) * direction
    arm = float(norm(foot))
    if arm <= 1e-9 * max(float(norm(image)), 1.0):
        return 0.0, np.zeros(2)                  # the line passes through p (rounding)
    return arm, foot


class _LeverFigure:
    """Zhukovsky's lever being drawn: the turned velocity plan, the force scale of the
    lever, and each force at the image of its point with its arm from the pole — drawn on any
    canvas (:meth:`content`), so that a crowded region can be drawn again as a detail."""

    def __init__(self, forces: Any, plans, growth: float = 1.0) -> None:
        lever = forces.solution.lever
        self.notation = notation = ForceNotation(forces.solution)
        self.plan = plan = plans.velocity
        self.turned = {label: (float(y), float(-x)) for label, (x, y) in plan.points_mm.items()}
        self.known: list[_LeverForce] = []
        self.couples: list[_LeverForce] = []
        self.friction: dict[str, float] = {}
        #: the couples on links with one point: their moment terms M·ω/μv
        self.terms = _moment_terms(forces.solution, lever)
        for force in lever.forces:
            vector = np.asarray(force.force[0], float)
            if force.term or float(norm(vector)) == 0:
                continue
            base, at = force.source, force.point
            image = np.asarray(force.image_mm[0], float)
            moment = float(force.moment[0])
            if at and base.startswith("M_f"):     # friction couples: in the sum, not drawn
                self.friction[base] = self.friction.get(base, 0.0) + moment
                continue
            arm, foot = _arm(image, vector)
            record = _LeverForce(force.name, force.link, image, vector, moment, arm, foot,
                                 notation.plain(base, force.link) if at else "",
                                 source=base, point=at)
            (self.couples if at else self.known).append(record)
        balancing = np.asarray(lever.balancing_force[0], float)
        pin = np.asarray(lever.balancing_image_mm[0], float)
        arm, foot = _arm(pin, balancing)
        balancing_force = _LeverForce("F_b", None, pin, balancing,
                                      float(cross(pin, balancing)), arm, foot, source="F_b")
        # the arms numbered h₁, h₂ … as the table lists them: known forces, couples, F_b
        numbered = [replace(item, number=number) for number, item in
                    enumerate([*self.known, *self.couples, balancing_force], start=1)]
        self.known = numbered[:len(self.known)]
        self.couples = numbered[len(self.known):-1]
        self.balancing = numbered[-1]
        drawn = [*self.known, self.balancing]
        largest = max(float(norm(item.force)) for item in drawn)
        points = list(self.turned.values())
        extent = max(max(abs(c) for xy in points for c in xy), 1.0)
        #: the force scale of the lever (N/mm), and the couples' own where theirs would
        #: be too short to see at it
        self.mu_f = mu_f = standard(largest / (0.45 * extent)) if largest > 0 else 1.0
        pair = max((float(norm(item.force)) for item in self.couples), default=0.0)
        self.mu_couple = mu_f if pair / mu_f >= COUPLE_LENGTH * extent or not pair else \
            standard(pair / (COUPLE_LENGTH * extent))
        ends = [tuple(item.image + item.force / mu_f) for item in drawn]
        ends += [tuple(item.image + item.force / self.mu_couple) for item in self.couples]
        self.zoom = growth * fit_zoom(points + ends, PLAN_SIZE)
        self.balancing_runs = symbol_runs(BALANCING_FORCE)
        numbered = _stacked([*self.known, *self.couples, self.balancing], self.zoom)
        self.known = numbered[:len(self.known)]
        self.couples = numbered[len(self.known):-1]
        self.balancing = numbered[-1]
        self.used: dict[Message, tuple[str, str | None]] = {}

    def content(self, figure: Canvas) -> None:
        """The turned plan and every force with its arm, on ``figure`` at its zoom."""
        plan = self.plan
        plan_content(figure, self.turned, plan.steps, plan.pole, rotate_deg=-90.0,
                     numbers=plan.numbers)
        for item in self.known:
            colour = _force_colour(item.source)
            self._draw(figure, item, self.mu_f, colour, "relative",
                       self.notation.runs(item.source, item.link))
            self.used.setdefault(_LEVER_LEGEND["known"], ("relative", colour))
        for item in self.couples:
            colour = _force_colour(item.source)
            symbol = self.notation.runs(item.source, item.link)
            self._draw(figure, item, self.mu_couple, colour, "tangential", symbol)
            self.used.setdefault(_LEVER_LEGEND["couple"], ("tangential", colour))
        for term in self.terms:
            if term.source.startswith("M_f"):       # friction: in the sum, not drawn
                continue
            colour = _force_colour(term.source)
            turning_arrow(figure, term.image, 22.0, math.pi / 4, 1.0 if term.moment >= 0
                          else -1.0, colour, f"term:{term.source}:{term.link}",
                          self.notation.runs(term.source, term.link), css="lever term")
            self.used.setdefault(_LEVER_LEGEND["term"], ("relative", colour))
        self._draw(figure, self.balancing, self.mu_f, INK, "result", self.balancing_runs)
        self.used[_LEVER_LEGEND["balancing"]] = ("result", None)

    def _draw(self, figure: Canvas, item: _LeverForce, mu_f: float, colour: str, style: str,
              runs) -> None:
        """The force at its image, its arm from p labelled h₁, h₂ …, and its line."""
        start, end = figure.px(item.image), figure.px(item.image + item.force / mu_f)
        figure.arrow(start, end, style, layer="results", color=colour, css="lever force")
        figure.request((f"force:{item.name}",), start + 0.6 * (end - start), runs, mark=2.0,
                       span=(start, end))
        if item.arm * figure.zoom < 2.0:
            return
        direction = unit(item.force)
        pole, foot = figure.px((0.0, 0.0)), figure.px(item.foot)
        step = figure.px(direction * item.side * item.row * ROW_PX / figure.zoom)
        if item.row:         # a dimension line beside the others: its extension lines
            for end in (pole, foot):
                figure.line(end, end + step, color=colour, width=0.5, dash="1.5,2.5",
                            layer="construction", css="arm extension")
        figure.line(pole + step, foot + step, color=colour, width=0.7, dash="1.5,2.5",
                    layer="construction", css="arm")
        figure.request((f"arm:{item.name}",), foot + step,        # at its end, beyond it
                       (("h", RunKind.MAIN), (str(item.number), RunKind.UPRIGHT)),
                       size=SMALL_LABEL, mark=0.0, css="arm", span=(pole + step, foot + step),
                       lean=(foot - pole) / max(float(norm(foot - pole)), 1e-12))
        reach = max(4.0 / figure.zoom, float(dot(item.image - item.foot, direction)))
        figure.line(foot, figure.px(item.foot + direction * reach), color=colour, width=0.5,
                    dash="4,3", layer="construction", css="line of action")

    def rows(self) -> tuple[list[list[str]], float, float]:
        """The sum's table, term by term, and Σ M, Σ |M| (N·mm)."""
        rows = []
        total = magnitude = 0.0
        for item in [*self.known, *self.couples]:
            shown = self.notation.plain(item.source, item.link)
            if item.couple:
                shown = render(message("{force} (pair, {point})", force=shown,
                                       point=point_text(item.point)))
            rows.append([shown, number_text(float(norm(item.force)), ".4g"),
                         f"h_{item.number}", number_text(item.arm, ".4g"),
                         _signed(item.moment if item.arm else 0.0)])
            total += item.moment
            magnitude += abs(item.moment)
        for term in self.terms:
            rows.append([render(message("{moment}·{omega}/μv (couple)",
                                        moment=self.notation.plain(term.source, term.link),
                                        omega=numbered("ω", self.notation.number(term.link)))),
                         "", "", "", _signed(term.moment)])
            total += term.moment
            magnitude += abs(term.moment)
        for name, moment in self.friction.items():
            rows.append([render(message("{force} (couple, not drawn)",
                                        force=self.notation.plain(name))), "", "",
                         "", _signed(moment)])
            total += moment
            magnitude += abs(moment)
        return rows, total, magnitude


#: the couples' force pairs are drawn at least this fraction of the plan's extent long (the
#: largest; at a scale of their own where the lever's would draw them shorter), so that their
#: labels sit clear of the images they start at
COUPLE_LENGTH = 0.2
#: a label's size for the arms h₁, h₂ … (smaller than the points' labels)
SMALL_LABEL = 12.0
#: the step (px) between the rows of arms that lie on one line from p
ROW_PX = 28.0
#: arms from p whose lines part less than this (px) along the shorter lie on one line
SAME_LINE_PX = 8.0


def _stacked(items: list[_LeverForce], zoom: float) -> list[_LeverForce]:
    """The arms numbered in rows: arms that leave p in one direction — their lines part less
    than :data:`SAME_LINE_PX` along the shorter, drawn at ``zoom`` — would be drawn on one
    another; the shortest stays on its line, each longer one is drawn :data:`ROW_PX` further
    along the forces' direction (all to the side away from the forces' images), as a stack of
    dimension lines, each labelled at its end.

    >>> def force(foot):
    ...     return _LeverForce("G", None, np.array([foot, 5.0]), np.array([0.0, -1.0]),
    ...                        0.0, abs(foot), np.array([foot, 0.0]))
    >>> rows = _stacked([force(-9.0), force(-4.0), force(6.0)], 10.0)
    >>> [(item.row, item.side) for item in rows]
    [(1, 1.0), (0, 1.0), (0, 1.0)]
    """
    angles = {index: math.atan2(item.foot[1], item.foot[0])
              for index, item in enumerate(items) if item.arm * zoom >= 2.0}   # drawn
    out = list(items)
    done: set[int] = set()

    def together(first: int, second: int) -> bool:
        apart = abs((angles[first] - angles[second] + math.pi) % (2 * math.pi) - math.pi)
        shorter = min(items[first].arm, items[second].arm) * zoom
        return apart < math.pi / 2 and shorter * math.sin(apart) < SAME_LINE_PX

    for index in sorted(angles, key=angles.get):
        if index in done:
            continue
        group = [other for other in angles if other not in done and together(index, other)]
        done.update(group)
        direction = unit(items[group[0]].force)
        # step away from the images: against where they lie along the group's direction
        lean = sum(float(dot(items[k].image - items[k].foot, direction)) for k in group)
        side = -1.0 if lean > 0 else 1.0
        for row, k in enumerate(sorted(group, key=lambda k: (items[k].arm, items[k].number))):
            along = 1.0 if float(dot(unit(items[k].force), direction)) >= 0 else -1.0
            out[k] = replace(items[k], row=row, side=side * along)   # one side for all
    return out


def lever_forces_svg(forces: Any, plans, *, details: bool = True) -> str | None:
    """Zhukovsky's lever with its forces: the velocity plan turned 90° clockwise about its
    pole p, each known force drawn at the image of its point (unchanged in size and
    direction, at a force scale of the lever) with its arm h₁, h₂ … from p, each inertia
    couple as the force pair ±Mᵘ/l the sum counts, the balancing force F_b at the image of the
    crank pin, and beside the drawing the table of the moment sum ΣM_p = 0 that gives M_b;
    where points crowd, an enlarged detail (None without a lever from the drawn plan)."""
    lever = forces.solution.lever
    if plans is None or lever.source != VelocitySource.PLAN or not np.isfinite(
            lever.balancing_moment[0]):
        return None
    return within_page(lambda growth: _lever_page(forces, plans, details, growth))


def _lever_page(forces: Any, plans, details: bool, growth: float) -> tuple[Canvas, str]:
    """The lever's page with its drawing ``growth`` times its own size: its canvas and SVG."""
    page = _LeverFigure(forces, plans, growth)
    plan = page.plan
    figure, regions = laid_out(page.zoom, page.content, lambda canvas: {
        label: canvas.px(xy) for label, xy in page.turned.items()}, details)

    def column(at) -> float:
        """The plan's styles, the forces' and the table of the sum, top-left at ``at``."""
        bottom = plan_legend(figure, at, PlanKind.VELOCITY)
        bottom = _force_legend(figure, (at[0], bottom + 34 if bottom > at[1] else at[1]),
                               page.used, heading=message("Forces on the lever"))
        return _lever_table(figure, (at[0], bottom + 40), page)

    details = column_and_details(
        figure, page.content, regions, "detail-lever", column,
        crowded=_crowded_rows({label: (label_text(label, plan.numbers), xy)
                               for label, xy in page.turned.items()}, regions),
        title=FROM_POLE.replace(pole=plan.pole))
    figure.used.clear()
    lines = [*_lever_notes(forces, page), *details]
    title = render(message("{title} — Zhukovsky's lever with its forces, {phi} = {angle:g}°",
                           title=shown_title(forces.solution.mechanism.title),
                           phi=_phi(plans), angle=plans.angle)).lstrip(" —")
    frame(figure, title, lines, (plan.scale, SCALES["mu_v"].drawn, 0.3 * PLAN_SIZE),
          plan.flags, PlanKind.VELOCITY)
    return figure, figure.svg(title).svg


def _lever_table(figure: Canvas, at, page: _LeverFigure) -> float:
    """The table of the moment sum ΣM_p = 0 about the pole, term by term, the balancing
    force's last and the remainder under it; returns the y under it."""
    rows, total, magnitude = page.rows()
    balancing = page.balancing
    remainder = total + balancing.moment
    if abs(remainder) <= 1e-9 * (magnitude + abs(balancing.moment)):
        remainder = 0.0                               # zero to the rounding of the terms
    rows.append([render(BALANCING_FORCE), number_text(float(norm(balancing.force)), ".4g"),
                 f"h_{balancing.number}", number_text(balancing.arm, ".4g"),
                 _signed(balancing.moment)])
    rows.append(["ΣM_p", "", "", "", _signed(remainder, "+.2g")])
    header = [message("force"), message("F, N"), message("arm"), message("h, mm"),
              message("±F·h, N·mm")]
    return figure.table(at, rows, header=[render(cell) for cell in header],
                        right=[False, True, False, True, True],
                 title=render(message("ΣM_p = Σ ± F·h = 0 (counter-clockwise +)")))


def _signed(value: float, specification: str = "+.5g") -> str:
    """A term of the moment sum with its sign; a zero is 0, never +0 or −0.

    >>> _signed(-75.6691), _signed(0.0), _signed(-0.0, "+.2g")
    ('-75.669', '0', '0')
    """
    return number_text(value, specification) if value != 0 else number_text(0.0, "g")


def _lever_notes(forces: Any, page: _LeverFigure) -> list[str]:
    """The lines under the lever: its scales, how the forces are carried, and M_b by the
    lever against the groups'."""
    lever = forces.solution.lever
    drive = forces.solution.mechanism.drive
    length = forces.solution.mechanism.links[drive.link].length(drive.pivot,
                                                                lever.balancing_point)
    velocity, force = scale_text("mu_v", page.plan.scale), scale_text("mu_f", page.mu_f)
    if page.couples and page.mu_couple != page.mu_f:      # words: vocabulary (scale_text)
        scales = message("{velocity}; forces on the lever at {force}; couples' force pairs at "
                         "{couple}", velocity=velocity, force=force,
                         couple=scale_text("mu_f", page.mu_couple))
    else:
        scales = message("{velocity}; forces on the lever at {force}", velocity=velocity,
                         force=force)
    terms = ([render(message("a couple on a link with one point on the plan enters the sum as "
                             "its power over μv, M·ω/μv (no arm)"))] if page.terms else [])
    return [render(scales),
            render(message("each force at the image of its point, turned with the plan (size "
                           "and direction kept); arm h from the pole p")), *terms,
            render(message("|{moment}| = {force}·l_{pivot}{point} = {size:.5g} N × "
                           "{length:.4g} m;  {moment} = {lever:.6g} N·m (Zhukovsky's lever), "
                           "by the groups {groups:.6g} N·m", moment=BALANCING_MOMENT,
                           force=BALANCING_FORCE, pivot=drive.pivot,
                           point=lever.balancing_point,
                           size=float(norm(page.balancing.force)), length=length,
                           lever=float(lever.balancing_moment[0]),
                           groups=float(forces.solution.balancing_moment[0])))]


class _LoadedFigure:
    """The loaded mechanism being drawn: the mechanism at μl, a force scale, every force as
    an arrow at its point, every moment as a curved arrow, every centre of mass S marked —
    drawn on any canvas (:meth:`content`), so that a crowded region can be drawn again as a
    detail — and the list of it all (:meth:`rows`)."""

    def __init__(self, forces: Any, plans, growth: float = 1.0) -> None:
        self.position = position = plans.position
        self.solution = solution = forces.solution
        self.notation = ForceNotation(solution)
        everything = [item for item in solution.applied.items if item.link != "frame"]
        # friction (a force or moment in each pair, on both its links) is listed, not drawn
        self.friction = [item for item in everything if item.kind == AppliedKind.FRICTION]
        items = [item for item in everything if item.kind != AppliedKind.FRICTION]
        mu_l = position.mu_l
        #: (item, its point mm, its force N) of each force that is not zero
        self.arrows = [(item, np.asarray(item.point[0], float) / mu_l,
                        np.asarray(item.force[0], float))
                       for item in items if item.force is not None
                       and float(norm(np.asarray(item.force[0], float))) > 0]
        self.couples = [(item, float(item.moment[0])) for item in items
                        if item.moment is not None and float(item.moment[0]) != 0.0]
        #: each link's centre of mass (mm), by link
        self.centres = {link: np.asarray(inertia.centre[0], float) / mu_l
                        for link, inertia in solution.applied.inertia.items()
                        if link in position.links}
        points = list(position.points_mm.values())
        extent = max(max(p[0] for p in points) - min(p[0] for p in points),
                     max(p[1] for p in points) - min(p[1] for p in points), 1.0)
        largest = max((float(norm(force)) for _, _, force in self.arrows), default=0.0)
        self.mu_f = mu_f = standard(largest / (0.3 * extent)) if largest > 0 else 1.0
        ends = [tuple(start + force / mu_f) for _, start, force in self.arrows]
        self.zoom = growth * position_zoom(position, ends)
        #: the frame (mm) the lines of action are clipped to: the mechanism, its slides'
        #: guides, its centres of mass and its forces' arrows, with a margin round them
        framed = np.asarray(points + [tuple(s["through_mm"]) for s in position.slides]
                            + [tuple(c) for c in self.centres.values()] + ends, float)
        low, high = framed.min(axis=0), framed.max(axis=0)
        margin = FRAME_MARGIN * max(float(np.max(high - low)), 1.0)
        self.frame_mm = (*(low - margin), *(high + margin))
        self.balancing = float(solution.balancing_moment[0])
        self.balancing_runs = symbol_runs(BALANCING_MOMENT)
        self.used: dict[Message, tuple[str, str | None]] = {}

    def where(self, figure: Canvas) -> dict[str, np.ndarray]:
        """The points a detail watches: the mechanism's points and the centres of mass."""
        where = {name: figure.px(xy) for name, xy in self.position.points_mm.items()}
        return where | {f"S:{link}": figure.px(xy) for link, xy in self.centres.items()}

    def content(self, figure: Canvas) -> None:
        """The mechanism with its centres of mass, forces and moments, at ``figure``'s zoom."""
        mechanism_content(figure, self.position)
        for link, centre in self.centres.items():
            runs = (("S", RunKind.MAIN), (self.notation.number(link), RunKind.UPRIGHT))
            figure.circle(figure.px(centre), 3.0, fill="#ffffff", stroke=KNOWN_COLOURS["F"],
                          width=1.4, css="centre of mass", points=(f"S:{link}",))
            figure.request((f"S:{link}",), figure.px(centre), runs, mark=3.0)
        for item, start, force in self.arrows:
            self._force(figure, item, start, force)
        for item, moment in self.couples:
            inertia = self.solution.applied.inertia.get(item.link)
            mu_l = self.position.mu_l
            centre = (np.asarray(item.point[0], float) / mu_l if item.point is not None
                      else np.asarray(inertia.centre[0], float) / mu_l
                      if item.kind == AppliedKind.INERTIA_MOMENT and inertia is not None
                      else _link_centre(self.position, item.link))
            colour = _force_colour(item.name)
            turning_arrow(figure, centre, 26.0, math.pi / 2, 1.0 if moment > 0 else -1.0,
                          colour, f"moment:{item.name}:{item.link}",
                          self.notation.runs(item.name, item.link), css="moment")
            self.used.setdefault(_LOADED_LEGEND["moment"], ("relative", colour))
        drive = self.solution.mechanism.drive
        if self.balancing and drive.pivot in self.position.points_mm:
            turning_arrow(figure, self.position.points_mm[drive.pivot], 40.0, -math.pi / 2,
                          1.0 if self.balancing > 0 else -1.0, INK, "moment:M_b",
                          self.balancing_runs, css="balancing moment")
            self.used[_LOADED_LEGEND["balancing"]] = ("result", None)

    def _force(self, figure: Canvas, item, start: np.ndarray, force: np.ndarray) -> None:
        """A force as an arrow at its point; an inertia force with the line of its single
        equivalent force (with Mᵘ), h = J·ε/(m·a_S) from S."""
        colour = _force_colour(item.name)
        begin, end = figure.px(start), figure.px(start + force / self.mu_f)
        figure.arrow(begin, end, "relative", layer="results", color=colour, css="load")
        figure.request((f"force:{item.name}:{item.link}",), begin + 0.65 * (end - begin),
                       self.notation.runs(item.name, item.link), mark=2.0, span=(begin, end))
        self.used.setdefault(_legend_key_of(item.name), ("relative", colour))
        shift = self._single_force_shift(item, force)
        if shift is not None and float(norm(shift)) * figure.zoom >= 1.5:
            self._line_of_action(figure, start, shift, force, colour)

    def _line_of_action(self, figure: Canvas, start: np.ndarray, shift: np.ndarray,
                        force: np.ndarray, colour: str) -> None:
        """The line of an inertia force's single equivalent force, ``shift`` (mm) from its
        point ``start``, within the mechanism's frame (:attr:`frame_mm`): a piece of it
        round the foot of the perpendicular from S, else its chord of the frame; where it
        misses the frame, a dashed pointer from S to the frame's edge towards it (its h is
        in the table)."""
        foot, along = start + shift, force / self.mu_f
        piece = _clipped(foot - 0.6 * along, foot + 1.2 * along, self.frame_mm)
        if piece is None:
            reach = float(norm(shift)) + float(np.hypot(self.frame_mm[2] - self.frame_mm[0],
                                                        self.frame_mm[3] - self.frame_mm[1]))
            piece = _clipped(foot - reach * unit(force), foot + reach * unit(force),
                             self.frame_mm)
        dash = STYLES["construction"].dash
        if piece is not None:
            figure.line(figure.px(piece[0]), figure.px(piece[1]), color=colour, width=0.8,
                        dash=dash, layer="construction", css="inertia line")
            self.used.setdefault(_LOADED_LEGEND["line"], ("construction", colour))
            return
        edge = _clipped(start, foot, self.frame_mm)
        if edge is None or float(norm(edge[1] - edge[0])) * figure.zoom < 12.0:
            return
        tip = figure.px(edge[1])
        figure.line(figure.px(edge[0]), tip, color=colour, width=0.8, dash=dash,
                    layer="construction", css="inertia line off")
        arrowhead(figure, tip, unit(figure.px(foot) - figure.px(start)), 8.0, colour,
                  "construction", css="inertia line off")
        self.used.setdefault(_OFF_THE_FIGURE, ("construction", colour))

    def _single_force_shift(self, item, force: np.ndarray) -> np.ndarray | None:
        """How far (mm) the single equivalent inertia force's line lies from S, or None."""
        inertia = self.solution.applied.inertia.get(item.link)
        if item.kind != AppliedKind.INERTIA_FORCE or inertia is None or not bool(
                inertia.single_force_defined[0]) or not abs(float(inertia.offset[0])) > 0:
            return None
        return float(inertia.offset[0]) * perp(unit(force)) / self.position.mu_l

    def rows(self) -> list[list[str]]:
        """The table beside the drawing: each force and moment, its size, its link."""
        notation = self.notation
        rows = []
        for item, _, force in self.arrows:
            shift = self._single_force_shift(item, force)
            offset = abs(float(self.solution.applied.inertia[item.link].offset[0])
                         ) if shift is not None else 0.0
            note = (render(message("with {symbol}: one force on a line h = {offset:.4g} m from "
                                   "S", symbol=INERTIA_MOMENT, offset=offset))
                    if shift is not None else "")
            rows.append([notation.plain(item.name, item.link),
                         render(message("{size:.4g} N", size=float(norm(force)))),
                         notation.link_name(item.link), note])
        for item, moment in self.couples:
            rows.append([notation.plain(item.name, item.link),
                         render(message("{size:.4g} N·m", size=abs(moment))),
                         notation.link_name(item.link), render(_SENSE[moment > 0])])
        for item in self.friction:
            size = (message("{size:.4g} N", size=_size(item)) if item.force is not None
                    else message("{size:.4g} N·m", size=_size(item)))
            rows.append([notation.plain(item.name, item.link), render(size),
                         notation.link_name(item.link), render(message("friction (not drawn)"))])
        if self.balancing:
            rows.append([render(BALANCING_MOMENT),
                         render(message("{size:.6g} N·m", size=abs(self.balancing))),
                         notation.link_name(self.solution.mechanism.drive.link),
                         render(message("{sense}, applied by the motor",
                                        sense=_SENSE[self.balancing > 0]))])
        return rows


#: the sense of a moment: counter-clockwise (positive) or clockwise
_SENSE = {True: message("counter-clockwise"), False: message("clockwise")}


def loaded_svg(forces: Any, plans, *, details: bool = True) -> str | None:
    """The loaded mechanism: the mechanism at the solved position with every force and moment
    acting on it — weights G, inertia forces Fᵘ at the centres of mass S (each marked) with the
    line of their single equivalent force (offset h = J·ε/(m·a_S)), inertia moments Mᵘ,
    loads, and the balancing moment M_b on the crank — with their list (friction too) in a
    table beside the drawing, and an enlarged detail where points crowd: the picture a force
    analysis starts from (None without plans)."""
    if plans is None:
        return None
    return within_page(lambda growth: _loaded_page(forces, plans, details, growth))


def _loaded_page(forces: Any, plans, details: bool, growth: float) -> tuple[Canvas, str]:
    """The loaded mechanism's page with its drawing ``growth`` times its own size: its canvas
    and SVG."""
    page = _LoadedFigure(forces, plans, growth)
    mechanism = forces.solution.mechanism
    figure, regions = laid_out(page.zoom, page.content, page.where, details)

    def column(at) -> float:
        """The forces' legend and their table, top-left at ``at``."""
        bottom = _force_legend(figure, at, page.used, heading=message("Forces and moments"))
        header = [message("force"), message("size"), message("on")]
        return figure.table((at[0], bottom + 40), page.rows(),
                            header=[*(render(cell) for cell in header), ""],
                            right=[False, True, False, False],
                            title=render(message("Forces and moments on the links")))

    named = {name: (label_text(name), xy) for name, xy in page.position.points_mm.items()}
    named |= {f"S:{link}": (numbered("S", page.notation.number(link)), xy)
              for link, xy in page.centres.items()}
    details = column_and_details(figure, page.content, regions, "detail-loaded", column,
                                 crowded=_crowded_rows(named, regions), title=ON_THE_DRAWING)
    lines = [render(message("{length}; forces at {force}",          # words: vocabulary
                            length=scale_text("mu_l", page.position.mu_l),
                            force=scale_text("mu_f", page.mu_f))),
             render(message("{phi} = {angle:g}°, {omega} = {speed:.6g} rad/s", phi=_phi(plans),
                            angle=plans.angle, omega=_phi(plans, "ω"),
                            speed=mechanism.drive.omega)), *details]
    title = render(message("{title} — the loaded mechanism, {phi} = {angle:g}°",
                           title=shown_title(mechanism.title), phi=_phi(plans),
                           angle=plans.angle)).lstrip(" —")
    frame(figure, title, lines, (page.position.mu_l, SCALES["mu_l"].drawn,
                                 0.25 * MECHANISM_SIZE),
          [render(flag) for flag in forces.solution.flags], PlanKind.POSITION)
    return figure, figure.svg(title).svg


#: the legend entries of the loaded mechanism's moments and lines
_LOADED_LEGEND = {
    "moment": message("moment (curved arrow: its sense)"),
    "balancing": message("balancing moment {symbol} on the crank", symbol=BALANCING_MOMENT),
    "line": message("line of the single equivalent inertia force (h from S)"),
    "inertia": message("inertia force {symbol} = −m·a_S at S", symbol=INERTIA_FORCE)}


#: the legend entry of a pointer towards a line of action that misses the figure
_OFF_THE_FIGURE = message("towards the line of the single equivalent inertia force, off the "
                          "figure (h in the table)")
#: the margin round the mechanism (a fraction of its extent) that lines of action are
#: clipped to, so that a long h never stretches the figure
FRAME_MARGIN = 0.15


def _clipped(start: np.ndarray, end: np.ndarray, box) -> tuple[np.ndarray, np.ndarray] | None:
    """The part of the segment from ``start`` to ``end`` inside ``box`` (x0, y0, x1, y1), or
    None (Liang–Barsky).

    >>> [p.tolist() for p in _clipped(np.array([-5.0, 0.0]), np.array([5.0, 0.0]),
    ...                               (0.0, -1.0, 2.0, 1.0))]
    [[0.0, 0.0], [2.0, 0.0]]
    """
    span = inside_span(start, end, box)
    if span is None:
        return None
    return start + span[0] * (end - start), start + span[1] * (end - start)


def _legend_key_of(name: str) -> Message:
    if name.startswith(("M_f", "F_f")):
        return _FRICTION_FORCE
    if name[:1] == "F":
        return _LOADED_LEGEND["inertia"]
    return _WEIGHT if name[:1] == "G" else _EXTERNAL_LOAD


def _size(item) -> float:
    """The size of a known force (N) or moment (N·m) at the first angle."""
    if item.force is not None:
        return float(norm(np.asarray(item.force[0], float)))
    return abs(float(item.moment[0]))


def _link_centre(position, link: str) -> tuple[float, float]:
    points = [position.points_mm[p] for p in position.links.get(link, ())
              if p in position.points_mm]
    if not points:
        return (0.0, 0.0)
    return (sum(p[0] for p in points) / len(points), sum(p[1] for p in points) / len(points))


def _file_name(index: int, group) -> str:
    name = re.sub(r"[^A-Za-z0-9_+-]", "_", group.name)
    return f"forces_{index}_{name}.svg"


def force_files(forces: Any, plans, *, loaded: bool = True, details: bool = True,
                views: Mapping[str, SteadyView] | None = None) -> dict[str, str]:
    """``{"forces_<n>_<group>.svg": …, "combined_force.svg": …, "lever.svg": …,
    "loaded.svg": …}`` for one crank angle. With ``views`` (frames of a turn,
    :func:`planmethod.render.steady.steady_views`) the polygons and the combined force keep
    one force scale, zoom and page over the turn, and neither the lever with its forces nor
    the loaded mechanism is drawn (their force scales follow each angle's forces)."""
    files: dict[str, str] = {}
    title = shown_title(forces.solution.mechanism.title)
    notation = ForceNotation(forces.solution)
    for number, group in enumerate(forces.solution.groups.groups, start=1):
        files[_file_name(number, group)] = polygon_svg(
            group, forces.mu_f, angle=forces.angle, notation=notation, details=details,
            view=(views or {}).get(f"forces_{number}"),
            title=render(message(
                "{title} — force polygon {number}: {group}, {phi} = {angle:g}°", title=title,
                number=number, group=notation.group_name(group),
                phi=numbered("φ", notation.numbers[forces.solution.mechanism.drive.link]),
                angle=forces.angle)))
    combined = combined_svg(forces, plans, view=(views or {}).get("combined_force"),
                            details=details)
    if combined is not None:
        files["combined_force.svg"] = combined
    if views:
        return files
    lever = lever_forces_svg(forces, plans, details=details)
    if lever is not None:
        files["lever.svg"] = lever
    drawing = loaded_svg(forces, plans, details=details) if loaded else None
    if drawing is not None:
        files["loaded.svg"] = drawing
    return files
