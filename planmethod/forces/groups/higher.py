"""The forces face of a higher group of any other shape (:mod:`planmethod.kinematics.groups.
higher`: a triad with prismatic pairs, a tetrad): no textbook sequence is written for it, so
its 3k equilibrium equations are solved at once — the group's linear system, the same
equations a sequence solves step by step.

Examples
--------
>>> from types import SimpleNamespace
>>> reactions(SimpleNamespace(linear=lambda group: f"{group}: solved at once"), "the group")
'the group: solved at once'
"""

from __future__ import annotations

from ...structure import AssurGroup
from .base import ForceSolver, GroupForces

__all__ = ["reactions"]


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The group's reactions by its linear system (see the module docstring)."""
    return solver.linear(group)
