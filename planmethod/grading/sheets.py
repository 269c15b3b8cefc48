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
from ..render.plan_words import label_text
from ..render.style import LABEL_FAMILY
from ..render.svg import position_drawing
from ..vocabulary import (
    PLAN_SCALES,
    numbered,
    point_text,
    question_words,
    scale_words,
    shown_title,
    symbol,
    unit_words,
)
from ..words import Message, message, render, template
from .keys import key_numbers
from .templates import drawn_lengths

__all__ = ["blank_plan_sheet", "given_data", "paper_plan_sheet", "paper_task_sheet",
           "plan_sheet_for_key", "task_figure_svg", "task_sheet_svg", "task_text"]


def _lines(key: Mapping[str, Any]) -> list[Message | str]:
    """The task's lines above its answer table."""
    scales = key.get("scales", {})
    numbers = key_numbers(key)
    exercise = _exercise(key)
    crank = numbers.get(exercise.mechanism.drive.link, 1) if exercise is not None else 1
    lines: list[Message | str] = [
        message("{title} — variant for {student}",
                title=shown_title(key["title"]) if "title" in key else message("Exercise"),
                student=key.get("student")), "", key.get("task", "").strip(), ""]
    if exercise is not None:
        lines.append(message("Given: {data}.", data=given_data(exercise, numbers)))
    scale_texts = [scale_words(name, scales.get(name, 0)) for name in ("mu_l", "mu_v", "mu_a")]
    lines.append(message("Crank angle {phi} = {angle:g}°; scales {scales}.",
                         phi=numbered("φ", crank), angle=key.get("angle", 0),
                         scales=scale_texts))
    if exercise is not None and scales:
        lines.append(message("At these scales: {lengths}.", lengths=[
            message("{segment} = {length:.3g} mm", segment=segment, length=length)
            for segment, length in drawn_lengths(exercise, scales).items()]))
    if numbers:
        lines.append(message("Links: {links}.", links=[
            message("{number} {name}", number=number, name=_words(name))
            for name, number in numbers.items()]))
    return lines


def _row(question: Mapping[str, Any], numbers: Mapping[str, int]) -> Message:
    """A question's row of the answer table: its symbol and unit, its words, its column."""
    unit = question.get("unit", "")
    shown = question.get("symbol") or symbol(question["id"], numbers)
    # the heading says counter-clockwise is positive: the row need not say it again
    try:
        text: Message | str = question_words(question["id"], numbers, sense=False)
    except KeyError:          # a quantity this version does not know: the key's own words
        text = question["text"]
    return message("  {symbol:<16} {question}   [{column}]",
                   symbol=message("{symbol}, {unit}", symbol=shown, unit=unit_words(unit)) if unit
                   else shown, question=text, column=question["id"])


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
    numbers = key_numbers(key)
    lines = [*_lines(key), "", message("Answer (SI units, counter-clockwise positive; in an "
                                       "answers file, the column named in brackets):")]
    lines += [_row(question, numbers) for question in key.get("questions", ())]
    return "\n".join(render(line) for line in lines).rstrip() + "\n"


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


def _length(symbol_text: str, value: float) -> Message:
    return message("{symbol} = {length:.4g} m", symbol=symbol_text, length=value)


def given_data(exercise, numbers: Mapping[str, int]) -> list[Message]:
    """What a task gives, in the course's symbols with units: the links' lengths (l_AB, from
    each link's first point to its others), the fixed points and guides seen from the crank's
    pivot, and the crank's φ, ω (and ε).

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
    >>> [render(item) for item in given_data(exercise, {"frame": 0, "AB": 1, "BC": 2,
    ...                                                 "slider": 3})]
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
            given.append(_length(f"l_{point_text(points[0])}{point_text(other)}",
                                 mechanism.links[name].length(points[0], other)))
    pivot = mechanism.local(FRAME, drive.pivot)
    for point, (x, y) in mechanism.links[FRAME].points.items():
        if point == drive.pivot:
            continue
        dx, dy = x - pivot[0], y - pivot[1]
        where = f"{point_text(drive.pivot)}{point_text(point)}"
        given.append(_length(f"l_{where}", dx) if dy == 0 and dx > 0 else
                     message("{x} = {dx:.4g} m, {y} = {dy:.4g} m", x=f"x_{where}", dx=dx,
                             y=f"y_{where}", dy=dy))
    for slide in mechanism.slides:
        if slide.along == FRAME and (slide.through != drive.pivot or slide.direction):
            given.append(message("the guide of {point} through {through} at {angle:g}°",
                                 point=point_text(slide.point),
                                 through=point_text(slide.through), angle=slide.direction))
    crank = numbers.get(drive.link, 1)
    given += [message("{symbol} = {angle:g}°", symbol=numbered("φ", crank), angle=drive.angle),
              message("{symbol} = {omega:g} rad/s", symbol=numbered("ω", crank),
                      omega=drive.omega)]
    if drive.epsilon:
        given.append(message("{symbol} = {epsilon:g} rad/s²", symbol=numbered("ε", crank),
                             epsilon=drive.epsilon))
    return given


def _words(name: str) -> Message | str:
    """A link's name as a sheet prints it: ``rocker_EF`` → ``rocker EF``; the frame, whose
    name is the file's keyword, in the course's word for it.

    >>> _words("rocker_EF"), render(_words("frame"), "ru")
    ('rocker EF', 'стойка')
    """
    if name == FRAME:
        return message("frame", context="link")
    return name.replace("_", " ")


def task_figure_svg(plans, notes: list[str] | None = None) -> str:
    """The task's figure: the mechanism at its position as the task sheet draws it (the
    position plan without its curvature construction, which would show ρ), with ``notes``
    under it, their symbols subscripted as a course prints them (l_AB with AB below; the
    answer columns' names in brackets as they are).

    ``plans`` are the variant's :class:`~planmethod.plans.Plans` (only the position plan is
    drawn).

    >>> from planmethod.plans import draw_plans
    >>> from planmethod.spec import load_exercise
    >>> plans = draw_plans(load_exercise("exercises/slotted_lever.toml"), acceleration=False)
    >>> "position plan, φ₁ = 30°" in task_figure_svg(plans)
    True
    """
    return _task_figure(plans, notes or []).svg


def _task_figure(plans, notes: list[str]):
    """The task's figure as an :class:`~planmethod.render.canvas.SvgFigure` (its size known)."""
    position = replace(plans.position, curvature={})
    return position_drawing(position, notes=notes, formulas=True)


def task_sheet_svg(key: Mapping[str, Any], plans) -> str:
    """The task sheet: the task's figure (:func:`task_figure_svg`, no answers on it) above the
    task text."""
    return _task_sheet_figure(key, plans).svg


def _task_sheet_figure(key: Mapping[str, Any], plans):
    lines: list[str] = []
    for line in task_text(key).splitlines():
        if line.startswith("  "):     # a row of the answer table: kept whole
            lines.append(line)
        else:
            lines += textwrap.wrap(line, 100, drop_whitespace=False) or [""]
    return _task_figure(plans, lines)


#: a blank plan sheet's header (what it is, whose, its scale, the given segment, what to do)
#: and its title, by plan
_HEADERS = {"velocity": template("{title} — velocity plan — {student} — {scale}. {given} Draw "
                                 "the plan from the pole {pole}; label every point (b, c, …) "
                                 "next to it. (grid: 10 mm)"),
            "acceleration": template("{title} — acceleration plan — {student} — {scale}. "
                                     "{given} Draw the plan from the pole {pole}; label every "
                                     "point (b, c, …) next to it. (grid: 10 mm)")}
_TITLES = {"velocity": template("{title} — blank velocity plan sheet"),
           "acceleration": template("{title} — blank acceleration plan sheet")}


def blank_plan_sheet(plan: str, *, pole: str, scale: float, unit: str, size_mm: float,
                     student: str = "", title: str = "", given: Message | str = "") -> str:
    """A square blank sheet (mm) of the ``velocity`` or ``acceleration`` plan with the pole at
    its centre and a 10 mm grid pattern."""
    size = float(size_mm)
    centre = size / 2
    title = shown_title(title)
    header = render(_HEADERS[plan].replace(title=title, student=student, given=given, pole=pole,
                                           scale=scale_words(PLAN_SCALES[plan], scale)))
    canvas = Canvas()
    grid = canvas.grid_pattern("grid", 10.0, color="#c9cede", width=0.2)
    canvas.rectangle((0.0, 12.0), (size, size), fill=grid, stroke="#99a", width=0.3,
                     css="grid")
    for index, line in enumerate(textwrap.wrap(header, int(size / 1.45))[:3]):
        canvas.text((3.0, 4.0 + 3.2 * index), line, size=2.6, css="header", area=False)
    canvas.circle((centre, centre + 12), 0.8, fill="#000000", css="pole", area=False)
    canvas.text((centre + 1.5, centre + 12 - 1.5), pole, size=5.0, family=LABEL_FAMILY,
                css="pole-label", area=False)
    return canvas.svg(render(_TITLES[plan].replace(title=title)),
                      view=(0.0, 0.0, size, size + 12),
                      unit="mm", attributes={"data-planmethod-plan": plan,
                                             "data-planmethod-student": student}).svg


def plan_sheet_for_key(key: Mapping[str, Any], plan: str) -> str:
    """The blank sheet of one of a key's plans, large enough for the plan with a margin."""
    entry = key["plans"][plan]
    extent = max((math.hypot(*xy) for xy in entry["points_mm"].values()), default=30.0)
    size = max(120.0, 20.0 * math.ceil((2 * extent + 40.0) / 20.0))
    first = next((s for s in entry["steps"] if s["action"] == "lay_off"), None)
    given = (message("({pole}{end}) = {length:.4g} mm.", pole=entry["pole"],
                     end=label_text(first["end"], key_numbers(key)),
                     length=first["length_mm"]) if first else "")
    return blank_plan_sheet(plan, pole=entry["pole"], scale=entry["scale"], unit=entry["unit"],
                            size_mm=size, student=str(key.get("student", "")),
                            title=str(key.get("title", "")), given=given)


# -- the booklet's pages (A4, mm; see planmethod.grading.paper) ------------------------------
#: the light grid of a paper plan sheet: every millimetre, and darker every 10 mm — a light blue
#: that a phone photo keeps (the grader finds the sheet's curl by it) and that a grey pencil line
#: stands out from, in colour and printed grey alike
GRID_MINOR = ("#d2e4f5", 0.1)
GRID_MAJOR = ("#8cb9e6", 0.2)
#: text sizes on the printed page (mm): the title, the lines under it, small print
PAGE_TITLE_MM, PAGE_TEXT_MM, PAGE_SMALL_MM = 4.2, 3.2, 2.6


def _plan_name(plan: str) -> Message:
    return (message("velocity plan") if plan == "velocity"
            else message("acceleration plan"))


def _value_unit(unit: str) -> str:
    """The unit of a plan's vectors from its scale's unit: ``(m/s)/mm`` → ``m/s``."""
    value = unit.removesuffix("/mm")
    return value[1:-1] if value.startswith("(") and value.endswith(")") else value


def _page_canvas() -> Canvas:
    return Canvas()


def _page_svg(canvas: Canvas, title: str, size: tuple[float, float], attributes=None) -> str:
    return canvas.svg(title, view=(0.0, 0.0, size[0], size[1]), unit="mm",
                      attributes=attributes).svg


def _wrapped(canvas: Canvas, at: tuple[float, float], text: str, width_mm: float,
             size: float, *, bold: bool = False, lines: int = 3) -> float:
    """Text wrapped to ``width_mm``; returns the y under it."""
    from ..render.style import SANS, SANS_BOLD, text_width

    x, y = at
    words = text.split(" ")
    row: list[str] = []
    rows: list[str] = []
    for word in words:
        trial = " ".join([*row, word])
        if row and text_width(trial, size, SANS_BOLD if bold else SANS) > width_mm:
            rows.append(" ".join(row))
            row = [word]
        else:
            row.append(word)
    rows.append(" ".join(row))
    for line in rows[:lines]:
        canvas.text((x, y), line, size=size, bold=bold, area=False, css="header")
        y += 1.35 * size
    return y


def _markers(canvas: Canvas, sheet) -> None:
    from .paper import MARKER_BITS

    cell = sheet.marker_mm / 6
    for marker in sheet.markers:
        bits = MARKER_BITS[marker.number]
        rows = [[True] * 6] + [[True] + [bit == "0" for bit in row] + [True] for row in bits] \
            + [[True] * 6]
        x, y = marker.centre
        canvas.cells((x - sheet.marker_mm / 2, y - sheet.marker_mm / 2), cell, rows,
                     css=f"marker marker-{marker.number}")


def _qr(canvas: Canvas, sheet) -> None:
    import segno

    code = segno.make_qr(sheet.code.text, error="m")
    rows = [[bool(value) for value in row] for row in code.matrix]
    left, top, side = sheet.qr_mm
    module = side / (len(rows) + 8)           # a quiet zone of 4 modules round it
    canvas.cells((left + 4 * module, top + 4 * module), module, rows, css="qr")


def _grid(canvas: Canvas, sheet) -> None:
    left, top, right, bottom = sheet.drawing_mm
    px, py = sheet.pole_mm
    xs = [px + k for k in range(math.ceil(left - px), math.floor(right - px) + 1)]
    ys = [py + k for k in range(math.ceil(top - py), math.floor(bottom - py) + 1)]
    canvas.rules((left, top, right, bottom), xs=[x for x in xs if round(x - px) % 10],
                 ys=[y for y in ys if round(y - py) % 10], color=GRID_MINOR[0],
                 width=GRID_MINOR[1], css="grid minor")
    canvas.rules((left, top, right, bottom), xs=[x for x in xs if not round(x - px) % 10],
                 ys=[y for y in ys if not round(y - py) % 10], color=GRID_MAJOR[0],
                 width=GRID_MAJOR[1], css="grid major")


def _scale_bar(canvas: Canvas, sheet) -> None:
    from ..render.style import INK

    (x, y), length = sheet.scale_bar_mm
    canvas.line((x, y), (x + length, y), color=INK, width=0.4, layer="text", obstacle=False,
                css="scale bar")
    for tenth in range(int(length // 10) + 1):
        tick = 2.0 if tenth in (0, int(length // 10)) else 1.2
        canvas.line((x + 10 * tenth, y - tick), (x + 10 * tenth, y), color=INK, width=0.3,
                    layer="text", obstacle=False, css="scale bar")
    canvas.text((x, y + 3.6), "0", size=PAGE_SMALL_MM, anchor="middle", area=False,
                css="scale")
    canvas.text((x + length, y + 3.6),
                render(message("{value:.4g} {unit}", value=length * sheet.scale,
                               unit=_value_unit(sheet.unit))),
                size=PAGE_SMALL_MM, anchor="middle", area=False, css="scale")
    canvas.text((x, y + 8.0), render(message(
        "Print at 100 % (actual size): this bar measures {length:g} mm.", length=length)),
        size=PAGE_SMALL_MM, area=False, css="scale note")


def paper_plan_sheet(key: Mapping[str, Any], sheet, pages: int) -> str:
    """A blank plan sheet of the booklet (A4, mm): the header, the light millimetre grid with
    the pole printed and named, the scale with its bar, the four corner markers and the QR
    code, each where ``sheet`` (:class:`planmethod.grading.paper.Sheet`, read from the key)
    puts it. The text is rendered in the language spoken.

    >>> from planmethod.grading.keys import build_key
    >>> from planmethod.grading.paper import add_sheets, read_sheet
    >>> from planmethod.grading.templates import draw_variant, load_template
    >>> key = build_key(draw_variant(load_template("exercises/templates/slider_crank.toml")))
    >>> _ = add_sheets([key])
    >>> svg = paper_plan_sheet(key, read_sheet(key, "velocity"), 3)
    >>> 'width="210mm"' in svg and 'class="qr"' in svg
    True
    """
    from ..render.style import INK

    canvas = _page_canvas()
    _grid(canvas, sheet)
    left, top, right, _ = sheet.drawing_mm
    canvas.rectangle((left, top), (right - left, sheet.drawing_mm[3] - top), fill="none",
                     stroke=GRID_MAJOR[0], width=0.3, css="drawing area")
    _markers(canvas, sheet)
    _qr(canvas, sheet)
    _header(canvas, key, sheet, pages)
    px, py = sheet.pole_mm
    canvas.circle((px, py), 0.55, fill=INK, css="pole", area=False)
    canvas.circle((px, py), 1.6, fill="none", stroke=INK, width=0.25, css="pole ring",
                  area=False)
    canvas.text((px - 2.2, py - 2.2), sheet.pole, size=5.0, family=LABEL_FAMILY,
                anchor="end", italic=True, css="pole-label", area=False)
    _scale_bar(canvas, sheet)
    shown = shown_title(str(key.get("title", "")))
    title = render(message("{title} — blank velocity plan sheet of student {student}",
                           title=shown, student=sheet.student) if sheet.plan == "velocity" else
                   message("{title} — blank acceleration plan sheet of student {student}",
                           title=shown, student=sheet.student))
    return _page_svg(canvas, title, sheet.page_mm,
                     {"data-planmethod-plan": sheet.plan,
                      "data-planmethod-student": sheet.student})


def _header(canvas: Canvas, key: Mapping[str, Any], sheet, pages: int) -> None:
    """A plan sheet's header: the title and plan, the student, angle and page, the scale and
    the first vector's drawn length, what to do."""

    numbers = key_numbers(key)
    exercise_drive = ((key.get("exercise") or {}).get("drive") or {}).get("link")
    phi = numbered("φ", numbers.get(exercise_drive, 1))
    x = 26.0
    y = _wrapped(canvas, (x, 15.0), render(message(
        "{title} — {plan}", title=shown_title(str(key.get("title", ""))),
        plan=_plan_name(sheet.plan))),
        162.0, PAGE_TITLE_MM, bold=True, lines=1) + 0.4
    given = key["plans"][sheet.plan]
    first = next((step for step in given["steps"] if step["action"] == "lay_off"), None)
    lines = [message("Student {student} · {angle_symbol} = {angle:g}° · page {page} of {pages}",
                     student=sheet.student, angle_symbol=phi, angle=float(key.get("angle", 0)),
                     page=sheet.page, pages=pages),
             message("Scale {symbol} = {scale:.6g} {unit}", symbol=_scale_symbol(sheet.plan),
                     scale=sheet.scale, unit=sheet.unit)]
    if first is not None:
        lines[-1] = message("Scale {symbol} = {scale:.6g} {unit}; ({pole}{point}) = "
                            "{length:.4g} mm", symbol=_scale_symbol(sheet.plan),
                            scale=sheet.scale, unit=sheet.unit, pole=sheet.pole,
                            point=label_text(first["end"], numbers),
                            length=float(first["length_mm"]))
    for line in lines:
        y = _wrapped(canvas, (x, y), render(line), 162.0, PAGE_TEXT_MM, lines=1)
    _wrapped(canvas, (x, y), render(message(
        "Draw the plan from the pole {pole} with a sharp pencil and a ruler; mark each point "
        "with a dot or a small cross and label it. Photograph the whole sheet with all four "
        "corner squares in view.", pole=sheet.pole)), 162.0, PAGE_SMALL_MM, lines=2)


def _scale_symbol(plan: str) -> str:
    from ..vocabulary import SCALES

    return SCALES[PLAN_SCALES[plan]].symbol


def paper_task_sheet(key: Mapping[str, Any], plans, page: int, pages: int) -> str:
    """The task sheet as a page of the booklet (A4, mm): the task sheet
    (:func:`task_sheet_svg`) at its true size — the mechanism at μl — or, if it is larger
    than the page's printed area, scaled down to it, with a note saying so."""
    from .paper import A4_MM

    figure = _task_sheet_figure(key, plans)
    millimetres = 25.4 / 96.0                     # the figure's user unit is a CSS px
    width, height = figure.width * millimetres, figure.height * millimetres
    room = (A4_MM[0] - 20.0, A4_MM[1] - 32.0)
    shrink = min(1.0, room[0] / width, room[1] / height)
    canvas = _page_canvas()
    notes = [message("Student {student} · page {page} of {pages}",
                     student=str(key.get("student")), page=page, pages=pages)]
    if shrink < 1.0:
        notes.append(message("The figure is printed at {percent:.0f} % of its scale "
                             "μl: measure lengths from the data, not from it.",
                             percent=100 * shrink))
    for index, note in enumerate(notes):
        canvas.text((10.0, 12.0 + 4.0 * index), render(note), size=PAGE_TEXT_MM, area=False,
                    css="header")
    canvas.nest([(figure, (10.0, 22.0), (width * shrink, height * shrink))], css="task")
    return _page_svg(canvas, render(message("{title} — task of student {student}",
                                            title=shown_title(str(key.get("title", ""))),
                                            student=str(key.get("student")))), A4_MM)
