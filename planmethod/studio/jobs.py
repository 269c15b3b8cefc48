"""The studio's long work as jobs, each in a process of its own: drawing variants with their
task sheets (``POST /api/variants``) and exporting a teaching run (``POST /api/export``).

The request checks what it can at once (:func:`~planmethod.studio.api.prepare_export`: the
count, the folder, the template; a mistake is its 400 at once), starts the job and answers
with it; the page asks for its progress (``GET /api/job?id=…``) and may cancel it
(``POST /api/cancel``). Solves, turns and file listings go on answering meanwhile.

Why a process rather than a thread (measured by ``benchmarks/studio.py``, said in
docs/studio.md): a job's computing shares no interpreter lock with the solves of a drag, so
on a second CPU it does not slow them; a cancel ends it at once, whatever it is doing; and a
job that fails badly fails alone.

* At most :data:`MAX_RUNNING` jobs run at once; a further one is refused (:class:`BusyError`: 429).
* A job's process is ``python -P -m planmethod.studio.worker`` (:mod:`~planmethod.studio.worker`),
  given its task on its standard input; it ends when that input closes, so when the studio
  ends however it ends. It runs in a session of its own: Ctrl-C in the studio's terminal
  reaches the studio, which stops its jobs (:meth:`Jobs.close`).
* An export is written into a hidden folder beside its target
  (:func:`~planmethod.studio.api.stage_folder`) and renamed into place when whole; a cancelled
  or failed export's folder is removed, so the target holds one whole run or nothing.
* The last :data:`MAX_KEPT` ended jobs are kept for the page to read.

Examples
--------
>>> jobs = Jobs()
>>> jobs.listing()
[]
>>> jobs.get("nothing")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
planmethod.studio.jobs.NoSuchJobError: no job 'nothing' (a job is kept while the studio runs, ...)
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from ..errors import PlanmethodError
from ..words import Message, message, render, speaking
from . import api

__all__ = ["MAX_KEPT", "MAX_RUNNING", "BusyError", "Job", "Jobs", "NoSuchJobError"]

#: jobs running at once (one export and one preview, say): each takes a CPU
MAX_RUNNING = 2
#: ended jobs kept for the page to read (their results: a preview's sheets)
MAX_KEPT = 20
#: the longest message line read from a job (bytes): a preview of 40 task sheets
MAX_LINE = 64_000_000
#: how long a cancelled job's process has to end before it is killed (s)
STOP_SECONDS = 5.0


class BusyError(PlanmethodError):
    """A job refused: as many are running as may (429)."""


class NoSuchJobError(PlanmethodError, LookupError):
    """A job the studio does not know (404)."""


@dataclass(eq=False)
class Job:
    """One job: what it is (``variants`` or ``export``), how far it is (``phase``, ``done`` of
    ``total``), its ``state`` (``running``, then ``done``, ``failed`` or ``cancelled``) and
    how it ended (``result`` or ``error``, as a refused request's)."""

    id: str
    kind: str
    total: int
    folder: str | None = None
    target: Path | None = None
    staging: Path | None = None
    state: str = "running"
    phase: str = "starting"
    done: int = 0
    result: dict[str, Any] | None = None
    error: dict[str, str] | None = None
    #: the language of its words (its errors, its result's notes)
    language: str | None = None
    started: float = field(default_factory=time.monotonic)
    ended: float | None = None
    process: subprocess.Popen | None = field(default=None, repr=False)
    lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def view(self, *, result: bool = False) -> dict[str, Any]:
        """The job as the page reads it (with its result if asked: a preview's is large)."""
        seconds = (self.ended if self.ended is not None else time.monotonic()) - self.started
        out = {"id": self.id, "kind": self.kind, "state": self.state, "phase": self.phase,
               "done": self.done, "total": self.total, "seconds": round(seconds, 1),
               "folder": self.folder, "error": self.error}
        if result:
            out["result"] = self.result
        return out


def _start_process() -> tuple[subprocess.Popen, IO[bytes]]:
    """A job's process, started (it imports what a job needs, then waits for its task), and
    the file its standard error goes to: this Python, this copy of planmethod first on its
    path, nothing taken from the current folder (``-P``), in a session of its own."""
    package_root = str(Path(__file__).resolve().parents[2])
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join(
        part for part in (package_root, environment.get("PYTHONPATH")) if part)
    errors = tempfile.TemporaryFile()   # noqa: SIM115 - closed when the job ends
    try:
        process = subprocess.Popen([sys.executable, "-P", "-m", "planmethod.studio.worker"],
                                   stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                   stderr=errors, env=environment, start_new_session=True)
    except OSError:
        errors.close()
        raise
    return process, errors


class Jobs:
    """The studio's jobs: :meth:`start` one, :meth:`get` it, :meth:`cancel` it; :meth:`close`
    stops them all."""

    def __init__(self, *, running: int = MAX_RUNNING) -> None:
        self.running = running
        self._jobs: dict[str, Job] = {}
        self._lock = threading.Lock()
        self._closed = False
        self._standby: tuple[subprocess.Popen, IO[bytes]] | None = None

    def warm(self) -> None:
        """Have a job's process started and waiting, its imports done, so that the next job
        starts at once (the page's first load asks for it, and every job started)."""
        with self._lock:
            if self._closed or (self._standby is not None
                                and self._standby[0].poll() is None):
                return
            with contextlib.suppress(OSError):   # then the next job starts its own
                self._standby = _start_process()

    def _take_standby(self) -> tuple[subprocess.Popen, IO[bytes]] | None:
        """The waiting process, if it still waits (its lock held)."""
        standby, self._standby = self._standby, None
        if standby is not None and standby[0].poll() is not None:
            standby[1].close()
            return None
        return standby

    def listing(self) -> list[dict[str, Any]]:
        """Every job kept, oldest first, without results."""
        with self._lock:
            return [job.view() for job in self._jobs.values()]

    def get(self, job_id: str) -> Job:
        with self._lock:
            job = self._jobs.get(job_id)
        if job is None:
            raise NoSuchJobError(message("no job {job!r} (a job is kept while the studio runs, "
                                         "until {kept} later ones end)", job=job_id[:40],
                                         kept=MAX_KEPT))
        return job

    def start(self, kind: str, arguments: dict[str, Any], *, total: int,
              language: str | None = None) -> Job:
        """Start a job of ``kind`` (``variants``: :func:`~planmethod.studio.api.run_variants`;
        ``export``: :func:`~planmethod.studio.api.run_export`) on ``arguments`` as the
        request's ``prepare_*`` checked them, its words in ``language`` (default: the
        environment's); :class:`BusyError` if :attr:`running` jobs run, a
        :class:`FileExistsError` if a running export writes the same folder."""
        target = Path(arguments["target"]) if "target" in arguments else None
        with self._lock:
            active = [job for job in self._jobs.values() if job.state == "running"]
            if self._closed:
                raise BusyError(message("the studio is stopping"))
            if len(active) >= self.running:
                raise BusyError(message("{count} jobs are running ({kinds}), at most {limit} at "
                                        "once: wait for one to end, or cancel it",
                                        count=len(active), kinds=[job.kind for job in active],
                                        limit=self.running))
            if target is not None and any(job.target == target for job in active):
                raise FileExistsError(render(message("{folder} (an export into it is running)",
                                                     folder=arguments["folder"])))
            job = Job(secrets.token_hex(6), kind, total, folder=arguments.get("folder"),
                      target=target, language=language)
            if target is not None:
                job.staging = api.stage_folder(target)
            self._jobs[job.id] = job
            self._forget_ended()
            standby = self._take_standby()
        with job.lock:
            self._spawn(job, {"kind": kind, "arguments": arguments, "language": language,
                              "staging": str(job.staging) if job.staging else None}, standby)
        self.warm()
        return job

    def _spawn(self, job: Job, task: dict[str, Any],
               standby: tuple[subprocess.Popen, IO[bytes]] | None) -> None:
        """Give ``task`` to the waiting process, or to a new one."""
        try:
            job.process, errors = standby if standby is not None else _start_process()
        except OSError as error:
            with speaking(job.language):
                self._end(job, "failed", error=_said(message(
                    "cannot start the job's process ({why})", why=error.strerror), "internal"))
            return
        with contextlib.suppress(OSError):   # a process that died at once: _follow says so
            job.process.stdin.write(json.dumps(task).encode("utf-8") + b"\n")
            job.process.stdin.flush()
        threading.Thread(target=self._follow, args=(job, job.process, errors), daemon=True,
                         name=f"planmethod-job-{job.id}").start()

    def _follow(self, job: Job, process: subprocess.Popen, errors: IO[bytes]) -> None:
        """Read the job's messages until its process ends, then end the job (its words in
        the job's language)."""
        with speaking(job.language):
            self._read_job(job, process, errors)

    def _read_job(self, job: Job, process: subprocess.Popen, errors: IO[bytes]) -> None:
        result = error = None
        try:
            while line := process.stdout.readline(MAX_LINE):
                try:
                    told = json.loads(line)
                except ValueError:
                    continue
                if "progress" in told:
                    with job.lock:
                        job.phase = told["progress"]["phase"]
                        job.done = told["progress"]["done"]
                        job.total = told["progress"]["total"]
                result = told.get("result", result)
                error = told.get("error", error)
            status = process.wait()
            if result is None and error is None:
                error = _said(message("the job's process ended unexpectedly (exit status "
                                      "{status}){last}", status=status, last=_last_line(errors)),
                              "internal")
        finally:
            errors.close()
            process.stdout.close()
            with contextlib.suppress(OSError):
                process.stdin.close()
        with job.lock:
            if job.state != "running":   # cancelled: already cleaned up
                return
            if error is None and job.target is not None:
                error = self._commit(job)
                result = {"folder": job.folder, **result} if error is None else None
            if error is not None and error.get("kind") == "internal":
                print(render(message("planmethod studio: {kind} job failed: {error}",
                                     kind=job.kind, error=error["error"])), file=sys.stderr)
            self._end(job, "failed" if error is not None else "done", result=result,
                      error=error)

    @staticmethod
    def _commit(job: Job) -> dict[str, str] | None:
        """Rename an export's staged folder into place; the error, if it cannot be."""
        try:
            api.commit_folder(job.staging, job.target, job.folder)
        except FileExistsError:
            return _said(message("{folder} exists already (made while the job ran): nothing "
                                 "was written there", folder=job.folder), "exists")
        except OSError as failure:
            return _said(message("cannot write {folder} ({why})", folder=job.folder,
                                 why=failure.strerror), "input")
        return None

    def _end(self, job: Job, state: str, *, result: dict[str, Any] | None = None,
             error: dict[str, str] | None = None) -> None:
        """End ``job`` (its lock held): its state, and its staged folder removed."""
        job.state, job.result, job.error, job.ended = state, result, error, time.monotonic()
        if job.staging is not None:
            shutil.rmtree(job.staging, ignore_errors=True)

    def cancel(self, job_id: str) -> Job:
        """Stop a running job: its process ended (killed if it does not end at once), its
        staged folder removed. A job that has ended stays as it ended."""
        job = self.get(job_id)
        with job.lock:
            if job.state == "running":
                if job.process is not None:
                    _stop(job.process)
                self._end(job, "cancelled")
        return job

    def close(self) -> None:
        """Cancel every running job, end the waiting process and refuse new jobs (the studio
        stops)."""
        with self._lock:
            self._closed = True
            running = [job.id for job in self._jobs.values() if job.state == "running"]
            standby = self._take_standby()
        for job_id in running:
            self.cancel(job_id)
        if standby is not None:
            _stop(standby[0])
            standby[1].close()

    def _forget_ended(self) -> None:
        """Keep at most :data:`MAX_KEPT` ended jobs (the oldest go first)."""
        ended = [job_id for job_id, job in self._jobs.items() if job.state != "running"]
        for job_id in ended[:max(0, len(ended) - MAX_KEPT)]:
            del self._jobs[job_id]


def _said(text: Message, kind: str) -> dict[str, str]:
    """A job's error as a refused request's: its one line and its kind."""
    return {"error": render(text), "kind": kind}


def _stop(process: subprocess.Popen) -> None:
    """End a job's process: asked (SIGTERM), then killed if it has not ended in
    :data:`STOP_SECONDS`."""
    with contextlib.suppress(OSError):
        process.terminate()
    try:
        process.wait(STOP_SECONDS)
    except subprocess.TimeoutExpired:
        with contextlib.suppress(OSError):
            process.kill()
        process.wait()


def _last_line(errors: IO[bytes]) -> str:
    """``: `` and the last line a job's process wrote on its standard error, if any."""
    try:
        errors.seek(0, os.SEEK_END)
        size = errors.tell()
        errors.seek(max(0, size - 2000))
        lines = errors.read().decode("utf-8", "replace").strip().splitlines()
    except OSError:
        return ""
    return f": {lines[-1][:300]}" if lines else ""
