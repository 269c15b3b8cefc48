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
