"""The ``planmethod`` command line.

Each subcommand lives in ``planmethod.commands.<name>`` (the studio's in
:mod:`planmethod.studio.command`) with ``add_arguments(parser)`` and ``run(args) -> int``;
heavy imports stay inside ``run`` so that start-up is quick. A command asks the application
layer (:mod:`planmethod.application`) for its work and prints what it
is given. Bad input prints one line ``planmethod: error: …`` naming the file and key, and
exits with status 2.

Everything a command prints — its help, argparse's own lines, its reports, its errors — is
in the run's language: ``--lang`` (before or after the command's name), else the ``[course]
language`` of the file it reads, else ``PLANMETHOD_LANG``, else English
(:func:`planmethod.application.language.run_language`). A language that cannot be spoken is
one line and exit status 2.

Examples
--------
>>> main(["solve", "exercises/no_such_file.toml"])
2
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import signal
import sys
import threading
import warnings
from typing import NoReturn

from .arguments import argparse_words, said
from .errors import LIMIT_WORDS, PlanmethodError, limit_words
from .words import Message, message, render, speaking

__all__ = ["COMMANDS", "main"]

#: subcommand → (module, one-line help)
COMMANDS: dict[str, tuple[str, Message]] = {
    "solve": ("planmethod.commands.solve",
              message("structural analysis, exact kinematics and the plans at one crank "
                      "angle")),
    "sweep": ("planmethod.commands.sweep",
              message("the full turn: curves of positions, v, a, ω, ε")),
    "variants": ("planmethod.commands.variants",
                 message("student variants of a template, with task sheets and answer keys")),
    "grade": ("planmethod.commands.grade",
              message("grade numeric answers and drawn plans against a key")),
    "export": ("planmethod.commands.export",
               message("answer keys to Gradescope, PrairieLearn, Moodle or a CSV gradebook")),
    "check": ("planmethod.commands.check",
              message("test a table of point coordinates against the links")),
    "study": ("planmethod.commands.study",
              message("a four-bar's reactions against G4, ω1 and Mc (the study of Jobborova "
                      "et al.)")),
    "workbook": ("planmethod.commands.workbook",
                 message("one offline HTML page: turn the crank, the plans redraw; practise "
                         "with the grader")),
    "animate": ("planmethod.commands.animate",
                message("the full turn of mechanism and plans as an animation (SVG, GIF or "
                        "MP4)")),
    "convert": ("planmethod.commands.convert",
                message("an exercise file in the other form: as drawn (global points) or in "
                        "link frames")),
    "studio": ("planmethod.studio.command",
               message("the instructor's studio: draw a mechanism in the browser, see its "
                       "plans live")),
}

EXIT_BAD_INPUT = 2

#: the arguments whose file a command reads first, in this order: the ``[course] language``
#: of that file (an exercise or a template) is the run's unless ``--lang`` is given
LANGUAGE_FILES = ("file", "template", "key")

#: a negative number as argparse should read it: a value, not an option (-1e300, -.5, -inf)
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$",
                              re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """argparse with the project's error line: one line, no usage block, exit 2; and negative
    numbers in any float notation read as values."""

    def __init__(self, *args, **keywords) -> None:
        super().__init__(*args, **keywords)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message_text: str) -> NoReturn:
        line = message("{program}: error: {problem} (see '{program} --help')",
                       program=self.prog, problem=message_text)
        self.exit(EXIT_BAD_INPUT, render(line) + "\n")


def _language_option(parser: argparse.ArgumentParser, *, default) -> None:
    parser.add_argument(
        "--lang", metavar=render(message("LANG", context="metavar")), default=default,
        help=said(message("the language of everything printed and written: en, ru or a "
                          "course's own (default: the file's [course] language, else "
                          "PLANMETHOD_LANG, else English)")))


def _parser() -> argparse.ArgumentParser:
    """The parser, its help in the language spoken (build it under :func:`argparse_words`)."""
    parser = _Parser(
        prog="planmethod",
        description=render(message("Graphical methods of planar-mechanism analysis (plans of "
                                   "velocities and accelerations, kinetostatics), checked "
                                   "against exact vectors.")),
        epilog=render(message("'planmethod COMMAND --help' shows a command's options.")))
    from . import __version__

    parser.add_argument("--version", action="version", version=f"planmethod {__version__}",
                        help=said(message("show program's version number and exit")))
    _language_option(parser, default=None)
    commands = parser.add_subparsers(dest="command", parser_class=_Parser,
                                     metavar=render(message("COMMAND", context="metavar")))
    commands.required = True
    for name, (module, summary) in COMMANDS.items():
        sub = commands.add_parser(name, help=said(summary), description=render(summary))
        importlib.import_module(module).add_arguments(sub)
        _language_option(sub, default=argparse.SUPPRESS)   # the one before the name stands
        sub.set_defaults(_module=module)
    return parser


def _option_given(argv: list[str]) -> str | None:
    """The value of ``--lang`` in ``argv`` (the last one), read before the parser is built:
    the help is made in that language."""
    found = None
    for index, argument in enumerate(argv):
        if argument == "--":
            break
        if argument == "--lang" and index + 1 < len(argv):
            found = argv[index + 1]
        elif argument.startswith("--lang="):
            found = argument.partition("=")[2]
    return found


def _refused(error: PlanmethodError) -> int:
    print(render(message("planmethod: error: {problem}", problem=str(error))), file=sys.stderr)
    return EXIT_BAD_INPUT


class _Terminated(BaseException):
    """SIGTERM, raised where the program is so that every temporary file is removed on the way
    out, as on Ctrl-C."""


def _on_terminate(_signum, _frame) -> NoReturn:
    raise _Terminated


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 bad input, 130 interrupted,
    143 terminated)."""
    from .application.language import run_language

    argv = sys.argv[1:] if argv is None else list(argv)
    try:   # the help and argparse's lines: in the language of --lang, else the environment's
        early = run_language(_option_given(argv), environment=os.environ)
    except PlanmethodError as error:
        return _refused(error)
    with speaking(early), argparse_words():
        try:
            args = _parser().parse_args(argv)
        except SystemExit as exit_:
            return int(exit_.code or 0)
    previous = None
    if threading.current_thread() is threading.main_thread():
        previous = signal.signal(signal.SIGTERM, _on_terminate)
    try:
        return _run(args)
    except _Terminated:
        with speaking(early):
            print(render(message("planmethod: terminated")), file=sys.stderr)
        return 143
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _run_language(args: argparse.Namespace) -> str:
    """The run's language: ``--lang``, else the ``[course] language`` of the file it reads
    first (:data:`LANGUAGE_FILES`), else ``PLANMETHOD_LANG``, else English."""
    from .application.language import run_language

    file = next((value for value in (getattr(args, name, None) for name in LANGUAGE_FILES)
                 if isinstance(value, str)), None)
    return run_language(getattr(args, "lang", None), file)


def _run(args: argparse.Namespace) -> int:
    try:
        language = _run_language(args)
    except PlanmethodError as error:
        return _refused(error)
    with speaking(language):
        return _run_command(args)


def _run_command(args: argparse.Namespace) -> int:
    try:
        with warnings.catch_warnings():
            # numbers that overflow are refused by name where they are made (spec limits);
            # numpy's warnings never reach the terminal as lines of source code
            warnings.simplefilter("ignore", RuntimeWarning)
            return int(importlib.import_module(args._module).run(args) or 0)
    except tuple(LIMIT_WORDS) as error:
        source = getattr(args, "file", None) or getattr(args, "key", None)
        where = (message("{source}: {problem}", source=source, problem=limit_words(error))
                 if source else limit_words(error))
        print(render(message("planmethod: error: {problem}", problem=where)), file=sys.stderr)
        return EXIT_BAD_INPUT
    except PlanmethodError as error:
        from .errors import StructureError

        source = getattr(args, "file", None)
        if isinstance(source, str):
            error.located(file=source, key="links" if isinstance(error, StructureError) else None)
        return _refused(error)
    except KeyboardInterrupt:
        print(render(message("planmethod: interrupted")), file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
