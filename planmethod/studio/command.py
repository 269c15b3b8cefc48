"""``planmethod studio [FILE]``: the instructor's studio, a local web app (the command line
dispatches to this module as to those of :mod:`planmethod.commands`; it lives beside the
server it starts, so that no command imports the studio and the studio imports no command).

Draw a mechanism on a grid — points, links, revolute and sliding pairs, the drive — and see its
plans of positions, velocities and accelerations redraw as a point is dragged; pick what is
asked, save the exercise (written as drawn), draw variants from ranges of its lengths and crank
angle with their task sheets, export LMS packages. The server (:mod:`planmethod.studio`) listens
on 127.0.0.1 only, serves the files under the folder it was started in, and needs the token
printed with its address; Ctrl-C stops it (and its jobs). docs/studio.md walks through it.
"""

from __future__ import annotations

import argparse
import sys

from ..arguments import said
from ..words import message, render

#: the port tried first when none is given (a free one is taken if it is busy)
DEFAULT_PORT = 8765


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", nargs="?", metavar=render(message("file", context="metavar")),
                        help=said(message("an exercise file under this folder to open (as "
                                          "drawn or in link frames; the studio saves as "
                                          "drawn)")))
    parser.add_argument("--port", type=int, metavar=render(message("N", context="metavar")),
                        help=said(message("the port to listen on (default {port}, or a free "
                                          "one if it is busy); the address is always "
                                          "127.0.0.1", port=DEFAULT_PORT)))
    parser.add_argument("--no-browser", action="store_true",
                        help=said(message("do not open the page in a browser (print its "
                                          "address only)")))


def run(args: argparse.Namespace) -> int:
    import signal
    import threading
    import webbrowser
    from pathlib import Path

    from ..errors import SpecError

    folder = Path.cwd()
    initial = None
    if args.file is not None:
        path = Path(args.file).resolve()
        if not path.is_relative_to(folder.resolve()):
            raise SpecError(message("the studio reads and writes only under the folder it is "
                                    "started in ({folder}): start it in the file's folder",
                                    folder=str(folder)), file=args.file)
        if path.is_dir():
            raise SpecError(message("is a folder, not an exercise file: the studio serves the "
                                    "folder it is started in (cd into it and run planmethod "
                                    "studio)"), file=args.file)
        if not path.is_file():
            raise SpecError(message("no such file"), file=args.file)
        initial = path.relative_to(folder.resolve()).as_posix()
    if args.port is not None and not 0 <= args.port <= 65535:
        raise SpecError(message("--port must be in 0…65535, got {port}", port=args.port))
    server = _listen(folder, args.port, initial, language=getattr(args, "lang", None))
    address = server.url("/", token=True)
    # Ctrl-C stops the studio even where it was started with SIGINT ignored (a background
    # job of a shell); its jobs' processes, in sessions of their own, are stopped by it. The
    # handler is in place before the address is told: a Ctrl-C the moment after still stops
    # the server it names
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.default_int_handler) if main else None
    try:
        print(render(message("planmethod studio: serving {folder} at\n    {address}\n(Ctrl-C "
                             "stops it)", folder=str(folder), address=address)), flush=True)
        if not args.no_browser:
            webbrowser.open(address)
        server.serve_forever(poll_interval=0.2)
    except KeyboardInterrupt:
        print("\n" + render(message("planmethod studio: stopped")), file=sys.stderr)
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)
        server.close()
    return 0


def _listen(folder, port: int | None, initial: str | None, *, language: str | None):
    """The studio listening on ``port`` (the default, or a free one if that is busy),
    speaking ``language`` (the ``--lang`` given, or None: each exercise's own, else the
    environment's)."""
    from ..errors import SpecError
    from .server import StudioServer

    try:
        return StudioServer(folder, DEFAULT_PORT if port is None else port, initial=initial,
                            language=language)
    except OSError as error:
        if port is not None:
            raise SpecError(message("cannot listen on 127.0.0.1:{port} ({why})", port=port,
                                    why=error.strerror), key="--port") from None
        return StudioServer(folder, 0, initial=initial, language=language)
