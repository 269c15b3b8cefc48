"""The exercise as the studio's page sends it: its tables as data, written as TOML by Python.

The page edits an exercise as drawn — ``title``, ``points`` {name: [x, y]}, ``links`` {name:
[points]}, ``slide`` [{link, along, through, direction, point}], ``drive``, ``plan``, ``ask``,
and every other table of the file it opened, kept as it came — and sends those tables as JSON
(``"exercise": {…}``). Python writes the TOML the server reads (:func:`exercise_toml`, with the
exercise files' one writer, :func:`planmethod.grading.templates.to_toml`): no script writes
TOML, and a text that TOML would read otherwise (a quote, a backslash, DEL, a line break) is
written so that it reads back equal. :func:`with_toml` turns a request's ``exercise`` into the
``toml`` every route reads.

Examples
--------
>>> print(exercise_toml({"title": "", "points": {"A": [0, 0]}, "slide": [], "ask": {}}))
title = "Mechanism"
<BLANKLINE>
[points]
A = [0, 0]
<BLANKLINE>
>>> with_toml({"exercise": {"title": "say \\"hi\\"\\u007f"}, "angle": 30})["toml"]
'title = "say \\\\"hi\\\\"\\\\u007f"\\n'
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Any

from ..errors import SpecError, value_text
from ..words import message, render

__all__ = ["exercise_toml", "with_toml"]

#: tables the page leaves empty when there is nothing in them (a drawing without a slider
#: asks nothing of one)
_EMPTY_LEFT_OUT = ("slide", "ask")
#: how deep the tables of an exercise go (``ask.velocity[0]``, ``mass.BC.S[1]``)
MAX_DEPTH = 6
#: the largest whole number TOML holds
_LARGEST = 2**63 - 1


def _key(name: str) -> str:
    """A table's key as an error names it: bare as TOML writes it bare, else quoted."""
    return name if re.fullmatch(r"[A-Za-z0-9_-]+", name) else value_text(name, limit=40)


def _checked(value: Any, key: str, depth: int = 0) -> Any:
    """``value`` as TOML can hold it, or a :class:`SpecError` naming its ``key``."""
    if depth > MAX_DEPTH:
        raise SpecError(message("nested more than {depth} deep", depth=MAX_DEPTH), key=key)
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        if abs(value) > _LARGEST:
            raise SpecError(message("a whole number beyond 64 bits"), key=key)
        return value
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SpecError(message("not a finite number"), key=key)
        return value
    if isinstance(value, str):
        if any(0xD800 <= ord(character) <= 0xDFFF for character in value):
            raise SpecError(message("a lone surrogate is not a character"), key=key)
        return value
    if isinstance(value, list):
        return [_checked(item, f"{key}[{index}]", depth + 1) for index, item in enumerate(value)]
    if isinstance(value, Mapping):
        return {str(name): _checked(item, f"{key}.{_key(str(name))}", depth + 1)
                for name, item in value.items()}
    raise SpecError(message("null or an empty value: give a value or leave the key out"),
                    key=key)


def exercise_toml(data: Any) -> str:
    """The TOML of the exercise the page sends (its tables, as drawn). An empty title is the
    default title; an empty ``slide`` or ``ask`` and a key whose value is null are left out.

    Raises
    ------
    SpecError
        If ``data`` is not a table, or holds what TOML cannot (null inside a table, a number
        beyond 64 bits, a lone surrogate), naming the key.
    """
    from ..grading.templates import to_toml

    if not isinstance(data, Mapping):
        raise SpecError(message("must be a table (a JSON object) of the exercise's tables"),
                        key="exercise")
    tables: dict[str, Any] = {"title": data.get("title") or render(message("Mechanism"))}
    for name, value in data.items():
        if name == "title" or value is None or (name in _EMPTY_LEFT_OUT and not value):
            continue
        tables[name] = _checked(value, f"exercise.{_key(str(name))}")
    tables["title"] = _checked(tables["title"], "exercise.title")
    return to_toml(tables)


def with_toml(fields: Mapping[str, Any]) -> dict[str, Any]:
    """A request's fields with the page's ``exercise`` written as the ``toml`` the routes
    read (a request gives one or the other)."""
    if "exercise" not in fields:
        return dict(fields)
    if "toml" in fields:
        raise SpecError(message("give the exercise once: as data ({data}) or as text ({text})",
                                data="exercise", text="toml"), key="exercise")
    out = {name: value for name, value in fields.items() if name != "exercise"}
    out["toml"] = exercise_toml(fields["exercise"])
    return out
