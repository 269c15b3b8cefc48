"""How long the test suite's inner loop takes: ``python -m benchmarks.suite``.

The inner loop (docs/contributing.md, "Test tiers") is every test but the documentation's and
the browser's, on two processes: ``python -m pytest -m "not docs and not browser" -n 2``. Its
target is two minutes on two CPUs. It is run here once (or ``--repeats`` times) in a process
of its own, with the machine's load measured before and after
(:func:`benchmarks.common.load_factor`), and the wall time, the CPU time of all its
processes, and the idle estimate (the wall time divided by the load factor) are written to
``results/suite.{json,md}``.

Examples
--------
>>> COMMAND[-4:]
['-m', 'not docs and not browser', '-n', '2']
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import time

from .common import ROOT, load_factor, load_sentence, machine, run_load, write_json, write_text
from .common import written_by as header

COMMAND = [sys.executable, "-m", "pytest", "-p", "no:cacheprovider",
           "-m", "not docs and not browser", "-n", "2"]
#: the inner loop's target (s, on two idle CPUs)
TARGET_SECONDS = 120.0


def time_once() -> dict:
    """One run of the inner loop: its wall and CPU seconds, and whether it passed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(COMMAND, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = done.stdout.strip().splitlines()
    return {"wall_s": wall, "cpu_s": cpu, "passed": done.returncode == 0,
            "failed": [line for line in lines if line.startswith("FAILED")],
            "failures": "" if done.returncode == 0 else done.stdout[-4000:],
            "last_line": (lines or [""])[-1]}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.suite",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args(argv)
    about = machine()
    before = load_factor(record=True)
    runs = [time_once() for _ in range(args.repeats)]
    load = run_load(before, load_factor(record=True))
    wall = statistics.median(run["wall_s"] for run in runs)
    idle = wall / load["factor"]
    result = {"machine": about, "command": " ".join(COMMAND[1:]), "runs": runs,
              "wall_s": wall, "idle_estimate_s": idle, "target_s": TARGET_SECONDS,
              "met": idle <= TARGET_SECONDS and all(run["passed"] for run in runs),
              "load": load}
    write_json("suite.json", result)
    verdict = "met" if result["met"] else "not met"
    text = (header("python -m benchmarks.suite", about)
            + f"The inner loop, `python {result['command']}`: {wall:.0f} s wall, "
            + f"{statistics.median(run['cpu_s'] for run in runs):.0f} s CPU in all its "
            + f"processes; idle estimate {idle:.0f} s against the target of "
            + f"{TARGET_SECONDS:.0f} s on two CPUs: **{verdict}**. "
            + f"({runs[-1]['last_line'] or 'no summary line'})\n\n{load_sentence(load)}\n")
    write_text("suite.md", text)
    print(text)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
