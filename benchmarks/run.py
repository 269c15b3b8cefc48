"""Run the benchmarks and write their results: ``python -m benchmarks.run [--quick]``.

Sections (all by default, or ``--only speed,accuracy,scene,memory,stress,workbook,…``):

* ``speed`` — full-turn analysis of the case A four-bar and the compressor slider-crank at
  N = 360, 3,600, 36,000 angles against the peers (``python -m benchmarks.peers --setup``
  first, to make their separate virtualenv) → ``results/speed.{json,md}``,
  ``figures/bench_speed.{png,svg}``;
* ``accuracy`` — run time against error of v and a by the exact closed form, Newton, finite
  differences and the graphical plans → ``results/accuracy.{json,md}``,
  ``figures/bench_error_vs_time.{png,svg}``;
* ``scene`` — what computing only what a scene needs saves, and the command line's start-up
  → ``results/scene.{json,md}``;
* ``memory`` — a 1,000,000-angle sweep of the shaper six-bar in bounded memory →
  ``results/memory.{json,md}``;
* ``stress`` — the long stress run → ``results/stress.{json,md}``;
* ``workbook`` — per-position analysis, plans + SVG and keys of the compressor and the
  conveyor, their 360-frame workbooks (time, size) and the frame switch in headless Chromium
  → ``results/workbook.{json,md}``, ``figures/workbook.png``;
* ``continuation`` — what following the assembly from ``drive.angle`` costs ``solve --angle``,
  against choosing it again at the angle, for every shipped exercise →
  ``results/continuation.{json,md}``;
* ``toggle`` — how close to a four-bar's toggle each stage still solves, and the error estimate
  against the measured error → ``results/toggle.{json,md}``;
* ``studio`` — the studio's time per update while a point is dragged, on the server and in
  headless Chromium → ``results/studio.{json,md}``;
* ``triad`` — a class III mechanism's first answer (one angle, a full turn) against a
  four-bar's, in fresh processes and for a new mechanism → ``results/triad.{json,md}``;
* ``language`` — what speaking the course's language costs ``solve --svg`` and a workbook's
  frames: English and Russian against text with no catalogue → ``results/language.{json,md}``.

A full run writes into ``benchmarks/results`` and ``figures``; ``--quick`` (smaller N, fewer
repeats, about a minute) writes into ``--out`` (default: a temporary folder), so that quick
numbers never replace the committed ones.

Examples
--------
>>> sorted(SECTIONS)
['accuracy', 'continuation', 'language', 'memory', 'scene', 'speed', 'stress', 'studio', 'toggle',
 'triad', 'workbook']
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

from . import (
    accuracy,
    continuation,
    language,
    memory,
    scene,
    speed,
    stress,
    studio,
    toggle,
    triad,
    workbook,
)
from .common import FIGURES, RESULTS, machine, written_by

SECTIONS = {
    "speed": (speed, "bench_speed"),
    "accuracy": (accuracy, "bench_error_vs_time"),
    "scene": (scene, None),
    "memory": (memory, None),
    "stress": (stress, None),
    "workbook": (workbook, None),
    "continuation": (continuation, None),
    "toggle": (toggle, None),
    "studio": (studio, None),
    "triad": (triad, None),
    "language": (language, None),
}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.run",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="a short run (smaller N, fewer repeats), written to --out")
    parser.add_argument("--only", default=",".join(SECTIONS),
                        help="comma-separated sections (default: all)")
    parser.add_argument("--out", help="folder for results and figures (default: the "
                                      "committed ones for a full run, a temporary folder "
                                      "for --quick)")
    args = parser.parse_args(argv)
    chosen = [name.strip() for name in args.only.split(",") if name.strip()]
    unknown = [name for name in chosen if name not in SECTIONS]
    if unknown:
        parser.error(f"unknown section(s): {', '.join(unknown)}")
    if args.out:
        results = figures = Path(args.out)
    elif args.quick:
        results = figures = Path(tempfile.mkdtemp(prefix="planmethod-bench-"))
    else:
        results, figures = RESULTS, FIGURES
    from planmethod.io import atomic_path, write_text_atomic

    about = machine()
    print(f"planmethod benchmarks on {about.get('cpu', about['machine'])}, "
          f"{about['cpus']} cpus, Python {about['python']}, numpy {about['numpy']}")
    for name in chosen:
        module, figure_name = SECTIONS[name]
        print(f"[{name}]")
        start = time.perf_counter()
        result = module.run(quick=args.quick)
        result["machine"] = about
        result["quick"] = args.quick
        result["seconds"] = time.perf_counter() - start
        text = module.table(result)
        write_text_atomic(results / f"{name}.json",
                          json.dumps(result, indent=1, ensure_ascii=False, default=float) + "\n")
        header = written_by(f"python -m benchmarks.run --only {name}"
                            + (" --quick" if args.quick else ""), about)
        write_text_atomic(results / f"{name}.md", header + text)
        print(text)
        if figure_name:
            fig = module.figure(result)
            for suffix, options in ((".png", {"dpi": 130}), (".svg", {})):
                with atomic_path(figures / f"{figure_name}{suffix}") as temporary:
                    fig.savefig(temporary, bbox_inches="tight", **options)
        print(f"  ({result['seconds']:.0f} s)")
    print(f"results in {results}" + (f", figures in {figures}" if figures != results else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
