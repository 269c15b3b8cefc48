"""The package's import graph points one way: no module imports a higher layer, and no modules
import each other, directly or round a cycle.

Every module of ``planmethod`` is read with :mod:`ast` and every import in it is found — at
module level and inside functions, methods, classes, ``if TYPE_CHECKING:`` blocks and ``try``
blocks; ``import planmethod.x``, ``from planmethod.x import y``, ``from . import y``,
``from ..x import y`` and ``importlib.import_module("planmethod.x")`` with a constant name. An
import names the deepest module it reaches: ``from .groups import base`` is an import of
``…groups.base`` when that is a module, else of the package ``…groups``; importing a module does
not count as importing the packages above it. (An ``import_module`` with a computed name, as a
registry uses to load its own package's modules, cannot be seen.)

A failure names the file, the line and the two modules of each upward import, and the path of
each cycle with the file and line of each of its imports.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = "planmethod"

#: The layers, lowest first (docs/architecture.md, "Layers"): a module may import its own layer's
#: modules (without a cycle) and lower layers', never a higher layer's. A module's layer is
#: that of the first name under ``planmethod`` (``planmethod.kinematics.groups.rrr`` →
#: ``kinematics``); the package root ``planmethod/__init__.py`` is "".
LAYERS: dict[str, int] = {
    # 0: words and plumbing every layer may use
    "words": 0, "errors": 0, "vocabulary": 0, "io": 0, "progress": 0, "vectors": 0, "runs": 0,
    # 1: the frozen model; 2: reading exercise files into it
    "model": 1,
    "spec": 2,
    # 3: structural analysis and what a scene asks
    "structure": 3, "scene": 3,
    "numbering": 3,
    # 4: exact kinematics; 5: the plans; 6: kinetostatics
    "kinematics": 4,
    "plans": 5,
    "forces": 6,
    # 7: what is made of the results: reports, sweeps, drawings, grading
    "report": 7, "sweep": 7, "render": 7, "grading": 7, "convert": 7,
    # 8: the application layer: use cases with typed requests and results (the Python API)
    "application": 8,
    # 9: helpers for tests and benchmarks
    "testing": 9,
    # 10: the surfaces — the command line, the studio, the notebook — and the package root;
    # they call the application layer, never each other (a test below)
    "commands": 10, "cli": 10, "arguments": 10, "__main__": 10, "notebook": 10, "studio": 10,
    "": 10,
}


@dataclass(frozen=True)
class Source:
    """One module: its file (as reported), its text, and whether it is a package's
    ``__init__``."""

    path: str
    text: str
    package: bool = False


@dataclass(frozen=True)
class Import:
    """``module`` imports ``target`` at ``path``:``line``."""

    module: str
    target: str
    path: str
    line: int


def package_sources(root: Path = ROOT / PACKAGE, name: str = PACKAGE) -> dict[str, Source]:
    """Every module of the package under ``root``, by dotted name."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root).with_suffix("").parts
        package = parts[-1] == "__init__"
        dotted = ".".join((name, *(parts[:-1] if package else parts)))
        out[dotted] = Source(str(path.relative_to(root.parent)), path.read_text(encoding="utf-8"),
                             package)
    return out


def layer_of(module: str) -> int | None:
    """The layer of a module of the package, or None if the table does not name it."""
    parts = module.split(".")
    return LAYERS.get(parts[1] if len(parts) > 1 else "")


def _deepest(name: str, modules: Mapping[str, Source]) -> str | None:
    """The longest dotted prefix of ``name`` that is a module of the package."""
    parts = name.split(".")
    for end in range(len(parts), 0, -1):
        if ".".join(parts[:end]) in modules:
            return ".".join(parts[:end])
    return None


def _ours(name: str) -> bool:
    return name == PACKAGE or name.startswith(PACKAGE + ".")


def imports_of(module: str, modules: Mapping[str, Source]) -> Iterator[Import]:
    """Every import of a module of the package in ``module``, wherever it is written."""
    source = modules[module]
    here = module if source.package else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(source.text, filename=source.path)):
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names if _ours(alias.name)]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here.rsplit(".", node.level - 1)[0] if node.level > 1 else here
                base = f"{base}.{node.module}" if node.module else base
            else:
                base = node.module or ""
            if _ours(base):
                targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base
                           for alias in node.names]
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "import_module" and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)
              and _ours(node.args[0].value)):
            targets = [node.args[0].value]
        for target in targets:
            found = _deepest(target, modules)
            if found is not None and found != module:
                yield Import(module, found, source.path, node.lineno)


def _cycles(edges: Mapping[str, Mapping[str, Import]]) -> list[list[Import]]:
    """One shortest cycle through every import that lies on a cycle, without repeats."""
    found: dict[tuple[str, ...], list[Import]] = {}
    for first, targets in sorted(edges.items()):
        for second, opening in sorted(targets.items()):
            # the shortest way back from second to first (breadth first)
            previous: dict[str, Import | None] = {second: None}
            frontier = [second]
            while frontier and first not in previous:
                following = []
                for node in frontier:
                    for nxt, edge in sorted(edges.get(node, {}).items()):
                        if nxt not in previous:
                            previous[nxt] = edge
                            following.append(nxt)
                frontier = following
            if first not in previous:
                continue
            path, node = [], first
            while previous[node] is not None:
                path.append(previous[node])
                node = previous[node].module
            cycle = [opening, *reversed(path)]
            names = [edge.module for edge in cycle]
            turn = names.index(min(names))
            key = tuple(names[turn:] + names[:turn])
            found.setdefault(key, cycle[turn:] + cycle[:turn])
    return [found[key] for key in sorted(found)]


def problems(modules: Mapping[str, Source]) -> list[str]:
    """What breaks the layering: modules without a layer, imports of a higher layer, and
    cycles; one line each (a cycle: its path, with where each import is written)."""
    out = [f"{source.path}: {module} has no layer (add it to LAYERS in tests/test_layers.py)"
           for module, source in sorted(modules.items()) if layer_of(module) is None]
    edges: dict[str, dict[str, Import]] = {}
    for module in sorted(modules):
        for found in imports_of(module, modules):
            edges.setdefault(module, {}).setdefault(found.target, found)
            low, high = layer_of(module), layer_of(found.target)
            if low is not None and high is not None and high > low:
                out.append(f"{found.path}:{found.line}: {module} (layer {low}) imports "
                           f"{found.target} (layer {high}), a higher layer")
    for cycle in _cycles(edges):
        steps = " → ".join(f"{edge.target} ({edge.path}:{edge.line})" for edge in cycle)
        out.append(f"import cycle: {cycle[0].module} → {steps}")
    return out


# -- the package ---------------------------------------------------------------------------------
def test_the_package_imports_downward_only_and_without_cycles():
    found = problems(package_sources())
    assert not found, "\n" + "\n".join(found)


#: the surfaces that call the application layer and never each other: the command line's
#: commands, the studio, the notebook
SURFACES = ("commands", "studio", "notebook")


def surface_crossings(modules: Mapping[str, Source]) -> list[str]:
    """Every import of one surface by another (the commands of the studio, the studio of a
    command…): each calls the application layer instead. One line each."""
    def surface(module: str) -> str | None:
        parts = module.split(".")
        return parts[1] if len(parts) > 1 and parts[1] in SURFACES else None

    out = []
    for module in sorted(modules):
        for found in imports_of(module, modules):
            here, there = surface(module), surface(found.target)
            if here and there and here != there:
                out.append(f"{found.path}:{found.line}: {module} imports {found.target}: "
                           "surfaces call the application layer, never each other")
    return out


def test_the_surfaces_call_the_application_layer_not_each_other():
    modules = package_sources()
    assert surface_crossings(modules) == []
    # the application layer is in place, below every surface and above what it uses
    assert layer_of("planmethod.application.workbook") == 8
    assert all(layer_of(f"planmethod.{name}") > 8 for name in SURFACES)
    assert max(LAYERS[name] for name in ("report", "render", "grading")) < 8
    users = {[*found.module.split("."), ""][1] for module in modules
             for found in imports_of(module, modules)
             if found.target.startswith("planmethod.application")}
    assert {"commands", "studio", "notebook"} <= users


def test_a_surface_importing_another_is_named():
    modules = _package({"commands__init": "", "commands__solve": "",
                        "studio__init": "", "studio__api": "from ..commands import solve\n"},
                       **CLEAN)
    assert surface_crossings(modules) == [
        "planmethod/studio/api.py:1: planmethod.studio.api imports "
        "planmethod.commands.solve: surfaces call the application layer, never each other"]


def test_every_module_of_the_package_is_read():
    modules = package_sources()
    assert {"planmethod", "planmethod.kinematics.constraints", "planmethod.testing.oracles",
            "planmethod.__main__"} <= set(modules)
    assert len(modules) == len(list((ROOT / PACKAGE).rglob("*.py")))


# -- the checker can fail ------------------------------------------------------------------------
def _package(*changes: dict, **texts: str) -> dict[str, Source]:
    """A synthetic package: dotted name (with ``__`` for ``.``, ``init`` for a package's
    ``__init__``) → source text; ``changes`` replace or add texts."""
    for change in changes:
        texts = {**texts, **change}
    out = {}
    for key, text in texts.items():
        parts = key.split("__")
        package = parts[-1] == "init"
        name = ".".join([PACKAGE, *(parts[:-1] if package else parts)]).rstrip(".")
        path = "/".join([PACKAGE, *parts[:-1], "__init__.py"] if package
                        else [PACKAGE, *parts[:-1], parts[-1] + ".py"])
        out[name] = Source(path, text, package)
    return out


CLEAN = dict(
    init="",
    errors="",
    model="from .errors import SpecError\n",
    kinematics__init="from .solve import solve\n",
    kinematics__solve="from ..model import Mechanism\nfrom . import state\n",
    kinematics__state="import numpy as np\n",
    plans__init="",
    plans__construction=("def draw():\n    import planmethod.kinematics.solve as s\n"
                         "    from planmethod.kinematics import state\n"),
    render__init="",
    render__svg="import svgwrite\n",
    cli="import importlib\nimportlib.import_module('planmethod.plans.construction')\n",
)


def test_a_clean_package_passes():
    assert problems(_package(**CLEAN)) == []


def test_every_form_of_import_is_seen():
    modules = _package(**CLEAN)
    seen = {(i.module, i.target, i.line) for name in modules for i in imports_of(name, modules)}
    assert seen == {
        ("planmethod.model", "planmethod.errors", 1),
        ("planmethod.kinematics", "planmethod.kinematics.solve", 1),
        ("planmethod.kinematics.solve", "planmethod.model", 1),
        ("planmethod.kinematics.solve", "planmethod.kinematics.state", 2),
        ("planmethod.plans.construction", "planmethod.kinematics.solve", 2),
        ("planmethod.plans.construction", "planmethod.kinematics.state", 3),
        ("planmethod.cli", "planmethod.plans.construction", 2),
    }


def test_an_upward_import_in_a_function_is_named():
    modules = _package({"model": "from .errors import SpecError\n\n"
                                 "def place():\n    from .render import svg\n"},
                       **CLEAN)
    assert problems(modules) == [
        "planmethod/model.py:4: planmethod.model (layer 1) imports "
        "planmethod.render.svg (layer 7), a higher layer"]


def test_an_upward_import_under_type_checking_is_named():
    modules = _package({"kinematics__state": "from typing import TYPE_CHECKING\n"
                                             "if TYPE_CHECKING:\n"
                                             "    from planmethod.render.svg import Canvas\n"},
                       **CLEAN)
    assert problems(modules) == [
        "planmethod/kinematics/state.py:3: planmethod.kinematics.state (layer 4) imports "
        "planmethod.render.svg (layer 7), a higher layer"]


def test_a_cycle_is_named_with_its_path():
    modules = _package({"kinematics__state": "class State:\n    def solve(self):\n"
                                             "        from .solve import solve\n"},
                       **CLEAN)
    assert problems(modules) == [
        "import cycle: planmethod.kinematics.solve → planmethod.kinematics.state "
        "(planmethod/kinematics/solve.py:2) → planmethod.kinematics.solve "
        "(planmethod/kinematics/state.py:3)"]


def test_a_longer_cycle_through_a_package_is_named():
    modules = _package({"errors": "from . import model\n",
                        "kinematics__state": "from .. import errors\n"}, **CLEAN)
    found = problems(modules)
    assert "import cycle: planmethod.errors → planmethod.model (planmethod/errors.py:1) → " \
           "planmethod.errors (planmethod/model.py:1)" in found
    assert "planmethod/errors.py:1: planmethod.errors (layer 0) imports planmethod.model " \
           "(layer 1), a higher layer" in found
    assert len(found) == 2


def test_a_module_without_a_layer_is_named():
    modules = _package({"widgets": ""}, **CLEAN)
    assert problems(modules) == [
        "planmethod/widgets.py: planmethod.widgets has no layer (add it to LAYERS in "
        "tests/test_layers.py)"]


# -- kinds are enums ---------------------------------------------------------------------------
def string_kind_comparisons(root: Path) -> list[str]:
    """Every comparison of a ``kind`` (a name or an attribute so called) with a string literal:
    kinds are enums or registry keys (vocabulary.py), not strings compared in ``if`` chains."""
    found = []
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if not isinstance(node, ast.Compare):
                continue
            sides = [node.left, *node.comparators]
            named = any((isinstance(side, ast.Name) and side.id == "kind")
                        or (isinstance(side, ast.Attribute) and side.attr == "kind")
                        for side in sides)
            literal = any((isinstance(side, ast.Constant) and isinstance(side.value, str))
                          or (isinstance(side, ast.Tuple | ast.List | ast.Set) and any(
                              isinstance(item, ast.Constant) and isinstance(item.value, str)
                              for item in side.elts))
                          for side in sides)
            if named and literal:
                found.append(f"{path.relative_to(root.parent)}:{node.lineno}: "
                             f"{ast.unparse(node)}")
    return found


def test_no_kind_is_a_string_compared():
    assert string_kind_comparisons(ROOT / PACKAGE) == []


def test_a_string_kind_comparison_is_named(tmp_path):
    package = tmp_path / PACKAGE
    package.mkdir()
    (package / "probe.py").write_text('def f(edge):\n    return edge.kind == "component"\n',
                                      encoding="utf-8")
    assert string_kind_comparisons(package) == [
        'planmethod/probe.py:2: edge.kind == "component"'.replace('"', "'")]


# -- each concept written once -------------------------------------------------------------------
#: the planar-vector helpers of planmethod.vectors, by name (with or without a leading _)
VECTOR_HELPERS = {"angle_deg", "cross", "dot", "norm", "perp", "rotate", "turn_onto", "unit",
                  "unit_angle", "unit_or_zero"}
#: where they may be defined: the one module, and the tracer's symbolic Vec (its own type)
VECTOR_HOMES = {"planmethod/vectors.py", "planmethod/kinematics/algebra.py"}


def vector_helper_copies(root: Path) -> list[str]:
    """Every function (not a method) named like a planar-vector helper outside its homes."""
    found = []
    for path in sorted(root.rglob("*.py")):
        where = str(path.relative_to(root.parent))
        if where in VECTOR_HOMES:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        methods = {id(item) for node in ast.walk(tree) if isinstance(node, ast.ClassDef)
                   for item in node.body}
        for node in ast.walk(tree):
            if (isinstance(node, ast.FunctionDef) and id(node) not in methods
                    and node.name.lstrip("_") in VECTOR_HELPERS):
                found.append(f"{where}: {node.name}")
    return found


def private_imports(root: Path) -> list[str]:
    """Every import of another module's private name (``from .x import _name``)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or node.module == "__future__":
                continue
            if not (node.level or _ours(node.module or "")):
                continue
            for alias in node.names:
                if alias.name.startswith("_") and not alias.name.startswith("__"):
                    found.append(f"{path.relative_to(root.parent)}:{node.lineno}: "
                                 f"{alias.name} from {'.' * node.level}{node.module or ''}")
    return found


def test_no_planar_vector_helper_is_written_outside_planmethod_vectors():
    assert vector_helper_copies(ROOT / PACKAGE) == []


def test_no_module_imports_another_modules_private_names():
    assert private_imports(ROOT / PACKAGE) == []


def test_a_vector_helper_copy_and_a_private_import_are_named(tmp_path):
    package = tmp_path / PACKAGE
    (package / "kinematics").mkdir(parents=True)
    (package / "vectors.py").write_text("def perp(a):\n    return a\n", encoding="utf-8")
    (package / "kinematics" / "probe.py").write_text(
        "from ..vocabulary import _SUBSCRIPT, symbol\n"
        "from planmethod.spec import _suggest\n\n"
        "def _unit(v):\n    def dot(a, b):\n        return 0\n    return v\n\n"
        "class System:\n    def norm(self, dq):\n        return dq\n",
        encoding="utf-8")
    assert vector_helper_copies(package) == ["planmethod/kinematics/probe.py: _unit",
                                             "planmethod/kinematics/probe.py: dot"]
    assert private_imports(package) == [
        "planmethod/kinematics/probe.py:1: _SUBSCRIPT from ..vocabulary",
        "planmethod/kinematics/probe.py:2: _suggest from planmethod.spec"]
