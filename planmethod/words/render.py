"""The one place where a sentence becomes text: :func:`render`.

A :class:`~planmethod.words.message.Message` is looked up in the language's catalogue (its
template is the key; a plural's form is chosen by its count, as the language's rule says),
and its fields are filled in: a number with the template's format specification and the
language's decimal sign (``0,002`` in Russian), a message rendered in turn, a list joined with
commas, text as it is. A translation that does not fit its fields (a catalogue written for
another version) is not shown half-filled: the English template is used instead.

Examples
--------
>>> from planmethod.words.message import message, plural
>>> render(message("μl = {scale:g} m/mm", scale=0.002))
'μl = 0.002 m/mm'
>>> render(plural("{count} variant", "{count} variants", count=3))
'3 variants'
>>> render(message("{what}: {where}", what=message("angle"), where=["B", "C"]))
'angle: B, C'
>>> decimal_number("0.002", ",")
'0,002'
"""

from __future__ import annotations

import functools
import numbers
import string
from collections.abc import Mapping, Sequence
from typing import Any

from .language import ENGLISH, catalogue, current
from .message import Message, message

__all__ = ["DECIMAL_SIGN", "decimal_number", "formatted_number", "number_text", "render"]

#: the decimal sign, as a catalogue translates it ("," in Russian)
DECIMAL_SIGN = message(".", context="decimal sign")


def render(text: Message | str, language: str | None = None) -> str:
    """``text`` in ``language`` (default: the one spoken now); a plain string is returned as
    it is (a name, a symbol, text the user wrote)."""
    if not isinstance(text, Message):
        return text
    language = language or current()
    translations, formatter = _speaker(language)
    template = _translated(text, translations, language)
    values = text.values
    try:
        return _filled(formatter, template, values)
    except (KeyError, IndexError, ValueError):
        if template is text.template:
            raise
        return _filled(formatter, _english(text), values)


@functools.lru_cache(maxsize=4096)
def _simple_fields(template: str) -> tuple[tuple[str, str | None, str, str | None], ...] | None:
    """A template as :meth:`string.Formatter.parse` splits it, if every field is a plain
    name with a literal format specification (what :func:`_filled` fills quickly); None
    otherwise (an attribute, an index, a nested field, a template that does not parse).

    >>> _simple_fields("{a:.3g} m/s, {b}")
    (('', 'a', '.3g', None), (' m/s, ', 'b', '', None))
    >>> _simple_fields("{a[0]}") is None, _simple_fields("{") is None
    (True, True)
    """
    try:
        parts = tuple(_PARSER.parse(template))
    except ValueError:
        return None
    for _, name, specification, _ in parts:
        if name is not None and (not name.isidentifier() or "{" in specification):
            return None
    return parts


def _filled(formatter: _Formatter, template: str, values: Mapping[str, Any]) -> str:
    """``formatter.vformat(template, (), values)``, the same text, without
    :class:`string.Formatter`'s generic walk where every field is a plain name with a literal
    format specification (the templates of the catalogues: rendered for every figure)."""
    parts = _simple_fields(template)
    if parts is None:
        return formatter.vformat(template, (), values)
    out = []
    for literal, name, specification, conversion in parts:
        if literal:
            out.append(literal)
        if name is not None:
            value = formatter.convert_field(values[name], conversion)
            out.append(formatter.format_field(value, specification))
    return "".join(out)


#: each language's catalogue with the formatter that writes its numbers (its decimal sign
#: asked of the catalogue once, not once a message): made again when the catalogue is
_SPEAKERS: dict[str, tuple[Any, _Formatter]] = {}


def _speaker(language: str) -> tuple[Any, _Formatter]:
    """``language``'s catalogue and the formatter of its messages."""
    translations = catalogue(language)
    found = _SPEAKERS.get(language)
    if found is None or found[0] is not translations:
        found = _SPEAKERS[language] = (translations,
                                       _Formatter(language, _decimal_sign(language)))
    return found


def _english(text: Message) -> str:
    if text.plural_template is not None and text.field(text.count) != 1:
        return text.plural_template
    return text.template


def _translated(text: Message, translations, language: str) -> str:
    if language == ENGLISH:
        return _english(text)
    if text.plural_template is None:
        if text.context is None:
            return translations.gettext(text.template)
        return translations.pgettext(text.context, text.template)
    count = int(text.field(text.count))
    if text.context is None:
        return translations.ngettext(text.template, text.plural_template, count)
    return translations.npgettext(text.context, text.template, text.plural_template, count)


def _decimal_sign(language: str) -> str:
    if language == ENGLISH:
        return "."
    sign = catalogue(language).pgettext(DECIMAL_SIGN.context, DECIMAL_SIGN.template)
    return sign if sign else "."


def decimal_number(text: str, sign: str) -> str:
    """A number already formatted with a decimal point, written with ``sign`` instead."""
    return text if sign == "." else text.replace(".", sign)


def formatted_number(value: Any, specification: str) -> str:
    """``format(value, specification)``, a zero never written with a minus sign: a −0.0 (or a
    −0.0004 at two decimals) prints as 0, as a reader writes it.

    >>> formatted_number(-0.0, ">6.5g"), formatted_number(-0.0004, ".2f")
    ('     0', '0.00')
    >>> formatted_number(-1e-20, ".3g"), formatted_number(float("-inf"), "g")
    ('-1e-20', '-inf')
    """
    text = format(value, specification)
    body = text.lstrip()
    if body.startswith("-"):
        mantissa = body[1:].partition("e")[0].partition("E")[0].rstrip(" %")
        if "0" in mantissa and set(mantissa) <= set("0.,_"):
            return format(-value, specification)
    return text


def number_text(value: float, specification: str = "g", language: str | None = None) -> str:
    """A number as the language writes it (``number_text(0.25, "g", "ru")`` → ``'0,25'``)."""
    language = language or current()
    return decimal_number(formatted_number(value, specification), _speaker(language)[1].sign)


class _Formatter(string.Formatter):
    """``str.format`` with the fields of a message: named only, numbers in the language's
    writing, messages and lists rendered."""

    def __init__(self, language: str, sign: str) -> None:
        super().__init__()
        self.language, self.sign = language, sign

    def get_value(self, key: int | str, args: Sequence[Any], kwargs: Mapping[str, Any]) -> Any:
        if isinstance(key, int):
            raise KeyError(key)       # a template's fields are named, never positional
        return kwargs[key]

    def format_field(self, value: Any, format_spec: str) -> str:
        if isinstance(value, Message):
            return format(render(value, self.language), format_spec)
        if isinstance(value, (list, tuple)):
            return ", ".join(self.format_field(item, format_spec) for item in value)
        if isinstance(value, numbers.Number) and not isinstance(value, bool):
            return decimal_number(formatted_number(value, format_spec), self.sign)
        return format(value, format_spec)


#: splits templates into literal text and fields (:func:`_simple_fields`)
_PARSER = string.Formatter()
