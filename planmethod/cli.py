"""The ``planmethod`` command line.

Each subcommand lives in ``planmethod.commands.<name>`` with ``add_arguments(parser)`` and
``run(args) -> int``; heavy imports stay inside ``run`` so that start-up is quick. Bad input
prints one line ``planmethod: error: …`` naming the file and key, and exits with status 2.

Examples
--------
>>> main(["solve", "exercises/no_such_file.toml"])
2
"""

from __future__ import annotations

import argparse
import importlib
import re
import signal
import sys
import threading
import warnings
from typing import NoReturn

from .errors import PlanmethodError

__all__ = ["COMMANDS", "main"]

#: subcommand → (module, one-line help)
COMMANDS: dict[str, tuple[str, str]] = {
    "solve": ("planmethod.commands.solve",
              "structural analysis, exact kinematics and the plans at one crank angle"),
    "sweep": ("planmethod.commands.sweep", "the full turn: curves of positions, v, a, ω, ε"),
    "variants": ("planmethod.commands.variants",
                 "student variants of a template, with task sheets and answer keys"),
    "booklet": ("planmethod.commands.booklet",
                "the class's booklet to print: task sheets and plan sheets, one A4 PDF"),
    "grade": ("planmethod.commands.grade",
              "grade numeric answers and drawn plans (files or phone photos) against a key"),
    "export": ("planmethod.commands.export",
               "answer keys to Gradescope, PrairieLearn, Moodle or a CSV gradebook"),
    "check": ("planmethod.commands.check", "test a table of point coordinates against the links"),
    "study": ("planmethod.commands.study",
              "a four-bar's reactions against G4, ω1 and Mc (the study of Jobborova et al.)"),
    "workbook": ("planmethod.commands.workbook",
                 "one offline HTML page: turn the crank, the plans redraw; practise with the "
                 "grader"),
    "animate": ("planmethod.commands.animate",
                "the full turn of mechanism and plans as an animation (SVG, GIF or MP4)"),
    "convert": ("planmethod.commands.convert",
                "an exercise file in the other form: as drawn (global points) or in link "
                "frames"),
    "studio": ("planmethod.commands.studio",
               "the instructor's studio: draw a mechanism in the browser, see its plans live"),
}

EXIT_BAD_INPUT = 2

#: a negative number as argparse should read it: a value, not an option (-1e300, -.5, -inf)
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$",
                              re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """argparse with the project's error line: one line, no usage block, exit 2; and negative
    numbers in any float notation read as values."""

    def __init__(self, *args, **keywords) -> None:
        super().__init__(*args, **keywords)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} "
                                  f"(see '{self.prog} --help')\n")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="planmethod",
        description="Graphical methods of planar-mechanism analysis (plans of velocities and "
                    "accelerations, kinetostatics), checked against exact vectors.",
        epilog="'planmethod COMMAND --help' shows a command's options.")
    from . import __version__

    parser.add_argument("--version", action="version", version=f"planmethod {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND",
                                     parser_class=_Parser)
    commands.required = True
    for name, (module, summary) in COMMANDS.items():
        sub = commands.add_parser(name, help=summary, description=summary)
        importlib.import_module(module).add_arguments(sub)
        sub.set_defaults(_module=module)
    return parser


class _Terminated(BaseException):
    """SIGTERM, raised where the program is so that every temporary file is removed on the way
    out, as on Ctrl-C."""


def _on_terminate(_signum, _frame) -> NoReturn:
    raise _Terminated


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 bad input, 130 interrupted,
    143 terminated)."""
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:
        return int(exit_.code or 0)
    previous = None
    if threading.current_thread() is threading.main_thread():
        previous = signal.signal(signal.SIGTERM, _on_terminate)
    try:
        return _run(args)
    except _Terminated:
        print("planmethod: terminated", file=sys.stderr)
        return 143
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _run(args: argparse.Namespace) -> int:
    try:
        with warnings.catch_warnings():
            # numbers that overflow are refused by name where they are made (spec limits);
            # numpy's warnings never reach the terminal as lines of source code
            warnings.simplefilter("ignore", RuntimeWarning)
            return int(importlib.import_module(args._module).run(args) or 0)
    except (OverflowError, RecursionError, MemoryError) as error:
        what = {OverflowError: "a number is too large to compute with",
                RecursionError: "the input is nested too deeply",
                MemoryError: "the input asks for more memory than there is"}[type(error)]
        source = getattr(args, "file", None) or getattr(args, "key", None)
        print(f"planmethod: error: {source + ': ' if source else ''}{what}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except PlanmethodError as error:
        from .errors import StructureError

        source = getattr(args, "file", None)
        if isinstance(source, str):
            error.located(file=source, key="links" if isinstance(error, StructureError) else None)
        print(f"planmethod: error: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("planmethod: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
