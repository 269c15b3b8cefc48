"""The teaching tools: throughput, and whether the grader names the mistakes students make.

Run from the repository root::

    python -m benchmarks.bench_grading            # 500 variants (writes the results)
    python -m benchmarks.bench_grading --quick    # 50 variants (prints only)

On variants of the slider-crank template, in one process on this machine, it times drawing the
variants (with the deterministic rejection of unfit draws), building their answer keys, writing
their task and plan sheets (SVG), the whole ``planmethod variants`` run with files on disk and
grading drawn plans (JSON points); then it grades numeric answers of two sorts, written into
one CSV and read and graded as ``planmethod grade`` does (the throughput is in answers/s):

* **mistake answers** — for every question, the answer each mistake the grader knows
  (:data:`planmethod.grading.mistakes.REGISTRY`) gives, made here from the exercise as a
  student would make it, not read from the key's list of mistakes: the sense reversed, the
  normal component left out or the Coriolis component reversed (the plans drawn with that
  mistake; only the answers it changes), the full acceleration for its normal component
  (ρ = v²/|a|), the plan's scale not applied or applied twice, degrees for radians,
  millimetres for metres, a length in mm in ω = v/l. Each is made once from the exact value
  and once from a drawn value (off by up to 0.8 of the question's tolerance, as a careful
  drawing is). The measure: the share of them the grader names with the right mistake (and
  how many it names as another mistake, accepts as right, or marks wrong without naming a
  mistake); a mistake the key does not list for a question (its answer is within twice the
  tolerance of the right one) cannot be named;
* **noise answers** — the right value off by a random amount of 0.5, 2, 5, 20 and 100 times
  the question's tolerance (either sign): the share accepted, and the share the grader
  wrongly names as a mistake.

Results go to ``benchmarks/results/grading.json`` and ``benchmarks/results/grading.md``.

``--scale N`` measures only what bounds ``variants --count``: the whole command run as a
subprocess for N variants of the template, with and without sheets — wall and CPU time, peak
memory, the machine's load — and how many variants that rate gives in a minute. Results go to
``benchmarks/results/grading_scale.json`` and ``.md``.

Examples
--------
>>> sorted(answers_of_mistakes({"id": "omega_BC", "unit": "rad/s", "signed": True,
...                             "value": 2.0}, {"mu_l": 0.01, "mu_v": 0.5, "mu_a": 2.0},
...                            {}, None))
['degrees', 'length_mm', 'scale_inverted', 'scale_none', 'scale_ten', 'scale_tenth',
 'scale_twice', 'sense']
"""

from __future__ import annotations

import argparse
import json
import math
import os
import random
import shutil
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np

from .common import RESULTS, ROOT, machine, written_by

TEMPLATE = ROOT / "exercises" / "templates" / "slider_crank.toml"

#: the sizes of the noise answers, in tolerances of the question
NOISE = (0.5, 2.0, 5.0, 20.0, 100.0)
#: a drawn value is off by up to this share of the question's tolerance
DRAWN = 0.8


def _scale(kind: str, scales) -> float | None:
    """What a drawn length (mm, or mm/mm for ω and ε) is multiplied by to give the quantity:
    v = (pc)·μv, a = (πc)·μa, s = (length)·μl, ω = (bc)·μv/((BC)·μl), ε = (n c)·μa/((BC)·μl),
    ρ = (pd)²·μv²/((πn)·μa)."""
    mu_l, mu_v, mu_a = scales["mu_l"], scales["mu_v"], scales["mu_a"]
    return {"v": mu_v, "ds": mu_v, "a": mu_a, "dds": mu_a, "coriolis": mu_a, "s": mu_l,
            "omega": mu_v / mu_l, "epsilon": mu_a / mu_l, "rho": mu_v ** 2 / mu_a}.get(kind)


def answers_of_mistakes(question: dict, scales, wrong_readings: dict, motion,
                        drawn: float = 0.0) -> dict[str, float]:
    """The answers a student gives to ``question`` with each mistake that applies to it,
    made from its value (``drawn`` added: a drafting error), the plans' scales, the readings
    of plans drawn with a construction mistake (``{mistake: {quantity: value}}``) and the
    exact motion (for ρ)."""
    name, value = question["id"], question["value"] + drawn
    kind, _, subject = name.partition("_")
    out: dict[str, float] = {}
    if question["signed"]:
        out["sense"] = -value
    for mistake, readings in wrong_readings.items():   # only where the mistake changes it
        wrong = readings.get(name)
        if wrong is not None and abs(wrong - question["value"]) > 1e-9 * abs(question["value"]):
            out[mistake] = float(wrong) + drawn
    if kind == "rho":
        from planmethod.report import exact_value

        here = motion.at(0)
        speed, accel = exact_value(here, f"v_{subject}"), exact_value(here, f"a_{subject}")
        out["full_acceleration"] = speed ** 2 / accel * value / question["value"]
    if kind in ("omega", "epsilon") and motion is not None:
        from planmethod.grading.mistakes import other_lengths

        for _, ratio in other_lengths(motion, subject):
            out["wrong_length"] = value * ratio
    if kind in ("v", "a") and "@" not in subject and motion is not None:
        # the segment from the image of the link's first other moving point (bc for pc)
        read = motion.velocity if kind == "v" else motion.acceleration
        mechanism = motion.mechanism
        own = np.reshape(read(subject), (-1, 2))[0]
        for link in mechanism.links_with_point(subject):
            others = [p for p in mechanism.links[link].points if p != subject]
            moving = [p for p in others
                      if link != "frame" and np.hypot(*np.reshape(read(p), (-1, 2))[0]) > 0]
            if moving:
                other = np.reshape(read(moving[0]), (-1, 2))[0]
                out["relative_for_absolute"] = float(np.hypot(*(own - other))) + drawn
                break
    factor = _scale(kind, scales)
    if factor:
        out["scale_none"] = value / factor
        out["scale_twice"] = value * factor
        out["scale_inverted"] = value / factor ** 2    # the length divided by the scale
    if factor is not None:                  # read off a plan: a scale misread by ten
        out["scale_ten"] = value * 10.0
        out["scale_tenth"] = value / 10.0
    if question["unit"].startswith("rad"):
        out["degrees"] = math.degrees(value)
        out["length_mm"] = value / 1000.0
    else:
        out["millimetres"] = value * 1000.0
    return out


def _outcome(result, expected: str | None) -> str:
    if result.correct:
        return "accepted"
    if result.mistake is None:
        return "unnamed"
    named = [result.mistake, *result.also]   # mistakes giving one answer
    return "named_right" if expected in named else "named_other"


def _numeric_rows(drawn_variants, keys, seed: int = 1):
    """The answers to grade: rows (student, {question: text}) and, per row and question,
    what the answer is (``("mistake", kind, how)`` or ``("noise", size)``)."""
    from planmethod.grading.mistakes import CONSTRUCTION_MISTAKES, mistaken_plans
    from planmethod.kinematics import solve

    generator = random.Random(seed)
    rows, truth = [], []
    for variant, key in zip(drawn_variants, keys, strict=True):
        mechanism = variant.exercise.mechanism
        motion = solve(mechanism, mechanism.drive.angle)
        wrong = {}
        for mistake in CONSTRUCTION_MISTAKES:
            plans = mistaken_plans(variant.exercise, mistake, motion=motion)
            if plans is not None:
                wrong[mistake] = plans.readings
        by_kind: dict[tuple[str, str], dict[str, float]] = {}
        for question in key["questions"]:
            for how in ("exact", "drawn"):
                error = 0.0 if how == "exact" else (
                    generator.uniform(-DRAWN, DRAWN) * question["tolerance"])
                made = answers_of_mistakes(question, key["scales"], wrong, motion, error)
                for mistake, answer in made.items():
                    by_kind.setdefault((mistake, how), {})[question["id"]] = answer
        for (mistake, how), answers in sorted(by_kind.items()):
            rows.append((key["student"], {q: f"{a:.7g}" for q, a in answers.items()}))
            truth.append({q: ("mistake", mistake, how) for q in answers})
        for size in NOISE:
            answers = {}
            for question in key["questions"]:
                off = generator.choice((-1, 1)) * generator.uniform(0.5, 1.0) * size
                answers[question["id"]] = question["value"] + off * question["tolerance"]
            rows.append((key["student"], {q: f"{a:.7g}" for q, a in answers.items()}))
            truth.append({q: ("noise", size) for q in answers})
    return rows, truth


def _tally(keys, results, truth) -> tuple[dict, dict]:
    by_student = {key["student"]: key for key in keys}
    mistakes: dict[str, dict[str, Counter]] = {}
    noise: dict[float, Counter] = {size: Counter() for size in NOISE}
    named_noise: dict[float, Counter] = {size: Counter() for size in NOISE}
    for result, what in zip(results, truth, strict=True):
        key = by_student[result.student.partition("~")[0]]
        listed = {q["id"]: {m["kind"] for m in q["mistakes"]} for q in key["questions"]}
        for graded in result.questions:
            if graded.id not in what:
                continue
            label = what[graded.id]
            if label[0] == "noise":
                outcome = _outcome(graded, None)
                noise[label[1]][outcome] += 1
                if graded.mistake:
                    named_noise[label[1]][graded.mistake] += 1
                continue
            _, mistake, how = label
            counts = mistakes.setdefault(how, {}).setdefault(mistake, Counter())
            counts["answers"] += 1
            counts["listed"] += mistake in listed[graded.id]
            counts[_outcome(graded, mistake)] += 1
            if mistake in listed[graded.id]:
                counts["listed_named_right"] += graded.mistake == mistake
    mistake_table = {how: {kind: dict(counts) for kind, counts in sorted(mistakes[how].items())}
                     for how in ("exact", "drawn") if how in mistakes}
    noise_table = {str(size): {**dict(noise[size]), "answers": sum(noise[size].values()),
                               "named_as": dict(named_noise[size])} for size in NOISE}
    return mistake_table, noise_table


def run(variants: int, drawings: int) -> dict:
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

    rows, truth = _numeric_rows(drawn, keys)
    answers = sum(len(a) for _, a in rows)
    folder = Path(tempfile.mkdtemp(prefix="bench-grading-"))
    try:
        from planmethod.cli import main

        started = time.perf_counter()
        status = main(["variants", str(TEMPLATE), "--count", str(variants), "--seed", "2026",
                       "--out", str(folder / "course")])
        timings["`planmethod variants` end to end (files on disk)"] = (
            time.perf_counter() - started)
        assert status == 0
        ids = [q["id"] for q in keys[0]["questions"]]
        path = folder / "answers.csv"
        # one row per attempt: a student answers once per file, so each attempt is its own
        # row id (student~n), graded against that student's key
        path.write_text("student," + ",".join(ids) + "\n" + "\n".join(
            f"{student}~{index}," + ",".join(given.get(i, "") for i in ids)
            for index, (student, given) in enumerate(rows)) + "\n")
        by_student = {key["student"]: key for key in keys}
        by_row = {f"{student}~{index}": by_student[student]
                  for index, (student, _) in enumerate(rows)}
        started = time.perf_counter()
        results = grade_many(by_row, read_answers(path))
        grading_seconds = time.perf_counter() - started
        assert len(results) == len(rows)
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
    mistakes, noise = _tally(keys, results, truth)
    per = {
        "draw variants (with rejection)": variants,
        "answer keys (tolerances, mistakes, plan points)": variants,
        "task and plan sheets (SVG)": variants,
        "`planmethod variants` end to end (files on disk)": variants,
        "grade drawn plans (JSON points)": drawings,
    }
    return {
        "machine": machine(),
        "template": str(TEMPLATE.relative_to(ROOT)),
        "variants": variants, "redrawn_variants": redrawn, "drawings": drawings,
        "questions_per_variant": len(keys[0]["questions"]),
        "numeric": {"submissions": len(rows), "answers": answers,
                    "seconds": round(grading_seconds, 4),
                    "answers_per_second": round(answers / grading_seconds)},
        "drawn_share_of_tolerance": DRAWN,
        "mistakes": mistakes, "noise": noise,
        "timings_s": {name: round(value, 4) for name, value in timings.items()},
        "per_item_ms": {name: round(1000 * value / per[name], 4)
                        for name, value in timings.items()},
    }


def _share(part: int, whole: int) -> str:
    return f"{part}/{whole} ({100 * part / whole:.1f} %)" if whole else "—"


def markdown(result: dict) -> str:
    numeric = result["numeric"]
    lines = [written_by("python -m benchmarks.bench_grading", result["machine"]).rstrip(), "",
             f"Template `{result['template']}`: {result['variants']} variants "
             f"({result['redrawn_variants']} redrawn after a rejected draw), "
             f"{result['questions_per_variant']} questions each; {result['drawings']} drawn "
             "plans.", "", "| step | total (s) | per item (ms) |", "|---|---:|---:|"]
    for name, seconds in result["timings_s"].items():
        lines.append(f"| {name} | {seconds:.3f} | {result['per_item_ms'][name]:.3f} |")
    lines += ["", f"Numeric answers: {numeric['answers']} in {numeric['submissions']} "
                  f"submissions (one CSV), read and graded in {numeric['seconds']:.3f} s: "
                  f"**{numeric['answers_per_second']:,} answers/s**.", "",
              "## Mistake answers", "",
              "Each mistake made by a student from the exercise (not taken from the key): "
              "*exact* from the exact value, *drawn* from a value off by up to "
              f"{result['drawn_share_of_tolerance']:g} of the question's tolerance. *in key*: "
              "answers to questions whose key lists that mistake (the others are within twice "
              "the tolerance of the right answer, or coincide with another mistake, and cannot "
              "be named).", "",
              "| mistake | answers | named right | named right, of those in key | "
              "named another mistake | accepted as right | wrong, no mistake named |",
              "|---|---:|---:|---:|---:|---:|---:|"]
    for how, kinds in result["mistakes"].items():
        totals: Counter = Counter()
        for kind, counts in kinds.items():
            totals.update(counts)
            lines.append(_mistake_row(f"{kind} ({how})", counts))
        lines.append(_mistake_row(f"**all ({how})**", totals))
    lines += ["", "## Noise answers", "",
              "The right value off by 0.5…1 times the size given (in tolerances of the "
              "question), either sign.", "",
              "| off by (tolerances) | answers | accepted as right | named as a mistake "
              "(wrongly) | which |", "|---:|---:|---:|---:|---|"]
    for size, counts in result["noise"].items():
        named = counts.get("named_right", 0) + counts.get("named_other", 0)
        which = ", ".join(f"{k} {v}" for k, v in sorted(counts["named_as"].items())) or "—"
        lines.append(f"| {size} | {counts['answers']} | "
                     f"{_share(counts.get('accepted', 0), counts['answers'])} | "
                     f"{_share(named, counts['answers'])} | {which} |")
    return "\n".join(lines) + "\n"


def _mistake_row(title: str, counts) -> str:
    total = counts.get("answers", 0)
    return (f"| {title} | {total} | {_share(counts.get('named_right', 0), total)} | "
            f"{_share(counts.get('listed_named_right', 0), counts.get('listed', 0))} | "
            f"{_share(counts.get('named_other', 0), total)} | "
            f"{_share(counts.get('accepted', 0), total)} | "
            f"{_share(counts.get('unnamed', 0), total)} |")


def scale_run(count: int) -> dict:
    """``planmethod variants`` for ``count`` variants of the template, as a subprocess (its
    own peak memory), with sheets and with ``--no-sheets``: wall and CPU seconds, peak memory
    (MB), and the variants a minute of each gives."""
    import resource
    import subprocess

    from planmethod.application.variants import MAX_VARIANTS

    runs = {}
    for sheets in (True, False):
        folder = Path(tempfile.mkdtemp(prefix="bench-scale-"))
        try:
            command = ["variants", str(TEMPLATE), "--count", str(count), "--seed", "2026",
                       "--out", str(folder / "course"), *([] if sheets else ["--no-sheets"])]
            # the child reports its own peak memory (RUSAGE_CHILDREN keeps the largest child's)
            script = ("import resource, sys\nfrom planmethod.cli import main\ntry:\n"
                      f"    code = main({command!r})\nfinally:\n    print('peak-kb', "
                      "resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, file=sys.stderr)\n"
                      "sys.exit(code)\n")
            load = os.getloadavg()[0]
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            started = time.perf_counter()
            done = subprocess.run([sys.executable, "-c", script], check=True, text=True,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                  env={**os.environ, "PYTHONPATH": str(ROOT)})
            wall = time.perf_counter() - started
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            peak_kb = int(next(line.split()[1] for line in done.stderr.splitlines()
                               if line.startswith("peak-kb")))
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        runs["with sheets" if sheets else "--no-sheets"] = {
            "wall_s": round(wall, 2), "cpu_s": round(cpu, 2),
            "peak_mb": round(peak_kb / 1024),   # Linux reports ru_maxrss in KB
            "load_average_at_start": round(load, 2),
            "ms_per_variant_wall": round(1000 * wall / count, 2),
            "ms_per_variant_cpu": round(1000 * cpu / count, 2),
            "variants_per_minute_wall": int(60 * count / wall),
            "variants_per_minute_cpu": int(60 * count / cpu)}
    return {"machine": machine(),
            "template": str(TEMPLATE.relative_to(ROOT)), "variants": count,
            "count_limit": MAX_VARIANTS, "runs": runs}


def scale_markdown(result: dict) -> str:
    lines = [written_by(f"python -m benchmarks.bench_grading --scale {result['variants']}",
                        result["machine"]).rstrip(), "",
             f"Template `{result['template']}`, {result['variants']} variants, the command "
             "run as a subprocess (`python -m benchmarks.bench_grading --scale "
             f"{result['variants']}`). The limit of `--count` (and of a roster): "
             f"{result['count_limit']:,}.", "",
             "| run | wall (s) | CPU (s) | ms a variant (wall / CPU) | variants a minute "
             "(wall / CPU) | peak memory (MB) | load average at start |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for name, run in result["runs"].items():
        lines.append(f"| {name} | {run['wall_s']:.1f} | {run['cpu_s']:.1f} | "
                     f"{run['ms_per_variant_wall']:.1f} / {run['ms_per_variant_cpu']:.1f} | "
                     f"{run['variants_per_minute_wall']:,} / {run['variants_per_minute_cpu']:,} "
                     f"| {run['peak_mb']} | {run['load_average_at_start']:.2f} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="50 variants, 100 drawn plans")
    parser.add_argument("--no-write", action="store_true", help="print only")
    parser.add_argument("--scale", type=int, metavar="N",
                        help="only time `planmethod variants` for N variants (the --count "
                             "limit's measure)")
    args = parser.parse_args(argv)
    if args.scale:
        result = scale_run(args.scale)
        text = scale_markdown(result)
        print(text)
        if not args.no_write:
            from planmethod.io import write_text_atomic

            write_text_atomic(RESULTS / "grading_scale.json",
                              json.dumps(result, indent=2) + "\n")
            write_text_atomic(RESULTS / "grading_scale.md", text)
        return 0
    variants, drawings = (50, 100) if args.quick else (500, 1000)
    result = run(variants, drawings)
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
