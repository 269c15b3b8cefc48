"""Every file the package reads at run time is shipped: a non-Python file under
``planmethod/`` that ``[tool.setuptools.package-data]`` does not name is missing from a wheel,
so ``pip install .`` (not editable) would fail where the checkout works (the workbook's
drawing script was once left out this way)."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "planmethod"


def test_every_data_file_of_the_package_is_declared():
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    patterns = declared["tool"]["setuptools"]["package-data"]["planmethod"]
    shipped = {path for pattern in patterns for path in PACKAGE.glob(pattern)}
    data = {path for path in PACKAGE.rglob("*")
            if path.is_file() and path.suffix not in (".py", ".pyc")
            and "__pycache__" not in path.parts}
    assert data, "no data files found: the test would prove nothing"
    missing = sorted(str(path.relative_to(ROOT)) for path in data - shipped)
    assert not missing, f"not in package-data (so not in a wheel): {missing}"
