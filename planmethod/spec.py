"""Exercise files (TOML) → :class:`~planmethod.model.Exercise`, with file- and key-precise errors.

The format is described in docs/exercise-file.md. Every problem is
reported as a :class:`~planmethod.errors.SpecError` naming the file and the dotted key, e.g.
``slider.toml: drive.omega: must be a finite number, got nan``.

Examples
--------
>>> text = '''
... [drive]
... link = "AB"
... pivot = "A"
... angle = 45
... omega = 100
... [links]
... frame = { A = [0, 0] }
... AB = { A = [0, 0], B = [0.06, 0] }
... BC = { B = [0, 0], C = [0.18, 0] }
... slider = { C = [0, 0] }
... [[slide]]
... link = "slider"
... along = "frame"
... through = "A"
... '''
>>> exercise = parse_exercise(text, file="compressor.toml")
>>> exercise.mechanism.slides[0].key
'slider/frame'
>>> parse_exercise(text.replace("omega = 100", "omega = nan"), file="x.toml")
Traceback (most recent call last):
...
planmethod.errors.SpecError: x.toml: drive.omega: must be a finite number, got nan
"""

from __future__ import annotations

import decimal
import difflib
import json
import math
import re
import tomllib
from collections.abc import Callable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .errors import SpecError, value_words
from .io import read_text_bounded
from .model import (
    FRAME,
    FRAME_PLACES,
    Ask,
    Course,
    Drive,
    Exercise,
    Link,
    Load,
    MassProperties,
    Mechanism,
    Notation,
    PlanSettings,
    Revolute,
    Slide,
)
from .vectors import angle_deg, cross, dot, norm, unit_angle
from .vocabulary import quantity, unit_words
from .words.language import problem as language_problem
from .words.message import Message, message, plural

__all__ = ["COURSE_KEYS", "DRAWN_TOLERANCE", "POINT_NAME", "checked_table", "course_from_dict",
           "did_you_mean", "drawing_size", "exercise_from_dict", "frames_from_drawn", "is_drawn",
           "leaves", "load_exercise", "parse_exercise", "parse_json", "parse_toml", "read_text"]

POINT_NAME = re.compile(r"^[A-Z][0-9]*$")
LINK_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")

TOP_LEVEL_KEYS = (
    "title", "description", "drive", "links", "slide", "sketch", "plan", "ask",
    "mass", "gravity", "load", "friction", "grading", "published", "points", "notation",
    "course",
)
#: the keys of the ``[course]`` table
COURSE_KEYS = ("language",)
PLAN_KEYS = (
    "crank_mm", "velocity_mm", "acceleration_mm", "mu_l", "mu_v", "mu_a", "force_mm", "mu_f",
    "scale_point", "precision_mm", "min_angle_deg", "exact_mm",
)
ASK_KEYS = ("velocity", "acceleration", "omega", "epsilon", "curvature", "sliding", "forces")


def load_exercise(path: str | Path) -> Exercise:
    """Read an exercise file.

    Parameters
    ----------
    path
        The TOML file.

    Raises
    ------
    SpecError
        If the file cannot be read, is not valid TOML, or breaks the exercise-file contract.
    """
    path = Path(path)
    return parse_exercise(read_text(path), file=str(path))


def parse_exercise(text: str, *, file: str | None = None) -> Exercise:
    """Parse the text of an exercise file (see :func:`load_exercise`).

    Parameters
    ----------
    text
        The TOML text of the exercise file.
    file
        The file name that error messages name (default: none).
    """
    return exercise_from_dict(parse_toml(text, file=file), file=file)


def read_text(path: str | Path) -> str:
    """The UTF-8 text of an exercise or template file (a regular file of at most
    :data:`MAX_FILE_BYTES`), or a :class:`SpecError` naming it."""
    return read_text_bounded(path, MAX_FILE_BYTES)


#: input limits (docs/commands.md, "Bad input"): what the stress suite covers, and no more
#: — coordinates and lengths (m), the crank's ω (rad/s) and ε (rad/s²), crank angles (°)
MAX_COORDINATE_M = 1e6
#: a length (m) — two points of one moving link apart, a pin radius — that is not 0 is at least
#: this: the stress suite covers cranks down to 6e-8 m; far shorter ones (a crank of 5e-324 m)
#: underflow and divide by zero. (A tiny coordinate is harmless: it is a length that counts.)
MIN_LENGTH_M = 1e-8
MAX_OMEGA = 1e4
MAX_EPSILON = 1e8
MAX_ANGLE_DEG = 36000.0
#: any other number (masses, forces, moments, g)
MAX_MAGNITUDE = 1e12
#: the largest exercise or template file read (bytes); the shipped ones are below 3 kB
MAX_FILE_BYTES = 1_000_000
#: tables and arrays nested deeper than this are refused before they are read
MAX_NESTING = 32
#: what Windows' Notepad and Excel may write first in a UTF-8 file (U+FEFF): dropped wherever
#: text is read (:func:`planmethod.io.read_text_bounded` drops it from files)
BYTE_ORDER_MARK = "\ufeff"
#: half of a UTF-16 pair: no character, and in no UTF-8 file (JSON text may hold "\\ud800")
_SURROGATE = re.compile("[\ud800-\udfff]")
#: whole numbers in TOML and JSON are 64-bit (TOML's own range); larger ones are refused where
#: they are read, before Python's limit on converting long digit strings can be met
MAX_INTEGER = 2**63 - 1
#: the friction iteration's largest allowed count
MAX_FRICTION_ITERATIONS = 10_000
#: a friction coefficient above this is not a joint's
MAX_FRICTION_COEFFICIENT = 2.0


#: what a bare word is made of in TOML (keys, numbers, dates, dots)
_WORD = r"""[^\s"'#\[\]{},=]"""
#: the tokens of TOML text that nesting is read from — a comment, a string's opening
#: (multi-line first), a bracket or brace, a comma, a line's end, a bare word holding a dot
#: (found from its first character only, so that a long word is read once) — by whether the
#: commas and the line ends count (they do while a dotted key is open)
_TOML_TOKENS = {
    (commas, lines): re.compile(
        r"""(#[^\n]*)|("{3}|'{3}|"|')|([\[{])|([\]}])|""" + ("(,)" if commas else "((?!))")
        + "|" + (r"(\n)" if lines else "((?!))")
        + rf"|(?<!{_WORD})(?={_WORD}*?\.)({_WORD}+)")
    for commas in (False, True) for lines in (False, True)}
#: the rest of a string after its opening, closing included, as tomllib reads it: a basic
#: string has escapes, a literal one none; a multi-line string ends at its first closing
#: triple, which takes up to two more quotes into the string; a single-line string left open
#: ends at its line's end (where tomllib stops with an error)
_TOML_STRING_REST = {
    '"': re.compile(r'(?:[^"\\\n]|\\.)*"?'),
    "'": re.compile(r"[^'\n]*'?"),
    '"""': re.compile(r'(?:[^"\\]|\\.|"(?!""))*(?:"""(?:""|")?)?', re.DOTALL),
    "'''": re.compile(r"(?:[^']|'(?!''))*(?:'''(?:''|')?)?"),
}
#: a JSON string with its escapes (to the text's end if it is never closed); what is no bracket
_JSON_STRING = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"?', re.DOTALL)
_JSON_NOT_BRACKET = re.compile(r'[^\[\]{}]+')
#: a word that is a number with a decimal point (``1.5``, ``07:32:00.25``): its dot is no key's
_DECIMAL = re.compile(r"[^.]*\d\.\d[^.]*")


def nesting_depth(text: str, syntax: str = "toml") -> int:
    r"""How deep tables and arrays nest in TOML text (or JSON: ``syntax="json"``), found
    without a parser and in linear time, so that a file nested 100,000 deep is refused before
    it can exhaust the stack.

    Strings and comments are read as TOML reads them — basic strings with their escapes,
    literal strings without, multi-line strings to their closing triple, ``#`` to the end of
    the line outside strings — so that no bracket in them counts. A level is a bracket or a
    brace, and each dot of a dotted key or a table header (``a.b.c = 1`` is two tables deep);
    a table header's levels hold for the keys under it.

    Examples
    --------
    >>> nesting_depth('a = [[1, 2], {b = "[[["}]  # [[[[')
    2
    >>> nesting_depth("d = '''He wrote ' and [[[['''"), nesting_depth("p = 'C:\\' # [[")
    (0, 0)
    >>> nesting_depth("[a.b]\nc.d = [1.5]"), nesting_depth('["[[", [1]]', syntax="json")
    (4, 2)
    """
    if syntax == "json":
        return _json_depth(text)
    deepest = header = 0    # header: the levels of the last table header, which keys are under
    pending = None          # the levels of a table header being read
    dots = [0]              # the dots of the key being read, outside brackets and in each one
    levels = 0              # the brackets open and the dots of their keys: sum(dots) + len - 1
    position = 0
    while (found := _TOML_TOKENS[dots[-1] > 0, len(dots) == 1 and dots[0] > 0].search(
            text, position)) is not None:
        position = found.end()
        kind = found.lastindex
        if kind == 2:           # a string
            position = _TOML_STRING_REST[found.group(2)].match(text, position).end()
        elif kind == 3:         # [ or {
            if len(dots) == 1 and found.group(3) == "[" and _starts_line(text, found.start()):
                pending = 0     # a table header
            dots.append(0)
            levels += 1
        elif kind == 4 and len(dots) > 1:   # ] or }
            levels -= dots.pop() + 1
            if len(dots) == 1 and pending is not None:   # the header's end
                header, pending = pending, None
                deepest = max(deepest, header)
                continue
        elif kind in (5, 6):    # a comma, a line's end: the dotted key is done
            levels -= dots[-1]
            dots[-1] = 0
        elif kind == 7:         # a dotted key (or a number with its decimal point)
            added = found.group(7).count(".") - (_DECIMAL.fullmatch(found.group(7)) is not None)
            dots[-1] += added
            levels += added
        if pending is not None:
            pending = max(pending, levels)
        elif levels + header > deepest:
            deepest = levels + header
    return max(deepest, pending or 0)


def _starts_line(text: str, position: int) -> bool:
    """True if only spaces and tabs are before ``position`` on its line."""
    while position > 0 and text[position - 1] in " \t":
        position -= 1
    return position == 0 or text[position - 1] in "\n\ufeff"


def _json_depth(text: str) -> int:
    """:func:`nesting_depth` of JSON text (strings with escapes; no comments): the strings
    cut out and everything but brackets and braces dropped by regular expressions, so that
    only the brackets are walked in Python (a bundle of 1000 keys, 24 MB, in well under a
    second)."""
    brackets = _JSON_NOT_BRACKET.sub("", _JSON_STRING.sub("", text))
    depth = deepest = 0
    for bracket in brackets:
        if bracket in "[{":
            depth += 1
            deepest = max(deepest, depth)
        else:
            depth = max(depth - 1, 0)
    return deepest


def check_nesting(text: str, *, file: str | None = None, syntax: str = "toml") -> None:
    """A :class:`SpecError` if ``text`` nests deeper than :data:`MAX_NESTING` (see
    :func:`nesting_depth`)."""
    depth = nesting_depth(text, syntax)
    if depth > MAX_NESTING:
        raise SpecError(message("tables or arrays nested {depth} deep; at most {limit} are "
                                "read", depth=depth, limit=MAX_NESTING), file=file)


def checked_table(value: Any, key: str, allowed: Sequence[str], *, file: str | None = None
                  ) -> Mapping[str, Any]:
    """``value`` as the table ``key`` of a file, holding only ``allowed`` keys.

    Raises
    ------
    SpecError
        If it is no table, or has another key (naming it, and the keys allowed).

    Examples
    --------
    >>> checked_table({"precision_mm": 0.5}, "grading", ("precision_mm", "points"))
    {'precision_mm': 0.5}
    >>> checked_table({"precision": 0.5}, "grading", ("precision_mm",), file="task.toml")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: task.toml: grading.precision: unknown key; expected one of \
precision_mm
    """
    if not isinstance(value, Mapping):
        raise SpecError(message("must be a table"), file=file, key=key)
    for name in value:
        if name not in allowed:
            raise SpecError(message("unknown key; expected one of {keys}", keys=list(allowed)),
                            file=file, key=f"{key}.{name}")
    return value


def parse_toml(text: str, *, file: str | None = None) -> dict[str, Any]:
    """TOML text → tables, or a :class:`SpecError` naming the file, line and column (or the
    key of a whole number beyond :data:`MAX_INTEGER`).

    >>> parse_toml("a = " + "9" * 5000, file="x.toml")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: x.toml: line 1: a whole number of 5000 digits, beyond the \
64-bit range (at most 9223372036854775807 in magnitude)
    """
    text = text.removeprefix(BYTE_ORDER_MARK)
    surrogate = _SURROGATE.search(text)
    if surrogate is not None:   # text that came through JSON ("\\ud800"), never from a file
        line = text.count("\n", 0, surrogate.start()) + 1
        raise SpecError(message("not valid TOML: U+{code:04X} is half of a UTF-16 pair, not a "
                                "character (line {line})", code=ord(surrogate.group()),
                                line=line), file=file)
    check_nesting(text, file=file)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise SpecError(message("not valid TOML: {reason}", reason=_toml_reason(error)),
                        file=file) from None
    except ValueError:  # a digit string beyond Python's integer-string conversion limit
        raise _long_digits_error(text, file) from None
    for key, value in leaves(data):
        if isinstance(value, int) and not isinstance(value, bool) and abs(value) > MAX_INTEGER:
            raise SpecError(_too_long(_digit_count(value)), file=file, key=key)
    return data


#: where tomllib says it stopped, at the end of its message
_TOML_WHERE = re.compile(r"(.*) \((?:at line (\d+), column (\d+)|(at end of document))\)",
                         re.DOTALL)


def _toml_reason(error: tomllib.TOMLDecodeError) -> Message | str:
    r"""What tomllib says is wrong: its own words (English: the library's), but a key given
    twice in ours, and where it stopped (a line and column, or the end) in a message.

    >>> from planmethod.words import render
    >>> for text in ("a = 1\na = 2\nb = 3", "a = 1\na = 2"):
    ...     try:
    ...         tomllib.loads(text)
    ...     except tomllib.TOMLDecodeError as error:
    ...         print(render(_toml_reason(error)))
    a key is given twice (at line 2, column 6)
    a key is given twice (at end of document)
    """
    text = str(error)
    where = _TOML_WHERE.fullmatch(text)
    what = where.group(1) if where else text
    said: Message | str = (message("a key is given twice")
                           if what == "Cannot overwrite a value" else what)
    if where is None:
        return said
    if where.group(4):
        return message("{what} (at end of document)", what=said)
    return message("{what} (at line {line}, column {column})", what=said,
                   line=int(where.group(2)), column=int(where.group(3)))


def _long_digits_error(text: str, file: str | None) -> SpecError:
    """The error for the line of ``text`` holding the longest run of digits."""
    best = (0, 0)
    for number, line in enumerate(text.splitlines(), start=1):
        for run in re.findall(r"\d[\d_]*", line):
            best = max(best, (len(run.replace("_", "")), -number))
    digits, line = best[0], -best[1]
    return SpecError(_too_long(digits), file=file, key=message("line {line}", line=line))


def _too_long(digits: int) -> Message:
    return plural("a whole number of {count} digit, beyond the 64-bit range (at most {limit} "
                  "in magnitude)", "a whole number of {count} digits, beyond the 64-bit range "
                  "(at most {limit} in magnitude)", count=digits, limit=MAX_INTEGER)


def _digit_count(value: int) -> int:
    """How many decimal digits ``value`` has, without converting it to text (which Python
    refuses beyond 4,300 digits)."""
    count = math.floor(max(abs(value).bit_length() - 1, 0) * math.log10(2)) + 1  # at least
    return count + (abs(value) >= 10 ** count)


def leaves(node: Any, prefix: str = "", *,
           whole: Callable[[Any], bool] | None = None) -> Iterator[tuple[str, Any]]:
    """(dotted key, value) of every value in nested tables and lists; a table or list for
    which ``whole`` is true is given as one value, not entered.

    >>> def ranged(value):
    ...     return isinstance(value, dict) and "range" in value
    >>> list(leaves({"a": [1, {"b": 2}], "c": {"range": [0, 1]}}, whole=ranged))
    [('a[0]', 1), ('a[1].b', 2), ('c', {'range': [0, 1]})]
    """
    if whole is not None and whole(node):
        yield prefix, node
    elif isinstance(node, Mapping):
        for name, value in node.items():
            yield from leaves(value, f"{prefix}.{name}" if prefix else str(name), whole=whole)
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from leaves(value, f"{prefix}[{index}]", whole=whole)
    else:
        yield prefix, node


class _LongInteger:
    """What a JSON whole number beyond :data:`MAX_INTEGER` is read as, until it is reported."""

    __slots__ = ("digits",)

    def __init__(self, digits: int) -> None:
        self.digits = digits


class _RepeatedKeyError(Exception):
    pass


def _unique_object(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out = dict(pairs)
    if len(out) != len(pairs):
        seen: set[str] = set()
        for name, _ in pairs:
            if name in seen:
                raise _RepeatedKeyError(name)
            seen.add(name)
    return out


def parse_json(text: str, *, file: str | None = None, unique_keys: bool = False) -> Any:
    """JSON text → data, or a :class:`SpecError` naming the file: nesting deeper than
    :data:`MAX_NESTING` is refused before parsing, a whole number beyond :data:`MAX_INTEGER`
    (a 5,000-digit one included) with its key, and — with ``unique_keys`` — a key given
    twice in one object (JSON would keep the last silently).

    Examples
    --------
    >>> parse_json('{"s1": {"v_C": 1, "v_C": 2}}', file="a.json", unique_keys=True)
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: a.json: v_C: the key is given twice in one object
    >>> parse_json('{"s1": {"v_C": 1' + '0' * 30 + '}}', file="a.json")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: a.json: s1.v_C: a whole number of 31 digits, beyond the \
64-bit range (at most 9223372036854775807 in magnitude)
    """
    text = text.removeprefix(BYTE_ORDER_MARK)
    check_nesting(text, file=file, syntax="json")
    long_integers: list[_LongInteger] = []

    def integer(digits: str) -> int | _LongInteger:
        # more than 19 digits is beyond 64 bits: never converted (a 5,000-digit one could not be)
        value = int(digits) if len(digits) <= 20 else None
        if value is not None and abs(value) <= MAX_INTEGER:
            return value
        long_integers.append(_LongInteger(len(digits.lstrip("-"))))
        return long_integers[-1]

    try:
        data = json.loads(text, parse_int=integer,
                          object_pairs_hook=_unique_object if unique_keys else None)
    except json.JSONDecodeError as error:
        raise SpecError(message("not valid JSON: {reason}", reason=str(error)),
                        file=file) from None
    except _RepeatedKeyError as error:
        raise SpecError(message("the key is given twice in one object"), file=file,
                        key=str(error.args[0])) from None
    if long_integers:
        for key, value in leaves(data):
            if isinstance(value, _LongInteger):
                raise SpecError(_too_long(value.digits), file=file, key=key or None)
    return data


def exercise_from_dict(data: Mapping[str, Any], *, file: str | None = None) -> Exercise:
    """Build an :class:`~planmethod.model.Exercise` from the parsed TOML tables."""
    return _Reader(file).exercise(data)


def course_from_dict(data: Mapping[str, Any], *, file: str | None = None) -> Course:
    """The ``[course]`` table of an exercise's or a template's tables (a template's variants
    carry it as it is), checked: a :class:`SpecError` naming ``course.language`` if it is no
    language planmethod can speak.

    Examples
    --------
    >>> course_from_dict({"course": {"language": "ru"}}), course_from_dict({})
    (Course(language='ru'), Course(language=None))
    >>> course_from_dict({"course": {"language": "zz"}}, file="t.toml")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: t.toml: course.language: no catalogue for the language zz ...
    """
    return _Reader(file).course(data)


def _mechanism_size(links: Mapping[str, Link]) -> float:
    """The largest extent of any link (m), at least 1 mm."""
    size = 1e-3
    for link in links.values():
        xs = [p[0] for p in link.points.values()]
        ys = [p[1] for p in link.points.values()]
        if xs:
            size = max(size, max(xs) - min(xs), max(ys) - min(ys))
    return size


def _distance_to_points(point, points) -> float:
    return min(math.hypot(point[0] - x, point[1] - y) for x, y in points)


def did_you_mean(word: str, choices) -> Message | str:
    """The closest of ``choices`` to a misspelt ``word``, as a message's tail (its ``hint``
    field), or "".

    >>> from planmethod.words import render
    >>> render(did_you_mean("crnak", ["crank", "rod"])), did_you_mean("xyz", ["crank"])
    (" (did you mean 'crank'?)", '')
    """
    close = difflib.get_close_matches(word, list(choices), n=1)
    return message(" (did you mean '{name}'?)", name=close[0]) if close else ""


def _decimals_apart(first: float, second: float) -> tuple[decimal.Decimal, decimal.Decimal]:
    """Two numbers written with as few decimals as tell them apart (at most 9), as decimals
    a message writes with its ``f`` format (and the course's decimal sign).

    >>> [format(number, "f") for number in _decimals_apart(44.99996, 45.0)]
    ['44.99996', '45']
    >>> [format(number, "f") for number in _decimals_apart(30.0, 30.0)]
    ['30', '30']
    """
    for decimals in range(10):
        texts = (f"{first:.{decimals}f}", f"{second:.{decimals}f}")
        if texts[0] != texts[1]:
            break
    return tuple(decimal.Decimal(text.rstrip("0").rstrip(".") if "." in text else text)
                 for text in texts)


def _not_a_point(point: str, link: str, points) -> Message:
    """``'{point}' is not a point of '{link}'`` with the closest of ``points``."""
    return message("'{point}' is not a point of '{link}'{hint}", point=point, link=link,
                   hint=did_you_mean(point, points))


def _unknown_link(name: str, links) -> Message:
    return message("unknown link '{link}'{hint}", link=name, hint=did_you_mean(name, links))


def _unknown_point(name: str, points) -> Message:
    return message("unknown point '{point}'{hint}", point=name, hint=did_you_mean(name, points))


#: what a point's name is, as an error says it
_POINT_NAME_WORDS = message("a point name is a capital letter, optionally followed by digits "
                            "(A, O2, C4)")
#: the note on a limit that is the range the stress suite covers, by unit
_TESTED_RANGE = {unit: message("{unit}; the range planmethod is tested on",
                               unit=unit_words(unit)) for unit in ("m", "rad/s", "rad/s²")}


#: what a key the file must give and does not is
_MISSING = message("missing")
#: the unit of an angle's limit
_DEGREES = message("degrees")


def _too_large(limit: float, what: Message | None, value: float | None = None) -> Message:
    """``must be at most {limit} in magnitude`` (with what the limit is, and the value)."""
    if value is None:
        return (message("must be at most {limit:g} in magnitude ({what})", limit=limit,
                        what=what) if what is not None
                else message("must be at most {limit:g} in magnitude", limit=limit))
    if what is None:
        return message("must be at most {limit:g} in magnitude, got {value:g}", limit=limit,
                       value=value)
    return message("must be at most {limit:g} in magnitude ({what}), got {value:g}",
                   limit=limit, what=what, value=value)


class _Reader:
    """Reads the tables with a file name at hand for every error."""

    def __init__(self, file: str | None) -> None:
        self.file = file

    def error(self, key: str, words: Message | str) -> SpecError:
        return SpecError(words, file=self.file, key=key)

    # -- scalar readers ---------------------------------------------------------------------
    def number(self, value: Any, key: str, *, positive: bool = False,
               non_negative: bool = False, limit: float = MAX_MAGNITUDE,
               what: Message | None = None) -> float:
        """A finite number of magnitude at most ``limit`` (``what`` names the limit: its
        unit, or the range it is)."""
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(key, message("must be a finite number, got {given}",
                                          given=value_words(value)))
        try:
            value = float(value)
        except OverflowError:   # an integer too large for a float
            raise self.error(key, _too_large(limit, what)) from None
        if not math.isfinite(value):
            raise self.error(key, message("must be a finite number, got {given}", given=value))
        if abs(value) > limit:
            raise self.error(key, _too_large(limit, what, value))
        if positive and value <= 0:
            raise self.error(key, message("must be positive, got {value:g}", value=value))
        if non_negative and value < 0:
            raise self.error(key, message("must not be negative, got {value:g}", value=value))
        return value

    def vector(self, value: Any, key: str, *, limit: float = MAX_MAGNITUDE,
               what: Message | None = None) -> tuple[float, float]:
        if not isinstance(value, list | tuple) or len(value) != 2:
            raise self.error(key, message("must be a pair of numbers [x, y], got {given}",
                                          given=value_words(value)))
        return (self.number(value[0], f"{key}[0]", limit=limit, what=what),
                self.number(value[1], f"{key}[1]", limit=limit, what=what))

    def coordinates(self, value: Any, key: str) -> tuple[float, float]:
        """A point's coordinates (m), within the range the stress suite covers."""
        return self.vector(value, key, limit=MAX_COORDINATE_M, what=_TESTED_RANGE["m"])

    def not_tiny(self, length: float, key: str, apart_from: str | None = None) -> None:
        """A :class:`SpecError` if ``length`` (m) is not 0 but below :data:`MIN_LENGTH_M`
        (``apart_from``: the point it is a distance from)."""
        if length == 0 or abs(length) >= MIN_LENGTH_M:
            return
        if apart_from is None:
            raise self.error(key, message(
                "must be 0 or at least {minimum:g} m in magnitude, got {length:g} (m; the "
                "range planmethod is tested on)", minimum=MIN_LENGTH_M, length=length))
        raise self.error(key, message(
            "its distance from {point} must be 0 or at least {minimum:g} m in magnitude, got "
            "{length:g} (m; the range planmethod is tested on)", point=apart_from,
            minimum=MIN_LENGTH_M, length=length))

    def string(self, value: Any, key: str) -> str:
        if not isinstance(value, str) or not value:
            raise self.error(key, message("must be a non-empty string, got {given}",
                                          given=value_words(value)))
        return value

    def table(self, value: Any, key: str) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            raise self.error(key, message("must be a table, got {given}",
                                          given=value_words(value)))
        return value

    def flag(self, value: Any, key: str) -> bool:
        """``true`` or ``false``."""
        if not isinstance(value, bool):
            raise self.error(key, message("must be true or false, got {given}",
                                          given=value_words(value)))
        return value

    def tables(self, data: Mapping[str, Any], name: str
               ) -> Iterator[tuple[int, str, Mapping[str, Any]]]:
        """The array of tables ``[[name]]`` (one table alone counts as one): (number from 1,
        its key, the table) each, checked one by one as they are read."""
        raw = data.get(name, [])
        if isinstance(raw, Mapping):
            raw = [raw]
        if not isinstance(raw, list):
            raise self.error(name, message("must be an array of tables ([[{name}]])",
                                           name=name))
        for number, table in enumerate(raw, start=1):
            yield number, f"{name}[{number}]", self.table(table, f"{name}[{number}]")

    def only_keys(self, table: Mapping[str, Any], allowed, key: str) -> None:
        for name in table:
            if name not in allowed:
                raise self.error(f"{key}.{name}" if key else name, message(
                    "unknown key{hint}; expected one of {keys}",
                    hint=did_you_mean(name, allowed), keys=list(allowed)))

    # -- the exercise -----------------------------------------------------------------------
    def exercise(self, data: Mapping[str, Any]) -> Exercise:
        for name in ("vars", "template"):
            if name in data:
                raise self.error(name, message(
                    "this is an exercise template (it has ranges, choices or expressions): "
                    "draw exercises from it with `planmethod variants`"))
        self.only_keys(data, TOP_LEVEL_KEYS, "")
        data = frames_from_drawn(data, file=self.file)
        title = data.get("title", Path(self.file).stem if self.file else "mechanism")
        title = self.string(title, "title")
        if not isinstance(data.get("description", ""), str):
            raise self.error("description", message(
                "must be a string (the task in words), got {given}",
                given=value_words(data["description"])))
        links = self.links(data)
        revolutes = self.revolutes(links)
        slides = self.slides(data, links)
        drive = self.drive(data, links)
        sketch = self.sketch(data, links)
        masses = self.masses(data, links)
        gravity = self.gravity(data)
        loads = self.loads(data, links)
        friction = self.friction(data, links, revolutes, slides)
        notation = self.notation(data, links)
        mechanism = Mechanism(
            title=title, links=links, revolutes=revolutes, slides=slides, drive=drive,
            sketch=sketch, masses=masses, gravity=gravity, loads=loads, friction=friction,
            notation=notation,
        )
        plan = self.plan(data, mechanism)
        ask = self.ask(data, mechanism)
        published, published_source = self.published(data)
        return Exercise(mechanism=mechanism, plan=plan, ask=ask, source=self.file,
                        published=published, published_source=published_source,
                        course=self.course(data))

    def course(self, data: Mapping[str, Any]) -> Course:
        """``[course]``: ``language = "ru"``, a language planmethod can speak (a shipped
        catalogue or a course's own, docs/languages.md)."""
        table = self.table(data.get("course", {}), "course")
        self.only_keys(table, COURSE_KEYS, "course")
        if "language" not in table:
            return Course()
        language = self.string(table["language"], "course.language")
        refused = language_problem(language)
        if refused is not None:
            raise self.error("course.language", refused)
        return Course(language)

    def published(self, data: Mapping[str, Any]) -> tuple[dict[str, float], str | None]:
        """``[published]``: the values a book prints (``v_C = 4.0``, SI units), with an
        optional ``source = "…"`` naming the book."""
        table = self.table(data.get("published", {}), "published")
        values: dict[str, float] = {}
        source = None
        for name, value in table.items():
            if name == "source":
                source = self.string(value, "published.source")
                continue
            try:
                quantity(name)
            except KeyError:
                raise self.error(f"published.{name}", message(
                    "is not a quantity (v_C, a_C, omega_BC, epsilon_BC, rho_D, …)")) from None
            values[name] = self.number(value, f"published.{name}")
        return values, source

    def links(self, data: Mapping[str, Any]) -> dict[str, Link]:
        if "links" not in data:
            raise self.error("links", message("missing the [links] table"))
        table = self.table(data["links"], "links")
        if FRAME not in table:
            raise self.error("links", message("missing the fixed link '{link}'{hint}",
                                              link=FRAME, hint=did_you_mean(FRAME, table)))
        links: dict[str, Link] = {}
        seen_lower: dict[str, str] = {}
        for name, points in table.items():
            key = f"links.{name}"
            if not LINK_NAME.match(name):
                raise self.error(key, message("a link name must be an identifier (letters, "
                                              "digits, _)"))
            if name.lower() in seen_lower:
                raise self.error(key, message("duplicate link name (also '{other}')",
                                              other=seen_lower[name.lower()]))
            seen_lower[name.lower()] = name
            points = self.table(points, key)
            if not points and name != FRAME:
                raise self.error(key, message("a link needs at least one point"))
            parsed = {}
            for point, xy in points.items():
                if not POINT_NAME.match(point):
                    raise self.error(f"{key}.{point}", _POINT_NAME_WORDS)
                parsed[point] = self.coordinates(xy, f"{key}.{point}")
            links[name] = Link(name, parsed)
        if len(links) < 2:
            raise self.error("links", message("a mechanism needs the frame and at least one "
                                              "moving link"))
        owners: dict[str, int] = {}
        for link in links.values():
            for point in link.points:
                owners[point] = owners.get(point, 0) + 1
        for name, link in links.items():
            if name != FRAME:
                self.no_tiny_lengths({point: xy for point, xy in link.points.items()
                                      if owners[point] > 1}, f"links.{name}")
        return links

    def no_tiny_lengths(self, points: Mapping[str, tuple[float, float]], key: str) -> None:
        """Two joints of one moving link (points it shares with another link) are one point
        or at least :data:`MIN_LENGTH_M` apart: the plans divide by such lengths. (A point of
        one link only — a coupler point — may lie as close to a joint as it likes.)"""
        names = list(points)
        for index, first in enumerate(names):
            for second in names[index + 1:]:
                (x1, y1), (x2, y2) = points[first], points[second]
                self.not_tiny(math.hypot(x2 - x1, y2 - y1), f"{key}.{second}", first)

    def revolutes(self, links: Mapping[str, Link]) -> tuple[Revolute, ...]:
        owners: dict[str, list[str]] = {}
        for name, link in links.items():
            for point in link.points:
                owners.setdefault(point, []).append(name)
        return tuple(Revolute(point, tuple(names)) for point, names in owners.items()
                     if len(names) >= 2)

    def slides(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> tuple[Slide, ...]:
        slides = []
        for number, key, table in self.tables(data, "slide"):
            self.only_keys(table, ("link", "along", "through", "direction", "point"), key)
            for needed in ("link", "along", "through"):
                if needed not in table:
                    raise self.error(f"{key}.{needed}", _MISSING)
            link = self.link_name(table["link"], f"{key}.link", links)
            along = self.link_name(table["along"], f"{key}.along", links)
            if link == along:
                raise self.error(f"{key}.along", message(
                    "a link cannot slide along itself ('{link}')", link=link))
            through = self.string(table["through"], f"{key}.through")
            if through not in links[along].points:
                raise self.error(f"{key}.through",
                                 _not_a_point(through, along, links[along].points))
            direction = self.number(table.get("direction", 0.0), f"{key}.direction")
            if "point" in table:
                point = self.string(table["point"], f"{key}.point")
                if point not in links[link].points:
                    raise self.error(f"{key}.point",
                                     _not_a_point(point, link, links[link].points))
            elif len(links[link].points) == 1:
                point = next(iter(links[link].points))
            else:
                raise self.error(f"{key}.point", message(
                    "'{link}' has several points ({points}): name the one on the guide",
                    link=link, points=list(links[link].points)))
            pair = Slide(link, along, through, direction, point, number)
            if any(s.key == pair.key or s.key == f"{along}/{link}" for s in slides):
                raise self.error(key, message(
                    "duplicate prismatic pair between '{link}' and '{along}'", link=link,
                    along=along))
            slides.append(pair)
        return tuple(slides)

    def link_name(self, value: Any, key: str, links: Mapping[str, Link]) -> str:
        name = self.string(value, key)
        if name not in links:
            raise self.error(key, _unknown_link(name, links))
        return name

    def drive(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> Drive:
        if "drive" not in data:
            unknown = [k for k in data if k not in TOP_LEVEL_KEYS]
            raise self.error("drive", message(
                "missing the [drive] table (link, pivot, angle, omega){hint}",
                hint=did_you_mean("drive", unknown)))
        table = self.table(data["drive"], "drive")
        self.only_keys(table, ("link", "pivot", "angle", "omega", "epsilon"), "drive")
        for needed in ("link", "pivot", "angle", "omega"):
            if needed not in table:
                raise self.error(f"drive.{needed}", _MISSING)
        link = self.link_name(table["link"], "drive.link", links)
        if link == FRAME:
            raise self.error("drive.link", message("the frame cannot be the drive link"))
        pivot = self.string(table["pivot"], "drive.pivot")
        if pivot not in links[link].points:
            raise self.error("drive.pivot", _not_a_point(pivot, link, links[link].points))
        if pivot not in links[FRAME].points:
            raise self.error("drive.pivot", message(
                "'{point}' must also be a point of '{frame}' (the drive turns about a fixed "
                "pivot)", point=pivot, frame=FRAME))
        if len(links[link].points) < 2:
            raise self.error(f"links.{link}", message("the drive link needs a point besides "
                                                      "its pivot"))
        return Drive(
            link=link, pivot=pivot,
            angle=self.number(table["angle"], "drive.angle", limit=MAX_ANGLE_DEG,
                              what=_DEGREES),
            omega=self.number(table["omega"], "drive.omega", limit=MAX_OMEGA,
                              what=_TESTED_RANGE["rad/s"]),
            epsilon=self.number(table.get("epsilon", 0.0), "drive.epsilon", limit=MAX_EPSILON,
                                what=_TESTED_RANGE["rad/s²"]),
        )

    def notation(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> Notation:
        """``[notation]``: how the course numbers the links — ``frame = 0`` (default: the
        frame 0, the crank 1, …), ``1`` or ``"last"``, and ``numbers = { AB = 1, … }`` for any
        links (docs/notation.md)."""
        table = self.table(data.get("notation", {}), "notation")
        self.only_keys(table, ("frame", "numbers"), "notation")
        place = table.get("frame", 0)
        if isinstance(place, bool) or place not in FRAME_PLACES:
            raise self.error("notation.frame", message('must be 0, 1 or "last", got {given}',
                                                       given=value_words(place)))
        numbers: dict[str, int] = {}
        owner: dict[int, str] = {}
        for name, value in self.table(table.get("numbers", {}), "notation.numbers").items():
            key = f"notation.numbers.{name}"
            if name not in links:
                raise self.error(key, _unknown_link(name, links))
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 99:
                raise self.error(key, message("must be a whole number from 0 to 99, got {given}",
                                              given=value_words(value)))
            if value in owner:
                raise self.error(key, message("{number} is already the number of '{link}'",
                                              number=value, link=owner[value]))
            if name == FRAME and "frame" in table:
                raise self.error(key, message("the frame's number is given twice: keep "
                                              "notation.frame or notation.numbers.frame"))
            if name != FRAME and FRAME not in table.get("numbers", {}) and place == value:
                raise self.error(key, message("{number} is the frame's number (notation.frame "
                                              "= {place})", number=value, place=place))
            numbers[name] = value
            owner[value] = name
        return Notation(place, numbers)

    def sketch(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> dict:
        table = self.table(data.get("sketch", {}), "sketch")
        known = {p for link in links.values() for p in link.points}
        sketch = {}
        for point, xy in table.items():
            if point not in known:
                raise self.error(f"sketch.{point}", _unknown_point(point, known))
            sketch[point] = self.coordinates(xy, f"sketch.{point}")
        return sketch

    def masses(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> dict:
        table = self.table(data.get("mass", {}), "mass")
        masses = {}
        for name, props in table.items():
            key = f"mass.{name}"
            if name not in links:
                raise self.error(key, _unknown_link(name, links))
            if name == FRAME:
                raise self.error(key, message("the frame does not move: it needs no mass"))
            props = self.table(props, key)
            self.only_keys(props, ("m", "J", "S"), key)
            if "m" not in props:
                raise self.error(f"{key}.m", _MISSING)
            m = self.number(props["m"], f"{key}.m", positive=True)
            J = self.number(props.get("J", 0.0), f"{key}.J", non_negative=True)
            points = links[name].points
            if "S" in props:
                S = self.coordinates(props["S"], f"{key}.S")
            else:  # centroid of the link's points
                S = (sum(p[0] for p in points.values()) / len(points),
                     sum(p[1] for p in points.values()) / len(points))
            if _distance_to_points(S, points.values()) > 10 * _mechanism_size(links):
                raise self.error(f"{key}.S", message(
                    "centre of mass ({x}, {y}) lies more than 10 times the mechanism's size "
                    "({size:g} m) from the link's points", x=S[0], y=S[1],
                    size=_mechanism_size(links)))
            masses[name] = MassProperties(name, m, J, S)
        return masses

    def gravity(self, data: Mapping[str, Any]) -> float | None:
        if "gravity" not in data:
            return None
        table = self.table(data["gravity"], "gravity")
        self.only_keys(table, ("g",), "gravity")
        return self.number(table.get("g", 9.81), "gravity.g", non_negative=True)

    def loads(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> tuple[Load, ...]:
        loads = []
        for number, key, table in self.tables(data, "load"):
            self.only_keys(table, ("link", "point", "force", "moment", "oppose_velocity", "name"),
                           key)
            if "link" not in table:
                raise self.error(f"{key}.link", _MISSING)
            link = self.link_name(table["link"], f"{key}.link", links)
            if link == FRAME:
                raise self.error(f"{key}.link", message("a load on the frame does nothing"))
            has_force, has_moment = "force" in table, "moment" in table
            if has_force == has_moment:
                raise self.error(key, message("give exactly one of `force = [fx, fy]` or "
                                              "`moment = m`"))
            point = None
            if has_force:
                if "point" not in table:
                    raise self.error(f"{key}.point", message("a force needs the point it "
                                                             "acts on"))
                point = self.string(table["point"], f"{key}.point")
                if point not in links[link].points:
                    raise self.error(f"{key}.point",
                                     _not_a_point(point, link, links[link].points))
            oppose = self.flag(table.get("oppose_velocity", False), f"{key}.oppose_velocity")
            name = None
            if "name" in table:
                name = self.string(table["name"], f"{key}.name")
                if not re.fullmatch(r"[^\W\d][\w,′']{0,15}", name):
                    raise self.error(f"{key}.name", message(
                        "{given} is not a symbol: a letter, then up to 15 letters, digits or _ "
                        "(P, P_c, F_res)", given=value_words(name)))
            loads.append(Load(
                link=link, point=point,
                force=self.vector(table["force"], f"{key}.force") if has_force else None,
                moment=self.number(table["moment"], f"{key}.moment") if has_moment else None,
                oppose_velocity=oppose, index=number, name=name,
            ))
        return tuple(loads)

    def friction(self, data, links, revolutes, slides) -> dict:
        """``[friction]``: ``f`` (coefficient, all pairs), ``pin_radius`` (m, all revolute
        pairs), and per-pair overrides ``[friction.pairs."B"]`` or
        ``[friction.pairs."slider/frame"]`` with ``f`` and ``pin_radius``. Validated here; used
        by the force module."""
        if "friction" not in data:
            return {}
        table = self.table(data["friction"], "friction")
        self.only_keys(table, ("f", "pin_radius", "pairs", "tolerance", "max_iterations"),
                       "friction")
        result: dict[str, Any] = {}
        limits = {"f": (MAX_FRICTION_COEFFICIENT, message("a friction coefficient")),
                  "pin_radius": (MAX_COORDINATE_M, unit_words("m")),
                  "tolerance": (MAX_MAGNITUDE, None)}
        for name in ("f", "pin_radius", "tolerance"):
            if name in table:
                limit, what = limits[name]
                result[name] = self.number(table[name], f"friction.{name}", non_negative=True,
                                           limit=limit, what=what)
        if "pin_radius" in result:
            self.not_tiny(result["pin_radius"], "friction.pin_radius")
        if "max_iterations" in table:
            value = table["max_iterations"]
            if (isinstance(value, bool) or not isinstance(value, int)
                    or not 1 <= value <= MAX_FRICTION_ITERATIONS):
                raise self.error("friction.max_iterations", message(
                    "must be an integer from 1 to {limit}, got {given}",
                    limit=MAX_FRICTION_ITERATIONS, given=value_words(value)))
            result["max_iterations"] = value
        pair_keys = {pair.point for pair in revolutes} | {pair.key for pair in revolutes}
        pair_keys |= {pair.key for pair in slides}
        pairs = {}
        for name, props in self.table(table.get("pairs", {}), "friction.pairs").items():
            key = f"friction.pairs.{name}"
            if name not in pair_keys:
                raise self.error(key, message("unknown pair '{pair}'{hint}", pair=name,
                                              hint=did_you_mean(name, pair_keys)))
            props = self.table(props, key)
            self.only_keys(props, ("f", "pin_radius"), key)
            pairs[name] = {k: self.number(v, f"{key}.{k}", non_negative=True,
                                          limit=limits[k][0], what=limits[k][1])
                           for k, v in props.items()}
            if "pin_radius" in pairs[name]:
                self.not_tiny(pairs[name]["pin_radius"], f"{key}.pin_radius")
        result["pairs"] = pairs
        return result

    def plan(self, data: Mapping[str, Any], mechanism: Mechanism) -> PlanSettings:
        table = self.table(data.get("plan", {}), "plan")
        self.only_keys(table, PLAN_KEYS, "plan")
        values: dict[str, Any] = {}
        for drawn, direct in (("crank_mm", "mu_l"), ("velocity_mm", "mu_v"),
                              ("acceleration_mm", "mu_a"), ("force_mm", "mu_f")):
            if drawn in table and direct in table:
                raise self.error(f"plan.{direct}", message(
                    "give either {drawn} or {direct}, not both", drawn=drawn, direct=direct))
            if direct in table:
                values[direct] = self.number(table[direct], f"plan.{direct}", positive=True)
                values[drawn] = None
            elif drawn in table:
                values[drawn] = self.number(table[drawn], f"plan.{drawn}", positive=True)
        if "scale_point" in table:
            point = self.string(table["scale_point"], "plan.scale_point")
            drive_points = mechanism.links[mechanism.drive.link].points
            if point not in drive_points or point == mechanism.drive.pivot:
                raise self.error("plan.scale_point", message(
                    "'{point}' must be a point of the drive link '{link}' other than its pivot",
                    point=point, link=mechanism.drive.link))
            values["scale_point"] = point
        if "precision_mm" in table:
            values["precision_mm"] = self.number(table["precision_mm"], "plan.precision_mm",
                                                 non_negative=True)
        if "min_angle_deg" in table:
            values["min_angle_deg"] = self.number(table["min_angle_deg"], "plan.min_angle_deg",
                                                  non_negative=True)
        if "exact_mm" in table:
            values["exact_mm"] = self.flag(table["exact_mm"], "plan.exact_mm")
        return PlanSettings(**values)

    def ask(self, data: Mapping[str, Any], mechanism: Mechanism) -> Ask:
        if "ask" not in data:
            return Ask(everything=True, forces=bool(mechanism.masses or mechanism.loads))
        table = self.table(data["ask"], "ask")
        self.only_keys(table, ASK_KEYS, "ask")
        points = {p for link in mechanism.links.values() for p in link.points}
        values: dict[str, Any] = {}
        for name in ("velocity", "acceleration", "curvature"):
            values[name] = tuple(self.point_ref(item, f"ask.{name}[{i}]", points, mechanism)
                                 for i, item in enumerate(self.names(table, name)))
        for name in ("omega", "epsilon"):
            items = self.names(table, name)
            for i, item in enumerate(items):
                if item not in mechanism.links:
                    raise self.error(f"ask.{name}[{i}]", _unknown_link(item, mechanism.links))
            values[name] = tuple(items)
        keys = [pair.key for pair in mechanism.slides]
        items = self.names(table, "sliding")
        for i, item in enumerate(items):
            if item not in keys:
                raise self.error(f"ask.sliding[{i}]", message(
                    "no prismatic pair '{pair}'{hint}; the pairs are {pairs}", pair=item,
                    hint=did_you_mean(item, keys), pairs=str(keys)) if keys else message(
                    "no prismatic pair '{pair}'{hint}; the pairs are none", pair=item,
                    hint=did_you_mean(item, keys)))
        values["sliding"] = tuple(items)
        values["forces"] = self.flag(table.get("forces", False), "ask.forces")
        return Ask(**values)

    def names(self, table: Mapping[str, Any], name: str) -> list[str]:
        items = table.get(name, [])
        if isinstance(items, str):
            items = [items]
        if not isinstance(items, list):
            raise self.error(f"ask.{name}", message("must be a list of names, got {given}",
                                                    given=value_words(items)))
        for i, item in enumerate(items):
            self.string(item, f"ask.{name}[{i}]")
        return items

    def point_ref(self, item: str, key: str, points, mechanism: Mechanism) -> str:
        """A point name, or ``X@link`` for the point of ``link`` coincident with X."""
        name, _, link = item.partition("@")
        if name not in points:
            raise self.error(key, _unknown_point(name, points))
        if link and link not in mechanism.links:
            raise self.error(key, _unknown_link(link, mechanism.links))
        return item


# -- the exercise written as drawn --------------------------------------------------------------
# An exercise may give every point's global position at drive.angle ([points], m) and each link
# as the list of its points; a slide's `direction` is then global too, and so is a centre of
# mass S. The functions below turn those tables into the link-frame form that the rest of this
# module reads (docs/exercise-file.md, "The as-drawn form"). Each link's frame is derived:
#   * frame: the global axes;
#   * the drive link: origin at its pivot, +x at drive.angle (its pin must be drawn there);
#   * a link that slides (the `link` of a [[slide]]): origin at its first point, +x along the
#     slide's direction (the contract: a sliding link's +x axis stays along its guide);
#   * any other link: origin at its first point, +x toward the next point drawn apart from it
#     (along global +x if there is none).
# Every point not on the frame is also a sketched point, so the solver takes, group by group,
# the assembly nearest the drawing: the one drawn.

#: as drawn, a point may be off the line it must lie on (the crank pin off the ray at
#: drive.angle, a slide's point off its guide) by this share of the drawing's size
DRAWN_TOLERANCE = 1e-6


def is_drawn(data: Mapping[str, Any]) -> bool:
    """True if exercise tables are written as drawn (they have a ``[points]`` table).

    >>> is_drawn({"points": {"A": [0, 0]}}), is_drawn({"links": {}})
    (True, False)
    """
    return "points" in data


def frames_from_drawn(data: Mapping[str, Any], *, file: str | None = None) -> dict[str, Any]:
    """The tables of an exercise written as drawn, in the link-frame form (tables in the
    link-frame form are returned as they are).

    Every link gets its own frame (origin and +x axis, see the comment above this function in
    the source and docs/exercise-file.md), its points their coordinates in it, each slide its
    ``direction`` in the frame of ``along``, each centre of mass ``S`` its coordinates in its
    link's frame, and ``[sketch]`` the drawn positions of every point not on the frame, so
    that the assembly is the drawn one.

    Raises
    ------
    SpecError
        If a link names a point that is not drawn, a drawn point belongs to no link, the crank
        is not drawn at ``drive.angle`` (naming both angles), a slide's point is drawn off its
        guide (with the distance), or the tables mix the two forms.

    Examples
    --------
    >>> tables = frames_from_drawn({
    ...     "drive": {"link": "AB", "pivot": "A", "angle": 90, "omega": 10},
    ...     "points": {"A": [0, 0], "B": [0, 0.05], "C": [0.2, 0]},
    ...     "links": {"frame": ["A"], "AB": ["A", "B"], "BC": ["B", "C"], "slider": ["C"]},
    ...     "slide": [{"link": "slider", "along": "frame", "through": "A"}]})
    >>> [round(value, 12) for value in tables["links"]["AB"]["B"]]
    [0.05, 0.0]
    >>> tables["links"]["BC"]["C"][1], tables["sketch"]
    (0.0, {'B': [0.0, 0.05], 'C': [0.2, 0.0]})
    >>> frames_from_drawn({"drive": {"link": "AB", "pivot": "A", "angle": 80},
    ...     "points": {"A": [0, 0], "B": [0, 0.05]},
    ...     "links": {"frame": ["A"], "AB": ["A", "B"]}}, file="x.toml")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: x.toml: drive.angle: the crank AB is drawn at 90°, but ...
    """
    if not is_drawn(data):
        links = data.get("links")
        for name, value in (links.items() if isinstance(links, Mapping) else ()):
            if isinstance(value, list):
                raise SpecError(message("a list of point names needs the [points] table "
                                        "(their positions as drawn)"), file=file,
                                key=f"links.{name}")
        return dict(data)
    return _Drawing(_Reader(file), data).tables()


def drawing_size(points) -> float:
    """The larger side of the box around points (m), at least 1 mm: the scale of a drawing's
    tolerances.

    >>> drawing_size([(0, 0), (0.2, 0.05)]), drawing_size([])
    (0.2, 0.001)
    """
    coordinates = np.array(list(points), dtype=float).reshape(-1, 2)
    if not len(coordinates):
        return 1e-3
    return max(1e-3, float(np.max(np.ptp(coordinates, axis=0))))


class _Drawing:
    """Reads the as-drawn tables (see :func:`frames_from_drawn`) with a reader's checks."""

    def __init__(self, reader: _Reader, data: Mapping[str, Any]) -> None:
        self.reader, self.data = reader, data
        self.points = self.read_points()
        self.lists = self.read_links()
        self.size = self.drawing_size()

    # -- reading ----------------------------------------------------------------------------
    def read_points(self) -> dict[str, np.ndarray]:
        table = self.reader.table(self.data["points"], "points")
        points = {}
        for name, xy in table.items():
            if not POINT_NAME.match(name):
                raise self.reader.error(f"points.{name}", _POINT_NAME_WORDS)
            points[name] = np.array(self.reader.coordinates(xy, f"points.{name}"))
        return points

    def read_links(self) -> dict[str, list[str]]:
        if "links" not in self.data:
            raise self.reader.error("links", message("missing the [links] table (each link as "
                                                     "the list of its points)"))
        table = self.reader.table(self.data["links"], "links")
        lists: dict[str, list[str]] = {}
        for name, names in table.items():
            key = f"links.{name}"
            if isinstance(names, Mapping):
                raise self.reader.error(key, message(
                    "with [points] (the exercise written as drawn) a link is the list of its "
                    "points, e.g. {example}",
                    example=f"{name} = {list(names)!r}".replace("'", '"')))
            if not isinstance(names, list):
                raise self.reader.error(key, message("must be a list of point names, got "
                                                     "{given}", given=value_words(names)))
            for index, point in enumerate(names):
                point = self.reader.string(point, f"{key}[{index}]")
                if point not in self.points:
                    raise self.reader.error(f"{key}[{index}]", message(
                        "'{point}' is not drawn in [points]{hint}", point=point,
                        hint=did_you_mean(point, self.points)))
                if point in names[:index]:
                    raise self.reader.error(f"{key}[{index}]", message(
                        "'{point}' is listed twice", point=point))
            lists[name] = list(names)
        used = {point for names in lists.values() for point in names}
        for point in self.points:
            if point not in used:
                raise self.reader.error(f"points.{point}",
                                        message("is not a point of any link"))
        return lists

    def drawing_size(self) -> float:
        return drawing_size(self.points.values())

    def drive(self) -> tuple[str, str, float] | None:
        """(link, pivot, angle) when ``[drive]`` names them well enough to draw the crank's
        frame (anything less is left to the link-frame reader's messages)."""
        table = self.data.get("drive")
        if not isinstance(table, Mapping) or "angle" not in table:
            return None
        link, pivot = table.get("link"), table.get("pivot")
        if not (isinstance(link, str) and link in self.lists and link != FRAME
                and isinstance(pivot, str) and pivot in self.lists[link]):
            return None
        angle = self.reader.number(table["angle"], "drive.angle", limit=MAX_ANGLE_DEG,
                                   what=_DEGREES)
        return link, pivot, angle

    def slides(self) -> list[tuple[int, Mapping[str, Any], str, str, float]]:
        """(number, table, link, along, direction) of each well-formed [[slide]] table."""
        raw = self.data.get("slide", [])
        raw = [raw] if isinstance(raw, Mapping) else raw
        found = []
        for number, table in enumerate(raw if isinstance(raw, list) else [], start=1):
            if not isinstance(table, Mapping):
                continue
            link, along = table.get("link"), table.get("along")
            if (isinstance(link, str) and isinstance(along, str) and link in self.lists
                    and along in self.lists and link != along and self.lists[link]):
                direction = self.reader.number(table.get("direction", 0.0),
                                               f"slide[{number}].direction")
                found.append((number, table, link, along, direction))
        return found

    # -- the frames -------------------------------------------------------------------------
    def frames(self) -> dict[str, tuple[np.ndarray, np.ndarray, float]]:
        """Each link's frame: (origin, axis, angle in degrees); a point's coordinates in it
        are (axis · r, axis × r) / |axis| with r from the origin."""
        frames: dict[str, tuple[np.ndarray, np.ndarray, float]] = {}
        if FRAME in self.lists:
            frames[FRAME] = (np.zeros(2), np.array([1.0, 0.0]), 0.0)
        drive = self.drive()
        if drive is not None:
            link, pivot, angle = drive
            frames[link] = (self.points[pivot], unit_angle(math.radians(angle)), angle)
            self.check_crank(link, pivot, angle)
        for number, _, link, _, direction in self.slides():
            if link in frames:
                self.check_turn(number, link, direction, frames[link][2])
                continue
            origin = self.points[self.lists[link][0]]
            frames[link] = (origin, unit_angle(math.radians(direction)), direction)
        for link, names in self.lists.items():
            if link in frames or not names:
                continue
            origin = self.points[names[0]]
            axis = next((self.points[p] - origin for p in names[1:]
                         if float(norm(self.points[p] - origin)) > 0), None)
            if axis is None:
                frames[link] = (origin, np.array([1.0, 0.0]), 0.0)
            else:
                frames[link] = (origin, axis, angle_deg(axis))
        return frames

    def check_crank(self, link: str, pivot: str, angle: float) -> None:
        """The drive link's pin (``plan.scale_point``, else its first point after the pivot)
        must be drawn on the ray from the pivot at ``drive.angle``."""
        names = self.lists[link]
        plan = self.data.get("plan")
        chosen = plan.get("scale_point") if isinstance(plan, Mapping) else None
        pin = chosen if chosen in names and chosen != pivot else next(
            (p for p in names if p != pivot), None)
        if pin is None:
            return
        arm = self.points[pin] - self.points[pivot]
        if float(norm(arm)) == 0:
            raise self.reader.error(f"points.{pin}", message(
                "the crank pin {pin} is drawn on the pivot {pivot}", pin=pin, pivot=pivot))
        axis = unit_angle(math.radians(angle))
        if (float(dot(axis, arm)) <= 0
                or abs(float(cross(axis, arm))) > DRAWN_TOLERANCE * self.size):
            drawn = angle_deg(arm)
            drawn += 360.0 * round((angle - drawn) / 360.0)
            drawn, angle = _decimals_apart(drawn, angle)
            raise self.reader.error("drive.angle", message(
                "the crank {pivot}{pin} is drawn at {drawn:f}°, but drive.angle is {angle:f}°",
                pivot=pivot, pin=pin, drawn=drawn, angle=angle))

    def check_turn(self, number: int, link: str, direction: float, angle: float) -> None:
        """A link already turned (the frame, the crank, or sliding on an earlier guide) must
        have its +x axis along this slide too (the contract: a sliding link's +x axis stays
        along its guide)."""
        if abs((direction - angle + 180.0) % 360.0 - 180.0) > 1e-9:
            direction, angle = _decimals_apart(direction, angle)
            raise self.reader.error(f"slide[{number}].direction", message(
                "'{link}' would slide at {direction:f}°, but its +x axis is at {angle:f}° (a "
                "sliding link's +x axis stays along its guide)", link=link,
                direction=direction, angle=angle))

    def check_guides(self) -> None:
        """Each slide's point lies on its guide: the line through ``through`` at
        ``direction`` (a one-line error with the distance if it does not)."""
        for number, table, link, along, direction in self.slides():
            through, point = table.get("through"), table.get("point")
            if point is None and len(self.lists[link]) == 1:
                point = self.lists[link][0]
            if through not in self.lists[along] or point not in self.lists[link]:
                continue   # the link-frame reader names what is missing
            offset = abs(float(cross(unit_angle(math.radians(direction)),
                                     self.points[point] - self.points[through])))
            allowed = DRAWN_TOLERANCE * self.size
            if offset > allowed:
                raise self.reader.error(f"slide[{number}].point", message(
                    "{point} is drawn {offset:.3g} m off its guide, the line through {through} "
                    "at {direction:g}° (at most {allowed:.1g} m is allowed)", point=point,
                    offset=offset, through=through, direction=direction, allowed=allowed))

    # -- the link-frame tables --------------------------------------------------------------
    def tables(self) -> dict[str, Any]:
        if "sketch" in self.data:
            raise self.reader.error("sketch", message("an exercise written as drawn is "
                                                      "assembled as drawn: it takes no [sketch]"))
        frames = self.frames()
        self.check_guides()

        def local(link: str, position: np.ndarray) -> list[float]:
            origin, axis, _ = frames[link]
            if link == FRAME:
                return [float(position[0]), float(position[1])]
            arm, length = position - origin, float(norm(axis))
            return [float(dot(axis, arm)) / length, float(cross(axis, arm)) / length]

        out = {key: value for key, value in self.data.items() if key != "points"}
        out["links"] = {link: {p: local(link, self.points[p]) for p in names}
                        for link, names in self.lists.items()}
        slides = self.data.get("slide")
        if isinstance(slides, list | Mapping):
            turned = {number: frames[along][2] - direction
                      for number, _, _, along, direction in self.slides()}
            out["slide"] = [dict(table, direction=-turned[number]) if number in turned else table
                            for number, table in enumerate(
                                [slides] if isinstance(slides, Mapping) else slides, start=1)]
        masses = self.data.get("mass")
        if isinstance(masses, Mapping):
            out["mass"] = {link: self.mass(link, table, local) for link, table in masses.items()}
        fixed = self.lists.get(FRAME, [])
        out["sketch"] = {p: [float(x) for x in self.points[p]] for link, names in
                         self.lists.items() if link != FRAME for p in names if p not in fixed}
        return out

    def mass(self, link: str, table: Any, local) -> Any:
        """A ``[mass.X]`` table with its drawn centre of mass ``S`` in the link's frame."""
        if not (isinstance(table, Mapping) and "S" in table and link in self.lists):
            return table
        where = np.array(self.reader.coordinates(table["S"], f"mass.{link}.S"))
        return dict(table, S=local(link, where))
