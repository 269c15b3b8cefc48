"""The paper course's sheets as data: where everything is on a printed plan sheet, which page of
the class's booklet it is, and what its QR code says.

A blank plan sheet of the booklet (``planmethod booklet``) is an A4 page. Four ArUco markers
of one fixed dictionary (OpenCV's ``DICT_4X4_50``, ids 0–3) sit near its corners, a QR code
names the sheet, a light millimetre grid covers the drawing area, and the pole is printed on
it. Where each of these is, in millimetres from the page's top-left corner (x right, y down),
is part of the answer key (``sheets`` of each key in ``keys.json``, written by ``planmethod
variants``): the booklet draws each sheet from it, and ``grade --photo`` maps a photo back to
the plan's millimetres by it. The layout is computed once, here, from the key alone
(:func:`add_sheets`), so the same course always prints the same pages.

The QR code says ``PM1|course|student|plan|angle|check``: the course's id (a digest of the
run's keys), the student (percent-encoded), ``v`` or ``a``, the crank angle in degrees and a
check value — a digest of the other fields and of the variant's exercise, so that a sheet
printed from another course, another variant or an edited key is told apart.

Examples
--------
>>> code = SheetCode("3f9a2b1c", "001", "velocity", 45.0, "0c1d2e3f")
>>> code.text
'PM1|3f9a2b1c|001|v|45|0c1d2e3f'
>>> read_sheet_code(code.text) == code
True
>>> plan_to_page((105.0, 150.0), (10.0, 5.0))
(115.0, 145.0)
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any
from urllib.parse import quote, unquote

from ..errors import SpecError
from ..words import message
from .drawings import SubmissionError
from .sheet_area import DRAWING_MM, PLAN_MARGIN_MM

__all__ = ["A4_MM", "MARKER_BITS", "MARKER_CENTRES", "MARKER_DICTIONARY",
           "MARKER_MM", "PLANS", "QR_MM", "SCALE_BAR_MM", "CourseError", "Marker", "PhotoError",
           "Sheet", "SheetCode", "add_sheets", "check_value", "course_id", "key_digest",
           "page_to_plan", "plan_to_page", "read_sheet", "read_sheet_code", "sheet_pages"]

#: an A4 page, portrait (mm)
A4_MM = (210.0, 297.0)
#: the markers' dictionary, as OpenCV names it
MARKER_DICTIONARY = "DICT_4X4_50"
#: a marker's black square (mm): 6 × 6 cells of 2 mm, the 4 × 4 inner bits in a black border
MARKER_MM = 12.0
#: the markers' centres (mm), ids 0–3: top left, top right, bottom left, bottom right — their
#: outer edges 10 mm from the page's edges, inside what every printer prints
MARKER_CENTRES = ((16.0, 16.0), (194.0, 16.0), (16.0, 281.0), (194.0, 281.0))
#: the inner 4 × 4 bits of markers 0–3 of ``DICT_4X4_50``, row by row, 1 white (a test checks
#: them against OpenCV's dictionary): the booklet prints them without OpenCV
MARKER_BITS = {0: ("1011", "0101", "0011", "0010"), 1: ("0000", "1111", "1001", "1010"),
               2: ("0011", "0011", "0010", "1101"), 3: ("1001", "1001", "0100", "0110")}
#: the QR code's square (left, top, side; mm), its quiet zone inside
QR_MM = (150.0, 260.0, 28.0)
#: the scale bar: its left end (mm) and its length (mm)
SCALE_BAR_MM = ((30.0, 270.0), 50.0)
#: the plans drawn on paper, in the booklet's order, and their letters in the QR code
PLANS = ("velocity", "acceleration")
_PLAN_LETTERS = {"velocity": "v", "acceleration": "a"}
#: the QR code's first field: the format of what follows
QR_FORMAT = "PM1"
#: a sheet's format tag in keys.json
SHEET_FORMAT = "planmethod-sheet"


class CourseError(SpecError):
    """A course folder or key that the booklet cannot print from."""


class PhotoError(SubmissionError):
    """A photo of a sheet that cannot be graded: one line says why."""


@dataclass(frozen=True)
class SheetCode:
    """What a sheet's QR code says: the course, the student, the plan, the crank angle (deg)
    and the check value."""

    course: str
    student: str
    plan: str
    angle: float
    check: str

    @property
    def text(self) -> str:
        """The QR code's text."""
        return "|".join((QR_FORMAT, self.course, quote(self.student, safe=""),
                         _PLAN_LETTERS[self.plan], f"{self.angle:.10g}", self.check))


def read_sheet_code(text: str) -> SheetCode | None:
    """The fields of a QR code's text, or None if it is not a sheet's code."""
    parts = text.split("|")
    letters = {letter: plan for plan, letter in _PLAN_LETTERS.items()}
    if len(parts) != 6 or parts[0] != QR_FORMAT or parts[3] not in letters:
        return None
    try:
        angle = float(parts[4])
    except ValueError:
        return None
    if not math.isfinite(angle):
        return None
    return SheetCode(parts[1], unquote(parts[2]), letters[parts[3]], angle, parts[5])


def key_digest(key: Mapping[str, Any]) -> str:
    """A digest of what a variant is: its title, student, crank angle, scales and exercise
    tables (16 hexadecimal digits).

    >>> len(key_digest({"title": "T", "student": "1", "angle": 30.0, "exercise": {}}))
    16
    """
    what = [key.get(name) for name in ("title", "student", "angle", "scales", "exercise")]
    text = json.dumps(what, sort_keys=True, ensure_ascii=False, allow_nan=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def course_id(keys: Sequence[Mapping[str, Any]]) -> str:
    """The course's id: a digest of its keys' digests (8 hexadecimal digits)."""
    text = " ".join(key_digest(key) for key in keys)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:8]


def check_value(course: str, key: Mapping[str, Any], plan: str) -> str:
    """The check value of a sheet's code: a digest of the course, the variant and the plan."""
    text = "|".join((course, str(key.get("student")), plan, key_digest(key)))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:8]


def plan_to_page(pole: Sequence[float], xy: Sequence[float]) -> tuple[float, float]:
    """A plan's point (mm from the pole, y up) on the page (mm from the top-left corner, y
    down)."""
    return (float(pole[0]) + float(xy[0]), float(pole[1]) - float(xy[1]))


def page_to_plan(pole: Sequence[float], xy: Sequence[float]) -> tuple[float, float]:
    """A point of the page (mm, y down) as a plan's point (mm from the pole, y up)."""
    return (float(xy[0]) - float(pole[0]), float(pole[1]) - float(xy[1]))


def _pole(entry: Mapping[str, Any]) -> tuple[float, float]:
    """Where the pole goes (page mm): the drawing area's centre on whole millimetres, moved
    only as far as the plan's points need to keep ``PLAN_MARGIN_MM`` from its edges (so the
    pole's place tells little of the answer)."""
    left, top, right, bottom = DRAWING_MM
    xs = [float(x) for x, _ in entry["points_mm"].values()] + [0.0]
    ys = [float(y) for _, y in entry["points_mm"].values()] + [0.0]
    centre = (round((left + right) / 2), round((top + bottom) / 2))

    def placed(middle: float, low: float, high: float, lowest: float, highest: float) -> float:
        # the pole's coordinate p with low + margin <= p + lowest and p + highest <= high - margin
        least, most = low + PLAN_MARGIN_MM - lowest, high - PLAN_MARGIN_MM - highest
        if least > most:                       # it cannot fit: centre the plan
            return float(round((least + most) / 2))
        return float(min(max(middle, math.ceil(least)), math.floor(most)))

    x = placed(centre[0], left, right, min(xs), max(xs))
    # page y runs down: a plan's y up is the page's −y
    y = placed(centre[1], top, bottom, -max(ys), -min(ys))
    return (x, y)


def _geometry(key: Mapping[str, Any], plan: str, page: int, course: str) -> dict[str, Any]:
    entry = key["plans"][plan]
    code = SheetCode(course, str(key.get("student")), plan, float(key.get("angle", 0.0)),
                     check_value(course, key, plan))
    return {
        "format": SHEET_FORMAT, "page": page, "page_mm": list(A4_MM),
        "markers": {"dictionary": MARKER_DICTIONARY, "size_mm": MARKER_MM,
                    "centres_mm": {str(number): list(centre)
                                   for number, centre in enumerate(MARKER_CENTRES)}},
        "drawing_mm": list(DRAWING_MM), "pole": entry["pole"], "pole_mm": list(_pole(entry)),
        "scale": entry["scale"], "unit": entry["unit"],
        "scale_bar_mm": [list(SCALE_BAR_MM[0]), SCALE_BAR_MM[1]],
        "qr_mm": list(QR_MM), "qr": code.text,
    }


def add_sheets(keys: Sequence[dict[str, Any]]) -> str:
    """Give each key its booklet pages: ``task_page``, and ``sheets`` with each plan's sheet
    geometry (:data:`PLANS` that the key has), in the keys' order — the task sheet, then one
    sheet per plan. Returns the course's id (:func:`course_id`), which the sheets' codes name.

    >>> from planmethod.grading.keys import build_key
    >>> from planmethod.grading.templates import draw_variant, load_template
    >>> key = build_key(draw_variant(load_template("exercises/templates/slider_crank.toml")))
    >>> course = add_sheets([key])
    >>> key["task_page"], key["sheets"]["velocity"]["page"], key["sheets"]["velocity"]["pole"]
    (1, 2, 'p')
    """
    course = course_id(keys)
    page = 1
    for key in keys:
        key["task_page"] = page
        page += 1
        sheets = {}
        for plan in PLANS:
            if plan in key.get("plans", {}):
                sheets[plan] = _geometry(key, plan, page, course)
                page += 1
        key["sheets"] = sheets
    return course


def sheet_pages(keys: Sequence[Mapping[str, Any]]) -> int:
    """How many pages the booklet of ``keys`` has."""
    return sum(1 + len(key.get("sheets", {})) for key in keys)


# -- reading a key's sheet --------------------------------------------------------------------
@dataclass(frozen=True)
class Marker:
    """A marker of a sheet: its id and its centre (page mm)."""

    number: int
    centre: tuple[float, float]


@dataclass(frozen=True)
class Sheet:
    """A plan sheet as its key records it (page mm from the top-left corner, y down)."""

    student: str
    plan: str
    page: int
    page_mm: tuple[float, float]
    markers: tuple[Marker, ...]
    marker_mm: float
    drawing_mm: tuple[float, float, float, float]
    pole: str
    pole_mm: tuple[float, float]
    scale: float
    unit: str
    scale_bar_mm: tuple[tuple[float, float], float]
    qr_mm: tuple[float, float, float]
    code: SheetCode

    def corners(self, number: int) -> list[tuple[float, float]]:
        """The four corners (page mm) of marker ``number`` in OpenCV's order: top left, top
        right, bottom right, bottom left."""
        marker = next(marker for marker in self.markers if marker.number == number)
        x, y = marker.centre
        half = self.marker_mm / 2
        return [(x - half, y - half), (x + half, y - half), (x + half, y + half),
                (x - half, y + half)]


def _number(value: Any, where: str, file: str | None, *, low: float = 0.0,
            high: float = 2000.0) -> float:
    if (isinstance(value, bool) or not isinstance(value, int | float)
            or not math.isfinite(value) or not low <= value <= high):
        raise CourseError(message("must be a number in {low:g}…{high:g} (mm), got {value}",
                                  low=low, high=high, value=repr(value)[:40]),
                          file=file, key=where)
    return float(value)


def _pair(value: Any, where: str, file: str | None) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise CourseError(message("must be [x, y] in mm, got {value}", value=repr(value)[:40]),
                          file=file, key=where)
    return (_number(value[0], where, file), _number(value[1], where, file))


def read_sheet(key: Mapping[str, Any], plan: str, *, file: str | None = None) -> Sheet:
    """A key's sheet of ``plan``, checked (a key is a file a person may have edited); an error
    names the sheet's key as the file has it (``keys[3].sheets.velocity.pole_mm`` in a
    bundle, ``sheets.velocity.pole_mm`` in a key file of its own).

    Raises
    ------
    CourseError
        If the key has no sheets (written before booklets: run variants again) or a sheet's
        geometry is not what variants writes.

    Examples
    --------
    >>> try:
    ...     read_sheet({"student": "001", "sheets": {"velocity": {}}}, "velocity")
    ... except CourseError as error:
    ...     print(error.key)
    sheets.velocity
    """
    student = str(key.get("student"))
    place = getattr(key, "place", "")
    where = f"{place}.sheets.{plan}" if place else f"sheets.{plan}"
    sheets = key.get("sheets")
    if not isinstance(sheets, Mapping):
        raise CourseError(message("the key of student {student} records no sheets: it was "
                                  "written before booklets; run `planmethod variants` again "
                                  "(the same seed draws the same variants)", student=student),
                          file=file)
    data = sheets.get(plan)
    if not isinstance(data, Mapping) or data.get("format") != SHEET_FORMAT:
        raise CourseError(message("is not a sheet that variants writes (format {format})",
                                  format=SHEET_FORMAT), file=file, key=where)
    page = data.get("page")
    if isinstance(page, bool) or not isinstance(page, int) or not 1 <= page <= 1_000_000:
        raise CourseError(message("must be a page number, got {value}", value=repr(page)[:40]),
                          file=file, key=f"{where}.page")
    size, markers = _markers(data.get("markers"), f"{where}.markers", file)
    scale = data.get("scale")
    if (isinstance(scale, bool) or not isinstance(scale, int | float)
            or not (math.isfinite(scale) and scale > 0)):
        raise CourseError(message("must be a positive number, got {value}",
                                  value=repr(scale)[:40]), file=file, key=f"{where}.scale")
    code = read_sheet_code(str(data.get("qr", "")))
    if code is None or code.student != student or code.plan != plan:
        raise CourseError(message("is not this sheet's code"), file=file, key=f"{where}.qr")
    return Sheet(student, plan, page, _pair(data.get("page_mm"), f"{where}.page_mm", file),
                 markers, size, _places(data, where, file, "drawing_mm"),
                 str(data.get("pole", "")), _pair(data.get("pole_mm"), f"{where}.pole_mm", file),
                 float(scale), str(data.get("unit", "")), _scale_bar(data, where, file),
                 _places(data, where, file, "qr_mm"), code)


def _markers(markers: Any, where: str, file: str | None) -> tuple[float, tuple[Marker, ...]]:
    """A sheet's ``markers``: their size (mm) and the four markers."""
    centres = markers.get("centres_mm") if isinstance(markers, Mapping) else None
    if (not isinstance(markers, Mapping) or markers.get("dictionary") != MARKER_DICTIONARY
            or not isinstance(centres, Mapping) or sorted(centres) != ["0", "1", "2", "3"]):
        raise CourseError(message("must give the centres of markers 0–3 of {dictionary}",
                                  dictionary=MARKER_DICTIONARY), file=file, key=where)
    size = _number(markers.get("size_mm"), f"{where}.size_mm", file, low=1.0, high=100.0)
    return size, tuple(Marker(int(number), _pair(centre, f"{where}.centres_mm.{number}", file))
                       for number, centre in sorted(centres.items()))


def _places(data: Mapping[str, Any], where: str, file: str | None, name: str
            ) -> tuple[float, ...]:
    """A sheet's ``drawing_mm`` (left, top, right, bottom) or ``qr_mm`` (left, top, side)."""
    value = data.get(name)
    count = 4 if name == "drawing_mm" else 3
    if not isinstance(value, list | tuple) or len(value) != count:
        said = (message("must be [left, top, right, bottom] in mm") if count == 4 else
                message("must be [left, top, side] in mm"))
        raise CourseError(said, file=file, key=f"{where}.{name}")
    return tuple(_number(number, f"{where}.{name}", file) for number in value)


def _scale_bar(data: Mapping[str, Any], where: str, file: str | None
               ) -> tuple[tuple[float, float], float]:
    """A sheet's scale bar: its left end (mm) and its length (mm)."""
    bar = data.get("scale_bar_mm")
    if not isinstance(bar, list | tuple) or len(bar) != 2:
        raise CourseError(message("must be [[x, y], length] in mm"), file=file,
                          key=f"{where}.scale_bar_mm")
    return (_pair(bar[0], f"{where}.scale_bar_mm", file),
            _number(bar[1], f"{where}.scale_bar_mm", file, low=1.0))
