"""The planmethod exception family.

Every error planmethod raises derives from :class:`PlanmethodError` and also from the built-in
exception that fits it (``ValueError`` for bad input, ``ArithmeticError`` for a singular
construction, ``RuntimeError`` for a solver that did not converge). Each error carries its
context as fields (file, key, link, crank angle, …) and builds its one-line message from them,
so that the command line can print it without a traceback.

Examples
--------
>>> from planmethod.errors import SpecError
>>> str(SpecError("must be a finite number, got 'abc'", file="slider.toml", key="drive.angle"))
"slider.toml: drive.angle: must be a finite number, got 'abc'"
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

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
    "limit_words",
]

#: what a computation that met one of Python's own limits says, in one line (no traceback)
LIMIT_WORDS: dict[type[BaseException], str] = {
    OverflowError: "a number is too large to compute with",
    RecursionError: "the input is nested too deeply",
    MemoryError: "the input asks for more memory than there is",
}


def limit_words(error: BaseException) -> str:
    """The line of :data:`LIMIT_WORDS` for ``error`` (of one of its kinds, or a subclass).

    Parameters
    ----------
    error
        An ``OverflowError``, ``RecursionError`` or ``MemoryError``.

    Examples
    --------
    >>> limit_words(OverflowError(34, "Numerical result out of range"))
    'a number is too large to compute with'
    """
    return next(words for kind, words in LIMIT_WORDS.items() if isinstance(error, kind))


def _format_angle(angle: float | None) -> str | None:
    if angle is None:
        return None
    return f"crank angle {float(angle):g}°"


class PlanmethodError(Exception):
    """Base class of every planmethod error.

    Parameters
    ----------
    message
        What is wrong, expected and got.
    file
        The exercise file, when the error comes from one.
    key
        The dotted key in that file (``drive.angle``, ``slide[2].along``).
    link
        The link (or group of links) involved.
    angle
        The crank angle in degrees at which it happened.
    """

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        key: str | None = None,
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
        where = [part for part in (self.file, self.key) if part]
        context = [part for part in (
            # one link, or a group of them joined by ", " (the links of a locked structure)
            f"{'links' if ', ' in self.link else 'link'} {self.link}" if self.link else None,
            _format_angle(self.angle),
        ) if part]
        text = self.message
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

    def under(self, prefix: str) -> PlanmethodError:
        """Return the same error with its key read inside the table ``prefix``: a table of
        one file kept inside another (a key's ``exercise``).

        >>> str(SpecError("too large", file="key.json", key="drive.omega").under("exercise"))
        'key.json: exercise.drive.omega: too large'
        """
        self.key = f"{prefix}.{self.key}" if self.key else prefix
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

    def __init__(self, message: str, *, shortfall: float | None = None, **context) -> None:
        self.shortfall = shortfall
        super().__init__(message, **context)


class ToggleError(PlanmethodError, ArithmeticError):
    """A group is in its own toggle position: its two construction lines are parallel.

    ``line_angle_deg`` is the angle between the two lines in degrees.
    """

    def __init__(self, message: str, *, line_angle_deg: float | None = None, **context) -> None:
        self.line_angle_deg = line_angle_deg
        super().__init__(message, **context)


class ConvergenceError(PlanmethodError, RuntimeError):
    """An iterative solve (Newton for a class III group, friction iteration) did not converge.

    ``residual`` is how far from a solution it stopped.
    """

    def __init__(self, message: str, *, residual: float | None = None, **context) -> None:
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
        raise SpecError(limit_words(error), file=file, key=key) from None
