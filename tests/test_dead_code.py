"""No dead code: vulture (the ``dev`` and ``test`` extras) at 60 % confidence finds nothing in the
package beyond what ``vulture_whitelist.py`` keeps on purpose, and that list names only what
still exists. Skipped, with the reason, where vulture is not installed."""

from __future__ import annotations

import ast
import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
WHITELIST = ROOT / "vulture_whitelist.py"

needs_vulture = pytest.mark.skipif(importlib.util.find_spec("vulture") is None,
                                   reason="vulture is not installed (pip install vulture)")


def _vulture(*paths: Path) -> str:
    found = subprocess.run([sys.executable, "-m", "vulture", *map(str, paths),
                            "--min-confidence", "60"], capture_output=True, text=True,
                           cwd=ROOT, check=False)
    assert found.returncode in (0, 3), found.stderr     # 3: dead code found
    return found.stdout


@needs_vulture
def test_vulture_finds_no_dead_code_in_the_package():
    assert _vulture(ROOT / "planmethod", WHITELIST) == ""


@needs_vulture
def test_vulture_names_an_unused_function(tmp_path):
    (tmp_path / "probe.py").write_text("def used():\n    return 1\n\n\ndef forgotten():\n"
                                       "    return 2\n\n\nused()\n", encoding="utf-8")
    assert "unused function 'forgotten'" in _vulture(tmp_path / "probe.py")


def _defined(module: str, name: str) -> bool:
    """Whether ``module``'s source defines ``name`` (a function, a class, an assignment, or an
    attribute set on ``self``)."""
    source = Path(importlib.util.find_spec(module).origin).read_text(encoding="utf-8")
    return any(pattern in source for pattern in (f"def {name}(", f"class {name}", f"{name} =",
                                                   f"self.{name} ="))


def test_every_whitelisted_name_still_exists():
    tree = ast.parse(WHITELIST.read_text(encoding="utf-8"))
    imported = {alias.asname or alias.name: node.module
                for node in tree.body if isinstance(node, ast.ImportFrom)
                for alias in node.names}
    kept = [node.value for node in tree.body if isinstance(node, ast.Expr)
            and isinstance(node.value, ast.Attribute | ast.Name)]
    assert kept, "the whitelist names nothing"
    for reference in kept:
        if isinstance(reference, ast.Name):      # a name imported from its module
            module, name = imported[reference.id], reference.id
        else:                                   # an attribute of an imported class
            module, name = imported[reference.value.id], reference.attr
        assert _defined(module, name), (
            f"{ast.unparse(reference)} is gone: drop it from vulture_whitelist.py")


def test_a_whitelisted_name_that_is_gone_is_named():
    assert _defined("planmethod.kinematics.program", "compilations")
    assert _defined("planmethod.kinematics.motion", "velocity_of")
    assert not _defined("planmethod.kinematics.motion", "velocity_off")
