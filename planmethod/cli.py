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
import sys

from .errors import PlanmethodError

__all__ = ["COMMANDS", "main"]

#: subcommand → (module, one-line help)
COMMANDS: dict[str, tuple[str, str]] = {
    "solve": ("planmethod.commands.solve",
              "structural analysis, exact kinematics and the plans at one crank angle"),
    "sweep": ("planmethod.commands.sweep", "the full turn: curves of positions, v, a, ω, ε"),
    "variants": ("planmethod.commands.variants",
                 "student variants of a template, with task sheets and answer keys"),
    "grade": ("planmethod.commands.grade", "grade numeric answers and drawn plans against a key"),
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
}

EXIT_BAD_INPUT = 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="planmethod",
        description="Graphical methods of planar-mechanism analysis (plans of velocities and "
                    "accelerations, kinetostatics), checked against exact vectors.",
        epilog="'planmethod COMMAND --help' shows a command's options.")
    from . import __version__

    parser.add_argument("--version", action="version", version=f"planmethod {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")
    commands.required = True
    for name, (module, summary) in COMMANDS.items():
        sub = commands.add_parser(name, help=summary, description=summary)
        importlib.import_module(module).add_arguments(sub)
        sub.set_defaults(_module=module)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 bad input)."""
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:
        return int(exit_.code or 0)
    try:
        return int(importlib.import_module(args._module).run(args) or 0)
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
