"""The plans face of a higher group of any other shape (:mod:`planmethod.kinematics.groups.
higher`): a triad with a prismatic pair is drawn by Assur's special point
(:mod:`planmethod.plans.groups.triad`, its sliding side as in a dyad); a group no textbook
construction is written for — a tetrad, a triad whose side link slides on both its pairs — is
not drawn, and saying so is its face. Its exact kinematics (and its reactions, by its linear
system) are still reported.

Examples
--------
>>> from planmethod.structure import AssurGroup
>>> from planmethod.vocabulary import GroupKind
>>> draw_velocity(None, AssurGroup(0, GroupKind.TETRAD, ("A", "B", "C", "D"), (), 3, 2, ()))
Traceback (most recent call last):
...
planmethod.plans.groups.base.PlansUnavailableError: link A+B+C+D: plans are drawn for class \
III triads whose side links have at most one prismatic pair each; this tetrad is not one — its \
exact kinematics is reported (planmethod solve --json)
"""

from __future__ import annotations

from ...structure import AssurGroup
from ...words import message
from . import triad
from .base import PlanDrawer, PlansUnavailableError

__all__ = ["draw_acceleration", "draw_velocity"]


def _refuse(group: AssurGroup) -> None:
    raise PlansUnavailableError(message(
        "plans are drawn for class III triads whose side links have at most one prismatic "
        "pair each; this {kind} is not one — its exact kinematics is reported (planmethod "
        "solve --json)", kind=str(group.kind)), link=group.name)


def draw_velocity(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Draw a triad with a prismatic pair by Assur's special point; refuse any other group
    (:class:`~.base.PlansUnavailableError`)."""
    if not triad.drawable(group):
        _refuse(group)
    triad.draw_velocity(emulator, group)


def draw_acceleration(emulator: PlanDrawer, group: AssurGroup) -> None:
    """As :func:`draw_velocity`, on the acceleration plan (drawn after it)."""
    if not triad.drawable(group):
        _refuse(group)
    triad.draw_acceleration(emulator, group)
