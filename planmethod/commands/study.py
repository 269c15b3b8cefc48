"""``planmethod study FILE``: the parameter study of a four-bar's reactions of M. A. Jobborova,
M. O'. Xakimova and Sh. A. Kulturayeva, "Study of the load on kinematic pairs of a four-bar linkage
mechanism".

The rocker weight G4, the crank speed ω1 and the resisting moment Mc on the rocker are stepped
one at a time over their ranges (default: the paper's 20…100 N, 10…50 rad/s, 80…160 N·m, step
20, 10, 20) around the base case of the exercise file (or ``--base-*``); for each value the full
turn is solved and the largest reaction of each pair is tabulated; the paper's two conclusions
are checked against the numbers. ``--plot`` draws the table, ``--csv`` writes it
(:mod:`planmethod.application.studying`).
"""

from __future__ import annotations

import argparse
import math

from ..arguments import said
from ..words import message, render


def _grid_values(text: str) -> tuple[float, ...]:
    """``20:100:20`` (first:last:step, inclusive) or ``20,40,60``: the values, at most
    :data:`~planmethod.application.studying.MAX_GRID` of them, or ``ValueError``."""
    from ..application.studying import MAX_GRID

    if ":" in text:
        first, last, step = (float(part) for part in text.split(":"))
        if not (step > 0 and last >= first and math.isfinite(last - first)):
            raise ValueError
        count = round((last - first) / step)
        if count + 1 > MAX_GRID:
            raise argparse.ArgumentTypeError(render(message(
                "{text!r} gives {count:.3g} values; at most {limit} per parameter", text=text,
                count=count + 1, limit=MAX_GRID)))
        return tuple(first + step * i for i in range(count + 1))
    values = tuple(float(part) for part in text.split(",")[:MAX_GRID + 1])
    if len(values) > MAX_GRID:
        raise argparse.ArgumentTypeError(render(message(
            "more than {limit} values in {text!r}", limit=MAX_GRID, text=text[:40])))
    return values


def _range(text: str, limit: float = math.inf, unit: str = "") -> tuple[float, ...]:
    """``20:100:20`` (first:last:step, inclusive) or ``20,40,60``; each value finite and at
    most ``limit`` in magnitude."""
    try:
        values = _grid_values(text)
    except ValueError:
        raise argparse.ArgumentTypeError(render(message(
            "expected first:last:step or a comma list of numbers, got {text!r}",
            text=text))) from None
    if not values or any(not math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(render(message("expected finite numbers, got "
                                                        "{text!r}", text=text)))
    largest = max(values, key=abs)
    if abs(largest) > limit:
        raise argparse.ArgumentTypeError(render(message(
            "{largest:g} is beyond the limit: at most {limit:g} {unit}in magnitude (as in an "
            "exercise file)", largest=largest, limit=limit, unit=unit)))
    return values


def _within(limit_name: str, unit: str, *, grid: bool):
    """An argparse type: a range (``grid``) or one number, at most the exercise file's limit
    ``limit_name`` (:mod:`planmethod.spec`) in magnitude — the same table as the file's."""
    def parse(text: str):
        from .. import spec

        limit = getattr(spec, limit_name)
        if grid:
            return _range(text, limit, unit)
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(render(message(
                "expected a number, got {text!r}", text=text))) from None
        if not math.isfinite(value) or abs(value) > limit:
            raise argparse.ArgumentTypeError(render(message(
                "must be a finite number at most {limit:g} {unit}in magnitude (as in an "
                "exercise file), got {text!r}", limit=limit, unit=unit, text=text)))
        return value
    parse.__name__ = "number" if not grid else "range"
    return parse


def add_arguments(parser: argparse.ArgumentParser) -> None:
    newtons = render(message("N", context="metavar"))
    speed = render(message("RAD/S", context="metavar"))
    moment = render(message("N·M", context="metavar"))
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(message("exercise file ({format}) of the four-bar (base case)",
                                          format="TOML")))
    parser.add_argument("--rocker", metavar=render(message("LINK", context="metavar")),
                        help=said(message("the link carrying the resisting moment (default: "
                                          "the link of the first [[load]] moment)")))
    parser.add_argument("--weights", type=_within("MAX_MAGNITUDE", "N ", grid=True),
                        default="20:100:20", metavar=newtons,
                        help=said(message("rocker weights G4, N (default 20:100:20)")))
    parser.add_argument("--omegas", type=_within("MAX_OMEGA", "rad/s ", grid=True),
                        default="10:50:10", metavar=speed,
                        help=said(message("crank speeds ω1, rad/s (default 10:50:10)")))
    parser.add_argument("--moments", type=_within("MAX_MAGNITUDE", "N·m ", grid=True),
                        default="80:160:20", metavar=moment,
                        help=said(message("resisting moments Mc, N·m (default 80:160:20)")))
    parser.add_argument("--base-weight", type=_within("MAX_MAGNITUDE", "N ", grid=False),
                        metavar=newtons,
                        help=said(message("base rocker weight (default: the file's)")))
    parser.add_argument("--base-omega", type=_within("MAX_OMEGA", "rad/s ", grid=False),
                        metavar=speed,
                        help=said(message("base crank speed (default: the file's)")))
    parser.add_argument("--base-moment", type=_within("MAX_MAGNITUDE", "N·m ", grid=False),
                        metavar=moment,
                        help=said(message("base resisting moment (default: the file's)")))
    parser.add_argument("--step", type=float, default=2.0,
                        metavar=render(message("DEG", context="metavar")),
                        help=said(message("crank-angle step of each full turn (default 2)")))
    file = render(message("FILE", context="metavar"))
    parser.add_argument("--csv", metavar=file, help=said(message("write the table as CSV")))
    parser.add_argument("--plot", metavar=file,
                        help=said(message("write the plots (PNG/SVG/PDF)")))


def run(args: argparse.Namespace) -> int:
    from ..application.studying import StudyRequest, check_study, study
    from ..spec import load_exercise
    from .output import say, wrote

    request = StudyRequest(weights=args.weights, omegas=args.omegas, moments=args.moments,
                           base_weight=args.base_weight, base_omega=args.base_omega,
                           base_moment=args.base_moment, rocker=args.rocker, step=args.step,
                           csv=args.csv, plot=args.plot)
    check_study(request)   # before any work
    done = study(load_exercise(args.file), request)
    say(done.table)
    wrote(done.written)
    return 0
