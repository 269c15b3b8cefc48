"""The group kinds: one module per kind, found by its kind.

Each module of this package that defines ``KIND`` (a :class:`~planmethod.vocabulary.GroupKind`)
is a group kind, registered when the package is first asked for one — adding a kind means adding
one module here (and its test), nothing else. A dyad kind defines ``BRANCHES`` (how many
assemblies it has) and ``place(context)``: its closed-form positions and its two vector
equations (see :mod:`~planmethod.kinematics.groups.base`); a higher kind defines
``evaluate(context, level)`` and ``assemblies(context)``. A module may also define
``accepts(group)`` (default: every group of its kind) and ``PRIORITY`` (higher first), and
``reactions(solver, group)`` and ``draw(drawer, group, plan)``, the textbook sequences the force
analysis and the plan emulator run for it.

Examples
--------
>>> from planmethod.vocabulary import GroupKind
>>> sorted(str(kind) for kind in registered())
['PRP', 'RPP', 'RPR', 'RRP', 'RRR', 'tetrad', 'triad']
"""

from __future__ import annotations

import importlib
import pkgutil
import threading
from types import ModuleType

from ...errors import StructureError
from ...structure import AssurGroup
from ...vocabulary import GroupKind

__all__ = ["kind_module", "registered"]

_REGISTRY: dict[GroupKind, list[ModuleType]] = {}
_LOCK = threading.Lock()


def registered() -> dict[GroupKind, list[ModuleType]]:
    """Every group kind with its modules (discovered once)."""
    with _LOCK:
        if not _REGISTRY:
            for info in pkgutil.iter_modules(__path__):
                module = importlib.import_module(f"{__name__}.{info.name}")
                kinds = getattr(module, "KINDS", None) or (
                    (module.KIND,) if hasattr(module, "KIND") else ())
                for kind in kinds:
                    _REGISTRY.setdefault(GroupKind(kind), []).append(module)
            for modules in _REGISTRY.values():
                modules.sort(key=lambda m: -getattr(m, "PRIORITY", 0))
        return _REGISTRY


def kind_module(group: AssurGroup) -> ModuleType:
    """The module that solves ``group``.

    Raises
    ------
    StructureError
        If no module accepts a group of its kind and shape.
    """
    for module in registered().get(group.kind, ()):
        accepts = getattr(module, "accepts", None)
        if accepts is None or accepts(group):
            return module
    raise StructureError(f"no solver for a group of kind {group.kind!s} of this shape",
                         link=group.name)
