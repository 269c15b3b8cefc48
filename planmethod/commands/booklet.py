"""``planmethod booklet COURSE -o class.pdf``: the class's booklet to print, one A4 PDF
(:mod:`planmethod.application.booklet` says what is on its pages).

COURSE is a folder written by ``planmethod variants`` (or its ``keys.json``). The pages speak
``--lang``, else the course's ``[course] language``, else ``PLANMETHOD_LANG``, else English.
"""

from __future__ import annotations

import argparse

from ..arguments import said
from ..words import message, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("course", metavar=render(message("course", context="metavar")),
                        help=said(message("a folder written by `planmethod variants` (or its "
                                          "keys.json)")))
    parser.add_argument("-o", "--output", required=True,
                        metavar=render(message("FILE.pdf", context="metavar")),
                        help=said(message("the booklet to write (PDF, A4)")))


def run(args: argparse.Namespace) -> int:
    from ..application.booklet import course_of, make_booklet
    from ..application.language import chosen_language
    from ..application.tasks import Watch
    from ..grading.paper import sheet_pages
    from ..progress import Progress
    from ..words import plural
    from ..words.language import speaking
    from .output import say

    course = course_of(args.course)
    # the course's language, unless --lang says another (the command line speaks that one)
    language = (None if getattr(args, "lang", None) or course.language is None else
                chosen_language(None, course.language, file=course.source))
    with speaking(language):
        with Progress(sheet_pages(course.keys), render(message("booklet"))) as bar:
            booklet = make_booklet(course, watch=Watch(lambda *_: bar.advance()))
        booklet.write(args.output)
        say(message("Wrote {pages} to {file}: {students}; print it at 100 % (actual size), A4",
                    pages=plural("{count} page", "{count} pages", count=booklet.pages),
                    students=plural("{count} student", "{count} students",
                                    count=booklet.students), file=str(args.output)))
    return 0
