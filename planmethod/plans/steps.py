"""The construction steps of a plan as data: one small frozen value per action.

A plan keeps the steps a student draws, in order (docs/json-report.md, "Plan steps"). Each is
a value of the action it takes — :class:`Pole`, :class:`LayOff` (a known vector laid off from a
plan point), :class:`Coincide` (a point that coincides with another), :class:`Line` (a line of
known direction through a plan point), :class:`Intersect` (where two lines meet),
:class:`Similarity` (a point placed by the similarity rule), :class:`Project` (a foot on a
path's normal), :class:`Read` and :class:`ReadRadius` (a segment read off) — with typed fields:
plan labels (``b``, ``b@lever``, ``n_CB``), link names, the vector drawn (:class:`VectorName`),
lengths in mm and values in SI. A step that lays off a vector, draws a line or finds a point
also says why, as a value: what the known vector is (:class:`CrankVelocity`,
:class:`NormalComponent`, :class:`CoriolisComponent`, …), what gives the line its direction
(:class:`Across`, :class:`Guide`, :class:`SpecialSide`, :class:`SpecialGuide`), which equation
the point found solves (:class:`VelocityEquation`, :class:`BothEquations`, …). A step holds no
sentence: the render layer writes each from its message template
(:mod:`planmethod.render.plan_words`), and a step's JSON (:meth:`Step.as_dict`, without its
sentence) keeps the report's names.

How the emulator keeps what it draws is a strategy it is given: :class:`KeepSteps` keeps every
step, :class:`DropSteps` keeps none (a tolerance analysis wants only the points and readings);
either way the steps are numbered, so that an intersection names the lines it meets.

Examples
--------
>>> step = Read(number=9, start="b", end="b@lever", length_mm=12.3, quantity="v_B@leverB",
...             value=-0.31, relative=VectorName("v", "B@lever", "B"))
>>> step.action, step.as_dict()["quantity"], str(step.relative)
('read', 'v_B@leverB', 'v_B@leverB')
>>> kept, dropped = KeepSteps(), DropSteps()
>>> for recorder in (kept, dropped):
...     recorder.record(lambda: Pole(number=1, end="p"))
>>> kept.steps, dropped.steps
((Pole(number=1, end='p', start=None),), ())
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple, Protocol

from ..vocabulary import PlanKind

__all__ = [
    "Across",
    "BothEquations",
    "BothSides",
    "Coincide",
    "CoriolisComponent",
    "CrankNormal",
    "CrankTangential",
    "CrankVelocity",
    "DropSteps",
    "FixedPivot",
    "FrameImage",
    "Guide",
    "Intersect",
    "KeepSteps",
    "LayOff",
    "Line",
    "NormalComponent",
    "NormalOfSegment",
    "Pole",
    "PoorIntersection",
    "Project",
    "Read",
    "ReadRadius",
    "Similarity",
    "SpecialAcceleration",
    "SpecialGuide",
    "SpecialPoint",
    "SpecialSide",
    "Step",
    "StepRecorder",
    "VectorName",
    "VelocityEquation",
]

#: a step's fields as the JSON report writes them, in this order (after ``number``, ``action``
#: and the sentence); a field a step does not have, or has empty, is left out
JSON_FIELDS = ("start", "end", "direction_deg", "length_mm", "component", "vector", "group",
               "lines", "angle_deg", "flagged", "references", "quantity", "value")


class VectorName(NamedTuple):
    """The identity of a vector drawn on a plan (a small frozen value, as every reason below
    is): its ``symbol`` (``v``, ``a``, ``aⁿ``, ``aᵗ``, ``aᵏ``, ``aʳ``), the ``point`` whose
    motion it is (a report name: ``B@lever`` is B taken as a point of the lever) and, for a
    relative motion, the ``base`` point it is relative to. ``str()`` is its report name
    (``aⁿ_B@leverO2``).

    >>> str(VectorName("aⁿ", "B@lever", "O2")), str(VectorName("v", "C"))
    ('aⁿ_B@leverO2', 'v_C')
    """

    symbol: str
    point: str
    base: str = ""

    def __str__(self) -> str:
        return f"{self.symbol}_{self.point}{self.base}"


# -- why a vector is known, why a line has its direction, what an intersection solves -----------
class CrankVelocity(NamedTuple):
    """The velocity of the crank ``link``'s scale ``point``, ω·l ⟂ ``pivot``–``point``, of
    magnitude ``speed`` (m/s)."""

    link: str
    pivot: str
    point: str
    speed: float


class CrankNormal(NamedTuple):
    """The crank pin's normal acceleration ω²·l from ``point`` towards ``pivot``, of magnitude
    ``magnitude`` (m/s²); ``whole`` where it is the pin's whole acceleration (ε = 0)."""

    link: str
    pivot: str
    point: str
    magnitude: float
    whole: bool


class CrankTangential(NamedTuple):
    """The crank pin's tangential acceleration ε·l ⟂ ``pivot``–``point`` (m/s²)."""

    link: str
    pivot: str
    point: str
    magnitude: float


class NormalComponent(NamedTuple):
    """A dyad's normal component, (v-plan segment)²·μv²/(length·μl·μa), from ``point`` towards
    ``centre`` (their names on the position plan)."""

    point: str
    centre: str


class NormalOfSegment(NamedTuple):
    """A triad's normal component from the velocity-plan segment ``first``–``second``, towards
    the centre."""

    first: str
    second: str


class CoriolisComponent(NamedTuple):
    """The Coriolis component 2ω·v_rel of a point sliding on ``carrier``; zero where the
    carrier does not ``turn``."""

    carrier: str
    turns: bool


class FixedPivot(NamedTuple):
    """The image of the fixed ``point`` is the pole."""

    point: str


class FrameImage(NamedTuple):
    """The image of a point of the frame is the pole: the frame does not move."""


class Across(NamedTuple):
    """A line ⟂ the segment ``first``–``second`` of the position plan (report names)."""

    first: str
    second: str


class Guide(NamedTuple):
    """A line along the guide of the prismatic pair of ``link`` on ``along``."""

    link: str
    along: str


class SpecialSide(NamedTuple):
    """A line through Assur's special point's side ⟂ the side link ``outer``–``inner`` (the
    velocity of S* relative to ``outer``; on the acceleration plan both tangential
    components)."""

    outer: str
    inner: str


class SpecialGuide(NamedTuple):
    """A line through Assur's special point's side along the guide of the prismatic pair of
    ``link`` on ``along`` (S* lies on the normal to the guide through the pin ``pin``; on the
    acceleration plan the relative and the tangential components, both along the guide)."""

    link: str
    along: str
    pin: str


class VelocityEquation(NamedTuple):
    """The point ``point`` found from v_X = v_base + v_X,base for each of ``bases``."""

    point: str
    bases: tuple[str, ...]


class BothEquations(NamedTuple):
    """``point``'s acceleration found from both vector equations of its dyad."""

    point: str


class SpecialPoint(NamedTuple):
    """Assur's special point S* of the triad's ``central`` link, at (``x``, ``y``) m, where the
    lines of the side links ``first`` and ``second`` meet."""

    x: float
    y: float
    central: str
    first: str
    second: str


class SpecialAcceleration(NamedTuple):
    """S*'s acceleration found from the two sides through it."""


class BothSides(NamedTuple):
    """The triad's third inner pin ``point`` found from both of its sides."""

    point: str


#: what a laid-off (or coinciding) vector is
Known = (CrankVelocity | CrankNormal | CrankTangential | NormalComponent | NormalOfSegment
         | CoriolisComponent | FixedPivot | FrameImage)
#: what gives a construction line its direction
Direction = Across | Guide | SpecialSide | SpecialGuide
#: what an intersection solves
Solves = VelocityEquation | BothEquations | SpecialPoint | SpecialAcceleration | BothSides


# -- the steps --------------------------------------------------------------------------------
# Each step is a NamedTuple (a frozen value that costs next to nothing to define: the package
# loads on every command), made by keywords; ``action`` is its class's constant and ``as_dict``
# the one writer of its JSON. Every step has ``number``, ``start`` and ``end`` (None where it
# has no such point), so that a reader of any step finds the plan points it names.
def _as_dict(step: Step) -> dict:
    """The step as the JSON report writes it, without its sentence: ``number``, ``action``,
    then the fields it has (:data:`JSON_FIELDS`; a similarity's link as ``vector``), report
    names as text."""
    out: dict = {"number": step.number, "action": step.action}
    renamed = _RENAMED.get(type(step), {})
    for key in JSON_FIELDS:
        value = getattr(step, renamed.get(key, key), None)
        if value is None or value == () or value is False:
            continue
        if isinstance(value, VectorName):
            value = str(value)
        elif isinstance(value, tuple):
            value = list(value)
        out[key] = value
    return out


class Pole(NamedTuple):
    """The pole (``end``)."""

    number: int
    end: str
    start: None = None

    action = "pole"
    as_dict = _as_dict


class LayOff(NamedTuple):
    """A known vector laid off from ``start`` to ``end``: its direction (deg), its drawn length
    (mm), its ``component`` (``absolute``, ``normal``, ``tangential``, ``coriolis``), the
    ``vector`` and the ``group`` index (None for the drive), and what it is (``known``)."""

    number: int
    start: str
    end: str
    direction_deg: float
    length_mm: float
    component: str
    vector: VectorName
    known: Known
    group: int | None = None

    action = "lay_off"
    as_dict = _as_dict


class Coincide(NamedTuple):
    """``end`` coincides with ``start``: a zero vector laid off (its ``component``,
    ``vector``, ``group``) or a fixed point's image at the pole; ``known`` says which."""

    number: int
    start: str
    end: str
    known: Known
    length_mm: float = 0.0
    component: str | None = None
    vector: VectorName | None = None
    group: int | None = None

    action = "coincide"
    as_dict = _as_dict


class Line(NamedTuple):
    """A construction line through ``start`` at ``direction_deg`` (0–180), the line of the
    ``vector``'s ``component``; ``along`` says what gives it its direction."""

    number: int
    start: str
    direction_deg: float
    component: str
    vector: VectorName
    along: Direction
    group: int | None = None
    end: None = None

    action = "line"
    as_dict = _as_dict


class Intersect(NamedTuple):
    """``end`` where the lines of steps ``lines`` meet at ``angle_deg``; ``flagged`` where that
    is below the plan's least angle; ``solves`` says what the point found is."""

    number: int
    end: str
    lines: tuple[int, int]
    angle_deg: float
    solves: Solves
    flagged: bool = False
    group: int | None = None
    start: None = None

    action = "intersect"
    as_dict = _as_dict


class Similarity(NamedTuple):
    """``end`` placed by the similarity rule on the image of ``link`` from its reference image
    ``start`` (``references``), ``length_mm`` from it at ``direction_deg`` (None: on it)."""

    number: int
    start: str
    end: str
    length_mm: float
    link: str
    direction_deg: float | None = None
    references: tuple[str, ...] = ()

    action = "similarity"
    as_dict = _as_dict


class Project(NamedTuple):
    """``end`` is the foot of ``start`` (the acceleration image of ``point``) on the normal
    to ``point``'s path, the line through the pole at ``direction_deg`` ⟂ its velocity image
    ``speed``."""

    number: int
    start: str
    end: str
    direction_deg: float
    point: str
    speed: str

    action = "project"
    as_dict = _as_dict


class Read(NamedTuple):
    """The segment ``start``–``end`` read off as ``length_mm``, giving ``quantity`` (its report
    name) = ``value`` (SI); a relative motion read off names its vector (``relative``)."""

    number: int
    start: str
    end: str
    length_mm: float
    quantity: str
    value: float
    relative: VectorName | None = None

    action = "read"
    as_dict = _as_dict


class ReadRadius(NamedTuple):
    """ρ of ``point``'s path read off: (p ``speed``)²·μv²/((π ``end``)·μa), the normal
    component's segment from the pole ``start`` to ``end`` being ``length_mm``."""

    number: int
    start: str
    end: str
    length_mm: float
    quantity: str
    value: float
    point: str
    speed: str

    action = "read"
    as_dict = _as_dict


#: a construction step: one of these (each with ``number``, ``start``, ``end``, ``action``
#: and ``as_dict``)
Step = Pole | LayOff | Coincide | Line | Intersect | Similarity | Project | Read | ReadRadius

#: a step's field that the JSON report names otherwise: {step type: {JSON key: field}}
_RENAMED: dict[type, dict[str, str]] = {Similarity: {"vector": "link"}}


# -- flags ------------------------------------------------------------------------------------
class PoorIntersection(NamedTuple):
    """A plan's flag: on the ``plan``, the lines of the group of ``links`` meet at
    ``angle_deg``, below the least angle ``limit_deg``, so that ``point`` (a plan label) is
    poorly defined."""

    plan: PlanKind
    links: tuple[str, ...]
    angle_deg: float
    limit_deg: float
    point: str


# -- recording --------------------------------------------------------------------------------
class StepRecorder(Protocol):
    """How a plan keeps its steps: ``record`` is given each step, in order, as the function
    that makes it — a recorder that keeps it makes it then, one that drops it never does (a
    tolerance analysis, whose copies of a drawing hold one length per copy, makes none);
    ``steps`` are those kept."""

    def record(self, make: Callable[[], Step]) -> None: ...

    @property
    def steps(self) -> tuple[Step, ...]: ...


class KeepSteps:
    """Keeps every step (the plans a person reads)."""

    def __init__(self) -> None:
        self._kept: list[Step] = []

    def record(self, make: Callable[[], Step]) -> None:
        self._kept.append(make())

    @property
    def steps(self) -> tuple[Step, ...]:
        return tuple(self._kept)


class DropSteps:
    """Keeps no step (only the plan's points and readings are wanted)."""

    def record(self, make: Callable[[], Step]) -> None:
        """Drop the step ``make`` would make, unmade."""

    @property
    def steps(self) -> tuple[Step, ...]:
        return ()
