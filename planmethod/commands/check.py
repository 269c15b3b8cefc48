"""``planmethod check FILE COORDS.csv``: test printed point coordinates against the mechanism.

Papers and students print tables of point coordinates per crank angle (Table 2 of Umbetkulov et
al., "Dynamic force analysis of a six-link planar mechanism").
This command checks each row two ways:

1. **Link lengths** — every two given points of one link must be as far apart as the link says
   (frame points missing from the row are taken from the exercise);
2. **Positions** — each given point against the exact assembly at that crank angle on the
   exercise's branch (when the mechanism can be assembled there).

A point is flagged when it is off its exact position by more than ``--tolerance`` (mm, default
2), or — where no exact assembly exists — when it takes part in a violated length. Exit status:
0 when every row passes, 1 when something is flagged, 2 for bad input.

The CSV has a header; the crank angle in a column ``angle`` (or ``phi``, ``phi1``; degrees) and
each point P in columns ``x_P`` and ``y_P`` (m). Lines starting with ``#`` are comments.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> exercise = load_exercise("exercises/conveyor_sixbar.toml")
>>> rows = read_coordinates("exercises/conveyor_sixbar_table2.csv", exercise)
>>> findings = [check_row(exercise, row, 0.002) for row in rows]
>>> [(f.angle, f.flagged_points) for f in findings]  # doctest: +ELLIPSIS
[(135.0, ('D',)), (225.0, (...))]
>>> next(v for v in findings[1].violations if v.link == "rocker_EF").given
1.049...
"""

from __future__ import annotations

import argparse
import csv
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

ANGLE_COLUMNS = ("angle", "phi", "phi1", "φ1", "φ")

#: the largest coordinates table read (bytes)
MAX_TABLE_BYTES = 50_000_000


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="exercise file (TOML)")
    parser.add_argument("coordinates", help="CSV of point coordinates per crank angle")
    parser.add_argument("--tolerance", type=float, default=2.0, metavar="MM",
                        help="allowed error of a length or a position, mm (default 2)")
    parser.add_argument("--json", action="store_true", help="print the findings as JSON")


@dataclass(frozen=True, slots=True)
class Row:
    """One row of the table: the crank angle (deg), the given points (m) and its line number."""

    angle: float
    points: dict
    line: int


@dataclass(frozen=True, slots=True)
class LengthCheck:
    """|PQ| as given against the length of ``link``."""

    link: str
    first: str
    second: str
    given: float
    expected: float

    @property
    def error(self) -> float:
        return self.given - self.expected


@dataclass(frozen=True, slots=True)
class PositionCheck:
    """A given point against the exact assembly."""

    point: str
    given: tuple[float, float]
    exact: tuple[float, float]

    @property
    def error(self) -> float:
        return math.hypot(self.given[0] - self.exact[0], self.given[1] - self.exact[1])


@dataclass(frozen=True)
class RowFindings:
    """What was found in one row."""

    angle: float
    line: int
    tolerance: float
    lengths: tuple[LengthCheck, ...]
    positions: tuple[PositionCheck, ...]
    branch: str | None
    assembly_error: str | None = None
    notes: tuple[str, ...] = field(default=())

    @property
    def violations(self) -> tuple[LengthCheck, ...]:
        return tuple(c for c in self.lengths if abs(c.error) > self.tolerance)

    @property
    def flagged_points(self) -> tuple[str, ...]:
        if self.positions:
            return tuple(c.point for c in self.positions if c.error > self.tolerance)
        names = []
        for check in self.violations:
            names += [check.first, check.second]
        return tuple(dict.fromkeys(names))

    @property
    def flagged(self) -> bool:
        return bool(self.violations or self.flagged_points)

    def as_dict(self) -> dict:
        return {"angle": self.angle, "line": self.line, "flagged": self.flagged,
                "flagged_points": list(self.flagged_points), "branch": self.branch,
                "assembly_error": self.assembly_error,
                "lengths": [{"link": c.link, "pair": f"{c.first}{c.second}", "given": c.given,
                             "expected": c.expected, "error": c.error,
                             "violated": abs(c.error) > self.tolerance} for c in self.lengths],
                "positions": [{"point": c.point, "given": list(c.given), "exact": list(c.exact),
                               "error": c.error, "flagged": c.error > self.tolerance}
                              for c in self.positions]}


def _number(text: str, file: str, line: int, column: str, limit: float, unit: str) -> float:
    """A cell's number, finite and at most ``limit`` in magnitude (the exercise file's limits
    for a crank angle and a coordinate), or a :class:`SpecError` naming its line and column."""
    from ..errors import SpecError

    try:
        value = float(text)
    except ValueError:
        raise SpecError(f"line {line}, column {column}: not a number: {text!r}",
                        file=file) from None
    if not math.isfinite(value):
        raise SpecError(f"line {line}, column {column}: must be finite, got {text}", file=file)
    if abs(value) > limit:
        raise SpecError(f"line {line}, column {column}: must be within ±{limit:g}{unit}, got "
                        f"{text.strip()[:40]}", file=file)
    return value


def _column_name(name: str) -> str:
    """A point's column as it is read: ``X_B`` is ``x_B``."""
    axis, _, point = name.partition("_")
    return f"{axis.lower()}_{point}"


def _columns(header: list[str], line: int, exercise, file: str) -> tuple[int, dict]:
    """(the crank angle's column, point → {"x": column, "y": column}) of a table's header on
    ``line``, or a :class:`SpecError`: no angle column, a column that is not x_P or y_P of a
    point of the exercise, a lone x or y, a column given twice (one of two values would be
    kept without a word)."""
    from ..errors import SpecError
    from ..grading.answers import refuse_twice
    from ..spec import did_you_mean

    refuse_twice([name if "_" in name else "" for name in header], _column_name, "column",
                 file=file, key=f"line {line}", places="columns",
                 compared="the axis compared ignoring case")
    lowered = [name.lower() for name in header]
    angle_column = next((lowered.index(name) for name in ANGLE_COLUMNS if name in lowered), None)
    if angle_column is None:
        raise SpecError(f"no crank-angle column (one of {', '.join(ANGLE_COLUMNS)}) in the "
                        f"header {header}", file=file)
    known = {p for link in exercise.mechanism.links.values() for p in link.points}
    columns: dict[str, dict[str, int]] = {}
    for index, name in enumerate(header):
        if index == angle_column:
            continue
        axis, _, point = name.partition("_")
        if axis.lower() not in ("x", "y") or not point:
            raise SpecError(f"column {name!r}: expected x_P or y_P for a point P", file=file)
        if point not in known:
            raise SpecError(f"column {name!r}: unknown point '{point}'{did_you_mean(point, known)}",
                            file=file)
        columns.setdefault(point, {})[axis.lower()] = index
    for point, axes in columns.items():
        if set(axes) != {"x", "y"}:
            raise SpecError(f"point {point} has only a {next(iter(axes))} column", file=file)
    return angle_column, columns


def read_coordinates(path: str | Path, exercise) -> list[Row]:
    """The rows of a coordinates CSV (see the module docstring).

    Raises
    ------
    SpecError
        For a missing file, a missing angle column, an unknown point, a lone x or y column, or
        a value that is not a finite number — naming the file, line and column.
    """
    from ..errors import SpecError
    from ..io import read_text_bounded
    from ..spec import MAX_ANGLE_DEG, MAX_COORDINATE_M

    path = Path(path)
    file = str(path)
    text = read_text_bounded(path, MAX_TABLE_BYTES)
    lines = [(number, line) for number, line in enumerate(text.splitlines(), start=1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise SpecError("no header and no rows", file=file)
    reader = csv.reader([line for _, line in lines])
    header = [name.strip() for name in next(reader)]
    angle_column, columns = _columns(header, lines[0][0], exercise, file)
    rows = []
    for (number, _), values in zip(lines[1:], reader, strict=False):
        if len(values) != len(header):
            raise SpecError(f"line {number}: {len(values)} values for {len(header)} columns",
                            file=file)
        angle = _number(values[angle_column], file, number, header[angle_column],
                        MAX_ANGLE_DEG, "°")
        points = {point: tuple(_number(values[axes[axis]], file, number, header[axes[axis]],
                                       MAX_COORDINATE_M, " m") for axis in ("x", "y"))
                  for point, axes in columns.items()}
        rows.append(Row(angle, points, number))
    if not rows:
        raise SpecError("the table has a header but no rows", file=file)
    return rows


def check_row(exercise, row: Row, tolerance: float) -> RowFindings:
    """Check one row against the link lengths and the exact assembly (tolerance in m)."""
    from ..errors import PlanmethodError
    from ..kinematics import solve
    from ..model import FRAME

    mechanism = exercise.mechanism
    given = dict(row.points)
    for point, xy in mechanism.links[FRAME].points.items():
        given.setdefault(point, xy)
    lengths = []
    for name, link in mechanism.links.items():
        present = [p for p in link.points if p in given]
        for i, first in enumerate(present):
            for second in present[i + 1:]:
                if name == FRAME and (first not in row.points or second not in row.points):
                    continue
                (x1, y1), (x2, y2) = given[first], given[second]
                lengths.append(LengthCheck(name, first, second, math.hypot(x2 - x1, y2 - y1),
                                           link.length(first, second)))
    positions = []
    branch = None
    error_text = None
    try:
        motion = solve(mechanism, row.angle, stage="position")
        branch = ", ".join(f"group {index + 1}: {b.reason}"
                           for index, b in sorted(motion.branches.items())) or None
        here = motion.at(0)
        for point, xy in row.points.items():
            exact = here.position(point)
            positions.append(PositionCheck(point, xy, (float(exact[0]), float(exact[1]))))
    except PlanmethodError as error:
        error_text = str(error)
    return RowFindings(row.angle, row.line, tolerance, tuple(lengths), tuple(positions), branch,
                       error_text)


def text_report(title: str, findings: list[RowFindings],
                numbers: Mapping[str, int] | None = None, crank: int = 1) -> str:
    """The findings as a person reads them: links by the course's numbers (``numbers``,
    :func:`planmethod.numbering.course_numbers`), the crank angle φ with the crank's number,
    points with the digits of their names as subscripts."""
    from ..vocabulary import link_text, numbered, point_text, shown_title

    lines = [f"{shown_title(title)}: {len(findings)} row(s) checked against the link lengths "
             "and the exact assembly"]
    for found in findings:
        verdict = "FLAGGED" if found.flagged else "ok"
        lines += ["", f"{numbered('φ', crank)} = {found.angle:g}° (line {found.line}): "
                      f"{verdict}"]
        lines.append(f"  lengths: {len(found.lengths)} checked, {len(found.violations)} "
                     f"off by more than {found.tolerance * 1000:g} mm")
        for check in found.violations:
            lines.append(f"    {link_text(check.link, numbers)}: |{point_text(check.first)}"
                         f"{point_text(check.second)}| = {check.given:.4g} m"
                         f", should be {check.expected:.4g} m ({check.error * 1000:+.1f} mm)")
        if found.assembly_error:
            lines.append(f"  no exact assembly at this angle: {found.assembly_error}")
        elif found.positions:
            lines.append(f"  points against the exact assembly ({found.branch}):")
            for check in found.positions:
                mark = "FLAGGED" if check.error > found.tolerance else "ok"
                lines.append(f"    {point_text(check.point):<4} given ({check.given[0]:>10.6f}, "
                             f"{check.given[1]:>10.6f})  exact ({check.exact[0]:>10.6f}, "
                             f"{check.exact[1]:>10.6f})  off {check.error * 1000:8.2f} mm  "
                             f"{mark}")
        if found.flagged_points:
            lines.append(f"  flagged: {', '.join(map(point_text, found.flagged_points))}")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    import json
    import sys

    from ..errors import SpecError, about
    from ..spec import load_exercise

    if not (math.isfinite(args.tolerance) and args.tolerance > 0):
        raise SpecError(f"--tolerance must be a positive number of mm, got {args.tolerance}")
    exercise = load_exercise(args.file)
    rows = read_coordinates(args.coordinates, exercise)
    findings = []
    for row in rows:   # an error at a row's angle is about that row of the table
        with about(args.coordinates, key=f"line {row.line}"):
            findings.append(check_row(exercise, row, args.tolerance / 1000.0))
    if args.json:
        json.dump({"title": exercise.mechanism.title, "tolerance_mm": args.tolerance,
                   "rows": [f.as_dict() for f in findings]}, sys.stdout, ensure_ascii=False,
                  indent=2, allow_nan=False)
        print()
    else:
        from ..numbering import course_numbers

        numbers = course_numbers(exercise.mechanism)
        print(text_report(exercise.mechanism.title, findings, numbers,
                          numbers[exercise.mechanism.drive.link]))
    return 1 if any(f.flagged for f in findings) else 0
