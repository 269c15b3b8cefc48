"""Memory of long sweeps: a 1,000,000-angle full turn of the shaper six-bar.

Each case runs in a fresh interpreter (``python -m benchmarks.memory --case …``) and reports
its wall time, the peak of traced allocations (``tracemalloc``: Python objects and numpy
arrays) and the process's peak resident memory (``resource.getrusage``, which includes the
interpreter and numpy themselves, about 30–40 MB). Cases:

* ``table`` — :func:`planmethod.sweep.sweep_table`: the whole table in memory (its size grows
  with N: about 8 bytes × columns × N);
* ``aggregate`` — :func:`planmethod.sweep.sweep_chunks`, keeping only each column's running
  minimum and maximum: bounded, the same peak for 10⁵ and 10⁶ angles;
* ``csv`` — the same chunks streamed to a CSV file on disk (written atomically, then removed).

Examples
--------
>>> summary = aggregate_columns([{"a": np.array([1.0, 5.0])}, {"a": np.array([-2.0, 3.0])}])
>>> summary["a"]
(-2.0, 5.0)
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

from .common import ROOT

FILE = "exercises/shaper_sixbar.toml"
CASES = ("table", "aggregate", "csv")


def aggregate_columns(chunks) -> dict[str, tuple[float, float]]:
    """Running (min, max) of every column over the chunks."""
    out: dict[str, tuple[float, float]] = {}
    for columns in chunks:
        for name, values in columns.items():
            low, high = float(np.nanmin(values)), float(np.nanmax(values))
            if name in out:
                low, high = min(low, out[name][0]), max(high, out[name][1])
            out[name] = (low, high)
    return out


def stream_csv(chunks, target: Path) -> int:
    """Write the chunks as one CSV (full precision, one chunk at a time); returns the number
    of rows."""
    from planmethod.io import atomic_path
    from planmethod.sweep import csv_rows

    rows = 0
    with atomic_path(target) as temporary, temporary.open("w", encoding="utf-8") as handle:
        for columns in chunks:
            if rows == 0:
                handle.write(",".join(columns) + "\n")
            handle.writelines(csv_rows(columns))
            rows += len(columns["angle"])
    return rows


def measure(case: str, count: int, trace: bool = False) -> dict:
    """Run one case in this process and measure it (with ``trace``, the traced peak too —
    tracing slows the Python-heavy parts, so times are taken in untraced runs)."""
    from planmethod.spec import load_exercise
    from planmethod.sweep import CHUNK, sweep_chunks, sweep_table

    exercise = load_exercise(ROOT / FILE)
    angles = 360.0 * np.arange(count) / count
    if trace:
        tracemalloc.start()
    start = time.perf_counter()
    detail: dict = {}
    if case == "table":
        table = sweep_table(exercise, angles=angles)
        detail["columns"] = len(table)
        detail["table_bytes"] = int(sum(column.nbytes for column in table.values()))
        detail["max_a_D"] = float(np.max(table["a_D"]))
        del table
    elif case == "aggregate":
        summary = aggregate_columns(sweep_chunks(exercise, angles=angles))
        detail["columns"] = len(summary)
        detail["max_a_D"] = summary["a_D"][1]
    elif case == "csv":
        with tempfile.TemporaryDirectory() as folder:
            target = Path(folder) / "sweep.csv"
            detail["rows"] = stream_csv(sweep_chunks(exercise, angles=angles), target)
            detail["csv_bytes"] = target.stat().st_size
    else:
        raise ValueError(case)
    seconds = time.perf_counter() - start
    rss_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    out = {"case": case, "angles": count, "seconds": seconds, "max_rss_bytes": rss_kib * 1024,
           "chunk": CHUNK, **detail}
    if trace:
        out["traced_peak_bytes"] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return out


def run(quick: bool = False, *, log=print) -> dict:
    counts = (100_000,) if quick else (100_000, 1_000_000)
    rows = []
    for case in CASES:
        for count in counts:
            log(f"  {case}, {count:,} angles …")
            runs = []
            for trace in (False, True):
                done = subprocess.run([sys.executable, "-m", "benchmarks.memory", "--case",
                                       case, "--angles", str(count)]
                                      + (["--trace"] if trace else []),
                                      capture_output=True, text=True, cwd=ROOT)
                if done.returncode != 0:
                    raise RuntimeError(f"memory case {case} failed: {done.stderr[-500:]}")
                runs.append(json.loads(done.stdout.strip().splitlines()[-1]))
            rows.append({**runs[0], "traced_peak_bytes": runs[1]["traced_peak_bytes"]})
    return {"file": FILE, "rows": rows}


def table(result: dict) -> str:
    lines = ["| case | angles | s | traced peak MB | max RSS MB | note |",
             "|---|---|---|---|---|---|"]
    for row in result["rows"]:
        note = ""
        if "table_bytes" in row:
            note = f"table {row['table_bytes'] / 1e6:.0f} MB ({row['columns']} columns)"
        if "csv_bytes" in row:
            note = f"CSV {row['csv_bytes'] / 1e6:.0f} MB on disk"
        if row["case"] == "aggregate":
            note = f"min/max of {row['columns']} columns"
        lines.append(f"| {row['case']} | {row['angles']:,} | {row['seconds']:.1f} | "
                     f"{row['traced_peak_bytes'] / 1e6:.0f} | {row['max_rss_bytes'] / 1e6:.0f} | "
                     f"{note} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.memory")
    parser.add_argument("--case", choices=CASES, required=True)
    parser.add_argument("--angles", type=int, default=1_000_000)
    parser.add_argument("--trace", action="store_true", help="also trace allocations")
    args = parser.parse_args(argv)
    print(json.dumps(measure(args.case, args.angles, args.trace)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
