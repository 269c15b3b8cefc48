"""Solve an exercise at a crank angle: the analysis, its figures and its report as a course
prints it.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> analysis = solve_at(load_exercise("exercises/compressor_slider_crank.toml"), 45.0)
>>> sorted(figures(analysis))
['acceleration.svg', 'lever.svg', 'position.svg', 'velocity.svg']
>>> report_text(analysis).splitlines()[0]
'Compressor slider-crank (Abduvaliev & Abduxoshimov) — crank angle φ₁ = 45°'
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

from ..errors import PlanmethodError, SpecError
from ..words import Message, message, render

__all__ = ["check_choices", "figures", "pngs", "report_text", "solve_at", "unwritten"]


def check_choices(angle: float | None = None, precision_mm: float | None = None) -> None:
    """Refuse a precision that is no non-negative number of mm, or an angle that is not
    finite or beyond the exercise file's limit (a :class:`SpecError` naming the option that
    gave it), before any work."""
    from ..spec import MAX_ANGLE_DEG

    if precision_mm is not None and not precision_mm >= 0:
        raise SpecError(message("--precision must be a non-negative number of mm, got "
                                "{precision}", precision=precision_mm))
    if angle is not None and not (math.isfinite(angle) and abs(angle) <= MAX_ANGLE_DEG):
        raise SpecError(message("must be a finite number of degrees within ±{limit:g}°, got "
                                "{angle:g}", limit=MAX_ANGLE_DEG, angle=angle),
                        key="option --angle")


def solve_at(exercise, angle: float | None = None, *, precision_mm: float | None = None):
    """The :class:`~planmethod.report.Analysis` of ``exercise`` at crank angle ``angle``
    (deg; default its ``drive.angle``: the assembly chosen there is followed to ``angle``),
    drawn at ``precision_mm`` (default the file's ``[plan] precision_mm``); both checked by
    :func:`check_choices`."""
    from ..report import analyse

    check_choices(angle, precision_mm)
    return analyse(exercise, angle, precision_mm=precision_mm)


def figures(analysis) -> dict[str, str]:
    """Every drawing of the analysis, as ``planmethod solve --svg`` writes it: file name →
    SVG text. Where the plans are not drawn (a group no construction is written for), the
    position plan and the force polygons that need no plan (:func:`unwritten` says why the
    others are missing)."""
    from ..render.figures import plan_files

    if analysis.plans is not None:
        return plan_files(analysis.plans, forces=analysis.forces)
    from ..plans import position_plan
    from ..render.svg import position_svg

    files = {"position.svg": position_svg(position_plan(analysis.exercise, analysis.angle,
                                                        motion=analysis.motion))}
    drawn, _ = _force_figures(analysis)
    return {**files, **drawn}


def _force_figures(analysis) -> tuple[dict[str, str], Message | None]:
    """The force drawings of an analysis whose plans are not drawn, and why none are where
    they cannot be drawn without the plans (None: drawn, or no forces asked)."""
    if analysis.forces is None:
        return {}, None
    from ..render.force_svg import force_files

    try:
        return force_files(analysis.forces, None), None
    except (PlanmethodError, AttributeError, TypeError):  # a drawing that needs the plans
        return {}, message("the force drawings are not written: they are drawn on the "
                           "velocity and acceleration plans, which are not drawn")


def pngs(drawings: Mapping[str, str]) -> dict[str, bytes]:
    """The drawings as PNG images 1200 pixels wide, by file name (``velocity.png``).

    Raises
    ------
    PlanmethodError
        If cairosvg, which draws them, is not installed.
    """
    try:
        import cairosvg
    except ImportError:
        raise PlanmethodError(message("--png needs cairosvg: pip install "
                                      "'planmethod[png]'")) from None
    return {Path(name).with_suffix(".png").name: cairosvg.svg2png(
        bytestring=text.encode("utf-8"), output_width=1200) for name, text in drawings.items()}


def unwritten(analysis) -> list[Message | str]:
    """Why drawings of ``planmethod solve --svg`` are left out, one line each: the plans of a
    group no construction is written for (with the reason), the force drawings that need
    them, the combined force where no gravity acts."""
    notes: list[Message | str] = []
    if analysis.plans is None:
        from ..plans import draw_plans
        from ..plans.groups.base import PlansUnavailableError

        try:
            draw_plans(analysis.exercise, analysis.angle, motion=analysis.motion,
                       position=False)
        except PlansUnavailableError as error:
            notes.append(message("only the position plan is drawn: the velocity, acceleration "
                                 "and lever plans of link {link} are not — {reason}",
                                 link=error.link, reason=error.message))
        _, why = _force_figures(analysis)
        if why is not None:
            notes.append(why)
    if analysis.forces is not None:
        from ..render.force_svg import combined_omitted

        omitted = combined_omitted(analysis.forces, analysis.plans)
        if omitted:
            notes.append(omitted)
    return notes


def report_text(analysis) -> str:
    """The report a course prints: structure, scales, check table, flags — every quantity,
    link and force in the course's notation (docs/notation.md: ω₂, v_B₃, R₀₁; the crank's
    φ and ω by its number), never a report name (those are the JSON report's); in the
    language spoken."""
    from ..numbering import course_numbers
    from ..render.report_text import check_lines, flag_lines, force_lines, published_lines
    from ..vocabulary import numbered, shown_title

    exercise = analysis.exercise
    numbers = course_numbers(exercise.mechanism)
    crank = numbers[exercise.mechanism.drive.link]
    lines = [render(message("{title} — crank angle {phi} = {angle:g}°",
                            title=shown_title(exercise.mechanism.title),
                            phi=numbered("φ", crank), angle=analysis.angle))]
    lines += ["", *_structure_lines(analysis, numbers)]
    if analysis.plans:
        lines += ["", *_scale_lines(analysis.plans)]
    lines += check_lines(analysis)        # each begins with an empty line
    lines += published_lines(analysis)
    if analysis.flags:
        lines += ["", render(message("Flags")), *flag_lines(analysis.flags)]
    if analysis.forces is not None:
        lines += ["", *force_lines(analysis.forces)]
    return "\n".join(lines)


def _structure_lines(analysis, numbers: Mapping[str, int]) -> list[str]:
    from ..structure import describe
    from ..vocabulary import branch_reason_words

    lines = [render(message("Structural analysis"))]
    lines += ["  " + line for line in describe(analysis.structure, numbers).splitlines()]
    for index, branch in sorted(analysis.motion.branches.items()):
        analysis.structure.groups[index]
        lines.append("  " + render(message("group {number} assembly: branch {sign:+d} "
                                           "({reason})", number=index + 1, sign=branch.sign,
                                           reason=branch_reason_words(branch.reason))))
    return lines


def _scale_lines(plans) -> list[str]:
    from ..render.plan_words import scale_lines

    lines = [render(message("Scales"))] + ["  " + render(line)
                                           for line in scale_lines(plans.scales)]
    precision = plans.velocity.precision_mm
    lines.append("  " + render(message("drafting precision: {precision:g} mm",
                                       precision=precision) if precision else
                               message("drafting precision: exact construction")))
    return lines
