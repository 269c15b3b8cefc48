"""Near a group's toggle: how close each stage still solves, and the error estimate against the
measured error — the numbers behind docs/accuracy.md's "What the error estimate is worth"
(``python -m benchmarks.run --only toggle``).

The four-bars of the stress suite whose RRR group reaches its toggle at φ* = 120° (BC and CD
stretched out in line) and at φ* = 200° (folded) are solved at φ* ± 10^-k rad (k = 1…12, on the
side where they assemble), one stage at a time. At each angle solved: s = |sin| of the angle
between the group's construction lines, the estimate the report gives (``error_estimate``,
ε·R/s³ for velocities, ε·R/s⁵ for accelerations) and the measured relative error against the
40-digit closed form (:func:`planmethod.testing.exact_fourbar`): the largest of |Δv_C|/|v_C|,
|Δω_BC|/|ω_BC|, |Δω_CD|/|ω_CD| (and of a_C, ε_BC, ε_CD), never below ε (an exact result
counts as ε). Then, by bisection on log Δφ, the smallest distance from the toggle at which each
stage still solves (a ``ToggleError`` or ``AssemblyError`` nearer).

Examples
--------
>>> row = approach_row(CASES[0][1], CASES[0][2], 1e-3)
>>> row["solved"]["acceleration"], row["estimate"]["velocity"] > row["measured"]["velocity"]
(True, True)
"""

from __future__ import annotations

import math

import numpy as np

from planmethod.errors import AssemblyError, ToggleError
from planmethod.kinematics import solve
from planmethod.testing.stress import EPS, exercise_of, toggle_fourbar

#: (name, case, φ* in degrees)
CASES = [("four-bar, stretched toggle at 120°", toggle_fourbar(120.0), 120.0),
         ("four-bar, folded toggle at 200°", toggle_fourbar(200.0, stretched=False), 200.0)]
STAGES = ("position", "velocity", "acceleration")
#: the quantities whose relative errors are measured, per stage: (point vector, link rates)
MEASURED = {"velocity": ("v_C", ("omega_BC", "omega_CD")),
            "acceleration": ("a_C", ("epsilon_BC", "epsilon_CD"))}


def _side(case, toggle: float) -> float:
    """+1 or −1: the side of φ* where the links assemble (that of the drive angle)."""
    return math.copysign(1.0, case.drive_angle - toggle)


def _errors(motion, case, exact: dict, stage: str) -> tuple[float, float]:
    """(the largest relative error of C's vector and the links' rates; C's error relative to
    the crank's scale V₀ = |ω|·L or A₀ = (ω² + |ε|)·L), each at least ε."""
    vector, rates = MEASURED[stage]
    read = motion.velocity if stage == "velocity" else motion.acceleration
    value = np.asarray(read("C"), dtype=float)
    truth = np.array([float(x) for x in exact[vector]])
    error = float(np.hypot(*(value - truth)))
    errors = [error / float(np.hypot(*truth))]
    for name in rates:
        link = name.split("_")[1]
        found = float(motion.omega(link) if stage == "velocity" else motion.epsilon(link))
        errors.append(abs(found - float(exact[name])) / abs(float(exact[name])))
    omega, epsilon = case.params["omega"], case.params["epsilon"]
    scale = case.length * (abs(omega) if stage == "velocity" else omega ** 2 + abs(epsilon))
    return max(max(errors), EPS), max(error / scale, EPS)


def approach_row(case, toggle: float, distance_rad: float) -> dict:
    """One angle φ* ± ``distance_rad``: what each stage gives."""
    mechanism = exercise_of(case).mechanism
    angle = toggle + _side(case, toggle) * math.degrees(distance_rad)
    exact = case.reference(angle, case.branch)
    row = {"distance_rad": distance_rad, "angle": angle, "sine": abs(float(exact["sine"])),
           "solved": {}, "estimate": {}, "measured": {}, "measured_scale": {}}
    for stage in STAGES:
        try:
            motion = solve(mechanism, angle, stage=stage)
        except (ToggleError, AssemblyError):
            row["solved"][stage] = False
            continue
        row["solved"][stage] = True
        if stage != "position":
            group = motion.groups[0]
            row["estimate"][stage] = float(np.max(group.error_estimate[stage]))
            row["measured"][stage], row["measured_scale"][stage] = _errors(motion.at(0), case,
                                                                          exact, stage)
    return row


def closest_solved(case, toggle: float, stage: str) -> float:
    """The smallest distance from the toggle (rad) at which ``stage`` still solves, to 1 %."""
    mechanism = exercise_of(case).mechanism
    side = _side(case, toggle)

    def solves(log_distance: float) -> bool:
        try:
            solve(mechanism, toggle + side * math.degrees(10.0 ** log_distance), stage=stage)
        except (ToggleError, AssemblyError):
            return False
        return True

    near, far = -16.0, -1.0        # solves at 10^far; below 10^near every angle is φ* itself
    if solves(near):
        return 10.0 ** near
    while far - near > 0.004:
        middle = 0.5 * (near + far)
        if solves(middle):
            far = middle
        else:
            near = middle
    return 10.0 ** far


def _ratios(rows: list[dict], key: str) -> dict[str, tuple[float, float, float]]:
    """Per stage: (min, median, max) of the estimate over the measured error ``key``."""
    out = {}
    for stage in MEASURED:
        values = [row["estimate"][stage] / row[key][stage] for row in rows
                  if stage in row[key]]
        if values:
            out[stage] = (min(values), float(np.median(values)), max(values))
    return out


def run(quick: bool = False) -> dict:
    exponents = range(1, 13) if not quick else (2, 4, 6, 8, 10, 12)
    cases = []
    for name, case, toggle in CASES:
        rows = [approach_row(case, toggle, 10.0 ** -k) for k in exponents]
        cases.append({
            "case": name, "rows": rows,
            "closest_solved_rad": {stage: closest_solved(case, toggle, stage)
                                   for stage in STAGES},
            "estimate_over_measured": _ratios(rows, "measured"),
            "estimate_over_measured_scale": _ratios(rows, "measured_scale")})
    return {"eps": EPS, "cases": cases}


def table(result: dict) -> str:
    lines = ["Errors at φ* ± Δφ (the side that assembles) against the 40-digit closed form. "
             "estimate: the report's `error_estimate` (ε·R/s³ for v, ε·R/s⁵ for a); "
             "relative: the largest relative error of C's vector and the two links' rates; "
             "of V₀/A₀: C's error over the crank's scale V₀ = |ω|·L, A₀ = (ω² + |ε|)·L "
             "(errors below ε count as ε); — = refused (ToggleError).", ""]
    for case in result["cases"]:
        lines += [f"**{case['case']}**", "",
                  "| Δφ (rad) | s | v: estimate | v: relative | v: of V₀ | a: estimate | "
                  "a: relative | a: of A₀ |", "|---|---|---|---|---|---|---|---|"]
        for row in case["rows"]:
            cells = []
            for stage in MEASURED:
                if stage in row["measured"]:
                    cells += [f"{row[key][stage]:.1e}"
                              for key in ("estimate", "measured", "measured_scale")]
                else:
                    cells += ["—"] * 3
            lines.append(f"| {row['distance_rad']:.0e} | {row['sine']:.1e} | "
                         + " | ".join(cells) + " |")
        closest = case["closest_solved_rad"]
        lines += ["", "Closest to the toggle still solved: "
                  + ", ".join(f"{stage} {closest[stage]:.2g} rad" for stage in STAGES) + "."]
        for key, what in (("estimate_over_measured", "the relative error"),
                          ("estimate_over_measured_scale", "C's error over V₀, A₀")):
            lines.append(f"Estimate over {what} (min, median, max): " + "; ".join(
                f"{stage} {low:.2g}, {middle:.2g}, {high:.2g}"
                for stage, (low, middle, high) in case[key].items()) + ".")
        lines.append("")
    return "\n".join(lines)
