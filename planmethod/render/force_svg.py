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
* :func:`force_files` — all of them as ``{file name: SVG text}`` for ``planmethod solve --svg``.

The figures are drawn on the one canvas (:mod:`planmethod.render.canvas`) with the plans' style,
frame and label placement (:mod:`planmethod.render.svg`), and are deterministic.

Examples
--------
>>> from planmethod.report import analyse
>>> from planmethod.spec import load_exercise
>>> analysis = analyse(load_exercise("exercises/fourbar_forces.toml"))
>>> sorted(force_files(analysis.forces, analysis.plans))      # no gravity: no combined force
['forces_1_BC+CD.svg', 'forces_2_AB.svg']
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from .canvas import Canvas, difference, fit_zoom, translate
from .labels import label_runs
from .style import INK, LEGEND_ORDER, SMALL_SIZE, TEXT_SIZE, quantity
from .svg import PLAN_SIZE, frame, plan_content, plan_legend

__all__ = ["combined_omitted", "combined_svg", "force_files", "polygon_svg"]

#: colour of each kind of known force in a polygon
KNOWN_COLOURS = {"G": "#8c564b", "F": "#c0392b", "l": "#7b3fa0", "R": "#666666"}
FRICTION = "#e67e22"


def _runs(name: str):
    """Label runs of a force's name: ``G_BC`` → G with subscript BC, ``F_u,BC`` → F with
    subscript u,BC, ``Rᵗ_B`` → Rᵗ with subscript B."""
    if name.startswith("load["):
        return ((name, "main"),)
    return label_runs(name)


def _edge_style(edge) -> tuple[str, str | None]:
    """(style key, colour override) of a polygon edge."""
    if edge.kind == "component":
        return ("tangential", None) if edge.label.startswith("Rᵗ") else ("normal", None)
    if edge.kind == "reaction":
        return "result", None
    if edge.kind == "transmitted":
        return "relative", KNOWN_COLOURS["R"]
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


def polygon_svg(group, mu_f: float, *, title: str, angle: float, index: int = 0) -> str:
    """One group's force polygon (see the module docstring); ``index`` picks the crank angle
    of a vectorised solve."""
    edges = [edge for edge in group.polygon if float(np.hypot(*edge.vector[index])) > 0]
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
        middle = translate(start, difference(end, start), 0.5)
        figure.request((edge.label,), middle, _runs(edge.label), mark=2.0)
    count = len(edges)
    for name, first, _ in _totals(edges, vectors):
        after = first + 2  # the corner after the second component (cyclically)
        start, end = where[first], where[after if after <= count else after - count]
        if figure.arrow(start, end, "result", layer="results", css="force total"):
            used.setdefault("whole reaction R = Rⁿ + Rᵗ", ("result", None))
            middle = translate(start, difference(end, start), 0.5)
            figure.request((name,), middle, _runs(name), mark=2.0)
    figure.circle(where[0], 3.4, fill=INK, css="start")
    closure = float(np.hypot(*(corners[-1] - corners[0])))
    figure.place()
    _, y0, x1, _ = figure.extent
    _force_legend(figure, (x1 + 34, y0 + 4), used)
    terms = " + ".join(edge.label for edge in edges)
    lines = [f"μF = {quantity(mu_f, 6)} N/mm", f"ΣF = 0: {terms} = 0",
             f"the polygon closes to {closure:.2g} mm"]
    lines += list(group.steps)
    lines = [line.replace("⟂", "⊥") for line in lines]   # ⊥ is in every common font
    frame(figure, title, lines, (mu_f, "N", 0.3 * PLAN_SIZE), (), "force")
    return figure.svg(title).svg


def _legend_key(edge) -> str:
    if edge.kind == "component":
        return ("tangential component Rᵗ (⊥ the link)" if edge.label.startswith("Rᵗ")
                else "normal component Rⁿ (along the link) or N (⊥ a guide)")
    if edge.kind == "reaction":
        return "reaction found by closing the polygon"
    if edge.kind == "transmitted":
        return "reaction from a group solved before"
    if edge.label.startswith(("M_f", "F_f")):
        return "friction force"
    return {"G": "weight G", "F": "inertia force F_u = −m·a_S"}.get(edge.label[:1],
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
    plan_content(figure, points, plan.steps, plan.pole)
    pole_px, new_px = figure.px((0.0, 0.0)), figure.px(new_pole)
    if combined.gravity_image_mm > 0:
        figure.arrow(pole_px, new_px, "normal", layer="results", color=KNOWN_COLOURS["G"],
                     css="gravity image")
        figure.request(("Z_g",), translate(pole_px, difference(new_px, pole_px), 0.5),
                       _runs("Z_g"), mark=2.0)
    figure.circle(new_px, 3.4, fill=KNOWN_COLOURS["F"], css="new pole")
    figure.request(("π′",), new_px, (("π′", "main"),), mark=3.4)
    for force in combined.forces:
        s = figure.px(force.image_mm)
        figure.circle(s, 2.6, fill=KNOWN_COLOURS["F"], css="centre of mass image")
        figure.request((f"s_{force.link}",), s, (("s", "main"), (force.link, "upright")),
                       mark=2.6)
        if math.hypot(*force.segment_mm) * figure.zoom >= 1.0:
            figure.arrow(s, new_px, "tangential", layer="results", color=KNOWN_COLOURS["F"],
                         css=f"combined {force.link}")
    figure.place()
    _, y0, x1, _ = figure.extent
    plan_legend(figure, (x1 + 34, y0 + 4), "acceleration")  # the plan's own styles first
    shown = sum(key in figure.used for key in (*LEGEND_ORDER, "flagged"))
    _force_legend(figure, (x1 + 34, y0 + 4 + 8 + 20 * shown + (34 if shown else 0)), {
        "image of g: π → π′, Z_g = g/μa": ("normal", KNOWN_COLOURS["G"]),
        "s → π′ = (g − a_S)/μa: Q = m·μa·(s π′)": ("tangential", KNOWN_COLOURS["F"])},
        heading="Combined force (Aliyev)")
    figure.used.clear()
    lines = [f"μa = {quantity(combined.mu_a, 6)} (m/s²)/mm; g = {combined.g:g} m/s², "
             f"Z_g = g/μa = {combined.gravity_image_mm:.4g} mm"]
    for force in combined.forces:
        length = math.hypot(*force.segment_mm)
        q = math.hypot(*force.from_plan)
        lines.append(f"{force.link}: (s π′) = {length:.4g} mm → Q = m·μa·(s π′) = "
                     f"{force.mass:g}·{quantity(combined.mu_a, 4)}·{length:.4g} = {q:.5g} N")
    title = (f"{plans.exercise.mechanism.title} — Q = G + F_u on the acceleration plan, "
             f"pole moved to π′, φ₁ = {plans.angle:g}°")
    frame(figure, title, lines, None, plan.flags, "acceleration")
    return figure.svg(title).svg


def combined_omitted(forces, plans) -> str | None:
    """Why the combined-force figure is not drawn, in one line (None when it is, or when the
    analysis has no combined-force construction at all)."""
    combined = getattr(forces, "combined", None)
    if combined is None or plans is None or plans.acceleration is None or combined.g:
        return None
    return ("combined_force.svg is not drawn: no gravity acts (g = 0), so the moved pole π′ "
            "is π and Q = G + F_u is the inertia force alone")


def _file_name(index: int, group) -> str:
    name = re.sub(r"[^A-Za-z0-9_+-]", "_", group.name)
    return f"forces_{index}_{name}.svg"


def force_files(forces: Any, plans) -> dict[str, str]:
    """``{"forces_<n>_<group>.svg": …, "combined_force.svg": …}`` for one crank angle."""
    files: dict[str, str] = {}
    title = forces.solution.mechanism.title
    for number, group in enumerate(forces.solution.groups.groups, start=1):
        kind = "drive link" if group.kind == "drive" else group.kind
        files[_file_name(number, group)] = polygon_svg(
            group, forces.mu_f, angle=forces.angle,
            title=f"{title} — force polygon {number}: {kind} {', '.join(group.links)}, "
                  f"φ₁ = {forces.angle:g}°")
    combined = combined_svg(forces, plans)
    if combined is not None:
        files["combined_force.svg"] = combined
    return files
