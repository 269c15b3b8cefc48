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

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from enum import StrEnum

from .words.message import Message, message, template
from .words.render import render

__all__ = [
    "COLUMN_WORDS",
    "PLAN_SCALES",
    "QUANTITY_KINDS",
    "SCALES",
    "STAGE_PLURAL",
    "SYMBOL_LETTERS",
    "TITLE_SHOWN_CHARACTERS",
    "UNIT_WORDS",
    "AppliedKind",
    "DrawingScale",
    "EdgeKind",
    "GroupKind",
    "PairKind",
    "PlanKind",
    "Quantity",
    "QuantityKind",
    "column_text",
    "column_words",
    "coriolis_letter",
    "group_kind_words",
    "link_numbers",
    "link_text",
    "link_words",
    "links_text",
    "links_words",
    "numbered",
    "pair_number",
    "point_name",
    "point_text",
    "quantity",
    "question_text",
    "question_words",
    "reads_as_symbol",
    "scale_text",
    "scale_words",
    "shown_title",
    "sign_words",
    "slide_points",
    "stage_words",
    "subscript",
    "symbol",
    "turn_words",
    "unit_words",
    "xml_characters",
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
#: the higher groups' (and the drive link's) kinds in words; a dyad's kind is its pairs' letters
_KIND_WORDS = {GroupKind.TRIAD: message("triad", context="group kind"),
               GroupKind.TETRAD: message("tetrad", context="group kind"),
               GroupKind.DRIVE: message("drive", context="group kind")}


def group_kind_words(kind: GroupKind) -> Message | str:
    """An Assur group's kind as a course names it: a dyad by its pairs' letters (``RRP``), a
    higher group in words (``triad``).

    >>> group_kind_words(GroupKind.RRP), render(group_kind_words(GroupKind.TRIAD))
    ('RRP', 'triad')
    """
    return _KIND_WORDS.get(kind, kind.value)

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


#: every unit a person reads, as its own short message (``context="unit"``: a catalogue writes
#: м/с for m/s), by the unit as the code and the JSON reports name it
UNIT_WORDS: dict[str, Message] = {
    "m": message("m", context="unit"),
    "mm": message("mm", context="unit"),
    "m/s": message("m/s", context="unit"),
    "m/s²": message("m/s²", context="unit"),
    "rad": message("rad", context="unit"),
    "rad/s": message("rad/s", context="unit"),
    "rad/s²": message("rad/s²", context="unit"),
    "N": message("N", context="unit"),
    "N·m": message("N·m", context="unit"),
    "W": message("W", context="unit"),
    "kg": message("kg", context="unit"),
    "kg·m²": message("kg·m²", context="unit"),
    "m/mm": message("m/mm", context="unit"),
    "(m/s)/mm": message("(m/s)/mm", context="unit"),
    "(m/s²)/mm": message("(m/s²)/mm", context="unit"),
    "N/mm": message("N/mm", context="unit"),
}


def unit_words(unit: str) -> Message | str:
    """A unit as a person reads it, in the course's language (:data:`UNIT_WORDS`); a unit
    not in the table is shown as it is.

    >>> render(unit_words("m/s")), unit_words("furlong")
    ('m/s', 'furlong')
    """
    return UNIT_WORDS.get(unit, unit)


#: why a group takes its assembly (:attr:`Branch.reason <planmethod.kinematics.groups.base.Branch>`:
#: the sketch's nearer one, the first where the sketch cannot tell, the only one), as a person
#: reads it in a report, by the reason's machine name (the JSON report keeps that name)
BRANCH_REASON_WORDS: dict[str, Message] = {
    "sketch": message("sketch", context="branch reason"),
    "default": message("default", context="branch reason"),
    "unique": message("unique", context="branch reason"),
}


def branch_reason_words(reason: str) -> Message | str:
    """Why a group takes its assembly, in the course's language (:data:`BRANCH_REASON_WORDS`);
    a reason not in the table is shown as it is.

    >>> render(branch_reason_words("sketch")), branch_reason_words("given")
    ('sketch', 'given')
    """
    return BRANCH_REASON_WORDS.get(reason, reason)


def scale_words(name: str, value: float) -> Message:
    """A scale as a drawing's header prints it, with its unit (``μv = 0.2 (m/s)/mm``).

    >>> render(scale_words("mu_v", 0.2))
    'μv = 0.2 (m/s)/mm'
    """
    scale = SCALES[name]
    return message("{symbol} = {value:.6g} {unit}", symbol=scale.symbol, value=value,
                   unit=unit_words(scale.unit))


def scale_text(name: str, value: float) -> str:
    """:func:`scale_words` as text in the language spoken now.

    >>> scale_text("mu_v", 0.2), scale_text("mu_f", 12.5)
    ('μv = 0.2 (m/s)/mm', 'μF = 12.5 N/mm')
    """
    return render(scale_words(name, value))


@dataclass(frozen=True, slots=True)
class QuantityKind:
    """One kind of quantity: its name prefix in reports (``v`` of ``v_C``), its symbol as
    printed, unit, what it describes, the drawing scale it is read at (None for a quantity not
    read off a plan at a scale), whether it is signed (counter-clockwise or along the guide
    positive) or a magnitude, and its subject (a ``point``, a ``link`` or a ``pair``).

    ``asked`` is what a task asks, a :func:`~planmethod.words.template` whose fields
    :func:`question_words` fills: ``{point}`` (the point read aloud: ``B@lever`` is "B of
    link lever") and ``{subject}`` (its name in the symbol) for a point's quantity;
    ``{symbol}`` and ``{link}`` for a link's; ``{symbol}`` and ``{pair}`` for a pair's.
    ``asked_numbered`` is the same question with the links named by their numbers in the
    course's notation (``{number}`` and ``{name}``, and for a pair ``{along_number}`` and
    ``{along_name}``); None for a point's quantity, whose question has no link in it.
    ``plotted`` titles the panel of a full-turn plot that draws this kind's curves (None:
    the kind has no panel of its own); ``what`` says what it is. ``asked_plain`` and
    ``asked_numbered_plain`` are ``asked`` and ``asked_numbered`` without the note of which
    sense is positive, for a page whose heading says it once (a task sheet's answer table);
    None where the question has no such note.
    """

    prefix: str
    symbol: str
    unit: str
    what: Message
    scale: str | None
    signed: bool
    subject: str
    asked: Message
    asked_numbered: Message | None = None
    plotted: Message | None = None
    asked_plain: Message | None = None
    asked_numbered_plain: Message | None = None

    @property
    def description(self) -> str:
        """:attr:`what` as text in the language spoken now."""
        return render(self.what)

    @property
    def panel(self) -> str:
        """:attr:`plotted` as text in the language spoken now ("" for no panel)."""
        return render(self.plotted) if self.plotted is not None else ""


#: every quantity a check table, a key or a sweep names, by prefix
QUANTITY_KINDS: dict[str, QuantityKind] = {kind.prefix: kind for kind in (
    QuantityKind("v", "v", "m/s", message("speed of a point"), "mu_v", False, "point",
                 template("speed of {point}, |v_{subject}|"),
                 plotted=message("speed of points |v|")),
    QuantityKind("a", "a", "m/s²", message("acceleration of a point"), "mu_a", False, "point",
                 template("magnitude of the acceleration of {point}, |a_{subject}|"),
                 plotted=message("acceleration of points |a|")),
    QuantityKind("omega", "ω", "rad/s", message("angular velocity of a link"), "mu_v", True,
                 "link", template("angular velocity {symbol} of {link} (counter-clockwise "
                                  "positive)"),
                 template("angular velocity {symbol} of link {number} ({name}) "
                          "(counter-clockwise positive)"),
                 message("angular velocity ω of links"),
                 template("angular velocity {symbol} of {link}"),
                 template("angular velocity {symbol} of link {number} ({name})")),
    QuantityKind("epsilon", "ε", "rad/s²", message("angular acceleration of a link"), "mu_a",
                 True, "link", template("angular acceleration {symbol} of {link} "
                                        "(counter-clockwise positive)"),
                 template("angular acceleration {symbol} of link {number} ({name}) "
                          "(counter-clockwise positive)"),
                 message("angular acceleration ε of links"),
                 template("angular acceleration {symbol} of {link}"),
                 template("angular acceleration {symbol} of link {number} ({name})")),
    QuantityKind("s", "s", "m", message("travel of a prismatic pair"), "mu_l", True, "pair",
                 template("travel {symbol} of the slide {pair}"),
                 template("travel {symbol} of link {number} ({name}) along link "
                          "{along_number} ({along_name})"),
                 message("travel s of prismatic pairs")),
    QuantityKind("ds", "ds/dt", "m/s", message("sliding velocity of a prismatic pair"), "mu_v",
                 True, "pair", template("sliding velocity of {pair} (along the guide)"),
                 template("sliding velocity {symbol} of link {number} ({name}) along link "
                          "{along_number} ({along_name}) (along the guide)"),
                 message("sliding velocity ds/dt")),
    QuantityKind("dds", "d²s/dt²", "m/s²", message("sliding acceleration of a prismatic pair"),
                 "mu_a", True, "pair",
                 template("sliding (relative) acceleration of {pair} (along the guide)"),
                 template("sliding (relative) acceleration {symbol} of link {number} ({name}) "
                          "along link {along_number} ({along_name}) (along the guide)"),
                 message("sliding acceleration d²s/dt²")),
    QuantityKind("rho", "ρ", "m", message("radius of curvature of a point's path"), "mu_l",
                 False, "point", template("radius of curvature ρ of the path of {point}"),
                 plotted=message("radius of curvature ρ")),
    QuantityKind("coriolis", "aᵏ", "m/s²", message("Coriolis acceleration of a prismatic pair"),
                 "mu_a", False, "pair",
                 template("magnitude of the Coriolis acceleration of {pair}"),
                 template("magnitude of the Coriolis acceleration {symbol} of link {number} "
                          "({name}) along link {along_number} ({along_name})")),
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
        |v_B@lever|``): :func:`question_words` without the course's numbers, as text."""
        return render(question_words(self.name))


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

#: a kinematic stage's quantities as a sentence names them ("its velocities would …"): the
#: English words, for callers not yet speaking through :func:`stage_words`
STAGE_PLURAL: dict[str, str] = {"position": "positions", "velocity": "velocities",
                                "acceleration": "accelerations"}
_STAGE_WORDS = {"position": message("positions"), "velocity": message("velocities"),
                "acceleration": message("accelerations")}


def stage_words(stage: str) -> Message | str:
    """A kinematic stage's quantities as a sentence names them (``velocities``); a name that
    is no stage is shown as it is.

    >>> render(stage_words("velocity")), stage_words("jerk")
    ('velocities', 'jerk')
    """
    return _STAGE_WORDS.get(stage, stage)


_TURNS = {1: message("counter-clockwise", context="sense"),
          -1: message("clockwise", context="sense"),
          0: message("zero", context="sense"), None: message("undefined", context="sense")}
#: what a positive and a negative value mean, by the kind's subject: a link turns
#: counter-clockwise or clockwise; a slide's travel, sliding velocity and acceleration are
#: along or against its guide's direction
_SIGNS = {"link": (_TURNS[1], _TURNS[-1]),
          "pair": (message("positive, along the guide"),
                   message("negative, against the guide"))}
_PLAIN_SIGNS = (message("positive"), message("negative"))


def turn_words(sense: int | None) -> Message:
    """The sense of a turn in words: +1 counter-clockwise, −1 clockwise, 0 zero, None
    undefined.

    >>> render(turn_words(-1)), render(turn_words(None))
    ('clockwise', 'undefined')
    """
    return _TURNS[sense]


def sign_words(name: str) -> tuple[Message, Message]:
    """What a positive and a negative value of the quantity ``name`` mean, in words: a
    link's turn, a pair's travel along its guide, else plain positive and negative.

    >>> [render(words) for words in sign_words("ds_slider/frame")]
    ['positive, along the guide', 'negative, against the guide']
    """
    try:
        subject = quantity(name).kind.subject
    except KeyError:
        return _PLAIN_SIGNS
    return _SIGNS.get(subject, _PLAIN_SIGNS)



#: the longest title a figure, a sheet, a page or a line of a report shows (characters): a
#: longer one is cut, with an ellipsis; the shipped exercises' titles are at most 66
TITLE_SHOWN_CHARACTERS = 80
#: a control character (C0, DEL, C1): none is shown in a title, and no XML file may hold one
#: but tab, line feed and carriage return
_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f]")
#: what XML 1.0 cannot hold (C0 controls but tab, line feed and carriage return; surrogates;
#: U+FFFE and U+FFFF)
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def shown_title(title: str) -> str:
    r"""A title as every figure, sheet, page and report shows it: on one line (a control
    character, a line break among them, shown as a space) and at most
    :data:`TITLE_SHOWN_CHARACTERS` long, a longer one cut with an ellipsis. The title itself
    (what a key and a drawing are matched by) is never changed.

    Examples
    --------
    >>> shown_title("Compressor slider-crank"), shown_title("two\nlines\x1b[2J")
    ('Compressor slider-crank', 'two lines [2J')
    >>> shown_title("Mechanism " * 20)
    'Mechanism Mechanism Mechanism Mechanism Mechanism Mechanism Mechanism Mechanism…'
    """
    text = str(title)
    if len(text) > TITLE_SHOWN_CHARACTERS:
        text = text[:TITLE_SHOWN_CHARACTERS - 1].rstrip() + "…"
    return _CONTROL.sub(" ", text)


def xml_characters(text: str) -> str:
    r"""``text`` with every character XML cannot hold (a control character but tab, line feed
    and carriage return; a lone surrogate; U+FFFE, U+FFFF) replaced by U+FFFD: what an SVG or
    a Moodle quiz may be given, so that it stays a file a browser and Moodle read.

    >>> xml_characters("a\x01b\tc") == "a\ufffdb\tc"
    True
    """
    return _NOT_XML.sub("\ufffd", text) if _NOT_XML.search(text) else text


_SUBSCRIPT_TEXT = str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉‚")


def subscript(text: str) -> str:
    """Digits (and a comma) as Unicode subscripts, as a course sets a link's number.

    >>> "R" + subscript("12"), "R" + subscript("1,12")
    ('R₁₂', 'R₁‚₁₂')
    """
    return text.translate(_SUBSCRIPT_TEXT)


#: the letters a force or a moment is printed by with a link's number as its subscript (G₂,
#: P₃, T₃, R₁₂, N₀₃, Fᵘ₂, Mᵘ₂, Q₂) and the centre of mass S₂: a point named by one of them and
#: digits is printed as it is written (G1), never as a symbol (G₁, the weight of link 1)
SYMBOL_LETTERS = frozenset("FGMNPQRST")


def reads_as_symbol(name: str) -> bool:
    """Whether the point ``name`` would print like a force's symbol with its digits set as a
    subscript (``G1`` as G₁, the weight of link 1): one of :data:`SYMBOL_LETTERS`, then
    digits.

    >>> reads_as_symbol("G1"), reads_as_symbol("O1"), reads_as_symbol("G")
    (True, False, False)
    """
    head = name.rstrip("0123456789")
    return head in SYMBOL_LETTERS and len(name) > len(head)


def point_text(name: str) -> str:
    """A point's name in plain text, its digits as subscripts (``O1`` → ``O₁``); a name
    that would read as a force's symbol (:func:`reads_as_symbol`) as it is written.

    >>> point_text("O1"), point_text("C"), point_text("G1")
    ('O₁', 'C', 'G1')
    """
    if reads_as_symbol(name):
        return name
    head = name.rstrip("0123456789")
    return head + subscript(name[len(head):])


def link_numbers(links: list[str] | tuple[str, ...], drive: str, frame: str = "frame", *,
                 frame_place: int | str = 0, explicit: Mapping[str, int] | None = None
                 ) -> dict[str, int]:
    """The links numbered as a course numbers them, in the order of their numbers.

    ``links`` are the moving links in the course's order (the order their Assur groups attach;
    :func:`planmethod.numbering.course_numbers` finds it), ``drive`` the crank. The frame's
    place is 0 (the frame 0, the crank 1, the others 2, 3, …), 1 (the frame 1, the crank 2, …)
    or ``"last"`` (the crank 1, …, the frame after the last moving link); ``explicit`` numbers
    win, and the other links take the free numbers in order.

    Examples
    --------
    >>> link_numbers(["AB", "BC", "slider"], "AB")
    {'frame': 0, 'AB': 1, 'BC': 2, 'slider': 3}
    >>> link_numbers(["AB", "BC", "slider"], "AB", frame_place="last")
    {'AB': 1, 'BC': 2, 'slider': 3, 'frame': 4}
    >>> link_numbers(["AB", "BC", "slider"], "AB", frame_place=1)
    {'frame': 1, 'AB': 2, 'BC': 3, 'slider': 4}
    >>> link_numbers(["AB", "BC", "slider"], "AB", explicit={"slider": 7})
    {'frame': 0, 'AB': 1, 'BC': 2, 'slider': 7}
    """
    numbers = dict(explicit or {})
    if frame not in numbers and frame_place != "last":
        numbers[frame] = int(frame_place)
    taken = set(numbers.values())
    free = 2 if frame_place == 1 else 1
    for link in [drive] + [name for name in links if name not in (frame, drive)]:
        if link in numbers:
            continue
        while free in taken:
            free += 1
        numbers[link] = free
        taken.add(free)
    if frame not in numbers:
        numbers[frame] = max(taken, default=0) + 1
    return dict(sorted(numbers.items(), key=lambda item: item[1]))


def numbered(symbol: str, number: int | str) -> str:
    """A symbol with a link's number as a subscript: the drive's φ, ω, ε follow the crank's
    number (φ₁ by default, θ₂ … in a course that numbers the frame 1).

    >>> numbered("ω", 2), numbered("R", "12")
    ('ω₂', 'R₁₂')
    """
    return symbol + subscript(str(number))


def pair_number(first: int, second: int) -> str:
    """The subscript of a pair of links (a reaction R₁₂: the force of link 1 on link 2),
    with a comma once a number has two digits (R₁‚₁₂).

    >>> pair_number(1, 2), pair_number(3, 12)
    ('12', '3,12')
    """
    return f"{first}{second}" if max(first, second) < 10 else f"{first},{second}"


def point_name(point: str, numbers: Mapping[str, int] | None = None) -> str:
    """A point as a course writes it: ``B@lever`` (point B taken as a point of link
    ``lever``) is B with the lever's number, B₃; a plain point keeps its name (digits as
    subscripts, O₁).

    >>> point_name("B@lever", {"lever": 3}), point_name("O1"), point_name("B@lever")
    ('B₃', 'O₁', 'B lever')
    """
    name, _, link = point.partition("@")
    if not link:
        return point_text(name)
    if numbers and link in numbers:
        return point_text(name) + subscript(str(numbers[link]))
    return f"{point_text(name)} {link}"


def symbol(name: str, numbers: Mapping[str, int] | None = None,
           points: Mapping[str, str] | None = None) -> str:
    """A quantity as a course writes it: a link's by the link's number as a subscript (ω₂,
    ε₃), a point's with the point's name (v_C, a_C, ρ_D; a point of a link by the link's
    number, v_B₃), a pair's by its two links' numbers (s₃₀: link 3 along link 0); a name that
    is no quantity is returned as it is. Without ``numbers`` a link's and a pair's quantity
    keep their names.

    ``points`` gives a prismatic pair's point by the pair's key (``{"slider/frame": "C"}``,
    :func:`slide_points`): its sliding velocity, relative acceleration and Coriolis component
    are then the motion of the slide's point B of link 3 relative to link 2, as a course
    writes them: v_B₃B₂, aʳ_B₃B₂, aᵏ_B₃B₂.

    Examples
    --------
    >>> numbers = {"frame": 0, "AB": 1, "BC": 2, "slider": 3, "lever": 4}
    >>> symbol("omega_BC", numbers), symbol("a_C"), symbol("v_B@lever", numbers)
    ('ω₂', 'a_C', 'v_B₄')
    >>> symbol("ds_slider/frame", numbers), symbol("s_slider/frame")
    ('ds/dt₃₀', 's (slider/frame)')
    >>> points = {"slider/frame": "C"}
    >>> [symbol(f"{kind}_slider/frame", numbers, points) for kind in ("ds", "dds", "coriolis")]
    ['v_C₃C₀', 'aʳ_C₃C₀', 'aᵏ_C₃C₀']
    """
    try:
        found = quantity(name)
    except KeyError:
        return name
    kind, subject = found.kind, found.subject
    if kind.subject == "link" and numbers and subject in numbers:
        return numbered(kind.symbol, numbers[subject])
    if kind.subject == "pair":
        link, _, along = subject.partition("/")
        if numbers and link in numbers and along in numbers:
            point = (points or {}).get(subject)
            if point is not None and kind.prefix in _SLIDE_LETTERS:
                return (f"{_SLIDE_LETTERS[kind.prefix]}_{point_name(f'{point}@{link}', numbers)}"
                        f"{point_name(f'{point}@{along}', numbers)}")
            return kind.symbol + subscript(pair_number(numbers[link], numbers[along]))
        return f"{kind.symbol} ({subject})"
    return f"{kind.symbol}_{point_name(subject, numbers)}"


#: a prismatic pair's quantities that a course writes as the relative motion of the slide's
#: point (v_B₃B₂, aʳ_B₃B₂, aᵏ_B₃B₂), by their letter
_SLIDE_LETTERS = {"ds": "v", "dds": "aʳ", "coriolis": "aᵏ"}


def slide_points(mechanism) -> dict[str, str]:
    """Each prismatic pair's point by the pair's key (``link/along``), for :func:`symbol`.

    >>> from types import SimpleNamespace as Slide
    >>> slide_points(Slide(slides=[Slide(key="slider/frame", point="C")]))
    {'slider/frame': 'C'}
    """
    return {slide.key: slide.point for slide in mechanism.slides}


#: the balancing moment's symbol, which a course's tradition writes in its own letters (Мур)
_BALANCING = message("M_b", context="symbol")
#: columns of a sweep that are no quantity of a point, link or pair, as a table prints them
COLUMN_WORDS: dict[str, Message | str] = {
    "M_b": _BALANCING,
    "M_b_system": message("{moment} (whole system)", moment=_BALANCING),
    "M_b_no_friction": message("{moment} (no friction)", moment=_BALANCING),
    "power_residual": "|ΣP|/Σ|P|",
    "friction_iterations": message("friction iterations")}


def column_words(name: str, numbers: Mapping[str, int] | None = None) -> Message | str:
    """A sweep column as a table a person reads prints it: a quantity by its :func:`symbol`,
    a link's angle ``theta_L`` as θ with the link's number, the balancing moment's columns in
    words (:data:`COLUMN_WORDS`); any other column keeps its name (the CSV header always
    does).

    >>> numbers = {"frame": 0, "AB": 1, "BC": 2}
    >>> column_words("theta_BC", numbers), column_words("omega_BC", numbers)
    ('θ₂', 'ω₂')
    >>> render(column_words("M_b_system")), column_words("x_C")
    ('M_b (whole system)', 'x_C')
    """
    if name in COLUMN_WORDS:
        return COLUMN_WORDS[name]
    head, _, link = name.partition("_")
    if head == "theta" and numbers and link in numbers:
        return numbered("θ", numbers[link])
    return symbol(name, numbers)


def column_text(name: str, numbers: Mapping[str, int] | None = None) -> str:
    """:func:`column_words` as text in the language spoken now.

    >>> column_text("M_b_system"), column_text("theta_BC", {"frame": 0, "AB": 1, "BC": 2})
    ('M_b (whole system)', 'θ₂')
    """
    return render(column_words(name, numbers))


def _name_words(link: str) -> str:
    """A link's name as words read it: an underscore a space (``rocker_EF``: rocker EF)."""
    return link.replace("_", " ")


def link_words(link: str, numbers: Mapping[str, int] | None = None, *,
               drive: bool = False) -> Message | str:
    """A link named in words: ``link 2 (BC)`` by its number, its name in words (an
    underscore a space); just the name without ``numbers``. ``drive`` says it is the drive
    link (``drive link 1 (AB)``, never ``link 1 (AB)`` inside another bracket).

    >>> render(link_words("rocker_EF", {"rocker_EF": 4})), link_words("BC")
    ('link 4 (rocker EF)', 'BC')
    >>> render(link_words("AB", {"AB": 1}, drive=True))
    'drive link 1 (AB)'
    """
    if not numbers or link not in numbers:
        return _name_words(link)
    if drive:
        return message("drive link {number} ({name})", number=numbers[link],
                       name=_name_words(link))
    return message("link {number} ({name})", number=numbers[link], name=_name_words(link))


def link_text(link: str, numbers: Mapping[str, int] | None = None, word: str = "link") -> str:
    """:func:`link_words` as text in the language spoken now; ``word`` is ``"link"`` or
    ``"drive link"``.

    >>> link_text("rocker_EF", {"rocker_EF": 4}), link_text("BC")
    ('link 4 (rocker EF)', 'BC')
    >>> link_text("AB", {"AB": 1}, "drive link")
    'drive link 1 (AB)'
    """
    return render(link_words(link, numbers, drive=word == "drive link"))


def links_words(links: Iterable[str], numbers: Mapping[str, int] | None = None
                ) -> Message | str:
    """Links named in words: ``links 2, 3 (BC, rocker EF)`` by their numbers (in the order
    of the numbers), their names in words; just the names without ``numbers``.

    >>> render(links_words(["rocker_EF", "BC"], {"BC": 2, "rocker_EF": 3}))
    'links 2, 3 (BC, rocker EF)'
    >>> links_words(["AB"])
    'AB'
    """
    links = list(links)
    if not numbers or any(link not in numbers for link in links):
        return ", ".join(_name_words(link) for link in links)
    if len(links) == 1:
        return link_words(links[0], numbers)
    links.sort(key=numbers.__getitem__)       # in the order of their numbers
    return message("links {numbers} ({names})", numbers=[numbers[link] for link in links],
                   names=[_name_words(link) for link in links])


def links_text(links: Iterable[str], numbers: Mapping[str, int] | None = None) -> str:
    """:func:`links_words` as text in the language spoken now.

    >>> links_text(["rocker_EF", "BC"], {"BC": 2, "rocker_EF": 3}), links_text(["AB"])
    ('links 2, 3 (BC, rocker EF)', 'AB')
    """
    return render(links_words(links, numbers))


def coriolis_letter(index: int | str = 1) -> str:
    """The letter of a Coriolis point as a course prints it: the end of the Coriolis
    component of a point's first (or only) sliding side is k, of its second k′ — never the
    report's side index (``k1_Q``, ``k2_Q`` are k_Q and k′_Q).

    >>> coriolis_letter(), coriolis_letter("1"), coriolis_letter(2)
    ('k', 'k', 'k′')
    """
    return "k" + "′" * (int(index or 1) - 1)


def _point_words(point: str) -> Message | str:
    """A point read aloud without the course's numbers: ``B@lever`` is "B of link lever"."""
    name, _, link = point.partition("@")
    return message("{point} of link {link}", point=name, link=link) if link else point


def question_words(name: str, numbers: Mapping[str, int] | None = None,
                   points: Mapping[str, str] | None = None, *, sense: bool = True) -> Message:
    """What a task asks for a quantity, in words and in a course's symbols: the kind's
    question (:attr:`QuantityKind.asked`) filled, its links named by their numbers where
    ``numbers`` has them (a slide's motion by its point's where ``points`` has it:
    :func:`symbol`); with ``sense=False`` without the note of which sense is positive
    (:attr:`QuantityKind.asked_plain`: a page that says it once above its questions).

    Examples
    --------
    >>> numbers = {"frame": 0, "AB": 1, "BC": 2, "slider": 3}
    >>> render(question_words("omega_BC", numbers))
    'angular velocity ω₂ of link 2 (BC) (counter-clockwise positive)'
    >>> render(question_words("omega_BC", numbers, sense=False))
    'angular velocity ω₂ of link 2 (BC)'
    >>> render(question_words("v_B@BC"))
    'speed of B of link BC, |v_B@BC|'
    """
    found = quantity(name)
    kind, subject = found.kind, found.subject
    if kind.subject == "point":
        if not numbers:
            return kind.asked.replace(point=_point_words(subject), subject=subject)
        point = point_name(subject, numbers)
        return kind.asked.replace(point=point, subject=point)
    shown = symbol(name, numbers, points) if numbers else kind.symbol
    if kind.subject == "link":
        asked, numbered = ((kind.asked, kind.asked_numbered) if sense or kind.asked_plain is None
                           else (kind.asked_plain, kind.asked_numbered_plain))
        if numbers and subject in numbers:
            return numbered.replace(symbol=shown, number=numbers[subject],
                                    name=_name_words(subject))
        return asked.replace(symbol=shown, link=_name_words(subject) if numbers else subject)
    link, _, along = subject.partition("/")
    if numbers and link in numbers and along in numbers:
        return kind.asked_numbered.replace(
            symbol=shown, number=numbers[link], name=_name_words(link),
            along_number=numbers[along], along_name=_name_words(along))
    return kind.asked.replace(symbol=shown, pair=subject)


def question_text(name: str, numbers: Mapping[str, int] | None = None) -> str:
    """:func:`question_words` as text in the language spoken now.

    Examples
    --------
    >>> numbers = {"frame": 0, "AB": 1, "BC": 2, "slider": 3}
    >>> question_text("omega_BC", numbers)
    'angular velocity ω₂ of link 2 (BC) (counter-clockwise positive)'
    >>> question_text("v_C", numbers)
    'speed of C, |v_C|'
    >>> question_text("ds_slider/frame", numbers)
    'sliding velocity ds/dt₃₀ of link 3 (slider) along link 0 (frame) (along the guide)'
    >>> question_text("coriolis_slider/frame", numbers)
    'magnitude of the Coriolis acceleration aᵏ₃₀ of link 3 (slider) along link 0 (frame)'
    >>> question_text("omega_BC")
    'angular velocity ω of BC (counter-clockwise positive)'
    """
    return render(question_words(name, numbers))
