"""The interactive workbook's speed: one position, a whole page, and the browser's frame switch.

*Per position* (median over 12 crank angles, ms): ``analyse`` (kinematics, plans data and
forces), ``plan_files`` (every drawing of a workbook frame as SVG: ``solve --svg``'s set without
the enlarged details and the loaded mechanism) and the answer key of the angle (``build_key``:
the tolerances of ``planmethod grade``), for the compressor slider-crank and the six-link
conveyor. *Page*: ``planmethod workbook`` of the full turn at 1° (360 frames), wall time with
its default worker processes and the page's size, the CPU time of the build (its serial part)
and of its workers, and the load factor of as many processes at once as it has workers.
*Browser*: the page opened from ``file://`` in headless Chromium (Playwright), the slider moved
through 36 angles one step at a time, 40 ms apart (a hand on the slider); the time of each frame
switch as the page itself records it (swap the drawings and the readings, lay the page out; the
page parses the neighbouring frames while idle). *Drawing mode*: at 12 angles the right velocity
and acceleration plans are placed, the page drawn, and each plan's check button clicked, each
check as the page times it (compare every point with its disc and the mistakes' positions, write
the verdicts, lay them out): best of three passes per angle, and the page's first check apart. A
full run also writes ``figures/workbook.png``, the screenshot in README. *Terminated*: SIGTERM
to ``planmethod workbook`` alone while two workers solve the conveyor's frames, the time until
it has ended and the processes of it left.

Targets of issue 13: plans + SVG ≤ 10 ms (compressor) and ≤ 40 ms (conveyor) per position, the
conveyor's ``analyse`` ≤ 20 ms, 360 frames in ≤ 5 s (compressor) and ≤ 20 s (conveyor), the
compressor's page ≤ 3 MB at 1°, a frame switch ≤ 16 ms. Issue 21 keeps the page's targets with
the drawing data included, and grading a drawn plan in the page ≤ 5 ms.

Examples
--------
>>> sorted(TARGETS_MS)
['compressor', 'conveyor']
"""

from __future__ import annotations

import statistics
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from planmethod.application.workbook import build_workbook, exercise_variant
from planmethod.grading.keys import build_key
from planmethod.render.figures import plan_files
from planmethod.report import analyse
from planmethod.spec import load_exercise

from .common import (
    FIGURES,
    ROOT,
    browser_launcher,
    load_factor,
    load_sentence,
    reference_workload,
    run_load,
)

FILES = {"compressor": "exercises/compressor_slider_crank.toml",
         "conveyor": "exercises/conveyor_sixbar.toml"}

#: issue 13's targets: (analyse, plans + SVG) per position in ms, and 360 frames in s
TARGETS_MS = {"compressor": {"analyse": None, "plan_files": 10.0, "page_s": 5.0},
              "conveyor": {"analyse": 20.0, "plan_files": 40.0, "page_s": 20.0}}
PAGE_LIMIT_MB = 3.0
SWITCH_LIMIT_MS = 16.0
CHECK_LIMIT_MS = 5.0
#: issue 24: SIGTERM to the command alone ends it and its workers within this (s)
SIGTERM_LIMIT_S = 2.0

#: the drawing mode in the page: place the right plans of the angle shown (the key's points,
#: which the page holds) through the page's own placing function; the plans placed
_PLACE_PLANS = """() => {
    const draw = workbook.draw, frame = workbook.data.frames[workbook.frame].draw;
    for (const plan of Object.keys(frame))
        for (const [label, [x, y]] of Object.entries(frame[plan].points))
            draw.place(plan, label, x, y);
    return Object.keys(frame);
}"""
#: resolves once the page has drawn what was done before (two animation frames)
_SETTLED = "() => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))"
_TO_ANGLE = """(slider, angle) => {
    slider.value = angle;
    slider.dispatchEvent(new Event("input", {bubbles: true}));}"""


def per_position(name: str, count: int = 12) -> dict:
    exercise = load_exercise(ROOT / FILES[name])
    variant = exercise_variant(exercise)
    times: dict[str, list[float]] = {"analyse": [], "plan_files": [], "key": []}
    analyse(exercise, 0.0)  # warm the caches a sweep also keeps
    for number in range(count):
        angle = 7.0 + number * 360.0 / count
        start = time.perf_counter()
        analysis = analyse(exercise, angle)
        middle = time.perf_counter()
        plan_files(analysis.plans, forces=analysis.forces, details=False, loaded=False)
        end = time.perf_counter()
        build_key(replace(variant, exercise=analysis.exercise))
        times["analyse"].append(middle - start)
        times["plan_files"].append(end - middle)
        times["key"].append(time.perf_counter() - end)
    return {stage: 1000.0 * statistics.median(values) for stage, values in times.items()}


def _cpu_seconds() -> tuple[float, float]:
    """CPU seconds of this process and of its children ended (the build's workers)."""
    import resource

    own, ended = (resource.getrusage(who) for who in (resource.RUSAGE_SELF,
                                                       resource.RUSAGE_CHILDREN))
    return own.ru_utime + own.ru_stime, ended.ru_utime + ended.ru_stime


def whole_page(name: str, step: float, folder: Path) -> dict:
    """``build_workbook`` of the whole turn at ``step``: its wall time, the CPU time of it
    (``own_cpu_seconds``: what this process did, the page's serial part included) and of its
    workers (``workers_cpu_seconds``: all the frames' work, whatever the load lets them run
    in), its workers and the page's size."""
    from planmethod.application.workers import worker_count

    exercise = load_exercise(ROOT / FILES[name])
    start, (own, ended) = time.perf_counter(), _cpu_seconds()
    page = build_workbook(exercise, step)
    seconds = time.perf_counter() - start
    own_after, ended_after = _cpu_seconds()
    path = folder / f"{name}.html"
    path.write_text(page, encoding="utf-8")
    frames = round(360 / step)
    return {"frames": frames, "seconds": seconds,
            "cpu_seconds": own_after - own + ended_after - ended,
            "own_cpu_seconds": own_after - own, "workers_cpu_seconds": ended_after - ended,
            "workers": worker_count(None, frames),
            "megabytes": len(page.encode("utf-8")) / 1e6, "path": str(path)}


def _reference_median(count: int) -> float:
    """The median wall time (ms) of ``count`` runs of the reference workload here (one
    process of :func:`parallel_load_factor`)."""
    reference_workload()
    times = []
    for _ in range(count):
        start = time.perf_counter()
        reference_workload()
        times.append(1000 * (time.perf_counter() - start))
    return statistics.median(times)


def parallel_load_factor(processes: int, count: int = 15) -> dict:
    """How much this run's load stretches a job of ``processes`` processes at once (a
    workbook's workers): the reference workload run in that many processes together, the
    median of their medians against the fastest single run ever seen here (see
    :func:`benchmarks.common.load_factor`). On a shared machine one process may find a CPU
    free where two find only one: the factor of one process understates what the load costs
    a page built by two.

    >>> found = parallel_load_factor(1, 3)
    >>> found["processes"], found["factor"] > 0
    (1, True)
    """
    import multiprocessing

    with multiprocessing.get_context("fork").Pool(processes) as pool:
        medians = pool.map(_reference_median, [count] * processes)
    idle = load_factor(1)["idle_reference_ms"]
    wall = statistics.median(medians)
    return {"processes": processes, "reference_ms": wall, "idle_reference_ms": idle,
            "factor": wall / idle}


def browser_switch(path: str, screenshot: Path | None = None) -> dict | None:
    found = browser_launcher()
    if found is None:
        return None
    sync_playwright, chromium = found
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        start = time.perf_counter()
        page.goto(Path(path).as_uri())
        page.wait_for_function("window.workbook && window.workbook.ready", timeout=120_000)
        load = time.perf_counter() - start
        angles = page.evaluate("workbook.data.angles")
        chosen = angles[1:37]
        for angle in chosen:
            page.eval_on_selector("#angle", _TO_ANGLE, angle)
            page.wait_for_timeout(40)  # a hand on the slider: at most 25 moves a second
        times = page.evaluate("workbook.switchTimes")[1:]
        page.check("#draw-mode")
        first, checks = drawn_plan_checks(page, angles[::max(1, len(angles) // 12)][:12])
        page.evaluate("localStorage.clear()")
        page.check("#watch")        # back to watching (the modes are radios)
        if screenshot is not None:
            page.eval_on_selector("#angle", _TO_ANGLE, 60)
            page.select_option("#step-plan", "velocity")
            for _ in range(5):
                page.click("#step-next")
            page.set_viewport_size({"width": 1400, "height": 1200})
            page.check("#compact")          # the four drawings at once, two to a row
            page.evaluate("window.scrollTo(0, 0)")
            page.screenshot(path=str(screenshot), clip={"x": 0, "y": 0, "width": 1400,
                                                        "height": 1200})
        browser.close()
    return {"switches": len(times), "median_ms": statistics.median(times),
            "max_ms": max(times), "load_s": load, "checks": len(checks),
            "check_median_ms": statistics.median(checks), "check_max_ms": max(checks),
            "check_first_ms": first}


def drawn_plan_checks(page, angles: list[float], passes: int = 3) -> tuple[float, list[float]]:
    """Each plan checked at ``angles`` as a student checks it: the right points placed, the
    page drawn, then the plan's check button clicked; each time as the page takes it (compare
    every point with its disc and the mistakes' positions, write the verdicts, lay them out).
    The angles are gone through ``passes`` times and each plan's best time at each angle kept
    (a spike of a shared machine is not the page's). Returns the page's first check, whose
    code is not yet compiled hot, apart, and the best times."""
    best: dict[tuple[float, str], float] = {}
    first = None
    for _ in range(passes):
        for angle in angles:
            page.eval_on_selector("#angle", _TO_ANGLE, angle)
            plans = page.evaluate(_PLACE_PLANS)
            page.evaluate(_SETTLED)
            for plan in plans:
                page.click(f'[data-check="{plan}"]')
                took = page.evaluate("workbook.draw.checkTimes.at(-1)")
                first = took if first is None else first
                best[angle, plan] = min(best.get((angle, plan), took), took)
    return first, list(best.values())


def terminated_mid_run(folder: Path) -> dict | None:
    """SIGTERM to ``planmethod workbook`` alone while its two workers solve frames: how long
    the command takes to end, and how many of its processes are left once it has (None
    without /proc or two CPUs)."""
    import signal
    import subprocess
    import sys

    from planmethod.application.workers import usable_cpus
    from planmethod.testing.processes import processes_holding

    if not Path("/proc/self/cmdline").exists() or usable_cpus() < 2:
        return None
    page = folder / "terminated-page.html"
    process = subprocess.Popen([sys.executable, "-m", "planmethod", "workbook",
                                str(ROOT / FILES["conveyor"]), "-o", str(page), "--step", "1",
                                "--jobs", "2"], cwd=ROOT, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while (len([pid for pid in processes_holding(str(page)) if pid != process.pid]) < 2
               and time.monotonic() < deadline):
            time.sleep(0.05)
        time.sleep(0.5)                     # the workers are solving frames now
        process.send_signal(signal.SIGTERM)
        sent = time.perf_counter()
        process.wait(timeout=120)
        took = time.perf_counter() - sent
        time.sleep(0.2)
        return {"seconds": took, "left": len(processes_holding(str(page))),
                "exit": process.returncode}
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


def run(*, quick: bool = False) -> dict:
    from planmethod.application.workers import worker_count

    step = 10.0 if quick else 1.0
    folder = Path(tempfile.mkdtemp(prefix="planmethod-workbook-"))
    result: dict = {"step": step, "mechanisms": {}}
    before = load_factor(record=not quick)
    for name in FILES:
        entry = {"per_position_ms": per_position(name, 4 if quick else 12)}
        workers = worker_count(None, round(360 / step))
        ahead = parallel_load_factor(workers)     # the load a page of that many workers meets
        entry["page"] = whole_page(name, step, folder)
        entry["page"]["parallel_load"] = {"before": ahead,
                                          "after": parallel_load_factor(workers)}
        print(f"  {name}: {entry}")
        result["mechanisms"][name] = entry
    shot = None if quick else FIGURES / "workbook.png"
    result["browser"] = {name: browser_switch(entry["page"]["path"],
                                              shot if name == "compressor" else None)
                         for name, entry in result["mechanisms"].items()}
    result["terminated"] = terminated_mid_run(folder)
    after = load_factor(record=not quick)
    result["load"] = run_load(before, after)
    return result


def _mark(value: float, target: float | None, factor: float | None = None) -> str:
    """A measure judged against its target, if it has one: a time by its idle estimate
    (divided by the run's load ``factor``), anything else (a size) as it is.

    >>> _mark(12.0, 10.0, 1.5), _mark(2.5, 3.0), _mark(2.0, None)
    ('12 (idle 8 ≤ 10)', '2.5 (≤ 3)', '2')
    """
    if target is None:
        return f"{value:.3g}"
    if factor is None:
        return f"{value:.3g} ({'≤' if value <= target else '>'} {target:g})"
    estimate = value / factor
    return f"{value:.3g} (idle {estimate:.3g} {'≤' if estimate <= target else '>'} {target:g})"


def page_verdicts(result: dict) -> list[str]:
    """Issue 39's targets of the 360-frame page, MET or NOT MET on the wall time's idle
    estimate, with the CPU time of the build and its workers beside (the frames' work: at
    best that divided by the workers, on an idle machine) and the other estimates
    (:func:`_other_estimates`)."""
    load = result.get("load")
    factor = load["factor"] if load else 1.0
    lines = ["The 360-frame page (issue 39; wall time divided by the run's load factor):", ""]
    for name, entry in result["mechanisms"].items():
        page, target = entry["page"], TARGETS_MS[name]["page_s"]
        estimate = page["seconds"] / factor
        cpu = (f"; CPU {page['cpu_seconds']:.3g} s in all, over {page['workers']} workers "
               f"{page['cpu_seconds'] / page['workers']:.3g} s" if "cpu_seconds" in page
               else "")
        lines.append(f"- {name}: {page['seconds']:.3g} s, idle estimate {estimate:.3g} s, target "
                     f"≤ {target:g} s: **{'MET' if estimate <= target else 'NOT MET'}**{cpu}"
                     f"{_other_estimates(page, load)}")
    return lines


def _other_estimates(page: dict, load: dict | None) -> str:
    """Two more idle estimates of a page, where the run measured them: its wall time divided
    by the load factor of as many processes at once as it has workers (taken just before and
    just after it), and its CPU path — this process's CPU time (the serial part) and the
    workers' divided by their number, divided by the run's CPU factor — what it would take
    with its workers balanced and nothing else running."""
    out = ""
    parallel = page.get("parallel_load")
    if parallel:
        factor = (parallel["before"]["factor"] + parallel["after"]["factor"]) / 2
        out += (f"; ÷ the load factor of {parallel['before']['processes']} processes at once "
                f"({factor:.2f}): {page['seconds'] / factor:.3g} s")
    if "own_cpu_seconds" in page:
        path = page["own_cpu_seconds"] + page["workers_cpu_seconds"] / page["workers"]
        path /= load["cpu_factor"] if load else 1.0
        out += (f"; CPU path (this process {page['own_cpu_seconds']:.3g} s + the workers' "
                f"{page['workers_cpu_seconds']:.3g} s ÷ {page['workers']}, ÷ the CPU factor): "
                f"{path:.3g} s")
    return out


def table(result: dict) -> str:
    frames = round(360 / result["step"])
    load = result.get("load")
    factor = load["factor"] if load else 1.0
    lines = ["| mechanism | analyse ms | plans + SVG ms | key ms | "
             f"{frames} frames, s | page MB | frame switch ms (median / max) | "
             "drawn plan checked, ms (median / slowest; best of 3) |",
             "|---|---|---|---|---|---|---|---|"]
    for name, entry in result["mechanisms"].items():
        target = TARGETS_MS[name]
        times, page = entry["per_position_ms"], entry["page"]
        switch = result["browser"].get(name)
        shown = ("browser absent" if switch is None else
                 f"{_mark(switch['median_ms'], SWITCH_LIMIT_MS, factor)} / "
                 f"{switch['max_ms']:.3g}")
        checked = ("browser absent" if switch is None else
                   f"{_mark(switch['check_median_ms'], CHECK_LIMIT_MS, factor)} / "
                   f"{_mark(switch['check_max_ms'], CHECK_LIMIT_MS, factor)}")
        page_target = target["page_s"] if frames == 360 else None
        size_target = PAGE_LIMIT_MB if frames == 360 and name == "compressor" else None
        lines.append(f"| {name} | {_mark(times['analyse'], target['analyse'], factor)} | "
                     f"{_mark(times['plan_files'], target['plan_files'], factor)} | "
                     f"{times['key']:.3g} | {_mark(page['seconds'], page_target, factor)} | "
                     f"{_mark(page['megabytes'], size_target)} | {shown} | {checked} |")
    firsts = [f"{name} {found['check_first_ms']:.3g} ms" for name, found in
              result["browser"].items() if found and found.get("check_first_ms") is not None]
    if firsts:
        lines += ["", "A drawn plan checked: each plan at 12 angles as a student checks it (the "
                      "points placed, the page drawn, the check button clicked), in three "
                      "passes, each angle's best kept; the page's very first check, before its "
                      f"code runs hot, apart: {', '.join(firsts)}."]
    if frames == 360:
        lines += ["", *page_verdicts(result)]
    if load:
        lines += ["", load_sentence(load)]
    ended = result.get("terminated")
    if ended is not None:
        lines += ["", f"`kill -TERM` of `planmethod workbook` alone (the conveyor at 1°, two "
                      f"workers mid-run): it ended in {_mark(ended['seconds'], SIGTERM_LIMIT_S)}"
                      f" s with exit status {ended['exit']}, and {ended['left']} of its "
                      "processes were left."]
    return "\n".join(lines) + "\n"
