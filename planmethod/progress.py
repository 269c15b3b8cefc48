"""A small progress bar on stderr for long runs (silent when stderr is not a terminal), and
the same steps told to a callback (the studio's jobs show them in the page).

Examples
--------
>>> with Progress(3, "sweep", enabled=False) as bar:
...     for _ in range(3):
...         bar.advance()
>>> seen = []
>>> with Progress(2, "variants", enabled=False,
...               on_advance=lambda done, total: seen.append((done, total))) as bar:
...     bar.advance(); bar.advance()
>>> seen
[(1, 2), (2, 2)]
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

from .words.message import Message, message
from .words.render import render


class Progress:
    """``with Progress(total, label) as bar: bar.advance(n)``; ``on_advance(done, total)`` is
    called at every step, whether the bar is drawn or not. ``label`` says what runs (a
    command's name, or a message)."""

    def __init__(self, total: int, label: str | Message, *, enabled: bool | None = None,
                 stream=None, on_advance: Callable[[int, int], None] | None = None) -> None:
        self.total = max(int(total), 1)
        self.label = label
        self.stream = stream or sys.stderr
        self.enabled = (self.stream.isatty() if enabled is None else enabled)
        self.done = 0
        self.started = time.perf_counter()
        self._last = 0.0
        self.on_advance = on_advance

    def __enter__(self) -> Progress:
        self._draw(force=True)
        return self

    def advance(self, count: int = 1) -> None:
        self.done = min(self.total, self.done + count)
        if self.on_advance is not None:
            self.on_advance(self.done, self.total)
        self._draw()

    def _draw(self, force: bool = False) -> None:
        if not self.enabled:
            return
        now = time.perf_counter()
        if not force and now - self._last < 0.1 and self.done < self.total:
            return
        self._last = now
        width = 30
        filled = int(width * self.done / self.total)
        elapsed = now - self.started
        rate = self.done / elapsed if elapsed > 0 else 0.0
        eta = (self.total - self.done) / rate if rate > 0 else 0.0
        line = message("{label} [{bar}] {done}/{total}  {elapsed:5.1f}s  eta {eta:5.1f}s",
                       label=self.label, bar="#" * filled + "." * (width - filled),
                       done=self.done, total=self.total, elapsed=elapsed, eta=eta)
        self.stream.write("\r" + render(line))
        self.stream.flush()

    def __exit__(self, *_exc) -> None:
        if self.enabled:
            self._draw(force=True)
            self.stream.write("\n")
            self.stream.flush()
