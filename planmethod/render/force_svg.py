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
from typing import Any

import numpy as np

from ..plans.scales import standard
from ..vectors import cross, dot, norm, perp, unit
from ..vocabulary import (
    SCALES,
    AppliedKind,
    EdgeKind,
    GroupKind,
    PlanKind,
    numbered,
    scale_text,
    subscript,
)
from .canvas import Canvas, fit_zoom
from .labels import RunKind, label_runs
from .notation import ForceNotation
from .style import INK, SMALL_SIZE, STYLES, TEXT_SIZE, significant
from .svg import (
    MECHANISM_SIZE,
    PLAN_SIZE,
    crank_number,
    frame,
    mechanism_content,
    plan_content,
    plan_legend,
    position_zoom,
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
    EdgeKind.REACTION: ("result", None, "reaction found by closing the polygon"),
    EdgeKind.TRANSMITTED: ("relative", KNOWN_COLOURS["R"], "reaction from a group solved before"),
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
                notation: ForceNotation | None = None) -> str:
    """One group's force polygon (see the module docstring); ``index`` picks the crank angle
    of a vectorised solve; ``notation`` prints the forces as a course writes them (R₁₂, G₃),
    else by their report names."""
    edges = [edge for edge in group.polygon if float(norm(edge.vector[index])) > 0]
    vectors = [edge.vector[index] / mu_f for edge in edges]
    corners = [np.zeros(2)]
    for vector in vectors:
        corners.append(corners[-1] + vector)
    figure = Canvas(fit_zoom([tuple(c) for c in corners], PLAN_SIZE))
    where = [figure.px(c) for c in corners]
    used: dict[str, tuple[str, str | None]] = {}
    for number, (edge, start, end) in enumerate(zip(edges, where[:-1], where[1:],
                                                    strict=True)):
        style, colour = _edge_style(edge)
        if figure.arrow(start, end, style, layer="components", color=colour,
                        css=f"force {edge.kind}", step=number + 1):
            used.setdefault(_legend_key(edge), (style, colour))
        middle = start + 0.5 * (end - start)
        runs = notation.runs(edge.label, edge.link) if notation else _runs(edge.label)
        figure.request((edge.label,), middle, runs, mark=2.0)
    count = len(edges)
    for name, first, _ in _totals(edges, vectors):
        on = edges[first].link
        after = first + 2  # the corner after the second component (cyclically)
        start, end = where[first], where[after if after <= count else after - count]
        if figure.arrow(start, end, "result", layer="results", css="force total"):
            used.setdefault("whole reaction R = Rⁿ + Rᵗ", ("result", None))
            middle = start + 0.5 * (end - start)
            figure.request((name,), middle,
                           notation.runs(name, on) if notation else _runs(name), mark=2.0)
    figure.circle(where[0], 3.4, fill=INK, css="start")
    closure = float(norm(corners[-1] - corners[0]))
    figure.place()
    _, y0, x1, _ = figure.extent
    _force_legend(figure, (x1 + 34, y0 + 4), used)
    terms = " + ".join(notation.plain(edge.label, edge.link) if notation else edge.label
                       for edge in edges)
    lines = [scale_text("mu_f", mu_f), f"ΣF = 0: {terms} = 0",
             f"the polygon closes to {closure:.2g} mm"]
    lines += [notation.line(step, group.links) if notation else step for step in group.steps]
    lines = [line.replace("⟂", "⊥") for line in lines]   # ⊥ is in every common font
    frame(figure, title, lines, (mu_f, SCALES["mu_f"].drawn, 0.3 * PLAN_SIZE), (), "force")
    return figure.svg(title).svg


def _legend_key(edge) -> str:
    if edge.kind == EdgeKind.COMPONENT:
        return ("tangential component Rᵗ (⊥ the link)" if edge.label.startswith("Rᵗ")
                else "normal component Rⁿ (along the link) or N (⊥ a guide)")
    if edge.kind in _EDGE_LOOKS:
        return _EDGE_LOOKS[edge.kind][2]
    if edge.label.startswith(("M_f", "F_f")):
        return "friction force"
    return {"G": "weight G", "F": "inertia force Fᵘ = −m·a_S"}.get(edge.label[:1],
                                                                  "external load")


def _force_legend(figure: Canvas, at, used: dict, heading: str = "Legend") -> None:
    x, y = at
    if not used:
        return
    figure.text((x, y), heading, size=TEXT_SIZE, bold=True, css="legend", area=False)
    y += 8
    for text, (style, colour) in used.items():
        y += 20
        figure.arrow((x, y - 4), (x + 34, y - 4), style, layer="text", color=colour)
        figure.obstacle_lines.pop()
        figure.text((x + 44, y), text, size=SMALL_SIZE, css="legend", area=False)


def combined_svg(forces, plans) -> str | None:
    """Aliyev's combined-force construction on the acceleration plan (None without one, and
    None where no gravity acts: with g = 0 the moved pole π′ is π and the construction is the
    inertia forces alone; see :func:`combined_omitted`)."""
    combined = forces.combined
    if combined is None or plans is None or plans.acceleration is None:
        return None
    if not combined.g:
        return None
    plan = plans.acceleration
    points = dict(plan.points_mm)
    new_pole = combined.new_pole_mm
    extra = [new_pole] + [f.image_mm for f in combined.forces]
    figure = Canvas(fit_zoom(list(points.values()) + extra, PLAN_SIZE))
    plan_content(figure, points, plan.steps, plan.pole, numbers=plan.numbers)
    pole_px, new_px = figure.px((0.0, 0.0)), figure.px(new_pole)
    if combined.gravity_image_mm > 0:
        figure.arrow(pole_px, new_px, "normal", layer="results", color=KNOWN_COLOURS["G"],
                     css="gravity image")
        figure.request(("Z_g",), pole_px + 0.5 * (new_px - pole_px), _runs("Z_g"), mark=2.0)
    figure.circle(new_px, 3.4, fill=KNOWN_COLOURS["F"], css="new pole")
    figure.request(("π′",), new_px, (("π′", RunKind.MAIN),), mark=3.4)
    notation = ForceNotation(forces.solution)
    for force in combined.forces:
        s = figure.px(force.image_mm)
        figure.circle(s, 2.6, fill=KNOWN_COLOURS["F"], css="centre of mass image")
        figure.request((f"s_{force.link}",), s,
                       (("s", RunKind.MAIN), (notation.number(force.link), RunKind.SUB)), mark=2.6)
        if float(norm(np.asarray(force.segment_mm))) * figure.zoom >= 1.0:
            figure.arrow(s, new_px, "tangential", layer="results", color=KNOWN_COLOURS["F"],
                         css=f"combined {force.link}")
    figure.place()
    _, y0, x1, _ = figure.extent
    bottom = plan_legend(figure, (x1 + 34, y0 + 4), PlanKind.ACCELERATION)  # the plan's styles
    _force_legend(figure, (x1 + 34, bottom + 34 if bottom > y0 + 4 else y0 + 4), {
        "image of g: π → π′, Z_g = g/μa": ("normal", KNOWN_COLOURS["G"]),
        "s → π′ = (g − a_S)/μa: Q = m·μa·(s π′)": ("tangential", KNOWN_COLOURS["F"])},
        heading="Combined force (Aliyev)")
    figure.used.clear()
    lines = [f"{scale_text('mu_a', combined.mu_a)}; g = {combined.g:g} m/s², "
             f"Z_g = g/μa = {combined.gravity_image_mm:.4g} mm"]
    for force in combined.forces:
        length = float(norm(np.asarray(force.segment_mm)))
        q = float(norm(np.asarray(force.from_plan)))
        sub = subscript(notation.number(force.link))
        lines.append(f"{notation.link_name(force.link)}: (s{sub}π′) = {length:.4g} mm → "
                     f"Q{sub} = m{sub}·μa·(s{sub}π′) = {force.mass:g}·"
                     f"{significant(combined.mu_a, 4)}·{length:.4g} = {q:.5g} N")
    title = (f"{plans.exercise.mechanism.title} — Q = G + Fᵘ on the acceleration plan, "
             f"pole moved to π′, {_phi(plans)} = {plans.angle:g}°")
    frame(figure, title, lines, None, plan.flags, PlanKind.ACCELERATION)
    return figure.svg(title).svg


def combined_omitted(forces, plans) -> str | None:
    """Why the combined-force figure is not drawn, in one line (None when it is, or when the
    analysis has no combined-force construction at all)."""
    combined = getattr(forces, "combined", None)
    if combined is None or plans is None or plans.acceleration is None or combined.g:
        return None
    return ("combined_force.svg is not drawn: no gravity acts (g = 0), so the moved pole π′ "
            "is π and Q = G + Fᵘ is the inertia force alone")


def _phi(plans, letter: str = "φ") -> str:
    """The crank's φ (or ω, ε) with the crank's number, as the course writes it."""
    return numbered(letter, crank_number(plans.position))


def _force_colour(name: str) -> str:
    if name.startswith(("M_f", "F_f")):
        return FRICTION
    if name.startswith("M_u"):
        return KNOWN_COLOURS["F"]
    return KNOWN_COLOURS.get(name[:1], KNOWN_COLOURS["l"])


class _LeverFigure:
    """Zhukovsky's lever being drawn: the turned velocity plan, the force scale of the
    lever, and each force at the image of its point with its arm from the pole."""

    def __init__(self, forces: Any, plans) -> None:
        lever = forces.solution.lever
        self.notation = ForceNotation(forces.solution)
        self.plan = plan = plans.velocity
        turned = {label: (float(y), float(-x)) for label, (x, y) in plan.points_mm.items()}
        items = [(force.name, force.link, np.asarray(force.image_mm[0], float),
                  np.asarray(force.force[0], float), float(force.moment[0]))
                 for force in lever.forces]
        #: (name, link, image mm, force N, moment N·mm) of each force that is not zero
        self.items = [item for item in items if float(norm(item[3])) > 0]
        self.balancing = np.asarray(lever.balancing_force[0], float)
        self.pin = np.asarray(lever.balancing_image_mm[0], float)
        largest = max([float(norm(force)) for _, _, _, force, _ in self.items]
                      + [float(norm(self.balancing))])
        points = list(turned.values())
        extent = max(max(abs(c) for xy in points for c in xy), 1.0)
        #: the force scale of the lever (N/mm)
        self.mu_f = mu_f = standard(largest / (0.45 * extent)) if largest > 0 else 1.0
        ends = [tuple(image + force / mu_f) for _, _, image, force, _ in self.items]
        self.figure = Canvas(fit_zoom(points + ends + [tuple(self.pin + self.balancing / mu_f)],
                                      PLAN_SIZE))
        plan_content(self.figure, turned, plan.steps, plan.pole, rotate_deg=-90.0,
                     numbers=plan.numbers)
        self.pole = self.figure.px((0.0, 0.0))
        self.used: dict[str, tuple[str, str | None]] = {}

    def draw(self, name: str, image: np.ndarray, force: np.ndarray, colour: str, style: str,
             runs) -> float:
        """The force at its image with its arm from p; returns the arm h (mm)."""
        figure, mu_f = self.figure, self.mu_f
        start, end = figure.px(image), figure.px(image + force / mu_f)
        figure.arrow(start, end, style, layer="results", color=colour, css="lever force")
        figure.request((f"force:{name}",), start + 0.6 * (end - start), runs, mark=2.0)
        direction = unit(force)
        foot = image - float(dot(image, direction)) * direction
        arm = float(norm(foot))
        if arm <= 1e-9 * max(float(norm(image)), 1.0):
            arm = 0.0                    # the line passes through p (rounding left over)
        if arm * figure.zoom >= 2.0:
            figure.line(self.pole, figure.px(foot), color=colour, width=0.7, dash="1.5,2.5",
                        layer="construction", css="arm", obstacle=False)
            reach = max(4.0 / figure.zoom, float(dot(image - foot, direction)))
            figure.line(figure.px(foot), figure.px(foot + direction * reach), color=colour,
                        width=0.5, dash="4,3", layer="construction", css="line of action",
                        obstacle=False)
        return arm

    def known_forces(self) -> tuple[list[str], float, float]:
        """Each known force drawn; the sum's lines, Σ M and Σ |M| (N·mm)."""
        lines = []
        total = magnitude = 0.0      # the sum is zero to rounding of Σ|M|
        couples: dict[str, float] = {}
        for name, link, image, force, moment in self.items:
            base, _, at = name.partition(" at ")
            total += moment
            magnitude += abs(moment)
            if at:     # a couple, carried as two forces ±M/l ⊥ the link: listed, not drawn
                couples[base] = couples.get(base, 0.0) + moment
                continue
            colour = _force_colour(base)
            arm = self.draw(name, image, force, colour, "relative",
                            self.notation.runs(base, link))
            self.used.setdefault("known force at the image of its point, arm h from p",
                                 ("relative", colour))
            lines.append(f"  {self.notation.plain(base, link)}: {float(norm(force)):.4g} N × "
                         f"h {arm:.4g} mm = {(moment if arm else 0.0) + 0.0:+.5g} N·mm")
        for base, moment in couples.items():
            lines.append(f"  {self.notation.plain(base)} (a couple, as ±M/l at two points of "
                         f"its link): {moment + 0.0:+.5g} N·mm")
        return lines, total, magnitude

    def balancing_force(self, total: float, magnitude: float) -> tuple[str, float]:
        """The balancing force drawn; its line of the sum and its size (N)."""
        runs = (("F", RunKind.MAIN), ("b", RunKind.SUB))
        arm = self.draw("F_b", self.pin, self.balancing, INK, "result", runs)
        moment = float(cross(self.pin, self.balancing))
        self.used["balancing force F_b (⊥ the crank) at the image of the crank pin"] = (
            "result", None)
        size = float(norm(self.balancing))
        remainder = total + moment
        if abs(remainder) <= 1e-9 * (magnitude + abs(moment)):
            remainder = 0.0                               # zero to the rounding of the terms
        return (f"  F_b: {size:.4g} N × h {arm:.4g} mm = {moment + 0.0:+.5g} N·mm;  "
                f"sum {remainder + 0.0:+.2g} N·mm"), size


def lever_forces_svg(forces: Any, plans) -> str | None:
    """Zhukovsky's lever with its forces: the velocity plan turned 90° clockwise about its
    pole p, each known force drawn at the image of its point (unchanged in size and
    direction, at a force scale of the lever), its arm h from p, the balancing force F_b at the
    image of the crank pin, and the moment sum ΣM_p = 0 that gives M_b (None without a lever
    from the drawn plan)."""
    lever = forces.solution.lever
    if plans is None or lever.source != "velocity plan" or not np.isfinite(
            lever.balancing_moment[0]):
        return None
    page = _LeverFigure(forces, plans)
    figure, plan = page.figure, page.plan
    lines = [f"{scale_text('mu_v', plan.scale)}; forces on the lever at "
             f"{scale_text('mu_f', page.mu_f)}",
             "each force at the image of its point, turned with the plan (size and direction "
             "kept); arm h from the pole p",
             "ΣM_p = Σ ± F·h = 0 (N·mm on the lever, counter-clockwise +):"]
    terms, total, magnitude = page.known_forces()
    balancing, size_b = page.balancing_force(total, magnitude)
    lines += [*terms, balancing]
    mechanism = forces.solution.mechanism
    drive = mechanism.drive
    length = mechanism.links[drive.link].length(drive.pivot, lever.balancing_point)
    lines.append(f"|M_b| = F_b·l_{drive.pivot}{lever.balancing_point} = {size_b:.5g} N × "
                 f"{length:.4g} m;  M_b = {float(lever.balancing_moment[0]):.6g} N·m "
                 f"(Zhukovsky's lever), by the groups "
                 f"{float(forces.solution.balancing_moment[0]):.6g} N·m")
    figure.place()
    _, y0, x1, _ = figure.extent
    bottom = plan_legend(figure, (x1 + 34, y0 + 4), PlanKind.VELOCITY)   # the plan's styles
    _force_legend(figure, (x1 + 34, bottom + 34 if bottom > y0 + 4 else y0 + 4), page.used,
                  heading="Forces on the lever")
    figure.used.clear()
    title = (f"{mechanism.title} — Zhukovsky's lever with its forces, "
             f"{_phi(plans)} = {plans.angle:g}°").lstrip(" —")
    frame(figure, title, lines, (plan.scale, SCALES["mu_v"].drawn, 0.3 * PLAN_SIZE),
          plan.flags, PlanKind.VELOCITY)
    return figure.svg(title).svg


class _LoadedFigure:
    """The loaded mechanism being drawn: the mechanism at μl and a force scale, and one
    method per kind of load (forces as arrows, moments as curved arrows, friction listed)."""

    def __init__(self, forces: Any, plans) -> None:
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
        points = list(position.points_mm.values())
        extent = max(max(p[0] for p in points) - min(p[0] for p in points),
                     max(p[1] for p in points) - min(p[1] for p in points), 1.0)
        largest = max((float(norm(force)) for _, _, force in self.arrows), default=0.0)
        self.mu_f = mu_f = standard(largest / (0.3 * extent)) if largest > 0 else 1.0
        ends = [tuple(start + force / mu_f) for _, start, force in self.arrows]
        self.figure = Canvas(position_zoom(position, ends))
        mechanism_content(self.figure, position)
        self.used: dict[str, tuple[str, str | None]] = {}

    def forces(self) -> list[str]:
        """Each force as an arrow at its point (an inertia force with the line of its single
        equivalent force); a line of the list for each."""
        figure, notation, mu_f, mu_l = self.figure, self.notation, self.mu_f, self.position.mu_l
        lines = []
        for item, start, force in self.arrows:
            colour = _force_colour(item.name)
            begin, end = figure.px(start), figure.px(start + force / mu_f)
            figure.arrow(begin, end, "relative", layer="results", color=colour, css="load")
            figure.request((f"force:{item.name}:{item.link}",), begin + 0.65 * (end - begin),
                           notation.runs(item.name, item.link), mark=2.0)
            self.used.setdefault(_legend_key_of(item.name), ("relative", colour))
            line = (f"{notation.plain(item.name, item.link)} = {float(norm(force)):.4g} N on "
                    f"{notation.link_name(item.link)}")
            inertia = self.solution.applied.inertia.get(item.link)
            if item.kind == AppliedKind.INERTIA_FORCE and inertia is not None and bool(
                    inertia.single_force_defined[0]) and abs(float(inertia.offset[0])) > 0:
                # the line of the single equivalent force Fᵘ (with Mᵘ), offset by h from S
                shift = float(inertia.offset[0]) * perp(unit(force)) / mu_l
                if float(norm(shift)) * figure.zoom >= 1.5:
                    figure.line(figure.px(start + shift - 0.6 * force / mu_f),
                                figure.px(start + shift + 1.2 * force / mu_f), color=colour,
                                width=0.8, dash=STYLES["construction"].dash,
                                layer="construction", css="inertia line", obstacle=False)
                    self.used.setdefault("line of the single equivalent inertia force "
                                         "(h from S)", ("construction", colour))
                    line += (f"; with Mᵘ, one force on a line h = "
                             f"{abs(float(inertia.offset[0])):.4g} m from S")
            lines.append(line)
        return lines

    def moments(self) -> list[str]:
        """Each moment as a curved arrow round its centre; a line of the list for each."""
        notation, mu_l = self.notation, self.position.mu_l
        lines = []
        for item, moment in self.couples:
            inertia = self.solution.applied.inertia.get(item.link)
            centre = (np.asarray(item.point[0], float) / mu_l if item.point is not None
                      else np.asarray(inertia.centre[0], float) / mu_l
                      if item.kind == AppliedKind.INERTIA_MOMENT and inertia is not None
                      else _link_centre(self.position, item.link))
            colour = _force_colour(item.name)
            turning_arrow(self.figure, centre, 26.0, math.pi / 2, 1.0 if moment > 0 else -1.0,
                          colour, f"moment:{item.name}:{item.link}",
                          notation.runs(item.name, item.link), css="moment")
            self.used.setdefault("moment (curved arrow: its sense)", ("relative", colour))
            lines.append(f"{notation.plain(item.name, item.link)} = {abs(moment):.4g} N·m "
                         f"{'counter-clockwise' if moment > 0 else 'clockwise'} on "
                         f"{notation.link_name(item.link)}")
        return lines

    def friction_lines(self) -> list[str]:
        """The friction in the pairs, listed (not drawn)."""
        if not self.friction:
            return []
        listed = [f"{self.notation.plain(item.name, item.link)} {_size(item):.4g}"
                  for item in self.friction]
        lines = ["friction (not drawn; N·m, N): " + ", ".join(listed[:8])]
        for start in range(8, len(listed), 10):
            lines.append("  " + ", ".join(listed[start:start + 10]))
        return lines

    def balancing_moment(self) -> list[str]:
        """The balancing moment on the crank as a curved arrow round its pivot."""
        drive = self.solution.mechanism.drive
        balancing = float(self.solution.balancing_moment[0])
        if not balancing or drive.pivot not in self.position.points_mm:
            return []
        turning_arrow(self.figure, self.position.points_mm[drive.pivot], 40.0, -math.pi / 2,
                      1.0 if balancing > 0 else -1.0, INK, "moment:M_b",
                      (("M", RunKind.MAIN), ("b", RunKind.SUB)), css="balancing moment")
        self.used["balancing moment M_b on the crank"] = ("result", None)
        return [f"M_b = {abs(balancing):.6g} N·m "
                f"{'counter-clockwise' if balancing > 0 else 'clockwise'} on "
                f"{self.notation.link_name(drive.link)} (to be applied by the motor)"]


def loaded_svg(forces: Any, plans) -> str | None:
    """The loaded mechanism: the mechanism at the solved position with every force and moment
    acting on it — weights G, inertia forces Fᵘ at the centres of mass with the line of their
    single equivalent force (offset h = J·ε/(m·a_S)), inertia moments Mᵘ, loads, friction, and
    the balancing moment M_b on the crank — the picture a force analysis starts from (None
    without plans)."""
    if plans is None:
        return None
    page = _LoadedFigure(forces, plans)
    figure, mechanism = page.figure, forces.solution.mechanism
    lines = [f"{scale_text('mu_l', page.position.mu_l)}; forces at "
             f"{scale_text('mu_f', page.mu_f)}",
             f"{_phi(plans)} = {plans.angle:g}°, {_phi(plans, 'ω')} = "
             f"{significant(mechanism.drive.omega, 6)} rad/s"]
    lines += page.forces()
    lines += page.moments()
    lines += page.friction_lines()
    lines += page.balancing_moment()
    figure.place()
    _, y0, x1, _ = figure.extent
    _force_legend(figure, (x1 + 34, y0 + 4), page.used, heading="Forces and moments")
    title = (f"{mechanism.title} — the loaded mechanism, {_phi(plans)} = {plans.angle:g}°"
             .lstrip(" —"))
    frame(figure, title, lines, (page.position.mu_l, SCALES["mu_l"].drawn,
                                 0.25 * MECHANISM_SIZE), forces.solution.flags,
          PlanKind.POSITION)
    return figure.svg(title).svg


def _legend_key_of(name: str) -> str:
    if name.startswith(("M_f", "F_f")):
        return "friction force"
    return {"G": "weight G", "F": "inertia force Fᵘ = −m·a_S at S"}.get(name[:1],
                                                                      "external load")


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


def force_files(forces: Any, plans, *, loaded: bool = True) -> dict[str, str]:
    """``{"forces_<n>_<group>.svg": …, "combined_force.svg": …}`` for one crank angle."""
    files: dict[str, str] = {}
    title = forces.solution.mechanism.title
    notation = ForceNotation(forces.solution)
    for number, group in enumerate(forces.solution.groups.groups, start=1):
        kind = "drive link" if group.kind == GroupKind.DRIVE else f"{group.kind} of"
        files[_file_name(number, group)] = polygon_svg(
            group, forces.mu_f, angle=forces.angle, notation=notation,
            title=f"{title} — force polygon {number}: {kind} {notation.links(group.links)}, "
                  f"{numbered('φ', notation.numbers[forces.solution.mechanism.drive.link])} = "
                  f"{forces.angle:g}°")
    combined = combined_svg(forces, plans)
    if combined is not None:
        files["combined_force.svg"] = combined
    lever = lever_forces_svg(forces, plans)
    if lever is not None:
        files["lever.svg"] = lever
    drawing = loaded_svg(forces, plans) if loaded else None
    if drawing is not None:
        files["loaded.svg"] = drawing
    return files
