"""Reactions in kinematic pairs: how a pair is keyed and oriented in the report.

A revolute pair is keyed by its point (``B``), or ``B:AB/BC`` where the point joins three or more
links (one key per pair of links, ``from/on``); a prismatic pair by ``link/along`` (the slide's
key). The reaction reported is the force on ``on`` from ``from`` (global axes, N) acting at the
pair's point, plus — for a prismatic pair — the reaction couple on ``on`` about the slide's
point (N·m). Orientation: an external pair of a group is reported from the known link on the
group's link; an internal revolute pair from the first to the second link of the pair; a
prismatic pair always on the slide's ``link`` from its ``along``.

Examples
--------
>>> import numpy as np
>>> reaction = Reaction("B", PairKind.REVOLUTE, "AB", "BC", np.zeros((1, 2)),
...                     np.array([[3.0, 4.0]]))
>>> reaction.reversed().force.tolist(), reaction.reversed().source
([[-3.0, -4.0]], 'BC')
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..model import Mechanism, Slide
from ..structure import Joint
from ..vectors import norm
from ..vocabulary import PairKind
from .applied import Wrench

__all__ = ["Reaction", "canonical", "pair_key"]


def canonical(joint: Joint, group_links: Sequence[str]) -> tuple[str, str]:
    """(from, on) of a pair in the report: an external pair of a group from the known link on
    the group's link, an internal revolute pair from its first to its second link, a prismatic
    pair on the slide's ``link`` from its ``along``."""
    if joint.kind is PairKind.PRISMATIC:
        return joint.slide.along, joint.slide.link
    first, second = joint.links
    if first in group_links and second in group_links:
        return first, second
    inside = first if first in group_links else second
    return joint.other(inside), inside


def pair_key(mechanism: Mechanism, kind: PairKind, point: str, source: str, target: str,
             slide: Slide | None = None) -> str:
    """The report key of a pair (see the module docstring)."""
    if kind == PairKind.PRISMATIC:
        return slide.key
    pair = mechanism.revolute_at(point)
    if pair is not None and len(pair.links) >= 3:
        return f"{point}:{source}/{target}"
    return point


@dataclass(frozen=True, slots=True)
class Reaction:
    """The reaction on ``target`` from ``source`` in the pair ``key`` (arrays over angles):
    ``force`` (N × 2) through ``point`` (N × 2), and for a prismatic pair the ``moment`` (N,),
    the couple about ``point``."""

    key: str
    kind: PairKind
    source: str
    target: str
    point: np.ndarray
    force: np.ndarray
    moment: np.ndarray | None = None
    slide: Slide | None = None

    def reversed(self) -> Reaction:
        """The same pair seen from the other side: the force on ``source`` from ``target``."""
        moment = None if self.moment is None else -self.moment
        return Reaction(self.key, self.kind, self.target, self.source, self.point, -self.force,
                        moment, self.slide)

    def oriented(self, source: str, target: str) -> Reaction:
        """This reaction as the force on ``target`` from ``source``."""
        if (self.source, self.target) == (source, target):
            return self
        if (self.source, self.target) == (target, source):
            return self.reversed()
        raise ValueError(f"pair {self.key} joins {self.source} and {self.target}, not "
                         f"{source} and {target}")

    def wrench(self) -> Wrench:
        """The reaction as a wrench on ``target``."""
        return Wrench.at(self.point, self.force, self.moment)

    def take(self, index) -> Reaction:
        moment = None if self.moment is None else self.moment[index]
        return Reaction(self.key, self.kind, self.source, self.target, self.point[index],
                        self.force[index], moment, self.slide)

    @property
    def magnitude(self) -> np.ndarray:
        return norm(self.force)
