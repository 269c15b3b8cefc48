"""Draw the variants of a template for a class, and the files of their course folder.

A run of variants writes: ``keys.json`` (the bundle of every key), ``index.csv`` (student,
folder, attempt, drawn values), ``manifest.json`` (every file of the run with its size and
SHA-256: what a later ``--force`` may remove) and, per student, a folder with
``exercise.toml`` (the variant as a plain exercise file), ``key.json``, ``task.svg`` and
``task.txt`` (the task sheet), and blank ``velocity_sheet.svg`` / ``acceleration_sheet.svg``
to draw the plans on. Everything is computed (:func:`draw_variants`) before anything is
written (:func:`write_variants`: whole or not at all, :mod:`planmethod.runs`).

The most variants one run draws, :data:`MAX_VARIANTS`, is the command line's and the
studio's.

Examples
--------
>>> from planmethod.grading.templates import load_template
>>> template = load_template("exercises/templates/slider_crank.toml")
>>> drawn = draw_variants(VariantsRequest(template, class_of(2), seed=3, sheets=False))
>>> sorted(drawn.files)[:3], [variant.student for variant in drawn.variants]
(['001/exercise.toml', '001/key.json', '002/exercise.toml'], ['001', '002'])
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import SpecError
from ..runs import MANIFEST, RunKind, write_run
from ..words import Message, message
from .tasks import Watch

__all__ = ["MANIFEST", "MAX_ROSTER_BYTES", "MAX_VARIANTS", "RUN", "RUN_FILES",
           "STUDENT_FILES", "Class", "DrawnVariant", "VariantSet", "VariantsRequest",
           "class_of", "draw_variants", "manifest_text", "read_roster",
           "write_variants"]

#: the files of a run beside its student folders
RUN_FILES = ("keys.json", "index.csv")

#: the files variants writes into a student's folder
STUDENT_FILES = ("exercise.toml", "key.json", "task.svg", "task.txt", "velocity_sheet.svg",
                 "acceleration_sheet.svg")

#: the largest roster (as the answers files: 200,000 students) read, bytes
MAX_ROSTER_BYTES = 20_000_000

#: the most variants one run draws: about a minute of CPU time, with sheets, on the 2-CPU
#: machine of ``python -m benchmarks.bench_grading --scale`` even when it is shared (48 ms a
#: variant at a load of 8, benchmarks/results/grading_scale.md; 19 ms idle, grading.md)
MAX_VARIANTS = 1_000


@dataclass(frozen=True)
class Class:
    """The students of a run: their ids, their folders' names (in the same order), every
    other id a roster gives each (e-mail, SID, name) and whether a roster named them."""

    students: tuple[str, ...]
    folders: tuple[str, ...]
    aliases: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    roster: bool = False


@dataclass(frozen=True)
class VariantsRequest:
    """What to draw: one variant of ``template`` per student of ``students`` with the random
    ``seed``, their task and plan sheets if ``sheets``; ``source`` is the template's name the
    bundle of keys records."""

    template: Any
    students: Class
    seed: int = 0
    sheets: bool = True
    source: str = ""


@dataclass(frozen=True)
class DrawnVariant:
    """One student's variant: the attempt that was kept and the values drawn."""

    student: str
    folder: str
    attempt: int
    values: Mapping[str, Any]


@dataclass(frozen=True)
class VariantSet:
    """The variants drawn and every file of their run, by relative path; the reasons of the
    draws that were rejected and drawn again."""

    files: Mapping[str, str]
    variants: tuple[DrawnVariant, ...]
    rejected: tuple[Message | str, ...]

    @property
    def redrawn(self) -> int:
        """How many students' variants were drawn again after a rejected draw."""
        return sum(1 for variant in self.variants if variant.attempt)

    def write(self, out: str | Path, *, force: bool = False) -> Message | str | None:
        """Write the run into the folder ``out`` as ``planmethod variants --out`` does: whole
        or not at all, into an empty folder, or (``force``) in place of an earlier run there
        that its manifest lists unchanged; a note if a file of the earlier run changed
        meanwhile and stays in a hidden folder."""
        from ..runs import earlier_run

        earlier = earlier_run(Path(out), RUN, force=force, name=f"--out {out}")
        return write_variants(out, self, earlier)


def read_roster(path: str) -> list[tuple[str, list[str]]]:
    """Students from a roster: a CSV with a student/id/email column, or one id per line.

    Each student comes with every other id the roster gives them (e-mail, SID, name), which an
    LMS may know them by: ``[(student, [aliases…]), …]``.
    """
    from ..grading.answers import STUDENT_COLUMNS, answers_from_csv
    from ..io import read_text_bounded

    text = read_text_bounded(path, MAX_ROSTER_BYTES, encoding="utf-8-sig")
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    if not lines:
        raise SpecError(message("the roster is empty"), file=path)
    header = [cell.strip().lower() for cell in re.split(r"[,;\t]", lines[0])]
    if len(header) > 1 and any(c in header for c in STUDENT_COLUMNS):
        students = []
        for student, cells in answers_from_csv(text, path):
            aliases = [str(value).strip() for name, value in cells.items()
                       if name.strip().lower() in STUDENT_COLUMNS and str(value).strip()]
            students.append((student, aliases))
    else:
        names = [re.split(r"[,;\t]", line)[0].strip() for line in lines]
        if names and names[0].lower() in STUDENT_COLUMNS:
            names = names[1:]
        students = [(name, []) for name in names]
    ids = [student for student, _ in students]
    duplicates = sorted({s for s in ids if ids.count(s) > 1})
    if duplicates:
        raise SpecError(message("duplicate student ids: {students}", students=duplicates[:5]),
                        file=path)
    if not students:
        raise SpecError(message("the roster lists no students"), file=path)
    return students


def class_of(count: int | None = None, roster: str | None = None, *, width: int = 3) -> Class:
    """The students of a run: those of the ``roster`` file, or ``count`` of them numbered
    ``001`` … (at least ``width`` digits; default 1 student); at most :data:`MAX_VARIANTS`.

    Parameters
    ----------
    count
        How many students (default: the roster's, or 1); with a roster, it must be the
        roster's size.
    roster
        A roster file: a CSV with a student/id/email column, or one id per line.
    width
        The fewest digits of a student's number.

    Raises
    ------
    SpecError
        For too many students, a count that is not the roster's, or students whose folder
        names clash (with each other or with a file of the run).
    """
    from ..io import student_folder

    if roster is not None:
        listed = read_roster(roster)
        students = [student for student, _ in listed]
        if len(students) > MAX_VARIANTS:
            raise SpecError(message("the roster lists {count} students; at most {limit} a run "
                                    "(a run of that many takes about a minute): split it",
                                    count=len(students), limit=MAX_VARIANTS), file=roster)
        if count is not None and count != len(students):
            raise SpecError(message("--count {count} does not match the roster's {students} "
                                    "students", count=count, students=len(students)),
                            file=roster)
        aliases = {student: tuple(names) for student, names in listed}
    else:
        count = 1 if count is None else count
        if not 1 <= count <= MAX_VARIANTS:
            raise SpecError(message("--count must be in 1…{limit}, got {count} (a run of "
                                    "{limit} takes about a minute)", limit=MAX_VARIANTS,
                                    count=count))
        digits = max(width, len(str(count)))
        students, aliases = [str(i).zfill(digits) for i in range(1, count + 1)], {}
    folders = [student_folder(student) for student in students]
    if len(set(folders)) != len(folders):
        raise SpecError(message("two student ids map to the same folder name"), file=roster)
    taken = sorted(set(folders) & {*RUN_FILES, MANIFEST})
    if taken:
        raise SpecError(message("a student id maps to the folder name {name}, which the "
                                "run's own file has", name=taken[0]), file=roster)
    return Class(tuple(students), tuple(folders), aliases, roster is not None)


def manifest_text(files: Mapping[str, bytes]) -> str:
    """The manifest of a run (:func:`planmethod.runs.manifest_text`): each file's relative
    path, size in bytes and SHA-256.

    >>> print(manifest_text({"001/key.json": b"{}"}))  # doctest: +ELLIPSIS
    {
     "format": "planmethod-variants-manifest",
     "note": "written by planmethod variants: ...",
     "files": [
      ["001/key.json", 2, "44136fa355b3678a1146ad16f7e8649e94fb4fc21fe77e8310c060f61caaff8a"]
     ]
    }
    """
    from ..runs import manifest_text as run_manifest

    return run_manifest(RUN, files)


def _manifest_path(name: str) -> bool:
    """Whether ``name`` is a path variants writes: a run file, or a student file in a
    student folder."""
    from ..io import path_component

    parts = name.split("/")
    if len(parts) == 1:
        return name in RUN_FILES
    try:
        path_component(parts[0], "folder")
    except SpecError:
        return False
    return (len(parts) == 2 and parts[1] in STUDENT_FILES
            and parts[0] not in (*RUN_FILES, MANIFEST))


#: what a run of variants is (its manifest's tag, the files it may list), for planmethod.runs
RUN = RunKind("variants", "planmethod-variants-manifest", _manifest_path)


def _student_files(variant, key: dict, folder: str, sheets: bool) -> dict[str, str]:
    """One student's files but the key (written once the class's booklet pages are known):
    the variant as an exercise file, and its sheets."""
    from ..grading.templates import to_toml

    # the description with its placeholders filled in, as the student reads it
    files = {f"{folder}/exercise.toml": to_toml({**variant.data,
                                                 "description": variant.description})}
    if sheets:
        from ..grading.sheets import plan_sheet_for_key, task_sheet_svg, task_text
        from ..plans import draw_plans

        plans = draw_plans(variant.exercise, acceleration=False)
        files[f"{folder}/task.svg"] = task_sheet_svg(key, plans)
        files[f"{folder}/task.txt"] = task_text(key)
        for plan in ("velocity", "acceleration"):
            if plan in key["plans"]:
                files[f"{folder}/{plan}_sheet.svg"] = plan_sheet_for_key(key, plan)
    return files


def draw_variants(request: VariantsRequest, *, watch: Watch | None = None) -> VariantSet:
    """Everything a run of variants writes, computed (nothing is written): each student's
    files, ``keys.json`` and ``index.csv``.

    Parameters
    ----------
    request
        The template, the students, the random seed, whether to draw the sheets.
    watch
        Hears each variant drawn (phase ``variants``) and may cancel the run.
    """
    import json

    from ..grading.keys import build_key, bundle
    from ..grading.paper import add_sheets
    from ..grading.templates import draw_variant
    from ..io import csv_text, json_text

    watch = watch or Watch()
    group = request.students
    files: dict[str, str] = {}
    rejected: list[Message | str] = []
    keys, drawn = [], []
    for student, folder in zip(group.students, group.folders, strict=True):
        variant = draw_variant(request.template, seed=request.seed, student=student)
        rejected += list(variant.rejected)
        key = build_key(variant)
        # who the LMS may know the student as, and whether a roster named them (an
        # autograder matches submitters to variants by these)
        key["identities"] = list(group.aliases.get(student, ()))
        key["roster"] = group.roster
        keys.append(key)
        files |= _student_files(variant, key, folder, request.sheets)
        drawn.append(DrawnVariant(student, folder, variant.attempt, dict(variant.values)))
        watch.step("variants", len(drawn), len(group.students))
    # the booklet's pages: each plan sheet's geometry (page mm) and QR code, in the keys
    course = add_sheets(keys)
    for key, folder in zip(keys, group.folders, strict=True):
        files[f"{folder}/key.json"] = json_text(key)
    files["keys.json"] = json_text(bundle(keys, template=request.source, seed=request.seed,
                                          count=len(keys), course=course))
    rows = [[item.student, item.folder, item.attempt,
             json.dumps(item.values, ensure_ascii=False)] for item in drawn]
    files["index.csv"] = csv_text([["student", "folder", "attempt", "values"], *rows])
    return VariantSet(files, tuple(drawn), tuple(rejected))


def write_variants(out: str | Path, drawn: VariantSet, earlier) -> Message | str | None:
    """Write the run into ``out`` whole, in place of the ``earlier`` run
    (:func:`planmethod.runs.earlier_run`) if any; a note if a file of the earlier run
    changed meanwhile and stays in a hidden folder."""
    return write_run(out, RUN, {name: text.encode("utf-8")
                                for name, text in drawn.files.items()}, earlier) or None


