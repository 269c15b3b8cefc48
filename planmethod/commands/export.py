"""``planmethod export KEY --format gradescope|prairielearn|moodle|csv``: the keys of a run
as an LMS import (see :mod:`planmethod.grading.exports`)."""

from __future__ import annotations

import argparse

#: the files of a Gradescope autograder that must be executable
EXECUTABLES = ("run_autograder", "setup.sh", "grade_submission.py")

#: the largest task sheet (task.svg) a Moodle quiz embeds, bytes
MAX_SHEET_BYTES = 2_000_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("key", help="keys.json (or its folder), a key.json, or an exercise file")
    parser.add_argument("--format", required=True,
                        choices=("gradescope", "prairielearn", "moodle", "csv"),
                        help="gradescope: an autograder; prairielearn: a question; moodle: a "
                             "quiz (XML); csv: a gradebook of --answers")
    parser.add_argument("--out", required=True, metavar="PATH",
                        help="output file (moodle: quiz.xml; csv: gradebook.csv) or folder "
                             "(gradescope, prairielearn)")
    parser.add_argument("--answers", metavar="FILE",
                        help="graded answers for csv (a gradebook) and gradescope "
                             "(results.json of one student)")
    parser.add_argument("--student", help="with --format gradescope --answers: the student")
    parser.add_argument("--feedback", choices=("full", "hints", "score"), default="hints",
                        help="what students see of each question (gradescope): full (the "
                             "right values), hints (default: the mistake and which way the "
                             "answer is off) or score (points only)")
    parser.add_argument("--slug", default="planmethod",
                        help="PrairieLearn question folder name (default planmethod)")


def run(args: argparse.Namespace) -> int:
    import json
    import os
    from pathlib import Path

    from ..errors import SpecError, about
    from ..grading import exports
    from ..grading.answers import grade_many, read_answers
    from ..grading.keys import bundle
    from ..io import output_set, path_component, read_text_bounded, student_folder
    from .grade import load_any_key

    if args.format == "prairielearn":
        path_component(args.slug, "--slug")  # before any work: it becomes a folder name
    keys = load_any_key(args.key)
    unique = list({id(k): k for k in keys.values()}.values())
    the_bundle = bundle(unique, source=str(args.key))
    out = Path(args.out)
    files: dict[str, str] = {}
    if args.format == "csv":
        if not args.answers:
            raise SpecError("--format csv needs --answers (the gradebook scores them)")
        with about(args.answers):   # an error here is about the answers, not the key
            files[""] = exports.gradebook_csv(grade_many(keys, read_answers(args.answers)))
    elif args.format == "gradescope":
        if args.answers:
            with about(args.answers):   # an error here is about the answers, not the key
                rows = read_answers(args.answers)
                if args.student is not None:
                    rows = [(args.student, a) for _, a in rows]
                if len(rows) != 1:
                    raise SpecError(f"results.json is for one student; the answers hold "
                                    f"{len(rows)}", file=args.answers)
                result = grade_many(keys, rows)[0]
            files["results.json"] = json.dumps(
                exports.gradescope_results(result, feedback=args.feedback),
                ensure_ascii=False, indent=1)
        else:
            files.update(exports.gradescope_autograder(the_bundle, feedback=args.feedback))
    elif args.format == "prairielearn":
        files.update(exports.prairielearn_questions(the_bundle, slug=args.slug))
    else:
        sheets = {}
        folder = Path(args.key) if Path(args.key).is_dir() else Path(args.key).parent
        for key in unique:   # each student's task sheet that variants wrote, if it is there
            sheet = folder / student_folder(str(key.get("student"))) / "task.svg"
            if os.path.lexists(sheet):
                sheets[str(key.get("student"))] = read_text_bounded(sheet, MAX_SHEET_BYTES)
        files[""] = exports.moodle_xml(unique, sheets=sheets)
    with output_set() as outputs:   # every file or none
        if "" in files:  # one output file
            written = [str(outputs.text(out, files[""]))]
        else:  # files inside the output folder, none of them outside it
            written = [str(path) for path in outputs.files(
                out, files, modes={name: 0o755 for name in EXECUTABLES if name in files})]
    print(f"Wrote {', '.join(written) if len(written) <= 4 else f'{len(written)} files in {out}'}")
    return 0
