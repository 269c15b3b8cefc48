"""The one vocabulary: kinds of pairs and Assur groups, and the quantities a course reads off.

Every layer that names a quantity — the report's check table, the figures, the grader, the LMS
exports, the workbook — asks this module for its symbol as printed (ω with subscript BC, a_C),
its unit and the drawing scale it is read at; every layer that branches on the kind of a group
looks the kind up as a :class:`GroupKind` (never a string compared in an ``if`` chain).

Examples
--------
>>> GroupKind("RRP").type_number, GroupKind.TRIAD.group_class
(2, 3)
>>> q = quantity("omega_BC")
>>> (q.symbol, q.subscript, q.unit, q.scale)
('ω', 'BC', 'rad/s', 'mu_v')
>>> quantity("coriolis_slider/frame").text
'aᵏ_slider/frame'
>>> quantity("omega_BC").question
'angular velocity ω of BC (counter-clockwise positive)'
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

__all__ = [
    "PLAN_SCALES",
    "QUANTITY_KINDS",
    "SCALES",
    "STAGE_PLURAL",
    "AppliedKind",
    "DrawingScale",
    "EdgeKind",
    "GroupKind",
    "PairKind",
    "PlanKind",
    "Quantity",
    "QuantityKind",
    "link_numbers",
    "point_text",
    "quantity",
    "scale_text",
    "subscript",
    "symbol",
]


class PairKind(StrEnum):
    """A lower kinematic pair: revolute (``R``) or prismatic (``P``)."""

    REVOLUTE = "R"
    PRISMATIC = "P"


class PlanKind(StrEnum):
    """A plan of the graphical method: of positions (the mechanism at μl), of velocities
    (pole p, μv) or of accelerations (pole π, μa). The value keys the report's ``plans``."""

    POSITION = "position"
    VELOCITY = "velocity"
    ACCELERATION = "acceleration"


class AppliedKind(StrEnum):
    """A known force or moment on a link in kinetostatics: its weight G, the inertia force Fᵘ
    and moment Mᵘ, a given load, or a friction force or moment in a pair."""

    WEIGHT = "weight"
    INERTIA_FORCE = "inertia_force"
    INERTIA_MOMENT = "inertia_moment"
    LOAD = "load"
    FRICTION = "friction"


class EdgeKind(StrEnum):
    """An edge of a force polygon: a ``known`` force (weight, inertia, load), a ``component``
    of a reaction found from a moment or a direction (Rᵗ, Rⁿ, N), a ``reaction`` found by
    closing the polygon, or a reaction ``transmitted`` from a group solved before."""

    KNOWN = "known"
    COMPONENT = "component"
    REACTION = "reaction"
    TRANSMITTED = "transmitted"


class GroupKind(StrEnum):
    """An Assur group's kind. A dyad's kind is its pair sequence external–internal–external
    (types 1–5 of the Russian school's numbering); higher groups are ``triad`` (class III) and
    ``tetrad`` (class IV). The value is what reports print."""

    RRR = "RRR"
    RRP = "RRP"
    RPR = "RPR"
    PRP = "PRP"
    RPP = "RPP"
    TRIAD = "triad"
    TETRAD = "tetrad"
    #: the drive link with the frame (class I, the initial mechanism): not an Assur group,
    #: but the force analysis solves it last, as a group of its own
    DRIVE = "drive"

    @property
    def type_number(self) -> int | None:
        """1–5 for the dyads, None for higher groups."""
        return _TYPE_NUMBERS.get(self)

    @property
    def is_dyad(self) -> bool:
        return self in _TYPE_NUMBERS

    @property
    def group_class(self) -> int:
        """1 for the drive link, 2 for a dyad, 3 for a triad, 4 for a tetrad."""
        return 2 if self.is_dyad else _HIGHER_CLASSES[self]

    @property
    def pairs(self) -> tuple[PairKind, ...] | None:
        """A dyad's pair sequence (external, internal, external); None for higher groups."""
        return tuple(PairKind(letter) for letter in self.value) if self.is_dyad else None

    @classmethod
    def of_dyad(cls, pairs: str) -> GroupKind | None:
        """The dyad kind of a pair sequence such as ``"RRP"`` (None if it is no dyad kind:
        ``"PPR"`` is an ``RPP`` read backwards, ``"PPP"`` has no definite position)."""
        try:
            kind = cls(pairs)
        except ValueError:
            return None
        return kind if kind.is_dyad else None


_TYPE_NUMBERS = {GroupKind.RRR: 1, GroupKind.RRP: 2, GroupKind.RPR: 3, GroupKind.PRP: 4,
                 GroupKind.RPP: 5}
_HIGHER_CLASSES = {GroupKind.DRIVE: 1, GroupKind.TRIAD: 3, GroupKind.TETRAD: 4}

@dataclass(frozen=True, slots=True)
class DrawingScale:
    """A drawing scale as printed: its symbol (μv), its unit ((m/s)/mm) and the unit of what
    one millimetre of the drawing stands for (m/s: a scale bar's unit)."""

    symbol: str
    unit: str
    drawn: str


#: the drawing scales, as printed, with their units
SCALES = {"mu_l": DrawingScale("μl", "m/mm", "m"),
          "mu_v": DrawingScale("μv", "(m/s)/mm", "m/s"),
          "mu_a": DrawingScale("μa", "(m/s²)/mm", "m/s²"),
          "mu_f": DrawingScale("μF", "N/mm", "N")}

#: the scale each plan is drawn at
PLAN_SCALES = {PlanKind.POSITION: "mu_l", PlanKind.VELOCITY: "mu_v",
               PlanKind.ACCELERATION: "mu_a"}


def scale_text(name: str, value: float, digits: int = 6) -> str:
    """A scale as a drawing's header prints it, with its unit.

    >>> scale_text("mu_v", 0.2), scale_text("mu_f", 12.5)
    ('μv = 0.2 (m/s)/mm', 'μF = 12.5 N/mm')
    """
    scale = SCALES[name]
    return f"{scale.symbol} = {value:.{digits}g} {scale.unit}"


@dataclass(frozen=True, slots=True)
class QuantityKind:
    """One kind of quantity: its name prefix in reports (``v`` of ``v_C``), its symbol as
    printed, unit, what it describes, the drawing scale it is read at (None for a quantity not
    read off a plan at a scale), whether it is signed (counter-clockwise or along the guide
    positive) or a magnitude, and its subject (a ``point``, a ``link`` or a ``pair``).
    ``question`` is what a task asks, in words: ``{subject}`` is replaced by the quantity's
    subject, ``{point}`` by the subject read aloud (``B@lever``: "B of link lever").
    ``panel`` titles the panel of a full-turn plot that draws this kind's curves (empty: the
    kind has no panel of its own)."""

    prefix: str
    symbol: str
    unit: str
    description: str
    scale: str | None
    signed: bool
    subject: str
    question: str = ""
    panel: str = ""


#: every quantity a check table, a key or a sweep names, by prefix
QUANTITY_KINDS: dict[str, QuantityKind] = {kind.prefix: kind for kind in (
    QuantityKind("v", "v", "m/s", "speed of a point", "mu_v", False, "point",
                 "speed of {point}, |v_{subject}|", "speed of points |v|"),
    QuantityKind("a", "a", "m/s²", "acceleration of a point", "mu_a", False, "point",
                 "magnitude of the acceleration of {point}, |a_{subject}|",
                 "acceleration of points |a|"),
    QuantityKind("omega", "ω", "rad/s", "angular velocity of a link", "mu_v", True, "link",
                 "angular velocity ω of {subject} (counter-clockwise positive)",
                 "angular velocity ω of links"),
    QuantityKind("epsilon", "ε", "rad/s²", "angular acceleration of a link", "mu_a", True,
                 "link", "angular acceleration ε of {subject} (counter-clockwise positive)",
                 "angular acceleration ε of links"),
    QuantityKind("s", "s", "m", "travel of a prismatic pair", "mu_l", True, "pair",
                 "travel s of the slide {subject}", "travel s of prismatic pairs"),
    QuantityKind("ds", "ds/dt", "m/s", "sliding velocity of a prismatic pair", "mu_v", True,
                 "pair", "sliding velocity of {subject} (along the guide)",
                 "sliding velocity ds/dt"),
    QuantityKind("dds", "d²s/dt²", "m/s²", "sliding acceleration of a prismatic pair", "mu_a",
                 True, "pair", "sliding (relative) acceleration of {subject} (along the guide)",
                 "sliding acceleration d²s/dt²"),
    QuantityKind("rho", "ρ", "m", "radius of curvature of a point's path", "mu_l", False,
                 "point", "radius of curvature ρ of the path of {point}",
                 "radius of curvature ρ"),
    QuantityKind("coriolis", "aᵏ", "m/s²", "Coriolis acceleration of a prismatic pair",
                 "mu_a", False, "pair", "magnitude of the Coriolis acceleration of {subject}"),
)}


@dataclass(frozen=True, slots=True)
class Quantity:
    """A named quantity such as ``omega_BC``: its kind and subject (``BC``)."""

    name: str
    kind: QuantityKind
    subject: str

    @property
    def symbol(self) -> str:
        return self.kind.symbol

    @property
    def subscript(self) -> str:
        return self.subject

    @property
    def unit(self) -> str:
        return self.kind.unit

    @property
    def scale(self) -> str | None:
        return self.kind.scale

    @property
    def text(self) -> str:
        """The symbol in plain text, subscript after an underscore (``ω_BC``)."""
        return f"{self.kind.symbol}_{self.subject}"

    @property
    def signed(self) -> bool:
        return self.kind.signed

    @property
    def question(self) -> str:
        """What a task asks for this quantity, in words (``speed of B of link lever,
        |v_B@lever|``)."""
        return self.kind.question.format(subject=self.subject,
                                         point=self.subject.replace("@", " of link "))


def quantity(name: str) -> Quantity:
    """The quantity named ``name`` (``v_C``, ``omega_BC``, ``dds_slider/frame``).

    Raises
    ------
    KeyError
        If the prefix names no known quantity.
    """
    prefix, _, subject = name.partition("_")
    if prefix not in QUANTITY_KINDS or not subject:
        raise KeyError(name)
    return Quantity(name, QUANTITY_KINDS[prefix], subject)

#: a kinematic stage's quantities as a sentence names them ("its velocities would …")
STAGE_PLURAL: dict[str, str] = {"position": "positions", "velocity": "velocities",
                                "acceleration": "accelerations"}


_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_SUBSCRIPT_TEXT = str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉‚")


def subscript(text: str) -> str:
    """Digits (and a comma) as Unicode subscripts, as a course sets a link's number.

    >>> "R" + subscript("12"), "R" + subscript("1,12")
    ('R₁₂', 'R₁‚₁₂')
    """
    return text.translate(_SUBSCRIPT_TEXT)


def point_text(name: str) -> str:
    """A point's name in plain text, its digits as subscripts (``O1`` → ``O₁``).

    >>> point_text("O1"), point_text("C")
    ('O₁', 'C')
    """
    head = name.rstrip("0123456789")
    return head + subscript(name[len(head):])


def link_numbers(links: list[str] | tuple[str, ...], drive: str,
                 frame: str = "frame") -> dict[str, int]:
    """The links numbered as a course numbers them: the frame 1, the crank (drive link) 2, the
    others 3, 4, … in the order the exercise lists them.

    Examples
    --------
    >>> link_numbers(["frame", "AB", "BC", "CD"], "AB")
    {'frame': 1, 'AB': 2, 'BC': 3, 'CD': 4}
    """
    order = [frame, drive] + [name for name in links if name not in (frame, drive)]
    return {name: number for number, name in enumerate(order, start=1)}


def symbol(name: str, numbers: dict[str, int] | None = None) -> str:
    """A quantity as a course writes it: a link's by the link's number as a subscript (ω₃,
    ε₄), a point's with the point's name (v_C, a_C, ρ_D), a pair's with its name; a name that is
    no quantity is returned as it is.

    Examples
    --------
    >>> symbol("omega_BC", {"frame": 1, "AB": 2, "BC": 3}), symbol("a_C"), symbol("rho_D")
    ('ω₃', 'a_C', 'ρ_D')
    """
    try:
        found = quantity(name)
    except KeyError:
        return name
    kind, subject = found.kind, found.subject
    if kind.subject == "link" and numbers and subject in numbers:
        return f"{kind.symbol}{str(numbers[subject]).translate(_SUBSCRIPT)}"
    if kind.subject == "pair":
        return f"{kind.symbol} ({subject})"
    return f"{kind.symbol}_{subject}"
