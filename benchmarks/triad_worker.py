"""Time a mechanism's first solve in a fresh process (run by :mod:`benchmarks.triad`).

Run as a plain script (``python benchmarks/triad_worker.py FILE CASE``, from the project's root,
with the package importable): it imports nothing of planmethod, nor the ``benchmarks`` package,
before its clock starts. Prints one JSON line, in ms: ``import`` (the package's kinematics
imported and the exercise read), ``kinds`` (the group kinds loaded, which the first solve of any
mechanism does), ``first`` and ``first_cpu`` (the first ``solve``: wall and CPU time).
``CASE``: ``drive`` (at ``drive.angle``), ``later`` (at ``drive.angle`` + 65°), ``turn`` (360
angles, 0…359°).

Examples
--------
>>> angles_of("turn", 135.0).shape, angles_of("later", 135.0), angles_of("drive", 135.0)
((360,), 200.0, 135.0)
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np


def angles_of(case: str, drive: float):
    """The crank angles of a case (deg): one angle, or the 360 of a full turn."""
    if case == "turn":
        return np.arange(360.0)
    return drive + (65.0 if case == "later" else 0.0)


def first_answer(path: str, case: str) -> dict[str, float]:
    """The import, the group kinds' loading and the first solve of ``path`` (ms)."""
    start = time.perf_counter()
    from planmethod.kinematics import solve
    from planmethod.kinematics.groups import registered
    from planmethod.spec import load_exercise

    mechanism = load_exercise(path).mechanism
    imported = time.perf_counter()
    registered()
    kinds, kinds_cpu = time.perf_counter(), time.process_time()
    solve(mechanism, angles_of(case, mechanism.drive.angle))
    done, done_cpu = time.perf_counter(), time.process_time()
    return {"import": 1e3 * (imported - start), "kinds": 1e3 * (kinds - imported),
            "first": 1e3 * (done - kinds), "first_cpu": 1e3 * (done_cpu - kinds_cpu)}


if __name__ == "__main__":
    print(json.dumps(first_answer(sys.argv[1], sys.argv[2])))
