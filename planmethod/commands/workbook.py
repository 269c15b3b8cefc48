"""``planmethod workbook FILE -o PAGE.html``: one offline HTML page for a full turn of the crank.

Every frame (one crank angle every ``--step`` degrees) is solved here as ``planmethod solve
--angle A`` solves it: its drawings are the ones ``solve --svg`` writes, its readings are the
report's ``checks``, and its grading questions are those of the answer key ``planmethod
grade`` builds at that angle. The page (:mod:`planmethod.render.workbook`) only shows them.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

from ..errors import SpecError

#: the finest crank-angle step of a workbook or an animation (deg): 3,600 frames
MIN_STEP_DEG = 0.1

#: default crank-angle step of a workbook (deg)
DEFAULT_STEP = 5.0

#: the drawings a frame shows, in this order, by file name of ``plan_files``
PANELS = ("position", "velocity", "acceleration", "lever")

#: what a question of the key keeps in the page (its ``text`` is not shown)
QUESTION_FIELDS = ("id", "symbol", "value", "tolerance", "unit", "signed", "mistakes")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML)")
    parser.add_argument("-o", "--output", required=True, metavar="PAGE.html",
                        help="the HTML page to write")
    parser.add_argument("--step", type=float, default=DEFAULT_STEP, metavar="DEG",
                        help=f"crank-angle step in degrees (default {DEFAULT_STEP:g}; "
                             "1 gives 360 frames)")
    parser.add_argument("--jobs", type=int, metavar="N",
                        help="worker processes, at most the CPUs this process may use "
                             "(default: every CPU, at least 12 frames each)")


def turn_angles(step: float, option: str = "--step", start: float = 0.0) -> list[float]:
    """The crank angles of a full turn, 0 ≤ φ < 360, ``step`` degrees apart, one of them
    ``start`` (the exercise's own ``drive.angle``: a page opens there).

    >>> turn_angles(90)
    [0.0, 90.0, 180.0, 270.0]
    >>> turn_angles(10, start=45)[:3], 45.0 in turn_angles(10, start=45)
    ([5.0, 15.0, 25.0], True)
    >>> turn_angles(0)
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: option --step: must be a number of degrees in [0.1, 180] ...
    """
    if not (isinstance(step, int | float) and math.isfinite(step)
            and MIN_STEP_DEG <= step <= 180):
        raise SpecError(f"must be a number of degrees in [{MIN_STEP_DEG:g}, 180] (at most "
                        f"{round(360 / MIN_STEP_DEG)} frames), got {step:g}",
                        key=f"option {option}")
    offset = float(start) % step
    if step - offset < 1e-9:          # start a whole number of steps from 0, but for rounding
        offset = 0.0
    count = math.ceil((360.0 - offset) / step - 1e-9)
    return [round(offset + number * step, 9) + 0.0 for number in range(count)]


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
    from ..grading.keys import build_key
    from ..grading.plan_points import drawing_frame
    from ..render.svg import vector_equations

    drawings = {name.removesuffix(".svg"): text for name, text in files.items()}
    readings = [[check.analytic, check.plan] for check in analysis.checks]
    steps, equations, reads = {}, {}, {}
    if analysis.plans is not None:
        for name in ("velocity", "acceleration"):
            plan = getattr(analysis.plans, name)
            if plan is not None:
                steps[name] = [[step.number, step.text, step.action,
                                 [point for point in (step.start, step.end) if point]]
                                for step in plan.steps]
                equations[name] = vector_equations(plan)
                reads |= {step.quantity: name for step in plan.steps
                          if step.action == "read" and step.quantity}
    key = build_key(replace(variant, exercise=analysis.exercise))
    questions = [{field: question[field] for field in QUESTION_FIELDS}
                 for question in key["questions"]]
    return {"drawings": drawings, "readings": readings, "steps": steps,
            "equations": equations, "reads": reads, "questions": questions,
            "tolerance_source": key["precision_mm"], "draw": drawing_frame(key)}


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
    exercise, angles, views, variant = job
    return solve_frames(exercise, angles, views, variant)


def usable_cpus() -> int:
    """The CPUs this process may run on (its CPU affinity, where the system tells it).

    >>> usable_cpus() >= 1
    True
    """
    import os

    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0)) or 1
    return os.cpu_count() or 1


def worker_count(jobs: int | None, frames: int) -> int:
    """Worker processes for ``frames`` frames: ``jobs`` (1 … the usable CPUs, else a
    :class:`SpecError`), by default every CPU with at least 12 frames each; never more than
    there are frames.

    >>> worker_count(None, 1), worker_count(1, 100)
    (1, 1)
    >>> worker_count(100_000, 4)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: option --jobs: must be a number of processes in 1…...
    """
    cpus = usable_cpus()
    if jobs is None:
        return max(1, min(cpus, frames // 12))
    if not 1 <= jobs <= cpus:
        raise SpecError(f"must be a number of processes in 1…{cpus} (the CPUs this process "
                        f"may use), got {jobs}", key="option --jobs")
    return max(1, min(jobs, frames))


def _end_with_parent(parent: int | None) -> None:
    """A worker's first act: end with the process that started it. SIGTERM ends it at once
    (not through the command's handler, which a pool worker would report and go on), Ctrl-C
    is left to the parent, and on Linux the kernel kills it when its parent ends, even by
    SIGKILL (``prctl(PR_SET_PDEATHSIG)``)."""
    import contextlib
    import os
    import signal
    import sys

    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        import ctypes

        set_parent_death_signal = 1   # PR_SET_PDEATHSIG of <linux/prctl.h>
        with contextlib.suppress(OSError, AttributeError):   # no libc or no prctl
            ctypes.CDLL(None, use_errno=True).prctl(set_parent_death_signal,
                                                    int(signal.SIGKILL), 0, 0, 0)
    if parent is not None and os.getppid() != parent:   # the parent ended before that
        os._exit(1)


def _solve_in_workers(exercise, angles: Sequence[float], workers: int,
                      progress: Callable[[int, int], None] | None, views=None, variant=None
                      ) -> list[dict[str, Any]]:
    """The frames of ``angles`` solved in ``workers`` processes, in order. The pool is
    terminated whenever this ends — done, failed, Ctrl-C or SIGTERM (the command line turns
    it into an exception here) — so that no worker outlives the command."""
    import multiprocessing
    import os
    import sys

    size = math.ceil(len(angles) / (4 * workers))
    chunks = [(exercise, angles[start:start + size], views, variant)
              for start in range(0, len(angles), size)]
    # fork on Linux: the workers are this process's children (the parent check above holds)
    method = "fork" if sys.platform.startswith("linux") else None
    context = multiprocessing.get_context(method)
    parent = os.getpid() if method == "fork" else None
    frames: list[dict[str, Any]] = []
    with context.Pool(min(workers, len(chunks)), initializer=_end_with_parent,
                      initargs=(parent,)) as pool:   # leaving the block terminates the pool
        for done in pool.imap(_solve_chunk, chunks):
            frames += done
            if progress is not None:
                progress(len(frames), len(angles))
    return frames


def build_workbook(exercise, step: float = DEFAULT_STEP, *, jobs: int | None = None,
                   progress: Callable[[int, int], None] | None = None) -> str:
    """The workbook page of ``exercise`` (an :class:`~planmethod.model.Exercise`) as HTML.

    The frames are solved in ``jobs`` worker processes (see :func:`worker_count`; 1 solves
    them here).

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> page = build_workbook(load_exercise("exercises/compressor_slider_crank.toml"), 120)
    >>> page.count('data-quantity="'), 'id="angle"' in page
    (7, True)
    """
    from ..grading.answers import magnitude_note, sense_words
    from ..numbering import course_numbers
    from ..render.steady import steady_views
    from ..render.workbook import PageQuantity, WorkbookPage, curve_chart, workbook_html
    from ..vocabulary import numbered, pair_number, point_name, quantity

    angles = turn_angles(step, start=exercise.mechanism.drive.angle)   # opens at its own angle
    workers = worker_count(jobs, len(angles))
    views = steady_views(exercise, angles)      # one zoom and one page per panel
    variant = exercise_variant(exercise)        # once: a frame keys it at its own angle
    frames: list[dict[str, Any]] = []
    if workers == 1:
        for angle in angles:
            frames += solve_frames(exercise, [angle], views, variant)
            if progress is not None:
                progress(len(frames), len(angles))
    else:
        frames = _solve_in_workers(exercise, angles, workers, progress, views, variant)
    first = frames[0]
    mechanism = exercise.mechanism
    numbers = course_numbers(mechanism)

    def subscript(name: str) -> str:
        """A link's quantity by the link's number (ω₂), a point's by its name (v_B₃), a
        slide's by the numbers of its two links (s₂₃)."""
        found = quantity(name)
        if found.kind.subject == "link" and found.subject in numbers:
            return str(numbers[found.subject])
        if found.kind.subject == "point":
            return point_name(found.subject, numbers)
        link, _, along = found.subject.partition("/")
        if found.kind.subject == "pair" and link in numbers and along in numbers:
            return pair_number(numbers[link], numbers[along])
        return found.subject.replace("_", " ")

    plans = reading_plans(frames)
    quantities = [PageQuantity(name, quantity(name).symbol, subscript(name), unit,
                               plans.get(name), magnitude_note(name, numbers), sense_words(name))
                  for name, unit in first["quantities"]]
    panels = [name for name in PANELS if name in first["drawings"]]
    panels += [name for name in first["drawings"] if name not in panels]
    precision = first["precision_mm"]
    notes = [f"{len(angles)} positions, every {step:g}°; drawings by planmethod, "
             f"drafting precision {precision:g} mm" if precision else
             f"{len(angles)} positions, every {step:g}°; drawings by planmethod, exact "
             "construction",
             f"practice mode grades as `planmethod grade` does: tolerances from a drafting "
             f"precision of {first['tolerance_source']:g} mm (each tolerance is shown)"]
    charts = turn_charts(frames, numbers)
    return workbook_html(WorkbookPage(
        exercise.mechanism.title, angles, panels, frames, quantities,
        charts=[curve_chart(angles, curves, title=title, unit=unit,
                            plans=sorted({plans[name] for name in names if plans.get(name)}))
                for title, unit, curves, names in charts],
        notes=notes, start=mechanism.drive.angle,
        phi=numbered("φ", numbers[mechanism.drive.link]),
        drawing=drawing_meta(exercise, frames), sense=-1 if mechanism.drive.omega < 0 else 1))


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
    from ..plans.construction import course_text
    from ..render.labels import label_runs
    from ..render.workbook_draw import drawing_data
    from ..vocabulary import numbered

    draws = [frame.get("draw", {}) for frame in frames]
    plans = [plan for plan in ("velocity", "acceleration")
             if any(plan in draw for draw in draws)]
    if not plans:
        return None
    mechanism = exercise.mechanism
    numbers = course_numbers(mechanism)
    labels = {label for draw in draws for entry in draw.values() for label in entry["points"]}
    poles = {plan: next(draw[plan]["pole"] for draw in draws if plan in draw)
             for plan in plans}
    return drawing_data(
        title=mechanism.title, exercise=exercise_digest(exercise),
        names={label: course_text(label, numbers) for label in sorted(labels)},
        runs={label: label_runs(label, numbers) for label in sorted(labels)},
        poles=poles, extents={plan: plan_extent(draws, plan) for plan in plans},
        mistakes=[(mistake, drawn_explanation(mistake)) for mistake in DRAWN_MISTAKES],
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


def turn_charts(frames: Sequence[dict[str, Any]], numbers: dict[str, int] | None = None
                ) -> list[tuple[str, str, dict, list[str]]]:
    """The full-turn curves: speeds, accelerations, angular velocities and accelerations of
    the checks, and the balancing moment when forces are computed; each curve named as a
    course writes it (ω₃ with the links' ``numbers``, v_C). Each chart is (title, unit,
    {curve: values}, the check quantities it draws)."""
    from ..vocabulary import symbol

    titles = {"v": "velocities", "a": "accelerations", "omega": "angular velocities",
              "epsilon": "angular accelerations"}
    charts: dict[str, tuple[str, str, dict, list[str]]] = {}
    for index, (name, unit) in enumerate(frames[0]["quantities"]):
        kind = name.partition("_")[0]
        if kind not in titles:
            continue
        _, _, curves, names = charts.setdefault(kind, (titles[kind], unit, {}, []))
        curves[symbol(name, numbers)] = [frame["readings"][index][0] for frame in frames]
        names.append(name)
    out = list(charts.values())
    if frames[0]["moment"] is not None:
        out.append(("balancing moment", "N·m", {"M_b": [frame["moment"] for frame in frames]},
                    []))
    return out


def run(args: argparse.Namespace) -> int:
    import sys
    from pathlib import Path

    from ..io import write_text_atomic
    from ..spec import load_exercise

    if Path(args.output).suffix.lower() not in (".html", ".htm"):
        raise SpecError(f"the page must be an .html file, got {args.output!r}",
                        key="option -o")
    worker_count(args.jobs, len(turn_angles(args.step)))   # before any work
    exercise = load_exercise(args.file)

    def progress(done: int, total: int) -> None:
        if sys.stderr.isatty():
            print(f"\rframe {done}/{total}", end="" if done < total else "\n",
                  file=sys.stderr)

    page = build_workbook(exercise, args.step, jobs=args.jobs, progress=progress)
    write_text_atomic(args.output, page)
    print(f"Wrote {args.output} ({len(page.encode('utf-8')) / 1e6:.2f} MB)")
    return 0
