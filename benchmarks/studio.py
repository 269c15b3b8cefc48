"""The studio's speed while a point is dragged: the server's time per update and the browser's
round trip.

*Server* (in-process, ms per update, median and 90th percentile of 40 steps): the crank pin
of the compressor slider-crank (B) and of the six-link conveyor (A) moved 0.5 mm at a time, as
a hand drags it — every step a new mechanism (new lengths, new angle) written as drawn, and
what ``POST /api/solve`` does with it: read the TOML, solve (structure, exact kinematics,
plans, forces where masses are given), the JSON report, and the position, velocity and
acceleration plans as SVG. Also each stage's share.

*Browser* (ms): the studio started on a free port, its page opened in headless Chromium
(Playwright) with the exercise, the pin moved the same way by the page's own drag code
(``studio.movePoint``), one step after the previous plans were shown; the time the page itself
records from sending the drawing to showing the plans (request, server, answer, putting the
SVG into the page).

Targets of issue 22 (again in issue 39): the server ≤ 16 ms (compressor) and ≤ 40 ms
(conveyor) per update, the round trip ≤ 50 ms and ≤ 100 ms, on the benchmark machine. A drag's
intermediate steps are drafts (``api.solve(draft=True)``: labels placed quickly, no forces
where everything is asked) and the step where it rests is solved in full (after its draft):
each is timed, and a full update of a mechanism not met before, along mirrored drags in
turn, five steps each.

*A solve during an export* (issue 35): a studio (in this process, on a free port) runs a
200-variant export as its job (in a process of its own: :mod:`planmethod.studio.jobs`) while
the compressor is solved over HTTP again and again (``POST /api/solve``, as a drag does) and
the folder listed (``GET /api/files``); each request's whole time from sending to the answer
read, against the same requests on the idle studio before it. Then the alternative the studio
did not choose: the same export run in a thread of the studio's own process (as a job thread
with cooperative cancellation would), with the same solves. Target: no solve waits more than
1 s (before, one lock served every request: a solve waited for the whole export, 17.5 s).

*Load*: the machine these run on is shared, and its load stretches wall times several times
over, and CPU times too (two virtual CPUs shared by many processes). So the run also times
a reference workload (:func:`~benchmarks.common.reference_workload`: numpy calls, formatting
and dicts, no planmethod code, so that speeding the package up does not move it) in wall and
CPU time, before and after, against the fastest it was ever seen to run here
(``results/load_reference.json``, lowered by a full run that finds it faster). The ratios are
the run's load factors; a time divided by its factor is shown as the idle estimate, and the
targets are judged on those (the server's on its CPU time: the update is single-threaded
computation; the round trip's on its wall time). Compare raw times only within one run.

Examples
--------
>>> sorted(TARGETS_MS)
['compressor', 'conveyor']
>>> steps = drag_steps({"points": {"A": [0.0, 0.0], "B": [0.06, 0.0]},
...                     "drive": {"pivot": "A", "angle": 0.0}}, "B", 2)
>>> [step["points"]["B"] for step in steps]
[[0.06, 0.0005], [0.06, 0.001]]
"""

from __future__ import annotations

import contextlib
import copy
import math
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from planmethod.convert import drawn_tables
from planmethod.grading.templates import to_toml
from planmethod.spec import parse_toml, read_text
from planmethod.studio import api

from .common import FIGURES, ROOT, browser_launcher, load_factor, load_sentence, run_load

FILES = {"compressor": ("exercises/compressor_slider_crank.toml", "B"),
         "conveyor": ("exercises/conveyor_sixbar.toml", "A")}

#: issue 22's targets: the server's time per update and the browser's round trip (ms)
TARGETS_MS = {"compressor": {"server": 16.0, "browser": 50.0},
              "conveyor": {"server": 40.0, "browser": 100.0}}

#: how far the pin moves per step (m), and how many steps
STEP_M, STEPS = 0.0005, 40


def drag_steps(tables: dict, pin: str, count: int, step_m: float = STEP_M) -> list[dict]:
    """The drawing after each of ``count`` steps of ``step_m`` of the crank pin moved ⟂ to the
    crank (the drive angle following the pin, as the page sets it)."""
    out = []
    pivot = tables["points"][tables["drive"]["pivot"]]
    for number in range(1, count + 1):
        step = copy.deepcopy(tables)
        x, y = step["points"][pin]
        angle = math.atan2(y - pivot[1], x - pivot[0])
        x -= number * step_m * math.sin(angle)
        y += number * step_m * math.cos(angle)
        step["points"][pin] = [round(x, 12) + 0.0, round(y, 12) + 0.0]
        step["drive"]["angle"] = math.degrees(math.atan2(y - pivot[1], x - pivot[0]))
        out.append(step)
    return out


def _percentile(values: list[float], share: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(share * (len(ordered) - 1)))]


def _timed_solves(texts: list[str], *, draft: bool) -> tuple[list[float], list[float]]:
    """Wall and CPU ms of ``api.solve`` of each text (a draft: a drag's intermediate step)."""
    totals, cpu = [], []
    for text in texts:
        start, start_cpu = time.perf_counter(), time.thread_time()
        api.solve(text, draft=draft)
        cpu.append(1000 * (time.thread_time() - start_cpu))
        totals.append(1000 * (time.perf_counter() - start))
    return totals, cpu


def _summaries(wall: list[float], cpu: list[float]) -> dict:
    return {"median_ms": statistics.median(wall), "p90_ms": _percentile(wall, 0.9),
            "cpu_median_ms": statistics.median(cpu), "cpu_p90_ms": _percentile(cpu, 0.9)}


def server_times(name: str, count: int = STEPS) -> dict:
    """ms per update of ``api.solve`` along a drag: in full on a mechanism not solved before,
    as the drag's intermediate steps (drafts: labels placed quickly; no forces where
    everything is asked) and in full where the drag rests, right after that step's draft (what
    the page asks for when the drag is released or held still), along two mirrored drags
    (every step a mechanism not met before) in turn, five steps at a time; and each stage's
    median (ms) of the full update."""
    from planmethod.render.svg import plan_svg, position_svg
    from planmethod.report import analyse, report_dict
    from planmethod.spec import parse_exercise

    path, pin = FILES[name]
    tables = drawn_tables(parse_toml(read_text(ROOT / path)))
    texts = [to_toml(step) for step in drag_steps(tables, pin, count)]
    mirrored = [to_toml(step) for step in drag_steps(tables, pin, count, -STEP_M)]
    api.solve(to_toml(tables))   # the imports and the first compilations
    api.solve(to_toml(tables), draft=True)
    totals, cpu, draft_totals, draft_cpu, rest_totals, rest_cpu = [], [], [], [], [], []
    for first in range(0, count, 5):
        more_wall, more_cpu = _timed_solves(texts[first:first + 5], draft=False)
        totals += more_wall
        cpu += more_cpu
        for text in mirrored[first:first + 5]:   # a draft, then the drag rests there
            for wall, spent, draft in ((draft_totals, draft_cpu, True),
                                       (rest_totals, rest_cpu, False)):
                more_wall, more_cpu = _timed_solves([text], draft=draft)
                wall += more_wall
                spent += more_cpu
    stages: dict[str, list[float]] = {"read": [], "solve": [], "report": [], "svg": []}
    for step in drag_steps(tables, pin, count // 2, -0.7 * STEP_M):   # mechanisms not met yet
        clock = [time.perf_counter()]
        exercise = parse_exercise(to_toml(step))
        clock.append(time.perf_counter())
        analysis = analyse(exercise)
        clock.append(time.perf_counter())
        report_dict(analysis)
        clock.append(time.perf_counter())
        plans = analysis.plans
        position_svg(plans.position, plans=plans, details=False)
        plan_svg(plans.velocity, details=False)
        plan_svg(plans.acceleration, details=False)
        clock.append(time.perf_counter())
        for stage, start, end in zip(stages, clock, clock[1:], strict=False):
            stages[stage].append(1000 * (end - start))
    return {"median_ms": statistics.median(totals), "p90_ms": _percentile(totals, 0.9),
            "cpu_median_ms": statistics.median(cpu), "cpu_p90_ms": _percentile(cpu, 0.9),
            "draft": _summaries(draft_totals, draft_cpu),
            "rest": _summaries(rest_totals, rest_cpu),
            "stages_ms": {stage: statistics.median(values) for stage, values in stages.items()}}


@contextlib.contextmanager
def studio_page(folder: Path, initial: str):
    """A studio serving ``folder`` (``initial`` open) and its page in headless Chromium, the
    first solve shown; None without Chromium and Playwright. Everything is stopped after."""
    found = browser_launcher()
    if found is None:
        yield None
        return
    sync_playwright, chromium = found
    from planmethod.studio.server import StudioServer

    server = StudioServer(folder, 0, initial=initial)
    server.start()
    try:
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=chromium,
                                                 args=["--no-sandbox"])
            # the page's policy forbids eval; Playwright's waits evaluate their text
            context = browser.new_context(bypass_csp=True,
                                          viewport={"width": 1500, "height": 1000})
            page = context.new_page()
            page.goto(server.url("/", token=True))
            page.wait_for_function("window.studio.ready && window.studio.solves > 0",
                                   timeout=120_000)
            yield page
            browser.close()
    finally:
        server.stop()


def browser_times(name: str, count: int = STEPS) -> dict | None:
    """The page's round trip per drag step (ms), or None without Chromium and Playwright."""
    path, pin = FILES[name]
    folder = Path(tempfile.mkdtemp(prefix="planmethod-studio-bench-"))
    tables = drawn_tables(parse_toml(read_text(ROOT / path)))
    (folder / "exercise.toml").write_text(to_toml(tables), encoding="utf-8")
    try:
        with studio_page(folder, "exercise.toml") as page:
            if page is None:
                return None
            # the steps come faster than a hand rests: no full answer between them
            page.evaluate("window.studio.restMs = 1e9")
            for step in drag_steps(tables, pin, 5):   # warm the solver and the page
                _move(page, pin, step["points"][pin])
                _move(page, pin, step["points"][pin], draft=True)
            page.evaluate("window.studio.timings = []; window.studio.draftTimings = []")
            steps, mirrored = drag_steps(tables, pin, count), drag_steps(tables, pin, count,
                                                                          -STEP_M)
            times, rests = [], []
            for first in range(0, count, 5):   # in full and dragging in turn, 5 steps each
                for step in steps[first:first + 5]:
                    _move(page, pin, step["points"][pin])
                    times.append(page.evaluate("window.studio.timings.at(-1)"))
                for step in mirrored[first:first + 5]:   # a draft, then it rests there
                    _move(page, pin, step["points"][pin], draft=True)
                    _move(page, pin, step["points"][pin])
                    rests.append(page.evaluate("window.studio.timings.at(-1)"))
            drafts = page.evaluate("window.studio.draftTimings")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return {"median_ms": statistics.median(times), "p90_ms": _percentile(times, 0.9),
            "steps": len(times),
            "draft": {"median_ms": statistics.median(drafts), "p90_ms": _percentile(drafts, 0.9),
                      "steps": len(drafts)},
            "rest": {"median_ms": statistics.median(rests), "p90_ms": _percentile(rests, 0.9),
                     "steps": len(rests)}}


def screenshot(path: Path, exercise: str = "exercises/fourbar_coupler_point.toml",
               point: str = "C") -> bool:
    """The studio with ``exercise`` open and ``point`` selected, 1500 × 1000 px, as a PNG at
    ``path`` (the picture in docs/studio.md); False without a browser."""
    from planmethod.io import write_bytes_atomic

    folder = Path(tempfile.mkdtemp(prefix="planmethod-studio-shot-"))
    shutil.copy(ROOT / exercise, folder / Path(exercise).name)
    try:
        with studio_page(folder, Path(exercise).name) as page:
            if page is None:
                return False
            page.click(f'circle.point-hit[data-point="{point}"]')
            for _ in range(3):   # solved again, warm
                where = page.evaluate(f"window.studio.tables.points[{point!r}]")
                _move(page, point, where)
            # the status line tells the last update's time, which on a shared machine says
            # more of the machine than of the studio (benchmarks/results/studio.md has it)
            page.evaluate("document.getElementById('status').textContent = ''")
            page.wait_for_timeout(500)
            image = page.screenshot(clip={"x": 0, "y": 0, "width": 1500, "height": 1000})
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    write_bytes_atomic(path, image)
    return True


#: issue 35's target: the longest a solve waits while an export runs (ms), and its size
EXPORT_TARGET_MS, EXPORT_COUNT = 1000.0, 200


def _timed_request(server, method: str, path: str,
                   body: bytes | None = None) -> tuple[float, bytes]:
    """(the wall time in ms, the answer) of one request to ``server``, from sending to the
    answer read."""
    import http.client

    from planmethod.studio.server import HOST

    connection = http.client.HTTPConnection(HOST, server.port, timeout=600)
    start = time.perf_counter()
    connection.request(method, path, body=body, headers={"X-Planmethod-Token": server.token})
    response = connection.getresponse()
    answer = response.read()
    elapsed = 1000 * (time.perf_counter() - start)
    connection.close()
    if response.status not in (200, 202):
        raise RuntimeError(f"{method} {path}: {response.status} {answer[:200]!r}")
    return elapsed, answer


def _summary(times: list[float]) -> dict:
    return {"median_ms": statistics.median(times), "p90_ms": _percentile(times, 0.9),
            "max_ms": max(times), "count": len(times)}


def _requests_while(server, running, text: bytes) -> tuple[list[float], list[float]]:
    """Solve ``text`` and list the folder on ``server`` while ``running()``; their times."""
    solves, listings = [], []
    while running():
        solves.append(_timed_request(server, "POST", "/api/solve", text)[0])
        listings.append(_timed_request(server, "GET", "/api/files")[0])
        time.sleep(0.05)   # as a drag: a new position every few frames
    return solves, listings


#: the ranges of the exported template: the rod's length and the crank angle
RANGES = {"lengths": {"BC": [0.17, 0.19]}, "angle": [40, 50, 5]}


def _export_body(text: str, folder: str, count: int) -> bytes:
    import json

    return json.dumps({"toml": text, "folder": folder, "count": count,
                       "ranges": RANGES}).encode()


def _preview_times(server, text: str) -> dict:
    """What a job's own process costs: a one-variant preview as a job (its process started
    ahead, as the page has it), from the request to its result read, against the same preview
    computed in the studio's process (ms)."""
    import json

    body = json.dumps({"toml": text, "ranges": RANGES, "count": 1}).encode()
    api.variants(text, RANGES, count=1)   # the imports, here
    server.jobs.warm()   # as the page's first load does
    jobs, inline = [], []
    for _ in range(3):
        time.sleep(2)   # an instructor's pace: the next job's process is ready
        start = time.perf_counter()
        job = json.loads(_timed_request(server, "POST", "/api/variants", body)[1])["job"]
        while json.loads(_timed_request(server, "GET", f"/api/job?id={job['id']}")[1])[
                "state"] == "running":
            time.sleep(0.01)
        jobs.append(1000 * (time.perf_counter() - start))
        start = time.perf_counter()
        api.variants(text, RANGES, count=1)
        inline.append(1000 * (time.perf_counter() - start))
    return {"job_ms": statistics.median(jobs), "inline_ms": statistics.median(inline)}


def solve_during_export(count: int = EXPORT_COUNT) -> dict:
    """A solve's and a listing's time (ms) on an idle studio, during a ``count``-variant export
    job (a process), and during the same export run in a thread of the studio's process."""
    import json
    import threading

    from planmethod.studio.server import StudioServer

    folder = Path(tempfile.mkdtemp(prefix="planmethod-studio-export-"))
    shutil.copy(ROOT / FILES["compressor"][0], folder / "compressor.toml")
    text = read_text(ROOT / FILES["compressor"][0])
    server = StudioServer(folder, 0)
    server.start()
    try:
        for _ in range(3):   # the imports and the first compilations
            _timed_request(server, "POST", "/api/solve", text.encode())
        idle = [(_timed_request(server, "POST", "/api/solve", text.encode())[0],
                 _timed_request(server, "GET", "/api/files")[0]) for _ in range(20)]
        preview = _preview_times(server, text)
        started = time.perf_counter()
        answer = _timed_request(server, "POST", "/api/export",
                                _export_body(text, "process-run", count))[1]
        job = server.jobs.get(json.loads(answer)["job"]["id"])
        during = _requests_while(server, lambda: job.state == "running", text.encode())
        process_seconds = time.perf_counter() - started
        if job.state != "done":
            raise RuntimeError(f"the export job ended {job.state}: {job.error}")
        thread = threading.Thread(target=api.export, args=(server.workspace, text, RANGES),
                                  kwargs={"folder": "thread-run", "count": count})
        started = time.perf_counter()
        thread.start()
        in_thread = _requests_while(server, thread.is_alive, text.encode())
        thread_seconds = time.perf_counter() - started
    finally:
        server.stop()
        shutil.rmtree(folder, ignore_errors=True)
    return {"count": count, "preview": preview,
            "idle": {"solve": _summary([a for a, _ in idle]),
                     "files": _summary([b for _, b in idle])},
            "process": {"solve": _summary(during[0]), "files": _summary(during[1]),
                        "export_s": process_seconds},
            "thread": {"solve": _summary(in_thread[0]), "files": _summary(in_thread[1]),
                       "export_s": thread_seconds}}


def _move(page, pin: str, xy: list[float], *, draft: bool = False) -> None:
    """Move ``pin`` to ``xy`` by the page's own code (a drag's intermediate step if
    ``draft``) and wait for the answer shown."""
    solves = page.evaluate("window.studio.solves")
    page.evaluate("([name, x, y, draft]) => window.studio.movePoint(name, x, y, {draft})",
                  [pin, *xy, draft])
    page.wait_for_function(f"window.studio.solves > {solves}", timeout=60_000, polling=1)


def run(*, quick: bool = False) -> dict:
    count = 10 if quick else STEPS
    result: dict = {"steps": count, "step_m": STEP_M, "mechanisms": {}}
    before = load_factor(record=not quick)
    for name in FILES:
        entry = {"server": server_times(name, count), "browser": browser_times(name, count)}
        print(f"  {name}: {entry}")
        result["mechanisms"][name] = entry
    result["export"] = solve_during_export(20 if quick else EXPORT_COUNT)
    print(f"  export: {result['export']}")
    after = load_factor(record=not quick)
    result["load"] = run_load(before, after)
    if not quick:
        screenshot(FIGURES / "studio.png")
    return result


def _mark(value: float, target: float) -> str:
    return f"{value:.3g} ({'≤' if value <= target else '>'} {target:g})"


def _row(name: str, label: str, server: dict, browser: dict | None, load: dict) -> str:
    target = TARGETS_MS[name]
    shown = ("browser absent" if browser is None else
             f"{browser['median_ms']:.3g} / {browser['p90_ms']:.3g} "
             f"({_mark(browser['median_ms'] / load['factor'], target['browser'])})")
    return (f"| {name}, {label} | {server['cpu_median_ms']:.3g} / {server['cpu_p90_ms']:.3g} "
            f"({_mark(server['cpu_median_ms'] / load['cpu_factor'], target['server'])}) | "
            f"{server['median_ms']:.3g} / {server['p90_ms']:.3g} | {shown} |")


def verdicts(result: dict) -> list[str]:
    """Each target of issue 39, MET or NOT MET, on the idle estimates of a drag's updates:
    its intermediate steps (drafts), the full update where it rests (after that step's
    draft), and a full update of a mechanism not met before (a typed change, an opened
    file)."""
    load, lines = result["load"], []
    for name, entry in result["mechanisms"].items():
        target = TARGETS_MS[name]
        for label, server, browser in (
                ("while dragging (drafts)", entry["server"].get("draft"),
                 (entry["browser"] or {}).get("draft")),
                ("where the drag rests (in full, after its draft)",
                 entry["server"].get("rest"), (entry["browser"] or {}).get("rest")),
                ("in full, a mechanism not met before", entry["server"], entry["browser"])):
            if server is None:
                continue
            cpu = server["cpu_median_ms"] / load["cpu_factor"]
            lines.append(f"- {name}, {label}: server {cpu:.3g} ms, target ≤ {target['server']:g}: "
                         f"**{'MET' if cpu <= target['server'] else 'NOT MET'}**")
            if browser is not None:
                wall = browser["median_ms"] / load["factor"]
                lines.append(f"- {name}, {label}: round trip {wall:.3g} ms, target ≤ "
                             f"{target['browser']:g}: "
                             f"**{'MET' if wall <= target['browser'] else 'NOT MET'}**")
    return lines


def table(result: dict) -> str:
    load = result["load"]
    lines = ["| mechanism, update | server per update, CPU ms: median / p90 (idle estimate) | "
             "wall ms: median / p90 | browser round trip ms: median / p90 (idle estimate) |",
             "|---|---|---|---|"]
    for name, entry in result["mechanisms"].items():
        server, browser = entry["server"], entry["browser"]
        lines.append(_row(name, "in full, not met before", server, browser, load))
        for key, label in (("draft", "while dragging (draft)"),
                           ("rest", "where the drag rests (in full, after its draft)")):
            if key in server:
                lines.append(_row(name, label, server[key],
                                  None if browser is None else browser[key], load))
    lines += ["", "Where the full update's wall time goes (read / solve / report / SVG, ms): "
              + "; ".join(f"{name} " + " / ".join(f"{value:.3g}" for value in
                                                   entry["server"]["stages_ms"].values())
                          for name, entry in result["mechanisms"].items()) + ".",
              "", "Targets (issue 39; server on CPU time, round trip on wall time, each "
              "divided by the run's load factor):", "", *verdicts(result)]
    lines += ["", *export_table(result["export"]), "", load_sentence(load)]
    return "\n".join(lines) + "\n"


def export_table(export: dict) -> list[str]:
    """The lines of the table of a solve's wait during an export."""
    idle = export["idle"]["solve"]["median_ms"]
    lines = [f"A solve of the compressor and a listing of the folder over HTTP, on the idle "
             f"studio and while it exports {export['count']} variants (ms; target: no solve "
             f"over {EXPORT_TARGET_MS:g} ms):", "",
             "| while | solve: median / p90 / max (median ÷ idle) | listing: median / max | "
             "solves | export, s |", "|---|---|---|---|---|"]
    for name, label in (("idle", "idle"), ("process", "the export job (its own process: "
                                                       "the studio's way)"),
                        ("thread", "the export in a thread of the studio (not chosen)")):
        entry = export[name]
        solve, files = entry["solve"], entry["files"]
        mark = ("" if name == "idle" else
                f" ({'≤' if solve['max_ms'] <= EXPORT_TARGET_MS else '>'} "
                f"{EXPORT_TARGET_MS:g})")
        lines.append(f"| {label} | {solve['median_ms']:.3g} / {solve['p90_ms']:.3g} / "
                     f"{solve['max_ms']:.3g}{mark} ({solve['median_ms'] / idle:.2f}) | "
                     f"{files['median_ms']:.3g} / {files['max_ms']:.3g} | {solve['count']} | "
                     f"{format(entry['export_s'], '.3g') if 'export_s' in entry else '—'} |")
    preview = export["preview"]
    lines += ["", f"What a job's own process costs: a one-variant preview takes "
                  f"{preview['job_ms']:.3g} ms as a job (in a process started ahead, its "
                  f"answer asked for every 10 ms) against {preview['inline_ms']:.3g} ms computed "
                  "in the studio's process (medians of 3)."]
    return lines
