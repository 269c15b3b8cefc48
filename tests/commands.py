"""What tests share to run the command line: :func:`cli`, ``planmethod ARGV…`` in a process of
its own from the project's root."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def cli(*argv, check: bool = True) -> subprocess.CompletedProcess:
    """``planmethod ARGV…`` run from the project's root (its output captured as text); fails
    the test on a non-zero exit unless ``check`` is False."""
    return subprocess.run([sys.executable, "-m", "planmethod", *map(str, argv)], cwd=ROOT,
                          capture_output=True, text=True, check=check)
