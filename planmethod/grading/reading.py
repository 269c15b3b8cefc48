"""Reading a typed answer as a number: the grammar as data, and the one reader of it.

A student types an answer; ``planmethod grade`` (:func:`planmethod.grading.answers.grade_question`)
and the workbook page (``render/page_rules.js``) read it by the same rule, written once here as
plain data (:func:`number_grammar`, a :class:`NumberGrammar`): the page receives the very
grammar (:meth:`NumberGrammar.as_dict`) and applies it as :func:`read_number` does, so the two
cannot read one text two ways. The grammar:

1. the spaces around the text are stripped (``spaces``: the characters ``str.isspace`` calls
   space — a list, since JavaScript's ``trim`` strips another set);
2. an empty text is no answer;
3. ``minus`` signs (U+2212) are written as ``-``, ``removed`` characters (the space between
   digit groups, ``1 000``) are dropped;
4. a text with one ``comma`` and no ``point`` has a decimal comma (``5,27``);
5. every decimal digit of any script (``５``, ``٥``, ``५``: the runs of ten from ``zeros``, made
   from :mod:`unicodedata`) is written as its ASCII digit;
6. what is left must match ``pattern`` — a sign, digits (one underscore between two digits,
   ``1_000``), a point, an exponent — read alike by Python's :mod:`re` and JavaScript's
   ``RegExp`` (ASCII classes only, no ``\\d``); the underscores are dropped and the text is read
   as a float (both languages round it correctly);
7. a text that does not match, or whose value is not finite (``1e999``), is not a number: at
   most ``limit`` characters of it are kept, to be quoted back.

This is the reading Python's ``float`` gave before the grammar was data, character for
character (tests/test_page_rules.py checks it against ``float`` on generated text).

Examples
--------
>>> read_number("５.27"), read_number("1_000"), read_number(" 5,27 "), read_number("\u22122e1")
(5.27, 1000.0, 5.27, -20.0)
>>> read_number(""), read_number("5.27 m/s"), read_number(None), read_number(3)
(None, '5.27 m/s', None, 3.0)
>>> number_grammar().as_dict()["minus"]
['−']
"""

from __future__ import annotations

import functools
import math
import re
import sys
import unicodedata
from dataclasses import dataclass
from typing import Any

__all__ = ["NumberGrammar", "number_grammar", "read_number"]


def _decimal_zeros() -> tuple[int, ...]:
    """The code point of the zero of every run of ten decimal digits (Unicode's ``Nd``: what
    ``float`` reads as a digit), in order. A run is ten code points in a row, so every tenth
    code point meets each run once."""
    found = (point for point in range(0, sys.maxunicode + 1, 10)
             if unicodedata.decimal(chr(point), None) is not None)
    zeros = tuple(sorted({point - unicodedata.decimal(chr(point)) for point in found}))
    # every decimal digit is in such a run (so that the page maps a digit by its run alone)
    assert all(unicodedata.decimal(chr(zero + step), None) == step
               for zero in zeros for step in range(10))
    return zeros


@dataclass(frozen=True)
class NumberGrammar:
    """How a typed answer is read (the module's steps 1–7): the characters stripped around it
    (``spaces``), written as a minus (``minus``) and dropped (``removed``); the decimal
    ``comma`` and ``point``; the zeros of the runs of decimal digits (``zeros``); the
    ``pattern`` the ASCII text must match whole; the characters of a refused text kept
    (``limit``)."""

    spaces: tuple[str, ...]
    minus: tuple[str, ...]
    removed: tuple[str, ...]
    comma: str
    point: str
    zeros: tuple[int, ...]
    pattern: str
    limit: int

    def as_dict(self) -> dict[str, Any]:
        """The grammar as JSON data, for the page."""
        return {"spaces": list(self.spaces), "minus": list(self.minus),
                "removed": list(self.removed), "comma": self.comma, "point": self.point,
                "zeros": list(self.zeros), "pattern": self.pattern, "limit": self.limit}


#: digits with at most one underscore between two of them
_DIGITS = "[0-9](?:_?[0-9])*"

@functools.cache
def number_grammar() -> NumberGrammar:
    """The one grammar of a typed answer (``planmethod grade`` and the pages), made when it
    is first read (its tables come from :mod:`unicodedata`). Every space character is in
    Unicode's first plane (tests/test_page_rules.py checks the whole range)."""
    return NumberGrammar(
        spaces=tuple(chr(point) for point in range(0x10000) if chr(point).isspace()),
        minus=("\u2212",), removed=(" ",), comma=",", point=".", zeros=_decimal_zeros(),
        pattern=(f"[+-]?(?:{_DIGITS}(?:\\.(?:{_DIGITS})?)?|\\.{_DIGITS})"
                 f"(?:[eE][+-]?{_DIGITS})?"),
        limit=40)


@functools.lru_cache(maxsize=4)
def _compiled(grammar: NumberGrammar) -> tuple[dict[int, str], re.Pattern[str], str]:
    """The grammar made quick to apply: digit → ASCII digit, the pattern, the spaces."""
    digits = {zero + step: str(step) for zero in grammar.zeros for step in range(10)}
    return digits, re.compile(grammar.pattern), "".join(grammar.spaces)


def read_number(raw: Any, grammar: NumberGrammar | None = None) -> float | str | None:
    """An answer read by ``grammar``: a number, None for no answer, or the text given instead
    (at most ``grammar.limit`` characters; ``True`` for a JSON true, ``inf`` for an infinite
    JSON number).

    >>> read_number("1,000.5"), read_number("٣٫٥"), read_number(True)
    ('1,000.5', '٣٫٥', 'True')
    """
    if raw is None:
        return None
    if isinstance(raw, bool):
        return repr(raw)
    if isinstance(raw, int | float):
        return float(raw) if math.isfinite(raw) else str(raw)
    grammar = grammar or number_grammar()
    digits, pattern, spaces = _compiled(grammar)
    text = str(raw).strip(spaces)
    if not text:
        return None
    cleaned = text
    for sign in grammar.minus:
        cleaned = cleaned.replace(sign, "-")
    for character in grammar.removed:
        cleaned = cleaned.replace(character, "")
    if cleaned.count(grammar.comma) == 1 and grammar.point not in cleaned:
        cleaned = cleaned.replace(grammar.comma, grammar.point)
    cleaned = cleaned.translate(digits)
    if pattern.fullmatch(cleaned) is None:
        return text[:grammar.limit]
    value = float(cleaned.replace("_", ""))
    return value if math.isfinite(value) else text[:grammar.limit]
