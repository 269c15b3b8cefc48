"""Exercise templates and their reproducible random variants.

A template is an exercise file (docs/exercise-file.md) in which any number may instead be

* a **range** ``{ range = [low, high], step = s }`` — drawn uniformly on the grid
  low, low + s, … ≤ high (without ``step``: uniformly in [low, high]);
* a **choice** ``{ choice = [a, b, c] }`` — one of the listed values (numbers or strings);
* a **derived value**: a string starting with ``=``, an expression of the safe language of
  :mod:`planmethod.grading.expressions` (``"= l_BC / 2"``, ``"= round(l_AB * ratio, 3)"``),
  referring to names of the ``[vars]`` table or to dotted keys of the file
  (``drive.omega``, ``links.BC.C[0]``). A literal string starting with ``=`` is written ``==…``.

Two extra tables belong to templates only:

* ``[vars]`` — named values (numbers, ranges, choices or expressions) used by expressions and
  by ``{name}`` / ``{name:.3g}`` placeholders in ``description``;
* ``[template]`` — ``min_line_angle_deg`` (default 15: reject a variant whose construction
  lines meet at a smaller angle), ``dead_centre_deg`` (default 10: reject a variant whose
  crank stands within this of a dead centre), ``min_segment_mm`` (default 10: reject a variant
  where a segment the student reads off a plan is shorter), ``require`` (components such as
  ``["coriolis", "tangential"]`` that must be drawn at least ``min_segment_mm`` long),
  ``max_tolerance`` (default 0.1: reject a variant where the tolerance a drawing at the
  ``[grading]`` precision allows exceeds this share of a quantity asked), ``max_attempts``
  (default 200).

The ``[grading]`` table (also allowed in plain exercise files) holds ``precision_mm``
(the drafting precision the tolerances assume, default 0.5 mm), ``rel_floor``, and per-quantity
``[grading.tolerance]`` overrides and ``[grading.points]`` — see :mod:`planmethod.grading.keys`.

A variant is a pure function of (template text, seed, student id): every random value is drawn
from a SHA-256 hash of those and of its own key, so it does not depend on the order of
evaluation or on the Python version. A drawn variant that cannot be assembled, stands near a
dead centre, or needs two construction lines meeting below ``min_line_angle_deg`` is rejected
and redrawn with the next attempt number (also part of the hash), deterministically.

Examples
--------
>>> template = load_template("exercises/templates/slider_crank.toml")
>>> first = draw_variant(template, seed=7, student="s01")
>>> again = draw_variant(template, seed=7, student="s01")
>>> first.data == again.data and first.attempt == again.attempt
True
>>> 0.05 <= first.values["l_AB"] <= 0.08
True
"""

from __future__ import annotations

import datetime
import hashlib
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from ..errors import (
    AssemblyError,
    ConvergenceError,
    PlanmethodError,
    SpecError,
    ToggleError,
    value_text,
)
from ..model import Exercise
from ..numbering import course_numbers, course_symbols
from ..render.plan_words import label_text
from ..spec import checked_table, leaves, parse_toml, read_text
from ..vectors import angle_deg
from ..vocabulary import PlanKind, point_text, symbol
from ..words import Message, message, number_text, plural, render, template
from .expressions import ExpressionError, evaluate, parse, references
from .plan_points import vector_name
from .sheet_area import PLAN_ROOM_MM, plan_size_mm

__all__ = [
    "Template",
    "TemplateSettings",
    "Variant",
    "check_variant",
    "draw_variant",
    "drawing_values",
    "drawn_lengths",
    "format_description",
    "load_template",
    "parse_template",
    "rejection_summary",
    "to_toml",
]

TEMPLATE_KEYS = ("min_line_angle_deg", "dead_centre_deg", "max_attempts", "min_segment_mm",
                 "require", "max_tolerance")
#: plan components a template may require to be drawn (not to vanish) in every variant
COMPONENTS = ("normal", "tangential", "coriolis", "relative")
_PLACEHOLDER = re.compile(r"\{([A-Za-z_][A-Za-z0-9_.\[\]]*)(?::([-+ #0]?\d*(?:\.\d+)?[efgd%]?))?\}")
#: a placeholder's format: its width (the characters it is padded to) and its precision (the
#: digits after the point, or significant ones) are at most these (``{l_AB:.100000000f}``
#: would write 100 MB)
MAX_FORMAT_WIDTH = 40
MAX_FORMAT_PRECISION = 15
#: a task's text, its placeholders filled in, is at most this many characters (a sheet, a key
#: and a quiz print it for every student)
MAX_TASK_CHARACTERS = 20_000
_PATH_PART = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)|\[(\d+)\]")


@dataclass(frozen=True, slots=True)
class TemplateSettings:
    """The ``[template]`` table: rejection thresholds and the attempt limit."""

    min_line_angle_deg: float = 15.0
    dead_centre_deg: float = 10.0
    max_attempts: int = 200
    #: every segment a student measures on a plan is at least this long (mm)
    min_segment_mm: float = 10.0
    #: components that must be drawn, at least ``min_segment_mm`` long, in every variant
    require: tuple[str, ...] = ()
    #: the drafting tolerance of every quantity asked is at most this share of its value
    max_tolerance: float = 0.10


@dataclass(frozen=True)
class Template:
    """A parsed template: its raw tables, its settings and a digest of its text."""

    data: Mapping[str, Any]
    settings: TemplateSettings
    digest: str
    source: str | None = None

    @property
    def is_random(self) -> bool:
        """True if any value is a range or a choice."""
        return any(_is_random(value) for _, value in _walk(self.data))


@dataclass(frozen=True)
class Variant:
    """One drawn variant: the resolved exercise tables, the exercise, the values of
    ``[vars]``, and the draw that gave it (seed, student, attempt, rejected attempts)."""

    student: str
    seed: int
    attempt: int
    data: Mapping[str, Any]
    values: Mapping[str, Any]
    exercise: Exercise
    #: why the attempts before it were rejected
    rejected: tuple[Message, ...] = ()
    #: the drawing tolerances found while checking the draw (reused by its answer key)
    propagation: Any = field(default=None, compare=False, repr=False)

    @property
    def description(self) -> str:
        """The task as the student reads it: placeholders filled from the variant's values,
        its file, the drawing its scales give (``{drawn.crank}``: (AB) in mm) and the
        course's symbols (``{symbol.omega}``: the crank's ω by its number, ω₁ or ω₂;
        :func:`planmethod.numbering.course_symbols`)."""
        text = self.data.get("description", "")
        drawing = drawing_values(self.exercise) if "{drawn." in str(text) or \
            "{scales." in str(text) else {}
        if "{symbol." in str(text):
            drawing = {**drawing, "symbol": course_symbols(self.exercise.mechanism)}
        try:
            return format_description(text, self.values, self.data, drawing or None)
        except SpecError as error:
            raise error.located(file=self.exercise.source) from None


def load_template(path: str | Path) -> Template:
    """Read a template (or a plain exercise file, which is a template without randomness).

    Parameters
    ----------
    path
        The template file.

    Raises
    ------
    SpecError
        If the file cannot be read, is not TOML, or has a malformed range, choice or
        expression (naming the file and key).
    """
    path = Path(path)
    return parse_template(read_text(path), file=str(path))


def parse_template(text: str, *, file: str | None = None) -> Template:
    """Parse the text of a template (see :func:`load_template`)."""
    data = parse_toml(text, file=file)
    settings = _settings(data.get("template", {}), file)
    if "ask" not in data and any(_is_random(value) for _, value in _walk(data)):
        # without [ask] everything is asked, fixed pivots' zero speeds and zero Coriolis terms
        # included: no drawn variant could pass the rules a random draw is held to
        raise SpecError(message("a template with random values must say what its students "
                                "are asked: add an [ask] table (velocity = [...], omega = [...] "
                                "…)"), file=file, key="ask")
    if not isinstance(data.get("description", ""), str):
        raise SpecError(message("must be a string (the task in words, with {{name}} "
                                "placeholders), got {given}",
                                given=value_text(data["description"])),
                        file=file, key="description")
    description = data.get("description", "")
    if len(description) > MAX_TASK_CHARACTERS:
        raise SpecError(_too_long_task(len(description)), file=file, key="description")
    for placeholder in _PLACEHOLDER.finditer(description):
        problem = _format_problem(placeholder)
        if problem:
            raise SpecError(problem, file=file, key="description")
    if "vars" in data and not isinstance(data["vars"], Mapping):
        raise SpecError(message("must be a table of named values"), file=file, key="vars")
    for name in data.get("vars", {}):
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
            raise SpecError(message("a variable name must be an identifier"), file=file,
                            key=f"vars.{name}")
    # check every random spec and expression now, so that a bad template fails at once
    for key, value in _walk(data):
        if _is_random(value):
            _check_random(value, key, file)
        elif isinstance(value, str) and _is_expression(value):
            _check_expression(data, value, key, file)
    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()
    return Template(data, settings, digest, file)


def _too_long_task(characters: int) -> Message:
    return plural("the task's text is {count} character; at most {limit}",
                  "the task's text is {count} characters; at most {limit}",
                  count=characters, limit=MAX_TASK_CHARACTERS)


def _check_expression(data: Mapping[str, Any], value: str, key: str, file: str | None) -> None:
    """Refuse an expression that does not parse or refers to a name the file lacks."""
    try:
        tree = parse(value[1:])
    except ExpressionError as error:
        raise SpecError(message("bad expression {expression}: {problem}",
                                expression=value_text(value), problem=error.message),
                        file=file, key=key) from None
    for name in references(tree):
        if not _exists(data, name):
            raise SpecError(message("expression {expression} refers to '{name}', which is "
                                    "neither in [vars] nor a key of the file",
                                    expression=value_text(value), name=name),
                            file=file, key=key)


def _settings(table: Any, file: str | None) -> TemplateSettings:
    table = checked_table(table, "template", TEMPLATE_KEYS, file=file)
    values: dict[str, Any] = {}
    for name in ("min_line_angle_deg", "dead_centre_deg"):
        if name in table:
            value = table[name]
            if (isinstance(value, bool) or not isinstance(value, int | float)
                    or not 0 <= value < 90):
                raise SpecError(message("must be an angle in [0, 90) degrees, got {given}",
                                        given=value_text(value)),
                                file=file, key=f"template.{name}")
            values[name] = float(value)
    if "max_attempts" in table:
        value = table["max_attempts"]
        if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= 10000:
            raise SpecError(message("must be a whole number in 1…10000, got {given}",
                                    given=value_text(value)),
                            file=file, key="template.max_attempts")
        values["max_attempts"] = value
    if "min_segment_mm" in table:
        value = table["min_segment_mm"]
        if isinstance(value, bool) or not isinstance(value, int | float) or not 0 <= value <= 200:
            raise SpecError(message("must be a length in [0, 200] mm, got {given}",
                                    given=value_text(value)),
                            file=file, key="template.min_segment_mm")
        values["min_segment_mm"] = float(value)
    if "max_tolerance" in table:
        value = table["max_tolerance"]
        if isinstance(value, bool) or not isinstance(value, int | float) or not 0 < value <= 1:
            raise SpecError(message("must be a share in (0, 1] (0.1 = 10 %), got {given}",
                                    given=value_text(value)),
                            file=file, key="template.max_tolerance")
        values["max_tolerance"] = float(value)
    if "require" in table:
        value = table["require"]
        if not isinstance(value, list) or any(item not in COMPONENTS for item in value):
            raise SpecError(message("must be a list of components from {components}, got "
                                    "{given}", components=list(COMPONENTS),
                                    given=value_text(value)),
                            file=file, key="template.require")
        values["require"] = tuple(value)
    return TemplateSettings(**values)


# -- walking the tables ----------------------------------------------------------------------
def _walk(node: Any, prefix: str = ""):
    """Yield (dotted key, value) for every leaf and random spec of the tables."""
    return leaves(node, prefix, whole=_is_random)


def _is_random(value: Any) -> bool:
    return isinstance(value, Mapping) and bool(value) and (
        (set(value) <= {"range", "step"} and "range" in value) or set(value) == {"choice"})


def _is_expression(value: str) -> bool:
    return value.startswith("=") and not value.startswith("==")


def _number(value: Any) -> bool:
    return not isinstance(value, bool) and isinstance(value, int | float) and math.isfinite(value)


def _check_random(spec: Mapping[str, Any], key: str, file: str | None) -> None:
    if "choice" in spec:
        options = spec["choice"]
        if not isinstance(options, list) or not options:
            raise SpecError(message("choice must be a non-empty list"), file=file,
                            key=f"{key}.choice")
        if not all(_number(o) or isinstance(o, str) for o in options):
            raise SpecError(message("choice holds numbers or strings, got {given}",
                                    given=value_text(options)), file=file, key=f"{key}.choice")
        return
    bounds = spec["range"]
    if (not isinstance(bounds, list) or len(bounds) != 2
            or not all(_number(b) for b in bounds)):
        raise SpecError(message("range must be [low, high] with finite numbers, got {given}",
                                given=value_text(bounds)), file=file, key=f"{key}.range")
    low, high = bounds
    if low > high:
        raise SpecError(message("range [{low:g}, {high:g}] has low above high", low=low,
                                high=high), file=file, key=f"{key}.range")
    if "step" in spec:
        step = spec["step"]
        if not _number(step) or step <= 0:
            raise SpecError(message("step must be a positive number, got {given}",
                                    given=value_text(step)), file=file, key=f"{key}.step")
        if (high - low) / step > 1e7:
            raise SpecError(message("range/step gives more than 10 million values ({step:g})",
                                    step=step), file=file, key=f"{key}.step")


def _path(name: str) -> list[str | int]:
    parts: list[str | int] = []
    for piece in name.split("."):
        for match in _PATH_PART.finditer(piece):
            parts.append(match.group(1) if match.group(1) else int(match.group(2)))
    return parts


def _lookup(data: Any, name: str) -> Any:
    node = data
    for part in _path(name):
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                raise KeyError(name)
            node = node[part]
        else:
            if not isinstance(node, Mapping) or part not in node:
                raise KeyError(name)
            node = node[part]
    return node


def _exists(data: Mapping[str, Any], name: str) -> bool:
    for root in (data.get("vars", {}), data):
        try:
            _lookup(root, name)
        except KeyError:
            continue
        return True
    return False


# -- drawing ---------------------------------------------------------------------------------
def _uniform(*parts: object) -> float:
    """A number in [0, 1) from a SHA-256 hash of the parts (stable across runs and versions)."""
    text = "\x1f".join(str(part) for part in parts)
    digest = hashlib.sha256(text.encode("utf-8")).digest()
    return int.from_bytes(digest[:7], "big") / float(1 << 56)


def _draw(spec: Mapping[str, Any], u: float) -> Any:
    if "choice" in spec:
        options = spec["choice"]
        return options[min(int(u * len(options)), len(options) - 1)]
    low, high = (float(b) for b in spec["range"])
    if "step" not in spec:
        return low + u * (high - low)
    step = float(spec["step"])
    count = math.floor((high - low) / step + 1e-9) + 1
    value = low + min(int(u * count), count - 1) * step
    decimals = max(0, -math.floor(math.log10(step)) + 6)
    return round(value, decimals)


class _Resolver:
    """Resolves every random spec and expression of one attempt, lazily and memoised."""

    def __init__(self, template: Template, seed: int, student: str, attempt: int) -> None:
        self.template = template
        self.salt = (template.digest, seed, student, attempt)
        self.memo: dict[str, Any] = {}
        self.active: list[str] = []

    def value(self, key: str, raw: Any) -> Any:
        if key in self.memo:
            return self.memo[key]
        if key in self.active:
            cycle = " → ".join([*self.active[self.active.index(key):], key])
            raise SpecError(message("the expressions refer to each other in a cycle: {cycle}",
                                    cycle=cycle), file=self.template.source, key=key)
        self.active.append(key)
        try:
            if _is_random(raw):
                result = _draw(raw, _uniform(*self.salt, key))
            elif isinstance(raw, str) and _is_expression(raw):
                try:
                    result = evaluate(parse(raw[1:]), self.reference)
                except ExpressionError as error:
                    raise SpecError(message("{expression}: {problem}",
                                            expression=value_text(raw), problem=error.message),
                                    file=self.template.source, key=key) from None
            elif isinstance(raw, str) and raw.startswith("=="):
                result = raw[1:]
            elif isinstance(raw, Mapping):
                result = {name: self.value(f"{key}.{name}" if key else name, item)
                          for name, item in raw.items()}
            elif isinstance(raw, list):
                result = [self.value(f"{key}[{index}]", item) for index, item in enumerate(raw)]
            else:
                result = raw
        finally:
            self.active.pop()
        self.memo[key] = result
        return result

    def reference(self, name: str) -> Any:
        data = self.template.data
        variables = data.get("vars", {})
        try:
            raw = _lookup(variables, name)
            key = f"vars.{name}"
        except KeyError:
            raw = _lookup(data, name)
            key = name
        canonical = ".".join(str(p) if isinstance(p, str) else f"[{p}]" for p in _path(key))
        return self.value(canonical.replace(".[", "["), raw)

    def resolve_all(self) -> dict[str, Any]:
        return {name: self.value(name, raw) for name, raw in self.template.data.items()}


def draw_variant(template: Template, seed: int = 0, student: str = "1",
                 *, check: bool = True) -> Variant:
    """Draw the variant of ``template`` for (``seed``, ``student``).

    Attempts 0, 1, 2, … are drawn in turn until one passes :func:`check_variant`.

    Parameters
    ----------
    template
        The template to draw from.
    seed
        The random number of the course (``variants --seed``).
    student
        The student's id.
    check
        Reject and redraw attempts that fail :func:`check_variant`.

    Raises
    ------
    SpecError
        If the template is malformed, or no attempt within ``max_attempts`` passes (the message
        counts the reasons of the rejections).
    """
    reasons: list[Message] = []
    for attempt in range(template.settings.max_attempts):
        variant = _attempt(template, seed, student, attempt, reasons, check)
        if variant is not None:
            return variant
    raise SpecError(plural("no acceptable variant in {count} attempt for student {student!r} "
                           "(seed {seed}): {summary}",
                           "no acceptable variant in {count} attempts for student {student!r} "
                           "(seed {seed}): {summary}", count=template.settings.max_attempts,
                           student=student, seed=seed, summary=_summary(reasons)),
                    file=template.source)


def _attempt(template: Template, seed: int, student: str, attempt: int,
             reasons: list[Message], check: bool) -> Variant | None:
    """The variant of one attempt, or None (the reason added to ``reasons``) if it is
    rejected."""
    resolver = _Resolver(template, seed, student, attempt)
    data = resolver.resolve_all()
    values = data.pop("vars", {})
    data.pop("template", None)
    try:
        from ..spec import exercise_from_dict

        exercise = exercise_from_dict(data, file=template.source)
    except SpecError as error:
        if not template.is_random:
            raise
        reasons.append(message("not a valid exercise: {problem} ({key})", problem=error.message,
                               key=error.key))
        return None
    if not check:
        return Variant(student, seed, attempt, data, values, exercise, tuple(reasons))
    problem = check_variant(exercise, template.settings, drawable=template.is_random)
    propagation = None
    if problem is None and template.is_random:
        problem, propagation = tolerance_problem(exercise, data, template.settings,
                                                 file=template.source)
    if problem is None:
        return Variant(student, seed, attempt, data, values, exercise, tuple(reasons),
                       propagation)
    if not template.is_random:
        raise SpecError(message("the exercise itself is unsuitable for grading: {problem}",
                                problem=problem), file=template.source)
    reasons.append(problem)
    return None


def _summary(reasons: list[Message]) -> str:
    """The three most frequent kinds of rejection, each counted, each number shown as the
    range it took (:func:`rejection_summary`)."""
    return "; ".join(rejection_summary(reasons)[:3])


def _number_pattern() -> re.Pattern:
    """A number in a reason as the language writes it (not a digit of a name such as O2)."""
    sign = re.escape(number_text(0.5)[1])
    return re.compile(rf"(?<![A-Za-z_])-?\d+(?:{sign}\d+)?")


def _value(text: str) -> float:
    return float(re.sub(r"[^\d\-]", ".", text))


def rejection_summary(reasons: list[Message | str]) -> list[str]:
    """The reasons of rejected draws, alike ones counted together, most frequent first, each
    number shown as the range it took; in the language spoken.

    Examples
    --------
    >>> for line in rejection_summary(["segment of ω₃ is 4.2 mm (below 10 mm)",
    ...                                "the crank is 3.1° from a dead centre (below 5°)",
    ...                                "segment of ω₃ is 9.5 mm (below 10 mm)"]):
    ...     print(line)
    2× segment of ω₃ is 4.2–9.5 mm (below 10 mm)
    1× the crank is 3.1° from a dead centre (below 5°)
    """
    number = _number_pattern()
    groups: dict[str, list[list[str]]] = {}
    for reason in map(render, reasons):
        groups.setdefault(number.sub("#", reason), []).append(number.findall(reason))
    lines = []
    for pattern, rows in sorted(groups.items(), key=lambda item: (-len(item[1]), item[0])):
        parts = pattern.split("#")
        text = parts[0]
        for column, rest in zip(zip(*rows, strict=True), parts[1:], strict=True):
            low, high = min(column, key=_value), max(column, key=_value)
            text += low if _value(low) == _value(high) else f"{low}–{high}"
            text += rest
        lines.append(f"{len(rows)}× {text}")
    return lines


def check_variant(exercise: Exercise, settings: TemplateSettings = TemplateSettings(), *,
                  drawable: bool = True) -> Message | None:
    """Why a drawn exercise is unfit to be set (None if it is fit).

    Unfit: it cannot be assembled, a group is at a toggle, two construction lines of a plan
    meet below ``min_line_angle_deg``, or the crank stands within ``dead_centre_deg`` of a
    dead centre — read off the velocity plan as the angle between the crank pin's velocity
    (pb) and the line of the relative velocity drawn through b (they are parallel exactly
    when the crank and the link it drives are in line: nothing is transmitted).
    """
    from ..plans import draw_plans

    try:
        plans = draw_plans(exercise, acceleration=exercise.ask.needs_acceleration)
    except AssemblyError as error:
        return message("cannot be assembled ({problem})", problem=error.message)
    except ToggleError as error:
        return message("toggle position ({problem})", problem=error.message)
    except ConvergenceError as error:
        return message("no converged assembly ({problem})", problem=error.message)
    except PlanmethodError as error:
        return message("cannot draw the plans ({problem})", problem=error.message)
    return plan_problem(plans, settings, drawable=drawable)


#: a plan's construction lines meet at too small an angle, by plan
_SHARP = {PlanKind.VELOCITY: template("on the velocity plan the lines meet at {angle:.1f}° "
                                      "(below {limit:g}°) for {point}"),
          PlanKind.ACCELERATION: template("on the acceleration plan the lines meet at "
                                          "{angle:.1f}° (below {limit:g}°) for {point}")}
#: a segment read off a plan is too short to measure, by plan
_SHORT = {PlanKind.VELOCITY: template("on the velocity plan the segment read for {quantity} is "
                                      "{length:.1f} mm (below {limit:g} mm)"),
          PlanKind.ACCELERATION: template("on the acceleration plan the segment read for "
                                          "{quantity} is {length:.1f} mm (below {limit:g} mm)")}
#: a component a template requires is too short or not drawn, by plan
_UNDRAWN = {PlanKind.VELOCITY: template("{component} required on the velocity plan is "
                                        "{length:.1f} mm (below {limit:g} mm, or not drawn)"),
            PlanKind.ACCELERATION: template("{component} required on the acceleration plan is "
                                            "{length:.1f} mm (below {limit:g} mm, or not "
                                            "drawn)")}
#: a plan too large for its printed sheet, by plan
_TOO_LARGE = {PlanKind.VELOCITY: template("the velocity plan spans {width:.0f} × {height:.0f} mm: "
                                          "more than its printed sheet holds ({room_width:g} × "
                                          "{room_height:g} mm)"),
              PlanKind.ACCELERATION: template("the acceleration plan spans {width:.0f} × "
                                              "{height:.0f} mm: more than its printed sheet "
                                              "holds ({room_width:g} × {room_height:g} mm)")}
#: the components a template may require, named
_COMPONENTS = {"normal": message("the normal component"),
               "tangential": message("the tangential component"),
               "coriolis": message("the coriolis component"),
               "relative": message("the relative component")}


def plan_problem(plans, settings: TemplateSettings, *, drawable: bool = True
                 ) -> Message | None:
    """The reason a variant's plans are unfit (see :func:`check_variant`), or None.
    ``drawable`` adds the rules a random draw must also pass (segments a student measures at
    least ``min_segment_mm``, required components drawn); an exercise set as written is not
    held to them. Quantities are named as the course writes them (ω₂, aʳ_CC₀)."""
    numbers = course_numbers(plans.exercise.mechanism)
    for plan in (plans.velocity, plans.acceleration):
        if plan is None:
            continue
        for step in plan.steps:
            if step.action == "intersect" and step.angle_deg < settings.min_line_angle_deg:
                return _SHARP[plan.kind].replace(angle=_shown_below(step.angle_deg),
                                                 limit=settings.min_line_angle_deg,
                                                 point=label_text(step.end, numbers))
    angle = dead_centre_angle(plans)
    if angle is not None and angle < settings.dead_centre_deg:
        return message("the crank is {angle:.1f}° from a dead centre (below {limit:g}°)",
                       angle=_shown_below(angle), limit=settings.dead_centre_deg)
    for plan in (plans.velocity, plans.acceleration):
        if plan is not None and drawable:
            problem = _unmeasurable(plan, settings, numbers)
            if problem is not None:
                return problem
    return None


def _shown_below(value: float) -> float:
    """A value found below its limit as a reason shows it (one decimal): cut, not rounded,
    so that 3.96 mm below 4 mm reads 3.9, not 4.0.

    >>> _shown_below(3.96), _shown_below(14.99), _shown_below(2.0)
    (3.9, 14.9, 2.0)
    """
    return math.floor(value * 10.0 + 1e-9) / 10.0


def _unmeasurable(plan, settings: TemplateSettings, numbers: Mapping[str, int]
                  ) -> Message | None:
    """Why a random draw's plan cannot be measured: a segment the student reads off shorter
    than ``min_segment_mm``, a required component not drawn that long, or the plan too large
    for its printed sheet (:data:`~planmethod.grading.sheet_area.PLAN_ROOM_MM`); else None."""
    for step in plan.steps:   # what the student reads off must be long enough to measure
        if (step.action == "read" and step.length_mm is not None
                and abs(step.length_mm) < settings.min_segment_mm):
            read = (vector_name(step.quantity, numbers) if step.quantity
                    else label_text(step.end, numbers))
            return _SHORT[plan.kind].replace(quantity=read,
                                             length=_shown_below(abs(step.length_mm)),
                                             limit=settings.min_segment_mm)
    for component in settings.require:
        drawn = [abs(step.length_mm or 0.0) for step in plan.steps
                 if step.action == "lay_off" and step.component == component]
        needed = plan.kind == PlanKind.ACCELERATION or component == "relative"
        if needed and (not drawn or max(drawn) < settings.min_segment_mm):
            return _UNDRAWN[plan.kind].replace(component=_COMPONENTS[component],
                                               length=_shown_below(max(drawn, default=0.0)),
                                               limit=settings.min_segment_mm)
    width, height = plan_size_mm(plan.points_mm)
    room_width, room_height = PLAN_ROOM_MM
    if width > room_width or height > room_height:
        return _TOO_LARGE[plan.kind].replace(width=math.ceil(width), height=math.ceil(height),
                                             room_width=room_width, room_height=room_height)
    return None


def tolerance_problem(exercise: Exercise, data: Mapping[str, Any], settings: TemplateSettings,
                      *, file: str | None = None) -> tuple[Message | None, Any]:
    """(why the draw is unfit, the drawing tolerances found): unfit where the tolerance a
    drawing at the ``[grading]`` precision allows (:func:`~planmethod.grading.tolerances.
    propagate`) is more than ``max_tolerance`` of a quantity asked — the student could not tell
    a right drawing from a wrong one. The tolerances are kept for the variant's key."""
    from .keys import grading_settings
    from .tolerances import propagate

    precision = grading_settings(data, file).precision_mm
    found = propagate(exercise, precision)
    mechanism = exercise.mechanism
    numbers = course_numbers(mechanism)
    for quantity, value in found.values.items():
        tolerance = found.tolerances.get(quantity)
        if value is None or tolerance is None or not value:
            continue
        if tolerance > settings.max_tolerance * abs(value):
            return message("the drafting tolerance of {symbol} is {percent:.0f} % of its value "
                           "(above {limit:g} %)", symbol=symbol(quantity, numbers),
                           percent=math.ceil(100 * tolerance / abs(value)),
                           limit=100 * settings.max_tolerance), found
    return None, found


def dead_centre_angle(plans) -> float | None:
    """Angle (deg, 0…90) between pb and the first relative-velocity line drawn through b."""
    velocity = plans.velocity
    label = next((s.end for s in velocity.steps if s.action == "lay_off"), None)
    if label is None:
        return None
    pb = velocity.points_mm[label]
    if pb[0] == 0 and pb[1] == 0:
        return None
    direction = angle_deg(pb)
    for step in velocity.steps:
        if step.action == "line" and step.start == label:
            difference = abs((step.direction_deg - direction + 90.0) % 180.0 - 90.0)
            return difference
    return None


def drawn_lengths(exercise: Exercise, scales: Mapping[str, float]) -> dict[str, float]:
    """The lengths the scales draw for the crank's scale point B (mm): (AB) = l_AB/μl,
    (pb) = v_B/μv, (πb) = a_B/μa, by segment as a sheet prints it.

    >>> from planmethod.spec import load_exercise
    >>> drawn_lengths(load_exercise("exercises/compressor_slider_crank.toml"),
    ...               {"mu_l": 0.002, "mu_v": 0.2, "mu_a": 20.0})
    {'(AB)': 30.0, '(pb)': 30.0, '(πb)': 30.0}
    """
    from ..plans.scales import scale_point

    mechanism = exercise.mechanism
    drive = mechanism.drive
    point = scale_point(mechanism, exercise.plan)
    length = mechanism.links[drive.link].length(drive.pivot, point)
    image = point.lower()
    out = {f"({point_text(drive.pivot)}{point_text(point)})": length / scales["mu_l"]}
    if scales.get("mu_v"):
        out[f"(p{image})"] = abs(drive.omega) * length / scales["mu_v"]
    if scales.get("mu_a"):
        out[f"(π{image})"] = length * math.hypot(drive.omega ** 2, drive.epsilon) / \
            scales["mu_a"]
    return out


def drawing_values(exercise: Exercise) -> dict[str, dict[str, float]]:
    """What a description may quote of the drawing its scales give: ``scales.mu_l`` …
    and the crank pin's drawn lengths ``drawn.crank`` ((AB), mm), ``drawn.velocity`` ((pb))
    and ``drawn.acceleration`` ((πb)), so that a task states the lengths its scales draw.

    >>> from planmethod.spec import load_exercise
    >>> drawing_values(load_exercise("exercises/compressor_slider_crank.toml"))["drawn"]
    {'crank': 30.0, 'velocity': 30.0, 'acceleration': 30.0}
    """
    from ..plans import choose_scales

    scales = choose_scales(exercise).as_dict()
    lengths = list(drawn_lengths(exercise, scales).values())
    return {"scales": scales,
            "drawn": dict(zip(("crank", "velocity", "acceleration"), lengths, strict=False))}


#: a task's text longer than :data:`MAX_TASK_CHARACTERS` once its placeholders are filled
_TOO_LONG_FILLED = plural("the task's text is more than {count} character once its "
                          "placeholders are filled in",
                          "the task's text is more than {count} characters once its "
                          "placeholders are filled in", count=MAX_TASK_CHARACTERS)


def format_description(text: Any, values: Mapping[str, Any], data: Mapping[str, Any],
                       drawing: Mapping[str, Any] | None = None) -> str:
    """Fill ``{name}`` and ``{name:.3g}`` placeholders from ``[vars]`` values, file keys and
    the ``drawing``'s values (:func:`drawing_values`), a number written as the language spoken
    writes it (``0,05`` in Russian); an unknown name is left as written, and so is a value
    inserted (a ``{name}`` in it is not filled in again).

    Raises
    ------
    SpecError
        If a placeholder's width is above :data:`MAX_FORMAT_WIDTH` or its precision above
        :data:`MAX_FORMAT_PRECISION`, or the text filled in would be longer than
        :data:`MAX_TASK_CHARACTERS` (key ``description``).

    Examples
    --------
    >>> format_description("l = {l:.3g} m, {x}", {"l": 0.0612345}, {})
    'l = 0.0612 m, {x}'
    >>> format_description("(AB) = {drawn.crank:.3g} mm", {}, {}, {"drawn": {"crank": 27.5}})
    '(AB) = 27.5 mm'
    >>> from planmethod.words import speaking
    >>> with speaking("ru"):
    ...     format_description("l = {l:.3f} м", {"l": 0.05}, {})
    'l = 0,050 м'
    >>> format_description("{l:.100000000f}", {"l": 0.06}, {})
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: description: the placeholder '{l:.100000000f}' has a \
precision of 100000000; at most 15
    """
    if not isinstance(text, str):
        return ""
    written = [0]    # the characters the text has grown by so far

    def fill(match: re.Match) -> str:
        problem = _format_problem(match)
        if problem:
            raise SpecError(problem, key="description")
        filled = _filled(match, (values, data, drawing or {}))
        if filled is None:
            return match.group(0)
        written[0] += len(filled) - len(match.group(0))
        if len(text) + written[0] > MAX_TASK_CHARACTERS:
            raise SpecError(_TOO_LONG_FILLED, key="description")
        return filled

    if len(text) > MAX_TASK_CHARACTERS:
        raise SpecError(_too_long_task(len(text)), key="description")
    return _PLACEHOLDER.sub(fill, text)


def _filled(placeholder: re.Match, sources: tuple[Mapping[str, Any], ...]) -> str | None:
    """A placeholder's value from the first of ``sources`` that has its name, formatted by
    its specification, a number as the course writes it (a decimal comma in Russian); None
    where no source has it, it is a table, or its specification does not fit it."""
    name, spec = placeholder.group(1), placeholder.group(2) or ""
    for source in sources:
        try:
            value = _lookup(source, name)
            break
        except KeyError:
            continue
    else:
        return None
    if isinstance(value, Mapping | list):
        return None
    try:
        return (number_text(value, spec or "g") if _number(value)
                else format(value, spec) if spec else str(value))
    except (ValueError, TypeError):
        return None


#: a placeholder's format asks for too much: its width, its precision
_TOO_MUCH = (template("the placeholder {placeholder} has a width of {amount}; at most {limit}"),
             template("the placeholder {placeholder} has a precision of {amount}; at most "
                      "{limit}"))


def _format_problem(placeholder: re.Match) -> Message | None:
    """Why a placeholder's format asks for too much (its width or precision above the
    bounds), or None.

    >>> render(_format_problem(_PLACEHOLDER.search("{l_AB:1000.3f}")))
    "the placeholder '{l_AB:1000.3f}' has a width of 1000; at most 40"
    """
    found = re.fullmatch(r"[-+ #0]?(\d*)(?:\.(\d+))?[efgd%]?", placeholder.group(2) or "")
    if found is None:
        return None
    for digits, sentence, limit in ((found.group(1), _TOO_MUCH[0], MAX_FORMAT_WIDTH),
                                    (found.group(2), _TOO_MUCH[1], MAX_FORMAT_PRECISION)):
        if digits and (len(digits) > 6 or int(digits) > limit):
            amount = digits if len(digits) <= 12 else plural("{count} digit", "{count} digits",
                                                             count=len(digits))
            return sentence.replace(placeholder=value_text(placeholder.group(0)), amount=amount,
                                    limit=limit)
    return None


# -- writing a resolved exercise back as TOML -----------------------------------------------
#: how a basic string writes each character TOML does not take as it is: the quote and the
#: backslash escaped, every control character (U+0000–U+001F, and DEL, U+007F, which JSON leaves
#: bare and TOML refuses) as its short escape or \uXXXX
_BASIC_ESCAPES = {**{code: f"\\u{code:04x}" for code in [*range(0x20), 0x7F]},
                  **{ord(char): escaped for char, escaped in (
                      ('"', '\\"'), ("\\", "\\\\"), ("\b", "\\b"), ("\t", "\\t"),
                      ("\n", "\\n"), ("\f", "\\f"), ("\r", "\\r"))}}
#: a UTF-16 surrogate: no character, and no UTF-8 file holds one (JSON text may: "\ud800")
_SURROGATE = re.compile("[\ud800-\udfff]")


def _toml_string(text: str) -> str:
    r"""``text`` as a TOML basic string, which reads back as exactly ``text``.

    >>> print(_toml_string('say "hi" \\ \x7f\n'))
    "say \"hi\" \\ \u007f\n"
    """
    if _SURROGATE.search(text):
        raise ValueError(render(message("cannot write a lone surrogate (not a character) to "
                                        "{format}", format="TOML")))
    return '"' + text.translate(_BASIC_ESCAPES) + '"'


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        if abs(value) > 2**63 - 1:
            raise ValueError(render(message("cannot write a whole number beyond 64 bits to "
                                            "{format}", format="TOML")))
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(render(message("cannot write {value} to {format}",
                                            value=str(value), format="TOML")))
        text = repr(value)
        return text if ("." in text or "e" in text or "inf" in text) else text + ".0"
    if isinstance(value, str):
        if _literal_block(value):   # a paragraph is written as it reads
            return "'''\n" + value + "'''"
        return _toml_string(value)
    if isinstance(value, datetime.date | datetime.time) and not (
            isinstance(value, datetime.time) and value.tzinfo is not None):
        return value.isoformat()    # a date-time is a date too; TOML has no time with offset
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}"
                                for k, v in value.items()) + " }"
    raise TypeError(render(message("cannot write {kind} to {format}",
                                   kind=type(value).__name__, format="TOML")))


def _literal_block(text: str) -> bool:
    """True if ``text`` has several lines and reads back unchanged as a TOML multi-line literal
    string: no three single quotes in it, no control character but newline and tab (nor DEL),
    no surrogate, not ending in a quote.

    >>> _literal_block("two\\nlines"), _literal_block("one line"), _literal_block("a\\r\\nb")
    (True, False, False)
    """
    return ("\n" in text and "'''" not in text and not text.endswith("'")
            and not any(ord(char) < 32 and char not in "\n\t" for char in text)
            and "\x7f" not in text and not _SURROGATE.search(text))


def _toml_key(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else _toml_string(key)


def to_toml(data: Mapping[str, Any]) -> str:
    """Write resolved exercise tables as TOML (nested tables inline); reads back equal.

    Examples
    --------
    >>> import tomllib
    >>> text = to_toml({"title": "x", "drive": {"angle": 45.0}, "slide": [{"link": "s"}]})
    >>> tomllib.loads(text) == {"title": "x", "drive": {"angle": 45.0}, "slide": [{"link": "s"}]}
    True
    """
    lines: list[str] = []
    tables = []
    for key, value in data.items():
        is_table_array = (isinstance(value, list) and bool(value)
                          and all(isinstance(v, Mapping) for v in value))
        if isinstance(value, Mapping) or is_table_array:
            tables.append((key, value))
        else:
            lines.append(f"{_toml_key(key)} = {_toml_value(value)}")
    for key, value in tables:
        if isinstance(value, Mapping):
            lines += ["", f"[{_toml_key(key)}]"]
            lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items()]
        else:
            for item in value:
                lines += ["", f"[[{_toml_key(key)}]]"]
                lines += [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in item.items()]
    return "\n".join(lines) + "\n"


def variant_exercise(variant: Variant, angle: float | None = None) -> Exercise:
    """The variant's exercise, optionally posed at another crank angle on the assemblies
    chosen at its ``drive.angle`` (:func:`planmethod.kinematics.continuation.pose`)."""
    from ..kinematics.continuation import pose

    if angle is None:
        return variant.exercise
    exercise = variant.exercise
    return replace(exercise, mechanism=pose(exercise.mechanism, angle).mechanism)

