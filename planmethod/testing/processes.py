"""The processes a command left: for tests and benchmarks of worker pools that must end with
their parent.

Examples
--------
>>> processes_holding("no-such-marker-in-any-command-line-8f3a")
[]
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["processes_holding"]


def processes_holding(marker: str) -> list[int]:
    """The live processes (zombies aside) whose command line holds ``marker`` — a forked
    worker keeps its parent's command line, so a marker in the command's arguments (an output
    path) finds the command and its workers. Empty where there is no ``/proc``.

    Parameters
    ----------
    marker
        Text to look for in each process's command line.
    """
    found = []
    root = Path("/proc")
    if not root.is_dir():
        return found
    for entry in root.iterdir():
        if entry.name.isdigit():
            try:
                command = (entry / "cmdline").read_bytes()
                state = (entry / "stat").read_text().rsplit(")", 1)[1].split()[0]
            except (OSError, IndexError):
                continue
            if marker.encode() in command and state != "Z":
                found.append(int(entry.name))
    return found
