"""``planmethod variants TEMPLATE``: one variant per student, with task sheets and answer keys
(:mod:`planmethod.application.variants` says what a run writes).

Everything is computed before anything is written, and the run is written whole or not at all:
into a private folder inside ``--out``, whose entries are moved into place only when every file
is written. ``--force`` replaces an earlier run only when everything in ``--out`` is what that
run's manifest lists, unchanged (no other file, no symbolic link, no edited file); its entries
are moved aside when the new run is in place and only then removed, file by file, each checked
again against the manifest.
"""
from __future__ import annotations

import argparse

from ..application.variants import MAX_VARIANTS
from ..arguments import said
from ..words import message, plural, render


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("template", metavar=render(message("template", context="metavar")),
                        help=said(message("exercise template ({format} with ranges, choices, "
                                          "expressions) or a plain exercise file",
                                          format="TOML")))
    parser.add_argument("--count", type=int, metavar=render(message("N", context="metavar")),
                        help=said(message("number of variants (students 001…N, at most "
                                          "{limit}); default: the roster's size, or 1",
                                          limit=MAX_VARIANTS)))
    parser.add_argument("--seed", type=_whole_number, default=0,
                        metavar=render(message("SEED", context="metavar")),
                        help=said(message("random seed of the draw (default 0): the same "
                                          "seed, template and student always give the same "
                                          "variant")))
    parser.add_argument("--students", metavar=render(message("ROSTER", context="metavar")),
                        help=said(message("roster CSV (a student/id/email column, or one id "
                                          "per line)")))
    parser.add_argument("--out", required=True,
                        metavar=render(message("DIR", context="metavar")),
                        help=said(message("output folder")))
    parser.add_argument("--no-sheets", action="store_true",
                        help=said(message("write keys only (no SVG task and plan sheets)")))
    parser.add_argument("--force", action="store_true",
                        help=said(message("replace an earlier variants run in --out: only "
                                          "when everything there is what that run's "
                                          "manifest.json lists, unchanged; its files are "
                                          "removed once the new run is written")))


def _whole_number(text: str) -> int:
    """A whole number within 64 bits, as the keys.json it goes into is read back."""
    from ..spec import MAX_INTEGER

    try:
        value = int(text) if len(text) <= 20 else None
    except ValueError:
        value = None
    if value is None or abs(value) > MAX_INTEGER:
        raise argparse.ArgumentTypeError(render(message(
            "expected a whole number within ±{limit}, got {text!r}", limit=MAX_INTEGER,
            text=text[:30])))
    return value


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..application.tasks import Watch
    from ..application.variants import (
        RUN,
        VariantsRequest,
        class_of,
        draw_variants,
        write_variants,
    )
    from ..grading.templates import load_template, rejection_summary
    from ..progress import Progress
    from ..runs import earlier_run
    from .output import note, say

    out = Path(args.out)
    # before any work: refuse, or find the earlier run to replace
    earlier = earlier_run(out, RUN, force=args.force, name=f"--out {out}")
    template = load_template(args.template)
    students = class_of(args.count, args.students)
    request = VariantsRequest(template, students, seed=args.seed, sheets=not args.no_sheets,
                              source=str(args.template))
    with Progress(len(students.students), render(message("variants"))) as bar:
        drawn = draw_variants(request, watch=Watch(lambda *_: bar.advance()))
    changed = write_variants(out, drawn, earlier)
    if changed:   # a file of the earlier run changed meanwhile: it stays, hidden
        note(changed)
    say(plural("Wrote {count} variant of {template} (seed {seed}) to {out}/ ({redrawn} "
               "redrawn after a rejected draw); keys in {keys}",
               "Wrote {count} variants of {template} (seed {seed}) to {out}/ ({redrawn} "
               "redrawn after a rejected draw); keys in {keys}",
               count=len(drawn.variants), template=template.source, seed=args.seed,
               out=str(out), redrawn=drawn.redrawn, keys=str(out / "keys.json")))
    if drawn.rejected:
        say(plural("{count} draw rejected:", "{count} draws rejected:",
                   count=len(drawn.rejected)),
            *(f"  {line}" for line in rejection_summary(list(drawn.rejected))))
    return 0
