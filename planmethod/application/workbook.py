"""Build a workbook: one offline HTML page for a full turn of the crank.

Every frame (one crank angle every ``step`` degrees) is solved as ``planmethod solve --angle
A`` solves it: its drawings are the ones ``solve --svg`` writes, its readings are the
report's ``checks``, and its grading questions are those of the answer key ``planmethod
grade`` builds at that angle. The page (:mod:`planmethod.render.workbook`) only shows them.
The frames are solved here or in a bounded pool of worker processes
(:mod:`planmethod.application.workers`); the page is made in the language spoken
(:func:`planmethod.words.speaking`).
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from ..errors import AssemblyError, BranchJumpError, SpecError, ToggleError
from ..words import Message, current, message, render, speaking
from .tasks import Watch
from .workers import chunked, in_workers, worker_count

if TYPE_CHECKING:
    from ..render.workbook import PageQuantity

__all__ = ["DEFAULT_STEP", "FULL_TURN", "MIN_STEP_DEG", "build_workbook", "drawing_meta",
           "exercise_variant", "frame_data", "limits_noted", "reading_plans", "solve_frames",
           "turn_angles", "turn_charts", "turn_order"]

#: the finest crank-angle step of a workbook or an animation (deg): 3,600 frames
MIN_STEP_DEG = 0.1

#: default crank-angle step of a workbook (deg)
DEFAULT_STEP = 5.0

#: the drawings a frame shows, in this order, by file name of ``plan_files``
PANELS = ("position", "velocity", "acceleration", "lever")

#: the crank angles of a page or an animation unless a range is given: one turn (deg)
FULL_TURN = (0.0, 360.0)
#: what a question of the key keeps in the page (its ``text`` is not shown)
QUESTION_FIELDS = ("id", "symbol", "value", "tolerance", "unit", "signed", "mistakes")


def turn_angles(step: float, option: str = "--step", start: float = 0.0,
                span: tuple[float, float] = FULL_TURN) -> list[float]:
    """The crank angles of a full turn, 0 ≤ φ < 360 (or of ``span``: low ≤ φ < high),
    ``step`` degrees apart, one of them ``start`` (the exercise's own ``drive.angle``: a page
    opens there) or a whole number of steps from it.

    >>> turn_angles(90)
    [0.0, 90.0, 180.0, 270.0]
    >>> turn_angles(10, start=45)[:3], 45.0 in turn_angles(10, start=45)
    ([5.0, 15.0, 25.0], True)
    >>> turn_angles(30, start=45, span=(-60, 100))
    [-45.0, -15.0, 15.0, 45.0, 75.0]
    >>> turn_angles(0)
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: option --step: must be a number of degrees in [0.1, 180] ...
    """
    if not (isinstance(step, int | float) and math.isfinite(step)
            and MIN_STEP_DEG <= step <= 180):
        raise SpecError(message("must be a number of degrees in [{finest:g}, 180] (at most "
                                "{frames} frames), got {step:g}", finest=MIN_STEP_DEG,
                                frames=round(360 / MIN_STEP_DEG), step=step),
                        key=f"option {option}")
    low, high = _checked_span(span)
    offset = (float(start) - low) % step
    if step - offset < 1e-9 or offset >= high - low:   # rounding; a range shorter than that
        offset = 0.0
    count = math.ceil((high - low - offset) / step - 1e-9)
    return [round(low + offset + number * step, 9) + 0.0 for number in range(count)]


@contextlib.contextmanager
def limits_noted() -> Iterator[None]:
    """Note on a limit the mechanism meets inside the block (a toggle, a link that cannot
    reach, a jump between assemblies) that ``--from`` and ``--to`` give the angles the crank
    reaches (a page or an animation of a crank that cannot turn fully).

    >>> with limits_noted():
    ...     raise ToggleError("the guides are parallel", angle=120)
    Traceback (most recent call last):
    ...
    planmethod.errors.ToggleError: crank angle 120°: the guides are parallel; give the angles ...
    """
    try:
        yield
    except (ToggleError, AssemblyError, BranchJumpError) as error:
        raise error.noted(message("give the angles the crank reaches with --from and "
                                  "--to")) from None


def _checked_span(span: tuple[float, float]) -> tuple[float, float]:
    """``span`` (--from, --to) as two floats, refused unless finite, --to above --from and
    at most one turn past it."""
    low, high = (float(value) for value in span)
    if not math.isfinite(low):
        raise SpecError(message("must be a finite angle in degrees, got {angle:g}", angle=low),
                        key="option --from")
    if not (math.isfinite(high) and low < high <= low + 360.0):
        raise SpecError(message("must be above --from ({low:g}°) and at most one turn past it "
                                "({most:g}°), got {angle:g}", low=low, most=low + 360.0,
                                angle=high), key="option --to")
    return low, high


def turn_order(angles: Sequence[float], start: float, omega: float) -> list[float]:
    """The frames of a turn in the order the crank passes them: from ``start`` (the
    exercise's own angle), φ growing if ω ≥ 0 (counter-clockwise), else falling.

    >>> turn_order([0.0, 90.0, 180.0, 270.0], 90, 10)
    [90.0, 180.0, 270.0, 0.0]
    >>> turn_order([0.0, 90.0, 180.0, 270.0], 90, -10)
    [90.0, 0.0, 270.0, 180.0]
    """
    ordered = sorted(angles)
    first = min(range(len(ordered)), key=lambda index: (
        abs((ordered[index] - start + 180.0) % 360.0 - 180.0), index))
    turned = ordered[first:] + ordered[:first]
    return turned if omega >= 0 else turned[:1] + turned[1:][::-1]


def exercise_variant(exercise):
    """The variant whose key ``planmethod grade`` builds for this exercise file (the file's
    own ``[grading]`` table), or a variant with default grading settings for an exercise
    that has no file."""
    from ..grading.templates import Variant, draw_variant, load_template

    if exercise.source:
        variant = draw_variant(load_template(exercise.source))
        return replace(variant, exercise=exercise)
    return Variant("1", 0, 0, {}, {}, exercise)


def frame_data(analysis, variant, files: dict[str, str]) -> dict[str, Any]:
    """One frame of the page as plain data (see :func:`planmethod.render.workbook.
    workbook_html`), with the plan each quantity is read off (``reads``)."""
    from ..grading.keys import build_key, key_numbers
    from ..grading.plan_points import drawing_frame
    from ..grading.tolerances import exact_drawing
    from ..render.plan_words import step_text
    from ..render.svg import vector_equations

    drawings = {name.removesuffix(".svg"): text for name, text in files.items()}
    readings = [[check.analytic, check.plan] for check in analysis.checks]
    key = build_key(replace(variant, exercise=analysis.exercise), plans=analysis.plans)
    # the key's steps are those of the analysis's plans where they are its exact drawing:
    # their sentences are rendered once
    said = exact_drawing(analysis.plans, analysis.exercise)
    steps, equations, reads = {}, {}, {}
    if analysis.plans is not None:
        for name in ("velocity", "acceleration"):
            plan = getattr(analysis.plans, name)
            if plan is not None:
                texts = ([step["text"] for step in key["plans"][name]["steps"]] if said
                         else [step_text(step, plan) for step in plan.steps])
                steps[name] = [[step.number, text, step.action,
                                [point for point in (step.start, step.end) if point]]
                               for step, text in zip(plan.steps, texts, strict=True)]
                equations[name] = vector_equations(plan)
                reads |= {step.quantity: name for step in plan.steps
                          if step.action == "read" and step.quantity}
    questions = [{field: question[field] for field in QUESTION_FIELDS}
                 for question in key["questions"]]
    return {"drawings": drawings, "readings": readings, "steps": steps,
            "equations": equations, "reads": reads, "questions": questions,
            "tolerance_source": key["precision_mm"],
            "draw": drawing_frame(key, key_numbers(key))}


def solve_frames(exercise, angles: Sequence[float], views=None, variant=None
                 ) -> list[dict[str, Any]]:
    """The frames of the given angles as plain data (:func:`frame_data`), each with its
    check quantities (``quantities``) and balancing moment (``moment``, None without
    forces) for the full-turn curves; ``views`` keep each panel steady over the turn
    (:func:`planmethod.render.steady.steady_views`); ``variant`` is the exercise's
    (:func:`exercise_variant`, drawn here if not given: a page draws it once)."""
    import numpy as np

    from ..render.figures import plan_files
    from ..report import analyse

    if variant is None:
        variant = exercise_variant(exercise)
    out = []
    for angle in angles:
        analysis = analyse(exercise, angle)
        # many frames: no enlarged details and no loaded mechanism (solve --svg draws them)
        files = (plan_files(analysis.plans, forces=analysis.forces, details=False,
                            loaded=False, views=views) if analysis.plans else {})
        frame = frame_data(analysis, variant, files)
        frame["quantities"] = [(check.quantity, check.unit) for check in analysis.checks]
        frame["moment"] = (None if analysis.forces is None else
                           float(np.ravel(analysis.forces.balancing_moment)[0]))
        frame["precision_mm"] = analysis.exercise.plan.precision_mm
        out.append(frame)
    return out


def _solve_chunk(job: tuple) -> list[dict[str, Any]]:
    """A worker's chunk of frames, made in the language of the page."""
    exercise, angles, views, variant, language = job
    with speaking(language):
        return solve_frames(exercise, angles, views, variant)


def _solve_turn(exercise, angles: Sequence[float], workers: int, watch: Watch, views,
                variant, packing=None) -> list[dict[str, Any]]:
    """The frames of ``angles``, here (one worker) or in ``workers`` processes, in order;
    ``watch`` hears each (phase ``frames``) and may cancel the page between two; ``packing``
    (a :class:`_Packing`) packs them for the page as they come."""
    frames: list[dict[str, Any]] = []

    def done(solved: list[dict[str, Any]]) -> None:
        frames.extend(solved)
        if packing is not None:
            packing.add(solved)
        watch.step("frames", len(frames), len(angles))

    if workers == 1:
        for angle in angles:
            done(solve_frames(exercise, [angle], views, variant))
    else:
        language = current()
        in_workers(_solve_chunk, [(exercise, chunk, views, variant, language)
                                  for chunk in chunked(angles, workers)], workers, done)
    return frames


def build_workbook(exercise, step: float = DEFAULT_STEP, *, jobs: int | None = None,
                   watch: Watch | None = None, span: tuple[float, float] = FULL_TURN) -> str:
    """The workbook page of ``exercise`` as HTML, in the language spoken.

    Parameters
    ----------
    exercise
        The exercise (a :class:`planmethod.model.Exercise`).
    step
        The crank-angle step between two frames (deg).
    jobs
        Worker processes to solve the frames in: 1 solves them here, None takes every CPU
        this process may use with at least 12 frames each.
    watch
        Hears each frame solved (phase ``frames``) and may cancel the page.
    span
        The crank angles the page shows, from the first up to (not including) the second
        (deg; default a full turn): a crank that cannot turn fully (its mechanism meets a
        limit) gets a page of the angles it reaches.

    Raises
    ------
    ToggleError, AssemblyError, BranchJumpError
        If the mechanism cannot take a frame's angle: the message says that ``--from`` and
        ``--to`` give the angles the crank reaches (:func:`limits_noted`).

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> page = build_workbook(load_exercise("exercises/compressor_slider_crank.toml"), 120)
    >>> page.count('data-quantity="'), 'id="angle"' in page
    (7, True)
    """
    from ..numbering import course_numbers
    from ..render.steady import steady_views
    from ..render.workbook import WorkbookPage, curve_chart, workbook_html
    from ..vocabulary import numbered

    mechanism = exercise.mechanism
    angles = turn_angles(step, start=mechanism.drive.angle, span=span)   # opens at its own
    workers = worker_count(jobs, len(angles))
    with limits_noted():
        views = steady_views(exercise, angles)      # one zoom and one page per panel
        variant = exercise_variant(exercise)        # once: a frame keys it at its own angle
        packing = _Packing(angles)                  # the page's data made while frames come
        frames = _solve_turn(exercise, angles, workers, watch or Watch(), views, variant,
                             packing)
    numbers = course_numbers(mechanism)
    plans = reading_plans(frames)
    return workbook_html(WorkbookPage(
        mechanism.title, angles, _panels(frames[0]), frames,
        _page_quantities(frames[0], numbers, plans),
        charts=[curve_chart(angles, curves, title=title, unit=unit,
                            plans=sorted({plans[name] for name in names if plans.get(name)}))
                for title, unit, curves, names in turn_charts(frames, numbers)],
        notes=_notes(angles, step, frames[0], span), start=mechanism.drive.angle,
        phi=numbered("φ", numbers[mechanism.drive.link]),
        drawing=drawing_meta(exercise, frames), sense=-1 if mechanism.drive.omega < 0 else 1),
        rules=packing.rules, data=packing.data)


class _Packing:
    """A page's frames packed as they come (:class:`planmethod.render.workbook.PageData`, made
    at the first frame, whose drawings name the page's panels), and the page's rules
    (:func:`planmethod.render.page_rules.page_rules`, in the language spoken): while the
    workers solve the frames that follow, this process enters the lines of those solved in
    the page's string table and compresses them, instead of doing it all once the last frame
    is in."""

    def __init__(self, angles: Sequence[float]) -> None:
        self.angles = angles
        self.data = None
        self.rules = None

    def add(self, frames: Sequence[dict[str, Any]]) -> None:
        """The next frames of the turn, in order."""
        from ..render.page_rules import page_rules
        from ..render.workbook import PageData

        if self.data is None:
            self.data = PageData(self.angles, _panels(frames[0]))
        self.data.add(frames)
        if self.rules is None:      # (its Unicode tables take a third of a second, once)
            self.rules = page_rules()


def _panels(first: dict[str, Any]) -> list[str]:
    """The drawings a frame shows: :data:`PANELS` first, in their order, then the others."""
    panels = [name for name in PANELS if name in first["drawings"]]
    return panels + [name for name in first["drawings"] if name not in panels]


def _subscript(name: str, numbers: dict[str, int]) -> str:
    """A quantity's subscript as the course writes it: a link's by the link's number (ω₂), a
    point's by its name (v_B₃), a slide's by the numbers of its two links (s₂₃)."""
    from ..vocabulary import pair_number, point_name, quantity

    found = quantity(name)
    if found.kind.subject == "link" and found.subject in numbers:
        return str(numbers[found.subject])
    if found.kind.subject == "point":
        return point_name(found.subject, numbers)
    link, _, along = found.subject.partition("/")
    if found.kind.subject == "pair" and link in numbers and along in numbers:
        return pair_number(numbers[link], numbers[along])
    return found.subject.replace("_", " ")


def _page_quantities(first: dict[str, Any], numbers: dict[str, int],
                     plans: dict[str, str]) -> list[PageQuantity]:
    """The readings table's quantities: symbol, subscript, unit, the plan each is read off,
    what a negative value means and the words of its two senses."""
    from ..grading.answers import magnitude_note, sense_words
    from ..render.workbook import PageQuantity
    from ..vocabulary import quantity, unit_words

    return [PageQuantity(name, quantity(name).symbol, _subscript(name, numbers),
                         render(unit_words(unit)),
                         plans.get(name), magnitude_note(name, numbers), sense_words(name))
            for name, unit in first["quantities"]]


def _notes(angles: Sequence[float], step: float, first: dict[str, Any],
           span: tuple[float, float]) -> list[Message]:
    """The page's notes: how many positions (and from which angle to which, unless a full
    turn), how they are drawn, how practice grades."""
    precision = first["precision_mm"]
    positions = len(angles)
    if span == FULL_TURN:
        drawn = (message("{positions} positions, every {step:g}°; drawings by planmethod, "
                         "drafting precision {precision:g} mm", positions=positions, step=step,
                         precision=precision) if precision else
                 message("{positions} positions, every {step:g}°; drawings by planmethod, exact "
                         "construction", positions=positions, step=step))
    else:
        drawn = (message("{positions} positions from {first:g}° to {last:g}°, every {step:g}°; "
                         "drawings by planmethod, drafting precision {precision:g} mm",
                         positions=positions, first=angles[0], last=angles[-1], step=step,
                         precision=precision) if precision else
                 message("{positions} positions from {first:g}° to {last:g}°, every {step:g}°; "
                         "drawings by planmethod, exact construction", positions=positions,
                         first=angles[0], last=angles[-1], step=step))
    graded = message("practice mode grades as `planmethod grade` does: tolerances from a "
                     "drafting precision of {precision:g} mm (each tolerance is shown)",
                     precision=first["tolerance_source"])
    return [drawn, graded]


def drawing_meta(exercise, frames: Sequence[dict[str, Any]]) -> dict[str, Any] | None:
    """The drawing mode's data for the whole page (:func:`planmethod.render.workbook_draw.
    drawing_data`): one sheet per plan for the turn, each point's course name (b₃), the
    mistakes with what the student is told. None when no frame has a plan to draw.

    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/slotted_lever.toml")
    >>> meta = drawing_meta(exercise, solve_frames(exercise, [30.0]))
    >>> meta["names"]["b@lever"], meta["poles"]
    ('b₃', {'velocity': 'p', 'acceleration': 'π'})
    """
    from ..grading.drawings import DRAWING_FORMAT, exercise_digest
    from ..grading.mistakes import drawn_explanation
    from ..grading.plan_points import DRAWN_MISTAKES, plan_extent
    from ..numbering import course_numbers
    from ..render.labels import label_runs
    from ..render.plan_words import label_text
    from ..render.workbook_draw import drawing_data
    from ..vocabulary import numbered
    from ..words import render

    draws = [frame.get("draw", {}) for frame in frames]
    plans = [plan for plan in ("velocity", "acceleration")
             if any(plan in draw for draw in draws)]
    if not plans:
        return None
    mechanism = exercise.mechanism
    numbers = course_numbers(mechanism)
    labels = {label for draw in draws for entry in draw.values()
              for label in (*entry["points"], *entry["others"])}
    poles = {plan: next(draw[plan]["pole"] for draw in draws if plan in draw)
             for plan in plans}
    return drawing_data(
        title=mechanism.title, exercise=exercise_digest(exercise),
        names={label: label_text(label, numbers) for label in sorted(labels)},
        runs={label: label_runs(label, numbers) for label in sorted(labels)},
        poles=poles, extents={plan: plan_extent(draws, plan) for plan in plans},
        mistakes=[(mistake, render(drawn_explanation(mistake))) for mistake in DRAWN_MISTAKES],
        file_format=DRAWING_FORMAT,
        phi=numbered("φ", numbers[mechanism.drive.link]))


def reading_plans(frames: Sequence[dict[str, Any]]) -> dict[str, str]:
    """The plan each check quantity of the ``frames`` is read off (``velocity`` or
    ``acceleration``): where a frame's construction reads it (ρ off the acceleration plan),
    else the plan drawn at the quantity's scale (μv, μa); a quantity of neither (the travel
    s, at μl) is in none. The drawing mode hides their values until that plan is shown.

    >>> reading_plans([{"quantities": [("v_C", "m/s"), ("rho_D", "m"), ("s_C/frame", "m")],
    ...                 "reads": {"rho_D": "acceleration"}}])
    {'v_C': 'velocity', 'rho_D': 'acceleration'}
    """
    from ..vocabulary import PLAN_SCALES, PlanKind, quantity

    by_scale = {scale: kind.value for kind, scale in PLAN_SCALES.items()
                if kind != PlanKind.POSITION}
    reads: dict[str, str] = {}
    for frame in frames:
        reads |= frame.get("reads", {})
    out = {}
    for name, _ in frames[0]["quantities"]:
        plan = reads.get(name) or by_scale.get(quantity(name).scale)
        if plan is not None:
            out[name] = plan
    return out


#: the full-turn charts, by the kind of quantity they draw: their titles
_CHART_TITLES = {"v": message("velocities"), "a": message("accelerations"),
                 "omega": message("angular velocities"),
                 "epsilon": message("angular accelerations")}


def turn_charts(frames: Sequence[dict[str, Any]], numbers: dict[str, int] | None = None
                ) -> list[tuple[str, str, dict, list[str]]]:
    """The full-turn curves: speeds, accelerations, angular velocities and accelerations of
    the checks, and the balancing moment when forces are computed; each curve named as a
    course writes it (ω₃ with the links' ``numbers``, v_C). Each chart is (title, unit,
    {curve: values}, the check quantities it draws), its title in the language spoken."""
    from ..vocabulary import symbol, unit_words

    charts: dict[str, tuple[str, str, dict, list[str]]] = {}
    for index, (name, unit) in enumerate(frames[0]["quantities"]):
        kind = name.partition("_")[0]
        if kind not in _CHART_TITLES:
            continue
        _, _, curves, names = charts.setdefault(kind, (render(_CHART_TITLES[kind]),
                                                       render(unit_words(unit)),
                                                       {}, []))
        curves[symbol(name, numbers)] = [frame["readings"][index][0] for frame in frames]
        names.append(name)
    out = list(charts.values())
    if frames[0]["moment"] is not None:
        out.append((render(message("balancing moment")),
                    render(message("N·m", context="unit")),
                    {"M_b": [frame["moment"] for frame in frames]}, []))
    return out
