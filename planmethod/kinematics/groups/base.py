"""What every group kind's formulas are given: the context (:class:`GroupInputs`), the branch,
how a link's angle is read (:class:`Theta`), what a higher group's solve returns and what it is
given of the mechanism's model (:class:`KindModel`).

The formulas run on floats, numpy arrays or traced values (:mod:`planmethod.kinematics.algebra`);
checks go through :meth:`GroupInputs.guard`: a cheap bound at every evaluation, the exact check
(:mod:`~planmethod.kinematics.groups.checks`, which raises the error) only where the bound
fails. A dyad's two vector equations and their solve are in
:mod:`~planmethod.kinematics.groups.dyad`.

Examples
--------
>>> turned_axes(1.0, 0.0, 0.0)          # θ + 0: the same axes
(1.0, 0.0)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable, Iterable, Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import NamedTuple, Protocol

import numpy as np

from ...errors import StructureError
from ...model import Mechanism, Slide
from ...structure import AssurGroup, Joint, Structure
from ...words.message import message
from ..algebra import Body, Number, Vec, dot
from ..tracing import Traced

__all__ = ["Branch", "Dyad", "GroupInputs", "KindModel", "Pin", "SolvedGroup", "Theta",
           "ThetaKind", "turned_axes"]


@dataclass(frozen=True, slots=True)
class Branch:
    """The assembly a group takes: ``sign`` (±1 for a dyad, the assembly's number for a higher
    group; see docs/exercise-file.md) and why (``sketch``, ``default`` or ``unique``)."""

    sign: int
    reason: str


# -- the context -----------------------------------------------------------------------------
class KindModel(Protocol):
    """What a higher group kind is given of the mechanism's model
    (:class:`planmethod.kinematics.program.Model`): the mechanism and its structure, the
    branches chosen at ``drive.angle``, the direct evaluation of the groups before it, the
    model of a sibling mechanism (the same at unit crank speed), and ``memo``, where a kind
    keeps what it finds once per model (its assemblies, its continuation path)."""

    mechanism: Mechanism
    structure: Structure
    memo: dict[Hashable, object]

    def sibling(self, mechanism: Mechanism) -> KindModel: ...

    def branches(self, groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]: ...

    def bodies(self, level: int, groups: tuple[AssurGroup, ...],
               branches: Mapping[int, Branch], angles_deg: np.ndarray) -> dict[str, Body]: ...


@dataclass(frozen=True, slots=True)
class Pin:
    """A revolute pair of a group with a known link: ``link`` (of the group) carries the pin at
    local ``local``; ``known`` carries it at ``known_local``; ``at`` is its global position and
    ``offset`` its offset from the known link's origin."""

    joint: Joint
    link: str
    known: str
    local: tuple[float, float]
    known_local: tuple[float, float]
    at: Vec
    offset: Vec
    bound: float | None


class Dyad(NamedTuple):
    """A dyad's pairs and links: ``link1`` is joined to a known link by ``external1`` and to
    ``link2`` by ``internal``; ``link2`` to a known link by ``external2`` (a prismatic pair's
    guide may be on either side)."""

    external1: Joint
    internal: Joint
    external2: Joint
    link1: str
    link2: str


class GroupInputs:
    """What a group kind's formulas see: the model, the group, its branch ``sign``, the bodies
    of the links known so far (and of the group's links once placed), the crank angles (deg),
    and :meth:`guard`. ``bounds`` holds, where known, an upper bound of the distance of a named
    point from the global origin over every assembled position."""

    def __init__(self, mechanism: Mechanism, group: AssurGroup, bodies: dict[str, Body],
                 sign: float, angles, bounds: dict[str, float]) -> None:
        self.mechanism, self.group, self.sign = mechanism, group, float(sign)
        self.bodies, self.angles, self.bounds = bodies, angles, bounds

    def local(self, link: str, point: str) -> tuple[float, float]:
        x, y = self.mechanism.local(link, point)
        return float(x), float(y)

    def dyad(self) -> Dyad:
        """The group's pairs and links as a dyad kind's formulas name them."""
        external1, internal, external2 = self.group.joints
        link1, link2 = self.group.links
        return Dyad(external1, internal, external2, link1, link2)

    def group_link(self, joint: Joint) -> str:
        return joint.links[0] if joint.links[0] in self.group.links else joint.links[1]

    def pin(self, joint: Joint) -> Pin:
        """The revolute pair ``joint`` between a group link and a known link."""
        link = self.group_link(joint)
        known = joint.other(link)
        known_local = self.local(known, joint.point)
        body = self.bodies[known]
        offset = body.offset(*known_local)
        return Pin(joint, link, known, self.local(link, joint.point), known_local,
                   body.origin + offset, offset, self.bounds.get(joint.point))

    def length(self, link: str, first: str, second: str) -> float:
        """Distance between two points of a link; a zero length is a :class:`StructureError`."""
        length = self.mechanism.links[link].length(first, second)
        if not length > 1e-12:
            raise StructureError(message("{link} ({first}{second}) has zero length: the group "
                                         "has no definite position", link=link, first=first,
                                         second=second), link=self.group.name)
        return length

    def guard(self, value, bound: float, check: Callable, *args,
              magnitude: bool = False) -> None:
        """Refuse a position: where ``value > bound`` (with ``magnitude``: ``|value| > bound``)
        fails at some angle, ``check(angles, *args)`` runs on the arrays and raises (or returns,
        where the bound was too cautious)."""
        if isinstance(value, Traced):
            value.tracer.guard(value, bound, check, *args, magnitude=magnitude)
        elif not (np.min(np.abs(value) if magnitude else value) > bound):
            check(self.angles, *args)

    def guide(self, slide: Slide, unknown: str, body: Body | None = None
              ) -> tuple[Vec, Vec, Number]:
        """A prismatic pair's guide as a line for the *unknown* link's frame: (d, n, c) with d
        the guide's global direction, n = J·d, and n·(origin of ``unknown``) = c. The guide's
        orientation comes from the known link's axes (``body``, default its known body)."""
        along_known = unknown == slide.link
        known = slide.along if along_known else slide.link
        body = body or self.bodies[known]
        angle = slide.direction_rad if along_known else -slide.direction_rad
        c, s = turned_axes(body.cos, body.sin, angle)
        if along_known:  # the guide is fixed in the known link
            d = Vec(c, s)
            n = d.perp()
            through = body.point(*self.local(slide.along, slide.through))
            own = Vec(*self.local(slide.link, slide.point)).turned(c, s)
            return d, n, dot(n, through - own)
        # the guide is fixed in the unknown link, whose axes are the known link's turned back
        d = Vec(body.cos, body.sin)
        n = d.perp()
        point = body.point(*self.local(slide.link, slide.point))
        own = Vec(*self.local(slide.along, slide.through)).turned(c, s)
        return d, n, dot(n, point - own)

    def slide_axes(self, slide: Slide, unknown: str) -> tuple[Number, Number]:
        """The axes (cos θ, sin θ) of ``unknown``, held by a prismatic pair to a known link."""
        if unknown == slide.link:
            body = self.bodies[slide.along]
            return turned_axes(body.cos, body.sin, slide.direction_rad)
        body = self.bodies[slide.link]
        return turned_axes(body.cos, body.sin, -slide.direction_rad)


def turned_axes(c: Number, s: Number, angle: float) -> tuple[Number, Number]:
    """(cos, sin) of θ + ``angle`` (rad, a constant) from (cos θ, sin θ).

    >>> turned_axes(1.0, 0.0, math.pi / 2)
    (6.123233995736766e-17, 1.0)
    """
    if angle == 0.0:
        return c, s
    turned = Vec(c, s).turned(math.cos(angle), math.sin(angle))
    return turned.x, turned.y


# -- how a link's angle is read --------------------------------------------------------------
class ThetaKind(StrEnum):
    """How a link's angle θ is read from the solved points (see :class:`Theta`)."""

    TWO = "two"      # θ = atan2(P_second − P_first) − alpha: a link through two pins
    TIED = "tied"    # θ = θ(link) + alpha: a prismatic pair forbids relative rotation
    SPAN = "span"    # θ = atan2(span) − atan2(span in the link's axes): a guide link turning
    #                  about its pivot, span = P_first − P_second


@dataclass(frozen=True, slots=True)
class Theta:
    """How a link's angle θ is read from the solved points (computed only when asked): its
    :class:`ThetaKind`, the points it is read from, the angle ``alpha`` (rad) and the ``link``
    it follows. A link with no recipe (the drive, a link whose θ Newton solved) has a result
    row of its own."""

    kind: ThetaKind
    first: str | None = None
    second: str | None = None
    alpha: float = 0.0
    link: str | None = None


class SolvedGroup(NamedTuple):
    """A higher group solved (what an iterative kind's ``evaluate`` returns, its links' bodies
    put into the context): the θ of its links that are results of their own (``thetas``:
    link → value), how the others' angles are read (``recipes``), and the conditioning of its
    Jacobian (``sine``: 1 at best, 0 at a toggle)."""

    thetas: Mapping[str, Number]
    recipes: Mapping[str, Theta]
    sine: Number
