"""A job's process (:mod:`planmethod.studio.jobs`): ``python -P -m planmethod.studio.worker``.

It reads its task, one JSON line ``{"kind": "variants" | "export", "arguments": …,
"language": …, "staging": …}``, from its standard input, does it with :mod:`planmethod.studio.api`
(:func:`~planmethod.studio.api.run_variants`, :func:`~planmethod.studio.api.run_export`) and
writes JSON lines to its standard output: ``{"progress": {"phase", "done", "total"}}`` as it
goes, then ``{"result": …}`` or ``{"error": {"error", "kind"}}`` (one line, as a refused
request's). Nothing else reaches that output: what a library might print goes nowhere.

It ends when its standard input closes — the studio closes it, and the system does when the
studio ends however it ends (killed too) — so a job never outlives its studio, and removes the
folder it was writing. It ignores
Ctrl-C: the studio, which receives it, stops its jobs.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import sys
import threading
import warnings
from pathlib import Path
from typing import IO, Any

#: the longest task line read (bytes): a drawing's TOML and its template, both bounded by the
#: studio's body limit
MAX_TASK = 8_000_000


def _lifeline(staging: str | None) -> None:
    """End the process when its standard input closes (the studio is gone), removing the
    folder it was writing (the studio, killed, cannot)."""
    try:   # the descriptor itself: no lock of sys.stdin held at the process's end
        while os.read(0, 65536):
            pass
    finally:
        if staging is not None:
            shutil.rmtree(staging, ignore_errors=True)
        os._exit(1)


def _channel() -> IO[bytes]:
    """The standard output, for the messages only; file descriptor 1 then leads nowhere."""
    channel = os.fdopen(os.dup(1), "wb")
    nowhere = os.open(os.devnull, os.O_WRONLY)
    os.dup2(nowhere, 1)
    os.close(nowhere)
    sys.stdout = open(os.devnull, "w", encoding="utf-8")   # noqa: SIM115 - for the process's life
    return channel


def _prepare() -> None:
    """Import what a job needs, before its task comes (a process may be started ahead of its
    job: :meth:`planmethod.studio.jobs.Jobs.warm`)."""
    import importlib

    for module in ("planmethod.studio.api", "planmethod.application.variants",
                   "planmethod.application.exporting", "planmethod.grading.exports",
                   "planmethod.grading.keys", "planmethod.grading.sheets",
                   "planmethod.grading.templates", "planmethod.kinematics", "planmethod.plans",
                   "planmethod.render.workbook", "planmethod.spec", "svgwrite"):
        importlib.import_module(module)


def run(task: dict[str, Any], tell) -> dict[str, Any]:
    """Do ``task``, telling its progress with ``tell(message)``; its result."""
    from . import api

    def progress(phase: str, done: int, total: int) -> None:
        tell({"progress": {"phase": phase, "done": done, "total": total}})

    runs = {"variants": lambda arguments: api.run_variants(arguments, progress),
            "export": lambda arguments: api.run_export(arguments, Path(task["staging"]),
                                                       progress)}
    return runs[task["kind"]](task["arguments"])


def main() -> int:
    """Read the task, do it, say how it ended, and end with status 0 (every failure is a
    message)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    channel = _channel()

    def tell(message: dict[str, Any]) -> None:
        channel.write(json.dumps(message, ensure_ascii=False, allow_nan=False).encode() + b"\n")
        channel.flush()

    _prepare()
    line = sys.stdin.buffer.readline(MAX_TASK)
    if not line:   # the studio ended before it had a task for this process
        return 0
    task = json.loads(line)
    threading.Thread(target=_lifeline, args=(task.get("staging"),), daemon=True,
                     name="planmethod-lifeline").start()
    from ..words import speaking

    with speaking(task.get("language")):
        _do(task, tell)
    os._exit(0)   # said and flushed: nothing is left to finish (the lifeline still reads)


def _do(task: dict[str, Any], tell) -> None:
    """Do ``task`` and tell how it ended: its result, or its error in one line."""
    from ..errors import PlanmethodError
    from ..words import message, render
    from . import api

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            tell({"result": run(task, tell)})
    except (PlanmethodError, OverflowError, RecursionError, MemoryError) as error:
        tell({"error": api.error_payload(error)})
    except Exception as error:   # a bug: its one line, for the page and the terminal
        line = render(message("internal error ({kind}): {error}", kind=type(error).__name__,
                              error=str(error))).replace("\n", " ")
        tell({"error": {"error": line, "kind": "internal"}})


if __name__ == "__main__":
    sys.exit(main())
