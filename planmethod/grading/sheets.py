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
import textwrap
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from ..model import FRAME
from ..render.canvas import Canvas
from ..render.style import LABEL_FAMILY
from ..render.svg import position_drawing
from ..vocabulary import PLAN_SCALES, numbered, point_text, scale_text, shown_title, symbol
from .keys import key_numbers
from .templates import drawn_lengths

__all__ = ["blank_plan_sheet", "plan_sheet_for_key", "task_figure_svg", "task_sheet_svg",
           "task_text"]


def task_text(key: Mapping[str, Any]) -> str:
    """The text of the task: the description, the given data in the course's symbols, the
    scales and the lengths they draw, the links' numbers and the questions.

    Examples
    --------
    >>> key = {"title": "T", "task": "Find v_C.", "student": "s1", "angle": 45.0,
    ...        "scales": {"mu_l": 0.002, "mu_v": 0.2, "mu_a": 20.0}, "given": {},
    ...        "questions": [{"id": "v_C", "text": "speed of C, |v_C|", "unit": "m/s"}]}
    >>> print(task_text(key).splitlines()[0])
    T — variant for s1
    """
    scales = key.get("scales", {})
    numbers = key_numbers(key)
    exercise = _exercise(key)
    crank = numbers.get(exercise.mechanism.drive.link, 1) if exercise is not None else 1
    lines = [f"{shown_title(key.get('title', 'Exercise'))} — variant for {key.get('student')}", "",
             key.get("task", "").strip(), ""]
    if exercise is not None:
        lines.append("Given: " + ", ".join(given_data(exercise, numbers)) + ".")
    scale_texts = (scale_text(name, scales.get(name, 0)) for name in ("mu_l", "mu_v", "mu_a"))
    lines.append(f"Crank angle {numbered('φ', crank)} = {key.get('angle', 0):g}°; scales "
                 f"{', '.join(scale_texts)}.")
    if exercise is not None and scales:
        lines.append("At these scales: " + ", ".join(
            f"{segment} = {length:.3g} mm" for segment, length in
            drawn_lengths(exercise, scales).items()) + ".")
    if numbers:
        lines.append("Links: " + ", ".join(f"{number} {_words(name)}"
                                           for name, number in numbers.items()) + ".")
    lines += ["", "Answer (SI units, counter-clockwise positive; in an answers file, the column "
              "named in brackets):"]
    for question in key.get("questions", ()):
        unit = question.get("unit", "")
        shown = question.get("symbol") or symbol(question["id"], numbers)
        # the heading says counter-clockwise is positive: the row need not say it again
        text = question["text"].replace(" (counter-clockwise positive)", "")
        lines.append(f"  {shown + (', ' + unit if unit else ''):<16} {text}"
                     f"   [{question['id']}]")
    return "\n".join(lines).rstrip() + "\n"


def _exercise(key: Mapping[str, Any]):
    """The key's exercise as a model (None for a key without one)."""
    from ..errors import PlanmethodError
    from ..spec import exercise_from_dict

    if not key.get("exercise"):
        return None
    try:
        return exercise_from_dict(key["exercise"])
    except PlanmethodError:
        return None


def _length(value: float) -> str:
    return f"{value:.4g} m"


def given_data(exercise, numbers: Mapping[str, int]) -> list[str]:
    """What a task gives, in the course's symbols with units: the links' lengths (l_AB, from
    each link's first point to its others), the fixed points and guides seen from the crank's
    pivot, and the crank's φ, ω (and ε).

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
    >>> given_data(exercise, {"frame": 0, "AB": 1, "BC": 2, "slider": 3})
    ['l_AB = 0.06 m', 'l_BC = 0.18 m', 'l_BD = 0.09 m', 'φ₁ = 45°', 'ω₁ = 100 rad/s']
    """
    mechanism = exercise.mechanism
    drive = mechanism.drive
    order = sorted((link for link in mechanism.links if link != FRAME),
                   key=lambda link: numbers.get(link, len(numbers)))
    given = []
    for name in order:
        points = list(mechanism.links[name].points)
        for other in points[1:]:
            given.append(f"l_{point_text(points[0])}{point_text(other)} = "
                         f"{_length(mechanism.links[name].length(points[0], other))}")
    pivot = mechanism.local(FRAME, drive.pivot)
    for point, (x, y) in mechanism.links[FRAME].points.items():
        if point == drive.pivot:
            continue
        dx, dy = x - pivot[0], y - pivot[1]
        where = f"{point_text(drive.pivot)}{point_text(point)}"
        given.append(f"l_{where} = {_length(dx)}" if dy == 0 and dx > 0 else
                     f"x_{where} = {_length(dx)}, y_{where} = {_length(dy)}")
    for slide in mechanism.slides:
        if slide.along == FRAME and (slide.through != drive.pivot or slide.direction):
            given.append(f"the guide of {point_text(slide.point)} through "
                         f"{point_text(slide.through)} at {slide.direction:g}°")
    crank = numbers.get(drive.link, 1)
    given += [f"{numbered('φ', crank)} = {drive.angle:g}°",
              f"{numbered('ω', crank)} = {drive.omega:g} rad/s"]
    if drive.epsilon:
        given.append(f"{numbered('ε', crank)} = {drive.epsilon:g} rad/s²")
    return given


def _words(name: str) -> str:
    """A link's name as a sheet prints it: ``rocker_EF`` → ``rocker EF``."""
    return name.replace("_", " ")


def task_figure_svg(plans, notes: list[str] | None = None) -> str:
    """The task's figure: the mechanism at its position as the task sheet draws it (the
    position plan without its curvature construction, which would show ρ), with ``notes``
    under it.

    ``plans`` are the variant's :class:`~planmethod.plans.Plans` (only the position plan is
    drawn).

    >>> from planmethod.plans import draw_plans
    >>> from planmethod.spec import load_exercise
    >>> plans = draw_plans(load_exercise("exercises/slotted_lever.toml"), acceleration=False)
    >>> "position plan, φ₁ = 30°" in task_figure_svg(plans)
    True
    """
    position = replace(plans.position, curvature={})
    return position_drawing(position, notes=notes or []).svg


def task_sheet_svg(key: Mapping[str, Any], plans) -> str:
    """The task sheet: the task's figure (:func:`task_figure_svg`, no answers on it) above the
    task text."""
    lines: list[str] = []
    for line in task_text(key).splitlines():
        if line.startswith("  "):     # a row of the answer table: kept whole
            lines.append(line)
        else:
            lines += textwrap.wrap(line, 100, drop_whitespace=False) or [""]
    return task_figure_svg(plans, lines)


def blank_plan_sheet(plan: str, *, pole: str, scale: float, unit: str, size_mm: float,
                     student: str = "", title: str = "", given: str = "") -> str:
    """A square blank sheet (mm) with the pole at its centre and a 10 mm grid pattern."""
    size = float(size_mm)
    centre = size / 2
    title = shown_title(title)
    header = (f"{title} — {plan} plan — {student} — {scale_text(PLAN_SCALES[plan], scale)}. "
              f"{given} Draw the plan from the pole {pole}; label every point (b, c, …) next "
              "to it.")
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
