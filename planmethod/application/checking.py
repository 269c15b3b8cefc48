"""Check a table of point coordinates against the mechanism (``planmethod check FILE
COORDS.csv``).

Papers and students print tables of point coordinates per crank angle (Table 2 of Umbetkulov et
al., "Dynamic force analysis of a six-link planar mechanism").
Each row is checked two ways:

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

import csv
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from ..errors import SpecError
from ..words import Message, message, plural, render

__all__ = ["ANGLE_COLUMNS", "CheckResult", "LengthCheck", "PositionCheck", "Row",
           "RowFindings", "check_row", "check_table", "check_tolerance", "read_coordinates",
           "text_report"]

ANGLE_COLUMNS = ("angle", "phi", "phi1", "φ1", "φ")

#: the largest coordinates table read (bytes)
MAX_TABLE_BYTES = 50_000_000


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
    """What was found in one row: the lengths and positions checked, the assembly's branch
    of each group (why it was chosen), or why there is no exact assembly."""

    angle: float
    line: int
    tolerance: float
    lengths: tuple[LengthCheck, ...]
    positions: tuple[PositionCheck, ...]
    branches: tuple[Message, ...] = ()
    assembly_error: Message | str | None = None

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

    @property
    def branch(self) -> str | None:
        """The groups' branches in words (``group 1: sketch``), or None."""
        return ", ".join(render(branch) for branch in self.branches) or None

    def as_dict(self) -> dict:
        """The findings for the JSON answer (their words in the language spoken)."""
        return {"angle": self.angle, "line": self.line, "flagged": self.flagged,
                "flagged_points": list(self.flagged_points), "branch": self.branch,
                "assembly_error": (None if self.assembly_error is None
                                   else render(self.assembly_error)),
                "lengths": [{"link": c.link, "pair": f"{c.first}{c.second}", "given": c.given,
                             "expected": c.expected, "error": c.error,
                             "violated": abs(c.error) > self.tolerance} for c in self.lengths],
                "positions": [{"point": c.point, "given": list(c.given), "exact": list(c.exact),
                               "error": c.error, "flagged": c.error > self.tolerance}
                              for c in self.positions]}


def _number(text: str, file: str, line: int, column: str, limit: float, unit: str) -> float:
    """A cell's number, finite and at most ``limit`` in magnitude (the exercise file's limits
    for a crank angle and a coordinate), or a :class:`SpecError` naming its line and column."""
    try:
        value = float(text)
    except ValueError:
        raise SpecError(message("line {line}, column {column}: not a number: {text!r}",
                                line=line, column=column, text=text), file=file) from None
    if not math.isfinite(value):
        raise SpecError(message("line {line}, column {column}: must be finite, got {text}",
                                line=line, column=column, text=text), file=file)
    if abs(value) > limit:
        raise SpecError(message("line {line}, column {column}: must be within ±{limit:g}{unit}, "
                                "got {text}", line=line, column=column, limit=limit, unit=unit,
                                text=text.strip()[:40]), file=file)
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
    from ..grading.answers import refuse_twice
    from ..spec import did_you_mean

    refuse_twice([name if "_" in name else "" for name in header], _column_name, "column",
                 file=file, key=f"line {line}", places="columns",
                 compared="the axis compared ignoring case")   # words: grading
    lowered = [name.lower() for name in header]
    angle_column = next((lowered.index(name) for name in ANGLE_COLUMNS if name in lowered), None)
    if angle_column is None:
        raise SpecError(message("no crank-angle column (one of {names}) in the header "
                                "{header}", names=list(ANGLE_COLUMNS), header=str(header)),
                        file=file)
    known = {p for link in exercise.mechanism.links.values() for p in link.points}
    columns: dict[str, dict[str, int]] = {}
    for index, name in enumerate(header):
        if index == angle_column:
            continue
        axis, _, point = name.partition("_")
        if axis.lower() not in ("x", "y") or not point:
            raise SpecError(message("column {name!r}: expected x_P or y_P for a point P",
                                    name=name), file=file)
        if point not in known:
            raise SpecError(message("column {name!r}: unknown point '{point}'{suggestion}",
                                    name=name, point=point,
                                    suggestion=did_you_mean(point, known)), file=file)
        columns.setdefault(point, {})[axis.lower()] = index
    for point, axes in columns.items():
        if set(axes) != {"x", "y"}:
            raise SpecError(message("point {point} has only a {axis} column", point=point,
                                    axis=next(iter(axes))), file=file)
    return angle_column, columns


def read_coordinates(path: str | Path, exercise) -> list[Row]:
    """The rows of a coordinates CSV (see the module docstring).

    Raises
    ------
    SpecError
        For a missing file, a missing angle column, an unknown point, a lone x or y column, or
        a value that is not a finite number — naming the file, line and column.
    """
    from ..io import read_text_bounded
    from ..spec import MAX_ANGLE_DEG, MAX_COORDINATE_M

    path = Path(path)
    file = str(path)
    text = read_text_bounded(path, MAX_TABLE_BYTES)
    lines = [(number, line) for number, line in enumerate(text.splitlines(), start=1)
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise SpecError(message("no header and no rows"), file=file)
    reader = csv.reader([line for _, line in lines])
    header = [name.strip() for name in next(reader)]
    angle_column, columns = _columns(header, lines[0][0], exercise, file)
    rows = []
    for (number, _), values in zip(lines[1:], reader, strict=False):
        if len(values) != len(header):
            raise SpecError(message("line {line}: {values} values for {columns} columns",
                                    line=number, values=len(values), columns=len(header)),
                            file=file)
        angle = _number(values[angle_column], file, number, header[angle_column],
                        MAX_ANGLE_DEG, "°")
        points = {point: tuple(_number(values[axes[axis]], file, number, header[axes[axis]],
                                       MAX_COORDINATE_M, " m") for axis in ("x", "y"))
                  for point, axes in columns.items()}
        rows.append(Row(angle, points, number))
    if not rows:
        raise SpecError(message("the table has a header but no rows"), file=file)
    return rows


def _lengths(mechanism, row: Row) -> list[LengthCheck]:
    """Every two given points of one link against the link's length (the frame's points
    the row leaves out taken from the exercise, but not compared among themselves)."""
    from ..model import FRAME

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
    return lengths


def check_row(exercise, row: Row, tolerance: float) -> RowFindings:
    """Check one row against the link lengths and the exact assembly (tolerance in m)."""
    from ..errors import PlanmethodError
    from ..kinematics import solve
    from ..vocabulary import branch_reason_words

    lengths = _lengths(exercise.mechanism, row)
    positions = []
    branches: tuple[Message, ...] = ()
    error = None
    try:
        motion = solve(exercise.mechanism, row.angle, stage="position")
        branches = tuple(message("group {number}: {reason}", number=index + 1,
                                 reason=branch_reason_words(branch.reason))
                         for index, branch in sorted(motion.branches.items()))
        here = motion.at(0)
        for point, xy in row.points.items():
            exact = here.position(point)
            positions.append(PositionCheck(point, xy, (float(exact[0]), float(exact[1]))))
    except PlanmethodError as failure:
        error = str(failure)
    return RowFindings(row.angle, row.line, tolerance, tuple(lengths), tuple(positions),
                       branches, error)


@dataclass(frozen=True)
class CheckResult:
    """A table checked: the exercise's title, the tolerance (mm) and each row's findings."""

    title: str
    tolerance_mm: float
    rows: tuple[RowFindings, ...]

    @property
    def flagged(self) -> bool:
        """Whether any row is flagged."""
        return any(found.flagged for found in self.rows)

    def as_dict(self) -> dict:
        """The JSON answer of ``planmethod check --json``."""
        return {"title": self.title, "tolerance_mm": self.tolerance_mm,
                "rows": [found.as_dict() for found in self.rows]}


def check_tolerance(tolerance_mm: float) -> None:
    """Refuse a tolerance that is no positive number of mm (before any work)."""
    if not (math.isfinite(tolerance_mm) and tolerance_mm > 0):
        raise SpecError(message("--tolerance must be a positive number of mm, got "
                                "{tolerance}", tolerance=tolerance_mm))


def check_table(exercise, path: str, tolerance_mm: float) -> CheckResult:
    """Check every row of the coordinates table ``path`` against ``exercise`` (a point off
    by more than ``tolerance_mm`` is flagged); an error at a row's angle names its line.

    Raises
    ------
    SpecError
        For a tolerance that is no positive number, or a table that cannot be read.
    """
    from ..errors import about

    check_tolerance(tolerance_mm)
    rows = read_coordinates(path, exercise)
    findings = []
    for row in rows:   # an error at a row's angle is about that row of the table
        with about(path, key=f"line {row.line}"):
            findings.append(check_row(exercise, row, tolerance_mm / 1000.0))
    return CheckResult(exercise.mechanism.title, tolerance_mm, tuple(findings))


def text_report(title: str, findings: list[RowFindings],
                numbers: Mapping[str, int] | None = None, crank: int = 1) -> str:
    """The findings as a person reads them: links by the course's numbers (``numbers``,
    :func:`planmethod.numbering.course_numbers`), the crank angle φ with the crank's number,
    points with the digits of their names as subscripts; in the language spoken."""
    from ..vocabulary import numbered, shown_title

    lines = [render(plural("{title}: {count} row(s) checked against the link lengths and the "
                           "exact assembly", "{title}: {count} row(s) checked against the link "
                           "lengths and the exact assembly", count=len(findings),
                           title=shown_title(title)))]
    for found in findings:
        verdict = (message("FLAGGED", context="verdict") if found.flagged
                   else message("ok", context="verdict"))
        lines += ["", render(message("{phi} = {angle:g}° (line {line}): {verdict}",
                                     phi=numbered("φ", crank), angle=found.angle,
                                     line=found.line, verdict=verdict))]
        lines += _row_lines(found, numbers)
    return "\n".join(lines)


def _row_lines(found: RowFindings, numbers: Mapping[str, int] | None) -> list[str]:
    """One row's findings: its lengths, its points against the exact assembly, what is
    flagged."""
    from ..vocabulary import link_text, point_text

    said: list[tuple[str, Message]] = [("  ", message(
        "lengths: {checked} checked, {off} off by more than {tolerance:g} mm",
        checked=len(found.lengths), off=len(found.violations),
        tolerance=found.tolerance * 1000))]
    for check in found.violations:   # words: vocabulary (link_text)
        said.append(("    ", message(
            "{link}: |{segment}| = {given:.4g} m, should be {expected:.4g} m ({error:+.1f} mm)",
            link=link_text(check.link, numbers),
            segment=point_text(check.first) + point_text(check.second), given=check.given,
            expected=check.expected, error=check.error * 1000)))
    if found.assembly_error:
        said.append(("  ", message("no exact assembly at this angle: {error}",
                                   error=found.assembly_error)))
    elif found.positions:
        said.append(("  ", message("points against the exact assembly ({branch}):",
                                   branch=found.branch)))
        for check in found.positions:
            mark = (message("FLAGGED", context="verdict") if check.error > found.tolerance
                    else message("ok", context="verdict"))
            said.append(("    ", message(
                "{point:<4} given ({x:>10.6f}, {y:>10.6f})  exact ({exact_x:>10.6f}, "
                "{exact_y:>10.6f})  off {off:8.2f} mm  {mark}", point=point_text(check.point),
                x=check.given[0], y=check.given[1], exact_x=check.exact[0],
                exact_y=check.exact[1], off=check.error * 1000, mark=mark)))
    if found.flagged_points:
        said.append(("  ", message("flagged: {points}", points=[
            point_text(point) for point in found.flagged_points])))
    return [indent + render(line) for indent, line in said]
