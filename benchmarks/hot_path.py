"""Before and after: the kinematics' hot path at an earlier commit against the working tree.

``python -m benchmarks.hot_path [REV]`` (default ``6008cc9``, the last commit before the
kinematics were rebuilt as one module per group kind traced into one program per mechanism,
:mod:`planmethod.kinematics.program`) checks REV out into a temporary git worktree, times the
same full-turn analysis (positions, velocities, accelerations of every point, kept as
:mod:`benchmarks.speed` keeps them) of the case A four-bar, the slider-crank of Abduvaliev &
Abduxoshimov, the shaper six-bar and the vibratory conveyor's class III six-bar with each
tree's planmethod in its own subprocess, one after the other on the same machine, and
writes ``benchmarks/results/hot_path.{md,json}``.

Examples
--------
>>> HARNESS.count("solve(")
1
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from .common import RESULTS, ROOT, machine, written_by

DEFAULT_REV = "6008cc9"

HARNESS = r'''
import dataclasses, json, sys, time
import numpy as np
from planmethod.kinematics import solve
from planmethod.spec import exercise_from_dict, load_exercise

FOURBAR = {"title": "Four-bar", "drive": {"link": "AB", "pivot": "A", "angle": 60.0,
           "omega": 10.0, "epsilon": 0.0},
           "links": {"frame": {"A": [0, 0], "D": [0.30, 0]}, "AB": {"A": [0, 0], "B": [0.08, 0]},
                     "BC": {"B": [0, 0], "C": [0.22, 0]}, "CD": {"C": [0, 0], "D": [0.18, 0]}},
           "sketch": {"C": [0.236, 0.168]}}
mechanisms = {"fourbar": exercise_from_dict(FOURBAR).mechanism,
              "slider_crank": load_exercise(sys.argv[1]).mechanism,
              "shaper": load_exercise(sys.argv[2]).mechanism,
              "conveyor (class III)": load_exercise(sys.argv[3]).mechanism}
out = {}
for name, m in mechanisms.items():
    points = list(dict.fromkeys(p for link in m.links.values() for p in link.points))
    fresh = [dataclasses.replace(m) for _ in range(2048)]  # a new model object per call
    for count in (1, 360, 3600, 36000):
        angles = 360.0 * np.arange(count) / count
        row = []
        for models in (None, iter(fresh)):
            def once():
                motion = solve(m if models is None else next(models), angles)
                return {p: (motion.position(p), motion.velocity(p), motion.acceleration(p))
                        for p in points}
            once()
            best, spent, repeats = 1e9, 0.0, 0
            while repeats < 3 or (spent < 0.5 and repeats < 2000):
                start = time.perf_counter()
                once()
                took = time.perf_counter() - start
                best, spent, repeats = min(best, took), spent + took, repeats + 1
            row.append(best / count)
        out[f"{name} {count}"] = row
print(json.dumps(out))
'''


def measure(tree: Path) -> dict:
    """Run the harness with ``tree``'s planmethod on ``tree``'s own exercise files (an older
    tree may not read keys added since): its folder first on the subprocess's PYTHONPATH
    (nothing of this process's import path is inherited but what PYTHONPATH held)."""
    path = os.pathsep.join([str(tree), *filter(None, [os.environ.get("PYTHONPATH")])])
    done = subprocess.run([sys.executable, "-c", HARNESS,
                           str(tree / "exercises" / "compressor_slider_crank.toml"),
                           str(tree / "exercises" / "shaper_sixbar.toml"),
                           str(tree / "exercises" / "conveyor_sixbar.toml")],
                          capture_output=True, text=True, cwd=tempfile.gettempdir(),
                          env={**os.environ, "PYTHONPATH": path})
    if done.returncode != 0:
        raise RuntimeError(done.stderr[-800:])
    return json.loads(done.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.hot_path")
    parser.add_argument("rev", nargs="?", default=DEFAULT_REV, help="the 'before' commit")
    args = parser.parse_args(argv)
    from planmethod.io import write_text_atomic

    with tempfile.TemporaryDirectory() as folder:
        tree = Path(folder) / "before"
        subprocess.run(["git", "worktree", "add", "--detach", "-q", str(tree), args.rev],
                       cwd=ROOT, check=True)
        try:
            before = measure(tree)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT,
                           check=False)
    after = measure(ROOT)
    lines = [f"Full-turn analysis (p, v, a of every point), µs per angle, best of repeats: "
             f"planmethod at {args.rev} → the working tree. *The same model*: solve called again "
             "and again with one model object (the working tree compiles it once and keeps the "
             "structure and branches); *a new model*: a new, equal model object at every call "
             "(structural analysis, branch choice and compilation every time).", "",
             "| mechanism, N | the same model at every call: before → after "
             "| a new model at every call: before → after |",
             "|---|---|---|"]
    for key, (cold, prepared) in before.items():
        now = after[key]
        lines.append(f"| {key} | {cold * 1e6:.3g} → {now[0] * 1e6:.3g} (×{cold / now[0]:.2f}) | "
                     f"{prepared * 1e6:.3g} → {now[1] * 1e6:.3g} "
                     f"(×{prepared / now[1]:.2f}) |")
    text = "\n".join(lines) + "\n"
    about = machine()
    write_text_atomic(RESULTS / "hot_path.md",
                      written_by(f"python -m benchmarks.hot_path {args.rev}", about) + text)
    write_text_atomic(RESULTS / "hot_path.json", json.dumps(
        {"rev": args.rev, "before": before, "after": after, "machine": about}, indent=1) + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
