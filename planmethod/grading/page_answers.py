"""Answers downloaded from the workbook page: one student's answers at one crank angle, with
the exercise they are for and the answers the page showed before the file was downloaded.

The file is the one-student JSON of :mod:`planmethod.grading.answers` inside an envelope::

    {"format": "planmethod-answers", "version": 1, "title": "…", "exercise": "<digest>",
     "angle": 60, "answers": {"v_C": "5.27", …}, "revealed": ["omega_BC"]}

``revealed`` lists the question ids whose right values the page showed at ``angle`` (the
file's angle). The answers are graded against the key of that angle, built from the exercise
the key keeps, as a drawing downloaded from the page is (:func:`key_for_answers`); a file of
another exercise is refused in one line. An older answers file (CSV, or JSON without the
envelope) is read as before and says nothing of what was revealed.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import SpecError, about
from ..io import read_text_bounded
from ..spec import parse_json
from ..words import Message, message
from .answers import ANSWERS_FORMAT, MAX_ANSWER_BYTES
from .drawings import exercise_digest, key_at_angle, page_drawing

__all__ = ["PageAnswers", "key_for_answers", "page_answers", "read_page_answers",
           "revealed_answers_note"]


@dataclass(frozen=True)
class PageAnswers:
    """What an answers file from the workbook page says besides the answers: the exercise's
    ``title`` and digest (``exercise``), the crank ``angle`` (deg) the answers are at, and the
    question ids whose right values the page showed (``revealed``)."""

    title: str
    exercise: str | None
    angle: float
    revealed: tuple[str, ...]
    source: str | None = None


def page_answers(parsed: Any, source: str | None = None) -> PageAnswers | None:
    """The page's envelope of a parsed answers JSON; None for any other answers file.

    >>> page_answers({"format": "planmethod-answers", "title": "T", "angle": 30,
    ...               "answers": {}, "revealed": ["v_C"]}).revealed
    ('v_C',)
    >>> page_answers({"s01": {"v_C": 5.2}}) is None
    True

    Raises
    ------
    SpecError
        In one line, naming the field, for a title, digest, angle or ``revealed`` that is
        not what the page writes.
    """
    if not isinstance(parsed, Mapping) or parsed.get("format") != ANSWERS_FORMAT:
        return None
    # the envelope's title, digest, angle and revealed are read as a page's drawing's are
    drawing = page_drawing(parsed, {}, None, source)
    return PageAnswers(str(drawing.title), drawing.exercise, float(drawing.angle),
                       drawing.revealed, source)


def read_page_answers(path: str | Path) -> PageAnswers | None:
    """The page's envelope of the answers file at ``path`` (:func:`page_answers`); None for a
    CSV or an answers JSON without it."""
    path = Path(path)
    text = read_text_bounded(path, MAX_ANSWER_BYTES, encoding="utf-8-sig")
    if not text.lstrip().startswith("{"):
        return None
    return page_answers(parse_json(text, file=str(path), unique_keys=True), str(path))


def key_for_answers(key: Mapping[str, Any], page: PageAnswers) -> Mapping[str, Any]:
    """The key the page's answers are graded against: the key of the same exercise at the
    answers' angle (:func:`~planmethod.grading.drawings.key_at_angle`, as a page drawing's
    key is found).

    Raises
    ------
    SpecError
        In one line, if the answers name another exercise than the key's, or the key keeps
        no exercise to pose at another angle.
    """
    title = key.get("title")
    if title is not None and page.title != title:
        raise SpecError(message("the answers are of {given!r}, the key of {title!r}: grade "
                                "them against the key of their own exercise",
                                given=page.title, title=title), file=page.source)
    from .keys import key_exercise

    exercise = key_exercise(key)
    if page.exercise is not None and exercise is not None \
            and exercise_digest(exercise) != page.exercise:
        raise SpecError(message("the answers were given on the page of another version of "
                                "{title!r}: grade them against the exercise its page was "
                                "made from", title=title), file=page.source)
    with about(page.source, key="angle"):   # e.g. cannot be assembled at that angle
        return key_at_angle(key, page.angle)


def revealed_answers_note(revealed: Sequence[str], key: Mapping[str, Any]) -> Message:
    """What a grader is told of the answers the page showed, by their course symbols.

    >>> from planmethod.words import render
    >>> render(revealed_answers_note(["omega_BC"], {"questions": [{"id": "omega_BC",
    ...                                                            "symbol": "ω₂"}]}))
    'the page showed the right values of these before the answers were downloaded: ω₂'
    """
    symbols = {question.get("id"): question.get("symbol") or question.get("id")
               for question in key.get("questions", []) if isinstance(question, Mapping)}
    return message("the page showed the right values of these before the answers were "
                   "downloaded: {symbols}", symbols=", ".join(str(symbols.get(name, name))
                                                              for name in revealed))
