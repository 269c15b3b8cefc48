"""Worker processes for a use case that solves many independent things (a workbook's
frames): bounded by the CPUs this process may use, and ending with their parent however it
ends.

Examples
--------
>>> usable_cpus() >= 1
True
>>> worker_count(None, 1), worker_count(1, 100)
(1, 1)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from ..errors import SpecError
from ..words import message

__all__ = ["in_workers", "usable_cpus", "worker_count"]


def usable_cpus() -> int:
    """The CPUs this process may run on (its CPU affinity, where the system tells it).

    >>> usable_cpus() >= 1
    True
    """
    import os

    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0)) or 1
    return os.cpu_count() or 1


def worker_count(jobs: int | None, frames: int) -> int:
    """Worker processes for ``frames`` frames: ``jobs`` (1 … the usable CPUs, else a
    :class:`SpecError`), by default every CPU with at least 12 frames each; never more than
    there are frames.

    >>> worker_count(None, 1), worker_count(1, 100)
    (1, 1)
    >>> worker_count(100_000, 4)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: option --jobs: must be a number of processes in 1…...
    """
    cpus = usable_cpus()
    if jobs is None:
        return max(1, min(cpus, frames // 12))
    if not 1 <= jobs <= cpus:
        raise SpecError(message("must be a number of processes in 1…{cpus} (the CPUs this "
                                "process may use), got {jobs}", cpus=cpus, jobs=jobs),
                        key="option --jobs")
    return max(1, min(jobs, frames))


def _end_with_parent(parent: int | None) -> None:
    """A worker's first act: end with the process that started it. SIGTERM ends it at once
    (not through the command's handler, which a pool worker would report and go on), Ctrl-C
    is left to the parent, and on Linux the kernel kills it when its parent ends, even by
    SIGKILL (``prctl(PR_SET_PDEATHSIG)``)."""
    import contextlib
    import os
    import signal
    import sys

    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        import ctypes

        set_parent_death_signal = 1   # PR_SET_PDEATHSIG of <linux/prctl.h>
        with contextlib.suppress(OSError, AttributeError):   # no libc or no prctl
            ctypes.CDLL(None, use_errno=True).prctl(set_parent_death_signal,
                                                    int(signal.SIGKILL), 0, 0, 0)
    if parent is not None and os.getppid() != parent:   # the parent ended before that
        os._exit(1)


def _start_worker(parent: int | None, setup: Callable[..., None] | None,
                  arguments: tuple) -> None:
    """A worker's first acts: end with its parent, then ``setup(*arguments)`` if given."""
    _end_with_parent(parent)
    if setup is not None:
        setup(*arguments)


def in_workers(function: Callable[[Any], Any], jobs: Sequence[Any], workers: int,
               each: Callable[[Any], None], *, setup: Callable[..., None] | None = None,
               arguments: tuple = (), fork: bool = True) -> None:
    """``function`` of every job, computed in ``workers`` processes and handed to ``each``
    in the jobs' order. The pool is terminated whenever this ends — done, failed, cancelled
    (``each`` raising), Ctrl-C or SIGTERM (the command line turns it into an exception
    here) — so that no worker outlives its caller. ``function`` (and ``setup``, which each
    worker calls once with ``arguments`` before its first job: what every job shares) must
    be a module's function (the workers receive it by name). The workers are forked on
    Linux unless ``fork`` is false (a library whose threads do not survive a fork already
    runs here): then they are started afresh, and still end with this process."""
    import multiprocessing
    import os
    import sys

    linux = sys.platform.startswith("linux")
    # fork on Linux: the workers are this process's children (the parent check above holds)
    method = "fork" if linux and fork else "spawn" if linux else None
    context = multiprocessing.get_context(method)
    parent = os.getpid() if linux else None
    with context.Pool(min(workers, len(jobs)), initializer=_start_worker,
                      initargs=(parent, setup, arguments)) as pool:   # leaving it ends them
        for done in pool.imap(function, jobs):
            each(done)


#: the most items in one chunk: a worker that ends its last chunk early waits for the
#: others at most that long (a workbook's frames: a second or two of the conveyor's)
CHUNK_LIMIT = 8


def chunked(items: Sequence[Any], workers: int) -> list[Sequence[Any]]:
    """``items`` in at least four chunks per worker, in order, of at most
    :data:`CHUNK_LIMIT` items each.

    >>> chunked(list(range(10)), 1)
    [[0, 1, 2], [3, 4, 5], [6, 7, 8], [9]]
    >>> [len(chunk) for chunk in chunked(list(range(40)), 2)]
    [5, 5, 5, 5, 5, 5, 5, 5]
    >>> [len(chunk) for chunk in chunked(range(360), 2)][:3], len(chunked(range(360), 2))
    ([8, 8, 8], 45)
    """
    size = min(math.ceil(len(items) / (4 * workers)), CHUNK_LIMIT)
    return [items[start:start + size] for start in range(0, len(items), size)]
