"""Shared fixtures: the project root and the reference mechanisms."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(autouse=True, scope="session")
def _run_from_root():
    """Doctests and tests name shipped exercises relative to the project root."""
    previous = os.getcwd()
    os.chdir(ROOT)
    yield
    os.chdir(previous)
