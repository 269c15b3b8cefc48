"""What a group kind's plans face is given: the plan emulator as a :class:`PlanDrawer` and its
two plan sheets as :class:`PlanSheet`; the sense a reading is taken with (:func:`sense`); and
:class:`PlansUnavailableError`, for a group whose plans are not drawn.

A plans face (:mod:`planmethod.plans.groups`) draws its group on both plans with the
construction steps a student draws — lines through known plan points, their intersections,
vectors laid off — reads ω and ε off the plans and fixes each link's images, from which the
emulator places the link's other points by similarity. It never reads the exact velocities or
accelerations: only the positions (:meth:`PlanDrawer.where`) and what the plans give.

A length or a reading is a number, or one number per copy of a drawing where the emulator
draws several at once (a tolerance analysis): :data:`Reading`.

Examples
--------
>>> sense(np.array([0.0, -2.0]), np.array([0.0, 1.0]))
-1.0
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping
from typing import Protocol

import numpy as np

from ...errors import PlanmethodError
from ...kinematics import Motion
from ...structure import AssurGroup
from ...vectors import dot, norm
from ..scales import Scales
from ..steps import Direction, Known, Solves, VectorName

__all__ = ["PlanDrawer", "PlanSheet", "PlansUnavailableError", "Reading", "sense"]

#: a length (mm) or a value read off a plan: one number, or one per copy of a drawing (N,)
Reading = float | np.ndarray


class PlansUnavailableError(PlanmethodError):
    """The plans of a group cannot be drawn (its exact kinematics is still available)."""


class PlanSheet(Protocol):
    """One plan being drawn (the velocity plan ``v`` or the acceleration plan ``a``): its
    labelled ``points`` (mm from the pole; (2,), or (N, 2) for copies of a drawing) and the
    construction steps that add to them, each recorded as a typed step
    (:mod:`planmethod.plans.steps`). ``component`` names what a line or vector is
    (``relative``, ``normal``, ``tangential``…), ``vector`` which vector it is, ``group`` the
    group's index; ``along``, ``solves`` and ``known`` say why a line has its direction, what
    an intersection finds and what a vector laid off is (the step's sentence is written from
    them in the render layer)."""

    points: Mapping[str, np.ndarray]

    def line(self, through: str, direction: np.ndarray, *, component: str, vector: VectorName,
             along: Direction, group: int | None) -> int:
        """A construction line through a plan point; returns its step's number."""
        ...

    def intersect(self, first: int, second: int, end: str, *, solves: Solves,
                  group: AssurGroup, angle: float) -> np.ndarray:
        """The point ``end`` where the lines of steps ``first`` and ``second`` meet."""
        ...

    def lay_off(self, start: str, end: str, vector_mm: np.ndarray, *, component: str,
                vector: VectorName, known: Known, group: int | None = None) -> np.ndarray:
        """A known vector (mm) laid off from ``start``: the point ``end``."""
        ...

    def read(self, start: str, end: str, *, quantity: str, factor: float,
             sign: Reading = 1.0, relative: VectorName | None = None) -> Reading:
        """The segment ``start``–``end`` read off as ``quantity``: ±length·``factor``."""
        ...


class PlanDrawer(Protocol):
    """What a group kind's plans face is given by the plan emulator
    (:mod:`planmethod.plans.construction`): the two sheets ``v`` and ``a``, the ``scales``,
    the crank ``angle`` (deg) and the exact ``motion`` drawn (its positions only), a ``memo``
    the face keeps between its two plans, and the steps it takes on the position plan and
    with the images of the links known so far."""

    v: PlanSheet
    a: PlanSheet
    scales: Scales
    angle: float
    motion: Motion
    memo: dict[Hashable, object]

    def where(self, link: str, point: str) -> np.ndarray:
        """A point of a link on the position plan (m, global axes)."""
        ...

    def label(self, point: str, sheet: PlanSheet) -> str:
        """The plan label of a point's image on ``sheet``."""
        ...

    def image_of(self, sheet: PlanSheet, link: str, position: np.ndarray, label: str) -> str:
        """The label of the image of ``link``'s material point at ``position`` on ``sheet``
        (placed by similarity from the link's images if it is not there yet)."""
        ...

    def omega(self, link: str) -> float:
        """A link's ω as read off the velocity plan (its images fixed)."""
        ...

    def epsilon(self, link: str) -> float:
        """A link's ε as read off the acceleration plan (its images fixed)."""
        ...

    def slid(self, key: str, segments: dict[str, object]) -> None:
        """The plan labels of the segments drawn for the prismatic pair ``key``'s relative
        motion: ``v`` (base, moving), ``a`` (base, k, moving) and ``reverse`` (the carrier is
        the pair's ``link``), for the pair's readings."""
        ...

    def radius_mm(self, centre: np.ndarray, point: np.ndarray) -> Reading:
        """A radius read off the position plan (mm) to divide a reading by."""
        ...

    def drawn_length(self, sheet: PlanSheet, start: str, end: str) -> Reading:
        """The segment ``start``–``end`` of ``sheet`` as read off the drawing (mm)."""
        ...

    def fix_velocity(self, link: str, ref: np.ndarray, label: str, omega: float) -> None:
        """A link's velocity image is known — its point at ``ref`` is at ``label``, its ω read
        off: the reading is kept and the link's other points follow by similarity."""
        ...

    def fix_acceleration(self, link: str, ref: np.ndarray, label: str, omega: float,
                         epsilon: float) -> None:
        """A link's acceleration image is known (its ε read off): as :meth:`fix_velocity`."""
        ...


def sense(segment: np.ndarray, direction: np.ndarray) -> Reading:
    """+1 where a segment drawn on a plan points along ``direction`` (a unit vector), −1 where
    against it: the sense a student reads an ω, ε or sliding speed with. A segment across the
    direction (a construction drawn with a mistake) has no sense; +1 (counter-clockwise) is
    taken there, whatever the rounding. ``segment`` may hold one vector per copy of a drawing
    (N, 2): one sense per copy.

    >>> sense(np.array([0.0, -2.0]), np.array([0.0, 1.0])), sense(np.array([3.0, 1e-17]),
    ...                                                           np.array([0.0, 1.0]))
    (-1.0, 1.0)
    """
    along = dot(segment, direction)
    across = 1e-9 * norm(segment)
    positive = (along >= 0) | (np.abs(along) <= across)
    return np.where(positive, 1.0, -1.0) if np.ndim(positive) else (1.0 if positive else -1.0)
