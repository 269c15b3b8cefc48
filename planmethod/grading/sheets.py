"""Task sheets for variants: the position plan with the given data and what is asked, and the
blank plan sheets a student draws on (and hands back for grading).

Both are drawn on the one canvas (:mod:`planmethod.render.canvas`): the task sheet is
:func:`planmethod.render.svg.position_drawing` (the mechanism at μl, without any answer on it)
with the task text under it. A blank plan sheet is in millimetres
(``width="…mm"`` with a matching ``viewBox``), marks the pole (p or π) at its centre, prints the
scale in one long text line (long texts are never taken for labels), and has its grid as a
pattern so that nothing on it is mistaken for a drawn point by
:func:`planmethod.grading.drawings.parse_drawing_svg`.

Examples
--------
>>> sheet = blank_plan_sheet("velocity", pole="p", scale=0.2, unit="(m/s)/mm", size_mm=120,
...                          student="s01", title="Slider-crank")
>>> from planmethod.grading.drawings import parse_drawing_svg
>>> drawing = parse_drawing_svg(sheet)
>>> drawing.plan, drawing.points["p"]
('velocity', (60.0, -72.0))
"""

from __future__ import annotations

import math
import re
import textwrap
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from ..render.canvas import Canvas
from ..render.style import LABEL_FAMILY
from ..render.svg import position_drawing
from ..vocabulary import link_numbers, scale_text, symbol

__all__ = ["blank_plan_sheet", "plan_sheet_for_key", "task_sheet_svg", "task_text"]


def task_text(key: Mapping[str, Any]) -> str:
    """The text of the task: the description, the given data, the scales and the questions.

    Examples
    --------
    >>> key = {"title": "T", "task": "Find v_C.", "student": "s1", "angle": 45.0,
    ...        "scales": {"mu_l": 0.002, "mu_v": 0.2, "mu_a": 20.0}, "given": {},
    ...        "questions": [{"id": "v_C", "text": "speed of C, |v_C|", "unit": "m/s"}]}
    >>> print(task_text(key).splitlines()[0])
    T — variant for s1
    """
    scales = key.get("scales", {})
    lines = [f"{key.get('title', 'Exercise')} — variant for {key.get('student')}", "",
             key.get("task", "").strip(), ""]
    given = key.get("given") or {}
    if given:
        lines.append("Given: " + ", ".join(f"{name} = {value:g}" if isinstance(value, float)
                                           else f"{name} = {value}"
                                           for name, value in given.items()))
    scale_texts = (scale_text(name, scales.get(name, 0)) for name in ("mu_l", "mu_v", "mu_a"))
    lines.append(f"Crank angle φ1 = {key.get('angle', 0):g}°; scales {', '.join(scale_texts)}.")
    exercise = key.get("exercise") or {}
    links = list((exercise.get("links") or {}).keys())
    drive = str((exercise.get("drive") or {}).get("link", ""))
    numbers = link_numbers(links, drive) if links and drive else {}
    if numbers:
        lines.append("Links: " + ", ".join(f"{number} {_words(name)}"
                                           for name, number in numbers.items()) + ".")
    lines += ["", "Answer (SI units, counter-clockwise positive; in an answers file, the column "
              "named in brackets):"]
    for question in key.get("questions", ()):
        unit = question.get("unit", "")
        shown = symbol(question["id"], numbers)
        text = question["text"]
        for name in numbers:
            text = re.sub(rf"\b{re.escape(name)}\b", _words(name), text) if "_" in name \
                else text
        lines.append(f"  {shown + (', ' + unit if unit else ''):<16} {text}"
                     f"   [{question['id']}]")
    return "\n".join(lines).rstrip() + "\n"


def _words(name: str) -> str:
    """A link's name as a sheet prints it: ``rocker_EF`` → ``rocker EF``."""
    return name.replace("_", " ")


def task_sheet_svg(key: Mapping[str, Any], plans) -> str:
    """The task sheet: the position plan (no answers on it) above the task text.

    ``plans`` are the variant's :class:`~planmethod.plans.Plans` (only the position plan is
    drawn; its curvature construction, which would show ρ, is left out).
    """
    position = replace(plans.position, curvature={})
    lines: list[str] = []
    for line in task_text(key).splitlines():
        if line.startswith("  "):     # a row of the answer table: kept whole
            lines.append(line)
        else:
            lines += textwrap.wrap(line, 100, drop_whitespace=False) or [""]
    return position_drawing(position, notes=lines).svg


def blank_plan_sheet(plan: str, *, pole: str, scale: float, unit: str, size_mm: float,
                     student: str = "", title: str = "", given: str = "") -> str:
    """A square blank sheet (mm) with the pole at its centre and a 10 mm grid pattern."""
    size = float(size_mm)
    centre = size / 2
    header = (f"{title} — {plan} plan — {student} — μ{'v' if plan == 'velocity' else 'a'} = "
              f"{scale:.6g} {unit}. {given} Draw the plan from the pole {pole}; label every "
              f"point (b, c, …) next to it.")
    canvas = Canvas()
    grid = canvas.grid_pattern("grid", 10.0, color="#c9cede", width=0.2)
    canvas.rectangle((0.0, 12.0), (size, size), fill=grid, stroke="#99a", width=0.3,
                     css="grid")
    for index, line in enumerate(textwrap.wrap(header + " (grid: 10 mm)",
                                               int(size / 1.45))[:3]):
        canvas.text((3.0, 4.0 + 3.2 * index), line, size=2.6, css="header", area=False)
    canvas.circle((centre, centre + 12), 0.8, fill="#000000", css="pole", area=False)
    canvas.text((centre + 1.5, centre + 12 - 1.5), pole, size=5.0, family=LABEL_FAMILY,
                css="pole-label", area=False)
    return canvas.svg(f"{title} — blank {plan} plan sheet", view=(0.0, 0.0, size, size + 12),
                      unit="mm", attributes={"data-planmethod-plan": plan,
                                             "data-planmethod-student": student}).svg


def plan_sheet_for_key(key: Mapping[str, Any], plan: str) -> str:
    """The blank sheet of one of a key's plans, large enough for the plan with a margin."""
    entry = key["plans"][plan]
    extent = max((math.hypot(*xy) for xy in entry["points_mm"].values()), default=30.0)
    size = max(120.0, 20.0 * math.ceil((2 * extent + 40.0) / 20.0))
    first = next((s for s in entry["steps"] if s["action"] == "lay_off"), None)
    given = (f"({entry['pole']}{first['end']}) = {first['length_mm']:.4g} mm."
             if first else "")
    return blank_plan_sheet(plan, pole=entry["pole"], scale=entry["scale"], unit=entry["unit"],
                            size_mm=size, student=str(key.get("student", "")),
                            title=str(key.get("title", "")), given=given)
