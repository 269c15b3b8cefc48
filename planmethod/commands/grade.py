"""``planmethod grade KEY ANSWERS``: score numeric answers (CSV or JSON, one row per student)
and drawn plans (``--drawing`` SVG or JSON) against a key, with feedback.

KEY is a key (``key.json``), a bundle (``keys.json`` or the folder that holds it), or a plain
exercise file (its key is built on the spot). Each student is graded against their own
variant's key when the bundle has one, else against the single key. A drawing downloaded from
the workbook page names its exercise (title and digest) and crank angle: it is refused in one
line if it is of another exercise, and graded against the key of its own angle, built from the
exercise the key keeps (docs/workbook-drawing.md).
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..io import OutputSet


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("key", nargs="?",
                        help="key.json, keys.json (or its folder), or an exercise file")
    parser.add_argument("answers", nargs="?", help="answers: CSV or JSON, one row per student")
    parser.add_argument("--key", dest="key_file", metavar="FILE",
                        help="the key, as KEY (then a file given after the options is ANSWERS)")
    parser.add_argument("--photo", nargs="+", action="extend", default=[], metavar="IMAGE",
                        help="phone photos of plan sheets printed by `planmethod booklet`: "
                             "each is graded against its student's key (the sheet's QR code "
                             "says whose); a photo that cannot be read is refused in one line")
    parser.add_argument("--marked", metavar="DIR",
                        help="write each graded photo into DIR, its points marked green or "
                             "red, with the sentences under it (for the student)")
    parser.add_argument("--jobs", type=int, metavar="N",
                        help="grade the photos in N worker processes (default: by their "
                             "number, at most the CPUs this process may use)")
    parser.add_argument("--drawing", action="append", default=[], metavar="FILE",
                        help="a drawn plan (SVG or JSON of points in mm); may be repeated; "
                             "one downloaded from the workbook page is graded at its own "
                             "crank angle")
    parser.add_argument("--plan", choices=("velocity", "acceleration"),
                        help="which plan the drawing is (default: told by its pole label)")
    parser.add_argument("--student", help="grade as this student (picks the variant's key; "
                                          "for a single submission)")
    parser.add_argument("--json", metavar="FILE", help="write every result as JSON")
    parser.add_argument("--csv", metavar="FILE", help="write a CSV gradebook")
    parser.add_argument("--gradescope", metavar="FILE",
                        help="write Gradescope's results.json (one student)")
    parser.add_argument("--feedback", choices=("full", "hints", "score"),
                        help="what each question's feedback shows: full (the right values), "
                             "hints (the mistake and which way the answer is off, never the "
                             "right value) or score (points only); default: full on the "
                             "screen and in --json, hints in --gradescope (the student sees it)")
    parser.add_argument("--report", metavar="DIR",
                        help="write the class report into DIR: questions.csv (mean score, "
                             "share right, most common mistake per question), mistakes.csv "
                             "and class_report.png (which step the class gets wrong)")
    parser.add_argument("--quiet", action="store_true", help="print the totals only")


def load_any_key(path: str) -> dict:
    """student → key from a key, a bundle, a folder, or an exercise file."""
    from pathlib import Path

    from ..grading.keys import build_key, load_keys

    if Path(path).suffix.lower() == ".toml":
        from ..grading.templates import draw_variant, load_template

        template = load_template(path)
        if template.is_random:
            from ..errors import SpecError

            raise SpecError("a template with ranges or choices has one key per student: run "
                            "`planmethod variants` and grade against its keys.json", file=path)
        key = build_key(draw_variant(template))
        return {"*": key, str(key["student"]): key}
    return load_keys(path)


def _stage_class_report(outputs: OutputSet, report: str, keys: dict, results: list
                        ) -> None:
    """Stage the class report (questions.csv, mistakes.csv, class_report.png) in the folder
    ``report`` of the output set ``outputs``."""
    import textwrap
    from pathlib import Path

    from ..errors import SpecError
    from ..grading.keys import key_numbers
    from ..grading.report import class_statistics, mistakes_csv, questions_csv
    from ..render.plots import save_class_report_plot
    from ..vocabulary import symbol

    rows = class_statistics(results)
    if not rows:
        raise SpecError("--report needs graded answers (give ANSWERS)")
    folder = Path(report)
    first = next(iter(keys.values()))
    numbers = key_numbers(first)
    symbols = {row["question"]: symbol(row["question"], numbers) for row in rows}
    words = {mistake["kind"]: textwrap.shorten(mistake["feedback"], 48, placeholder="…")
             for key in keys.values() for question in key.get("questions", ())
             for mistake in question.get("mistakes", ())}
    outputs.text(folder / "questions.csv", questions_csv(rows))
    outputs.text(folder / "mistakes.csv", mistakes_csv(rows))
    save_class_report_plot(rows, outputs.path(folder / "class_report.png"),
                           title=str(first.get("title", "")), symbols=symbols,
                           mistakes=words)


def run(args: argparse.Namespace) -> int:
    import json
    import sys
    from pathlib import Path

    from ..errors import SpecError
    from ..grading.answers import feedback_text, grade_many, read_answers
    from ..grading.drawings import grade_drawing, key_for_drawing, read_drawing
    from ..grading.exports import gradebook_csv, gradescope_results
    from ..io import output_set

    if args.key_file is not None:
        if args.answers is not None:
            raise SpecError("give the key once: as KEY or as --key FILE")
        args.key, args.answers = args.key_file, args.key
    if args.key is None:
        raise SpecError("give the key: KEY or --key FILE")
    if not args.answers and not args.drawing and not args.photo:
        raise SpecError("give ANSWERS, --drawing FILE and/or --photo IMAGE")
    if (args.marked or args.jobs is not None) and not args.photo:
        raise SpecError(f"{'--marked' if args.marked else '--jobs'} is for --photo")
    keys = load_any_key(args.key)
    photos = _grade_photos(keys, args) if args.photo else []
    key_of_student = None
    if args.student is not None:
        key_of_student = keys.get(args.student, keys.get("*"))
        if key_of_student is None:
            raise SpecError(f"no key for student {args.student!r}", file=args.key)
    results = []
    if args.answers:
        rows = read_answers(args.answers)
        if args.student is not None:
            rows = [(args.student if s == "*" or len(rows) == 1 else s, a) for s, a in rows]
        results = grade_many(keys, rows)
    drawings = []
    for path in args.drawing:
        key = key_of_student or keys.get("*")
        if key is None:
            raise SpecError("grading a drawing against a bundle needs --student", file=path)
        drawing = read_drawing(path)
        # a drawing from the workbook page is graded at its own angle, on its own exercise
        drawings.append(grade_drawing(key_for_drawing(key, drawing), drawing, args.plan))
    lines = []
    for result in results:
        total = result.get("max_score")
        who = "the answers" if result["student"] == "*" else result["student"]
        head = (f"{who}: {result['score']:g}/{total:g}" if total is not None
                else f"{who}: {result['error']}")
        lines.append(head)
        if not args.quiet:
            lines += [f"  {'ok ' if q['correct'] else 'XX '} "
                      f"{feedback_text(q, args.feedback or 'full')}"
                      for q in result["questions"]]
    for path, drawing in zip(args.drawing, drawings, strict=True):
        lines.append(f"{path} ({drawing['plan']} plan): {drawing['score']:g}/"
                     f"{drawing['max_score']:g}")
        if not args.quiet:
            lines += [f"  {'ok ' if p['correct'] else 'XX '} {p['feedback']}"
                      for p in drawing["points"]]
            lines += [f"  !  {line}" for line in drawing["feedback"]]
    graded = [(path, done) for path, done in photos if isinstance(done, dict)]
    drawings += [done["result"] for _, done in graded]
    lines += _photo_lines([done for _, done in graded], quiet=args.quiet)
    refused = [(path, done) for path, done in photos if isinstance(done, str)]
    if args.gradescope and len(results) > 1:
        raise SpecError(f"--gradescope writes one student's results; the answers hold "
                        f"{len(results)}", file=args.answers)
    with output_set() as outputs:   # every output file, or none
        if args.json:
            data = {"answers": results, "drawings": drawings}
            if args.photo:
                data["refused"] = [{"photo": path, "error": why} for path, why in refused]
            outputs.text(args.json, json.dumps(data, ensure_ascii=False, indent=1,
                                               allow_nan=False))
        if args.marked:
            for name, (_, done) in zip(_marked_names([path for path, _ in graded]), graded,
                                       strict=True):
                outputs.binary(Path(args.marked) / name, done["marked"])
        if args.csv:
            outputs.text(args.csv, gradebook_csv(results))
        if args.report:
            _stage_class_report(outputs, args.report, keys, results)
        if args.gradescope:
            result = results[0] if results else {"questions": [], "score": 0.0,
                                                 "variant": args.student}
            outputs.text(args.gradescope, json.dumps(
                gradescope_results(result, drawings, feedback=args.feedback or "hints"),
                ensure_ascii=False, indent=1))
    if lines:
        sys.stdout.write("\n".join(lines) + "\n")
    for _, why in refused:
        print(f"planmethod: error: {why}", file=sys.stderr)
    return 2 if refused else 0


# -- photos ------------------------------------------------------------------------------------
#: what a photo worker grades against (set once in each worker, inherited by fork)
_WORK: dict = {}


def _photo_lines(graded: list[dict], *, quiet: bool) -> list[str]:
    """What the screen shows of graded photos: each photo's score, then (unless ``quiet``) its
    points' verdicts and the plan's feedback, as for a drawing."""
    lines = []
    for done in graded:
        lines.append(done["header"])
        if not quiet:
            lines += [f"  {'ok ' if p['correct'] else 'XX '} {p['feedback']}"
                      for p in done["result"]["points"]]
            lines += [f"  !  {line}" for line in done["result"]["feedback"]]
    return lines


def _marked_names(paths: list[str]) -> list[str]:
    """The marked photos' file names: each photo's name with ``_marked.jpg``, numbered where
    two photos share a name.

    >>> _marked_names(["a/s1.jpg", "b/s1.jpg", "s2.png"])
    ['s1_marked.jpg', 's1_2_marked.jpg', 's2_marked.jpg']
    """
    from pathlib import Path

    seen: dict[str, int] = {}
    out = []
    for path in paths:
        stem = Path(path).stem
        seen[stem] = seen.get(stem, 0) + 1
        out.append(f"{stem}_marked.jpg" if seen[stem] == 1 else f"{stem}_{seen[stem]}_marked.jpg")
    return out


def _start_photo_worker(parent: int | None, keys: dict, key_source: str, marked: bool) -> None:
    """A photo worker's first act: end with its parent, one thread for OpenCV (the pool is the
    bound), and the keys to grade against."""
    import cv2

    from .workbook import end_with_parent

    end_with_parent(parent)
    cv2.setNumThreads(1)
    _WORK.update(keys=keys, key_source=key_source, marked=marked)


def _photo_header(result: dict) -> str:
    from ..words import message, render

    plan = (message("velocity plan") if result["plan"] == "velocity"
            else message("acceleration plan"))
    return render(message("{photo} (student {student}, {plan}): {score:g}/{total:g}",
                          photo=result["photo"], student=str(result["student"]), plan=plan,
                          score=result["score"], total=result["max_score"]))


def _grade_one(path: str):
    """One photo graded (with its marked image if asked), or why it was refused (text)."""
    from ..errors import PlanmethodError
    from ..grading.photos import photo_graded

    try:
        graded = photo_graded(_WORK["keys"], path, key_source=_WORK["key_source"])
    except PlanmethodError as error:
        return path, str(error)
    done = {"result": graded.result, "header": _photo_header(graded.result)}
    if _WORK["marked"]:
        from ..render.marked import marked_photo

        done["marked"] = marked_photo(graded.image, graded.result, [done["header"]])
    return path, done


def _grade_photos(keys: dict, args: argparse.Namespace) -> list:
    """Every photo of ``--photo`` graded, in order — in a pool of ``--jobs`` worker processes
    that ends with this one — as (path, result or the reason it was refused)."""
    import importlib.util
    import multiprocessing
    import os
    import sys

    from ..errors import SpecError
    from .workbook import worker_count

    if importlib.util.find_spec("cv2") is None:
        raise SpecError("grading photos needs OpenCV: pip install 'planmethod[paper]'")
    workers = worker_count(args.jobs, len(args.photo)) if args.jobs is not None else \
        worker_count(None, 6 * len(args.photo))
    workers = min(workers, len(args.photo))
    initial = (keys, str(args.key), bool(args.marked))
    if workers <= 1:
        _WORK.update(keys=keys, key_source=str(args.key), marked=bool(args.marked))
        return [_grade_one(path) for path in args.photo]
    # fork on Linux: the workers are this process's children (the parent check holds) — unless
    # OpenCV already runs here (a notebook, a test): its thread pool does not survive a fork
    method = "fork" if sys.platform.startswith("linux") and "cv2" not in sys.modules else \
        "spawn"
    context = multiprocessing.get_context(method)
    parent = os.getpid() if sys.platform.startswith("linux") else None
    with context.Pool(workers, initializer=_start_photo_worker,
                      initargs=(parent, *initial)) as pool:   # leaving it ends the workers
        return list(pool.imap(_grade_one, args.photo))
