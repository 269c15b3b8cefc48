"""``planmethod variants TEMPLATE``: one variant per student, with task sheets and answer keys.

Writes into ``--out``: ``keys.json`` (the bundle of every key), ``index.csv`` (student, attempt,
drawn values), ``manifest.json`` (every file of the run with its size and SHA-256: what a later
``--force`` may remove) and, per student, a folder with ``exercise.toml`` (the variant as a
plain exercise file), ``key.json``, ``task.svg`` and ``task.txt`` (the task sheet), and blank
``velocity_sheet.svg`` / ``acceleration_sheet.svg`` to draw the plans on.

Everything is computed before anything is written, and the run is written whole or not at all:
into a private folder inside ``--out``, whose entries are moved into place only when every file
is written. ``--force`` replaces an earlier run only when everything in ``--out`` is what that
run's manifest lists, unchanged (no other file, no symbolic link, no edited file); its entries
are moved aside when the new run is in place and only then removed, file by file, each checked
again against the manifest.
"""
from __future__ import annotations

import argparse
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

#: the files of a run beside its student folders
RUN_FILES = ("keys.json", "index.csv")

#: the run's list of its own files (what ``--force`` may remove), and its format tag
MANIFEST = "manifest.json"
MANIFEST_FORMAT = "planmethod-variants-manifest"

#: the files variants writes into a student's folder
STUDENT_FILES = ("exercise.toml", "key.json", "task.svg", "task.txt", "velocity_sheet.svg",
                 "acceleration_sheet.svg")

#: the largest roster (as the answers files: 200,000 students) and manifest read, bytes
MAX_ROSTER_BYTES = 20_000_000
MAX_MANIFEST_BYTES = 200_000_000

#: the most variants one run draws: about a minute of CPU time, with sheets, on the 2-CPU
#: machine of ``python -m benchmarks.bench_grading --scale`` even when it is shared (48 ms a
#: variant at a load of 8, benchmarks/results/grading_scale.md; 19 ms idle, grading.md)
MAX_VARIANTS = 1_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("template", help="exercise template (TOML with ranges, choices, "
                                         "expressions) or a plain exercise file")
    parser.add_argument("--count", type=int, metavar="N",
                        help=f"number of variants (students 001…N, at most {MAX_VARIANTS}); "
                             "default: the roster's size, or 1")
    parser.add_argument("--seed", type=_whole_number, default=0,
                        help="random seed of the draw (default 0): the same seed, template "
                             "and student always give the same variant")
    parser.add_argument("--students", metavar="ROSTER",
                        help="roster CSV (a student/id/email column, or one id per line)")
    parser.add_argument("--out", required=True, metavar="DIR", help="output folder")
    parser.add_argument("--no-sheets", action="store_true",
                        help="write keys only (no SVG task and plan sheets)")
    parser.add_argument("--force", action="store_true",
                        help="replace an earlier variants run in --out: only when everything "
                             "there is what that run's manifest.json lists, unchanged; its "
                             "files are removed once the new run is written")


def _whole_number(text: str) -> int:
    """A whole number within 64 bits, as the keys.json it goes into is read back."""
    from ..spec import MAX_INTEGER

    try:
        value = int(text) if len(text) <= 20 else None
    except ValueError:
        value = None
    if value is None or abs(value) > MAX_INTEGER:
        raise argparse.ArgumentTypeError(f"expected a whole number within ±{MAX_INTEGER}, got "
                                         f"{text[:30]!r}")
    return value


def read_roster(path: str) -> list[tuple[str, list[str]]]:
    """Students from a roster: a CSV with a student/id/email column, or one id per line.

    Each student comes with every other id the roster gives them (e-mail, SID, name), which an
    LMS may know them by: ``[(student, [aliases…]), …]``.
    """
    from ..errors import SpecError
    from ..grading.answers import STUDENT_COLUMNS, answers_from_csv
    from ..io import read_text_bounded

    text = read_text_bounded(path, MAX_ROSTER_BYTES, encoding="utf-8-sig")
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    if not lines:
        raise SpecError("the roster is empty", file=path)
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
        raise SpecError(f"duplicate student ids: {', '.join(duplicates[:5])}", file=path)
    if not students:
        raise SpecError("the roster lists no students", file=path)
    return students


@dataclass(frozen=True)
class EarlierRun:
    """A run of ``variants`` found in ``--out``: its entries there (student folders, run files,
    manifest) and every file its manifest lists, relative path → (bytes, SHA-256)."""

    entries: tuple[str, ...]
    files: Mapping[str, tuple[int, str]]


def manifest_text(files: Mapping[str, bytes]) -> str:
    """The manifest of a run: each file's relative path, size in bytes and SHA-256.

    >>> print(manifest_text({"001/key.json": b"{}"}))  # doctest: +ELLIPSIS
    {
     "format": "planmethod-variants-manifest",
     "note": "...",
     "files": [
      ["001/key.json", 2, "44136fa355b3678a1146ad16f7e8649e94fb4fc21fe77e8310c060f61caaff8a"]
     ]
    }
    """
    import hashlib

    from ..io import json_text

    return json_text({"format": MANIFEST_FORMAT,
                      "note": "written by planmethod variants: the files `variants --force` may "
                              "remove, each only while its size and SHA-256 are these",
                      "files": [[name, len(data), hashlib.sha256(data).hexdigest()]
                                for name, data in sorted(files.items())]})


def _manifest_path(name: object) -> bool:
    """Whether ``name`` is a path variants writes: a run file, or a student file in a
    student folder."""
    from ..errors import SpecError
    from ..io import path_component

    if not isinstance(name, str):
        return False
    parts = name.split("/")
    if len(parts) == 1:
        return name in RUN_FILES
    try:
        path_component(parts[0], "folder")
    except SpecError:
        return False
    return (len(parts) == 2 and parts[1] in STUDENT_FILES
            and parts[0] not in (*RUN_FILES, MANIFEST))


def _read_manifest(out: Path) -> dict[str, tuple[int, str]]:
    """The files the manifest in ``out`` lists, or a :class:`SpecError`."""
    import json
    import os

    from ..errors import SpecError
    from ..io import read_text_bounded

    path = out / MANIFEST
    if not os.path.lexists(path):
        raise SpecError(f"--out {out} holds no {MANIFEST}, so no variants run of this version "
                        "wrote it: --force replaces only such a run; choose another folder")
    if os.path.islink(path):
        raise SpecError("is a symbolic link, which variants never writes: --force replaces "
                        "only an earlier run", file=str(path))
    try:
        data = json.loads(read_text_bounded(path, MAX_MANIFEST_BYTES))
    except json.JSONDecodeError as error:
        raise SpecError(f"not valid JSON ({error})", file=str(path)) from None
    if not isinstance(data, dict) or data.get("format") != MANIFEST_FORMAT:
        raise SpecError(f"not a manifest of variants (format {MANIFEST_FORMAT!r})",
                        file=str(path))
    files: dict[str, tuple[int, str]] = {}
    rows = data.get("files")
    for index, row in enumerate(rows if isinstance(rows, list) else [None]):
        if not (isinstance(row, list) and len(row) == 3 and _manifest_path(row[0])
                and type(row[1]) is int and isinstance(row[2], str)
                and re.fullmatch(r"[0-9a-f]{64}", row[2])):
            raise SpecError(f"lists {str(row)[:60]!r}, not a file variants writes with its "
                            "size and SHA-256", file=str(path), key=f"files[{index}]")
        files[row[0]] = (row[1], row[2])
    return files


def _unchanged(path: Path, size: int, digest: str) -> bool:
    """Whether ``path`` is a regular file (not a link) of ``size`` bytes and SHA-256
    ``digest``."""
    import os
    import stat

    from ..io import sha256_of_file

    try:
        status = os.lstat(path)
    except OSError:
        return False
    return (stat.S_ISREG(status.st_mode) and status.st_size == size
            and sha256_of_file(path) == digest)


def earlier_run(out: str | Path, *, force: bool) -> EarlierRun | None:
    """The earlier run in ``out`` that ``--force`` may replace; None for a folder that is
    missing or empty. A :class:`SpecError` if ``out`` is not empty and ``force`` is not given,
    or if anything there is not what the run's manifest lists, unchanged: another file, a
    symbolic link, an edited file (an ``index.csv`` edited to name ``notes.txt`` is one)."""
    import os

    from ..errors import SpecError

    out = Path(out)
    if not os.path.lexists(out):
        return None
    if not out.is_dir():
        raise SpecError(f"--out {out} is a file, not a folder")
    entries = sorted(os.listdir(out))
    if not entries:
        return None
    if not force:
        raise SpecError(f"--out {out} is not empty ({len(entries)} entries): choose an empty "
                        "folder, or give --force to replace an earlier variants run there")
    files = _read_manifest(out)
    tops = {name.split("/")[0] for name in files}
    foreign, linked, changed = [], [], []
    for name in entries:
        path = out / name
        if os.path.islink(path):
            linked.append(name)
        elif name == MANIFEST:
            continue
        elif name not in tops:
            foreign.append(name)
        elif path.is_dir():
            for inner in sorted(os.listdir(path)):
                relative = f"{name}/{inner}"
                if os.path.islink(path / inner):
                    linked.append(relative)
                elif relative not in files:
                    foreign.append(relative)
                elif not _unchanged(path / inner, *files[relative]):
                    changed.append(relative)
        elif name not in files or not _unchanged(path, *files[name]):
            changed.append(name)
    if foreign:
        raise SpecError(f"--out {out} holds files no variants run wrote ({', '.join(foreign[:3])}"
                        f"{', …' if len(foreign) > 3 else ''}): --force only replaces an "
                        "earlier run; choose another folder")
    if linked:
        raise SpecError(f"--out {out} holds symbolic links ({', '.join(linked[:3])}), which "
                        "variants never writes: --force only replaces an earlier run; choose "
                        "another folder")
    if changed:
        raise SpecError(f"--out {out}: {', '.join(changed[:3])} changed since variants wrote "
                        f"{'them' if len(changed) > 1 else 'it'} (size or SHA-256 differs from "
                        f"{MANIFEST}): --force removes only what variants wrote; move "
                        f"{'them' if len(changed) > 1 else 'it'} away or choose another folder")
    return EarlierRun(tuple(entries), files)


def remove_retired(retired: Path, earlier: EarlierRun | None) -> list[str]:
    """Remove an earlier run moved aside into ``retired``: each file its manifest lists, if
    still unchanged, then the manifest and the emptied folders. Returns what is left there
    (changed since the check), which stays."""
    import contextlib
    import os

    files = earlier.files if earlier is not None else {}
    for name, (size, digest) in files.items():
        path = retired / name
        if _unchanged(path, size, digest):
            os.unlink(path)
    manifest = retired / MANIFEST
    if os.path.lexists(manifest) and not os.path.islink(manifest) and manifest.is_file():
        os.unlink(manifest)
    for name in sorted({name.split("/")[0] for name in files if "/" in name}):
        with contextlib.suppress(OSError):
            os.rmdir(retired / name)
    left = sorted(os.listdir(retired))
    if not left:
        os.rmdir(retired)
    return left


def run(args: argparse.Namespace) -> int:
    import sys

    from ..errors import SpecError
    from ..grading.templates import load_template
    from ..io import output_set, student_folder

    out = Path(args.out)
    earlier = earlier_run(out, force=args.force)   # before any work: refuse, or what to replace
    template = load_template(args.template)
    aliases: dict[str, list[str]] = {}
    if args.students:
        roster = read_roster(args.students)
        students = [student for student, _ in roster]
        if len(students) > MAX_VARIANTS:
            raise SpecError(f"the roster lists {len(students)} students; at most {MAX_VARIANTS} "
                            "a run (a run of that many takes about a minute): split it",
                            file=args.students)
        aliases = dict(roster)
        if args.count is not None and args.count != len(students):
            raise SpecError(f"--count {args.count} does not match the roster's "
                            f"{len(students)} students", file=args.students)
    else:
        count = 1 if args.count is None else args.count
        if not 1 <= count <= MAX_VARIANTS:
            raise SpecError(f"--count must be in 1…{MAX_VARIANTS}, got {count} (a run of "
                            f"{MAX_VARIANTS} takes about a minute)")
        width = max(3, len(str(count)))
        students = [str(i).zfill(width) for i in range(1, count + 1)]
    folders = [student_folder(s) for s in students]
    if len(set(folders)) != len(folders):
        raise SpecError("two student ids map to the same folder name", file=args.students)
    taken = sorted(set(folders) & {*RUN_FILES, MANIFEST})
    if taken:
        raise SpecError(f"a student id maps to the folder name {taken[0]}, which the run's own "
                        "file has", file=args.students)
    files, rejected, index_rows = variant_files(
        template, students, folders, seed=args.seed, aliases=aliases,
        roster=bool(args.students), sheets=not args.no_sheets, source=str(args.template))
    data = {name: text.encode("utf-8") for name, text in files.items()}
    data[MANIFEST] = manifest_text(data).encode("utf-8")
    with output_set() as outputs:   # the whole run, beside the earlier one, then swapped in
        outputs.folder(out, data, replaces=earlier.entries if earlier else ())
    retired = outputs.retired.get(out)
    left = remove_retired(retired, earlier) if retired is not None else []
    if left:
        print(f"planmethod: note: {retired} keeps what changed in the earlier run during this "
              f"one ({', '.join(left[:3])}{', …' if len(left) > 3 else ''})", file=sys.stderr)
    redrawn = sum(1 for row in index_rows if row[2])
    print(f"Wrote {len(index_rows)} variants of {template.source} (seed {args.seed}) to {out}/ "
          f"({redrawn} redrawn after a rejected draw); keys in {out / 'keys.json'}")
    if rejected:
        print(f"{len(rejected)} draws rejected:")
        for line in rejection_summary(rejected):
            print(f"  {line}")
    return 0


def variant_files(template, students: list[str], folders: list[str], *, seed: int,
                  aliases: dict[str, list[str]] | None = None, roster: bool = False,
                  sheets: bool = True, source: str = "",
                  progress: bool | None = None) -> tuple[dict[str, str], list[str], list[list]]:
    """Everything a ``variants`` run writes, computed: (files by relative path, the reasons of
    rejected draws, the rows of index.csv). ``folders`` are the students' folder names."""
    import json

    from ..grading.keys import build_key, bundle
    from ..grading.paper import add_sheets
    from ..grading.templates import draw_variant, to_toml
    from ..io import csv_text, json_text
    from ..progress import Progress

    aliases = aliases or {}
    files: dict[str, str] = {}
    rejected: list[str] = []
    keys = []
    index_rows = []
    with Progress(len(students), "variants", enabled=progress) as bar:
        for student, folder in zip(students, folders, strict=True):
            variant = draw_variant(template, seed=seed, student=student)
            rejected += list(variant.rejected)
            key = build_key(variant)
            # who the LMS may know the student as, and whether a roster named them (an
            # autograder matches submitters to variants by these)
            key["identities"] = aliases.get(student, [])
            key["roster"] = roster
            keys.append(key)
            # the description with its placeholders filled in, as the student reads it
            files[f"{folder}/exercise.toml"] = to_toml({**variant.data,
                                                        "description": variant.description})
            if sheets:
                from ..grading.sheets import plan_sheet_for_key, task_sheet_svg, task_text
                from ..plans import draw_plans

                plans = draw_plans(variant.exercise, acceleration=False)
                files[f"{folder}/task.svg"] = task_sheet_svg(key, plans)
                files[f"{folder}/task.txt"] = task_text(key)
                for plan in ("velocity", "acceleration"):
                    if plan in key["plans"]:
                        files[f"{folder}/{plan}_sheet.svg"] = plan_sheet_for_key(key, plan)
            index_rows.append([student, folder, variant.attempt,
                               json.dumps(variant.values, ensure_ascii=False)])
            bar.advance()
    # the booklet's pages: each plan sheet's geometry (page mm) and QR code, in the keys
    course = add_sheets(keys)
    for key, folder in zip(keys, folders, strict=True):
        files[f"{folder}/key.json"] = json_text(key)
    files["keys.json"] = json_text(bundle(keys, template=source, seed=seed, count=len(keys),
                                          course=course))
    files["index.csv"] = csv_text([["student", "folder", "attempt", "values"], *index_rows])
    return files, rejected, index_rows


#: a number in a reason (not a digit of a name such as O2)
_NUMBER = re.compile(r"(?<![A-Za-z_])-?\d+(?:\.\d+)?")


def rejection_summary(reasons: list[str]) -> list[str]:
    """The reasons of rejected draws, alike ones counted together, most frequent first, each
    number shown as the range it took.

    Examples
    --------
    >>> for line in rejection_summary(["segment of ω₃ is 4.2 mm (below 10 mm)",
    ...                                "the crank is 3.1° from a dead centre (below 5°)",
    ...                                "segment of ω₃ is 9.5 mm (below 10 mm)"]):
    ...     print(line)
    2× segment of ω₃ is 4.2–9.5 mm (below 10 mm)
    1× the crank is 3.1° from a dead centre (below 5°)
    """
    groups: dict[str, list[list[str]]] = {}
    for reason in reasons:
        groups.setdefault(_NUMBER.sub("#", reason), []).append(_NUMBER.findall(reason))
    lines = []
    for pattern, rows in sorted(groups.items(), key=lambda item: (-len(item[1]), item[0])):
        parts = pattern.split("#")
        text = parts[0]
        for column, rest in zip(zip(*rows, strict=True), parts[1:], strict=True):
            low, high = min(column, key=float), max(column, key=float)
            text += low if float(low) == float(high) else f"{low}–{high}"
            text += rest
        lines.append(f"{len(rows)}× {text}")
    return lines
