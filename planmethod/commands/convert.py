"""``planmethod convert FILE``: an exercise file in the other form — as drawn, or in link frames.

An exercise written *as drawn* gives every point's global position at ``drive.angle``
(``[points]``) and each link as the list of its points; one in *link frames* gives each link's
points in its own frame and a ``[sketch]`` to pick the assembly (docs/exercise-file.md).
``convert`` writes either from the other (default: the other form; ``--to`` chooses), to
``-o OUT`` or to the standard output. Converting back and forth writes the same bytes
(:mod:`planmethod.convert` says how the numbers are written for that).

Examples
--------
>>> from planmethod.cli import main
>>> main(["convert", "exercises/compressor_slider_crank.toml"])  # doctest: +ELLIPSIS
# Exactly as stated in U. A. Abduvaliev...
[points]
A = [0.0, 0.0]
B = [0.0424264068711929, 0.0424264068711928]
C = [0.2173549637165519, 0.0]
D = [0.1298906852938724, 0.0212132034355964]
<BLANKLINE>
[links]
frame = ["A"]
AB = ["A", "B"]
BC = ["B", "C", "D"]
slider = ["C"]
...
0
"""

from __future__ import annotations

import argparse
import sys

from ..arguments import said
from ..words import message, render

#: the forms ``--to`` names (:data:`planmethod.convert.FORMS`; not imported here, which would
#: load numpy for ``--help``)
FORMS = ("drawn", "frames")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar=render(message("file", context="metavar")),
                        help=said(message("exercise file ({format}), as drawn or in link "
                                          "frames", format="TOML")))
    parser.add_argument("-o", "--output", metavar=render(message("OUT", context="metavar")),
                        help=said(message("write the converted file here (default: the "
                                          "standard output)")))
    parser.add_argument("--to", choices=FORMS,
                        help=said(message("the form to write: drawn ([points], global "
                                          "positions at drive.angle) or frames (each link's "
                                          "points in its own frame); default: the other form")))


def run(args: argparse.Namespace) -> int:
    from ..convert import convert_text
    from ..io import write_text_atomic
    from ..spec import read_text

    text = convert_text(read_text(args.file), to=args.to, file=args.file)
    if args.output:
        write_text_atomic(args.output, text)
    else:
        sys.stdout.write(text)
    return 0
