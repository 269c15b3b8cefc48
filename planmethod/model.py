"""The frozen model of a mechanism: links, pairs, drive, mass properties and loads.

A :class:`Mechanism` is built once from an exercise file (see :mod:`planmethod.spec`) and never
mutated by a solve. Every value here is immutable and hashable by value: two mechanisms built
from the same file are equal and hash alike, so whatever is computed once per mechanism (its
structure, its compiled solver) is found again for an equal one. Links carry their points in
their own frames; a point name shared by two or more links is a revolute pair; a
:class:`Slide` is a prismatic pair. The fixed link is called ``frame``.

Examples
--------
>>> from planmethod.model import Link
>>> crank = Link("AB", {"A": (0.0, 0.0), "B": (0.06, 0.0)})
>>> crank.length("A", "B")
0.06
>>> again = Link("AB", {"A": [0, 0], "B": [0.06, 0]})
>>> crank == again, hash(crank) == hash(again)
(True, True)
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

FRAME = "frame"

Vector = tuple[float, float]

__all__ = [
    "FRAME",
    "Ask",
    "Course",
    "Drive",
    "Exercise",
    "FrozenMap",
    "Link",
    "Load",
    "MassProperties",
    "Mechanism",
    "Notation",
    "PlanSettings",
    "Revolute",
    "Slide",
]


class FrozenMap(Mapping):
    """An immutable mapping, equal to any mapping with the same items and hashable by value
    (nested dicts become FrozenMaps, lists tuples). Its hash is computed once.

    Examples
    --------
    >>> a = FrozenMap({"f": 0.1, "pairs": {"B": {"f": 0.2}}})
    >>> a == {"f": 0.1, "pairs": {"B": {"f": 0.2}}}, hash(a) == hash(FrozenMap(dict(a)))
    (True, True)
    """

    __slots__ = ("_data", "_hash")

    def __init__(self, data: Mapping | None = None) -> None:
        items = {} if data is None else (data._data if isinstance(data, FrozenMap) else data)
        self._data = {key: _freeze(value) for key, value in dict(items).items()}
        self._hash: int | None = None

    def __getitem__(self, key):
        return self._data[key]

    def __contains__(self, key) -> bool:
        return key in self._data

    def __iter__(self) -> Iterator:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, FrozenMap):
            return self._data == other._data
        if isinstance(other, Mapping):
            return self._data == dict(other)
        return NotImplemented

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self._data.items()))
        return self._hash

    def __repr__(self) -> str:
        return f"FrozenMap({self._data!r})"


def _freeze(value: Any) -> Any:
    if isinstance(value, Mapping) and not isinstance(value, FrozenMap):
        return FrozenMap(value)
    if isinstance(value, list):
        return tuple(_freeze(item) for item in value)
    return value


def _frozen_mapping(mapping: Mapping) -> FrozenMap:
    return mapping if isinstance(mapping, FrozenMap) else FrozenMap(mapping)


@dataclass(frozen=True, slots=True)
class Link:
    """A rigid link: its name and its points in its own frame (m).

    Examples
    --------
    >>> Link("BC", {"B": (0, 0), "C": (0.18, 0)}).points["C"]
    (0.18, 0.0)
    """

    name: str
    points: Mapping[str, Vector]

    def __post_init__(self) -> None:
        object.__setattr__(
            self,
            "points",
            _frozen_mapping({k: (float(v[0]), float(v[1])) for k, v in self.points.items()}),
        )

    def length(self, first: str, second: str) -> float:
        """Distance between two points of the link (m)."""
        (x1, y1), (x2, y2) = self.points[first], self.points[second]
        return math.hypot(x2 - x1, y2 - y1)


@dataclass(frozen=True, slots=True)
class Revolute:
    """A revolute pair: the point ``point`` shared by ``links`` (two or more).

    A point shared by k links counts as k − 1 revolute pairs.
    """

    point: str
    links: tuple[str, ...]

    @property
    def key(self) -> str:
        """The report key of the pair: the point name, or ``B:AB/BC/CD`` for a multiple joint."""
        return self.point if len(self.links) == 2 else f"{self.point}:{'/'.join(self.links)}"


@dataclass(frozen=True, slots=True)
class Slide:
    """A prismatic pair: ``point`` of ``link`` moves along a line fixed in ``along``.

    The line passes through the point ``through`` of ``along`` at ``direction`` degrees in
    ``along``'s frame, and ``link``'s +x axis stays at ``direction`` in ``along``'s frame.
    ``index`` is the 1-based position of the ``[[slide]]`` table in the file (for messages).
    """

    link: str
    along: str
    through: str
    direction: float
    point: str
    index: int = 1

    @property
    def key(self) -> str:
        """The report key: ``link/along``."""
        return f"{self.link}/{self.along}"

    @property
    def direction_rad(self) -> float:
        return math.radians(self.direction)


@dataclass(frozen=True, slots=True)
class Drive:
    """The input link: it turns about ``pivot`` (shared with the frame).

    ``angle`` (deg) is the global angle of the link's own +x axis; ``omega`` (rad/s) and
    ``epsilon`` (rad/s²) are counter-clockwise positive.
    """

    link: str
    pivot: str
    angle: float
    omega: float
    epsilon: float = 0.0


@dataclass(frozen=True, slots=True)
class MassProperties:
    """Mass ``m`` (kg), moment of inertia ``J`` about the centre of mass (kg·m²) and the centre
    of mass ``S`` in the link's own frame (m)."""

    link: str
    m: float
    J: float
    S: Vector


@dataclass(frozen=True, slots=True)
class Load:
    """An external force on a point of a link (N, global axes) or a moment on a link (N·m).

    With ``oppose_velocity`` the force has magnitude |force| and acts against the velocity of
    its point, and a moment has magnitude |moment| and turns against the angular velocity of
    its link (at zero velocity it acts as given, and the report flags it).
    """

    link: str
    point: str | None = None
    force: Vector | None = None
    moment: float | None = None
    oppose_velocity: bool = False
    index: int = 1
    #: the name figures print (``P_c``, ``F_res``); default P₃ for a force and T₃ for a moment
    #: on link 3 (two of one letter on one link: P₃′, P₃″)
    name: str | None = None


@dataclass(frozen=True, slots=True)
class PlanSettings:
    """Drawing choices of the ``[plan]`` table.

    Each scale is given either as a drawn length of the drive link's scale point (``crank_mm``,
    ``velocity_mm``, ``acceleration_mm``) or directly (``mu_l`` m/mm, ``mu_v`` (m/s)/mm,
    ``mu_a`` (m/s²)/mm). ``precision_mm`` is the drafting precision (0 = exact);
    ``min_angle_deg`` the angle below which two intersected lines are flagged. A scale set by a
    drawn length is rounded to the standard series (:func:`planmethod.plans.scales.standard`)
    unless ``exact_mm`` keeps the lengths exactly as written.
    """

    crank_mm: float | None = 30.0
    velocity_mm: float | None = 30.0
    acceleration_mm: float | None = 30.0
    mu_l: float | None = None
    mu_v: float | None = None
    mu_a: float | None = None
    force_mm: float | None = None
    mu_f: float | None = None
    scale_point: str | None = None
    precision_mm: float = 0.0
    exact_mm: bool = False
    min_angle_deg: float = 1.0


@dataclass(frozen=True, slots=True)
class Ask:
    """What a scene needs (the ``[ask]`` table). With ``everything`` set (no ``[ask]`` table at
    all) every point and link is asked, and forces when masses or loads are given."""

    velocity: tuple[str, ...] = ()
    acceleration: tuple[str, ...] = ()
    omega: tuple[str, ...] = ()
    epsilon: tuple[str, ...] = ()
    curvature: tuple[str, ...] = ()
    sliding: tuple[str, ...] = ()
    forces: bool = False
    everything: bool = False

    @property
    def needs_acceleration(self) -> bool:
        return bool(self.acceleration or self.epsilon or self.curvature or self.forces
                    or self.sliding or self.everything)


#: where the frame stands in a course's numbering: first (0, the crank then 1), first as 1
#: (the crank 2, as English-language texts write θ₂, ω₂) or after the last moving link
FRAME_PLACES = (0, 1, "last")


@dataclass(frozen=True, slots=True)
class Notation:
    """How a course numbers the links (docs/notation.md): the frame's place
    (:data:`FRAME_PLACES`; default 0: the frame 0, the crank 1, then the moving links in the
    order their Assur groups attach) and explicit numbers of some links (the others take the
    free numbers in that order). Only what a person reads follows it: JSON keys and CSV
    headers keep the links' names.

    >>> Notation(), Notation("last", {"AB": 1}).numbers["AB"]
    (Notation(frame=0, numbers=FrozenMap({})), 1)
    """

    frame: int | str = 0
    numbers: Mapping[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "numbers", _frozen_mapping(self.numbers))


@dataclass(frozen=True, slots=True)
class Mechanism:
    """A planar linkage: links, revolute and prismatic pairs, the drive, masses and loads.

    ``sketch`` holds rough global positions (m) of some points that pick the assembly branch.
    Equal mechanisms hash alike (the hash is computed once, when the model is made).
    """

    title: str
    links: Mapping[str, Link]
    revolutes: tuple[Revolute, ...]
    slides: tuple[Slide, ...]
    drive: Drive
    sketch: Mapping[str, Vector] = field(default_factory=dict)
    masses: Mapping[str, MassProperties] = field(default_factory=dict)
    gravity: float | None = None
    loads: tuple[Load, ...] = ()
    friction: Mapping[str, object] = field(default_factory=dict)
    #: how the course numbers the links (printed names only; equal mechanisms under two
    #: notations hash alike)
    notation: Notation = field(default_factory=Notation)
    _hash: int = field(default=0, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "links", _frozen_mapping(self.links))
        object.__setattr__(self, "sketch", _frozen_mapping(
            {name: (float(x), float(y)) for name, (x, y) in self.sketch.items()}))
        object.__setattr__(self, "masses", _frozen_mapping(self.masses))
        object.__setattr__(self, "friction", _frozen_mapping(self.friction))
        object.__setattr__(self, "revolutes", tuple(self.revolutes))
        object.__setattr__(self, "slides", tuple(self.slides))
        object.__setattr__(self, "loads", tuple(self.loads))
        object.__setattr__(self, "_hash", hash((
            self.title, self.links, self.revolutes, self.slides, self.drive, self.sketch,
            self.masses, self.gravity, self.loads, self.friction)))

    def __hash__(self) -> int:
        return self._hash

    @property
    def moving_links(self) -> tuple[str, ...]:
        """Names of the links other than the frame, in file order."""
        return tuple(name for name in self.links if name != FRAME)

    def links_with_point(self, point: str) -> tuple[str, ...]:
        """Names of the links that carry ``point``, in file order."""
        return tuple(name for name, link in self.links.items() if point in link.points)

    def local(self, link: str, point: str) -> Vector:
        """Coordinates of ``point`` in ``link``'s own frame."""
        return self.links[link].points[point]

    def revolute_at(self, point: str) -> Revolute | None:
        """The revolute pair at ``point``, or None."""
        return next((pair for pair in self.revolutes if pair.point == point), None)

    def slide(self, key: str) -> Slide | None:
        """The prismatic pair keyed ``link/along``, or None."""
        return next((pair for pair in self.slides if pair.key == key), None)


@dataclass(frozen=True, slots=True)
class Course:
    """The course an exercise is set in (the ``[course]`` table): the language its text is
    shown in (``"ru"``; None: the run's choice, ``--lang`` or ``PLANMETHOD_LANG``, else
    English). It belongs to the exercise, not to the mechanism: an exercise set in two
    languages is one mechanism, solved once.

    >>> Course(), Course("ru").language
    (Course(language=None), 'ru')
    """

    language: str | None = None


@dataclass(frozen=True, slots=True)
class Exercise:
    """An exercise: the mechanism, the drawing choices and what is asked, and where it came from."""

    mechanism: Mechanism
    plan: PlanSettings
    ask: Ask
    source: str | None = None
    #: values a book or paper prints for this exercise (quantity → value, SI), and where
    published: Mapping[str, float] = field(default_factory=dict)
    published_source: str | None = None
    #: the course it is set in (its language)
    course: Course = field(default_factory=Course)

    def __post_init__(self) -> None:
        object.__setattr__(self, "published", _frozen_mapping(self.published))
