"""How a long use case tells its progress and is cancelled.

A long use case (a workbook's frames, a class's variants, a teaching run) is given a
:class:`Watch`: it calls :meth:`Watch.step` after each step of work with the phase it is in
and how far it is; the watch tells its caller (a progress bar on a terminal, a job's line to
the studio's page, a notebook's widget) and, if the caller has asked to stop
(:meth:`Watch.cancel`), ends the use case there with :class:`CancelledError`, nothing written.

Examples
--------
>>> seen = []
>>> watch = Watch(lambda phase, done, total: seen.append((phase, done, total)))
>>> watch.step("variants", 1, 3)
>>> seen
[('variants', 1, 3)]
>>> watch.cancel()
>>> watch.step("variants", 2, 3)
Traceback (most recent call last):
...
planmethod.application.tasks.CancelledError: cancelled
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field

from ..words import message, render

__all__ = ["CancelledError", "Tell", "Watch"]

#: what a use case tells of its progress: (the phase, steps done, steps in all)
Tell = Callable[[str, int, int], None]


class CancelledError(Exception):
    """A use case stopped because its caller asked it to (:meth:`Watch.cancel`)."""

    def __init__(self) -> None:
        super().__init__(render(message("cancelled")))


@dataclass(frozen=True)
class Watch:
    """What a long use case reports its progress to and takes its cancel from: ``tell``
    (optional) hears each step; :meth:`cancel`, from any thread, stops the use case at its
    next step."""

    tell: Tell | None = None
    _stop: threading.Event = field(default_factory=threading.Event, repr=False,
                                   compare=False)

    def step(self, phase: str, done: int, total: int) -> None:
        """One more step done: tell it, or end the use case if it was cancelled."""
        if self._stop.is_set():
            raise CancelledError
        if self.tell is not None:
            self.tell(phase, done, total)

    def cancel(self) -> None:
        """Ask the use case to stop at its next step."""
        self._stop.set()

    @property
    def cancelled(self) -> bool:
        """Whether :meth:`cancel` was called."""
        return self._stop.is_set()
