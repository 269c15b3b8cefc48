"""The group kinds: one module per kind and layer, found by its kind, checked against one
interface per layer.

A group kind has a face in each layer that handles groups: its kinematics here, its plans in
:mod:`planmethod.plans.groups`, its reactions in :mod:`planmethod.forces.groups` — each a module
named as the kind's module here, each layer's protocol written in that layer (docs/
architecture.md, "Group kinds"). Each module of this package that defines ``KIND`` (a
:class:`~planmethod.vocabulary.GroupKind`) or ``KINDS`` (several) is a group kind, registered
when the package is first asked for one. Its kinematic face is written once, here, as
protocols:

* :class:`ClosedFormKind` — a dyad: ``BRANCHES`` (how many assemblies it has) and
  ``place(context)``, its closed-form positions and its two vector equations (see
  :mod:`~planmethod.kinematics.groups.dyad`); or
* :class:`IterativeKind` — a higher group: ``evaluate(context, level, model, branch)`` and
  ``choose(context, model)`` (Newton continued along the crank angle, see :mod:`.higher`);

and, optionally, :class:`Accepts` (``accepts(group)``: which groups of its kind it solves;
default every one) with ``PRIORITY`` (higher first).

When the registry loads the modules, :func:`describe` checks each one against the protocols —
every function present, callable with the protocol's arguments — and records what it found as a
:class:`KindModule`, which is what the solver and the later layers' registries call. A module
that breaks the interface is a :class:`TypeError` naming the module and what is wrong, at load.
:func:`protocol_functions` and :func:`face_modules` serve the later layers' registries alike.

Examples
--------
>>> sorted(str(kind) for kind in registered())
['PRP', 'RPP', 'RPR', 'RRP', 'RRR', 'tetrad', 'triad']
>>> rrr = registered()[GroupKind.RRR][0]
>>> rrr.name, rrr.closed_form, rrr.branches
('rrr', True, 2)
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import threading
from collections.abc import Callable
from dataclasses import dataclass
from types import ModuleType
from typing import Protocol

from ...errors import StructureError
from ...structure import AssurGroup
from ...vocabulary import GroupKind, group_kind_words
from ...words.message import message
from ..algebra import Body
from .base import Branch, GroupInputs, KindModel, SolvedGroup
from .dyad import Placed

__all__ = ["Accepts", "ClosedFormKind", "IterativeKind", "KindModule", "describe",
           "face_modules", "kind_module", "kinds_by_name", "protocol_functions", "registered"]


# -- the interface ----------------------------------------------------------------------------
class ClosedFormKind(Protocol):
    """A dyad kind: closed-form positions and the two vector equations, on ``BRANCHES`` (1 or 2)
    assemblies."""

    BRANCHES: int

    def place(self, context: GroupInputs) -> Placed: ...


class IterativeKind(Protocol):
    """A higher group kind: its links' motion by Newton continued from ``drive.angle``
    (``evaluate``), and its assembly there (``choose``)."""

    def evaluate(self, context: GroupInputs, level: int, model: KindModel,
                 branch: Branch) -> SolvedGroup: ...

    def choose(self, context: GroupInputs, model: KindModel) -> tuple[Branch, dict[str, Body]]: ...


class Accepts(Protocol):
    """Which groups of its kind a module solves (the first accepting module by ``PRIORITY``)."""

    def accepts(self, group: AssurGroup) -> bool: ...


@dataclass(frozen=True, eq=False)
class KindModule:
    """A group kind's module as the registry checked it (see the module docstring): its short
    ``name`` (that of its faces in the later layers too), the ``kinds`` it registers for, its
    ``priority``, and its functions — None where the module does not provide that part."""

    name: str
    kinds: tuple[GroupKind, ...]
    priority: int = 0
    accepts: Callable[[AssurGroup], bool] | None = None
    branches: int = 0
    place: Callable[[GroupInputs], Placed] | None = None
    evaluate: Callable[[GroupInputs, int, KindModel, Branch], SolvedGroup] | None = None
    choose: Callable[[GroupInputs, KindModel], tuple[Branch, dict[str, Body]]] | None = None

    @property
    def closed_form(self) -> bool:
        """Whether the kind is a closed-form dyad (else an iterative higher group)."""
        return self.place is not None

    def solves(self, group: AssurGroup) -> bool:
        """Whether the module solves ``group`` (one of its kinds, and accepted)."""
        return group.kind in self.kinds and (self.accepts is None or self.accepts(group))


def _arguments(protocol: type) -> dict[str, int]:
    """Each function of a protocol with the number of arguments it is called with."""
    return {name: len(inspect.signature(member).parameters) - 1
            for name, member in vars(protocol).items()
            if inspect.isfunction(member) and not name.startswith("_")}


def protocol_functions(module: ModuleType, protocol: type,
                       problems: list[str]) -> dict[str, Callable] | None:
    """The module's functions of ``protocol`` (None where it has none of them); a function
    missing beside the others, or one that cannot take the protocol's arguments, is added to
    ``problems``."""
    wanted = _arguments(protocol)
    present = {name: getattr(module, name) for name in wanted if hasattr(module, name)}
    if not present:
        return None
    for name, count in wanted.items():
        if name not in present:
            problems.append(f"defines {', '.join(sorted(present))} but not {name} "
                            f"({protocol.__name__})")
            continue
        function = present[name]
        try:
            inspect.signature(function).bind(*range(count))
        except (TypeError, ValueError):
            problems.append(f"{name} cannot be called with the {count} arguments of "
                            f"{protocol.__name__}.{name}")
    return present


def describe(module: ModuleType) -> KindModule:
    """Check a kind module against the interface and record what it provides.

    Raises
    ------
    TypeError
        Naming the module and each way it breaks the interface.

    Examples
    --------
    >>> from types import ModuleType
    >>> fake = ModuleType("planmethod.kinematics.groups.fake")
    >>> fake.KIND, fake.BRANCHES = "RRR", 2
    >>> describe(fake)
    Traceback (most recent call last):
    ...
    TypeError: group kind module planmethod.kinematics.groups.fake: defines neither place \
(ClosedFormKind) nor evaluate and choose (IterativeKind)
    """
    problems: list[str] = []
    declared = getattr(module, "KINDS", None) or (
        (module.KIND,) if hasattr(module, "KIND") else ())
    kinds = []
    for kind in declared:
        try:
            kinds.append(GroupKind(kind))
        except ValueError:
            problems.append(f"KIND {kind!r} is no GroupKind")
    if not declared:
        problems.append("defines neither KIND nor KINDS")
    closed = protocol_functions(module, ClosedFormKind, problems)
    iterative = protocol_functions(module, IterativeKind, problems)
    accepts = protocol_functions(module, Accepts, problems)
    branches = getattr(module, "BRANCHES", 0)
    if closed and iterative:
        problems.append("defines both place (ClosedFormKind) and evaluate/choose "
                        "(IterativeKind)")
    elif closed is None and iterative is None:
        problems.append("defines neither place (ClosedFormKind) nor evaluate and choose "
                        "(IterativeKind)")
    elif closed and branches not in (1, 2):
        problems.append(f"BRANCHES must be 1 or 2 for a closed-form kind, not {branches!r}")
    priority = getattr(module, "PRIORITY", 0)
    if not isinstance(priority, int):
        problems.append(f"PRIORITY must be a whole number, not {priority!r}")
    if problems:
        raise TypeError(f"group kind module {module.__name__}: " + "; ".join(problems))
    return KindModule(
        name=module.__name__.rpartition(".")[2], kinds=tuple(kinds), priority=priority,
        accepts=(accepts or {}).get("accepts"), branches=branches if closed else 0,
        place=(closed or {}).get("place"), evaluate=(iterative or {}).get("evaluate"),
        choose=(iterative or {}).get("choose"))


# -- the registry -----------------------------------------------------------------------------
_REGISTRY: dict[GroupKind, tuple[KindModule, ...]] | None = None
_LOCK = threading.Lock()


def _modules() -> list[ModuleType]:
    """The modules of this package that declare a kind."""
    out = []
    for info in pkgutil.iter_modules(__path__):
        module = importlib.import_module(f"{__name__}.{info.name}")
        if hasattr(module, "KIND") or hasattr(module, "KINDS"):
            out.append(module)
    return out


def registered() -> dict[GroupKind, tuple[KindModule, ...]]:
    """Every group kind with its modules, highest ``PRIORITY`` first (discovered and checked
    once)."""
    global _REGISTRY
    with _LOCK:
        if _REGISTRY is None:
            found: dict[GroupKind, list[KindModule]] = {}
            for module in _modules():
                described = describe(module)
                for kind in described.kinds:
                    found.setdefault(kind, []).append(described)
            _REGISTRY = {kind: tuple(sorted(modules, key=lambda m: -m.priority))
                         for kind, modules in found.items()}
        return _REGISTRY


def kind_module(group: AssurGroup) -> KindModule:
    """The kind module that solves ``group``.

    Raises
    ------
    StructureError
        If no module accepts a group of its kind and shape.
    """
    for module in registered().get(group.kind, ()):
        if module.solves(group):
            return module
    raise StructureError(message("no solver for a group of kind {kind} of this shape",
                                 kind=group_kind_words(group.kind)),
                         link=group.name)


def kinds_by_name() -> dict[str, KindModule]:
    """Every registered kind module by its name (the name of its faces in the later layers).

    >>> sorted(kinds_by_name())
    ['higher', 'prp', 'rpp', 'rpr', 'rrp', 'rrr', 'triad']
    """
    return {module.name: module for modules in registered().values() for module in modules}


def face_modules(package: ModuleType) -> dict[str, ModuleType]:
    """The face modules of a later layer's group-kind package (``planmethod.plans.groups``,
    ``planmethod.forces.groups``), by name: every module of it but ``base`` (what its faces
    are given) and private ones (``_…``) — each named as the kind's module here."""
    return {info.name: importlib.import_module(f"{package.__name__}.{info.name}")
            for info in pkgutil.iter_modules(package.__path__)
            if info.name != "base" and not info.name.startswith("_")}
