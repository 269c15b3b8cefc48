"""``python -m planmethod``: the same command line as ``planmethod`` (see :mod:`planmethod.cli`;
tested in ``tests/test_words.py`` — pytest collects no doctests from a ``__main__`` module)."""

from __future__ import annotations

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
