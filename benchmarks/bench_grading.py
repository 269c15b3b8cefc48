"""Throughput of the teaching tools: variants with keys and sheets, and grading.

Run from the repository root::

    python -m benchmarks.bench_grading            # 500 variants, 10,000 numeric submissions
    python -m benchmarks.bench_grading --quick    # 50 variants, 1,000 submissions

It times, in one process on this machine: drawing 500 variants of the slider-crank template
(with the deterministic rejection of unfit draws), building their answer keys (exact values,
drawing-derived tolerances by the perturbation of every segment, mistake values, plan points),
writing their task and plan sheets (SVG), the whole ``planmethod variants`` run with files on
disk; then reading and grading 10,000 numeric submissions (a CSV spread over the 500 variants:
right answers, careful-drawing errors and the common mistakes) and 1,000 drawn plans (JSON).
Results go to ``benchmarks/results/grading.json`` and ``benchmarks/results/grading.md``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import random
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"


def _answers(keys: list[dict], count: int, seed: int = 1) -> list[tuple[str, dict]]:
    """``count`` submissions over the keys: right, slightly off, or with a common mistake."""
    generator = random.Random(seed)
    rows = []
    for index in range(count):
        key = keys[index % len(keys)]
        answers = {}
        for question in key["questions"]:
            roll = generator.random()
            value = question["value"]
            if roll < 0.6:
                value += generator.uniform(-0.8, 0.8) * question["tolerance"]
            elif roll < 0.8 and question["mistakes"]:
                value = generator.choice(question["mistakes"])["value"]
            else:
                value *= generator.uniform(0.7, 1.3)
            answers[question["id"]] = f"{value:.4g}"
        rows.append((f"{key['student']}", answers))
    return rows


def run(variants: int, submissions: int, drawings: int) -> dict:
    from planmethod.grading.answers import grade_many, read_answers
    from planmethod.grading.drawings import Drawing, grade_drawing
    from planmethod.grading.keys import build_key
    from planmethod.grading.sheets import plan_sheet_for_key, task_sheet_svg
    from planmethod.grading.templates import draw_variant, load_template
    from planmethod.plans import draw_plans

    template = load_template(TEMPLATE)
    students = [f"{i:04d}" for i in range(1, variants + 1)]
    timings: dict[str, float] = {}

    started = time.perf_counter()
    drawn = [draw_variant(template, seed=2026, student=s) for s in students]
    timings["draw variants (with rejection)"] = time.perf_counter() - started
    redrawn = sum(1 for v in drawn if v.attempt)

    started = time.perf_counter()
    keys = [build_key(v) for v in drawn]
    timings["answer keys (tolerances, mistakes, plan points)"] = time.perf_counter() - started

    started = time.perf_counter()
    for variant, key in zip(drawn, keys, strict=True):
        task_sheet_svg(key, draw_plans(variant.exercise, acceleration=False))
        plan_sheet_for_key(key, "velocity")
        plan_sheet_for_key(key, "acceleration")
    timings["task and plan sheets (SVG)"] = time.perf_counter() - started

    folder = Path(tempfile.mkdtemp(prefix="bench-grading-"))
    try:
        from planmethod.cli import main

        started = time.perf_counter()
        status = main(["variants", str(TEMPLATE), "--count", str(variants), "--seed", "2026",
                       "--out", str(folder / "course")])
        timings["`planmethod variants` end to end (files on disk)"] = (
            time.perf_counter() - started)
        assert status == 0
        rows = _answers(keys, submissions)
        ids = [q["id"] for q in keys[0]["questions"]]
        path = folder / "answers.csv"
        path.write_text("student," + ",".join(ids) + "\n" + "\n".join(
            student + "," + ",".join(answers[i] for i in ids) for student, answers in rows)
            + "\n")
        by_student = {key["student"]: key for key in keys}
        started = time.perf_counter()
        results = grade_many(by_student, read_answers(path))
        timings["read and grade numeric submissions"] = time.perf_counter() - started
        assert len(results) == submissions
        correct = sum(q["correct"] for r in results for q in r["questions"])
        recognised = sum(bool(q["mistake"]) for r in results for q in r["questions"])
        generator = random.Random(3)
        sheets = []
        for index in range(drawings):
            key = keys[index % len(keys)]
            plan = key["plans"]["velocity"]
            points = {label: (x + generator.uniform(-1, 1), y + generator.uniform(-1, 1))
                      for label, (x, y) in plan["points_mm"].items()}
            points["p"] = (0.0, 0.0)
            sheets.append((key, Drawing(points, "velocity")))
        started = time.perf_counter()
        graded = [grade_drawing(key, drawing) for key, drawing in sheets]
        timings["grade drawn plans (JSON points)"] = time.perf_counter() - started
        assert len(graded) == drawings
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    per = {
        "draw variants (with rejection)": variants,
        "answer keys (tolerances, mistakes, plan points)": variants,
        "task and plan sheets (SVG)": variants,
        "`planmethod variants` end to end (files on disk)": variants,
        "read and grade numeric submissions": submissions,
        "grade drawn plans (JSON points)": drawings,
    }
    return {
        "machine": {"python": sys.version.split()[0], "platform": platform.platform(),
                    "cpus": os.cpu_count()},
        "template": str(TEMPLATE.relative_to(ROOT)),
        "variants": variants, "redrawn_variants": redrawn, "submissions": submissions,
        "questions_per_submission": len(keys[0]["questions"]),
        "answers_within_tolerance": correct, "mistakes_recognised": recognised,
        "drawings": drawings,
        "timings_s": {name: round(value, 4) for name, value in timings.items()},
        "per_item_ms": {name: round(1000 * value / per[name], 4)
                        for name, value in timings.items()},
    }


def markdown(result: dict) -> str:
    lines = [f"# Grading throughput ({result['machine']['platform']}, "
             f"Python {result['machine']['python']}, {result['machine']['cpus']} cpus)", "",
             f"Template `{result['template']}`: {result['variants']} variants "
             f"({result['redrawn_variants']} redrawn after a rejected draw); "
             f"{result['submissions']} numeric submissions of "
             f"{result['questions_per_submission']} answers; {result['drawings']} drawn plans.",
             "", "| step | total (s) | per item (ms) |", "|---|---:|---:|"]
    for name, seconds in result["timings_s"].items():
        lines.append(f"| {name} | {seconds:.3f} | {result['per_item_ms'][name]:.3f} |")
    lines += ["", f"Answers within tolerance: {result['answers_within_tolerance']}; wrong "
                  f"answers recognised as a common mistake: {result['mistakes_recognised']}.",
              ""]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="50 variants, 1,000 submissions")
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args(argv)
    variants, submissions, drawings = (50, 1000, 100) if args.quick else (500, 10_000, 1000)
    result = run(variants, submissions, drawings)
    text = markdown(result)
    print(text)
    if not args.no_write and not args.quick:
        from planmethod.io import write_text_atomic

        write_text_atomic(RESULTS / "grading.json", json.dumps(result, indent=2) + "\n")
        write_text_atomic(RESULTS / "grading.md", text)
    assert math.isfinite(sum(result["timings_s"].values()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
