"""The plans face of a higher group of any other shape (:mod:`planmethod.kinematics.groups.
higher`: a triad with prismatic pairs, a tetrad): its plans are not drawn — no textbook
construction is written for it — and saying so is its face. Its exact kinematics (and its
reactions, by its linear system) are still reported.

Examples
--------
>>> from planmethod.structure import AssurGroup
>>> from planmethod.vocabulary import GroupKind
>>> draw_velocity(None, AssurGroup(0, GroupKind.TETRAD, ("A", "B", "C", "D"), (), 3, 2, ()))
Traceback (most recent call last):
...
planmethod.plans.groups.base.PlansUnavailableError: link A+B+C+D: plans are drawn for class \
III triads of revolute pairs only; this tetrad has other pairs — its exact kinematics is \
reported (planmethod solve --json)
"""

from __future__ import annotations

from ...structure import AssurGroup
from .base import PlanDrawer, PlansUnavailableError

__all__ = ["draw_acceleration", "draw_velocity"]


def draw_velocity(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Refuse: the group's plans are not drawn (:class:`~.base.PlansUnavailableError`)."""
    raise PlansUnavailableError(
        f"plans are drawn for class III triads of revolute pairs only; this {group.kind} "
        "has other pairs — its exact kinematics is reported (planmethod solve --json)",
        link=group.name)


def draw_acceleration(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Refuse, as :func:`draw_velocity` (the velocity plan, drawn first, refuses already)."""
    draw_velocity(emulator, group)
