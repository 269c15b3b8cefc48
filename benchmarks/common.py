"""Shared pieces of the benchmarks: the benchmarked mechanisms, a timer, the machine, output.

The two mechanisms of the speed benchmark are the four-bar of case A (docs/reference-cases.md)
and the compressor slider-crank of Abduvaliev & Abduxoshimov, modelled with the same joints as
the peers model them (no extra points).

Examples
--------
>>> mechanism = exercise("fourbar").mechanism
>>> sorted(mechanism.links)
['AB', 'BC', 'CD', 'frame']
>>> full_turn(4).tolist()
[0.0, 90.0, 180.0, 270.0]
>>> best_time(lambda: None, min_time=0.0, min_repeats=2)["repeats"]
2
"""

from __future__ import annotations

import json
import os
import platform
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from planmethod.io import write_text_atomic
from planmethod.model import Exercise
from planmethod.spec import exercise_from_dict, load_exercise

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
FIGURES = ROOT / "figures"

#: reference case A with the peers' joints only (A, B, C, D)
FOURBAR = {
    "title": "Four-bar, reference case A",
    "drive": {"link": "AB", "pivot": "A", "angle": 60.0, "omega": 10.0, "epsilon": 0.0},
    "links": {"frame": {"A": [0, 0], "D": [0.30, 0]}, "AB": {"A": [0, 0], "B": [0.08, 0]},
              "BC": {"B": [0, 0], "C": [0.22, 0]}, "CD": {"C": [0, 0], "D": [0.18, 0]}},
    "sketch": {"C": [0.236, 0.168]},
}


def exercise(name: str) -> Exercise:
    """``fourbar`` (case A) or ``slider_crank`` (``exercises/compressor_slider_crank.toml``)."""
    if name == "fourbar":
        return exercise_from_dict(FOURBAR)
    if name == "slider_crank":
        return load_exercise(ROOT / "exercises" / "compressor_slider_crank.toml")
    raise KeyError(name)


def full_turn(count: int) -> np.ndarray:
    """Crank angles 360°·k/N, k = 0…N−1 (deg)."""
    return 360.0 * np.arange(count) / count


def best_time(function: Callable[[], object], *, min_time: float = 0.5, min_repeats: int = 3,
              max_repeats: int = 2000) -> dict:
    """Wall time of ``function()``: best and median of repeats (s), repeated at least
    ``min_repeats`` times and until ``min_time`` seconds were spent."""
    times: list[float] = []
    while len(times) < max_repeats and (len(times) < min_repeats or sum(times) < min_time):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return {"best": min(times), "median": statistics.median(times), "repeats": len(times)}


def interleaved_best_times(functions: dict[str, Callable[[], object]], *,
                           min_time: float = 0.5, min_repeats: int = 3,
                           max_repeats: int = 2000) -> dict[str, dict]:
    """Wall times of several functions taken in turn, one call of each per round, so that a
    change in a shared machine's load touches all of them alike: best and median (s) of each,
    after at least ``min_repeats`` rounds and ``min_time`` seconds per function.

    >>> sorted(interleaved_best_times({"a": lambda: None, "b": lambda: None}, min_time=0.0))
    ['a', 'b']
    """
    times: dict[str, list[float]] = {name: [] for name in functions}
    rounds = 0
    while rounds < max_repeats and (rounds < min_repeats or min(
            sum(spent) for spent in times.values()) < min_time):
        for name, function in functions.items():
            start = time.perf_counter()
            function()
            times[name].append(time.perf_counter() - start)
        rounds += 1
    return {name: {"best": min(spent), "median": statistics.median(spent), "repeats": rounds}
            for name, spent in times.items()}


def browser_launcher():
    """(Playwright's ``sync_playwright``, the system Chromium's path), or None where either
    is missing (the browser measures are then left out)."""
    import shutil

    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    return None if chromium is None else (sync_playwright, chromium)


#: the load reference's fastest times seen on this machine (see :func:`load_factor`)
LOAD_REFERENCE = "load_reference.json"


def reference_workload() -> int:
    """A fixed piece of work of the kind the package does — small numpy calls on a few dozen
    points, floats formatted, a dict filled — written here, so that no change to the package
    changes it: its time measures how busy the machine is, not how fast planmethod is.

    >>> reference_workload()
    19549
    """
    points = np.random.default_rng(12345).random((48, 2)) * 100.0
    texts, table = [], {}
    for index in range(1800):
        here = points[index % 48]
        distances = np.sqrt(((points - here) ** 2).sum(axis=1))
        nearest = int(np.argsort(distances)[1])
        table[(index % 48, nearest)] = float(distances[nearest])
        texts.append("%.2f,%.2f" % (float(here[0]), float(here[1])))  # noqa: UP031
    return len("".join(texts)) + len(table)


def load_factor(count: int = 15, *, record: bool = False) -> dict:
    """How much this run's load stretches wall and CPU times: the median of ``count`` runs
    of :func:`reference_workload` now, against the fastest median ever seen here (kept in
    ``results/load_reference.json``; with ``record``, a faster median found now replaces
    it). A time divided by its factor is its *idle estimate*.

    >>> found = load_factor(3)
    >>> found["factor"] >= 1.0 and found["cpu_factor"] >= 1.0
    True
    """
    wall, cpu = [], []
    reference_workload()
    for _ in range(count):
        start, start_cpu = time.perf_counter(), time.thread_time()
        reference_workload()
        cpu.append(1000 * (time.thread_time() - start_cpu))
        wall.append(1000 * (time.perf_counter() - start))
    wall_ms, cpu_ms = statistics.median(wall), statistics.median(cpu)
    path = RESULTS / LOAD_REFERENCE
    try:
        fastest = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        fastest = {}
    idle_wall = min(float(fastest.get("wall_ms", wall_ms)), wall_ms)
    idle_cpu = min(float(fastest.get("cpu_ms", cpu_ms)), cpu_ms)
    if record and (idle_wall, idle_cpu) != (fastest.get("wall_ms"), fastest.get("cpu_ms")):
        write_json(LOAD_REFERENCE, {"wall_ms": idle_wall, "cpu_ms": idle_cpu,
                                    "machine": machine().get("cpu", "?")})
    return {"reference_ms": wall_ms, "reference_cpu_ms": cpu_ms, "idle_reference_ms": idle_wall,
            "idle_reference_cpu_ms": idle_cpu, "idle_machine": fastest.get("machine", "?"),
            "factor": wall_ms / idle_wall, "cpu_factor": cpu_ms / idle_cpu}


def run_load(before: dict, after: dict) -> dict:
    """A run's load: :func:`load_factor` taken before and after it, and the mean factors.

    >>> run_load({"factor": 1.0, "cpu_factor": 1.2}, {"factor": 2.0, "cpu_factor": 1.4})["factor"]
    1.5
    """
    return {"before": before, "after": after,
            "factor": (before["factor"] + after["factor"]) / 2,
            "cpu_factor": (before["cpu_factor"] + after["cpu_factor"]) / 2}


def load_sentence(load: dict) -> str:
    """The run's load, as the tables of the studio and the workbook state it."""
    before, after = load["before"], load["after"]
    return (f"Load of this run: the reference workload (benchmarks/common.py, no planmethod "
            f"code in it; fastest seen here {before['idle_reference_ms']:.3g} ms wall, "
            f"{before['idle_reference_cpu_ms']:.3g} ms CPU, {before['idle_machine']}) took "
            f"{before['reference_ms']:.3g} / {after['reference_ms']:.3g} ms wall and "
            f"{before['reference_cpu_ms']:.3g} / {after['reference_cpu_ms']:.3g} ms CPU before "
            f"/ after: factors {load['factor']:.2f} (wall) and {load['cpu_factor']:.2f} (CPU). "
            "An idle estimate is a time divided by its factor: a rough one.")


def machine() -> dict:
    """What the numbers were measured on."""
    info = {"python": platform.python_version(), "numpy": np.__version__,
            "machine": platform.machine(), "system": platform.system(),
            "cpus": os.cpu_count()}
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                info["cpu"] = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    if hasattr(os, "getloadavg"):  # other work on a shared machine (not on Windows)
        info["load"] = round(os.getloadavg()[0], 2)
    info["time"] = time.strftime("%Y-%m-%d %H:%M:%S")
    return info


def written_by(command: str, about: dict | None = None) -> str:
    """The first line of a results file, shown where the file is included: when, by which
    command and on which machine its numbers were measured, and how busy the machine was when
    the run began (its one-minute load average, where the system tells it).

    >>> print(written_by("python -m benchmarks.run", {"time": "2026-11-27 10:00:00",
    ...     "cpu": "Xeon", "cpus": 2, "python": "3.11.7", "numpy": "2.4.6", "load": 1.5}).strip())
    *Written by `python -m benchmarks.run` on 2026-11-27 10:00:00 — Xeon, 2 cpus, load 1.5, ...*
    """
    about = about or machine()
    processor = about.get("cpu") or about.get("machine", "")
    load = f"load {about['load']:g}, " if "load" in about else ""
    return (f"*Written by `{command}` on {about['time']} — {processor}, {about['cpus']} cpus, "
            f"{load}Python {about['python']}, numpy {about['numpy']}.*\n\n")


def write_json(name: str, data: dict) -> Path:
    """Write ``benchmarks/results/NAME`` atomically (pretty JSON, no NaN)."""
    path = RESULTS / name
    write_text_atomic(path, json.dumps(data, indent=1, ensure_ascii=False, allow_nan=False)
                      + "\n")
    return path


def write_text(name: str, text: str) -> Path:
    path = RESULTS / name
    write_text_atomic(path, text)
    return path


def save_figure(figure, name: str) -> list[Path]:
    """Save a matplotlib figure as ``figures/NAME.png`` (and .svg), atomically."""
    from planmethod.io import atomic_path

    paths = []
    for suffix, options in ((".png", {"dpi": 130}), (".svg", {})):
        target = FIGURES / f"{name}{suffix}"
        with atomic_path(target, suffix) as temporary:
            figure.savefig(temporary, bbox_inches="tight", **options)
        paths.append(target)
    return paths


def microseconds(seconds: float) -> str:
    """A time per angle for a table: 3 significant digits, in µs."""
    value = seconds * 1e6
    return f"{value:.3g}" if value < 1000 else f"{value:,.0f}"
