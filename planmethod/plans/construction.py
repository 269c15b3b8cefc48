"""The plan emulator: velocity and acceleration plans built the way a student draws them.

For one crank angle the plans are drawn group by group in build order from the groups' vector
equations (see :mod:`planmethod.kinematics.groups.dyad`): a known vector is laid off from a
known plan point; an unknown one is a line of known direction through a known plan point; two
such lines are intersected. The acceleration plan lays off the normal components computed from
velocity-plan segments, (bn) = (bc)²·μv²/((BC)·μl·μa), and the Coriolis components 2ω·v_rel
turned 90° in the sense of ω. Extra points follow by the similarity rule. ω and ε are read off
the plans.

Only the mechanism's *positions* (the position plan) and the drive's ω1, ε1 enter; velocities
and accelerations are never taken from the analytical solution. With ``precision_mm`` > 0 every
length laid off or read off is rounded to that precision (directions are drawn exactly), so a
student sees what a drawing's accuracy gives; at 0 the plans equal the exact vectors.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> plans = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
>>> round(plans.readings["v_C"], 4), round(plans.omega("BC"), 3)
(5.2716, -24.254)
>>> [round(x, 3) for x in plans.velocity.points_mm["b"]]
[-21.213, 21.213]
"""

from __future__ import annotations

import functools
import math
import re
import threading
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..errors import PlanmethodError, SpecError, ToggleError
from ..kinematics import Motion, solve
from ..kinematics.groups.checks import TOGGLE_SINE
from ..kinematics.groups.dyad import Construction, follow_tied
from ..model import FRAME, Exercise, PlanSettings
from ..numbering import course_numbers
from ..vectors import angle_deg, cross, dot, norm, perp, unit, unit_or_zero
from ..vocabulary import (
    PlanKind,
    coriolis_letter,
    links_text,
    numbered,
    shown_title,
    subscript,
    symbol,
)
from .groups import plan_face
from .groups.base import PlansUnavailableError, sense
from .scales import Scales, choose_scales

__all__ = [
    "LinkImage",
    "Plan",
    "Plans",
    "PlansUnavailableError",
    "PositionPlan",
    "Segment",
    "Step",
    "draw_plans",
    "image_label",
]

#: A drawing sheet is never larger than this (mm): lines that would meet further away than
#: this, given the drafting precision, are parallel to within the drawing's precision.
SHEET_MM = 1000.0


def image_label(point: str, pole: str = "p") -> str:
    """The plan label of a point's image: its name in lower case (``B`` → ``b``,
    ``B@lever`` → ``b@lever``); a name that would clash with the pole gets a prime (p′).

    Examples
    --------
    >>> image_label("C"), image_label("O2"), image_label("P"), image_label("B@lever")
    ('c', 'o2', 'p′', 'b@lever')
    """
    name, at, link = point.partition("@")
    label = name.lower()
    if label == pole:
        label += "′"
    return label + (at + link if at else "")


@dataclass(frozen=True, slots=True)
class Segment:
    """A length about to be laid off or read off a drawing, as shown to a ``perturb`` model.

    ``plan`` is ``velocity``, ``acceleration`` or ``position``; ``action`` is ``lay_off``,
    ``read``, ``similarity`` or ``measure`` (a length read off the position plan), or ``line``
    (a construction line's direction, as shown to a ``turn`` model); ``name``
    says which (the component, the quantity or the label); a lay-off also names its
    ``vector`` and the ``group`` index (None for the drive).
    """

    plan: str
    action: str
    name: str | None = None
    vector: str | None = None
    group: int | None = None


@dataclass(frozen=True, slots=True)
class Step:
    """One construction step of a plan (docs/json-report.md, "Plan steps").

    ``action`` is one of ``pole``, ``lay_off`` (a vector from ``start`` to ``end``), ``line`` (a
    construction line through ``start`` at ``direction_deg``), ``intersect`` (``lines`` are the
    two line steps' numbers; ``angle_deg`` the angle between them), ``similarity`` (``end``
    placed from the images ``references`` of the same link), ``coincide`` (``end`` coincides
    with ``start``), ``project`` (``end`` is the foot of ``start`` on a line) and ``read``
    (a segment ``start``–``end`` read off as ``length_mm`` giving ``value`` in SI).
    """

    number: int
    action: str
    text: str
    start: str | None = None
    end: str | None = None
    direction_deg: float | None = None
    length_mm: float | None = None
    component: str | None = None
    vector: str | None = None
    group: int | None = None
    lines: tuple[int, int] | None = None
    angle_deg: float | None = None
    flagged: bool = False
    references: tuple[str, ...] = ()
    quantity: str | None = None
    value: float | None = None

    def as_dict(self) -> dict:
        out = {}
        for name in self.__slots__:
            value = getattr(self, name)
            if value is None or value == () or (name == "flagged" and not value):
                continue
            out[name] = list(value) if isinstance(value, tuple) else value
        return out


@dataclass(frozen=True)
class Plan:
    """A velocity or acceleration plan as data: pole, scale, labelled points (mm), steps."""

    kind: str
    pole: str
    scale: float
    unit: str
    points_mm: Mapping[str, tuple[float, float]]
    steps: tuple[Step, ...]
    flags: tuple[str, ...] = ()
    precision_mm: float = 0.0
    title: str = ""
    #: the links' numbers in the course's notation (for printed names; not in the report)
    numbers: Mapping[str, int] = field(default_factory=dict)

    def point(self, label: str) -> np.ndarray:
        return np.asarray(self.points_mm[label], dtype=float)

    def vector(self, label: str) -> np.ndarray:
        """The SI vector a plan point represents (from the pole, times the scale)."""
        return self.point(label) * self.scale

    def as_dict(self) -> dict:
        return {"pole": self.pole, "scale": self.scale, "unit": self.unit,
                "points_mm": {k: list(v) for k, v in self.points_mm.items()},
                "steps": [step.as_dict() for step in self.steps],
                "flags": list(self.flags)}


@dataclass(frozen=True)
class PositionPlan:
    """The mechanism drawn at μl: every point (mm, global axes), the links, guides, pivots."""

    mu_l: float
    points_mm: Mapping[str, tuple[float, float]]
    links: Mapping[str, tuple[str, ...]]
    pivots: tuple[str, ...]
    slides: tuple[dict, ...]
    drive: tuple[str, str, float]
    curvature: Mapping[str, dict] = field(default_factory=dict)
    angle: float = 0.0
    title: str = ""
    #: the links' numbers in the course's notation (for printed names; not in the report)
    numbers: Mapping[str, int] = field(default_factory=dict)

    def as_dict(self) -> dict:
        return {"mu_l": self.mu_l, "points_mm": {k: list(v) for k, v in self.points_mm.items()},
                "links": {k: list(v) for k, v in self.links.items()},
                "pivots": list(self.pivots), "slides": list(self.slides),
                "curvature": dict(self.curvature)}


@dataclass(frozen=True)
class Plans:
    """The position, velocity and acceleration plans of one crank angle, and what is read off
    them (``readings``: quantity → SI value, e.g. ``v_C``, ``omega_BC``, ``rho_D``).
    ``position`` is None when drawn with ``position=False`` (readings only)."""

    exercise: Exercise
    angle: float
    scales: Scales
    position: PositionPlan | None
    velocity: Plan
    acceleration: Plan | None
    readings: Mapping[str, float]
    flags: tuple[str, ...]
    motion: Motion

    def omega(self, link: str) -> float | None:
        """ω of ``link`` as read off the velocity plan (None: not read)."""
        return self.readings.get(f"omega_{link}")

    def epsilon(self, link: str) -> float | None:
        """ε of ``link`` as read off the acceleration plan (None: not read)."""
        return self.readings.get(f"epsilon_{link}")

    def rotated_velocity_plan(self) -> dict[str, tuple[float, float]]:
        """The velocity plan turned 90° clockwise onto the position plan, pole p at the drive's
        pivot (mm on the position plan): Zhukovsky's lever stands on it. For ω1 > 0 the image
        of the crank pin then lies along the crank (Abduvaliev & Abduxoshimov)."""
        pivot = np.asarray(self.position.points_mm[self.position.drive[1]])
        out = {}
        for label, (x, y) in self.velocity.points_mm.items():
            out[label] = (float(pivot[0] + y), float(pivot[1] - x))
        return out


@dataclass(frozen=True, slots=True)
class LinkImage:
    """How a link's points map onto a plan: the image of a point P of the link is
    ``ref_mm + (ω·J(P − ref))/μv`` on the velocity plan and
    ``ref_mm + (ε·J(P − ref) − ω²(P − ref))/μa`` on the acceleration plan (the similarity rule),
    with ω and ε as read off the plans."""

    ref: np.ndarray
    ref_mm: np.ndarray
    ref_label: str
    omega: float
    epsilon: float = 0.0


# The emulator draws one drawing, or — where a ``perturb`` model returns arrays of lengths —
# several copies of it at once (a tolerance analysis: one copy per segment lengthened): then
# the numbers it lays off and reads are arrays with a leading copy axis (N,), its points (N, 2).
# The vector helpers (planmethod.vectors) take a vector's coordinates from its last axis, so
# they serve both.
def _times(factor, vector: np.ndarray) -> np.ndarray:
    """A vector times a number, or times each copy's number."""
    return np.asarray(factor)[..., None] * vector


def _sign(value):
    """+1 where ``value`` ≥ 0, else −1 (a number, or one per copy)."""
    if np.ndim(value) == 0:
        return 1.0 if value >= 0 else -1.0
    return np.where(value >= 0, 1.0, -1.0)


#: a quantity's report name inside a sentence (``omega_BC``, ``v_CC@frame``, ``ds_slider/frame``)
_QUANTITY = re.compile(r"\b(?:a_rel|omega|epsilon|coriolis|dds|ds|rho|v|a|s)_[A-Za-z0-9_@/:*]+")
#: a Coriolis point's report name (``k1_Q``, ``k2_B@yoke``): its side's index
_CORIOLIS = re.compile(r"k([0-9])_(?=[A-Z])")
#: the digits of a point's name (``O2``, ``o2``, ``BO2``), set as subscripts (O₂, o₂, BO₂)
_POINT_DIGITS = re.compile(r"(?<=[A-Za-z])[0-9]+")


class _LinkPatterns(NamedTuple):
    """The patterns of :func:`course_text` that name a mechanism's links."""

    on_link: re.Pattern
    pair: re.Pattern
    rate: re.Pattern
    similarity: re.Pattern
    #: a link's name with an underscore, and it in words
    worded: tuple[tuple[re.Pattern, str], ...]


@functools.lru_cache(maxsize=64)
def _link_patterns(names: tuple[str, ...]) -> _LinkPatterns:
    """The patterns for links ``names`` (compiled once per mechanism; longest name first)."""
    joined = "|".join(re.escape(name) for name in sorted(names, key=len, reverse=True))
    return _LinkPatterns(re.compile(rf"@({joined})"),
                         re.compile(rf"(?<![\w/])({joined})/({joined})(?![\w/])"),
                         re.compile(rf"([ωε])_({joined})\b"),
                         re.compile(rf"similarity on ({joined})\b"),
                         tuple((re.compile(rf"\b{re.escape(name)}\b"), name.replace("_", " "))
                               for name in names if "_" in name))


def course_text(text: str, numbers: Mapping[str, int]) -> str:
    """A construction step's sentence as a course writes it: a point on a link with the
    link's number (``c@frame`` → ``c₁``, ``v_CC@frame`` → ``v_CC₁``), a link's quantity by its
    symbol (``omega_BC`` → ``ω₃``, ``a_rel_…`` → ``aʳ_…``), the digits of a point's name as
    subscripts (``o2``, ``aᵗ_BO2`` → o₂, aᵗ_BO₂), a Coriolis point without its side's index
    (``k1_Q``, ``k2_Q`` → k_Q, k′_Q: :func:`~planmethod.vocabulary.coriolis_letter`), a link's
    name with an underscore in words.

    Examples
    --------
    >>> numbers = {"frame": 0, "AB": 1, "BC": 2, "rocker_EF": 3}
    >>> course_text("(c@framec) = 29 mm → v_CC@frame = 0.58; omega_BC, omega_rocker_EF",
    ...             numbers)
    '(c₀c) = 29 mm → v_CC₀ = 0.58; ω₂, ω₃'
    >>> course_text("aᵏ = 2·ω_BC·v_rel; along the guide of AB/BC; d by similarity on BC",
    ...             numbers)
    'aᵏ = 2·ω₂·v_rel; along the guide of pair 1–2; d by similarity on link 2'
    >>> course_text("aᵗ_B@BCO2 from o2; (q@ABk1_Q) = 12 mm; k2_Q coincides with q@frame",
    ...             numbers)
    'aᵗ_B₂O₂ from o₂; (q₁k_Q) = 12 mm; k′_Q coincides with q₀'
    """
    patterns = _link_patterns(tuple(numbers)) if numbers else None
    if "@" in text and patterns:   # a point on a link: its name, the link's number below
        text = patterns.on_link.sub(
            lambda match: subscript(str(numbers[match.group(1)])), text)

    def quantity(match: re.Match) -> str:
        name = match.group(0)
        if name.startswith("a_rel_"):
            return "aʳ_" + name[len("a_rel_"):]
        return symbol(name, dict(numbers))

    text = _QUANTITY.sub(quantity, text)
    if patterns:
        # a slide by its two links' numbers (the guide of pair 2–3), a link's ω or ε by its
        # number (2·ω₂·v_rel), the link of a similarity rule by its number
        # (each only where its mark is in the text: most steps have none of them)
        if "/" in text:
            text = patterns.pair.sub(
                lambda match: f"pair {numbers[match.group(1)]}–{numbers[match.group(2)]}",
                text)
        if "ω_" in text or "ε_" in text:
            text = patterns.rate.sub(
                lambda match: match.group(1) + subscript(str(numbers[match.group(2)])), text)
        if "similarity on " in text:
            text = patterns.similarity.sub(
                lambda match: f"similarity on link {numbers[match.group(1)]}", text)
        for pattern, words in patterns.worded:
            text = pattern.sub(words, text)
    if "_" in text:
        text = _CORIOLIS.sub(lambda match: coriolis_letter(match.group(1)) + "_", text)
    return _POINT_DIGITS.sub(lambda match: subscript(match.group(0)), text)


class _Sheet:
    """One plan being drawn: its points, steps and the drafting precision."""

    def __init__(self, kind: str, pole: str, scale: float, unit: str, precision: float,
                 min_angle: float, perturb=None, record: bool = True,
                 numbers: Mapping[str, int] | None = None, turn=None) -> None:
        self.kind, self.pole, self.scale, self.unit = kind, pole, scale, unit
        self.precision, self.min_angle = precision, min_angle
        self.perturb = perturb
        #: a direction model ``turn(direction, segment) -> direction`` for construction lines
        #: (a construction drawn with a mistake); None draws them as they are
        self.turn = turn
        #: keep the steps (False: only points and readings are wanted; steps are counted)
        self.record = record
        #: the links' numbers, for the sentences (:func:`course_text`)
        self.numbers = numbers or {}
        self.count = 0
        self.points: dict[str, np.ndarray] = {pole: np.zeros(2)}
        self.steps: list[Step] = []
        self.flags: list[str] = []
        self.lines: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self.add(Step(0, "pole", f"pole {pole}", end=pole))

    def add(self, step: Step) -> int:
        self.count += 1
        if self.record:
            fields = [getattr(step, n) for n in Step.__slots__[1:]]
            fields[1] = course_text(fields[1], self.numbers)      # the sentence
            self.steps.append(Step(self.count, *fields))
        return self.count

    def round(self, length: float, segment: Segment) -> float:
        """A length as laid off or read off the drawing, ``segment`` saying which (``perturb``
        replaces the rounding, and may return one length per copy of the drawing)."""
        if self.perturb is not None:
            drawn = self.perturb(length, segment)
            return float(drawn) if np.ndim(drawn) == 0 else drawn
        if self.precision > 0:
            return round(float(length) / self.precision) * self.precision
        return float(length)

    def lay_off(self, start: str, end: str, vector_mm: np.ndarray, *, text: str,
                component: str, vector: str, group: int | None = None) -> np.ndarray:
        """Lay off a known vector (exact direction, rounded length) from ``start``."""
        length = norm(vector_mm)
        drawn = self.round(length, Segment(self.kind, "lay_off", component, vector, group))
        direction = unit_or_zero(vector_mm, length)
        self.points[end] = self.points[start] + _times(drawn, direction)
        if not self.record:
            self.count += 1
        elif length > 0:
            self.add(Step(0, "lay_off", text, start=start, end=end,
                          direction_deg=angle_deg(direction), length_mm=drawn,
                          component=component, vector=vector, group=group))
        else:
            self.add(Step(0, "coincide", text, start=start, end=end, length_mm=0.0,
                          component=component, vector=vector, group=group))
        return self.points[end]

    def line(self, through: str, direction: np.ndarray, *, text: str, component: str,
             vector: str, group: int | None) -> int:
        if self.turn is not None:
            direction = np.asarray(self.turn(direction, Segment(self.kind, "line", component,
                                                                vector, group)), float)
        if self.record:
            number = self.add(Step(0, "line", text, start=through,
                                   direction_deg=angle_deg(direction) % 180.0,
                                   component=component, vector=vector, group=group))
        else:
            self.count += 1
            number = self.count
        self.lines[number] = (self.points[through].copy(), direction)
        return number

    def intersect(self, first: int, second: int, end: str, *, text: str, group_name: str,
                  group: int, angle: float) -> np.ndarray:
        (p1, e1), (p2, e2) = self.lines[first], self.lines[second]
        sine = cross(e1, e2)
        # the angle between the lines, 0…90°: atan2 keeps its digits near 90°, where asin of
        # the sine would lose half of them
        degrees = math.degrees(float(np.min(np.arctan2(np.abs(sine), np.abs(dot(e1, e2))))))
        limit = max(TOGGLE_SINE, self.precision / SHEET_MM)
        if np.min(np.abs(sine)) < limit:
            raise ToggleError(
                f"toggle position: on the {self.kind} plan the lines of steps {first} and "
                f"{second} are parallel to within the drawing's precision "
                f"({degrees:.3g}°)", line_angle_deg=degrees, link=group_name, angle=angle)
        t = cross(p2 - p1, e2) / sine
        self.points[end] = p1 + _times(t, e1)
        flagged = degrees < self.min_angle
        if flagged:     # the group by its links' numbers, the point as the course names it
            group_text = links_text(group_name.split("+"), self.numbers)
            self.flags.append(f"{self.kind} plan, group of {group_text}: the lines meet at "
                              f"{degrees:.3g}° (below {self.min_angle:g}°): point "
                              f"{course_text(end, self.numbers)} is poorly defined")
        self.add(Step(0, "intersect", text, end=end, lines=(first, second),
                      angle_deg=degrees, flagged=flagged, group=group))
        return self.points[end]

    def read(self, start: str, end: str, *, quantity: str, factor: float,
             sign: float = 1.0) -> float:
        """Read the segment start–end (rounded) and convert it: value = ±length·factor."""
        length = self.round(norm(self.points[end] - self.points[start]),
                            Segment(self.kind, "read", quantity))
        value = sign * length * factor
        if not self.record:
            self.count += 1
            return value
        self.add(Step(0, "read", f"({start}{end}) = {length:.4g} mm → {quantity} = {value:.6g}",
                      start=start, end=end, length_mm=length, quantity=quantity, value=value))
        return value

    def place_image(self, label: str, offset_mm: np.ndarray, image: LinkImage, link: str,
                    text: str) -> None:
        """Place a point by the similarity rule from the link's reference image."""
        length = norm(offset_mm)
        drawn = self.round(length, Segment(self.kind, "similarity", label))
        direction = unit_or_zero(offset_mm, length)
        self.points[label] = image.ref_mm + _times(drawn, direction)
        if not self.record:
            self.count += 1
            return
        self.add(Step(0, "similarity", text, start=image.ref_label, end=label,
                      references=(image.ref_label,), length_mm=drawn,
                      direction_deg=angle_deg(direction) if length > 0 else None,
                      vector=link))

    def finish(self, title: str) -> Plan:
        points = {k: (v if np.ndim(v) == 2 else (float(v[0]), float(v[1])))
                  for k, v in self.points.items()}    # copies of a drawing: (N, 2) each
        return Plan(self.kind, self.pole, self.scale, self.unit, points, tuple(self.steps),
                    tuple(self.flags), self.precision, title, self.numbers)


def _velocity_offset(image: LinkImage, point: np.ndarray, mu_v: float) -> np.ndarray:
    return _times(image.omega, perp(point - image.ref)) / mu_v


def _acceleration_offset(image: LinkImage, point: np.ndarray, mu_a: float) -> np.ndarray:
    r = point - image.ref
    return (_times(image.epsilon, perp(r)) - _times(image.omega ** 2, r)) / mu_a


class _Emulator:
    """Draws the three plans of one crank angle."""

    def __init__(self, exercise: Exercise, settings: PlanSettings, angle: float,
                 motion: Motion, scales: Scales, perturb=None, record: bool = True,
                 turn=None, mirror=None) -> None:
        self.mechanism = exercise.mechanism
        self.settings = settings
        self.angle = angle
        self.motion = motion
        self.scales = scales
        self.readings: dict[str, float] = {}
        self.states: dict = {}
        self.vimages: dict[str, LinkImage] = {}
        self.aimages: dict[str, LinkImage] = {}
        self.rel_velocity: dict[tuple[int, int], float] = {}
        #: a similarity model ``mirror(segment) -> bool``: place the image of a point off its
        #: link's line mirrored across the image of that line (a construction drawn with a
        #: mistake); None places every image as the similarity rule says
        self.mirror = mirror
        #: prismatic pair key → plan labels of the group side that draws its relative motion
        self.sliding_sides: dict[str, dict[str, object]] = {}
        precision, min_angle = settings.precision_mm, settings.min_angle_deg
        #: what a group kind's own drawing keeps between its velocity and acceleration plans
        self.memo: dict = {}
        numbers = course_numbers(self.mechanism)
        #: the drive's symbols follow the crank's number (ω₁ by default)
        self.crank_symbols = {letter: numbered(letter, numbers[self.mechanism.drive.link])
                              for letter in ("φ", "ω", "ε")}
        self.v = _Sheet(PlanKind.VELOCITY, "p", scales.mu_v, "(m/s)/mm", precision, min_angle,
                        perturb, record, numbers, turn)
        self.a = _Sheet(PlanKind.ACCELERATION, "π", scales.mu_a, "(m/s²)/mm", precision, min_angle,
                        perturb, record, numbers, turn)

    # -- geometry from the position plan ---------------------------------------------------
    def where(self, link: str, point: str) -> np.ndarray:
        state = self.states.get(link)
        if state is None:                # each link's state read once per drawing
            state = self.states[link] = self.motion.links[link]
        return state.place(self.mechanism.local(link, point))[0]

    def length_mm(self, first: np.ndarray, second: np.ndarray) -> float:
        """A length read off the position plan (rounded to the precision)."""
        return self.v.round(float(norm(second - first)) / self.scales.mu_l,
                            Segment("position", "measure"))

    def radius_mm(self, centre: np.ndarray, point: np.ndarray) -> float:
        """A radius read off the position plan to divide a reading by (ω, ε, aⁿ).

        Raises
        ------
        SpecError
            If the drafting precision rounds it to 0 mm (a precision coarser than the
            drawing's lengths).
        """
        drawn = self.length_mm(centre, point)
        if np.any(np.asarray(drawn) == 0):
            exact = float(norm(point - centre)) / self.scales.mu_l
            raise SpecError(f"a precision of {self.v.precision:g} mm draws a radius of "
                            f"{exact:.3g} mm on the position plan as 0 mm, and a reading "
                            "divides by it: the precision must be finer than the drawing",
                            key="plan.precision_mm", angle=self.angle)
        return drawn

    def label(self, point: str, sheet: _Sheet) -> str:
        return image_label(point, sheet.pole)

    def drawn_length(self, sheet: _Sheet, start: str, end: str) -> float:
        """The segment start–end of ``sheet`` as read off the drawing (mm, rounded)."""
        return sheet.round(norm(sheet.points[end] - sheet.points[start]),
                           Segment(sheet.kind, "read", "relative"))

    def omega(self, link: str) -> float:
        """A link's ω as read off the velocity plan (its images fixed)."""
        return self.vimages[link].omega

    def fix_velocity(self, link: str, ref: np.ndarray, label: str, omega: float) -> None:
        """The link's velocity image is known (its point ``ref`` at ``label``, its ω read off):
        the reading is kept, its other points follow by similarity."""
        self.readings[f"omega_{link}"] = omega
        self.vimages[link] = LinkImage(ref, self.v.points[label], label, omega)
        self.image_points(link, self.v, self.vimages[link], _velocity_offset, self.scales.mu_v)

    def fix_acceleration(self, link: str, ref: np.ndarray, label: str, omega: float,
                         epsilon: float) -> None:
        """The link's acceleration image is known (its ε read off): the reading is kept, its
        other points follow by similarity."""
        self.readings[f"epsilon_{link}"] = epsilon
        self.aimages[link] = LinkImage(ref, self.a.points[label], label, omega, epsilon)
        self.image_points(link, self.a, self.aimages[link], _acceleration_offset,
                          self.scales.mu_a)

    # -- images --------------------------------------------------------------------------------
    def image_points(self, link: str, sheet: _Sheet, image: LinkImage, offset, scale,
                     skip=()) -> None:
        for name in self.mechanism.links[link].points:
            label = self.label(name, sheet)
            if label in sheet.points or name in skip:
                continue
            position = self.where(link, name)
            if link == FRAME:
                sheet.points[label] = np.zeros(2)
                sheet.add(Step(0, "coincide", f"{label} at the pole: {name} is fixed",
                               start=sheet.pole, end=label, length_mm=0.0))
                continue
            position = self.similar(sheet, link, image, position, label)
            sheet.place_image(label, offset(image, position, scale), image, link,
                              f"{label} by similarity on {link} from {image.ref_label}")

    def image_of(self, sheet: _Sheet, link: str, position: np.ndarray, label: str) -> str:
        """The label of the image of ``link``'s material point at ``position`` on ``sheet``
        (placed if new, from the link's images on that sheet)."""
        images = self.vimages if sheet is self.v else self.aimages
        return self.image_at(sheet, images, link, position, label)

    def image_at(self, sheet: _Sheet, images: dict, link: str, position: np.ndarray,
                 label: str) -> str:
        """Label of the image of ``link``'s material point at ``position`` (placed if new)."""
        if label in sheet.points:
            return label
        image = images[link]
        position = self.similar(sheet, link, image, position, label)
        if sheet is self.v:
            offset = _velocity_offset(image, position, self.scales.mu_v)
        else:
            offset = _acceleration_offset(image, position, self.scales.mu_a)
        if link == FRAME:
            sheet.points[label] = np.zeros(2)
            sheet.add(Step(0, "coincide", f"{label} at the pole: the frame does not move",
                           start=sheet.pole, end=label, length_mm=0.0))
        else:
            sheet.place_image(label, offset, image, link,
                              f"{label} by similarity on {link} from {image.ref_label}")
        return label

    def similar(self, sheet: _Sheet, link: str, image: LinkImage, position: np.ndarray,
                label: str) -> np.ndarray:
        """The point whose image the similarity rule places for ``position`` of ``link``: the
        point itself, or — where the ``mirror`` model says so — its mirror image across the
        line through the image's reference point and another pin of the link (the student's
        triangle turned over)."""
        if self.mirror is None or link == FRAME:
            return position
        pins = [name for name in self.mechanism.links[link].points
                if len(self.mechanism.links_with_point(name)) > 1]
        for name in pins:
            other = self.where(link, name)
            axis = other - image.ref
            length = float(norm(axis))
            if length <= 1e-12 * max(1.0, float(norm(image.ref))):
                continue
            unit = axis / length
            offset = position - image.ref
            across = float(cross(unit, offset))
            if abs(across) <= 1e-9 * length:         # on the link's line: no mirror image
                return position
            if not self.mirror(Segment(sheet.kind, "similarity", label, link)):
                return position
            return position - 2.0 * across * perp(unit)
        return position

    # -- drive ---------------------------------------------------------------------------------
    def drive(self) -> None:
        drive, scales = self.mechanism.drive, self.scales
        crank = self.crank_symbols
        pivot = self.where(drive.link, drive.pivot)
        point = self.where(drive.link, scales.scale_point)
        radius = point - pivot
        length = float(norm(radius))
        pole_v, pole_a = self.v.pole, self.a.pole
        for sheet, images in ((self.v, self.vimages), (self.a, self.aimages)):
            images[FRAME] = LinkImage(np.zeros(2), np.zeros(2), sheet.pole, 0.0, 0.0)
            self.image_points(FRAME, sheet, images[FRAME], None, None)
        a_label = self.label(drive.pivot, self.v)
        b_v, b_a = self.label(scales.scale_point, self.v), self.label(scales.scale_point, self.a)
        omega, epsilon = drive.omega, drive.epsilon
        v_b = omega * perp(radius)
        # the reference vector is drawn as long as the scale makes it: exactly the written
        # *_mm where the scale is what that length asks (no rounding noise), else value/μ
        pinned = _pinned_mm(self.settings.velocity_mm, self.settings.mu_v,
                            float(norm(v_b)), scales.mu_v)
        b_vector = (unit(v_b) * pinned if pinned and omega else v_b / scales.mu_v)
        self.v.lay_off(pole_v, b_v, b_vector, component="absolute",
                       vector=f"v_{scales.scale_point}",
                       text=f"v_{scales.scale_point} = {crank['ω']}·l_{drive.pivot}"
                            f"{scales.scale_point} = {abs(omega) * length:.6g} m/s, ⟂ "
                            f"{drive.pivot}{scales.scale_point} in the sense of {crank['ω']}")
        self.vimages[drive.link] = LinkImage(pivot, self.v.points[a_label], a_label, omega)
        normal = -omega ** 2 * radius
        tangential = epsilon * perp(radius)
        total = normal + tangential
        fixed = _pinned_mm(self.settings.acceleration_mm, self.settings.mu_a,
                           float(norm(total)), scales.mu_a)
        factor = (fixed / norm(total)) if fixed and norm(total) else 1 / scales.mu_a
        point_name = scales.scale_point
        if epsilon == 0:
            self.a.lay_off(pole_a, b_a, normal * factor, component="normal",
                           vector=f"a_{point_name}",
                           text=f"a_{point_name} = aⁿ = {crank['ω']}²·l = "
                                f"{omega ** 2 * length:.6g} m/s², from {point_name} towards "
                                f"{drive.pivot}")
        else:
            n_label = f"n_{point_name}{drive.pivot}"
            self.a.lay_off(pole_a, n_label, normal * factor, component="normal",
                           vector=f"aⁿ_{point_name}{drive.pivot}",
                           text=f"aⁿ = {crank['ω']}²·l = {omega ** 2 * length:.6g} m/s², "
                                f"from {point_name} towards {drive.pivot}")
            self.a.lay_off(n_label, b_a, tangential * factor, component="tangential",
                           vector=f"aᵗ_{point_name}{drive.pivot}",
                           text=f"aᵗ = {crank['ε']}·l = {abs(epsilon) * length:.6g} m/s², ⟂ "
                                f"{drive.pivot}{point_name} in the sense of {crank['ε']}")
        a_pivot = self.label(drive.pivot, self.a)
        self.aimages[drive.link] = LinkImage(pivot, self.a.points[a_pivot], a_pivot, omega,
                                             epsilon)
        self.image_points(drive.link, self.v, self.vimages[drive.link], _velocity_offset,
                          scales.mu_v)
        self.image_points(drive.link, self.a, self.aimages[drive.link], _acceleration_offset,
                          scales.mu_a)
        self.readings[f"omega_{drive.link}"] = omega
        self.readings[f"epsilon_{drive.link}"] = epsilon
        self.readings[f"omega_{FRAME}"] = 0.0
        self.readings[f"epsilon_{FRAME}"] = 0.0

    # -- groups ----------------------------------------------------------------------------------
    def _base_label(self, side, sheet) -> str:
        name = side.base
        if "@" not in name:
            return self.label(name, sheet)
        return self.label(name, sheet)

    def velocity_group(self, construction: Construction) -> None:
        group = construction.group
        mu_v, mu_l = self.scales.mu_v, self.scales.mu_l
        x_label = self.label(construction.point, self.v)
        x = construction.position[0]
        line_numbers = []
        sides = construction.sides
        equation = " = ".join([f"v_{construction.point}"] + [
            f"v_{side.base} + v_{construction.point}{side.base}" for side in sides])
        for side in sides:
            base = side.position[0]
            base_label = self.image_at(self.v, self.vimages, side.base_link, base,
                                       self._base_label(side, self.v))
            direction = side.direction[0]
            if side.rotation:
                text = (f"through {base_label}: v_{construction.point}{side.base} ⟂ "
                        f"{construction.point}{side.base}")
                component = "relative"
            else:
                text = (f"through {base_label}: v_{construction.point}{side.base} along the "
                        f"guide of {side.slide.key}")
                component = "relative"
            line_numbers.append(self.v.line(base_label, direction, text=text,
                                            component=component,
                                            vector=f"v_{construction.point}{side.base}",
                                            group=group.index))
        self.v.intersect(*line_numbers, x_label, text=f"{x_label}: {equation}",
                         group_name=group.name, group=group.index, angle=self.angle)
        # read the relative velocities and the angular velocities
        omegas: dict[str, float] = {}
        rel: list[float] = []
        for _index, side in enumerate(sides):
            base_label = self.image_at(self.v, self.vimages, side.base_link,
                                       side.position[0], self._base_label(side, self.v))
            segment = self.v.points[x_label] - self.v.points[base_label]
            direction = side.direction[0]
            sign = sense(segment, direction)
            if side.rotation:
                radius = x - side.position[0]
                length_mm = self.radius_mm(side.position[0], x)
                omega = self.v.read(
                    base_label, x_label, quantity=f"omega_{side.link}", sign=sign,
                    factor=mu_v / (length_mm * mu_l))
                omegas[side.link] = omega
                rel.append(sign * self.v.round(norm(segment),
                                               Segment("velocity", "read", "relative")))
                del radius
            else:
                value = self.v.read(base_label, x_label,
                                    quantity=f"v_{construction.point}{side.base}",
                                    sign=sign, factor=mu_v)
                rel.append(value / mu_v)
                # the side draws X's link relative to the carrier; the pair's reading wants
                # `link` relative to `along`, the reverse when the carrier is the pair's `link`
                self.sliding_sides[side.slide.key] = {
                    "v": (base_label, x_label), "reverse": side.link == side.slide.link}
        self.rel_velocity[(group.index, 0)] = rel[0]
        self.rel_velocity[(group.index, 1)] = rel[1]
        follow_tied(construction.tied, omegas, lambda link: self.readings.get(f"omega_{link}"))
        for link in group.links:
            self.readings[f"omega_{link}"] = omegas[link]
            name, ref, known = construction.reference(link)
            ref_label = (self.image_at(self.v, self.vimages, known, ref[0],
                                       self.label(name, self.v)) if known else x_label)
            self.vimages[link] = LinkImage(ref[0], self.v.points[ref_label], ref_label,
                                           omegas[link])
        for link in group.links:
            self.image_points(link, self.v, self.vimages[link], _velocity_offset, mu_v)

    def acceleration_group(self, construction: Construction) -> None:
        group = construction.group
        mu_v, mu_a, mu_l = self.scales.mu_v, self.scales.mu_a, self.scales.mu_l
        x_label = self.label(construction.point, self.a)
        x = construction.position[0]
        point = construction.point
        line_numbers = []
        normals: dict[int, str] = {}
        for index, side in enumerate(construction.sides):
            base = side.position[0]
            base_label = self.image_at(self.a, self.aimages, side.base_link, base,
                                       self._base_label(side, self.a))
            direction = side.direction[0]
            relative = self.rel_velocity[(group.index, index)]  # signed, mm on the v-plan
            if side.rotation:
                radius = x - base
                length_mm = self.radius_mm(base, x)
                magnitude = (relative ** 2) * mu_v ** 2 / (length_mm * mu_l * mu_a)
                centre = side.base.partition("@")[0]
                x_name = point.partition("@")[0]
                n_label = (f"n_{point}" if "@" in point else f"n_{x_name}{centre}")
                # the components of X (B@lever: B₃) about the centre, aⁿ_B₃O₂ and aᵗ_B₃O₂;
                # the segment they are measured on is the position plan's BO₂
                self.a.lay_off(
                    base_label, n_label, _times(-magnitude, unit(radius)),
                    component="normal", vector=f"aⁿ_{point}{centre}", group=group.index,
                    text=f"aⁿ_{point}{centre} from {base_label}: ({base_label}{n_label}) = "
                         f"(v-plan segment)²·μv²/(({x_name}{centre})·μl·μa), from "
                         f"{x_name} towards {centre}")
                normals[index] = n_label
                line_numbers.append(self.a.line(
                    n_label, direction, component="tangential", group=group.index,
                    vector=f"aᵗ_{point}{centre}",
                    text=f"through {n_label}: aᵗ_{point}{centre} ⟂ {x_name}{centre}"))
            else:
                carrier = side.link
                omega_c = self.readings[f"omega_{carrier}"]
                multi = sum(not s.rotation for s in construction.sides) > 1
                k_label = f"k{index + 1}_{point}" if multi else f"k_{point}"
                coriolis = _times(2 * omega_c * relative * mu_v, perp(direction)) / mu_a
                # X relative to the side's base, as the velocity equation names it: v_B₃B
                # there, aᵏ_B₃B and aʳ_B₃B here (each side its own relative motion)
                relative_name = f"{point}{side.base}"
                self.a.lay_off(
                    base_label, k_label, coriolis, component="coriolis", group=group.index,
                    vector=f"aᵏ_{relative_name}",
                    text=(f"aᵏ = 2·ω_{carrier}·v_rel from {base_label}, v_rel turned 90° in the "
                          f"sense of ω_{carrier}" if np.any(omega_c) else
                          f"aᵏ = 0: {carrier} does not turn; {k_label} coincides with "
                          f"{base_label}"))
                normals[index] = k_label
                self.sliding_sides[side.slide.key]["a"] = (base_label, k_label, x_label)
                line_numbers.append(self.a.line(
                    k_label, direction, component="relative", group=group.index,
                    vector=f"aʳ_{relative_name}",
                    text=f"through {k_label}: aʳ_{relative_name} (relative) along the guide "
                         f"of {side.slide.key}"))
        self.a.intersect(*line_numbers, x_label,
                         text=f"{x_label}: a_{point} from both vector equations",
                         group_name=group.name, group=group.index, angle=self.angle)
        epsilons: dict[str, float] = {}
        for index, side in enumerate(construction.sides):
            start = normals[index]
            segment = self.a.points[x_label] - self.a.points[start]
            direction = side.direction[0]
            sign = sense(segment, direction)
            if side.rotation:
                length_mm = self.radius_mm(side.position[0], x)
                epsilons[side.link] = self.a.read(
                    start, x_label, quantity=f"epsilon_{side.link}", sign=sign,
                    factor=mu_a / (length_mm * mu_l))
            else:
                self.a.read(start, x_label, quantity=f"a_rel_{point}{side.base}", sign=sign,
                            factor=mu_a)
        follow_tied(construction.tied, epsilons,
                    lambda link: self.readings.get(f"epsilon_{link}"))
        for link in group.links:
            self.readings[f"epsilon_{link}"] = epsilons[link]
            omega = self.readings[f"omega_{link}"]
            name, ref, known = construction.reference(link)
            ref_label = (self.image_at(self.a, self.aimages, known, ref[0],
                                       self.label(name, self.a)) if known else x_label)
            self.aimages[link] = LinkImage(ref[0], self.a.points[ref_label], ref_label, omega,
                                           epsilons[link])
        for link in group.links:
            self.image_points(link, self.a, self.aimages[link], _acceleration_offset, mu_a)


def _position_plan(exercise: Exercise, motion: Motion, scales: Scales, angle: float
                   ) -> PositionPlan:
    mechanism = exercise.mechanism
    points: dict[str, tuple[float, float]] = {}
    links: dict[str, tuple[str, ...]] = {}
    for name, link in mechanism.links.items():
        if name not in motion.links:
            continue
        links[name] = tuple(link.points)
        state = motion.links[name]
        for point, local in link.points.items():
            if point not in points:
                xy = state.place(local)[0] / scales.mu_l
                points[point] = (float(xy[0]), float(xy[1]))
    pivots = tuple(p for p in mechanism.links[FRAME].points
                   if len(mechanism.links_with_point(p)) > 1)
    slides = []
    for slide in mechanism.slides:
        if slide.link not in motion.links or slide.along not in motion.links:
            continue
        guide = motion.links[slide.along]
        through = guide.place(mechanism.local(slide.along, slide.through))[0] / scales.mu_l
        direction = math.degrees(float(guide.theta[0]) + slide.direction_rad)
        slides.append({"key": slide.key, "link": slide.link, "along": slide.along,
                       "through": slide.through, "point": slide.point,
                       "through_mm": [float(through[0]), float(through[1])],
                       "direction_deg": direction})
    drive = mechanism.drive
    return PositionPlan(scales.mu_l, points, links, pivots, tuple(slides),
                        (drive.link, drive.pivot, drive.omega), {}, angle,
                        shown_title(mechanism.title),
                        course_numbers(mechanism))


def _curvature_readings(emulator: _Emulator, point: str,
                        position_plan: PositionPlan | None) -> None:
    """ρ = (pd)²·μv² / ((πn_D)·μa): project πd on the normal to pd (Abduvaliev &
    Abduxoshimov, with their ρ formula's slip corrected)."""
    v, a, scales = emulator.v, emulator.a, emulator.scales
    name = point.partition("@")[0]
    link, position = emulator.motion.locate(point)
    v_label = emulator.image_at(v, emulator.vimages, link, position[0],
                                image_label(point, v.pole))
    a_label = emulator.image_at(a, emulator.aimages, link, position[0],
                                image_label(point, a.pole))
    velocity = v.points[v_label]
    speed_mm = v.round(norm(velocity), Segment("velocity", "read", f"v_{point}"))
    if np.any(speed_mm == 0) or emulator.motion.moves_straight(point):
        return
    tangent = unit_or_zero(velocity)
    normal = perp(tangent)
    along_normal = dot(a.points[a_label], normal)
    outward = _sign(along_normal)          # the normal turned towards the centre
    normal = _times(outward, normal)
    along_normal = outward * along_normal
    n_label = f"n_{name}"
    a.points[n_label] = _times(along_normal, normal)
    if a.record:
        a.add(Step(0, "project", f"project π{a_label} on the normal to the path of {name} "
                                 f"(⟂ p{v_label}): {n_label}", start=a_label, end=n_label,
                   direction_deg=angle_deg(normal) % 180.0))
    else:
        a.count += 1
    normal_mm = a.round(along_normal, Segment("acceleration", "read", f"an_{point}"))
    if np.any(normal_mm == 0):
        return
    rho = speed_mm ** 2 * scales.mu_v ** 2 / (normal_mm * scales.mu_a)
    if a.record:
        a.add(Step(0, "read", f"ρ_{name} = (p{v_label})²·μv²/((π{n_label})·μa) = {rho:.6g} m",
                   start=a.pole, end=n_label, length_mm=normal_mm, quantity=f"rho_{point}",
                   value=rho))
    else:
        a.count += 1
    emulator.readings[f"rho_{point}"] = rho
    if position_plan is None:            # drawn without the mechanism: nothing to mark
        return
    centre = position[0] / scales.mu_l + rho / scales.mu_l * normal
    position_plan.curvature[name] = {
        "center_mm": [float(centre[0]), float(centre[1])], "rho_mm": rho / scales.mu_l,
        "tangent_deg": angle_deg(tangent) % 180.0, "normal_deg": angle_deg(normal),
        "path_mm": _path_mm(emulator.motion, point, scales.mu_l)}


def _pinned_mm(drawn_mm: float | None, direct: float | None, value: float,
               scale: float) -> float | None:
    """The written length of a reference vector, where the scale is exactly what it asks
    (``value/drawn_mm``, not rounded to the standard series and not given directly); None
    where the drawn length must follow from the scale."""
    if not drawn_mm or direct is not None or not value:
        return None
    return drawn_mm if abs(scale * drawn_mm - value) <= 1e-12 * value else None


def _path_mm(motion: Motion, point: str, mu_l: float) -> list[list[float]] | None:
    """The point's path over a full turn every 2° (mm), on the branch of the plan; None where
    the mechanism does not assemble over the whole turn. Kept for the motion's model and
    branches, so drawing the same position again (the tolerance analysis draws each plan once
    per segment) does not solve the turn again."""
    key = (motion.mechanism, tuple(sorted(motion.branches.items())), point, mu_l)
    with _PATHS_LOCK:
        if key in _PATHS:
            found = _PATHS[key]
            return None if found is None else [list(xy) for xy in found]
    angles = np.arange(0.0, 360.0, 2.0)
    try:
        path = solve(motion.mechanism, angles, stage="position", links=list(motion.links),
                     branches=motion.branches).position(point)
        found = [[float(x) / mu_l, float(y) / mu_l] for x, y in path]
    except PlanmethodError:
        found = None
    with _PATHS_LOCK:
        if len(_PATHS) >= 256:
            _PATHS.pop(next(iter(_PATHS)))
        _PATHS[key] = found
    return found


#: the paths of :func:`_path_mm`, by model, branches, point and scale (oldest dropped first)
_PATHS: dict = {}
_PATHS_LOCK = threading.Lock()


def _sliding_readings(emulator: _Emulator, key: str, acceleration: bool) -> None:
    """Read a prismatic pair's travel s off the position plan, and its sliding velocity,
    Coriolis and relative acceleration off the segments its group drew.

    Every prismatic pair a plan is drawn for is a side of a dyad (a higher group with one is
    not drawn: :class:`PlansUnavailableError`), so its group has drawn its relative motion; a
    pair no group drew is an internal error, never a reading made up here.
    """
    mechanism = emulator.mechanism
    slide = mechanism.slide(key)
    mover, guide = emulator.motion.links[slide.link], emulator.motion.links[slide.along]
    point = mover.place(mechanism.local(slide.link, slide.point))[0]
    through = guide.place(mechanism.local(slide.along, slide.through))[0]
    d = np.array([math.cos(float(guide.theta[0]) + slide.direction_rad),
                  math.sin(float(guide.theta[0]) + slide.direction_rad)])
    travel = float((point - through) @ d)
    emulator.readings[f"s_{key}"] = (math.copysign(1.0, travel)
                                     * emulator.length_mm(through, point) * emulator.scales.mu_l)
    drawn = emulator.sliding_sides.get(key)
    if drawn is None:
        raise PlanmethodError(f"internal error: no group drew the relative motion of the "
                              f"prismatic pair {key}, so its sliding velocity cannot be read "
                              "off the plans", link=slide.link)
    _read_drawn_sliding(emulator, key, d, drawn, acceleration)


def _read_drawn_sliding(emulator: _Emulator, key: str, d: np.ndarray, drawn: dict,
                        acceleration: bool) -> None:
    """Read a prismatic pair's sliding velocity, Coriolis and relative acceleration off the
    segments its group already drew (reversed when the group drew `along` relative to `link`:
    between two links that do not turn relative to each other, v_rel, aᵏ and aʳ change sign)."""
    v, a, scales = emulator.v, emulator.a, emulator.scales

    def read(sheet, start, end, quantity, factor):
        if drawn["reverse"]:
            start, end = end, start
        segment = sheet.points[end] - sheet.points[start]
        sign = sense(segment, d)
        return sheet.read(start, end, quantity=quantity, factor=factor, sign=sign)

    base, x = drawn["v"]
    emulator.readings[f"ds_{key}"] = read(v, base, x, f"ds_{key}", scales.mu_v)
    if not acceleration or "a" not in drawn:
        return
    base, k_label, x = drawn["a"]
    emulator.readings[f"coriolis_{key}"] = a.read(base, k_label, quantity=f"coriolis_{key}",
                                                  factor=scales.mu_a)
    emulator.readings[f"dds_{key}"] = read(a, k_label, x, f"dds_{key}", scales.mu_a)


def draw_plans(exercise: Exercise, angle: float | None = None, *,
               settings: PlanSettings | None = None, acceleration: bool = True,
               motion: Motion | None = None, perturb=None, scales: Scales | None = None,
               position: bool = True, turn=None, mirror=None) -> Plans:
    """Draw the position, velocity and (optionally) acceleration plans at one crank angle.

    Parameters
    ----------
    exercise
        The exercise (its ``[plan]`` table gives the scales and drafting precision).
    angle
        Crank angle (deg); default ``drive.angle``.
    settings
        Overrides the exercise's ``[plan]`` settings.
    acceleration
        Also draw the acceleration plan.
    motion
        Exact positions at that angle, if already solved (only positions are used).
    perturb
        A drafting-error model ``perturb(length_mm, segment) -> drawn_length_mm`` that
        replaces the rounding to ``precision_mm`` for every length laid off or read off
        (``segment`` is a :class:`Segment`); the calls come in construction order. Used to
        propagate reading errors into grading tolerances. Default: round to ``precision_mm``.
    scales
        The drawing scales, if already chosen for these settings (a tolerance analysis draws
        the same position many times).
    position
        Also make the position plan (the mechanism's drawing, with the paths of the points
        whose ρ is read); without it ``Plans.position`` is None and only the points of the
        velocity and acceleration plans and the readings are made (no steps).
    turn
        A direction model ``turn(direction, segment) -> direction`` for every construction
        line (``segment.action`` is ``line``, ``segment.name`` its component): a construction
        drawn with a mistake (:mod:`planmethod.grading.mistakes`). Default: as they are.
    mirror
        A similarity model ``mirror(segment) -> bool`` for every image placed by the
        similarity rule off its link's line (``segment.name`` its label, ``segment.vector``
        the link): True places it mirrored across the image of the link's line (a mistake).
        Default: as the rule says.

    Raises
    ------
    ToggleError
        If a group's two construction lines are parallel to within the drawing's precision.
    """
    settings = settings or exercise.plan
    mechanism = exercise.mechanism
    angle = float(mechanism.drive.angle if angle is None else angle)
    if motion is None:
        motion = solve(mechanism, angle, stage="position")
    scales = scales or choose_scales(exercise, settings)
    emulator = _Emulator(exercise, settings, angle, motion, scales, perturb, record=position,
                         turn=turn, mirror=mirror)
    position_plan = _position_plan(exercise, motion, scales, angle) if position else None
    emulator.drive()
    groups = [motion.structure.groups[index] for index in sorted(motion.groups)]
    for group in groups:
        _draw(emulator, motion, group, "velocity")
    if acceleration:
        for group in groups:
            _draw(emulator, motion, group, "acceleration")
    ask = exercise.ask
    # each plan drawn: its quantity's letter, its sheet, its links' images and its scale
    sheets = [("v", emulator.v, emulator.vimages, scales.mu_v)]
    if acceleration:
        sheets.append(("a", emulator.a, emulator.aimages, scales.mu_a))
    for point in _asked_points(exercise, motion):
        link, position = motion.locate(point)
        # a fixed pivot's image is the pole: placed (its links' images pass through it), but
        # not read when nobody asked for it by name (no segment to measure)
        read = not ask.everything or FRAME not in mechanism.links_with_point(point)
        for letter, sheet, images, factor in sheets:
            label = emulator.image_at(sheet, images, link, position[0],
                                      image_label(point, sheet.pole))
            if read:
                emulator.readings[f"{letter}_{point}"] = sheet.read(
                    sheet.pole, label, quantity=f"{letter}_{point}", factor=factor)
    if acceleration:
        curvature = ask.curvature if not ask.everything else ()
        for point in curvature:
            _curvature_readings(emulator, point, position_plan)
    sliding = ask.sliding if not ask.everything else tuple(
        s.key for s in mechanism.slides if s.link in motion.links and s.along in motion.links)
    for key in sliding:
        _sliding_readings(emulator, key, acceleration)
    phi = emulator.crank_symbols["φ"]
    title = shown_title(mechanism.title)     # as the figures show it
    velocity_plan = emulator.v.finish(f"{title} — velocity plan, {phi} = {angle:g}°")
    acceleration_plan = (emulator.a.finish(f"{title} — acceleration plan, "
                                           f"{phi} = {angle:g}°") if acceleration else None)
    flags = tuple(velocity_plan.flags) + (tuple(acceleration_plan.flags)
                                          if acceleration_plan else ())
    return Plans(exercise, angle, scales, position_plan, velocity_plan, acceleration_plan,
                 dict(emulator.readings), flags, motion)


def _draw(emulator: _Emulator, motion: Motion, group, plan: str) -> None:
    """Draw one group on one plan: a dyad from its two vector equations, any other group by
    its kind's plans face (:mod:`planmethod.plans.groups`)."""
    face = plan_face(group)
    if face is None:
        construction = motion.groups[group.index].construction
        if plan == "velocity":
            emulator.velocity_group(construction)
        else:
            emulator.acceleration_group(construction)
        return
    face.draw(PlanKind(plan), emulator, group)


def _asked_points(exercise: Exercise, motion: Motion) -> tuple[str, ...]:
    ask = exercise.ask
    if ask.everything:
        names = []
        for link in motion.links:
            if link == FRAME:
                continue
            names += [p for p in exercise.mechanism.links[link].points if p not in names]
        return tuple(names)
    return tuple(dict.fromkeys(ask.velocity + ask.acceleration + ask.curvature))
