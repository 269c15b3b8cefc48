"""The long run of the stress suite: ``python -m benchmarks.run --only stress``.

Every scenario of :func:`planmethod.testing.stress.scenarios` (crank dead centres and group
toggles approached to 1e-12 rad, Grashof-limit four-bars, link-length ratios from 1e-6 to 1e6,
absolute sizes from 1e-6 to 1e6 m, ω up to 1e4 rad/s with ε up to 1e8 rad/s²) and 400 random
mechanisms over full turns, each angle judged by :func:`planmethod.testing.stress.check`
against the 40-digit reference (the stated bounds are described there); the results go to
``benchmarks/results/stress.md``. ``tests/test_stress.py`` runs a fast subset.

Examples
--------
>>> print(table({"K": 16.0, "eps": 2.2e-16, "scenarios": []}).splitlines()[-1])
|---|---|---|---|---|---|---|---|---|
"""

from __future__ import annotations

import random

import numpy as np

from planmethod.testing.stress import (
    EPS,
    NEAR_SINGULAR,
    K,
    assemblable,
    check,
    random_case,
    scenarios,
    summary,
)


def run(quick: bool = False, *, log=print, seed: int = 20261121) -> dict:
    results = []
    for title, case, angles in scenarios(quick):
        log(f"  {title} …")
        rows = check(case, angles)
        results.append({"scenario": title, **summary(rows),
                        "examples": [r for r in rows if r["violation"]][:5]})
    generator = random.Random(seed)
    count = 40 if quick else 400
    rows: list[dict] = []
    made = 0
    log(f"  {count} random mechanisms over full turns …")
    while made < count:
        case = random_case(generator)
        if not assemblable(case):
            continue
        made += 1
        rows += check(case, np.arange(0.0, 360.0, 10.0 if quick else 2.0))
    results.append({"scenario": f"{count} random mechanisms, full turns", **summary(rows),
                    "examples": [r for r in rows if r["violation"]][:5]})
    return {"K": K, "eps": EPS, "near_singular": NEAR_SINGULAR, "seed": seed,
            "scenarios": results}


def table(result: dict) -> str:
    lines = [f"Stated bound: |ΔC| ≤ K·ε·L/s, |Δv| ≤ K·ε·R·max(V₀/s³, V/s²), "
             f"|Δa| ≤ K·ε·R·max(A₀/s⁵, A/s²) with "
             f"K = {result['K']:g}, ε = {result['eps']:.3g}; worst = the largest error over "
             "its bound among the solved angles (≤ 1 passes).", "",
             "| scenario | angles | solved | AssemblyError | ToggleError | violations | "
             "worst error/bound | smallest s solved | worst relative error p / v / a |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in result["scenarios"]:
        smallest = "—" if r["smallest_sine_solved"] is None else (
            f"{r['smallest_sine_solved']:.1e}")
        rel = " / ".join(f"{x:.1e}" for x in r["worst_relative"])
        lines.append(f"| {r['scenario']} | {r['angles']} | {r['ok']} | {r['assembly_errors']} "
                     f"| {r['toggle_errors']} | {r['violations']} | {r['worst_ratio']:.2g} | "
                     f"{smallest} | {rel} |")
    return "\n".join(lines) + "\n"
