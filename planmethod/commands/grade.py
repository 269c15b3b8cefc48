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
    parser.add_argument("key", help="key.json, keys.json (or its folder), or an exercise file")
    parser.add_argument("answers", nargs="?", help="answers: CSV or JSON, one row per student")
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
    symbols = {row.question: symbol(row.question, numbers) for row in rows}
    words = {mistake["kind"]: textwrap.shorten(mistake["feedback"], 48, placeholder="…")
             for key in keys.values() for question in key.get("questions", ())
             for mistake in question.get("mistakes", ())}
    outputs.text(folder / "questions.csv", questions_csv(rows))
    outputs.text(folder / "mistakes.csv", mistakes_csv(rows))
    with outputs.writing(folder / "class_report.png") as temporary:
        save_class_report_plot(rows, temporary, title=str(first.get("title", "")),
                               symbols=symbols, mistakes=words)


def _printed(args: argparse.Namespace, results: list, drawings: list) -> list[str]:
    """The lines grade prints: each student's score and, unless ``--quiet``, each question's
    feedback; each drawing's score and each point's feedback."""
    from ..grading.answers import feedback_text
    from ..words import render

    lines = []
    for result in results:
        total = result.max_score
        who = "the answers" if result.student == "*" else result.student
        head = (f"{who}: {result.score:g}/{total:g}" if total is not None
                else f"{who}: {render(result.error)}")
        lines.append(head)
        if not args.quiet:
            lines += [f"  {'ok ' if q.correct else 'XX '} "
                      f"{render(feedback_text(q, args.feedback or 'full'))}"
                      for q in result.questions]
    for path, drawing in zip(args.drawing, drawings, strict=True):
        lines.append(f"{path} ({drawing.plan} plan): {drawing.score:g}/"
                     f"{drawing.max_score:g}")
        if not args.quiet:
            lines += [f"  {'ok ' if p.correct else 'XX '} {render(p.feedback)}"
                      for p in drawing.points]
            lines += [f"  !  {render(line)}" for line in drawing.feedback]
    return lines


def run(args: argparse.Namespace) -> int:
    import json
    import sys

    from ..errors import SpecError, about
    from ..grading.answers import grade_many, read_answers
    from ..grading.drawings import grade_drawing, key_for_drawing, read_drawing
    from ..grading.exports import gradebook_csv, gradescope_results
    from ..grading.results import StudentGrade
    from ..io import output_set

    if not args.answers and not args.drawing:
        raise SpecError("give ANSWERS and/or --drawing FILE")
    keys = load_any_key(args.key)
    key_of_student = None
    if args.student is not None:
        key_of_student = keys.get(args.student, keys.get("*"))
        if key_of_student is None:
            raise SpecError(f"no key for student {args.student!r}", file=args.key)
    results = []
    if args.answers:
        with about(args.answers):   # an error here is about the answers, not the key
            rows = read_answers(args.answers)
            if args.student is not None:
                rows = [(args.student if s == "*" or len(rows) == 1 else s, a) for s, a in rows]
            results = grade_many(keys, rows)
    drawings = []
    for path in args.drawing:
        key = key_of_student or keys.get("*")
        if key is None:
            raise SpecError("grading a drawing against a bundle needs --student", file=path)
        with about(path):   # an error here is about this drawing, not the key
            drawing = read_drawing(path)
            # a drawing from the workbook page is graded at its own angle, on its own exercise
            drawings.append(grade_drawing(key_for_drawing(key, drawing), drawing, args.plan))
    lines = _printed(args, results, drawings)
    if args.gradescope and len(results) > 1:
        raise SpecError(f"--gradescope writes one student's results; the answers hold "
                        f"{len(results)}", file=args.answers)
    with output_set() as outputs:   # every output file, or none
        if args.json:
            outputs.text(args.json, json.dumps(
                {"answers": [result.as_dict() for result in results],
                 "drawings": [drawing.as_dict() for drawing in drawings]},
                ensure_ascii=False, indent=1, allow_nan=False))
        if args.csv:
            outputs.text(args.csv, gradebook_csv(results))
        if args.report:
            _stage_class_report(outputs, args.report, keys, results)
        if args.gradescope:
            result = results[0] if results else StudentGrade(args.student, args.student,
                                                             0.0, None)
            outputs.text(args.gradescope, json.dumps(
                gradescope_results(result, drawings, feedback=args.feedback or "hints"),
                ensure_ascii=False, indent=1))
    sys.stdout.write("\n".join(lines) + "\n")
    return 0
