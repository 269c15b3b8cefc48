"""Forces as a course writes them: links by number, reactions R₁₂, inertia Fᵘ₂ and Mᵘ₂.

The solver names its forces for the JSON report (``G_BC``, ``F_u,rocker_EF``, ``R_B``,
``load[1]``); a figure prints them in a mechanisms course's notation:

=====================  ======================================================================
report name            printed
=====================  ======================================================================
``G_BC``               G₂ — the weight of link 2
``F_u,BC``             Fᵘ₂ — the inertia force (principal vector) of link 2
``M_u,BC``             Mᵘ₂ — the inertia moment of link 2
``R_B``, ``Rᵗ_B``      R₁₂, Rᵗ₁₂ … — the force of link 1 on link 2 (R₂₁ = −R₁₂); also Rⁿ, N
``M_f,B``, ``F_f,B``   Mᶠ₁₂, Fᶠ₁₂ — the friction moment or force of link 1 on link 2
``load[1]``            the load's ``name`` from the exercise, else P₃ (a force) or T₃ (a moment)
                       with the number of the link it acts on (two on link 3: P₃′, P₃″)
=====================  ======================================================================

Links are numbered as the exercise's course numbers them
(:func:`planmethod.numbering.course_numbers`): by default the frame 0, the crank 1, the others
as their Assur groups attach.

The letters of the inertia force Fᵘ, the inertia moment Mᵘ, the balancing moment M_b and force
F_b and the friction's Fᶠ, Mᶠ are a tradition's: they are messages (``context="symbol"``) that
a course's catalogue writes its own way (a Russian course: Fи, Mи, Mур, Fур, Fтр, Mтр;
:mod:`planmethod.forces.names`). A sentence of the force
analysis (a group's step, a flag) names its forces and links by typed fields
(:mod:`planmethod.forces.names`): :meth:`ForceNotation.sentence` prints them in the notation.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.report import analyse
>>> from planmethod.words import render
>>> analysis = analyse(load_exercise("exercises/fourbar_forces.toml"))
>>> notation = ForceNotation(analysis.forces.solution)
>>> notation.plain("F_u,BC"), notation.plain("R_B", "BC"), notation.plain("R_B", "AB")
('Fᵘ₂', 'R₁₂', 'R₂₁')
>>> step = analysis.forces.solution.groups.groups[0].steps[1]
>>> render(step)
'Rᵗ_D ⟂ DC from ΣM_C(CD) = 0: Rᵗ_D = ΣM_C/DC'
>>> render(notation.sentence(step, ("BC", "CD")))
'Rᵗ₀₃ ⟂ DC from ΣM_C(3) = 0: Rᵗ₀₃ = ΣM_C/DC'
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

from ..forces.names import (
    BALANCING_FORCE,
    BALANCING_MOMENT,
    FRICTION_FORCE,
    FRICTION_MOMENT,
    INERTIA_FORCE,
    INERTIA_MOMENT,
    ForceName,
    LinkNumber,
    PairNumbers,
    PointNames,
    load_symbols,
)
from ..numbering import course_numbers
from ..vocabulary import (
    GroupKind,
    column_text,
    group_kind_words,
    link_text,
    links_text,
    pair_number,
    point_text,
    subscript,
)
from ..words import Message, message, render
from .labels import Run, RunKind, label_runs

__all__ = ["BALANCING_FORCE", "BALANCING_MOMENT", "FRICTION_FORCE", "FRICTION_MOMENT",
           "INERTIA_FORCE", "INERTIA_MOMENT", "ForceNotation", "symbol_runs"]

#: a reaction or one of its components, by the pair's key
_REACTION = re.compile(r"^(Rᵗ|Rⁿ|R∥|R⊥|R|N)_(.+)$")

#: the symbol of each kind of known force's report name (``F_u,BC``: the inertia force)
_SYMBOLS = {"F_u": INERTIA_FORCE, "M_u": INERTIA_MOMENT, "F_f": FRICTION_FORCE,
            "M_f": FRICTION_MOMENT}


def symbol_runs(symbol: Message | str) -> tuple[Run, ...]:
    """A symbol's label runs: what follows an underscore set as a subscript (M_b: M with
    subscript b, as the course's catalogue writes it).

    >>> symbol_runs(BALANCING_MOMENT)
    (('M', <RunKind.MAIN: 'main'>), ('b', <RunKind.SUB: 'sub'>))
    """
    head, _, sub = render(symbol).partition("_")
    return ((head, RunKind.MAIN), (sub, RunKind.SUB)) if sub else ((head, RunKind.MAIN),)


def symbol_text(parts: tuple[str, str]) -> str:
    """(symbol, subscript) in one string, the subscript in Unicode subscript digits."""
    symbol, sub = parts
    return symbol + subscript(sub)


class ForceNotation:
    """The printed names of one solution's forces (see the module docstring)."""

    def __init__(self, solution: Any) -> None:
        mechanism = solution.mechanism
        self.numbers = course_numbers(mechanism)
        #: the letters of a tradition as the language spoken writes them (once per figure)
        self.symbols = {head: render(symbol) for head, symbol in _SYMBOLS.items()}
        self.pairs = {key: (reaction.source, reaction.target)
                      for key, reaction in solution.reactions.items()}
        self.loads = load_symbols(mechanism)

    # -- links -------------------------------------------------------------------------------
    def number(self, link: str) -> str:
        """The link's number as text (its name where it has none)."""
        return str(self.numbers[link]) if link in self.numbers else link

    def link_name(self, link: str) -> str:
        """``link 3 (rocker EF)``: the number, with the exercise's name in words."""
        return link_text(link, self.numbers)        # words: vocabulary

    def links(self, links: Iterable[str]) -> str:
        """``links 3, 4 (BC, CD)``."""
        return links_text(links, self.numbers)      # words: vocabulary

    def pair_name(self, key: str) -> str:
        """A pair by its report key as a course names it: a revolute pair by its point (O₂),
        a prismatic pair by its two links' numbers (3–0: the slide on the guide)."""
        point, _, links = key.partition(":")
        if not links and "/" in key:
            link, _, along = key.partition("/")
            if link in self.numbers and along in self.numbers:
                return f"{self.numbers[link]}–{self.numbers[along]}"
            return key
        return point_text(point)

    def column(self, name: str) -> Message | str:
        """A sweep column as a table prints it: a pair's reaction by its printed name (``Rx_B``
        → R₁₂ (x), ``R_B`` → |R₁₂|, a prismatic pair's couple ``M_K`` → M₀₃), the balancing
        moment's and the friction's columns in words, any other column as
        :func:`planmethod.vocabulary.column_text` prints it.

        >>> from planmethod.spec import load_exercise
        >>> from planmethod.report import analyse
        >>> from planmethod.words import render
        >>> solved = analyse(load_exercise("exercises/fourbar_forces.toml")).forces
        >>> notation = ForceNotation(solved.solution)
        >>> [render(notation.column(name))
        ...  for name in ("Rx_B", "R_B", "omega_BC", "M_b_system")]
        ['R₁₂ (x)', '|R₁₂|', 'ω₂', 'M_b (whole system)']
        """
        head, _, key = name.partition("_")
        if name.startswith("friction_sense_"):
            key = name[len("friction_sense_"):]
            reaction = self.parts(f"R_{key}")
            return (message("friction sense, {reaction}", reaction=symbol_text(reaction))
                    if reaction else name)
        if name in _MOMENT_COLUMNS:
            return _MOMENT_COLUMNS[name]
        reaction = self.parts(f"R_{key}") if head in ("Rx", "Ry", "R", "M") else None
        if reaction is None:
            return column_text(name, self.numbers)
        printed = symbol_text(reaction)
        if head == "M":
            return "M" + subscript(reaction[1])
        return {"Rx": f"{printed} (x)", "Ry": f"{printed} (y)"}.get(head, f"|{printed}|")

    def group_name(self, group: Any) -> Message | str:
        """A group of the force analysis as a course names it: ``drive link 1 (AB)`` (the
        drive with the frame, solved last), ``RRR of links 2, 3 (BC, CD)``."""
        if group.kind == GroupKind.DRIVE:
            return link_text(group.links[0], self.numbers, "drive link")  # words: vocabulary
        return message("{kind} of {links}", kind=group_kind_words(group.kind),
                       links=self.links(group.links))

    def _pair(self, key: str, on: str | None) -> str | None:
        """The subscript ``ij`` of the pair ``key``: force of link i on link j, j = ``on``."""
        found = self.pairs.get(key)
        if found is None or (on is not None and on not in found):
            found = next((pair for name, pair in self.pairs.items()
                          if name.partition(":")[0] == key and (on is None or on in pair)),
                         found)
        if found is None:
            return None
        source, target = found
        if on is not None and on == source:
            source, target = target, source
        first, second = self.numbers.get(source), self.numbers.get(target)
        if first is None or second is None:
            return None
        return pair_number(first, second)

    # -- forces ------------------------------------------------------------------------------
    def parts(self, name: str, on: str | None = None) -> tuple[str, str] | None:
        """(symbol, subscript) of a force's report name acting on link ``on`` (None for a name
        that is no force of this solution)."""
        if name in self.loads:
            return self.loads[name]
        head, comma, rest = name.partition(",")
        if comma and head in ("F_u", "M_u") and rest in self.numbers:
            return (self.symbols[head], self.number(rest))
        if comma and head in ("M_f", "F_f"):
            pair = self._pair(rest, on)
            return (self.symbols[head], pair) if pair else None
        if name.startswith("G_") and name[2:] in self.numbers:
            return ("G", self.number(name[2:]))
        match = _REACTION.match(name)
        if match:
            pair = self._pair(match.group(2), on)
            return (match.group(1), pair) if pair else None
        return None

    def runs(self, name: str, on: str | None = None) -> tuple[Run, ...]:
        """A label's runs: the symbol, its subscript set small."""
        found = self.parts(name, on)
        if found is None:
            return label_runs(name)
        symbol, sub = found
        if not sub:
            return label_runs(symbol)
        marks = sub[len(sub.rstrip("′″‴")):]     # a load's primes (P₃′) stand beside
        runs = ((symbol, RunKind.MAIN), (sub[:len(sub) - len(marks)], RunKind.SUB))
        return (*runs, (marks, RunKind.MAIN)) if marks else runs

    def plain(self, name: str, on: str | None = None) -> str:
        """The printed name in one string, the subscript in Unicode subscript digits."""
        found = self.parts(name, on)
        return name if found is None else symbol_text(found)

    def sentence(self, text: Message, links: Iterable[str] = ()) -> Message:
        """A sentence of the force analysis (a group's step, a flag) in the course's
        notation: each force field (:class:`~planmethod.forces.names.ForceName`) printed by
        its symbol — a reaction acting on the one link of ``links`` (the group's) at its pair —
        a :class:`~planmethod.forces.names.LinkNumber` by the link's number, a prismatic pair
        (:class:`~planmethod.forces.names.PairNumbers`) by its links' numbers (3–0), points
        (:class:`~planmethod.forces.names.PointNames`) with their digits as subscripts (O₂B,
        :func:`~planmethod.vocabulary.point_text`), and any link name with an underscore in
        the other fields in words."""
        return self._resolved(text, tuple(links))

    def _resolved(self, value: Any, links: tuple[str, ...]) -> Any:
        if isinstance(value, Message):
            return value.replace(**{name: self._resolved(field, links)
                                    for name, field in value.fields})
        if isinstance(value, list | tuple):
            return [self._resolved(item, links) for item in value]
        if isinstance(value, ForceName):
            return self._force(value.name, links)
        if isinstance(value, LinkNumber):
            return self.number(value.link)
        if isinstance(value, PairNumbers):
            return self.pair_name(f"{value.link}/{value.along}")
        if isinstance(value, PointNames):
            return "".join(point_text(point) for point in value.points)
        if isinstance(value, str):
            return self._words(value)
        return value

    def _force(self, name: str, links: tuple[str, ...]) -> str:
        """A force of a sentence printed: a reaction acts on the group's link at its pair."""
        key = _REACTION.match(name)
        on = None
        if key:
            for pair_key, pair in self.pairs.items():
                if key.group(2) in (pair_key, pair_key.partition(":")[0]):
                    inside = [link for link in pair if link in links]
                    on = inside[0] if len(inside) == 1 else None
                    break
        return self.plain(name, on)

    def _words(self, text: str) -> str:
        """Each link name with an underscore in ``text`` in words (``rocker_EF``: rocker
        EF)."""
        for link in sorted(self.numbers, key=len, reverse=True):
            if "_" in link:
                text = re.sub(rf"\b{re.escape(link)}\b", link.replace("_", " "), text)
        return text


#: the balancing moment's and the friction's sweep columns, as a table prints them
_MOMENT_COLUMNS: dict[str, Message] = {
    "M_b": BALANCING_MOMENT,
    "M_b_system": message("{symbol} (whole system)", symbol=BALANCING_MOMENT),
    "M_b_no_friction": message("{symbol} (no friction)", symbol=BALANCING_MOMENT),
    "friction_iterations": message("friction iterations")}
