"""The command line's words: argparse in the course's language (for :mod:`planmethod.cli`,
the commands and the studio's command).

The options' help texts, metavariables and the commands' summaries are messages, rendered
when the parser is built (:func:`said`), in the language the command line speaks. argparse's
own sentences — ``usage:``, the titles of the option lists, the lines of its errors
(``the following arguments are required: file``) — are looked up in the standard library's
gettext domain ``argparse`` at the moment argparse makes them; :func:`argparse_words` routes
those look-ups through this table of messages while the command line parses, and gives them
back after.

A sentence argparse fills with ``%`` placeholders is kept as a template with named fields;
it is rendered with each field standing for its placeholder, so that argparse fills in the
translation as it filled in the English.

Examples
--------
>>> import argparse
>>> with argparse_words():
...     argparse._("the following arguments are required: %s") % "file"
'the following arguments are required: file'
>>> said(message("at most 5 %"))
'at most 5 %%'
"""

from __future__ import annotations

import argparse
import contextlib
from collections.abc import Iterator

from .words import Message, message, plural, render, template

__all__ = ["EXERCISE_FILE", "add_angle_range", "argparse_words", "said"]

#: the help of a command's exercise file (a file format is a name, not a word)
EXERCISE_FILE = message("exercise file ({format})", format="TOML")


def add_angle_range(parser: argparse.ArgumentParser) -> None:
    """``--from`` and ``--to`` (``start``, ``stop``): the crank angles a page or an animation
    shows, a full turn unless given (:func:`planmethod.application.workbook.turn_angles`)."""
    from .application.workbook import FULL_TURN

    degrees = render(message("DEG", context="metavar"))
    parser.add_argument("--from", dest="start", type=float, default=FULL_TURN[0],
                        metavar=degrees,
                        help=said(message("the first frame's crank angle (default 0; with "
                                          "--to, a crank that cannot turn fully)")))
    parser.add_argument("--to", dest="stop", type=float, default=FULL_TURN[1], metavar=degrees,
                        help=said(message("frames up to (not including) this crank angle "
                                          "(default 360)")))


def said(text: Message) -> str:
    """A help text for argparse: rendered, with ``%`` written as argparse reads it."""
    return render(text).replace("%", "%%")


#: argparse's own sentences (the English it looks up) → (ours, each field's placeholder)
_SENTENCES: dict[str, tuple[Message, dict[str, str]]] = {  # words: argparse's keys
    "usage: ": (message("usage: "), {}),
    "positional arguments": (message("positional arguments"), {}),
    "options": (message("options"), {}),
    "show this help message and exit": (message("show this help message and exit"), {}),
    "argument %(argument_name)s: %(message)s": (
        template("argument {argument}: {problem}"),
        {"argument": "%(argument_name)s", "problem": "%(message)s"}),
    "the following arguments are required: %s": (
        template("the following arguments are required: {arguments}"), {"arguments": "%s"}),
    "unrecognized arguments: %s": (template("unrecognized arguments: {arguments}"),
                                   {"arguments": "%s"}),
    "invalid choice: %(value)r (choose from %(choices)s)": (
        template("invalid choice: {value} (choose from {choices})"),
        {"value": "%(value)r", "choices": "%(choices)s"}),
    "invalid %(type)s value: %(value)r": (
        template("invalid {type} value: {value}"), {"type": "%(type)s", "value": "%(value)r"}),
    "expected one argument": (message("expected one argument"), {}),
    "expected at most one argument": (message("expected at most one argument"), {}),
    "expected at least one argument": (message("expected at least one argument"), {}),
    "ambiguous option: %(option)s could match %(matches)s": (
        template("ambiguous option: {option} could match {matches}"),
        {"option": "%(option)s", "matches": "%(matches)s"}),
    "not allowed with argument %s": (template("not allowed with argument {argument}"),
                                     {"argument": "%s"}),
    "one of the arguments %s is required": (
        template("one of the arguments {arguments} is required"), {"arguments": "%s"}),
    "ignored explicit argument %r": (template("ignored explicit argument {value}"),
                                     {"value": "%r"}),
    "unknown parser %(parser_name)r (choices: %(choices)s)": (
        template("unknown command {command} (choices: {choices})"),
        {"command": "%(parser_name)r", "choices": "%(choices)s"}),
}


class _Slot(int):
    """A field's stand-in while a sentence is rendered for argparse: formatted as a mark
    that becomes argparse's placeholder (an ``int``, so that it may choose a plural form)."""

    def __new__(cls, value: int, name: str) -> _Slot:
        slot = super().__new__(cls, value)
        slot.name = name
        return slot

    def __format__(self, specification: str) -> str:
        return f"\x00{self.name}\x00"

    def __str__(self) -> str:
        return f"\x00{self.name}\x00"


def _filled(sentence: Message, places: dict[str, str]) -> str:
    """``sentence`` (its fields :class:`_Slot` marks) rendered with argparse's placeholders
    where its fields are (a ``%`` of its own doubled, as argparse fills it in with ``%``)."""
    text = render(sentence).replace("%", "%%")
    for name, place in places.items():
        text = text.replace(f"\x00{name}\x00", place)
    return text


def _gettext(text: str) -> str:
    found = _SENTENCES.get(text)
    if found is None:
        return text
    sentence, places = found
    return _filled(sentence.replace(**{name: _Slot(0, name) for name in places}), places)


def _ngettext(singular: str, plural_form: str, count: int) -> str:
    if singular == "expected %s argument":
        sentence = plural("expected {count} argument", "expected {count} arguments",
                          count=_Slot(count, "count"))
        return _filled(sentence, {"count": "%s"})
    return singular if count == 1 else plural_form


@contextlib.contextmanager
def argparse_words() -> Iterator[None]:
    """argparse's sentences through the catalogue, in the language spoken, inside the block
    (the parser's titles are made when it is built: build it inside too)."""
    saved = argparse._, argparse.ngettext
    argparse._, argparse.ngettext = _gettext, _ngettext
    try:
        yield
    finally:
        argparse._, argparse.ngettext = saved
