"""What a group kind's forces face is given and gives back: the force analysis as a
:class:`ForceSolver`, the edges of the group's force polygon (:class:`PolygonEdge`) and the
group's solve (:class:`GroupForces`).

A forces face (:mod:`planmethod.forces.groups`) runs its group's textbook reaction sequence —
tangential components from the links' moments, the force polygon, the inner pairs from one
link's equilibrium — on the solver's positions and known wrenches, records each reaction it
finds and returns the group's steps, polygon and reactions. Arrays are over the crank angles.

Examples
--------
>>> import numpy as np
>>> unit, length = split(np.array([[3.0, 4.0]]))
>>> unit.tolist(), length.tolist()
([[0.6, 0.8]], [5.0])
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ...structure import AssurGroup, Joint
from ...vectors import norm
from ...vocabulary import EdgeKind, GroupKind
from ...words import Message
from ..applied import Wrench
from ..reactions import Reaction

__all__ = ["ForceSolver", "GroupForces", "PolygonEdge", "split"]


@dataclass(frozen=True, slots=True)
class PolygonEdge:
    """One vector of a group's force polygon, in drawing order (head to tail).

    ``kind``: an :class:`~planmethod.vocabulary.EdgeKind` — a known force (weight, inertia,
    load, friction), a reaction transmitted from a group solved before, a component of an
    unknown reaction (Rᵗ, Rⁿ, N…), or a whole reaction found from the polygon's closure.
    """

    label: str
    vector: np.ndarray
    kind: EdgeKind
    link: str


@dataclass(frozen=True, slots=True)
class GroupForces:
    """One group's solve: the steps as a course writes them (sentences whose forces and links
    are :mod:`~planmethod.forces.names` fields), its force polygon (closing to zero), the
    reactions it found and, for a triad, Assur's special point used (N × 2)."""

    name: str
    kind: GroupKind
    links: tuple[str, ...]
    steps: tuple[Message, ...]
    polygon: tuple[PolygonEdge, ...]
    reactions: tuple[str, ...]
    special_point: np.ndarray | None = None


class ForceSolver(Protocol):
    """What a group kind's forces face is given by the force analysis
    (:mod:`planmethod.forces.group_method`): the solved positions, each link's known wrench
    (``wrench[link]``: its reactions from the groups solved before included), the 2 × 2 solve
    and the singularity check, the recording of reactions, polygon edges and the group's
    result, and the group's equilibrium equations solved at once (:meth:`linear`). ``count``
    is the number of crank angles."""

    count: int
    wrench: Mapping[str, Wrench]

    def at(self, link: str, point: str) -> np.ndarray:
        """A point of a link (N, 2)."""
        ...

    def guide(self, joint: Joint) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(d, n, slide point) of a prismatic pair: guide direction, its normal, the point."""
        ...

    def solve2(self, e1: np.ndarray, e2: np.ndarray, w: np.ndarray, group: str,
               what: Message) -> tuple[np.ndarray, np.ndarray]:
        """u1, u2 of u1·e1 + u2·e2 = w (``what`` says why it may be singular)."""
        ...

    def singular(self, value: np.ndarray, scale: np.ndarray | float, group: str,
                 what: Message) -> None:
        """Refuse where ``value`` vanishes against ``scale`` (a singular force system)."""
        ...

    def record(self, joint: Joint, group_links: Sequence[str], target: str, source: str,
               point: np.ndarray, force: np.ndarray,
               moment: np.ndarray | None = None) -> Reaction:
        """Keep the reaction on ``target`` from ``source`` in ``joint``."""
        ...

    def known_edges(self, links: Iterable[str]) -> list[PolygonEdge]:
        """The known forces on ``links`` as polygon edges."""
        ...

    def edge(self, label: str, vector: np.ndarray, kind: EdgeKind, link: str) -> PolygonEdge:
        ...

    def total(self, links: Iterable[str]) -> Wrench:
        """The sum of the links' known wrenches."""
        ...

    def result(self, group: AssurGroup, steps: Sequence[Message], edges: Sequence[PolygonEdge],
               keys: Sequence[str], special: np.ndarray | None = None) -> GroupForces:
        """The group's solve, as the face ends it."""
        ...

    def linear(self, group: AssurGroup) -> GroupForces:
        """The group's 3k equilibrium equations solved at once (its linear system)."""
        ...


def split(vector: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(unit vector, length) of arrays of 2-vectors."""
    length = norm(vector)
    return vector / length[..., None], length
