"""What following the assembly from ``drive.angle`` costs ``solve --angle``
(``python -m benchmarks.run --only continuation``).

``planmethod solve FILE --angle X`` is :func:`planmethod.report.analyse` at X. It used to pose
the exercise at X and choose each group's assembly there again from a sketch made for
``drive.angle``; it now follows the assembly chosen at ``drive.angle`` to X
(:func:`planmethod.kinematics.continuation.pose`: a sweep of the way every degree with the compiled
program, refined where a group may meet a limit position, then the exercise posed at X with the
followed positions as its sketch). Both are timed here in one run, in turn, for every shipped
exercise at twelve crank angles (those of ``tests/test_continuation.py``), each call at an
angle not solved before (so each poses and compiles a new model, as one ``solve --angle``
does): the whole analysis with its plans, the exact values only (``plans=False``), and
:func:`~planmethod.kinematics.continuation.follow` alone on a model already compiled. Times are
medians over the angles and rounds, in ms.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
>>> sorted(time_angle(exercise, 100.0))
['chosen_there', 'chosen_there_exact', 'follow', 'followed', 'followed_exact']
"""

from __future__ import annotations

import statistics
import time
from dataclasses import replace

import numpy as np

from planmethod.errors import PlanmethodError
from planmethod.kinematics.continuation import follow
from planmethod.report import analyse
from planmethod.scene import plan_scene
from planmethod.spec import load_exercise

from .common import ROOT

SHIPPED = sorted((ROOT / "exercises").glob("*.toml"))


def angles_of(drive: float) -> list[float]:
    """The twelve angles of ``tests/test_continuation.py``."""
    return ([drive + 30.0 * k for k in range(1, 7)] + [drive - 30.0 * k for k in range(1, 6)]
            + [drive + 360.0])


def _chosen_there(exercise, angle: float, plans: bool):
    """What ``solve --angle`` did before: the exercise posed at the angle, its assemblies
    chosen there again from its sketch."""
    mechanism = exercise.mechanism
    posed = replace(exercise, mechanism=replace(mechanism, drive=replace(mechanism.drive,
                                                                         angle=angle)))
    return analyse(posed, plans=plans)


def _timed(call) -> float:
    start = time.perf_counter()
    call()
    return (time.perf_counter() - start) * 1e3


def time_angle(exercise, angle: float, flip: bool = False) -> dict[str, float]:
    """One angle never solved before: each way once (in turn, the order flipped by ``flip``)."""
    ways = [("followed", lambda: analyse(exercise, angle)),
            ("chosen_there", lambda: _chosen_there(exercise, angle, True))]
    exact = [("followed_exact", lambda: analyse(exercise, angle + 1e-7, plans=False)),
             ("chosen_there_exact", lambda: _chosen_there(exercise, angle + 1e-7, False))]
    out = {}
    for name, call in (ways[::-1] + exact[::-1]) if flip else (ways + exact):
        out[name] = _timed(call)
    links = plan_scene(exercise).links
    out["follow"] = _timed(lambda: follow(exercise.mechanism, angle, links=links))
    return out


def run(quick: bool = False) -> dict:
    rounds = 1 if quick else 3
    rows = []
    for path in SHIPPED[:4] if quick else SHIPPED:
        exercise = load_exercise(path)
        analyse(exercise, plans=False)       # the exercise's own model, once
        times: dict[str, list[float]] = {}
        for round_ in range(rounds):
            for number, angle in enumerate(angles_of(exercise.mechanism.drive.angle)):
                try:
                    found = time_angle(exercise, angle + 1e-4 * round_, flip=number % 2 == 1)
                except PlanmethodError:   # an angle the exercise cannot reach
                    continue
                for name, value in found.items():
                    times.setdefault(name, []).append(value)
        medians = {name: statistics.median(values) for name, values in times.items()}
        rows.append({"exercise": path.stem, "angles": len(times.get("follow", [])),
                     **medians,
                     "ratio": medians["followed"] / medians["chosen_there"],
                     "ratio_exact": medians["followed_exact"] / medians["chosen_there_exact"]})
    ratios = np.array([row["ratio"] for row in rows])
    exact = np.array([row["ratio_exact"] for row in rows])
    return {"rounds": rounds, "rows": rows,
            "ratio_median": float(np.median(ratios)), "ratio_max": float(ratios.max()),
            "ratio_exact_median": float(np.median(exact)), "ratio_exact_max": float(exact.max())}


def table(result: dict) -> str:
    lines = ["`analyse(exercise, X)` (= `solve --angle X`) at an angle not solved before, ms "
             "(median over the angles and rounds): *chosen there* = the assemblies chosen again "
             "at X (before), *followed* = followed from drive.angle (now); *exact only* = "
             "`plans=False`; *follow* = the check of the way alone, on a compiled model.", "",
             "| exercise | angles | chosen there | followed | × | exact only: chosen there | "
             "followed | × | follow |", "|---|---|---|---|---|---|---|---|---|"]
    for row in result["rows"]:
        lines.append(
            f"| {row['exercise']} | {row['angles']} | {row['chosen_there']:.1f} | "
            f"{row['followed']:.1f} | {row['ratio']:.2f} | {row['chosen_there_exact']:.1f} | "
            f"{row['followed_exact']:.1f} | {row['ratio_exact']:.2f} | {row['follow']:.2f} |")
    lines += ["", f"followed / chosen there: median {result['ratio_median']:.2f}, worst "
                  f"{result['ratio_max']:.2f} (with plans); exact only: median "
                  f"{result['ratio_exact_median']:.2f}, worst {result['ratio_exact_max']:.2f}."]
    return "\n".join(lines) + "\n"
