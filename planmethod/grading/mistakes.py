"""The mistakes students make, in one registry: each with what the student is told and how the
answer it gives is predicted.

Two kinds:

* **construction mistakes** — a step of the construction done wrong (a component left out or
  laid off the wrong way, a construction line drawn in the wrong direction). The plan
  emulator draws the plans again with the mistake (:func:`mistaken_plans`, through
  :func:`~planmethod.plans.draw_plans`' ``perturb`` and ``turn`` hooks), so the answer is
  predicted for every quantity read downstream of it;
* **value mistakes** — a slip in turning the right reading into the answer (the sign, a
  scale, a unit, a length): the wrong answer follows from the right value
  (:func:`value_answers`).

A drawn plan point can land where a mistake puts it: a construction mistake's re-drawn plan
places it, and a mistake with a ``placed`` rule places it from the right plan (the plan laid
off at a wrong scale, a relative vector laid off from the pole). :func:`drawn_mistakes` lists
those positions for every point of a plan; the answer key carries them, and the workbook's
drawing mode, PrairieLearn's ``grade()`` and ``planmethod grade --drawing`` name a misplaced
point by them.

Adding a mistake is adding one entry here (and its test in ``tests/test_mistakes.py``). The
keys (:func:`planmethod.grading.keys.build_key`) list, per question, every mistake whose
answer differs from the right one by more than twice the tolerance; the grader names it when
a student's answer matches.

Examples
--------
>>> CONSTRUCTION_MISTAKES
('no_normal', 'no_coriolis', 'coriolis_reversed', 'tangential_along', 'mirrored_similarity')
>>> from planmethod.words import render
>>> render(MISTAKES["scale_ten"])
"the plan's scale was misread ten times too large"
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from functools import partial
from typing import Any

import numpy as np

from ..model import Exercise
from ..plans.construction import Segment
from ..vectors import norm, perp
from ..vocabulary import QUANTITY_KINDS
from ..words import Message, message
from .tolerances import kind_of, scale_factor

__all__ = ["CONSTRUCTION_MISTAKES", "MISTAKES", "REGISTRY", "Mistake", "PlanContext",
           "drawn_explanation", "drawn_mistakes", "mistaken_plans", "value_answers"]

#: a construction rule: (laid-off length, segment) → the length drawn with the mistake, or
#: None where the mistake does not touch that segment
Rule = Callable[[float, Segment], float | None]
#: a value rule: (quantity, right value, tolerance, the scales and the exact motion) →
#: [(wrong answer, its tolerance)]
Answers = Callable[[str, float, float, "ScalesAndMotion"], list[tuple[float, float]]]
#: a drawn-plan rule: (plan label, the right plan) → where the mistake puts that point (mm)
Placed = Callable[[str, "PlanContext"], list[tuple[float, float]]]

#: positions of drawn-plan mistakes are kept to this many decimals of a millimetre
DRAWN_DECIMALS = 2
#: a drawing sheet is at most this large (mm): a mistake that puts a point further from the pole
#: is not listed (no one draws it there)
DRAWN_SHEET_MM = 1000.0


@dataclass(frozen=True)
class ScalesAndMotion:
    """What a value rule may use: the drawing scales and the exact motion at the angle."""

    scales: Any
    motion: Any


@dataclass(frozen=True)
class PlanContext:
    """What a drawn-plan rule may use: the right plan's points (mm, the pole at the origin),
    for each image the images of the other points of its links (``others``), the drive's
    vector laid off first (``first``: its quantity, ``v_B`` or ``a_B``, and exact value) and
    the value rules' context."""

    points_mm: Mapping[str, Sequence[float]]
    others: Mapping[str, tuple[str, ...]]
    first: tuple[str, float] | None
    context: ScalesAndMotion


@dataclass(frozen=True)
class Mistake:
    """One mistake: its key (in keys, grades and reports), what the student is told, and how
    its answer is made — a ``construction`` rule or a ``value`` rule."""

    key: str
    explanation: Message
    construction: Rule | None = None
    value: Answers | None = None
    #: a construction line drawn in the wrong direction: (direction, segment) → the direction
    #: drawn, or None where the mistake does not touch that line
    direction: Callable[[Any, Segment], Any] | None = None
    #: an image placed by the similarity rule turned over: segment → True where it is
    mirror: Callable[[Segment], bool] | None = None
    #: where the mistake puts a point of a drawn plan, from the right plan (a mistake that
    #: re-draws the plans places its points by the re-drawn plans instead)
    placed: Placed | None = None
    #: what a student is told whose drawn point lies where the mistake puts it (default: the
    #: explanation)
    drawing: Message | None = None

    @property
    def redraws(self) -> bool:
        """Whether it is a construction mistake (its answers come from the plans drawn
        again with it)."""
        return (self.construction or self.direction or self.mirror) is not None


# The rules below that depend on a name or a factor are bound to it with functools.partial in
# the registry (not built as closures when the module loads), so each runs, as written, when a
# key is built.
def _left_out(name: str, length: float, segment: Segment) -> float | None:
    """The component ``name`` not laid off: a group's normal component (the drive's own is
    drawn as the crank's acceleration), or a Coriolis component that is drawn."""
    if segment.name != name:
        return None
    if name == "normal":
        return 0.0 if segment.group is not None else None
    return 0.0 if length > 0 else None


def _reversed(name: str, length: float, segment: Segment) -> float | None:
    """The component ``name`` laid off the wrong way (where it is drawn)."""
    return -length if segment.name == name and length > 0 else None


def _along(name: str, direction, segment: Segment):
    """A group's ``name`` construction line drawn along the link instead of across it."""
    if segment.name == name and segment.group is not None:
        return perp(direction)            # turned 90°: along the link
    return None


def _mirrored(segment: Segment) -> bool:
    """Every image placed by the similarity rule off its link's line, turned over."""
    return segment.action == "similarity"


def _sense(quantity, value, tolerance, given):
    return [(-value, tolerance)] if QUANTITY_KINDS[kind_of(quantity)].signed else []


def _full_acceleration(quantity, value, tolerance, given):
    if kind_of(quantity) != "rho":
        return []
    from ..report import exact_value

    point = quantity.partition("_")[2]
    here = given.motion.at(0)
    speed = exact_value(here, f"v_{point}")
    accel = exact_value(here, f"a_{point}")
    return [(speed ** 2 / accel, tolerance)] if accel else []


def _factor(quantity, given) -> float | None:
    scales = given.scales
    return scale_factor(quantity, scales.mu_l, scales.mu_v, scales.mu_a)


def _scale_none(quantity, value, tolerance, given):
    factor = _factor(quantity, given)
    return [(value / factor, tolerance / factor)] if factor and factor != 1.0 else []


def _scale_twice(quantity, value, tolerance, given):
    factor = _factor(quantity, given)
    return [(value * factor, tolerance * factor)] if factor and factor != 1.0 else []


def _scale_inverted(quantity, value, tolerance, given):
    """The drawn length divided by the scale instead of multiplied."""
    factor = _factor(quantity, given)
    return ([(value / factor ** 2, tolerance / factor ** 2)] if factor and factor != 1.0
            else [])


def _scaled_by(times: float, quantity, value, tolerance, given):
    """Ten times too large (10) or too small (-10: divided, exactly)."""
    if QUANTITY_KINDS[kind_of(quantity)].scale is None:    # not read off a plan
        return []
    if times < 0:
        return [(value / -times, tolerance / -times)]
    return [(value * times, tolerance * times)]


def _link_length(mechanism, link: str) -> float | None:
    """A link's length as a plan reads ω off it: between its first two points."""
    points = list(mechanism.links[link].points)
    return mechanism.links[link].length(points[0], points[1]) if len(points) >= 2 else None


def other_lengths(motion, link: str) -> list[tuple[str, float]]:
    """(other link of the same Assur group, l_link / l_other): the factor an angular
    velocity or acceleration takes when read off with the other link's length.

    >>> from planmethod.kinematics import solve
    >>> from planmethod.spec import load_exercise
    >>> mechanism = load_exercise("exercises/fourbar_forces.toml").mechanism
    >>> [(other, round(ratio, 4)) for other, ratio in other_lengths(solve(mechanism, 60.0),
    ...                                                               "BC")]
    [('CD', 1.2222)]
    """
    mechanism = motion.mechanism
    if link not in mechanism.links:
        return []
    own = _link_length(mechanism, link)
    out = []
    for group in motion.structure.groups:
        if link not in group.links:
            continue
        for other in group.links:
            length = _link_length(mechanism, other) if other != link else None
            if own and length and abs(length - own) > 1e-9 * own:
                out.append((other, own / length))
    return out


def _wrong_length(quantity, value, tolerance, given):
    kind, _, link = quantity.partition("_")
    if QUANTITY_KINDS[kind].subject != "link":    # ω and ε: read with a link's length
        return []
    return [(value * ratio, tolerance * ratio) for _, ratio in other_lengths(given.motion,
                                                                             link)]


#: the quantities read as a segment from the pole, and the motion's reading of each
_ABSOLUTE = {"v": "velocity", "a": "acceleration"}


def _relative(quantity, value, tolerance, given):
    """|v_XY| (or |a_XY|) for the other points Y of X's link: the segment from the image of Y
    read instead of the segment from the pole."""
    kind, _, point = quantity.partition("_")
    if kind not in _ABSOLUTE or "@" in point:
        return []
    motion = given.motion
    read = getattr(motion.at(0), _ABSOLUTE[kind])
    mechanism = motion.mechanism
    out = []
    try:
        own = np.asarray(read(point), float).reshape(-1, 2)[0]
    except Exception:                     # not a point this scene solved
        return []
    others = []
    for link in mechanism.links_with_point(point):
        if link == "frame" or link not in motion.links:
            continue
        others += [name for name in mechanism.links[link].points
                   if name != point and name not in others]
    for other in others:
        try:
            theirs = np.asarray(read(other), float).reshape(-1, 2)[0]
        except Exception:
            continue
        if float(norm(theirs)) > 0:      # from a fixed point it is the absolute one
            out.append((float(norm(own - theirs)), tolerance))
    return out


def _relative_placed(label: str, plan: PlanContext) -> list[tuple[float, float]]:
    """The image laid off from the pole by its relative vector (from the image of another
    point of its link) instead of its absolute one: ``x − y`` for each such image ``y`` off
    the pole (from a fixed point the relative vector is the absolute one)."""
    x, y = plan.points_mm[label]
    out = []
    for other in plan.others.get(label, ()):
        other_x, other_y = plan.points_mm[other]
        if math.hypot(other_x, other_y) > 0:
            out.append((x - other_x, y - other_y))
    return out


def _at_scale(rule: Answers, label: str, plan: PlanContext) -> list[tuple[float, float]]:
    """The whole plan laid off at a wrong scale: the slip that turns a reading into ``rule``'s
    wrong answer, made when the drive's vector is turned into a length, draws every point at
    (right reading / wrong reading) times its right place."""
    if plan.first is None:
        return []
    quantity, value = plan.first
    x, y = plan.points_mm[label]
    return [(x * value / wrong, y * value / wrong)
            for wrong, _ in rule(quantity, value, 0.0, plan.context) if wrong]


def _degrees(quantity, value, tolerance, given):
    if not QUANTITY_KINDS[kind_of(quantity)].unit.startswith("rad"):
        return []
    return [(math.degrees(value), math.degrees(tolerance))]


def _length_mm(quantity, value, tolerance, given):
    if not QUANTITY_KINDS[kind_of(quantity)].unit.startswith("rad"):
        return []
    return [(value / 1000.0, tolerance / 1000.0)]


def _millimetres(quantity, value, tolerance, given):
    if QUANTITY_KINDS[kind_of(quantity)].unit.startswith("rad"):
        return []
    return [(value * 1000.0, tolerance * 1000.0)]


_TEN_TIMES, _TENTH = partial(_scaled_by, 10.0), partial(_scaled_by, -10.0)

#: every known mistake, in the order a key lists them (the first of two that give the same
#: answer is named first)
REGISTRY: dict[str, Mistake] = {mistake.key: mistake for mistake in (
    Mistake("sense", message("the sense (sign) is reversed"), value=_sense,
            drawing=message("the crank's sense of rotation was reversed (the plan is turned "
                            "180°)")),
    Mistake("no_normal", message("the normal component aⁿ was left out"),
            construction=partial(_left_out, "normal")),
    Mistake("no_coriolis", message("the Coriolis component aᵏ was left out"),
            construction=partial(_left_out, "coriolis")),
    Mistake("coriolis_reversed", message("the Coriolis component aᵏ was laid off the wrong way"),
            construction=partial(_reversed, "coriolis")),
    Mistake("tangential_along", message("the tangential component aᵗ was drawn along the link "
                                        "instead of across it"),
            direction=partial(_along, "tangential")),
    Mistake("mirrored_similarity", message("the image of a point was placed by the similarity "
                                           "rule with its triangle turned over (mirrored "
                                           "across the image of the link's line)"),
            mirror=_mirrored),
    Mistake("full_acceleration",
            message("the full acceleration was used instead of its normal component"),
            value=_full_acceleration),
    Mistake("relative_for_absolute",
            message("a relative velocity or acceleration (from the image of another point of "
                    "the link) was read instead of the absolute one (from the pole)"),
            value=_relative, placed=_relative_placed,
            drawing=message("a relative velocity or acceleration was laid off from the pole "
                            "instead of from the image of the link's other point (relative for "
                            "absolute)")),
    Mistake("wrong_length", message("the angular velocity or acceleration was read off with "
                                    "the length of the group's other link"),
            value=_wrong_length),
    Mistake("scale_none", message("the plan's scale was not applied (the answer is a drawn "
                                  "length)"),
            value=_scale_none, placed=partial(_at_scale, _scale_none),
            drawing=message("the plan was drawn at a wrong scale: the drive's vector laid off "
                            "as its value in mm, without the scale")),
    Mistake("scale_twice", message("the plan's scale was applied twice"), value=_scale_twice,
            placed=partial(_at_scale, _scale_twice),
            drawing=message("the plan was drawn at a wrong scale: the drive's vector divided by "
                            "the scale twice")),
    Mistake("scale_inverted", message("the drawn length was divided by the plan's scale "
                                      "instead of multiplied"),
            value=_scale_inverted, placed=partial(_at_scale, _scale_inverted),
            drawing=message("the plan was drawn at a wrong scale: the drive's vector multiplied "
                            "by the scale instead of divided")),
    Mistake("scale_ten", message("the plan's scale was misread ten times too large"),
            value=_TEN_TIMES, placed=partial(_at_scale, _TEN_TIMES),
            drawing=message("the plan was drawn at a wrong scale, misread ten times too large "
                            "(every length ten times too short)")),
    Mistake("scale_tenth", message("the plan's scale was misread ten times too small"),
            value=_TENTH, placed=partial(_at_scale, _TENTH),
            drawing=message("the plan was drawn at a wrong scale, misread ten times too small "
                            "(every length ten times too long)")),
    Mistake("degrees", message("degrees were given for radians"), value=_degrees),
    Mistake("length_mm", message("the length was taken in mm instead of m"), value=_length_mm),
    Mistake("millimetres", message("millimetres were given for metres"), value=_millimetres),
)}

#: key → what the student is told
MISTAKES: dict[str, Message] = {key: mistake.explanation for key, mistake in REGISTRY.items()}
#: the mistakes made in the construction itself (the plans are drawn again with them)
CONSTRUCTION_MISTAKES = tuple(key for key, mistake in REGISTRY.items() if mistake.redraws)


class _Mistaken:
    """The plan emulator's hooks that draw a construction mistake (``perturb``, ``turn``,
    ``mirror``), noting every segment the mistake changed (``found``)."""

    def __init__(self, mistake: Mistake) -> None:
        self.rule, self.turning, self.mirroring = (mistake.construction, mistake.direction,
                                                   mistake.mirror)
        self.found: list[Segment] = []

    def wrong(self, length: float, segment: Segment) -> float:
        if (self.rule is not None and segment.plan == "acceleration"
                and segment.action == "lay_off"):
            drawn = self.rule(length, segment)
            if drawn is not None:
                self.found.append(segment)
                return drawn
        return length

    def turn(self, direction, segment: Segment):
        if self.turning is not None and segment.plan == "acceleration":
            drawn = self.turning(direction, segment)
            if drawn is not None:
                self.found.append(segment)
                return drawn
        return direction

    def mirror(self, segment: Segment) -> bool:
        if self.mirroring is not None and self.mirroring(segment):
            self.found.append(segment)
            return True
        return False

    def changes_none(self, drawn) -> bool:
        """Whether a mistake made only in the lengths laid off changes none of ``drawn``
        ((length, segment) pairs of the exact drawing)."""
        return (self.rule is not None and self.turning is None and self.mirroring is None
                and not any(self.rule(length, segment) is not None for length, segment in drawn
                            if segment.plan == "acceleration" and segment.action == "lay_off"))


def mistaken_plans(exercise: Exercise, mistake: str, *, motion=None, drawn=None):
    """The plans as drawn with a construction mistake of :data:`REGISTRY`: their points and
    readings (no position plan, no steps: ``draw_plans(position=False)``). None if the
    exercise has no step the mistake changes (or asks for no acceleration plan).

    ``drawn`` are the exact drawing's (length, :class:`~planmethod.plans.construction.
    Segment`) pairs in construction order, if known (a
    :class:`~planmethod.grading.tolerances.Propagation`'s ``lengths`` and ``segments``): a
    mistake made only in the lengths laid off that changes none of them changes nothing
    (until one length changes, the drawing is the exact one), and gives None undrawn.

    Raises
    ------
    KeyError
        If ``mistake`` is not a construction mistake.
    """
    if not REGISTRY[mistake].redraws:
        raise KeyError(mistake)
    from ..errors import ToggleError
    from ..plans import draw_plans

    hooks = _Mistaken(REGISTRY[mistake])
    if not exercise.ask.needs_acceleration:
        return None
    if drawn is not None and hooks.changes_none(drawn):
        return None
    settings = replace(exercise.plan, precision_mm=0.0)
    try:
        plans = draw_plans(exercise, settings=settings, motion=motion, perturb=hooks.wrong,
                           turn=hooks.turn,
                           mirror=hooks.mirror if hooks.mirroring is not None else None,
                           position=False)
    except ToggleError:       # the wrong lines do not meet: no answer to predict
        return None
    return plans if hooks.found else None


def value_answers(quantity: str, value: float, tolerance: float, *, scales,
                  motion) -> list[tuple[str, float, float]]:
    """(mistake, wrong answer, its tolerance) of every value mistake that applies to
    ``quantity``, in registry order."""
    given = ScalesAndMotion(scales, motion)
    return [(key, wrong, wrong_tolerance) for key, mistake in REGISTRY.items()
            if mistake.value is not None
            for wrong, wrong_tolerance in mistake.value(quantity, value, tolerance, given)]


def drawn_explanation(mistake: str) -> Message:
    """What a student who drew a plan point where ``mistake`` puts it is told: the registry's
    explanation, and for a reversed sense the plan turned 180°.

    >>> from planmethod.words import render
    >>> render(drawn_explanation("sense"))
    "the crank's sense of rotation was reversed (the plan is turned 180°)"
    >>> render(drawn_explanation("no_coriolis"))
    'the Coriolis component aᵏ was left out'
    """
    return REGISTRY[mistake].drawing or REGISTRY[mistake].explanation


def drawn_mistakes(plan: PlanContext, radii: Mapping[str, float],
                   redrawn: Mapping[str, Mapping[str, Sequence[float]]],
                   labels: Sequence[str]) -> dict[str, list[list]]:
    """Where the known mistakes put each drawn point: ``label → [[mistake, x, y], …]`` (mm, y up,
    rounded to :data:`DRAWN_DECIMALS`), in registry order.

    ``redrawn`` holds the points of the plans re-drawn with a construction mistake (and the
    velocity plan turned 180° under ``sense``); a mistake with a ``placed`` rule places the
    point from the right plan. Only positions told apart from the right one and from the pole
    (by more than the point's tolerance radius in ``radii``) and on a sheet are listed.

    Examples
    --------
    >>> context = PlanContext({"p": (0.0, 0.0), "b": (0.0, 30.0), "c": (20.0, 10.0)},
    ...                       {"c": ("b",)}, None, ScalesAndMotion(None, None))
    >>> drawn_mistakes(context, {"b": 0.5, "c": 0.5}, {}, ["b", "c"])
    {'c': [['relative_for_absolute', 20.0, -20.0]]}
    """
    out: dict[str, list[list]] = {}
    for label in labels:
        right_x, right_y = (float(v) for v in plan.points_mm[label])
        radius = float(radii.get(label, 0.0))
        found: list[list] = []
        for key, mistake in REGISTRY.items():
            positions = []
            if label in redrawn.get(key, {}):
                positions.append(redrawn[key][label])
            if mistake.placed is not None:
                positions += mistake.placed(label, plan)
            for position in positions:
                x, y = (round(float(value), DRAWN_DECIMALS) + 0.0 for value in position)
                if not (math.isfinite(x) and math.isfinite(y)):
                    continue
                away = math.hypot(x, y)
                if (math.hypot(x - right_x, y - right_y) <= radius or away <= radius
                        or away > DRAWN_SHEET_MM or [key, x, y] in found):
                    continue
                found.append([key, x, y])
        if found:
            out[label] = found
    return out


def plan_context(plans, name: str, motion) -> PlanContext:
    """The :class:`PlanContext` of the plan ``name`` (``velocity`` or ``acceleration``) of
    :class:`~planmethod.plans.Plans` drawn from ``motion`` (their exact motion).

    >>> from planmethod.kinematics import solve
    >>> from planmethod.plans import draw_plans
    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
    >>> motion = solve(exercise.mechanism, exercise.mechanism.drive.angle)
    >>> context = plan_context(draw_plans(exercise, motion=motion), "velocity", motion)
    >>> context.others["c"], context.first[0]
    (('b', 'd'), 'v_B')
    """
    from ..model import FRAME
    from ..plans import image_label
    from ..report import exact_value

    plan = getattr(plans, name)
    mechanism = plans.exercise.mechanism
    labels = set(plan.points_mm)
    others: dict[str, tuple[str, ...]] = {}
    for label in plan.points_mm:
        if "_" in label or label == plan.pole:      # n_CB, k_C…: no point of a link
            continue
        point_name, at, link = label.partition("@")
        point = point_name.rstrip("′").upper()
        links = [link] if at else [each for each in mechanism.links_with_point(point)
                                    if each != FRAME]
        found: list[str] = []
        for each in links:
            for other in mechanism.links[each].points if each in mechanism.links else ():
                image = image_label(other, plan.pole)
                if other != point and image in labels and image not in found:
                    found.append(image)
        others[label] = tuple(found)
    quantity = f"{'v' if name == 'velocity' else 'a'}_{plans.scales.scale_point}"
    try:
        value = exact_value(motion.at(0), quantity)
    except KeyError:
        value = None
    first = (quantity, float(value)) if value else None
    return PlanContext(plan.points_mm, others, first, ScalesAndMotion(plans.scales, motion))
