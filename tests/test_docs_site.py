"""The documentation site builds, offline, with every warning an error.

``python -m sphinx -W --keep-going -n`` on docs/: a broken link or reference, a page outside
the table of contents, or a function of the API reference whose docstring does not list its
parameters (numpydoc's validation) fails the build. Skipped, with the reason, where the ``docs``
extra is not installed (``pip install ".[docs]"``; the test extra has it too).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

for _package in ("sphinx", "myst_parser", "numpydoc"):
    pytest.importorskip(_package, reason=f"{_package} is not installed (pip install '.[docs]')")


def test_site_builds_with_warnings_as_errors(tmp_path):
    """The whole site, from a fresh environment, as contributing.md says to build it."""
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-n", "-q",
                           "-E", "-b", "html", "-d", str(tmp_path / "doctrees"), "docs",
                           str(tmp_path / "html")],
                          cwd=ROOT, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-6000:] + done.stdout[-2000:]
    assert (tmp_path / "html" / "api.html").exists()
    api = (tmp_path / "html" / "api.html").read_text(encoding="utf-8")
    assert "load_exercise" in api and "grade_answers" in api
