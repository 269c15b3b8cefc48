"""``planmethod export KEY --format gradescope|prairielearn|moodle|csv``: the keys of a run
as an LMS import (see :mod:`planmethod.grading.exports`).

A folder it writes — a PrairieLearn question ``OUT/SLUG/``, a Gradescope autograder ``OUT/``
— is a run folder (:mod:`planmethod.runs`) with a ``manifest.json``: a later export into it
replaces it whole (no file of the earlier run is left, say a task figure of a student the new
keys no longer have), and only when everything there is what that manifest lists, unchanged;
a folder holding anything else is refused, never emptied. A single file (Moodle's quiz, a CSV
gradebook, Gradescope's ``results.json``) is replaced whole, as every output is.
"""

from __future__ import annotations

import argparse

from ..runs import RunKind

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


def _prairielearn_file(name: str) -> bool:
    """Whether ``name`` is a file of a PrairieLearn question folder an export writes."""
    from ..grading.exports import PRAIRIELEARN_FIGURES, PRAIRIELEARN_FILES

    parts = name.split("/")
    return (name in PRAIRIELEARN_FILES
            or (len(parts) == 2 and parts[0] == PRAIRIELEARN_FIGURES
                and parts[1].endswith(".svg") and parts[1] not in ("", ".svg")))


def _gradescope_file(name: str) -> bool:
    """Whether ``name`` is a file of a Gradescope autograder folder an export writes."""
    from ..grading.exports import GRADESCOPE_FILES

    return name in GRADESCOPE_FILES


#: the run folders export writes, by format (their manifests' tags, the files they may
#: list): a PrairieLearn question ``OUT/SLUG/``, a Gradescope autograder ``OUT/``
RUNS = {"prairielearn": RunKind("export --format prairielearn",
                                "planmethod-prairielearn-manifest", _prairielearn_file,
                                force=None),
        "gradescope": RunKind("export --format gradescope", "planmethod-gradescope-manifest",
                              _gradescope_file, force=None)}


def _run_folder(args: argparse.Namespace):
    """(the folder, its :class:`~planmethod.runs.RunKind`) of an export that writes a run
    folder, else None (a single file). The files of a PrairieLearn export are named with
    the slug in front (``SLUG/info.json``): its run folder is ``OUT/SLUG``."""
    from pathlib import Path

    from ..io import path_component

    if args.format == "prairielearn":
        path_component(args.slug, "--slug")  # before any work: it becomes a folder name
        return Path(args.out) / args.slug, RUNS["prairielearn"]
    if args.format == "gradescope" and not args.answers:
        return Path(args.out), RUNS["gradescope"]
    return None


def _task_sheets(key_path: str, keys: list) -> dict[str, str]:
    """Each student's task sheet (SVG text) that variants wrote beside the keys, by student,
    for those that are there."""
    import os
    from pathlib import Path

    from ..io import read_text_bounded, student_folder

    sheets = {}
    folder = Path(key_path) if Path(key_path).is_dir() else Path(key_path).parent
    for key in keys:
        sheet = folder / student_folder(str(key.get("student"))) / "task.svg"
        if os.path.lexists(sheet):
            sheets[str(key.get("student"))] = read_text_bounded(sheet, MAX_SHEET_BYTES)
    return sheets


def _write_run_folder(args: argparse.Namespace, files: dict[str, str], folder, kind,
                      earlier) -> list[str]:
    """Write an export's run folder whole, in place of the ``earlier`` export there; the
    files written (a note on stderr if a file of the earlier one changed meanwhile and stays
    in a hidden folder)."""
    import sys

    from ..runs import write_run

    prefix = f"{args.slug}/" if args.format == "prairielearn" else ""
    inside = {name.removeprefix(prefix): text.encode("utf-8") for name, text in files.items()}
    note = write_run(folder, kind, inside, earlier,
                     modes={name: 0o755 for name in EXECUTABLES if name in inside})
    if note:
        print(f"planmethod: note: {note}", file=sys.stderr)
    return [str(folder / name) for name in inside]


def run(args: argparse.Namespace) -> int:
    import json
    from pathlib import Path

    from ..errors import SpecError, about
    from ..grading import exports
    from ..grading.answers import grade_many, read_answers
    from ..grading.keys import bundle
    from ..io import output_set
    from ..runs import earlier_run
    from .grade import load_any_key

    run_folder = _run_folder(args)
    # before any work: refuse a folder that holds what no export wrote, or find its earlier run
    earlier = earlier_run(*run_folder) if run_folder is not None else None
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
        files[""] = exports.moodle_xml(unique, sheets=_task_sheets(args.key, unique))
    if run_folder is not None:   # the run folder, whole, in place of an earlier export
        out = run_folder[0]
        written = _write_run_folder(args, files, *run_folder, earlier)
    else:
        with output_set() as outputs:   # every file or none
            if "" in files:  # one output file
                written = [str(outputs.text(out, files[""]))]
            else:  # results.json inside the output folder
                written = [str(path) for path in outputs.files(out, files)]
    print(f"Wrote {', '.join(written) if len(written) <= 4 else f'{len(written)} files in {out}'}")
    return 0
