"""``planmethod booklet COURSE -o class.pdf``: the class's booklet to print, one A4 PDF.

COURSE is a folder written by ``planmethod variants`` (or its ``keys.json``). For each student,
in the order of the keys: the task sheet, then one blank sheet per plan to draw (velocity,
acceleration) with the pole printed and named, the scale and its bar, a light millimetre grid,
four corner markers and a QR code — each page where the key's sheet geometry puts it
(:mod:`planmethod.grading.paper`), at its true size, fonts embedded. ``--lang`` prints the
pages' words in a course language. Needs the ``paper`` extra (CairoSVG, segno).
"""

from __future__ import annotations

import argparse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("course", help="a folder written by `planmethod variants` (or its "
                                       "keys.json)")
    parser.add_argument("-o", "--output", required=True, metavar="FILE.pdf",
                        help="the booklet to write (PDF, A4)")
    parser.add_argument("--lang", metavar="LANG",
                        help="the language of the pages' words (en, ru, or a course's own "
                             "catalogue); default: PLANMETHOD_LANG, else English")


def _needs_paper() -> None:
    """Refuse in one line when the paper extra is missing."""
    import importlib.util

    from ..grading.paper import CourseError
    from ..words import message

    missing = [name for name in ("cairosvg", "segno") if importlib.util.find_spec(name) is None]
    if missing:
        raise CourseError(message("the booklet needs {names}: pip install "
                                  "'planmethod[paper]'", names=", ".join(missing)))


def course_keys(path: str) -> list[dict]:
    """The keys of a course, in the order of its bundle, each with its sheets checked."""
    from pathlib import Path

    from ..grading.keys import load_keys
    from ..grading.paper import PLANS, CourseError, read_sheet
    from ..words import message

    source = Path(path)
    keys_file = source / "keys.json" if source.is_dir() else source
    keys = [key for student, key in load_keys(keys_file).items() if student != "*"]
    if not keys:
        raise CourseError(message("holds no keys"), file=str(keys_file))
    page = 1
    for key in keys:
        if key.get("task_page") != page:
            raise CourseError(message("the key of student {student} does not say on which "
                                      "page its task is (or not on page {page}): run "
                                      "`planmethod variants` again (the same seed draws the "
                                      "same variants)", student=str(key.get("student")),
                                      page=page), file=str(keys_file))
        page += 1
        for plan in PLANS:
            if plan not in key.get("plans", {}):
                continue
            sheet = read_sheet(key, plan, file=str(keys_file))
            if sheet.page != page:
                raise CourseError(message("the {plan} sheet of student {student} is on page "
                                          "{found}, the booklet's page {page}: run `planmethod "
                                          "variants` again", plan=plan, student=sheet.student,
                                          found=sheet.page, page=page), file=str(keys_file))
            _check_fits(key, sheet, str(keys_file))
            page += 1
    return keys


def _check_fits(key, sheet, source: str) -> None:
    """Refuse a plan whose right points fall off the sheet's drawing area."""
    from ..grading.paper import CourseError, plan_to_page
    from ..words import message

    left, top, right, bottom = sheet.drawing_mm
    for label, xy in key["plans"][sheet.plan]["points_mm"].items():
        x, y = plan_to_page(sheet.pole_mm, xy)
        if not (left <= x <= right and top <= y <= bottom):
            raise CourseError(message("the {plan} plan of student {student} does not fit on "
                                      "an A4 sheet (its point {point} falls off the drawing "
                                      "area): draw it at a smaller scale", plan=sheet.plan,
                                      student=sheet.student, point=label), file=source)


def booklet_pages(keys: list[dict], *, progress: bool | None = None) -> list[str]:
    """Every page of the booklet as SVG (mm), in order: per student the task sheet, then the
    blank plan sheets."""
    from ..grading.keys import key_exercise
    from ..grading.paper import PLANS, read_sheet, sheet_pages
    from ..grading.sheets import paper_plan_sheet, paper_task_sheet
    from ..plans import draw_plans
    from ..progress import Progress

    total = sheet_pages(keys)
    pages = []
    with Progress(total, "booklet", enabled=progress) as bar:
        for key in keys:
            plans = draw_plans(key_exercise(key), acceleration=False)
            pages.append(paper_task_sheet(key, plans, int(key["task_page"]), total))
            bar.advance()
            for plan in PLANS:
                if plan in key["plans"]:
                    pages.append(paper_plan_sheet(key, read_sheet(key, plan), total))
                    bar.advance()
    return pages


def run(args: argparse.Namespace) -> int:
    from ..errors import SpecError
    from ..io import output_set
    from ..words import message, plural, render
    from ..words.language import choose, problem, speaking

    language = choose(args.lang, None)
    reason = problem(language)
    if reason is not None:
        raise SpecError(render(reason), key="option --lang")
    _needs_paper()
    with speaking(language):
        keys = course_keys(args.course)
        pages = booklet_pages(keys)
        from ..render.pdf import pdf_pages

        title = render(message("{title} — the class's booklet",
                               title=str(keys[0].get("title", ""))))
        pdf = pdf_pages(pages, title=title)
        with output_set() as outputs:
            outputs.binary(args.output, pdf)
        print(render(message("Wrote {pages} to {file}: {students}; print it at 100 % "
                             "(actual size), A4",
                             pages=plural("{count} page", "{count} pages", count=len(pages)),
                             students=plural("{count} student", "{count} students",
                                             count=len(keys)),
                             file=str(args.output))))
    return 0
