"""The paper course: plans drawn in pencil, photographed with a phone, graded from the photos.

Run from the repository root::

    python -m benchmarks.paper            # 12 students of each shipped template (writes results)
    python -m benchmarks.paper --quick    # 2 students of each (prints only)

For the variants of each shipped template (``exercises/templates/*.toml``), every plan sheet is
drawn by the right construction and by each named mistake the key gives positions for — a
mistake that re-draws the plan moves all its points, one that places single points moves one
point at a time — where that plan can be drawn and read on the sheet
(:func:`planmethod.testing.photos.drawable_constructions`). Each drawing is pencilled on the
booklet's page and photographed as a phone would (:class:`planmethod.testing.photos.
Conditions`: up to 30° off the normal, turned, curled, unevenly lit with a shadow, blurred,
noisy, JPEG at quality 70), then graded by :func:`planmethod.grading.photos.grade_photo`.

The measures: the share of points that get the verdict their construction deserves (a point of
the right construction, or one a mistake does not move, graded right; a point a mistake moves
graded wrong and named with that mistake); the points a mistaken construction moved that are
called right (none may be); the photos refused; and the time and CPU time one photo takes to
grade in one process with OpenCV on one thread (the photos are made and graded by two worker
processes, each on its own core, the machine's load stated). Results go to
``benchmarks/results/paper.json`` and ``benchmarks/results/paper.md``.

Examples
--------
>>> deserved_verdict({"correct": True}, "right"), deserved_verdict({"correct": False,
...                   "mistakes": ["sense"]}, "sense")
(True, True)
>>> deserved_verdict({"correct": False}, "right")
False
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from benchmarks.common import (
    ROOT,
    load_factor,
    load_sentence,
    machine,
    run_load,
    write_json,
    write_text,
    written_by,
)

TEMPLATES = ("slider_crank", "four_bar")
COMMAND = "python -m benchmarks.paper"


def deserved_verdict(point: dict, verdict: str) -> bool:
    """Whether a graded point got the verdict its construction deserves (``right``, or the
    mistake that moved it)."""
    if verdict == "right":
        return bool(point.get("correct"))
    return not point.get("correct") and verdict in point.get("mistakes", [])


def course_keys(template: str, count: int, seed: int) -> list[dict]:
    """The keys of ``count`` variants of a shipped template, with their sheets."""
    from planmethod.application.variants import VariantsRequest, class_of, draw_variants
    from planmethod.grading.templates import load_template

    template_file = load_template(ROOT / "exercises" / "templates" / f"{template}.toml")
    drawn = draw_variants(VariantsRequest(template_file, class_of(count), seed=seed,
                                          sheets=False))
    return json.loads(drawn.files["keys.json"])["keys"]


def _cases(keys: list[dict], template: str) -> list[tuple]:
    from planmethod.testing.photos import drawable_constructions

    out = []
    for key in keys:
        for plan in ("velocity", "acceleration"):
            if plan in key["plans"]:
                out += [(template, key, plan, mistake, label)
                        for mistake, label in drawable_constructions(key, plan)]
    return out


_PAGES: dict = {}


def _start() -> None:
    import cv2

    cv2.setNumThreads(1)


def photograph_and_grade(case: tuple) -> dict:
    """One case: its photo made, written and graded; the verdicts and the grading's time."""
    import os

    from planmethod.errors import PlanmethodError
    from planmethod.grading.paper import read_sheet
    from planmethod.grading.photos import grade_photo
    from planmethod.grading.sheets import paper_plan_sheet
    from planmethod.testing.photos import page_image, sheet_photo

    number, (template, key, plan, mistake, label), folder = case
    page = _PAGES.get((template, key["student"], plan))
    if page is None:
        _PAGES.clear()
        last = max(entry["page"] for entry in key["sheets"].values())
        page = page_image(paper_plan_sheet(key, read_sheet(key, plan), last))
        _PAGES[(template, key["student"], plan)] = page
    photo = sheet_photo(key, plan, mistake, label, seed=10_000 + number, page=page)
    path = Path(folder) / f"{number}.jpg"
    path.write_bytes(photo.jpeg)
    keys = {key["student"]: key}
    start, start_cpu = time.perf_counter(), time.process_time()
    try:
        result = grade_photo(keys, path).as_dict()
        refused = None
    except PlanmethodError as error:
        result, refused = None, str(error)
    seconds, cpu = time.perf_counter() - start, time.process_time() - start_cpu
    os.unlink(path)
    points = []
    for point in (result or {}).get("points", []):
        verdict = photo.drawn.deserved.get(point["point"])
        if verdict is not None:
            points.append({"point": point["point"], "deserved": verdict,
                           "ok": deserved_verdict(point, verdict),
                           "correct": bool(point["correct"]),
                           "mistakes": point.get("mistakes", []),
                           "distance_mm": point.get("distance_mm"),
                           "feedback": point["feedback"]})
    return {"template": template, "student": key["student"], "plan": plan,
            "construction": mistake or "right", "label": label, "seconds": seconds,
            "cpu_seconds": cpu, "refused": refused, "points": points,
            "expected_points": len(photo.drawn.deserved),
            "tilt_deg": photo.conditions.tilt_deg,
            "reading": (result or {}).get("reading")}


def run(count: int, seed: int = 2026) -> dict:
    """The benchmark over ``count`` students of each shipped template."""
    import multiprocessing

    cases = []
    for template in TEMPLATES:
        cases += _cases(course_keys(template, count, seed), template)
    before = load_factor()
    with tempfile.TemporaryDirectory() as folder:
        work = [(number, case, folder) for number, case in enumerate(cases)]
        with multiprocessing.get_context("spawn").Pool(2, initializer=_start) as pool:
            done = []
            for index, found in enumerate(pool.imap(photograph_and_grade, work, chunksize=4)):
                done.append(found)
                if (index + 1) % 20 == 0:
                    print(f"{index + 1}/{len(work)} photos", file=sys.stderr, flush=True)
    after = load_factor()
    return {"machine": machine(), "load": run_load(before, after), "students": count,
            "seed": seed, "photos": done}


def summary(data: dict) -> dict:
    """The measures of a run (see the module notes)."""
    photos = data["photos"]
    points = [point for photo in photos for point in photo["points"]]
    refused = [photo for photo in photos if photo["refused"]]
    missing = sum(photo["expected_points"] for photo in refused)
    mistaken = [point for point in points if point["deserved"] != "right"]
    called_right = [point for point in mistaken if point["correct"]]
    graded = [photo for photo in photos if not photo["refused"]]
    seconds = sorted(photo["seconds"] for photo in graded)
    cpu = sorted(photo["cpu_seconds"] for photo in graded)
    by_template = {}
    for template in TEMPLATES:
        mine = [point for photo in photos if photo["template"] == template
                for point in photo["points"]]
        mine_missing = sum(photo["expected_points"] for photo in refused
                           if photo["template"] == template)
        by_template[template] = {"points": len(mine) + mine_missing,
                                 "deserved": sum(point["ok"] for point in mine)}
    by_construction: dict[str, Counter] = {}
    for photo in photos:
        counter = by_construction.setdefault(photo["construction"], Counter())
        counter["photos"] += 1
        for point in photo["points"]:
            counter["points"] += 1
            counter["deserved"] += point["ok"]
    total = len(points) + missing
    return {"photos": len(photos), "refused": len(refused), "points": total,
            "deserved": sum(point["ok"] for point in points),
            "share": sum(point["ok"] for point in points) / max(total, 1),
            "mistaken_points": len(mistaken), "mistaken_called_right": len(called_right),
            "seconds": {"median": statistics.median(seconds), "p95": seconds[int(0.95 * (
                len(seconds) - 1))], "max": seconds[-1]} if seconds else {},
            "cpu_seconds": {"median": statistics.median(cpu), "p95": cpu[int(0.95 * (
                len(cpu) - 1))], "max": cpu[-1]} if cpu else {},
            "by_template": by_template,
            "by_construction": {name: dict(counter)
                                for name, counter in sorted(by_construction.items())},
            "refusals": [f"{photo['template']} {photo['student']} {photo['plan']} "
                         f"{photo['construction']}: {photo['refused'].split(': ', 1)[-1]}"
                         for photo in refused]}


#: issue 40's targets: the share of points with the verdict they deserve, and the CPU time to
#: grade a photo on one core (s; its 95th percentile)
TARGET_SHARE, TARGET_CPU_SECONDS = 0.97, 1.5


def targets(found: dict) -> list[str]:
    """Whether the run meets issue 40's targets, one line each.

    >>> targets({"share": 0.98, "mistaken_called_right": 0, "cpu_seconds": {"p95": 0.7}})[1]
    '- no point a mistake moved is called right: **met** (0)'
    """
    def met(ok: bool) -> str:
        return "**met**" if ok else "**not met**"

    cpu = found["cpu_seconds"].get("p95", math.inf) if found["cpu_seconds"] else math.inf
    return [f"- ≥ {100 * TARGET_SHARE:.0f} % of points get the verdict their construction "
            f"deserves: {met(found['share'] >= TARGET_SHARE)} ({100 * found['share']:.1f} %)",
            f"- no point a mistake moved is called right: "
            f"{met(found['mistaken_called_right'] == 0)} ({found['mistaken_called_right']})",
            f"- a photo graded in ≤ {TARGET_CPU_SECONDS:g} s on one core (95 % of the photos' "
            f"CPU time): {met(cpu <= TARGET_CPU_SECONDS)} ({cpu:.2f} s)"]


def report(data: dict, found: dict) -> str:
    lines = [written_by(COMMAND, data["machine"]).rstrip(), "",
             f"{found['photos']} photos of plan sheets ({data['students']} students of each "
             f"shipped template: {', '.join(TEMPLATES)}, seed {data['seed']}), "
             f"{found['points']} graded points.", "",
             "| measure | value |", "|---|---:|",
             f"| points with the verdict their construction deserves | {found['deserved']}/"
             f"{found['points']} (**{100 * found['share']:.1f} %**) |",
             f"| points a mistake moved, called right | **{found['mistaken_called_right']}** "
             f"of {found['mistaken_points']} |",
             f"| photos refused | {found['refused']} |"]
    if found["seconds"]:
        lines += [f"| time to grade a photo, median / 95 % / max (s) | "
                  f"{found['seconds']['median']:.2f} / {found['seconds']['p95']:.2f} / "
                  f"{found['seconds']['max']:.2f} |",
                  f"| CPU time to grade a photo, median / 95 % / max (s) | "
                  f"{found['cpu_seconds']['median']:.2f} / {found['cpu_seconds']['p95']:.2f} / "
                  f"{found['cpu_seconds']['max']:.2f} |"]
    lines += ["", *targets(found)]
    lines += ["", load_sentence(data["load"]), "",
              "Each photo is made and graded in one of two worker processes (each on its own "
              "core of the two); grading runs with OpenCV on one thread.", "",
              "| construction | photos | points | deserved |", "|---|---:|---:|---:|"]
    for name, counter in found["by_construction"].items():
        lines.append(f"| {name} | {counter.get('photos', 0)} | {counter.get('points', 0)} | "
                     f"{counter.get('deserved', 0)} |")
    lines += ["", "| template | points | deserved |", "|---|---:|---:|"]
    for template, counter in found["by_template"].items():
        lines.append(f"| {template} | {counter['points']} | {counter['deserved']} |")
    wrong = [(photo, point) for photo in data["photos"] for point in photo["points"]
             if not point["ok"]]
    if wrong or found["refusals"]:
        lines += ["", "Points without the verdict they deserve, and refused photos:", ""]
        lines += [f"- {photo['template']} {photo['student']} {photo['plan']} "
                  f"{photo['construction']}{' on ' + photo['label'] if photo['label'] else ''}"
                  f": {point['point']} (deserves {point['deserved']}): {point['feedback']}"
                  for photo, point in wrong[:40]]
        lines += [f"- refused: {text}" for text in found["refusals"]]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="2 students of each template; "
                                                             "prints only")
    parser.add_argument("--students", type=int, default=12)
    args = parser.parse_args(argv)
    data = run(2 if args.quick else args.students)
    found = summary(data)
    text = report(data, found)
    print(text)
    if not args.quick:
        write_json("paper.json", {**{key: value for key, value in data.items()
                                     if key != "photos"}, "summary": found})
        write_text("paper.md", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
