"""A group kind's forces face: how the force analysis finds the reactions of a group of that
kind.

The forces layer's part of a group kind (:mod:`planmethod.kinematics.groups`) is the module of
this package named as the kind's module there: its forces face, ``reactions(solver, group)``
(:class:`Reactions`) — the textbook sequence the group-by-group method
(:mod:`planmethod.forces.group_method`) runs for a group of that kind, given the method as a
:class:`~planmethod.forces.groups.base.ForceSolver`: each dyad kind's own, the triad's by
Assur's special point; a higher group of any other shape solves its 3k equilibrium equations
at once (:meth:`~planmethod.forces.groups.base.ForceSolver.linear`).

When first asked (:func:`registered`), the registry checks every kind the kinematics registers
against this package, and every module of it against the kinds: a kind without its face, a face
without ``reactions`` or whose ``reactions`` cannot take the protocol's arguments, a face of no
kind at all is a :class:`TypeError` naming the module and what is wrong — at load, never in the
middle of a force analysis.

Examples
--------
>>> from planmethod.forces.groups import rrr
>>> registered()["rrr"] is rrr.reactions
True
>>> sorted(registered())
['higher', 'prp', 'rpp', 'rpr', 'rrp', 'rrr', 'triad']
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable, Mapping
from types import ModuleType
from typing import Protocol

from ...kinematics.groups import (
    KindModule,
    face_modules,
    kind_module,
    kinds_by_name,
    protocol_functions,
)
from ...structure import AssurGroup
from .base import ForceSolver, GroupForces

__all__ = ["Reactions", "describe", "reactions_of", "registered"]

#: a kind's reaction sequence: the solver and the group → the group's solve
ReactionSequence = Callable[[ForceSolver, AssurGroup], GroupForces]


class Reactions(Protocol):
    """A kind's forces face: its group's reactions, found by its textbook sequence (or, for a
    group without one, its linear system) on the solver's positions and known wrenches."""

    def reactions(self, solver: ForceSolver, group: AssurGroup) -> GroupForces: ...


def describe(module: ModuleType | None, kind: KindModule | None) -> ReactionSequence:
    """Check the forces face ``module`` (None: the kind has none) of the kinematics' ``kind``
    (None: no kind of that name). Returns its reaction sequence.

    Raises
    ------
    TypeError
        Naming the module and each way it breaks the interface.

    Examples
    --------
    >>> from planmethod.kinematics.groups import kinds_by_name
    >>> describe(None, kinds_by_name()["rrr"])
    Traceback (most recent call last):
    ...
    TypeError: group kind module planmethod.kinematics.groups.rrr: no forces face \
(planmethod.forces.groups.rrr with reactions: Reactions)
    """
    if module is None:
        raise TypeError(f"group kind module planmethod.kinematics.groups.{kind.name}: no forces "
                        f"face ({__name__}.{kind.name} with reactions: Reactions)")
    problems: list[str] = []
    name = module.__name__.rpartition(".")[2]
    functions = protocol_functions(module, Reactions, problems)
    if kind is None:
        problems.append(f"no group kind module planmethod.kinematics.groups.{name}")
    elif functions is None:
        problems.append("defines no reactions (Reactions)")
    if problems:
        raise TypeError(f"forces face {module.__name__}: " + "; ".join(problems))
    return functions["reactions"]


# -- the registry -----------------------------------------------------------------------------
_REGISTRY: dict[str, ReactionSequence] | None = None
_LOCK = threading.Lock()


def _modules() -> Mapping[str, ModuleType]:
    """The face modules of this package, by name."""
    return face_modules(sys.modules[__name__])


def registered() -> dict[str, ReactionSequence]:
    """Each kind module's name with its reaction sequence, checked once (see the module
    docstring)."""
    global _REGISTRY
    with _LOCK:
        if _REGISTRY is None:
            kinds, modules = kinds_by_name(), _modules()
            found: dict[str, ReactionSequence] = {}
            problems = []
            for name in sorted(set(kinds) | set(modules)):
                try:
                    found[name] = describe(modules.get(name), kinds.get(name))
                except TypeError as error:
                    problems.append(str(error))
            if problems:
                raise TypeError("; ".join(problems))
            _REGISTRY = found
        return _REGISTRY


def reactions_of(group: AssurGroup) -> ReactionSequence:
    """The reaction sequence of ``group``'s kind."""
    return registered()[kind_module(group).name]
