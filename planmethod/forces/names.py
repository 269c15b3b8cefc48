"""Forces, links and crank angles named inside a sentence of the force analysis.

The force analysis says what it did in sentences (a group's steps, its flags): messages
(:mod:`planmethod.words`) whose fields name forces and links. The JSON report writes a force
by its report name (``Rᵗ_B``, ``F_u,BC``, ``load[1]``) and a link by its name; a course's
text prints the force's symbol (Rᵗ₁₂, Fᵘ₂, P₁) and, where a course writes a link by its
number (ΣM_C(2)), the number. So such a field is a typed value, not text: a
:class:`ForceName` or a :class:`LinkNumber`, which is written as its report name when the
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
>>> render(message("at {angles}", angles=crank_angles([0.0, 90.0])))
'at 0°, 90°'
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from ..words import Message, message

__all__ = ["BALANCING_FORCE", "BALANCING_MOMENT", "FRICTION_FORCE", "FRICTION_MOMENT",
           "INERTIA_FORCE", "INERTIA_MOMENT", "ForceName", "LinkNumber", "crank_angles"]

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


def crank_angles(angles: Iterable[float]) -> list[Message]:
    """Crank angles as a sentence lists them (``0°, 90°``): one message each, its number a
    field (a decimal comma where the language writes one)."""
    return [message("{angle:g}°", angle=float(angle)) for angle in angles]
