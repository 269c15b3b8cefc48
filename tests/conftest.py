"""Shared fixtures, and the suite's tiers.

Every test belongs to one tier, given as a marker when the suite is collected (so that a new
test file needs no marker of its own): ``docs`` (the documentation's examples and site),
``browser`` (headless Chromium), ``cli`` (the command line and the studio, run as a user runs
them, in processes of their own) and ``unit`` (everything else, the modules' doctests too).
docs/contributing.md ("Test tiers") gives the command of each; the inner loop is
``python -m pytest -m "not docs and not browser" -n 2``.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: the test files of the ``docs`` and ``cli`` tiers (``browser`` tests carry their marker)
TIERS: dict[str, str] = {
    "test_docs_examples.py": "docs", "test_docs_site.py": "docs", "test_docs_answers.py": "docs",
    "test_cli.py": "cli", "test_hostile_commands.py": "cli", "test_hostile_outputs.py": "cli",
    "test_forces_cli.py": "cli", "test_studio.py": "cli", "test_words.py": "cli",
    "test_russian_runs.py": "cli",
}
TIER_NAMES = ("unit", "cli", "docs", "browser")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Give each test its tier's marker: ``browser`` where it has that marker, else the one
    its file is listed with in :data:`TIERS`, else ``unit``."""
    for item in items:
        if item.get_closest_marker("browser") is not None:
            continue
        tier = TIERS.get(item.path.name, "unit")
        item.add_marker(getattr(pytest.mark, tier))


@pytest.fixture(autouse=True, scope="session")
def _run_from_root():
    """Doctests and tests name shipped exercises relative to the project root."""
    previous = os.getcwd()
    os.chdir(ROOT)
    yield
    os.chdir(previous)
