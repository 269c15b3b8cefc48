"""What a command prints: its lines, made of messages, in the language spoken.

Examples
--------
>>> say(message("Wrote {files}", files=["a.svg", "b.svg"]))
Wrote a.svg, b.svg
>>> wrote(["a.csv"], blank=False)
Wrote a.csv
"""

from __future__ import annotations

import sys
from collections.abc import Iterable

from ..words import Message, message, render

__all__ = ["note", "say", "wrote"]

#: the program's name, as its lines on the standard error begin
PROGRAM = "planmethod"


def say(*lines: Message | str, file=None) -> None:
    """Print ``lines`` (messages rendered in the language spoken, text as it is)."""
    print("\n".join(render(line) for line in lines), file=file or sys.stdout)


def note(text: Message | str) -> None:
    """A note on the standard error: ``planmethod: note: …``."""
    say(message("{program}: note: {note}", program=PROGRAM, note=text), file=sys.stderr)


def wrote(paths: Iterable[object], *, blank: bool = True) -> None:
    """``Wrote a, b`` for the files written (after a blank line, below a report), if any."""
    files = [str(path) for path in paths]
    if files:
        say(*([""] if blank else []), message("Wrote {files}", files=files))
