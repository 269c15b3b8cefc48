"""A sentence as data: a message template with named fields, made text only by rendering.

Every sentence planmethod shows a person — a report's line, an error, a construction step, a
figure's legend, a sheet's question, the grader's feedback — is a :class:`Message`: an English
template with named fields (``"through {point}: {vector} ⟂ {link}"``) and the values of those
fields. Layers that compute make messages; only :func:`planmethod.words.render.render` turns
one into text, in the course's language (:mod:`planmethod.words.language`), through the
translation catalogue whose keys are these very templates.

A field's value is text shown as it is (a point's name, a symbol), a number (formatted with
the template's format specification and the language's decimal sign), another message
(rendered in turn), or a list or tuple of those (joined with commas).

Examples
--------
>>> note = message("{count} draws rejected", count=4)
>>> note.template, note.field("count")
('{count} draws rejected', 4)
>>> plural("{count} variant", "{count} variants", count=3).forms
('{count} variant', '{count} variants')
>>> template("speed of {point}").replace(point="C").values
{'point': 'C'}
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["Message", "message", "plural", "template"]


@dataclass(frozen=True, slots=True)
class Message:
    """A template and its fields, not yet text.

    Parameters
    ----------
    template
        The English sentence with ``{named}`` fields; the key of its translations.
    fields
        The fields' values, as ``(name, value)`` pairs in the order given.
    plural_template
        For a sentence that depends on a number: its English plural form (``template`` is
        the singular); the catalogue holds each language's forms.
    count
        The field whose value chooses the plural form.
    context
        A word that tells two equal English templates apart for a translator (``"unit"``).
    """

    template: str
    fields: tuple[tuple[str, Any], ...] = ()
    plural_template: str | None = None
    count: str | None = None
    context: str | None = None

    @property
    def forms(self) -> tuple[str, ...]:
        """The English forms: the template, and its plural if it has one."""
        return (self.template,) if self.plural_template is None else (
            self.template, self.plural_template)

    @property
    def values(self) -> dict[str, Any]:
        """The fields as a dictionary."""
        return dict(self.fields)

    def field(self, name: str) -> Any:
        """The value of one field (``KeyError`` if the message has none of that name)."""
        for key, value in self.fields:
            if key == name:
                return value
        raise KeyError(name)

    def replace(self, **fields: Any) -> Message:
        """The same message with some fields' values replaced or added."""
        merged = {**self.values, **fields}
        return Message(self.template, tuple(merged.items()), self.plural_template,
                       self.count, self.context)


def message(template: str, /, *, context: str | None = None, **fields: Any) -> Message:
    """A sentence to show a person: ``template`` in English with its ``fields``.

    ``template`` must be a literal string at the call (the catalogue is made by reading the
    calls); its fields are named, never positional.

    Examples
    --------
    >>> message("{file} written", file="out.svg").values
    {'file': 'out.svg'}
    """
    return Message(template, tuple(fields.items()), context=context)


def plural(singular: str, plural_template: str, /, *, count: int, context: str | None = None,
           **fields: Any) -> Message:
    """A sentence whose words follow a number (``1 variant``, ``3 variants``; Russian has
    three forms): ``count`` is both the number that chooses and a field of the templates.

    Examples
    --------
    >>> plural("{count} file", "{count} files", count=1).count
    'count'
    """
    return Message(singular, (("count", count), *fields.items()), plural_template, "count",
                   context)



def template(text: str, /, *, context: str | None = None) -> Message:
    """A sentence whose fields are given later, with :meth:`Message.replace` (a table of
    sentences made once, filled where each is used): ``text`` must be a literal string at
    the call, as :func:`message`'s.

    Examples
    --------
    >>> template("{count} files", context="disk").context
    'disk'
    """
    return Message(text, context=context)
