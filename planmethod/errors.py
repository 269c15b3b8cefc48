"""The planmethod exception family.

Every error planmethod raises derives from :class:`PlanmethodError` and also from the built-in
exception that fits it (``ValueError`` for bad input, ``ArithmeticError`` for a singular
construction, ``RuntimeError`` for a solver that did not converge). Each error carries its
context as fields (file, key, link, crank angle, …) and builds its one-line message from them,
so that the command line can print it without a traceback.

Examples
--------
>>> from planmethod.errors import SpecError
>>> from planmethod.words import message
>>> str(SpecError(message("must be a finite number, got '{given}'", given="abc"),
...               file="slider.toml", key="drive.angle", angle=45))
"slider.toml: drive.angle: crank angle 45°: must be a finite number, got 'abc'"
"""

from __future__ import annotations

import contextlib
import datetime
import math
from collections.abc import Iterator, Mapping

from .words.message import Message, message, plural, template
from .words.render import render

__all__ = [
    "LIMIT_WORDS",
    "AssemblyError",
    "BranchJumpError",
    "ConvergenceError",
    "ForceError",
    "PlanmethodError",
    "SpecError",
    "StructureError",
    "ToggleError",
    "about",
    "limit_message",
    "limit_words",
    "value_text",
    "value_words",
]

#: what a computation that met one of Python's own limits says, in one line (no traceback)
LIMIT_WORDS: dict[type[BaseException], Message] = {
    OverflowError: message("a number is too large to compute with"),
    RecursionError: message("the input is nested too deeply"),
    MemoryError: message("the input asks for more memory than there is"),
}

#: the longest description of a value an error gives (characters; a longer one is cut with …)
VALUE_TEXT_LIMIT = 60


def value_words(value: object, limit: int = VALUE_TEXT_LIMIT) -> Message | str:
    """A value read from a file, as an error's "got …" says it, in the file's words: text in
    quotes (its control characters escaped), a number, ``true`` or ``false``, ``null``, a
    date or time with its kind (``a date-time 1979-05-27T07:32:00``), a list or a table
    written inline — cut at about ``limit`` characters with an ellipsis, so that a value of a
    megabyte gives a line of an error. The file's own words are text; what is said of the
    value (its kind, a whole number too long to write) is a message.

    Parameters
    ----------
    value
        What the file gave (as tomllib or json read it).
    limit
        The most characters of it written (default :data:`VALUE_TEXT_LIMIT`).

    Examples
    --------
    >>> value_words("fast"), render(value_words(10 ** 100 ** 2))
    ("'fast'", 'a whole number of 10001 digits')
    """
    kinds = ((datetime.datetime, template("a date-time {value}")),
             (datetime.date, template("a date {value}")),
             (datetime.time, template("a time {value}")))
    kind = next((words for kind, words in kinds if isinstance(value, kind)), None)
    if isinstance(value, str) and len(value) > limit:
        return repr(value[:limit]) + "…"
    said = _said(value)
    if said is not None:
        return said
    written = _written(value, limit + 1)
    text = written if len(written) <= limit else written[:limit] + "…"
    return kind.replace(value=text) if kind is not None else text


def value_text(value: object, limit: int = VALUE_TEXT_LIMIT) -> str:
    """:func:`value_words` as text in the language spoken now.

    Parameters
    ----------
    value
        What the file gave (as tomllib or json read it).
    limit
        The most characters of it written (default :data:`VALUE_TEXT_LIMIT`).

    Examples
    --------
    >>> import datetime
    >>> value_text(datetime.datetime(1979, 5, 27, 7, 32)), value_text(True), value_text(None)
    ('a date-time 1979-05-27T07:32:00', 'true', 'null')
    >>> value_text([0, "x", {"a": 1.5}]), value_text("fast"), value_text(float("nan"))
    ("[0, 'x', {a = 1.5}]", "'fast'", 'nan')
    >>> value_text("x" * 1000, limit=10), value_text(list(range(1000)), limit=10)
    ("'xxxxxxxxxx'…", '[0, 1, 2, …')
    """
    return render(value_words(value, limit))


def _said(value: object) -> Message | None:
    """What is said of a value that is not written as it is: a whole number too long to
    write, a value of no kind a file holds."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 200:
        # Python refuses to write more than 4,300 digits
        digits = math.ceil(value.bit_length() * math.log10(2))
        return plural("a whole number of {count} digit", "a whole number of {count} digits",
                      count=digits)
    if isinstance(value, bool | int | float | str | list | tuple | Mapping | datetime.date
                  | datetime.time) or value is None:
        return None
    return message("a {kind}", kind=type(value).__name__)


def _written(value: object, budget: int) -> str:
    """``value`` written inline, stopping once more than ``budget`` characters are written
    (what is said of an item rather than written, :func:`_said`, in the language spoken
    now: the cut counts its characters)."""
    said = _said(value)
    if said is not None:
        return render(said)
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):
        return repr(value[:budget])
    if isinstance(value, datetime.date | datetime.time):
        return value.isoformat()
    items = value.items() if isinstance(value, Mapping) else value
    parts: list[str] = []
    used = 2
    for item in items:
        if used > budget:
            break
        part = (f"{_key_written(str(item[0]), budget)} = {_written(item[1], budget)}"
                if isinstance(value, Mapping) else _written(item, budget))
        parts.append(part)
        used += len(part) + 2
    opening, closing = "{}" if isinstance(value, Mapping) else "[]"
    return opening + ", ".join(parts) + closing


def _key_written(key: str, budget: int) -> str:
    """A table's key: bare if it may be (letters, digits, ``_`` and ``-``), else quoted."""
    bare = key and all(char.isascii() and (char.isalnum() or char in "_-") for char in key)
    return key[:budget] if bare else repr(key[:budget])


def limit_message(error: BaseException) -> Message:
    """The message of :data:`LIMIT_WORDS` for ``error`` (of one of its kinds, or a subclass).

    Parameters
    ----------
    error
        An ``OverflowError``, ``RecursionError`` or ``MemoryError``.

    Examples
    --------
    >>> render(limit_message(RecursionError()))
    'the input is nested too deeply'
    """
    return next(words for kind, words in LIMIT_WORDS.items() if isinstance(error, kind))


def limit_words(error: BaseException) -> str:
    """:func:`limit_message` as text in the language spoken now.

    Parameters
    ----------
    error
        An ``OverflowError``, ``RecursionError`` or ``MemoryError``.

    Examples
    --------
    >>> limit_words(OverflowError(34, "Numerical result out of range"))
    'a number is too large to compute with'
    """
    return render(limit_message(error))


def _context(link: str | None, angle: float | None) -> list[Message]:
    """Where in the mechanism: the link (or group of links joined by ", ": the links of a
    locked structure) and the crank angle."""
    parts = []
    if link:
        parts.append(message("links {links}", links=link) if ", " in link
                     else message("link {link}", link=link))
    if angle is not None:
        parts.append(message("crank angle {angle:g}°", angle=float(angle)))
    return parts


class PlanmethodError(Exception):
    """Base class of every planmethod error.

    Parameters
    ----------
    message
        What is wrong, expected and got: a :class:`~planmethod.words.Message` (a template
        and its fields, shown in the course's language), or text shown as it is.
    file
        The exercise file, when the error comes from one.
    key
        The dotted key in that file (``drive.angle``, ``slide[2].along``), or where else in
        it (a message: ``line 3``).
    link
        The link (or group of links) involved.
    angle
        The crank angle in degrees at which it happened.
    """

    def __init__(
        self,
        message: Message | str,
        *,
        file: str | None = None,
        key: str | Message | None = None,
        link: str | None = None,
        angle: float | None = None,
    ) -> None:
        self.message = message
        self.file = file
        self.key = key
        self.link = link
        self.angle = angle
        super().__init__(self._text())

    def _text(self) -> str:
        """The one line: file and key, then link and crank angle, then what is wrong — in
        the language spoken now."""
        where = [render(part) for part in (self.file, self.key) if part]
        context = [render(part) for part in _context(self.link, self.angle)]
        text = render(self.message)
        if context:
            text = f"{', '.join(context)}: {text}"
        if where:
            text = f"{': '.join(where)}: {text}"
        return text

    def __str__(self) -> str:
        return self._text()

    def located(self, *, file: str | None = None, key: str | None = None) -> PlanmethodError:
        """Return the same error with a file (and key) attached where they were missing."""
        if file and not self.file:
            self.file = file
        if key and not self.key:
            self.key = key
        self.args = (self._text(),)
        return self

    def noted(self, note: Message | str) -> PlanmethodError:
        """Return the same error with what the user can do about it after what is wrong.

        >>> str(ToggleError("the lines are parallel", angle=120).noted("take another range"))
        'crank angle 120°: the lines are parallel; take another range'
        """
        self.message = message("{problem}; {note}", problem=self.message, note=note)
        self.args = (self._text(),)
        return self

    def under(self, prefix: str) -> PlanmethodError:
        """Return the same error with its key read inside the table ``prefix``: a table of
        one file kept inside another (a key's ``exercise``).

        >>> str(SpecError("too large", file="key.json", key="drive.omega").under("exercise"))
        'key.json: exercise.drive.omega: too large'
        """
        self.key = f"{prefix}.{render(self.key)}" if self.key else prefix
        self.args = (self._text(),)
        return self


class SpecError(PlanmethodError, ValueError):
    """The exercise file (or a value given in code) is malformed or inconsistent."""


class StructureError(PlanmethodError, ValueError):
    """The mechanism's structure is not supported: W ≠ 1, or no decomposition into Assur groups."""


class AssemblyError(PlanmethodError, ValueError):
    """A group cannot be assembled at the given crank angle (a link falls short or overreaches).

    ``shortfall`` is by how much (m) the links fail to reach.
    """

    def __init__(self, message: Message | str, *, shortfall: float | None = None,
                 **context) -> None:
        self.shortfall = shortfall
        super().__init__(message, **context)


class ToggleError(PlanmethodError, ArithmeticError):
    """A group is in its own toggle position: its two construction lines are parallel.

    ``line_angle_deg`` is the angle between the two lines in degrees.
    """

    def __init__(self, message: Message | str, *, line_angle_deg: float | None = None,
                 **context) -> None:
        self.line_angle_deg = line_angle_deg
        super().__init__(message, **context)


class ConvergenceError(PlanmethodError, RuntimeError):
    """An iterative solve (Newton for a class III group, friction iteration) did not converge.

    ``residual`` is how far from a solution it stopped.
    """

    def __init__(self, message: Message | str, *, residual: float | None = None,
                 **context) -> None:
        self.residual = residual
        super().__init__(message, **context)


class BranchJumpError(PlanmethodError, RuntimeError):
    """A sweep would jump from one assembly branch to another between two crank angles."""


class ForceError(PlanmethodError, ArithmeticError):
    """The force system of a group (or of the whole mechanism) is singular or ill-posed."""


@contextlib.contextmanager
def about(file: str | None, key: str | None = None) -> Iterator[None]:
    """``with about(path):`` the errors raised in the block are about ``path`` (and ``key``)
    where they name no file of their own; a number too large to compute with (Python's
    ``OverflowError``, and its other limits of :data:`LIMIT_WORDS`) becomes a
    :class:`SpecError` naming it. A command wraps it round the work on each of its inputs
    after the first (a drawing, an answers file, a coordinates table), so that an error
    names the input it is about, never the exercise the command line would name otherwise.

    Parameters
    ----------
    file
        The input the block works on.
    key
        The key in it the block reads (``angle``), if one.

    Examples
    --------
    >>> with about("plan.json", key="angle"):
    ...     raise SpecError("out of range")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: plan.json: angle: out of range
    >>> with about("plan.json", key="angle"):
    ...     raise SpecError("out of range", file="key.json")
    Traceback (most recent call last):
    ...
    planmethod.errors.SpecError: key.json: out of range
    """
    try:
        yield
    except PlanmethodError as error:
        if error.file:   # about a file of its own (and its own key there)
            raise
        raise error.located(file=file, key=key) from None
    except tuple(LIMIT_WORDS) as error:
        raise SpecError(limit_message(error), file=file, key=key) from None
