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

Each plan keeps its construction steps as typed values (:mod:`planmethod.plans.steps`), kept or
dropped by the recorder it is drawn with; their sentences are written in the render layer
(:mod:`planmethod.render.plan_words`).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> plans = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
>>> round(plans.readings["v_C"], 4), round(plans.omega("BC"), 3)
(5.2716, -24.254)
>>> [round(x, 3) for x in plans.velocity.points_mm["b"]]
[-21.213, 21.213]
>>> [step.action for step in plans.velocity.steps[:3]]
['pole', 'coincide', 'lay_off']
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import PlanmethodError, SpecError, ToggleError
from ..kinematics import Motion, solve
from ..kinematics.groups.checks import TOGGLE_SINE
from ..kinematics.groups.dyad import Construction, Side, follow_tied
from ..model import FRAME, Exercise, PlanSettings
from ..numbering import course_numbers
from ..structure import AssurGroup
from ..vectors import angle_deg, cross, dot, norm, perp, unit, unit_or_zero
from ..vocabulary import (
    PlanKind,
    shown_title,
    slide_points,
)
from ..words import message
from .groups import plan_face
from .groups.base import PlansUnavailableError, sense
from .scales import Scales, choose_scales
from .steps import (
    Across,
    BothEquations,
    Coincide,
    CoriolisComponent,
    CrankNormal,
    CrankTangential,
    CrankVelocity,
    Direction,
    FixedPivot,
    FrameImage,
    Guide,
    Intersect,
    KeepSteps,
    Known,
    LayOff,
    Line,
    NormalComponent,
    Pole,
    PoorIntersection,
    Project,
    Read,
    ReadRadius,
    Similarity,
    Solves,
    Step,
    StepRecorder,
    VectorName,
    VelocityEquation,
)

__all__ = [
    "LinkImage",
    "Plan",
    "Plans",
    "PlansUnavailableError",
    "PositionPlan",
    "Segment",
    "draw_plans",
    "image_label",
    "is_image",
    "position_plan",
]

#: A drawing sheet is never larger than this (mm): lines that would meet further away than
#: this, given the drafting precision, are parallel to within the drawing's precision.
SHEET_MM = 1000.0


def is_image(label: str, pole: str) -> bool:
    """Whether a plan point is the image of a mechanism's point (``b``, ``b@lever``), not a
    construction point (``n_CB``, ``k_B@lever``) or the pole.

    >>> is_image("b@lever", "p"), is_image("n_CB", "p"), is_image("p", "p")
    (True, False, False)
    """
    return "_" not in label and label != pole


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


@dataclass(frozen=True)
class Plan:
    """A velocity or acceleration plan as data: pole, scale, labelled points (mm), ordered
    typed steps (:mod:`planmethod.plans.steps`; none where drawn with :class:`~planmethod.
    plans.steps.DropSteps`), its flags (:class:`~planmethod.plans.steps.PoorIntersection`),
    the drafting precision, and what its title names: the mechanism's ``title`` (as figures
    show it), the crank ``angle`` (deg) and the crank's number ``crank``."""

    kind: str
    pole: str
    scale: float
    unit: str
    points_mm: Mapping[str, tuple[float, float]]
    steps: tuple[Step, ...]
    flags: tuple[PoorIntersection, ...] = ()
    precision_mm: float = 0.0
    title: str = ""
    #: the links' numbers in the course's notation (for printed names; not in the report)
    numbers: Mapping[str, int] = field(default_factory=dict)
    angle: float = 0.0
    crank: int = 1
    #: each prismatic pair's point by the pair's key (for printed names: v_B₃B₂)
    slides: Mapping[str, str] = field(default_factory=dict)

    def point(self, label: str) -> np.ndarray:
        return np.asarray(self.points_mm[label], dtype=float)

    def vector(self, label: str) -> np.ndarray:
        """The SI vector a plan point represents (from the pole, times the scale)."""
        return self.point(label) * self.scale


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
    ``position`` is None when drawn with ``position=False``; ``flags`` are both plans'."""

    exercise: Exercise
    angle: float
    scales: Scales
    position: PositionPlan | None
    velocity: Plan
    acceleration: Plan | None
    readings: Mapping[str, float]
    flags: tuple[PoorIntersection, ...]
    motion: Motion
    #: an exact drawing's (precision 0, no drafting-error or mistake model) lengths laid off
    #: and read off, each with its :class:`Segment`, in construction order (what a ``perturb``
    #: model would have been shown); None for any other drawing
    exact: tuple[tuple[float, Segment], ...] | None = None

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


class _Sheet:
    """One plan being drawn: its points, its steps (kept or dropped by its ``recorder``, but
    numbered either way: an intersection names the lines it meets), its flags and the drafting
    precision."""

    def __init__(self, kind: PlanKind, pole: str, scale: float, unit: str, precision: float,
                 min_angle: float, recorder: StepRecorder, perturb=None, turn=None,
                 exact: list | None = None) -> None:
        self.kind, self.pole, self.scale, self.unit = kind, pole, scale, unit
        self.precision, self.min_angle = precision, min_angle
        self.perturb = perturb
        #: an exact drawing's (length, segment) pairs, shared by its sheets (None: not kept)
        self.exact = exact
        #: a direction model ``turn(direction, segment) -> direction`` for construction lines
        #: (a construction drawn with a mistake); None draws them as they are
        self.turn = turn
        self.recorder = recorder
        self.count = 0
        self.points: dict[str, np.ndarray] = {pole: np.zeros(2)}
        self.flags: list[PoorIntersection] = []
        self.lines: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        number = self.take()
        self.recorder.record(lambda: Pole(number=number, end=pole))

    def take(self) -> int:
        """The next step's number."""
        self.count += 1
        return self.count

    def round(self, length: float, segment: Segment) -> float:
        """A length as laid off or read off the drawing, ``segment`` saying which (``perturb``
        replaces the rounding, and may return one length per copy of the drawing)."""
        if self.perturb is not None:
            drawn = self.perturb(length, segment)
            return float(drawn) if np.ndim(drawn) == 0 else drawn
        if self.exact is not None:
            self.exact.append((length, segment))
        if self.precision > 0:
            return round(float(length) / self.precision) * self.precision
        return float(length)

    def lay_off(self, start: str, end: str, vector_mm: np.ndarray, *, component: str,
                vector: VectorName, known: Known, group: int | None = None) -> np.ndarray:
        """Lay off a known vector (exact direction, rounded length) from ``start``; a zero one
        makes ``end`` coincide with ``start``."""
        length = norm(vector_mm)
        drawn = self.round(length, Segment(self.kind, "lay_off", component, str(vector), group))
        direction = unit_or_zero(vector_mm, length)
        self.points[end] = self.points[start] + _times(drawn, direction)
        number = self.take()
        self.recorder.record(lambda: LayOff(
            number=number, start=start, end=end, direction_deg=angle_deg(direction),
            length_mm=drawn, component=component, vector=vector, group=group, known=known)
            if length > 0 else Coincide(number=number, start=start, end=end,
                                        component=component, vector=vector, group=group,
                                        known=known))
        return self.points[end]

    def line(self, through: str, direction: np.ndarray, *, component: str, vector: VectorName,
             along: Direction, group: int | None) -> int:
        """A construction line through a plan point, of the ``vector``'s ``component``, its
        direction given by ``along``; returns its step's number."""
        if self.turn is not None:
            direction = np.asarray(self.turn(direction, Segment(
                self.kind, "line", component, str(vector), group)), float)
        number = self.take()
        self.recorder.record(lambda: Line(
            number=number, start=through, direction_deg=angle_deg(direction) % 180.0,
            component=component, vector=vector, group=group, along=along))
        self.lines[number] = (self.points[through].copy(), direction)
        return number

    def intersect(self, first: int, second: int, end: str, *, solves: Solves,
                  group: AssurGroup, angle: float) -> np.ndarray:
        """The point ``end`` where the lines of steps ``first`` and ``second`` meet (a flag
        where they meet at less than the least angle).

        Raises
        ------
        ToggleError
            If the lines are parallel to within the drawing's precision.
        """
        (p1, e1), (p2, e2) = self.lines[first], self.lines[second]
        sine = cross(e1, e2)
        # the angle between the lines, 0…90°: atan2 keeps its digits near 90°, where asin of
        # the sine would lose half of them
        degrees = math.degrees(float(np.min(np.arctan2(np.abs(sine), np.abs(dot(e1, e2))))))
        limit = max(TOGGLE_SINE, self.precision / SHEET_MM)
        if np.min(np.abs(sine)) < limit:
            raise ToggleError(message(
                "toggle position: on the velocity plan the lines of steps {first} and {second} "
                "are parallel to within the drawing's precision ({angle:.3g}°)", first=first,
                second=second, angle=degrees) if self.kind == PlanKind.VELOCITY else message(
                "toggle position: on the acceleration plan the lines of steps {first} and "
                "{second} are parallel to within the drawing's precision ({angle:.3g}°)",
                first=first, second=second, angle=degrees),
                line_angle_deg=degrees, link=group.name, angle=angle)
        t = cross(p2 - p1, e2) / sine
        self.points[end] = p1 + _times(t, e1)
        flagged = degrees < self.min_angle
        if flagged:
            self.flags.append(PoorIntersection(self.kind, group.links, degrees, self.min_angle,
                                               end))
        number = self.take()
        self.recorder.record(lambda: Intersect(
            number=number, end=end, lines=(first, second), angle_deg=degrees, flagged=flagged,
            group=group.index, solves=solves))
        return self.points[end]

    def read(self, start: str, end: str, *, quantity: str, factor: float,
             sign: float = 1.0, relative: VectorName | None = None) -> float:
        """Read the segment start–end (rounded) and convert it: value = ±length·factor (a
        relative motion read off names its vector, ``relative``)."""
        length = self.round(norm(self.points[end] - self.points[start]),
                            Segment(self.kind, "read", quantity))
        value = sign * length * factor
        number = self.take()
        self.recorder.record(lambda: Read(
            number=number, start=start, end=end, length_mm=length, quantity=quantity,
            value=value, relative=relative))
        return value

    def coincide(self, label: str, known: Known) -> None:
        """A point whose image is the pole (``known``: a fixed pivot, the frame)."""
        self.points[label] = np.zeros(2)
        number = self.take()
        self.recorder.record(lambda: Coincide(number=number, start=self.pole, end=label,
                                              known=known))

    def place_image(self, label: str, offset_mm: np.ndarray, image: LinkImage,
                    link: str) -> None:
        """Place a point by the similarity rule from the link's reference image."""
        length = norm(offset_mm)
        drawn = self.round(length, Segment(self.kind, "similarity", label))
        direction = unit_or_zero(offset_mm, length)
        self.points[label] = image.ref_mm + _times(drawn, direction)
        number = self.take()
        self.recorder.record(lambda: Similarity(
            number=number, start=image.ref_label, end=label, references=(image.ref_label,),
            length_mm=drawn, direction_deg=angle_deg(direction) if length > 0 else None,
            link=link))

    def finish(self, title: str, angle: float, crank: int,
               numbers: Mapping[str, int], slides: Mapping[str, str] | None = None) -> Plan:
        points = {k: (v if np.ndim(v) == 2 else (float(v[0]), float(v[1])))
                  for k, v in self.points.items()}    # copies of a drawing: (N, 2) each
        return Plan(self.kind, self.pole, self.scale, self.unit, points, self.recorder.steps,
                    tuple(self.flags), self.precision, title, numbers, angle, crank,
                    dict(slides or {}))


def _velocity_offset(image: LinkImage, point: np.ndarray, mu_v: float) -> np.ndarray:
    return _times(image.omega, perp(point - image.ref)) / mu_v


def _acceleration_offset(image: LinkImage, point: np.ndarray, mu_a: float) -> np.ndarray:
    r = point - image.ref
    return (_times(image.epsilon, perp(r)) - _times(image.omega ** 2, r)) / mu_a


class _Emulator:
    """Draws the three plans of one crank angle."""

    def __init__(self, exercise: Exercise, settings: PlanSettings, angle: float,
                 motion: Motion, scales: Scales, recorder: Callable[[], StepRecorder],
                 perturb=None, turn=None, mirror=None) -> None:
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
        #: an exact drawing keeps what it lays off and reads off (:attr:`Plans.exact`)
        self.exact = ([] if precision == 0 and perturb is None and turn is None
                      and mirror is None else None)
        self.v = _Sheet(PlanKind.VELOCITY, "p", scales.mu_v, "(m/s)/mm", precision, min_angle,
                        recorder(), perturb, turn, self.exact)
        self.a = _Sheet(PlanKind.ACCELERATION, "π", scales.mu_a, "(m/s²)/mm", precision,
                        min_angle, recorder(), perturb, turn, self.exact)

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
            raise SpecError(message(
                "a precision of {precision:g} mm draws a radius of {radius:.3g} mm on the "
                "position plan as 0 mm, and a reading divides by it: the precision must be "
                "finer than the drawing", precision=self.v.precision, radius=exact),
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

    def epsilon(self, link: str) -> float:
        """A link's ε as read off the acceleration plan (its images fixed)."""
        return self.aimages[link].epsilon

    def slid(self, key: str, segments: dict[str, object]) -> None:
        """The plan labels of the segments a group drew for the prismatic pair ``key``'s
        relative motion (``v``: base, moving; ``a``: base, k, moving; ``reverse``)."""
        self.sliding_sides.setdefault(key, {}).update(segments)

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
                sheet.coincide(label, FixedPivot(name))
                continue
            position = self.similar(sheet, link, image, position, label)
            sheet.place_image(label, offset(image, position, scale), image, link)

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
            sheet.coincide(label, FrameImage())
        else:
            sheet.place_image(label, offset, image, link)
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
        """The frame's points at both poles, the crank pin's velocity and acceleration laid
        off, the crank's images and readings."""
        drive, scales = self.mechanism.drive, self.scales
        pivot = self.where(drive.link, drive.pivot)
        radius = self.where(drive.link, scales.scale_point) - pivot
        for sheet, images in ((self.v, self.vimages), (self.a, self.aimages)):
            images[FRAME] = LinkImage(np.zeros(2), np.zeros(2), sheet.pole, 0.0, 0.0)
            self.image_points(FRAME, sheet, images[FRAME], None, None)
        a_label = self.label(drive.pivot, self.v)
        self._crank_velocity(radius)
        self.vimages[drive.link] = LinkImage(pivot, self.v.points[a_label], a_label, drive.omega)
        self._crank_acceleration(radius)
        a_pivot = self.label(drive.pivot, self.a)
        self.aimages[drive.link] = LinkImage(pivot, self.a.points[a_pivot], a_pivot, drive.omega,
                                             drive.epsilon)
        self.image_points(drive.link, self.v, self.vimages[drive.link], _velocity_offset,
                          scales.mu_v)
        self.image_points(drive.link, self.a, self.aimages[drive.link], _acceleration_offset,
                          scales.mu_a)
        self.readings[f"omega_{drive.link}"] = drive.omega
        self.readings[f"epsilon_{drive.link}"] = drive.epsilon
        self.readings[f"omega_{FRAME}"] = 0.0
        self.readings[f"epsilon_{FRAME}"] = 0.0

    def _crank_velocity(self, radius: np.ndarray) -> None:
        """The crank pin's velocity ω·l ⟂ the crank, laid off from the pole p: as long as the
        scale makes it — exactly the written ``velocity_mm`` where the scale is what that
        length asks (no rounding noise), else v/μv."""
        drive, scales = self.mechanism.drive, self.scales
        point, omega = scales.scale_point, drive.omega
        v_b = omega * perp(radius)
        pinned = _pinned_mm(self.settings.velocity_mm, self.settings.mu_v,
                            float(norm(v_b)), scales.mu_v)
        b_vector = (unit(v_b) * pinned if pinned and omega else v_b / scales.mu_v)
        self.v.lay_off(self.v.pole, self.label(point, self.v), b_vector, component="absolute",
                       vector=VectorName("v", point),
                       known=CrankVelocity(drive.link, drive.pivot, point,
                                           abs(omega) * float(norm(radius))))

    def _crank_acceleration(self, radius: np.ndarray) -> None:
        """The crank pin's acceleration laid off from the pole π: its normal component ω²·l
        towards the pivot, then (ε ≠ 0) its tangential one ε·l ⟂ the crank (as long as the
        written ``acceleration_mm`` where the scale is what it asks, else a/μa)."""
        drive, scales = self.mechanism.drive, self.scales
        point, pivot, omega, epsilon = scales.scale_point, drive.pivot, drive.omega, drive.epsilon
        length = float(norm(radius))
        normal = -omega ** 2 * radius
        tangential = epsilon * perp(radius)
        total = normal + tangential
        fixed = _pinned_mm(self.settings.acceleration_mm, self.settings.mu_a,
                           float(norm(total)), scales.mu_a)
        factor = (fixed / norm(total)) if fixed and norm(total) else 1 / scales.mu_a
        b_a = self.label(point, self.a)
        whole = CrankNormal(drive.link, pivot, point, omega ** 2 * length, epsilon == 0)
        if epsilon == 0:
            self.a.lay_off(self.a.pole, b_a, normal * factor, component="normal",
                           vector=VectorName("a", point), known=whole)
            return
        n_label = f"n_{point}{pivot}"
        self.a.lay_off(self.a.pole, n_label, normal * factor, component="normal",
                       vector=VectorName("aⁿ", point, pivot), known=whole)
        self.a.lay_off(n_label, b_a, tangential * factor, component="tangential",
                       vector=VectorName("aᵗ", point, pivot),
                       known=CrankTangential(drive.link, pivot, point, abs(epsilon) * length))

    # -- groups ----------------------------------------------------------------------------------
    def _base_image(self, sheet: _Sheet, side: Side) -> str:
        """The label of a side's base point's image on ``sheet`` (placed if new)."""
        images = self.vimages if sheet is self.v else self.aimages
        return self.image_at(sheet, images, side.base_link, side.position[0],
                             self.label(side.base, sheet))

    def velocity_group(self, construction: Construction) -> None:
        """A dyad on the velocity plan: a line through each side's base image (⟂ the side's
        link, or along its guide), their intersection the image of the dyad's point X; the
        links' ω and the relative velocities read off."""
        group, point = construction.group, construction.point
        x_label = self.label(point, self.v)
        lines = [self.v.line(self._base_image(self.v, side), side.direction[0],
                             component="relative", vector=VectorName("v", point, side.base),
                             group=group.index,
                             along=Across(point, side.base) if side.rotation
                             else Guide(side.slide.link, side.slide.along))
                 for side in construction.sides]
        self.v.intersect(*lines, x_label, group=group, angle=self.angle,
                         solves=VelocityEquation(point, tuple(side.base for side in
                                                             construction.sides)))
        omegas = {}
        for index, side in enumerate(construction.sides):
            omega, relative = self._read_velocity_side(construction, side, x_label)
            if side.rotation:
                omegas[side.link] = omega
            self.rel_velocity[(group.index, index)] = relative
        self._refer_links(construction, PlanKind.VELOCITY, omegas, x_label)

    def _read_velocity_side(self, construction: Construction, side: Side, x_label: str
                            ) -> tuple[float | None, float]:
        """What one side of a dyad gives on the velocity plan: the ω of its link (a rotation
        side) or its sliding velocity (a sliding side, kept for the pair's readings), and
        its relative velocity, signed, in mm of the plan."""
        mu_v, mu_l = self.scales.mu_v, self.scales.mu_l
        point, x = construction.point, construction.position[0]
        base_label = self._base_image(self.v, side)
        segment = self.v.points[x_label] - self.v.points[base_label]
        sign = sense(segment, side.direction[0])
        if side.rotation:
            length_mm = self.radius_mm(side.position[0], x)
            omega = self.v.read(base_label, x_label, quantity=f"omega_{side.link}", sign=sign,
                                factor=mu_v / (length_mm * mu_l))
            return omega, sign * self.v.round(norm(segment),
                                              Segment("velocity", "read", "relative"))
        value = self.v.read(base_label, x_label, quantity=f"v_{point}{side.base}", sign=sign,
                            factor=mu_v, relative=VectorName("v", point, side.base))
        # the side draws X's link relative to the carrier; the pair's reading wants `link`
        # relative to `along`, the reverse when the carrier is the pair's `link`
        self.sliding_sides[side.slide.key] = {"v": (base_label, x_label),
                                              "reverse": side.link == side.slide.link}
        return None, value / mu_v

    def _refer_links(self, construction: Construction, plan: PlanKind,
                     rates: dict[str, float], x_label: str) -> None:
        """The group's links' ω (or ε) read off ``plan``, those tied to another's followed;
        each link's image referred to its pin on a known link (or to X), and its other
        points placed by similarity."""
        velocity = plan == PlanKind.VELOCITY
        sheet, images = (self.v, self.vimages) if velocity else (self.a, self.aimages)
        letter = "omega" if velocity else "epsilon"
        follow_tied(construction.tied, rates, lambda link: self.readings.get(f"{letter}_{link}"))
        links = construction.group.links
        for link in links:
            self.readings[f"{letter}_{link}"] = rates[link]
            name, ref, known = construction.reference(link)
            ref_label = (self.image_at(sheet, images, known, ref[0], self.label(name, sheet))
                         if known else x_label)
            images[link] = (
                LinkImage(ref[0], sheet.points[ref_label], ref_label, rates[link]) if velocity
                else LinkImage(ref[0], sheet.points[ref_label], ref_label,
                               self.readings[f"omega_{link}"], rates[link]))
        offset, scale = ((_velocity_offset, self.scales.mu_v) if velocity
                         else (_acceleration_offset, self.scales.mu_a))
        for link in links:
            self.image_points(link, sheet, images[link], offset, scale)

    def acceleration_group(self, construction: Construction) -> None:
        """A dyad on the acceleration plan: from each side's base image its known components
        (the normal one of a rotation side, the Coriolis one of a sliding side) laid off and
        the line of its unknown one (tangential, relative) through their end; their
        intersection the image of X; the links' ε and the relative accelerations read off."""
        group, point = construction.group, construction.point
        x_label = self.label(point, self.a)
        ends, lines = [], []
        for index, side in enumerate(construction.sides):
            draw = self._rotation_side if side.rotation else self._sliding_side
            end, line = draw(construction, index, side, x_label)
            ends.append(end)
            lines.append(line)
        self.a.intersect(*lines, x_label, group=group, angle=self.angle,
                         solves=BothEquations(point))
        epsilons: dict[str, float] = {}
        for end, side in zip(ends, construction.sides, strict=True):
            sign = sense(self.a.points[x_label] - self.a.points[end], side.direction[0])
            if side.rotation:
                length_mm = self.radius_mm(side.position[0], construction.position[0])
                epsilons[side.link] = self.a.read(
                    end, x_label, quantity=f"epsilon_{side.link}", sign=sign,
                    factor=self.scales.mu_a / (length_mm * self.scales.mu_l))
            else:
                self.a.read(end, x_label, quantity=f"a_rel_{point}{side.base}", sign=sign,
                            factor=self.scales.mu_a,
                            relative=VectorName("aʳ", point, side.base))
        self._refer_links(construction, PlanKind.ACCELERATION, epsilons, x_label)

    def _rotation_side(self, construction: Construction, index: int, side: Side,
                       x_label: str) -> tuple[str, int]:
        """A rotation side on the acceleration plan: its normal component (v-plan
        segment)²·μv²/((length)·μl·μa) laid off from the base image towards the centre, the
        line of its tangential one ⟂ the link through its end. Returns (that end, the line's
        step number)."""
        scales, group, point = self.scales, construction.group, construction.point
        base, x = side.position[0], construction.position[0]
        base_label = self._base_image(self.a, side)
        relative = self.rel_velocity[(group.index, index)]  # signed, mm on the v-plan
        length_mm = self.radius_mm(base, x)
        magnitude = relative ** 2 * scales.mu_v ** 2 / (length_mm * scales.mu_l * scales.mu_a)
        centre = side.base.partition("@")[0]
        x_name = point.partition("@")[0]
        n_label = f"n_{point}" if "@" in point else f"n_{x_name}{centre}"
        # the components of X (B@lever: B₃) about the centre, aⁿ_B₃O₂ and aᵗ_B₃O₂; the segment
        # they are measured on is the position plan's BO₂
        self.a.lay_off(base_label, n_label, _times(-magnitude, unit(x - base)),
                       component="normal", vector=VectorName("aⁿ", point, centre),
                       group=group.index, known=NormalComponent(x_name, centre))
        return n_label, self.a.line(n_label, side.direction[0], component="tangential",
                                    vector=VectorName("aᵗ", point, centre), group=group.index,
                                    along=Across(x_name, centre))

    def _sliding_side(self, construction: Construction, index: int, side: Side,
                      x_label: str) -> tuple[str, int]:
        """A sliding side on the acceleration plan: its Coriolis component 2ω·v_rel turned 90°
        in the sense of the carrier's ω laid off from the base image, the line of its relative
        one along the guide through its end (k). Returns (k, the line's step number)."""
        scales, group, point = self.scales, construction.group, construction.point
        base_label = self._base_image(self.a, side)
        direction = side.direction[0]
        relative = self.rel_velocity[(group.index, index)]  # signed, mm on the v-plan
        omega = self.readings[f"omega_{side.link}"]
        several = sum(not other.rotation for other in construction.sides) > 1
        k_label = f"k{index + 1}_{point}" if several else f"k_{point}"
        coriolis = _times(2 * omega * relative * scales.mu_v, perp(direction)) / scales.mu_a
        # X relative to the side's base, as the velocity equation names it: v_B₃B there,
        # aᵏ_B₃B and aʳ_B₃B here (each side its own relative motion)
        self.a.lay_off(base_label, k_label, coriolis, component="coriolis", group=group.index,
                       vector=VectorName("aᵏ", point, side.base),
                       known=CoriolisComponent(side.link, bool(np.any(omega))))
        self.sliding_sides[side.slide.key]["a"] = (base_label, k_label, x_label)
        return k_label, self.a.line(k_label, direction, component="relative",
                                    vector=VectorName("aʳ", point, side.base),
                                    group=group.index,
                                    along=Guide(side.slide.link, side.slide.along))


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
    projected = a.take()
    a.recorder.record(lambda: Project(number=projected, start=a_label, end=n_label,
                                      direction_deg=angle_deg(normal) % 180.0, point=name,
                                      speed=v_label))
    normal_mm = a.round(along_normal, Segment("acceleration", "read", f"an_{point}"))
    if np.any(normal_mm == 0):
        return
    rho = speed_mm ** 2 * scales.mu_v ** 2 / (normal_mm * scales.mu_a)
    read = a.take()
    a.recorder.record(lambda: ReadRadius(number=read, start=a.pole, end=n_label,
                                         length_mm=normal_mm, quantity=f"rho_{point}",
                                         value=rho, point=name, speed=v_label))
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

    Every prismatic pair a plan is drawn for is a side of a dyad or of a triad (a higher group
    of another shape is not drawn: :class:`PlansUnavailableError`), so its group has drawn its
    relative motion; a pair no group drew is an internal error, never a reading made up here.
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
        raise PlanmethodError(message(
            "internal error: no group drew the relative motion of the prismatic pair {pair}, "
            "so its sliding velocity cannot be read off the plans", pair=key), link=slide.link)
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
               position: bool = True, motion: Motion | None = None,
               scales: Scales | None = None, perturb=None, turn=None, mirror=None,
               recorder: Callable[[], StepRecorder] = KeepSteps) -> Plans:
    """Draw the position, velocity and (optionally) acceleration plans at one crank angle.

    Parameters
    ----------
    exercise
        The exercise (its ``[plan]`` table gives the scales and drafting precision).
    angle
        Crank angle (deg); default ``drive.angle``.
    settings
        Overrides the exercise's ``[plan]`` settings.
    acceleration, position
        Also draw the acceleration plan; also make the position plan (the mechanism's
        drawing, with the paths of the points whose ρ is read; else ``Plans.position`` is None).
    motion, scales
        The exact positions at that angle (only positions are used) and the drawing scales,
        if known already (a tolerance analysis draws the same position many times).
    perturb
        A drafting-error model ``perturb(length_mm, segment) -> drawn_length_mm`` replacing
        the rounding to ``precision_mm`` for every length laid off or read off (``segment`` a
        :class:`Segment`), called in construction order: reading errors propagated into
        grading tolerances.
    turn, mirror
        A construction drawn with a mistake (:mod:`planmethod.grading.mistakes`): a direction
        model ``turn(direction, segment) -> direction`` for every construction line
        (``segment.name`` its component), a similarity model ``mirror(segment) -> bool`` for
        every image placed off its link's line (True: mirrored across the image of the line).
    recorder
        Makes each plan's :class:`~planmethod.plans.steps.StepRecorder`:
        :class:`~planmethod.plans.steps.KeepSteps`, or
        :class:`~planmethod.plans.steps.DropSteps` where only points and readings are wanted.

    Raises
    ------
    ToggleError
        If a group's two construction lines are parallel to within the drawing's precision.
    """
    settings = settings or exercise.plan
    angle = float(exercise.mechanism.drive.angle if angle is None else angle)
    if motion is None:
        motion = solve(exercise.mechanism, angle, stage="position")
    scales = scales or choose_scales(exercise, settings)
    emulator = _Emulator(exercise, settings, angle, motion, scales, recorder, perturb,
                         turn=turn, mirror=mirror)
    position_plan = _position_plan(exercise, motion, scales, angle) if position else None
    return _drawn(emulator, exercise, position_plan, acceleration)


def position_plan(exercise: Exercise, angle: float | None = None, *,
                  motion: Motion | None = None) -> PositionPlan:
    """The position plan alone — the mechanism at μl — where the velocity and acceleration
    plans are not drawn (:class:`PlansUnavailableError`): its points, links and guides, at
    the scale :func:`draw_plans` would take.

    >>> from planmethod.spec import load_exercise
    >>> plan = position_plan(load_exercise("exercises/compressor_slider_crank.toml"))
    >>> plan.mu_l, [round(x, 3) for x in plan.points_mm["B"]]
    (0.002, [21.213, 21.213])
    """
    angle = float(exercise.mechanism.drive.angle if angle is None else angle)
    if motion is None:
        motion = solve(exercise.mechanism, angle, stage="position")
    return _position_plan(exercise, motion, choose_scales(exercise, exercise.plan), angle)


def _drawn(emulator: _Emulator, exercise: Exercise, position_plan: PositionPlan | None,
           acceleration: bool) -> Plans:
    """The plans ``emulator`` draws: the drive, every group on the velocity plan (then on
    the acceleration plan), the points asked about read off, the radii of curvature and the
    sliding pairs' readings."""
    mechanism, motion, angle = exercise.mechanism, emulator.motion, emulator.angle
    emulator.drive()
    groups = [motion.structure.groups[index] for index in sorted(motion.groups)]
    for plan in (PlanKind.VELOCITY, PlanKind.ACCELERATION) if acceleration else (
            PlanKind.VELOCITY,):
        for group in groups:
            _draw(emulator, motion, group, plan)
    _read_points(emulator, exercise, motion, acceleration)
    ask = exercise.ask
    if acceleration:
        for point in ask.curvature if not ask.everything else ():
            _curvature_readings(emulator, point, position_plan)
    sliding = ask.sliding if not ask.everything else tuple(
        s.key for s in mechanism.slides if s.link in motion.links and s.along in motion.links)
    for key in sliding:
        _sliding_readings(emulator, key, acceleration)
    numbers = course_numbers(mechanism)
    title, crank = shown_title(mechanism.title), numbers[mechanism.drive.link]
    slides = slide_points(mechanism)
    velocity_plan = emulator.v.finish(title, angle, crank, numbers, slides)
    acceleration_plan = (emulator.a.finish(title, angle, crank, numbers, slides)
                         if acceleration else None)
    flags = velocity_plan.flags + (acceleration_plan.flags if acceleration_plan else ())
    return Plans(exercise, angle, emulator.scales, position_plan, velocity_plan,
                 acceleration_plan, dict(emulator.readings), flags, motion,
                 None if emulator.exact is None else tuple(emulator.exact))


def _read_points(emulator: _Emulator, exercise: Exercise, motion: Motion,
                 acceleration: bool) -> None:
    """Place the image of every point asked about on each plan drawn, and read its velocity
    (and acceleration) off the pole's segment to it."""
    scales, mechanism = emulator.scales, exercise.mechanism
    # each plan drawn: its quantity's letter, its sheet, its links' images and its scale
    sheets = [("v", emulator.v, emulator.vimages, scales.mu_v)]
    if acceleration:
        sheets.append(("a", emulator.a, emulator.aimages, scales.mu_a))
    for point in _asked_points(exercise, motion):
        link, position = motion.locate(point)
        # a fixed pivot's image is the pole: placed (its links' images pass through it), but
        # not read when nobody asked for it by name (no segment to measure)
        read = not exercise.ask.everything or FRAME not in mechanism.links_with_point(point)
        for letter, sheet, images, factor in sheets:
            label = emulator.image_at(sheet, images, link, position[0],
                                      image_label(point, sheet.pole))
            if read:
                emulator.readings[f"{letter}_{point}"] = sheet.read(
                    sheet.pole, label, quantity=f"{letter}_{point}", factor=factor)


def _draw(emulator: _Emulator, motion: Motion, group, plan: PlanKind) -> None:
    """Draw one group on one plan: a dyad from its two vector equations, any other group by
    its kind's plans face (:mod:`planmethod.plans.groups`)."""
    face = plan_face(group)
    if face is None:
        construction = motion.groups[group.index].construction
        if plan == PlanKind.VELOCITY:
            emulator.velocity_group(construction)
        else:
            emulator.acceleration_group(construction)
        return
    face.draw(plan, emulator, group)


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
