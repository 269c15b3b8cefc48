"""Answer keys: every asked value with its tolerance, the plan points in mm with their
tolerance radii, and the answers that common mistakes would give.

A key is plain JSON (``format: "planmethod-key"``) so that graders and LMS exports read it
without planmethod's solvers::

    {"format": "planmethod-key", "version": 1, "student": "s01", "seed": 7, "attempt": 0,
     "title": ..., "task": "what is asked, with the given data", "given": {"l_AB": 0.06, ...},
     "angle": 45.0, "exercise": {...the resolved exercise tables...},
     "scales": {"mu_l": ..., "mu_v": ..., "mu_a": ...}, "precision_mm": 0.5,
     "questions": [{"id": "v_C", "text": ..., "unit": "m/s", "value": 5.27, "signed": false,
                    "tolerance": 0.094, "tolerance_from": "drawing", "points": 1.0,
                    "mistakes": [{"kind": "scale_twice", "value": 1.05, "tolerance": 0.019}]}],
     "plans": {"position": {"mu_l": ..., "points_mm": {...}},
               "velocity": {"pole": "p", "scale": ..., "points_mm": {...},
                            "tolerance_mm": {...}, "steps": [...],
                            "mistakes": {"sense": {...points...}},
                            "mistake_points": {"c": [["sense", x, y], ...]}},
               "acceleration": {...}}}

``mistakes`` holds the points of each plan re-drawn with a construction mistake (the velocity
plan turned 180° under ``sense``); ``mistake_points`` lists, for each point a student draws,
where the known mistakes put it (:func:`~planmethod.grading.mistakes.drawn_mistakes`).

The ``[grading]`` table of a template or exercise file sets ``precision_mm`` (default 0.5),
``rel_floor`` (default 0.005), ``points`` (default per question, 1) and per-quantity overrides::

    [grading.tolerance]
    v_C = { rel = 0.03 }        # ±3 % of the exact value
    rho_D = { abs = 0.002 }     # ±0.002 m
    [grading.points]
    rho_D = 2

A bundle of keys (``format: "planmethod-keys"``) holds the keys of all variants of a run.

Examples
--------
>>> from planmethod.grading.templates import load_template, draw_variant
>>> key = build_key(draw_variant(load_template("exercises/compressor_slider_crank.toml")))
>>> question = next(q for q in key_questions(key) if q.id == "omega_BC")
>>> round(question.value, 3), question.signed, question.tolerance_from
(-24.254, True, 'drawing')
"""

from __future__ import annotations

import math
import stat
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..errors import PlanmethodError, SpecError, value_text
from ..io import read_text_bounded
from ..numbering import course_numbers
from ..render.plan_words import line_text, step_dict
from ..spec import checked_table, parse_json
from ..vocabulary import QUANTITY_KINDS, symbol
from ..vocabulary import question_text as course_question
from ..words import Message, message, template
from .mistakes import (
    CONSTRUCTION_MISTAKES,
    MISTAKES,
    REGISTRY,
    drawn_mistakes,
    mistaken_plans,
    plan_context,
    value_answers,
)
from .plan_points import drawn_labels
from .results import KeyMistake, KeyQuestion
from .tolerances import kind_of, propagate

__all__ = [
    "KEYS_FORMAT",
    "KEY_FORMAT",
    "GradingSettings",
    "ReadKey",
    "build_key",
    "bundle",
    "grading_settings",
    "key_numbers",
    "key_questions",
    "load_keys",
    "question_text",
]

KEY_FORMAT = "planmethod-key"
KEYS_FORMAT = "planmethod-keys"
VERSION = 1

#: the largest key or bundle read (bytes): some 20,000 students of the largest shipped exercise
MAX_KEYS_BYTES = 1_000_000_000

#: Keys of the [grading] table.
GRADING_KEYS = ("precision_mm", "rel_floor", "points", "tolerance")

#: Absolute floor of a tolerance, as a fraction of the drive's own value of the same kind.
ABS_FLOOR = 1e-3


class ReadKey(dict):
    """A key as read from a file: its tables, and where they are — ``file``, and the key's
    ``place`` in a bundle (``keys[3]``; empty for a key file of its own) — so that an error
    in the exercise the key keeps names the file it was read from, not the exercise file it
    was built from long ago (:func:`key_exercise`)."""

    __slots__ = ("file", "place")

    def __init__(self, tables: Mapping[str, Any], file: str, place: str = "") -> None:
        super().__init__(tables)
        self.file, self.place = file, place


class GradingSettings:
    """The parsed ``[grading]`` table."""

    __slots__ = ("overrides", "points", "precision_mm", "rel_floor")

    def __init__(self, precision_mm: float = 0.5, rel_floor: float = 0.005,
                 points: Mapping[str, float] | None = None, default_points: float = 1.0,
                 overrides: Mapping[str, tuple[str, float]] | None = None) -> None:
        self.precision_mm = precision_mm
        self.rel_floor = rel_floor
        self.points = {"*": default_points, **(points or {})}
        self.overrides = dict(overrides or {})


def _positive(value: Any, key: str, file: str | None, *, zero: bool = False) -> float:
    if (isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value)
            or value < 0 or (value == 0 and not zero)):
        raise SpecError(message("must be a non-negative number, got {given}",
                                given=value_text(value)) if zero else
                        message("must be a positive number, got {given}",
                                given=value_text(value)), file=file, key=key)
    return float(value)


def _not_asked(name: str, quantities, file: str | None, key: str) -> SpecError:
    return SpecError(message("'{name}' is not asked; asked: {asked}", name=name,
                             asked=list(quantities)), file=file, key=key)


def grading_settings(data: Mapping[str, Any], file: str | None = None,
                     quantities=()) -> GradingSettings:
    """Read the ``[grading]`` table of resolved exercise tables (key-precise errors)."""
    table = checked_table(data.get("grading", {}), "grading", GRADING_KEYS, file=file)
    precision = _positive(table.get("precision_mm", 0.5), "grading.precision_mm", file,
                          zero=True)
    rel_floor = _positive(table.get("rel_floor", 0.005), "grading.rel_floor", file, zero=True)
    points_table = table.get("points", 1.0)
    points: dict[str, float] = {}
    default_points = 1.0
    if isinstance(points_table, Mapping):
        for name, value in points_table.items():
            if quantities and name not in quantities:
                raise _not_asked(name, quantities, file, f"grading.points.{name}")
            points[name] = _positive(value, f"grading.points.{name}", file, zero=True)
    else:
        default_points = _positive(points_table, "grading.points", file, zero=True)
    overrides: dict[str, tuple[str, float]] = {}
    tolerance = table.get("tolerance", {})
    if not isinstance(tolerance, Mapping):
        raise SpecError(message("must be a table of quantity = {{ rel = … }} or {{ abs = … }}"),
                        file=file, key="grading.tolerance")
    for name, value in tolerance.items():
        key = f"grading.tolerance.{name}"
        if quantities and name not in quantities:
            raise _not_asked(name, quantities, file, key)
        if isinstance(value, Mapping) and len(value) == 1 and next(iter(value)) in ("rel", "abs"):
            which = next(iter(value))
            overrides[name] = (which, _positive(value[which], f"{key}.{which}", file))
        elif isinstance(value, int | float) and not isinstance(value, bool):
            overrides[name] = ("abs", _positive(value, key, file))
        else:
            raise SpecError(message("must be {{ rel = r }} or {{ abs = a }}, got {given}",
                                    given=value_text(value)), file=file, key=key)
    return GradingSettings(precision, rel_floor, points, default_points, overrides)


def question_text(quantity: str, numbers: Mapping[str, int] | None = None) -> str:
    """What a quantity asks, in words and in the course's symbols (``numbers``: the links'
    numbers, :func:`planmethod.numbering.course_numbers`).

    Examples
    --------
    >>> question_text("omega_BC"), question_text("omega_BC", {"frame": 0, "AB": 1, "BC": 2})
    ('angular velocity ω of BC (counter-clockwise positive)', \
'angular velocity ω₂ of link 2 (BC) (counter-clockwise positive)')
    """
    try:   # words: vocabulary (English text until it returns a message)
        return course_question(quantity, numbers)
    except KeyError:
        return quantity


def key_questions(key: Mapping[str, Any]) -> tuple[KeyQuestion, ...]:
    """A key's questions, typed (a key file's are checked when it is read:
    :func:`load_keys`).

    >>> key_questions({"questions": [{"id": "v_C", "value": 5.27, "tolerance": 0.1}]})[0].unit
    ''
    """
    return tuple(KeyQuestion.read(question) for question in key.get("questions", ()))


def key_numbers(key: Mapping[str, Any]) -> dict[str, int]:
    """The links' numbers a key's texts use: its own ``numbers``, or for a key written
    before they were kept, those of its exercise (empty if it has none)."""
    if key.get("numbers"):
        return {str(link): int(number) for link, number in key["numbers"].items()}
    if not key.get("exercise"):
        return {}
    from ..spec import exercise_from_dict

    try:
        return course_numbers(exercise_from_dict(key["exercise"]).mechanism)
    except PlanmethodError:
        return {}


def _drive_reference(exercise, kind: str) -> float:
    drive = exercise.mechanism.drive
    link = exercise.mechanism.links[drive.link]
    length = max(link.length(drive.pivot, p) for p in link.points)
    omega, epsilon = abs(drive.omega), abs(drive.epsilon)
    return {
        "v": omega * length, "ds": omega * length,
        "a": length * math.hypot(omega ** 2, epsilon), "dds": length * math.hypot(omega ** 2,
                                                                               epsilon),
        "coriolis": length * omega ** 2, "omega": omega, "epsilon": max(epsilon, omega ** 2),
        "rho": length, "s": length,
    }.get(kind, 0.0)


#: two mistakes that give the same answer: one explanation or the other
_OR = template("{first}, or {second}")


def _mistake_answers(quantity: str, value: float, tolerance: float, scales, alternatives,
                     motion) -> list[tuple[str, float, float]]:
    """(mistake, wrong answer, its tolerance) of every mistake of
    :data:`~planmethod.grading.mistakes.REGISTRY` for one quantity, in registry order: a
    construction mistake's reading off its re-drawn plans (``alternatives``), a value
    mistake's answer from the right value."""
    values: dict[str, list[tuple[float, float]]] = {}
    for mistake, wrong, wrong_tolerance in value_answers(quantity, value, tolerance,
                                                          scales=scales, motion=motion):
        values.setdefault(mistake, []).append((wrong, wrong_tolerance))
    found: list[tuple[str, float, float]] = []
    for key, mistake in REGISTRY.items():
        if mistake.redraws:
            wrong = (alternatives.get(key) or {}).get(quantity)
            if wrong is not None and math.isfinite(float(wrong)):
                found.append((key, float(wrong), tolerance))
        else:
            found += [(key, wrong, wrong_tolerance)
                      for wrong, wrong_tolerance in values.get(key, ())]
    return found


def _mistakes(quantity: str, value: float, tolerance: float, scales, alternatives,
              motion) -> tuple[KeyMistake, ...]:
    """The answers the mistakes give for one quantity, in registry order (only those told
    apart from the right answer by more than twice the tolerance; two that give the same
    answer are one, named with both)."""
    out: list[list] = []    # [kind, answer, tolerance, the others: None until one is met]
    for mistake, wrong, wrong_tolerance in _mistake_answers(quantity, value, tolerance,
                                                             scales, alternatives, motion):
        if abs(wrong - value) <= 2 * tolerance:
            continue
        same = next((other for other in out
                     if abs(wrong - other[1]) <= 1e-12 * max(1.0, abs(wrong))), None)
        if same is None:
            out.append([mistake, wrong, abs(wrong_tolerance), None])
            continue
        # the same answer again (of another mistake, or of this one another way): a key
        # lists the others, and the feedback names them all
        same[3] = same[3] if same[3] is not None else []
        if mistake not in same[3] and mistake != same[0]:
            same[3].append(mistake)
    return tuple(KeyMistake(kind, wrong, wrong_tolerance, _explained(kind, also or ()),
                            tuple(also) if also is not None else None)
                 for kind, wrong, wrong_tolerance, also in out)


def _explained(kind: str, also) -> Message:
    """What a student is told whose answer ``kind`` and the mistakes ``also`` give."""
    explanation = MISTAKES[kind]
    for other in also:
        explanation = _OR.replace(first=explanation, second=MISTAKES[other])
    return explanation


def _tolerance(quantity: str, value: float, drawing: float, exercise,
               settings: GradingSettings) -> tuple[float, str]:
    """A question's tolerance and where it comes from: the drawing's own (``drawing``: the
    reading errors propagated), raised to the floor, or the ``[grading]`` table's override."""
    kind = kind_of(quantity)
    floor = max(settings.rel_floor * abs(value), ABS_FLOOR * _drive_reference(exercise, kind))
    tolerance, source = drawing, "drawing"
    if tolerance < floor:
        tolerance, source = floor, "floor"
    if quantity in settings.overrides:
        which, amount = settings.overrides[quantity]
        tolerance = amount * abs(value) if which == "rel" else amount
        source = f"override ({which})"
    return tolerance, source


def _plan_table(found, scales, settings: GradingSettings, wrong_plans: dict,
                motion) -> dict[str, Any]:
    """The key's plans: the position plan's points, and each drawn plan's points with their
    tolerance discs, its steps and where a mistake puts its points."""
    plans = found.plans
    table: dict[str, Any] = {"position": {"mu_l": scales.mu_l,
                                          "points_mm": dict(plans.position.points_mm)}}
    for name in ("velocity", "acceleration"):
        plan = getattr(plans, name)
        if plan is None:
            continue
        radii = found.radii[name]
        floor_mm = settings.precision_mm / 2
        entry = {"pole": plan.pole, "scale": plan.scale, "unit": plan.unit,
                 "points_mm": {k: list(v) for k, v in plan.points_mm.items()},
                 "tolerance_mm": {k: max(radii.get(k, 0.0), floor_mm if k != plan.pole else 0.0)
                                  for k in plan.points_mm},
                 "steps": [_key_step(step, plan) for step in plan.steps],
                 "mistakes": {}}
        if name == "velocity":
            entry["mistakes"]["sense"] = {k: [-v[0], -v[1]] for k, v in plan.points_mm.items()}
        else:
            for mistake, wrong in wrong_plans.items():
                entry["mistakes"][mistake] = {
                    k: list(v) for k, v in wrong.acceleration.points_mm.items()}
        # where the known mistakes put each point a student draws (named when one lands there)
        entry["mistake_points"] = drawn_mistakes(
            plan_context(plans, name, motion), entry["tolerance_mm"], entry["mistakes"],
            drawn_labels(entry))
        table[name] = entry
    return table


def _key_step(step, plan) -> dict[str, Any]:
    """A step of a key's plan: as the JSON report writes it, and a line step with its line's
    name (``line``: what a drawn point's sentence names the line by)."""
    entry = step_dict(step, plan)
    line = line_text(step, plan)
    if line is not None:
        entry["line"] = line
    return entry


def _propagation(variant, exercise, settings: GradingSettings, quantities, motion, plans):
    """The drawing tolerances of the variant's quantities: those found while its draw was
    checked, when they are of that very exercise at these settings, else found now."""
    found = getattr(variant, "propagation", None)
    if (found is None or found.plans.exercise is not exercise   # that very exercise only
            or found.precision_mm != settings.precision_mm
            or set(found.values) != set(quantities)):
        found = propagate(exercise, settings.precision_mm, quantities=quantities,
                          motion=motion, plans=plans)
    return found


def _wrong_plans(exercise, found, motion) -> dict:
    """The plans re-drawn with each construction mistake that changes them."""
    wrong_plans = {}
    drawn = tuple(zip(found.lengths, found.segments, strict=True)) if found.lengths else None
    for mistake in CONSTRUCTION_MISTAKES:
        plans = mistaken_plans(exercise, mistake, motion=motion, drawn=drawn)
        if plans is not None:
            wrong_plans[mistake] = plans
    return wrong_plans


def _questions(exercise, quantities, found, settings: GradingSettings, scales,
               wrong_plans: dict, motion) -> list[KeyQuestion]:
    """The key's questions: each asked quantity with a finite value, its tolerance and the
    answers the mistakes give."""
    alternatives = {mistake: plans.readings for mistake, plans in wrong_plans.items()}
    numbers = course_numbers(exercise.mechanism)
    questions = []
    for quantity in quantities:
        value = found.values[quantity]
        if value is None:  # a straight path has no finite ρ: nothing to ask
            continue
        tolerance, source = _tolerance(quantity, value, found.tolerances[quantity], exercise,
                                       settings)
        kind = QUANTITY_KINDS[kind_of(quantity)]
        questions.append(KeyQuestion(
            quantity, value, tolerance, symbol(quantity, numbers), kind.unit,
            question_text(quantity, numbers), kind.signed, source,
            settings.points.get(quantity, settings.points["*"]),
            _mistakes(quantity, value, tolerance, scales, alternatives, motion)))
    return questions


def build_key(variant, *, settings: GradingSettings | None = None, plans=None) -> dict:
    """The answer key of a variant (:class:`~planmethod.grading.templates.Variant`).

    Parameters
    ----------
    variant
        The variant to key.
    settings
        The grading settings (default: the exercise's ``[grading]`` table).
    plans
        The variant's plans drawn already (an analysis's), if so: taken as the key's exact
        drawing where they are one (:func:`~planmethod.grading.tolerances.exact_drawing`).

    Raises
    ------
    SpecError
        If the ``[grading]`` table is malformed.
    """
    from ..kinematics import solve
    from ..plans import choose_scales
    from ..report import asked_quantities

    exercise = variant.exercise
    mechanism = exercise.mechanism
    acceleration = exercise.ask.needs_acceleration
    motion = solve(mechanism, mechanism.drive.angle,
                   stage="acceleration" if acceleration else "velocity")
    quantities = asked_quantities(exercise, motion)
    if settings is None:
        settings = grading_settings(variant.data, exercise.source, quantities)
    found = _propagation(variant, exercise, settings, quantities, motion, plans)
    scales = choose_scales(exercise)
    wrong_plans = _wrong_plans(exercise, found, motion)
    questions = _questions(exercise, quantities, found, settings, scales, wrong_plans, motion)
    return {
        "format": KEY_FORMAT, "version": VERSION, "title": mechanism.title,
        "student": variant.student, "seed": variant.seed, "attempt": variant.attempt,
        "source": exercise.source, "task": variant.description.strip(),
        "given": dict(variant.values), "angle": mechanism.drive.angle,
        "exercise": variant.data, "numbers": course_numbers(mechanism),
        "scales": scales.as_dict(), "precision_mm": settings.precision_mm,
        "rel_floor": settings.rel_floor,
        "questions": [question.as_dict() for question in questions],
        "plans": _plan_table(found, scales, settings, wrong_plans, motion),
    }


def key_exercise(key: Mapping[str, Any]):
    """The exercise a key was built for, from the resolved tables it keeps (``exercise``),
    or None for a key that keeps none.

    >>> from planmethod.grading.templates import load_template, draw_variant
    >>> key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    >>> key_exercise(key).mechanism.drive.angle, key_exercise({"exercise": {}})
    (30.0, None)
    """
    if not key.get("exercise"):
        return None
    from ..spec import exercise_from_dict

    if not isinstance(key, ReadKey):   # built here: its tables are of its source file
        return exercise_from_dict(key["exercise"], file=key.get("source"))
    try:
        return exercise_from_dict(key["exercise"], file=key.file)
    except PlanmethodError as error:   # a key file's own table: named as its key there
        raise error.under(f"{key.place}.exercise" if key.place else "exercise") from None


def bundle(keys: list[dict], **about: Any) -> dict:
    """A bundle of keys (one per variant), with ``about`` (template, seed, count)."""
    return {"format": KEYS_FORMAT, "version": VERSION, **about, "keys": keys}


def _finite(value: Any) -> bool:
    return (not isinstance(value, bool) and isinstance(value, int | float)
            and math.isfinite(value))


def _not_finite(value: Any, where: str, key: str) -> SpecError:
    return SpecError(message("must be a finite number, got {given}", given=value_text(value)),
                     file=where, key=key)


def _check_mistakes(mistakes: Any, where: str, place: str) -> None:
    """A question's known mistakes in a key file: a list of tables, each with a ``kind``
    and a finite ``value`` and ``tolerance``."""
    if not isinstance(mistakes, list):
        raise SpecError(message("must be a list of tables"), file=where, key=place)
    for index, mistake in enumerate(mistakes):
        if not isinstance(mistake, Mapping):
            raise SpecError(message("must be a table"), file=where, key=f"{place}[{index}]")
        for name in ("kind", "value", "tolerance"):
            if name not in mistake:
                raise SpecError(message("missing"), file=where, key=f"{place}[{index}].{name}")
        for name in ("value", "tolerance"):
            if not _finite(mistake[name]):
                raise _not_finite(mistake[name], where, f"{place}[{index}].{name}")
        if mistake.get("also") is not None and not isinstance(mistake["also"], list):
            raise SpecError(message("must be a list of mistakes"), file=where,
                            key=f"{place}[{index}].also")


def _check_question(question: Any, where: str, place: str) -> None:
    """One question of a key file: a table with an ``id``, a finite ``value`` and
    ``tolerance``, finite ``points`` (if given) and its known mistakes."""
    if not isinstance(question, Mapping):
        raise SpecError(message("must be a table"), file=where, key=place)
    for name in ("id", "value", "tolerance"):
        if name not in question:
            raise SpecError(message("missing"), file=where, key=f"{place}.{name}")
    for name in ("value", "tolerance", "points"):
        if name in question and not _finite(question[name]):
            raise _not_finite(question[name], where, f"{place}.{name}")
    if question.get("mistakes") is not None:
        _check_mistakes(question["mistakes"], where, f"{place}.mistakes")


def _check_key(key: Any, where: str) -> dict:
    if not isinstance(key, Mapping) or key.get("format") != KEY_FORMAT:
        raise SpecError(message("not a planmethod answer key (format must be "
                                "'planmethod-key')"), file=where)
    questions = key.get("questions")
    if not isinstance(questions, list):
        raise SpecError(message("the key has no list of questions"), file=where,
                        key="questions")
    for index, question in enumerate(questions):
        _check_question(question, where, f"questions[{index}]")
    return dict(key)


#: the last key file parsed: its identity (path, inode, size, modification time) → its data
_LAST_PARSED: dict[tuple, Any] = {}


def _parsed_keys(path: Path) -> Any:
    """The JSON of a key file, parsed once per process while the file stays the same: a
    command reads a bundle's course language before it grades, and a bundle of 1000 keys
    takes about a second to parse. Only the last regular file is kept; callers copy the
    tables they change (:func:`_check_key`, :class:`ReadKey`)."""
    try:
        status = path.stat()
    except OSError:
        status = None
    identity = None
    if status is not None and stat.S_ISREG(status.st_mode):
        identity = (str(path.resolve()), status.st_ino, status.st_size, status.st_mtime_ns)
        if identity in _LAST_PARSED:
            return _LAST_PARSED[identity]
    data = parse_json(read_text_bounded(path, MAX_KEYS_BYTES), file=str(path))
    if identity is not None:
        _LAST_PARSED.clear()
        _LAST_PARSED[identity] = data
    return data


def load_keys(path: str | Path) -> dict[str, dict]:
    """Read a key or a bundle of keys: student → key (a single key is keyed ``*`` too, so
    that every student is graded against it).

    Parameters
    ----------
    path
        A key, a bundle (``keys.json``) or its folder.

    Raises
    ------
    SpecError
        If the file cannot be read or is not a key.
    """
    path = Path(path)
    if path.is_dir():
        path = path / "keys.json"
    data = _parsed_keys(path)
    if isinstance(data, Mapping) and data.get("format") == KEYS_FORMAT:
        keys = data.get("keys")
        if not isinstance(keys, list):
            raise SpecError(message("the bundle has no list of keys"), file=str(path),
                            key="keys")
        out = {}
        for index, key in enumerate(keys):
            key = ReadKey(_check_key(key, f"{path}: keys[{index}]"), str(path), f"keys[{index}]")
            out[str(key.get("student"))] = key
        return out
    key = ReadKey(_check_key(data, str(path)), str(path))
    return {str(key.get("student")): key, "*": key}
