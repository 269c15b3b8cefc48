"""A group kind's plans face: how the plan emulator draws a group of that kind.

The plans layer's part of a group kind (:mod:`planmethod.kinematics.groups`) is the module of
this package named as the kind's module there: its plans face, ``draw_velocity(drawer, group)``
and ``draw_acceleration(drawer, group)`` (:class:`PlanDrawing`) — the construction the plan
emulator (:mod:`planmethod.plans.construction`) runs for a group of that kind, given the
emulator as a :class:`~planmethod.plans.groups.base.PlanDrawer`. A closed-form kind has no
face of its own: a dyad is drawn from its two vector equations (its
:class:`~planmethod.kinematics.groups.dyad.Construction`), the same for every dyad, by the
emulator itself.

When first asked (:func:`registered`), the registry checks every kind the kinematics registers
against this package, and every module of it against the kinds: an iterative kind without a
face, a face that lacks a function or cannot take the protocol's arguments, a face of a
closed-form kind or of no kind at all is a :class:`TypeError` naming the module and what is
wrong — at load, never in the middle of a drawing.

Examples
--------
>>> sorted(name for name, face in registered().items() if face is not None)
['higher', 'triad']
>>> registered()["rrr"] is None          # a dyad: drawn from its two vector equations
True
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable, Mapping
from types import ModuleType
from typing import NamedTuple, Protocol

from ...kinematics.groups import (
    KindModule,
    face_modules,
    kind_module,
    kinds_by_name,
    protocol_functions,
)
from ...structure import AssurGroup
from ...vocabulary import PlanKind
from .base import PlanDrawer

__all__ = ["PlanDrawing", "PlanFace", "describe", "plan_face", "registered"]


class PlanDrawing(Protocol):
    """A kind's plans face: its group drawn on the velocity plan, then on the acceleration
    plan (after the velocity plan of every group)."""

    def draw_velocity(self, drawer: PlanDrawer, group: AssurGroup) -> None: ...

    def draw_acceleration(self, drawer: PlanDrawer, group: AssurGroup) -> None: ...


class PlanFace(NamedTuple):
    """A kind's plans face as the registry checked it: the kind module's ``name`` and its two
    drawings."""

    name: str
    draw_velocity: Callable[[PlanDrawer, AssurGroup], None]
    draw_acceleration: Callable[[PlanDrawer, AssurGroup], None]

    def draw(self, plan: PlanKind, drawer: PlanDrawer, group: AssurGroup) -> None:
        """Draw ``group`` on ``plan`` (velocity or acceleration)."""
        drawing = self.draw_velocity if plan == PlanKind.VELOCITY else self.draw_acceleration
        drawing(drawer, group)


def describe(module: ModuleType | None, kind: KindModule | None) -> PlanFace | None:
    """Check the plans face ``module`` (None: the kind has none) of the kinematics' ``kind``
    (None: no kind of that name). Returns the face, or None for a closed-form kind.

    Raises
    ------
    TypeError
        Naming the module and each way it breaks the interface.

    Examples
    --------
    >>> from planmethod.kinematics.groups import kinds_by_name
    >>> describe(None, kinds_by_name()["triad"])
    Traceback (most recent call last):
    ...
    TypeError: group kind module planmethod.kinematics.groups.triad: no plans face \
(planmethod.plans.groups.triad with draw_velocity and draw_acceleration: PlanDrawing); only a \
closed-form kind is drawn from its two vector equations
    """
    if module is None:
        if kind is None or kind.closed_form:
            return None
        raise TypeError(f"group kind module {_kinematics(kind.name)}: no plans face "
                        f"({__name__}.{kind.name} with draw_velocity and draw_acceleration: "
                        "PlanDrawing); only a closed-form kind is drawn from its two vector "
                        "equations")
    problems: list[str] = []
    name = module.__name__.rpartition(".")[2]
    functions = protocol_functions(module, PlanDrawing, problems)
    if kind is None:
        problems.append(f"no group kind module {_kinematics(name)}")
    elif kind.closed_form:
        problems.append(f"{kind.name} is a closed-form kind: it is drawn from its two vector "
                        "equations, by no face of its own")
    elif functions is None:
        problems.append("defines neither draw_velocity nor draw_acceleration (PlanDrawing)")
    if problems:
        raise TypeError(f"plans face {module.__name__}: " + "; ".join(problems))
    return PlanFace(name, functions["draw_velocity"], functions["draw_acceleration"])


def _kinematics(name: str) -> str:
    return f"planmethod.kinematics.groups.{name}"


# -- the registry -----------------------------------------------------------------------------
_REGISTRY: dict[str, PlanFace | None] | None = None
_LOCK = threading.Lock()


def _modules() -> Mapping[str, ModuleType]:
    """The face modules of this package, by name."""
    return face_modules(sys.modules[__name__])


def registered() -> dict[str, PlanFace | None]:
    """Each kind module's name with its plans face (None: a dyad, drawn from its two vector
    equations), checked once (see the module docstring)."""
    global _REGISTRY
    with _LOCK:
        if _REGISTRY is None:
            kinds, modules = kinds_by_name(), _modules()
            found: dict[str, PlanFace | None] = {}
            problems = []
            for name in sorted(set(kinds) | set(modules)):
                try:
                    face = describe(modules.get(name), kinds.get(name))
                except TypeError as error:
                    problems.append(str(error))
                    continue
                if name in kinds:
                    found[name] = face
            if problems:
                raise TypeError("; ".join(problems))
            _REGISTRY = found
        return _REGISTRY


def plan_face(group: AssurGroup) -> PlanFace | None:
    """The plans face of ``group``'s kind (None: a dyad, drawn from its two vector
    equations)."""
    return registered()[kind_module(group).name]
