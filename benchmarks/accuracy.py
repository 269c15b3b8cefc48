"""Run time against error: what each way of getting velocities and accelerations costs.

On the four-bar of reference case A (docs/reference-cases.md), the velocity and acceleration of
the coupler pin C over a full turn are obtained by

* **exact closed form** — planmethod's :func:`~planmethod.kinematics.solve`, in bulk (N angles
  at once) and one angle at a time;
* **Newton** on the loop equations Φ(q) = 0 (the generic
  :class:`~planmethod.kinematics.constraints.ConstraintSystem`), vectorised over the angles,
  each angle started from the solution at the previous angle (a continuation sweep), stopped
  when max |Φ| ≤ tol, for several tolerances; velocities and accelerations then follow from
  the exact linear solves at the Newton positions;
* **finite differences** of the exact positions, central, with angle steps h:
  v ≈ ω·(p(φ+h) − p(φ−h))/2h, a ≈ ω²·(p(φ+h) − 2p(φ) + p(φ−h))/h²;
* **the graphical emulation** (:func:`~planmethod.plans.draw_plans`) at several drawing scales
  (the crank and the plan vectors of the crank pin drawn 10…200 mm long) and drafting
  precisions (every length laid off or read rounded to 1, 0.5, 0.25, 0.1 mm); what is
  compared is what a student reads off: the magnitudes (pc)·μv and (πc)·μa.

The error is max over the sampled angles of |value − exact| / max over the turn of |exact|
(vectors; magnitudes for the plans), the exact values from the 40-digit
:mod:`planmethod.testing.oracles`; the time is per crank angle.

Examples
--------
>>> import numpy as np
>>> from benchmarks.common import exercise
>>> mechanism = exercise("fourbar").mechanism
>>> q, iterations = newton_positions(mechanism, np.array([0.0, 90.0]), tol=1e-12)
>>> iterations <= 6
True
"""

from __future__ import annotations

import dataclasses

import numpy as np

from planmethod.kinematics import solve
from planmethod.kinematics.constraints import ConstraintSystem
from planmethod.kinematics.state import LinkState
from planmethod.model import FRAME
from planmethod.plans import draw_plans
from planmethod.testing import exact_fourbar as fourbar_reference

from .common import best_time, exercise, full_turn

UNKNOWN = ("BC", "CD")
NEWTON_TOLERANCES = (1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-13)
STEPS_DEG = (3.0, 1.0, 0.1, 1e-2, 1e-3, 1e-4, 1e-5)
SCALES_MM = (10.0, 30.0, 100.0, 200.0)
PRECISIONS_MM = (1.0, 0.5, 0.25, 0.1)


# -- the exact reference ------------------------------------------------------------------------
def reference(angles) -> tuple[np.ndarray, np.ndarray]:
    """C's velocity and acceleration from the 40-digit reference, (N, 2) each."""
    v = np.empty((len(angles), 2))
    a = np.empty((len(angles), 2))
    for k, phi in enumerate(angles):
        exact = fourbar_reference(float(phi))
        v[k] = [float(x) for x in exact["v_C"]]
        a[k] = [float(x) for x in exact["a_C"]]
    return v, a


def error(values: np.ndarray, exact: np.ndarray, scale: float) -> float:
    """Vector error for (N, 2) values; for (N,) values (magnitudes read off a plan) the error
    of the magnitude."""
    values = np.asarray(values, dtype=float)
    if not np.all(np.isfinite(values)):
        return float("inf")
    if values.ndim == 1:
        return float(np.max(np.abs(values - np.hypot(*exact.T)))) / scale
    return float(np.max(np.hypot(*(values - exact).T))) / scale


# -- Newton on the loop equations ----------------------------------------------------------------
def _states(mechanism, angles, q):
    base = solve(mechanism, angles, links=())  # the frame and the drive only
    states = {FRAME: base.links[FRAME], mechanism.drive.link: base.links[mechanism.drive.link]}
    for index, link in enumerate(UNKNOWN):
        states[link] = LinkState(q[:, 3 * index + 2], q[:, 3 * index:3 * index + 2].copy())
    return states


def newton_positions(mechanism, angles, *, tol: float, max_iterations: int = 50):
    """Positions (x, y, θ of BC and CD, (N, 6)) by Newton from the previous angle's exact
    solution; returns (q, iterations)."""
    exact = solve(mechanism, angles, stage="position")
    q = np.concatenate([np.column_stack((exact.links[link].origin,
                                         exact.links[link].theta)) for link in UNKNOWN], axis=1)
    q = np.roll(q, 1, axis=0)  # each angle starts where the previous one ended
    system = ConstraintSystem.between(mechanism, UNKNOWN)
    base = solve(mechanism, angles, links=())
    fixed = {FRAME: base.links[FRAME], mechanism.drive.link: base.links[mechanism.drive.link]}
    for iteration in range(max_iterations + 1):
        states = dict(fixed)
        for index, link in enumerate(UNKNOWN):
            states[link] = LinkState(q[:, 3 * index + 2], q[:, 3 * index:3 * index + 2].copy())
        residual = system.residual(states)
        if float(np.max(np.abs(residual))) <= tol:
            return q, iteration
        matrix, _ = system.jacobian(states)
        q = q - np.linalg.solve(matrix, residual[..., None])[..., 0]
    raise RuntimeError(f"Newton did not reach {tol:g} in {max_iterations} iterations")


def newton_motion(mechanism, angles, *, tol: float):
    """C's velocity and acceleration from Newton positions and exact linear solves."""
    q, _ = newton_positions(mechanism, angles, tol=tol)
    system = ConstraintSystem.between(mechanism, UNKNOWN)
    states = _states(mechanism, angles, q)
    moving = system.moving_states(states)["BC"]
    c = moving.place(mechanism.local("BC", "C"))
    return moving.velocity_at(c), moving.acceleration_at(c)


# -- finite differences ----------------------------------------------------------------------------
def finite_differences(mechanism, angles, *, step_deg: float):
    omega = mechanism.drive.omega
    h = np.radians(step_deg)
    ahead = solve(mechanism, angles + step_deg, stage="position").position("C")
    here = solve(mechanism, angles, stage="position").position("C")
    behind = solve(mechanism, angles - step_deg, stage="position").position("C")
    return (omega * (ahead - behind) / (2 * h),
            omega ** 2 * (ahead - 2 * here + behind) / (h * h))


# -- the graphical emulation ---------------------------------------------------------------------
def drawn(exercise_, angles, *, scale_mm: float, precision_mm: float):
    settings = dataclasses.replace(exercise_.plan, crank_mm=scale_mm, velocity_mm=scale_mm,
                                   acceleration_mm=scale_mm, mu_l=None, mu_v=None, mu_a=None,
                                   precision_mm=precision_mm)
    v = np.empty(len(angles))
    a = np.empty(len(angles))
    for k, angle in enumerate(angles):
        plans = draw_plans(exercise_, float(angle), settings=settings)
        v[k] = plans.readings["v_C"]  # (pc)·μv and (πc)·μa, as read off the drawing
        a[k] = plans.readings["a_C"]
    return v, a


def run(quick: bool = False, *, log=print) -> dict:
    ex = exercise("fourbar")
    mechanism = ex.mechanism
    count = 120 if quick else 360
    plan_count = 24 if quick else 72
    min_time = 0.1 if quick else 0.3
    angles = full_turn(count)
    plan_angles = full_turn(plan_count) + 2.5  # off the grid points of the other methods
    v_exact, a_exact = reference(angles)
    v_plan_exact, a_plan_exact = reference(plan_angles)
    v_scale = float(np.max(np.hypot(*v_exact.T)))
    a_scale = float(np.max(np.hypot(*a_exact.T)))
    rows: list[dict] = []

    def record(method, parameter, label, value_pair, seconds, per, exact=(v_exact, a_exact)):
        rows.append({"method": method, "parameter": parameter, "label": label,
                     "time_per_angle": seconds / per,
                     "velocity_error": error(value_pair[0], exact[0], v_scale),
                     "acceleration_error": error(value_pair[1], exact[1], a_scale)})

    log("  exact closed form …")

    def exact_bulk():
        motion = solve(mechanism, angles)
        return motion.velocity("C"), motion.acceleration("C")

    timing = best_time(exact_bulk, min_time=min_time)
    record("exact", count, f"closed form, {count} angles at once", exact_bulk(),
           timing["best"], count)

    def exact_single():
        out_v, out_a = [], []
        for angle in plan_angles:
            motion = solve(mechanism, float(angle)).at(0)
            out_v.append(motion.velocity("C"))
            out_a.append(motion.acceleration("C"))
        return np.array(out_v), np.array(out_a)

    timing = best_time(exact_single, min_time=min_time, min_repeats=1)
    record("exact", 1, "closed form, one angle per call", exact_single(), timing["best"],
           plan_count, (v_plan_exact, a_plan_exact))
    log("  Newton …")
    for tol in NEWTON_TOLERANCES:
        timing = best_time(lambda t=tol: newton_motion(mechanism, angles, tol=t),
                           min_time=min_time)
        _, iterations = newton_positions(mechanism, angles, tol=tol)
        record("newton", tol, f"tol {tol:g} m ({iterations} iterations)",
               newton_motion(mechanism, angles, tol=tol), timing["best"], count)
    log("  finite differences …")
    for step in STEPS_DEG:
        timing = best_time(lambda s=step: finite_differences(mechanism, angles, step_deg=s),
                           min_time=min_time)
        record("finite differences", step, f"h = {step:g}°",
               finite_differences(mechanism, angles, step_deg=step), timing["best"], count)
    log("  graphical emulation …")
    for scale in SCALES_MM:
        for precision in PRECISIONS_MM if scale == 30.0 else (0.5,):
            timing = best_time(lambda s=scale, p=precision: drawn(ex, plan_angles, scale_mm=s,
                                                                  precision_mm=p),
                               min_time=min_time, min_repeats=1)
            record("plans", [scale, precision], f"{scale:g} mm, ±{precision:g} mm",
                   drawn(ex, plan_angles, scale_mm=scale, precision_mm=precision),
                   timing["best"], plan_count, (v_plan_exact, a_plan_exact))
    timing = best_time(lambda: drawn(ex, plan_angles, scale_mm=30.0, precision_mm=0.0),
                       min_time=min_time, min_repeats=1)
    record("plans", [30.0, 0.0], "30 mm, exact construction",
           drawn(ex, plan_angles, scale_mm=30.0, precision_mm=0.0), timing["best"],
           plan_count, (v_plan_exact, a_plan_exact))
    return {"mechanism": "four-bar, reference case A", "point": "C",
            "angles": count, "plan_angles": plan_count, "rows": rows}


STYLES = {"exact": ("black", "*"), "newton": ("tab:blue", "o"),
          "finite differences": ("tab:orange", "s"), "plans": ("tab:green", "^")}
NAMES = {"exact": "exact closed form", "newton": "Newton, tolerance tol",
         "finite differences": "finite differences, step h",
         "plans": "graphical plans, scale ± precision"}


def _merged(rows, key):
    """Rows at (nearly) the same point of the plot, with their labels joined."""
    groups: list[list[dict]] = []
    for row in rows:
        for group in groups:
            first = group[0]
            if (abs(np.log10(max(row[key], 1e-17) / max(first[key], 1e-17))) < 0.05
                    and abs(np.log10(row["time_per_angle"] / first["time_per_angle"])) < 0.05):
                group.append(row)
                break
        else:
            groups.append([row])
    return groups


OFFSETS = {"exact": (6, -4, "left"), "newton": (7, 0, "left"),
           "finite differences": (-7, 0, "right"), "plans": (-7, 0, "right")}


def figure(result: dict):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    floor = 1e-17
    fig = Figure(figsize=(13, 6))
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, 2, sharey=True)
    for axis, key, title in ((axes[0], "velocity_error", "velocity of C"),
                             (axes[1], "acceleration_error", "acceleration of C")):
        for method, (color, marker) in STYLES.items():
            rows = [r for r in result["rows"] if r["method"] == method]
            xs = [r["time_per_angle"] * 1e6 for r in rows]
            ys = [max(r[key], floor) for r in rows]
            line = "-" if method in ("newton", "finite differences") else "none"
            axis.plot(xs, ys, color=color, marker=marker, linestyle=line, alpha=0.85,
                      label=NAMES[method], markersize=7)
            dx, dy, align = OFFSETS[method]
            groups = sorted(_merged(rows, key), key=lambda g: g[0][key])
            for number, group in enumerate(groups):
                if method == "plans" and number % 2:  # alternate sides: the points are dense
                    dx, align = 7, "left"
                elif method == "plans":
                    dx, align = -7, "right"
                labels = [r["label"].split(" (")[0].replace("closed form, ", "")
                          for r in group]
                x = group[0]["time_per_angle"] * 1e6
                y = max(group[0][key], floor)
                axis.annotate("; ".join(labels), (x, y), fontsize=6.5, color=color,
                              textcoords="offset points", xytext=(dx, dy), ha=align,
                              va="center")
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlim(0.3, 1e4)
        axis.set_xlabel("time per crank angle (µs)")
        axis.set_title(title)
        axis.axhline(np.finfo(float).eps, color="grey", linewidth=0.8, linestyle=":")
        axis.grid(True, which="major", alpha=0.3)
    axes[0].set_ylabel("max error / max |exact| over the turn")
    axes[1].legend(fontsize=8, loc="center right")
    fig.suptitle(f"Four-bar (case A), point C: run time against error "
                 f"({result['angles']} angles; plans at {result['plan_angles']} angles, "
                 "magnitudes as read off)")
    fig.tight_layout()
    return fig


def table(result: dict) -> str:
    lines = ["| method | setting | µs per angle | error of v_C | error of a_C |",
             "|---|---|---|---|---|"]
    for r in result["rows"]:
        lines.append(f"| {NAMES[r['method']].split(',')[0]} | {r['label']} | "
                     f"{r['time_per_angle'] * 1e6:.3g} | {r['velocity_error']:.1e} | "
                     f"{r['acceleration_error']:.1e} |")
    return "\n".join(lines) + "\n"
