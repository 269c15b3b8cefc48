"""Full-turn speed: planmethod against the open-source peers, in the same run, same machine.

For each mechanism (case A four-bar; Abduvaliev & Abduxoshimov's slider-crank) and each N, the
time of a full-turn analysis — positions, velocities and accelerations of every point at N
crank angles — divided by N:

* ``planmethod``: ``solve(mechanism, angles)`` and then ``position``, ``velocity``,
  ``acceleration`` of every point, called again and again with the same frozen model, whose
  structure, branch choice and traced program (:func:`planmethod.kinematics.program.model`,
  cached by the model's value) are kept after the first call — as the peers reuse their built
  and compiled models;
* ``planmethod (new model each call)``: the same with a new (equal) model object at every call,
  so that every call pays the structural analysis, the branch choice and the compilation;
* each peer (:mod:`benchmarks.peers`) inside its own virtualenv, timed in its subprocess.

The error of each tool is that of C's position, velocity and acceleration over the whole turn,
relative to the largest magnitude of each over the turn, against planmethod's exact values
(themselves checked against the 40-digit :mod:`planmethod.testing.oracles` here and in the stress
suite).

Examples
--------
>>> from benchmarks.common import exercise
>>> table = planmethod_times(exercise("fourbar").mechanism, [36], min_time=0.0,
...                          floor_name="fourbar")
>>> sorted(table[36])
['floor', 'fresh', 'reused']
"""

from __future__ import annotations

import dataclasses

import numpy as np

from planmethod.kinematics import solve
from planmethod.testing import exact_fourbar as fourbar_reference
from planmethod.testing import exact_slider_crank as slider_reference

from . import floor
from . import peers as peer_tools
from .common import exercise, full_turn, interleaved_best_times, microseconds

COUNTS = (360, 3600, 36000)
QUICK_COUNTS = (360, 3600)
MECHANISMS = ("fourbar", "slider_crank")
TITLES = {"fourbar": "four-bar (case A)",
          "slider_crank": "slider-crank (Abduvaliev & Abduxoshimov)"}
FLOOR = "numpy floor (hand-fused, this mechanism only)"
FRESH = "planmethod (new model each call)"
COLORS = {"planmethod": "black", FRESH: "black", "pylinkage": "tab:blue",
          "mechanism": "tab:orange", "kimech": "tab:green", "fourbarhinge": "tab:purple",
          "kinepy": "tab:red", FLOOR: "grey"}


def every_point(mechanism) -> list[str]:
    return list(dict.fromkeys(p for link in mechanism.links.values() for p in link.points))


def full_analysis(mechanism, angles, points):
    """Positions, velocities and accelerations of every point at every angle."""
    motion = solve(mechanism, angles)
    return {p: (motion.position(p), motion.velocity(p), motion.acceleration(p))
            for p in points}


def planmethod_times(mechanism, counts, *, min_time: float = 0.5, floor_name=None) -> dict:
    """Best times of the full analysis at each count: ``reused`` (the same model object at
    every call) and ``fresh`` (a new, equal model object at every call), and with
    ``floor_name`` the numpy floor's (:mod:`benchmarks.floor`) — taken in turn, one call of
    each per round, so that the ratios hold on a machine whose load changes."""
    points = every_point(mechanism)
    # more new models than calls: none of them is met twice (the program cache keeps 64)
    fresh = [dataclasses.replace(mechanism) for _ in range(2048)]
    out = {}
    for count in counts:
        angles = full_turn(count)
        full_analysis(mechanism, angles, points)  # warm-up
        models = iter(fresh)
        functions = {
            "reused": lambda a=angles: full_analysis(mechanism, a, points),
            "fresh": lambda a=angles, m=models: full_analysis(next(m), a, points),
        }
        if floor_name is not None:
            phi = np.radians(angles)
            function = floor.RUNNERS[floor_name]
            function(phi)
            functions["floor"] = lambda p=phi, f=function: f(p)
        out[count] = interleaved_best_times(functions, min_time=min_time,
                                            max_repeats=len(fresh))
    return out


def exact_c(mechanism, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    motion = solve(mechanism, full_turn(count))
    return motion.position("C"), motion.velocity("C"), motion.acceleration("C")


def relative_errors(arrays, exact) -> dict:
    """max |tool − exact| / max |exact| over the turn, for C's position, velocity and
    acceleration."""
    out = {}
    for name, mine, truth in zip(("position", "velocity", "acceleration"), arrays, exact,
                                 strict=True):
        mine = np.asarray(mine, dtype=float)
        if mine.shape != truth.shape or not np.all(np.isfinite(mine)):
            out[name] = None
            continue
        scale = float(np.max(np.hypot(truth[:, 0], truth[:, 1])))
        out[name] = float(np.max(np.hypot(*(mine - truth).T))) / scale
    return out


def planmethod_error(name: str, mechanism, count: int = 360) -> dict:
    """planmethod's own error against the 40-digit reference at ``count`` angles."""
    position, velocity, acceleration = exact_c(mechanism, count)
    reference = np.empty((3, count, 2))
    for k, phi in enumerate(full_turn(count)):
        exact = fourbar_reference(phi) if name == "fourbar" else slider_reference(phi)
        for row, key in enumerate(("C", "v_C", "a_C")):
            reference[row, k] = [float(exact[key][0]), float(exact[key][1])]
    return relative_errors((position, velocity, acceleration), tuple(reference))


def floor_record(name: str, mechanism, counts, times: dict) -> dict:
    """The hand-fused numpy closed form of :mod:`benchmarks.floor` (not general: this one
    mechanism only): its times (taken with planmethod's) and its error."""
    function = floor.RUNNERS[name]
    count = counts[-1]
    out = function(np.radians(full_turn(count)))
    cy = out.get("cy", np.zeros(count))
    vcy = out.get("vcy", np.zeros(count))
    acy = out.get("acy", np.zeros(count))
    arrays = (np.column_stack((out["cx"], cy)), np.column_stack((out["vcx"], vcy)),
              np.column_stack((out["acx"], acy)))
    return {"runs": {str(c): times[c]["floor"] for c in counts},
            "error": relative_errors(arrays, exact_c(mechanism, count)), "error_at": count}


def run(quick: bool = False, *, log=print) -> dict:
    counts = QUICK_COUNTS if quick else COUNTS
    min_time = 0.2 if quick else 0.5
    result: dict = {"counts": list(counts), "mechanisms": {}}
    have_peers = peer_tools.available()
    if not have_peers:
        log(f"  (no peers' virtualenv at {peer_tools.venv_path()}: run "
            "`python -m benchmarks.peers --setup` to compare against them)")
    for name in MECHANISMS:
        mechanism = exercise(name).mechanism
        log(f"  {TITLES[name]}: planmethod …")
        times = planmethod_times(mechanism, counts, min_time=min_time, floor_name=name)
        entry = {"planmethod": {"runs": {str(c): times[c]["reused"] for c in counts},
                                "error": planmethod_error(name, mechanism)},
                 FRESH: {"runs": {str(c): times[c]["fresh"] for c in counts}},
                 FLOOR: floor_record(name, mechanism, counts, times)}
        if have_peers:
            for peer in peer_tools.PEERS:
                log(f"  {TITLES[name]}: {peer} …")
                report, arrays = peer_tools.run_peer(peer, name, list(counts),
                                                     budget=8.0 if quick else 20.0,
                                                     min_time=min_time)
                record = {"version": report.get("version"),
                          "runs": {str(k): v for k, v in report.get("runs", {}).items()}}
                for key in ("unsupported", "failed"):
                    if key in report:
                        record[key] = report[key]
                if arrays is not None:
                    count = int(arrays["count"])
                    record["error"] = relative_errors(
                        (arrays["position"], arrays["velocity"], arrays["acceleration"]),
                        exact_c(mechanism, count))
                    record["error_at"] = count
                entry[peer] = record
        result["mechanisms"][name] = entry
    return result


def per_angle(run_record: dict | None, count: int) -> float | None:
    if not run_record or "best" not in run_record:
        return None
    return run_record["best"] / count


def table(result: dict) -> str:
    """The Markdown table: µs per angle (best of repeats) and the ratio to planmethod."""
    counts = result["counts"]
    lines = []
    for name, entry in result["mechanisms"].items():
        lines += [f"**{TITLES[name]}** — µs per crank angle (positions, velocities and "
                  "accelerations of every point), best of repeats; ×: the tool's time over "
                  "planmethod's; error: max over the turn of |C − exact| / max |exact| for "
                  "position / velocity / acceleration", ""]
        header = "| tool | " + " | ".join(f"N = {c:,}" for c in counts) + " | error p / v / a |"
        lines += [header, "|" + "---|" * (len(counts) + 2)]
        base = entry["planmethod"]["runs"]
        for tool, record in entry.items():
            cells = []
            for count in counts:
                mine = per_angle(record["runs"].get(str(count)), count)
                ours = per_angle(base.get(str(count)), count)
                if mine is None:
                    skipped = record["runs"].get(str(count), {}).get("skipped")
                    cells.append("—" if not skipped else "skipped")
                    continue
                ratio = "" if tool == "planmethod" else f" (×{mine / ours:.3g})"
                cells.append(f"{microseconds(mine)}{ratio}")
            if "unsupported" in record:
                cells = ["not supported"] * len(counts)
            if "failed" in record:
                cells = ["failed"] * len(counts)
            error = record.get("error")
            error_text = " / ".join("—" if error.get(k) is None else f"{error[k]:.1e}"
                                    for k in ("position", "velocity", "acceleration")
                                    ) if error else "—"
            label = tool if not record.get("version") else f"{tool} {record['version']}"
            lines.append(f"| {label} | " + " | ".join(cells) + f" | {error_text} |")
        lines.append("")
    return "\n".join(lines)


def figure(result: dict):
    """Time per angle against N, one panel per mechanism, log–log."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    counts = result["counts"]
    fig = Figure(figsize=(11, 4.2))
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, len(result["mechanisms"]), sharey=True)
    for axis, (name, entry) in zip(np.atleast_1d(axes), result["mechanisms"].items(),
                                   strict=True):
        for tool, record in entry.items():
            xs, ys = [], []
            for count in counts:
                value = per_angle(record["runs"].get(str(count)), count)
                if value is not None:
                    xs.append(count)
                    ys.append(value * 1e6)
            if not xs:
                continue
            style = {"linewidth": 1.5, "color": COLORS.get(tool, "grey")}
            if tool == "planmethod":
                style["linewidth"] = 2.8
            if tool in (FRESH, FLOOR):
                style["linestyle"] = "--" if tool != FLOOR else ":"
            label = tool if not record.get("version") else f"{tool} {record['version']}"
            axis.plot(xs, ys, marker="o", label=label, **style)
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_title(TITLES[name])
        axis.set_xlabel("crank angles N per full turn")
        axis.grid(True, which="both", alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("µs per angle (p, v, a of every point)")
    handles: dict = {}
    for axis in np.atleast_1d(axes):
        for handle, label in zip(*axis.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, handle)
    fig.suptitle("Full-turn kinematics: time per crank angle (lower is better), one run, "
                 "one machine")
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.legend(list(handles.values()), list(handles), loc="lower center", ncol=4, fontsize=8,
               frameon=False)
    return fig
