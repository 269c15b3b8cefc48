"""Forces, links and crank angles named inside a sentence of the force analysis.

The force analysis says what it did in sentences (a group's steps, its flags): messages
(:mod:`planmethod.words`) whose fields name forces and links. The JSON report writes a force
by its report name (``Rᵗ_B``, ``F_u,BC``, ``load[1]``) and a link by its name; a course's
text prints the force's symbol (Rᵗ₁₂, Fᵘ₂, P₃) and, where a course writes a link by its
number (ΣM_C(2)), the number; and it writes a point's digits as subscripts (ΣM_O₁, O₂B).
So such a field is a typed value, not text: a :class:`ForceName`, a :class:`LinkNumber`,
:class:`PointNames` or a prismatic pair's :class:`PairNumbers` (3–0 in a course's text,
``piston/frame`` in the JSON report), which is written as its report name when the
sentence is rendered as it is (the JSON report), and which
:meth:`planmethod.render.notation.ForceNotation.sentence` replaces by the course's notation.
The symbols of a tradition (the balancing moment M_b, the inertia force Fᵘ …) are messages
of their own.

Examples
--------
>>> from planmethod.words import message, render
>>> step = message("{force} from ΣM_C({link}) = 0", force=ForceName("Rᵗ_B"),
...                link=LinkNumber("BC"))
>>> render(step)
'Rᵗ_B from ΣM_C(BC) = 0'
>>> render(message("⟂ {segment} from ΣM_{pin}", segment=PointNames("O2", "B"),
...                pin=PointNames("O1")))
'⟂ O2B from ΣM_O1'
>>> render(message("the guide of pair {pair}", pair=PairNumbers("piston", "frame")))
'the guide of pair piston/frame'
>>> render(message("at {angles}", angles=crank_angles([0.0, 90.0])))
'at 0°, 90°'
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from ..model import Mechanism
from ..numbering import course_numbers
from ..vocabulary import subscript
from ..words import Message, message

__all__ = ["BALANCING_FORCE", "BALANCING_MOMENT", "FRICTION_FORCE", "FRICTION_MOMENT",
           "INERTIA_FORCE", "INERTIA_MOMENT", "ForceName", "LinkNumber", "PairNumbers",
           "PointNames",
           "crank_angles",
           "load_symbol", "load_symbols"]

#: the letters a course's tradition writes its own way: a course's catalogue translates these
#: symbols (a Russian course: Fи, Mи, Mур, Fтр, Mтр); what follows an underscore is a subscript
INERTIA_FORCE = message("Fᵘ", context="symbol")
INERTIA_MOMENT = message("Mᵘ", context="symbol")
BALANCING_MOMENT = message("M_b", context="symbol")
BALANCING_FORCE = message("F_b", context="symbol")
FRICTION_FORCE = message("Fᶠ", context="symbol")
FRICTION_MOMENT = message("Mᶠ", context="symbol")


@dataclass(frozen=True, slots=True)
class ForceName:
    """A force named in a sentence by its report name (``R_B``, ``Rᵗ_C``, ``N_slider/frame``,
    ``F_u,BC``, ``load[1]``): written as the name where the sentence is rendered as it is."""

    name: str

    def __format__(self, specification: str) -> str:
        return format(self.name, specification)


@dataclass(frozen=True, slots=True)
class LinkNumber:
    """A link named in a sentence where a course writes its number (the link of a moment
    equation, ΣM_C(2)): written as the link's name where the sentence is rendered as it
    is."""

    link: str

    def __format__(self, specification: str) -> str:
        return format(self.link, specification)


@dataclass(frozen=True, slots=True)
class PairNumbers:
    """A prismatic pair named in a sentence by its two links, the sliding one first and the
    one it slides along (its guide's) second: written as the pair's report key
    (``piston/frame``) where the sentence is rendered as it is; a course's text writes the
    two links' numbers (3–0, :meth:`planmethod.render.notation.ForceNotation.pair_name`)."""

    link: str
    along: str

    def __format__(self, specification: str) -> str:
        return format(f"{self.link}/{self.along}", specification)


@dataclass(frozen=True, slots=True, init=False)
class PointNames:
    """A point (``O1``: the pivot of a moment equation, ΣM_O1) or a segment by its two points
    (``O2``, ``B``: the segment O2B) named in a sentence: written as the names run together
    where the sentence is rendered as it is; a course's text sets each name's digits as
    subscripts (O₂B, :func:`planmethod.vocabulary.point_text`)."""

    points: tuple[str, ...]

    def __init__(self, *points: str) -> None:
        object.__setattr__(self, "points", points)

    def __format__(self, specification: str) -> str:
        return format("".join(self.points), specification)


def crank_angles(angles: Iterable[float]) -> list[Message]:
    """Crank angles as a sentence lists them (``0°, 90°``): one message each, its number a
    field (a decimal comma where the language writes one)."""
    return [message("{angle:g}°", angle=float(angle)) for angle in angles]


#: the marks that set apart two loads of one letter on one link (P₃′, P₃″, P₃‴)
_PRIMES = ("′", "″", "‴")


def load_symbols(mechanism: Mechanism) -> dict[str, tuple[str, str]]:
    """Each external load's printed symbol by its report name (``load[1]``): (letter,
    subscript). A load keeps the ``name`` its exercise gives it; otherwise a force is P and a
    moment T, with the number of the link it acts on (P₃ on link 3), and two or more of one
    letter on one link are told apart by primes in the file's order (P₃′, P₃″).

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> load_symbols(load_exercise("exercises/fourbar_study.toml").mechanism)
    {'load[1]': ('T', '3')}
    """
    numbers = course_numbers(mechanism)
    keys: dict[str, tuple[str, str]] = {}
    for load in mechanism.loads:
        letter = "T" if load.moment is not None else "P"
        number = str(numbers[load.link]) if load.link in numbers else str(load.index)
        keys[f"load[{load.index}]"] = (letter, number)
    counts: dict[tuple[str, str], int] = {}
    for key in keys.values():
        counts[key] = counts.get(key, 0) + 1
    seen: dict[tuple[str, str], int] = {}
    out: dict[str, tuple[str, str]] = {}
    for load in mechanism.loads:
        name = f"load[{load.index}]"
        if load.name:
            out[name] = (load.name, "")
            continue
        letter, number = key = keys[name]
        seen[key] = seen.get(key, 0) + 1
        order = seen[key]
        mark = "" if counts[key] == 1 else _PRIMES[order - 1] if order <= 3 else "′" * order
        out[name] = (letter, number + mark)
    return out


def load_symbol(parts: tuple[str, str]) -> str:
    """A load's (letter, subscript) in one string, the link's number in subscript digits.

    >>> load_symbol(("P", "3″")), load_symbol(("F_res", ""))
    ('P₃″', 'F_res')
    """
    letter, sub = parts
    return letter + subscript(sub)
