"""A class III mechanism's first answer (``python -m benchmarks.run --only triad``).

A class III group has no closed form: its positions follow a continuation path of Newton
nodes, one every degree from ``drive.angle``, built for each new mechanism as far as the angles
asked (:mod:`planmethod.kinematics.groups.higher`). The first solve of a new mechanism pays for
its assemblies at ``drive.angle``, its compiled program and the nodes up to the angles asked;
issue 39 measured 0.42–0.60 s before a class III mechanism's first full-turn answer, against a
four-bar's 14 ms. Target: the first solve at one angle ≤ 50 ms after import.

Timed here, for the conveyor six-bar (crank + class III triad) and a four-bar
(``exercises/fourbar_study.toml``) in turn, round after round, so that the shared machine's load
touches both alike (ms, medians of the rounds; ×: the conveyor over the four-bar):

* *fresh process* — a new Python process imports the package's kinematics and reads the
  exercise; then the group kinds are loaded (imported by the first solve of any mechanism: timed
  apart, the same for both); then its first ``solve``: at ``drive.angle`` (what the studio's
  ``/api/solve`` and ``planmethod solve`` solve), at ``drive.angle`` + 65° (65 nodes marched),
  and over a full turn (360 angles, 0…359°; 359 nodes);
* *new mechanism* — in one process with everything loaded, each call a new mechanism (an
  equal one but for its title: a model of its own, as every step of a drag in the studio is):
  its first solve at ``drive.angle`` + 65° and its first full turn;
* *nodes on arrays* — the same new-mechanism full turn and one angle with the conveyor's nodes
  made as before this change (:meth:`~planmethod.kinematics.groups.higher.Path.quick`
  disabled: each node by Newton on numpy arrays of one angle); ×: over the nodes on floats.

Examples
--------
>>> sorted(CASES), TARGET_MS
(['drive', 'later', 'turn'], 50.0)
"""

from __future__ import annotations

import dataclasses
import json
import os
import statistics
import subprocess
import sys
import time

from planmethod.kinematics import solve
from planmethod.kinematics.groups import higher
from planmethod.spec import load_exercise

from .common import ROOT, load_factor, load_sentence, run_load
from .triad_worker import angles_of

MECHANISMS = {"conveyor": "exercises/conveyor_sixbar.toml",
              "four-bar": "exercises/fourbar_study.toml"}
#: what is solved first: one angle at drive.angle, one 65° further, a full turn
CASES = {"drive": "first solve at drive.angle", "later": "first solve at drive.angle + 65°",
         "turn": "first full-turn solve (360 angles)"}
#: the target of issue 39 for the first solve at one angle (ms)
TARGET_MS = 50.0


def _fresh(name: str, case: str) -> dict:
    """A fresh process's times (:mod:`benchmarks.triad_worker`)."""
    environment = dict(os.environ, PYTHONPATH=str(ROOT))
    found = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "triad_worker.py"),
                            MECHANISMS[name], case], cwd=ROOT, env=environment,
                           capture_output=True, text=True, check=True, timeout=120)
    return json.loads(found.stdout)


def _new_mechanism(mechanism, count: list[int]):
    count[0] += 1
    return dataclasses.replace(mechanism, title=f"{mechanism.title} #{count[0]}")


def _timed(call) -> dict[str, float]:
    start, start_cpu = time.perf_counter(), time.process_time()
    call()
    return {"first": 1e3 * (time.perf_counter() - start),
            "first_cpu": 1e3 * (time.process_time() - start_cpu)}


def _in_process(mechanisms: dict, count: list[int]) -> dict[str, dict[str, float]]:
    """One round of the new-mechanism times: each mechanism's first solve at drive.angle +
    65° and first full turn, then the conveyor's with its nodes on arrays."""
    out = {}
    for name, mechanism in mechanisms.items():
        for case in ("later", "turn"):
            fresh = _new_mechanism(mechanism, count)
            angles = angles_of(case, mechanism.drive.angle)
            out[f"{name}/{case}"] = _timed(lambda: solve(fresh, angles))  # noqa: B023
    conveyor = mechanisms["conveyor"]
    quick = higher.Path.quick
    higher.Path.quick = lambda *args: None    # the nodes on arrays, as before
    try:
        for case in ("later", "turn"):
            fresh = _new_mechanism(conveyor, count)
            angles = angles_of(case, conveyor.drive.angle)
            out[f"arrays/{case}"] = _timed(lambda: solve(fresh, angles))  # noqa: B023
    finally:
        higher.Path.quick = quick
    return out


def _medians(rounds: dict[str, list[dict[str, float]]]) -> dict[str, dict[str, float]]:
    return {key: {part: statistics.median(row[part] for row in rows) for part in rows[0]}
            for key, rows in rounds.items()}


def run(quick: bool = False) -> dict:
    rounds = 2 if quick else 7
    before = load_factor()
    fresh: dict[str, list[dict]] = {}
    for _ in range(rounds):
        for case in CASES:
            for name in MECHANISMS:
                fresh.setdefault(f"{name}/{case}", []).append(_fresh(name, case))
    mechanisms = {name: load_exercise(ROOT / path).mechanism
                  for name, path in MECHANISMS.items()}
    count = [0]
    for mechanism in mechanisms.values():      # modules loaded, programs' code warm
        solve(_new_mechanism(mechanism, count), mechanism.drive.angle)
    inside: dict[str, list[dict]] = {}
    for _ in range(rounds):
        for key, value in _in_process(mechanisms, count).items():
            inside.setdefault(key, []).append(value)
    load = run_load(before, load_factor())
    medians = _medians(fresh)
    one_angle = max(medians[f"conveyor/{case}"]["first_cpu"] for case in ("drive", "later"))
    return {"rounds": rounds, "fresh": medians, "in_process": _medians(inside),
            "one_angle_cpu_ms": one_angle, "target_ms": TARGET_MS,
            "met": one_angle <= TARGET_MS, "load": load}


def table(result: dict) -> str:
    fresh, inside = result["fresh"], result["in_process"]
    lines = [f"First answers, ms, wall / CPU (medians of {result['rounds']} rounds, the two "
             "mechanisms in turn); ×: the conveyor (crank + class III triad) over the four-bar, "
             "in CPU time.", "",
             "| | conveyor | four-bar | × |", "|---|---|---|---|"]

    def row(label: str, ours: dict, theirs: dict) -> None:
        lines.append(f"| {label} | {ours['first']:.1f} / {ours['first_cpu']:.1f} | "
                     f"{theirs['first']:.1f} / {theirs['first_cpu']:.1f} | "
                     f"{ours['first_cpu'] / theirs['first_cpu']:.2f} |")

    conveyor, fourbar = fresh["conveyor/drive"], fresh["four-bar/drive"]
    lines.append(f"| fresh process: import, read the exercise (wall) | {conveyor['import']:.1f} "
                 f"| {fourbar['import']:.1f} | |")
    lines.append(f"| fresh process: load the group kinds (wall) | {conveyor['kinds']:.1f} | "
                 f"{fourbar['kinds']:.1f} | |")
    for case, label in CASES.items():
        row(f"fresh process: {label}", fresh[f"conveyor/{case}"], fresh[f"four-bar/{case}"])
    for case in ("later", "turn"):
        row(f"new mechanism: {CASES[case]}", inside[f"conveyor/{case}"],
            inside[f"four-bar/{case}"])
    lines += ["", "The conveyor's nodes made as before (by Newton on numpy arrays of one angle) "
              "against now (on floats), new mechanism, same run; ×: before over now, in CPU "
              "time:", "", "| | nodes on arrays (before) | on floats (now) | × |",
              "|---|---|---|---|"]
    for case in ("later", "turn"):
        row(CASES[case], inside[f"arrays/{case}"], inside[f"conveyor/{case}"])
    verdict = "met" if result["met"] else "not met"
    lines += ["", f"Target (issue 39): a class III mechanism's first solve at one angle ≤ "
              f"{result['target_ms']:g} ms after import — **{verdict}**: "
              f"{result['one_angle_cpu_ms']:.1f} ms of CPU time (the slower of drive.angle and "
              "drive.angle + 65°, in a fresh process with the group kinds loaded; judged on CPU "
              "time, as the studio's server time is: the solve is single-threaded computation, "
              "and on this shared machine wall time also counts the time other processes hold "
              "the CPUs).", "", load_sentence(result["load"])]
    return "\n".join(lines) + "\n"
