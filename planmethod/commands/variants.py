"""``planmethod variants TEMPLATE``: one variant per student, with task sheets and answer keys.

Writes into ``--out``: ``keys.json`` (the bundle of every key), ``index.csv`` (student, attempt,
drawn values) and, per student, a folder with ``exercise.toml`` (the variant as a plain
exercise file), ``key.json``, ``task.svg`` and ``task.txt`` (the task sheet), and blank
``velocity_sheet.svg`` / ``acceleration_sheet.svg`` to draw the plans on. Everything is
computed before anything is written; every file is written whole or not at all.
"""

from __future__ import annotations

import argparse
import re


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("template", help="exercise template (TOML with ranges, choices, "
                                         "expressions) or a plain exercise file")
    parser.add_argument("--count", type=int, metavar="N",
                        help="number of variants (students 001…N); default: the roster's size, "
                             "or 1")
    parser.add_argument("--seed", type=int, default=0,
                        help="random seed of the draw (default 0): the same seed, template "
                             "and student always give the same variant")
    parser.add_argument("--students", metavar="ROSTER",
                        help="roster CSV (a student/id/email column, or one id per line)")
    parser.add_argument("--out", required=True, metavar="DIR", help="output folder")
    parser.add_argument("--no-sheets", action="store_true",
                        help="write keys only (no SVG task and plan sheets)")
    parser.add_argument("--force", action="store_true",
                        help="write into a folder that is not empty: what an earlier "
                             "`variants` run wrote there (its index.csv lists it) is removed "
                             "first; nothing else is touched")


def read_roster(path: str) -> list[tuple[str, list[str]]]:
    """Students from a roster: a CSV with a student/id/email column, or one id per line.

    Each student comes with every other id the roster gives them (e-mail, SID, name), which an
    LMS may know them by: ``[(student, [aliases…]), …]``.
    """
    from ..errors import SpecError
    from ..grading.answers import STUDENT_COLUMNS, _answers_from_csv

    try:
        with open(path, encoding="utf-8-sig") as handle:
            text = handle.read(5_000_000)
    except FileNotFoundError:
        raise SpecError("no such file", file=path) from None
    except (OSError, UnicodeDecodeError) as error:
        raise SpecError(f"cannot read the roster ({error})", file=path) from None
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    if not lines:
        raise SpecError("the roster is empty", file=path)
    header = [cell.strip().lower() for cell in re.split(r"[,;\t]", lines[0])]
    if len(header) > 1 and any(c in header for c in STUDENT_COLUMNS):
        students = []
        for student, cells in _answers_from_csv(text, path):
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


def _earlier_run(out, *, force: bool) -> list:
    """What an earlier ``variants`` run wrote into ``out`` (its student folders, keys.json and
    index.csv), to be replaced; a :class:`SpecError` if ``out`` is not empty and ``force`` is
    not given, or if it holds anything that no ``variants`` run wrote."""
    import csv
    from pathlib import Path

    from ..errors import SpecError
    from ..io import path_component

    out = Path(out)
    if not out.is_dir():
        return []
    entries = sorted(out.iterdir())
    if not entries:
        return []
    if not force:
        raise SpecError(f"--out {out} is not empty ({len(entries)} entries): choose an empty "
                        "folder, or give --force to replace an earlier variants run there")
    index = out / "index.csv"
    ours = {out / "keys.json", index}
    try:
        with index.open(encoding="utf-8", newline="") as handle:
            for row in csv.DictReader(handle):
                ours.add(out / path_component(row.get("folder") or "", "index.csv folder"))
    except (OSError, UnicodeDecodeError, csv.Error):
        pass
    foreign = [entry.name for entry in entries if entry not in ours]
    if foreign:
        raise SpecError(f"--out {out} holds files no variants run wrote ({', '.join(foreign[:3])}"
                        f"{', …' if len(foreign) > 3 else ''}): --force only replaces an "
                        "earlier run; choose another folder")
    return [entry for entry in entries if entry in ours]


def run(args: argparse.Namespace) -> int:
    import shutil
    from pathlib import Path

    from ..errors import SpecError
    from ..grading.templates import load_template
    from ..io import student_folder, write_files

    out = Path(args.out)
    earlier = _earlier_run(out, force=args.force)   # before any work: refuse or plan removal
    template = load_template(args.template)
    aliases: dict[str, list[str]] = {}
    if args.students:
        roster = read_roster(args.students)
        students = [student for student, _ in roster]
        aliases = dict(roster)
        if args.count is not None and args.count != len(students):
            raise SpecError(f"--count {args.count} does not match the roster's "
                            f"{len(students)} students", file=args.students)
    else:
        count = 1 if args.count is None else args.count
        if not 1 <= count <= 100_000:
            raise SpecError(f"--count must be in 1…100000, got {count}")
        width = max(3, len(str(count)))
        students = [str(i).zfill(width) for i in range(1, count + 1)]
    folders = [student_folder(s) for s in students]
    if len(set(folders)) != len(folders):
        raise SpecError("two student ids map to the same folder name", file=args.students)
    files, rejected, index_rows = variant_files(
        template, students, folders, seed=args.seed, aliases=aliases,
        roster=bool(args.students), sheets=not args.no_sheets, source=str(args.template))
    for path in earlier:       # the earlier run's students, keys and index, now replaced
        if path.is_dir():
            shutil.rmtree(path)
        elif path.exists():
            path.unlink()
    write_files(out, files)
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
    import csv
    import io
    import json

    from ..grading.keys import build_key, bundle
    from ..grading.templates import draw_variant, to_toml
    from ..io import json_text
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
            files[f"{folder}/key.json"] = json_text(key)
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
    files["keys.json"] = json_text(bundle(keys, template=source, seed=seed, count=len(keys)))
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["student", "folder", "attempt", "values"])
    writer.writerows(index_rows)
    files["index.csv"] = buffer.getvalue()
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
