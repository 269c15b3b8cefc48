"""Make the class's booklet to print: one A4 PDF of a course folder written by ``planmethod
variants``.

For each student, in the order of the keys: the task sheet, then one blank sheet per plan to
draw (velocity, acceleration) with the pole printed and named, the scale and its bar, a light
millimetre grid, four corner markers and a QR code — each page where the key's sheet geometry
puts it (:mod:`planmethod.grading.paper`), at its true size, fonts embedded. The pages' words
are in the language spoken (the course's, :func:`course_of`). Needs the ``paper`` extra
(CairoSVG, segno).

Examples
--------
>>> course = course_of("missing-course")
Traceback (most recent call last):
...
planmethod.errors.SpecError: missing-course: no such file
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..words import Message, message
from .tasks import Watch

__all__ = ["Booklet", "Course", "booklet_pages", "course_of", "make_booklet", "write_booklet"]

#: the packages the booklet needs (the ``paper`` extra)
NEEDS = ("cairosvg", "segno")


@dataclass(frozen=True)
class Course:
    """A course folder's keys, in the order of its bundle, each with its sheets checked; the
    bundle's file; the ``[course] language`` its exercise names (None if none)."""

    keys: tuple[Mapping[str, Any], ...]
    source: str
    language: Any = None


@dataclass(frozen=True)
class Booklet:
    """A class's booklet: the PDF, its pages and how many students it is for."""

    pdf: bytes
    pages: int
    students: int

    def write(self, path: str | Path) -> None:
        """Write the PDF to ``path`` (whole or not at all)."""
        write_booklet(path, self)


def _needs_paper() -> None:
    """Refuse in one line when the paper extra is missing."""
    import importlib.util

    from ..grading.paper import CourseError

    missing = [name for name in NEEDS if importlib.util.find_spec(name) is None]
    if missing:
        raise CourseError(message("the booklet needs {names}: pip install "
                                  "'planmethod[paper]'", names=missing))


def _page_refused(plan: str, student: str, found: int, page: int) -> Message:
    if plan == "velocity":
        return message("the velocity plan sheet of student {student} is on page {found}, the "
                       "booklet's page {page}: run `planmethod variants` again",
                       student=student, found=found, page=page)
    return message("the acceleration plan sheet of student {student} is on page {found}, the "
                   "booklet's page {page}: run `planmethod variants` again", student=student,
                   found=found, page=page)


def course_of(path: str | Path) -> Course:
    """The course in ``path`` (a folder written by ``planmethod variants``, or its
    ``keys.json``): its keys, each with its task page and sheets checked.

    Raises
    ------
    CourseError
        In one line, if the folder holds no keys, or a key records no booklet pages (written
        before booklets) or pages that are not the booklet's.
    """
    from ..grading.keys import load_keys
    from ..grading.paper import PLANS, CourseError, read_sheet
    from .language import course_language

    source = Path(path)
    keys_file = str(source / "keys.json" if source.is_dir() else source)
    keys = [key for student, key in load_keys(keys_file).items() if student != "*"]
    if not keys:
        raise CourseError(message("holds no keys"), file=keys_file)
    page = 1
    for key in keys:
        if key.get("task_page") != page:
            raise CourseError(message("the key of student {student} does not say on which "
                                      "page its task is (or not on page {page}): run "
                                      "`planmethod variants` again (the same seed draws the "
                                      "same variants)", student=str(key.get("student")),
                                      page=page), file=keys_file)
        page += 1
        for plan in PLANS:
            if plan not in key.get("plans", {}):
                continue
            sheet = read_sheet(key, plan, file=keys_file)
            if sheet.page != page:
                raise CourseError(_page_refused(plan, sheet.student, sheet.page, page),
                                  file=keys_file)
            _check_fits(key, sheet, keys_file)
            page += 1
    exercise = keys[0].get("exercise")
    return Course(tuple(keys), keys_file,
                  course_language(exercise) if isinstance(exercise, Mapping) else None)


def _check_fits(key: Mapping[str, Any], sheet, source: str) -> None:
    """Refuse a plan whose right points fall off the sheet's drawing area."""
    from ..grading.keys import key_numbers
    from ..grading.paper import CourseError, plan_to_page
    from ..render.plan_words import label_text

    left, top, right, bottom = sheet.drawing_mm
    for label, xy in key["plans"][sheet.plan]["points_mm"].items():
        x, y = plan_to_page(sheet.pole_mm, xy)
        if left <= x <= right and top <= y <= bottom:
            continue
        point = label_text(label, key_numbers(key))
        raise CourseError(
            message("the velocity plan of student {student} does not fit on an A4 sheet (its "
                    "point {point} falls off the drawing area): draw it at a smaller scale",
                    student=sheet.student, point=point) if sheet.plan == "velocity" else
            message("the acceleration plan of student {student} does not fit on an A4 sheet "
                    "(its point {point} falls off the drawing area): draw it at a smaller "
                    "scale", student=sheet.student, point=point), file=source)


def booklet_pages(keys: Sequence[Mapping[str, Any]], *, watch: Watch | None = None
                  ) -> list[str]:
    """Every page of the booklet as SVG (mm), in order: per student the task sheet, then the
    blank plan sheets; ``watch`` hears each page made (phase ``booklet``)."""
    from ..grading.keys import key_exercise
    from ..grading.paper import PLANS, read_sheet, sheet_pages
    from ..grading.sheets import paper_plan_sheet, paper_task_sheet
    from ..plans import draw_plans

    watch = watch or Watch()
    total = sheet_pages(keys)
    pages: list[str] = []
    for key in keys:
        plans = draw_plans(key_exercise(key), acceleration=False)
        pages.append(paper_task_sheet(key, plans, int(key["task_page"]), total))
        watch.step("booklet", len(pages), total)
        for plan in PLANS:
            if plan in key["plans"]:
                pages.append(paper_plan_sheet(key, read_sheet(key, plan), total))
                watch.step("booklet", len(pages), total)
    return pages


def make_booklet(course: Course, *, watch: Watch | None = None) -> Booklet:
    """The booklet of ``course``, its words in the language spoken.

    Raises
    ------
    CourseError
        If the ``paper`` extra is missing.
    """
    from ..render.pdf import pdf_pages
    from ..vocabulary import shown_title
    from ..words import render

    _needs_paper()
    pages = booklet_pages(course.keys, watch=watch)
    title = render(message("{title} — the class's booklet",
                           title=shown_title(str(course.keys[0].get("title", "")))))
    return Booklet(pdf_pages(pages, title=title), len(pages), len(course.keys))


def write_booklet(path: str | Path, booklet: Booklet) -> None:
    """Write ``booklet``'s PDF to ``path``: whole or not at all."""
    from ..io import output_set

    with output_set() as outputs:
        outputs.binary(path, booklet.pdf)
