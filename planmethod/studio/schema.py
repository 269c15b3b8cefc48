"""The shape of every request the studio's page sends: one small typed schema per route.

A schema names a request's fields, the type of each and which are needed; :func:`read_fields`
checks a request's JSON object (or query) against it, in one place for every route: a field of
the wrong type (``"overwrite": "false"`` — text where true or false is meant), a field the
route does not know (a misspelt ``"overwite"``) or a needed field that is missing is a
:class:`~planmethod.errors.SpecError` naming the field, which the server answers with 400.
``null`` is the same as leaving an optional field out. What a value may be beyond its type
(a count's range, a path inside the folder) the route's function checks, with the command
line's limits.

Examples
--------
>>> read_fields({"path": "a.toml", "toml": "title = 'x'", "overwrite": True}, SAVE)
{'path': 'a.toml', 'toml': "title = 'x'", 'overwrite': True, 'template': False}
>>> read_fields({"path": "a.toml", "toml": "", "overwrite": "false"}, SAVE)
Traceback (most recent call last):
...
planmethod.errors.SpecError: overwrite: must be true or false, got the text 'false'
>>> read_fields({"toml": "", "ranges": {"angle": [30, "60", 5]}}, VARIANTS)
Traceback (most recent call last):
...
planmethod.errors.SpecError: ranges.angle[1]: must be a finite number, got the text '60'
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..errors import SpecError
from ..words import Message, message

__all__ = ["CANCEL", "EXPORT", "JOB", "OPEN", "SAVE", "SOLVE", "TURN", "VARIANTS", "Field",
           "read_fields"]

#: what each type of field must be, in the page's words (JSON's), and the test of a value
TYPES = {
    "text": (message("text"), lambda value: isinstance(value, str)),
    "flag": (message("true or false"), lambda value: isinstance(value, bool)),
    "whole": (message("a whole number"),
              lambda value: isinstance(value, int) and not isinstance(value, bool)),
    "number": (message("a finite number"), lambda value: isinstance(value, int | float)
               and not isinstance(value, bool) and math.isfinite(value)),
    "list": (message("a list"), lambda value: isinstance(value, list)),
    "table": (message("a table (a JSON object)"), lambda value: isinstance(value, dict)),
}


@dataclass(frozen=True)
class Field:
    """One field: its type (a key of :data:`TYPES`), whether it is needed, and for a list the
    field each item is, for a table either its own fields or the field every value is (a table
    of names). A field left out is absent from what :func:`read_fields` returns (the route's
    function has its default), except a flag: left out, it is false."""

    type: str
    required: bool = False
    items: Field | None = None
    fields: Mapping[str, Field] | None = None
    values: Field | None = None


def _shown(value: Any) -> Message | str:
    """A value as the message shows it, in JSON's words."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, str):
        return message("the text {text!r}{more}", text=value[:40],
                       more="…" if len(value) > 40 else "")
    if isinstance(value, int | float):
        return message("the number {number}", number=repr(value)[:49])
    return message("a list") if isinstance(value, list) else message("a table")


def _value(value: Any, field: Field, key: str) -> Any:
    """``value`` checked against ``field`` (items and tables within it too)."""
    what, test = TYPES[field.type]
    if not test(value):
        raise SpecError(message("must be {what}, got {value}", what=what, value=_shown(value)),
                        key=key)
    if field.items is not None:
        return [_value(item, field.items, f"{key}[{index}]") for index, item in enumerate(value)]
    if field.fields is not None:
        return read_fields(value, field.fields, where=f"{key}.")
    if field.values is not None:
        return {name: _value(item, field.values, f"{key}.{name}") for name, item in value.items()}
    return value


def read_fields(data: Mapping[str, Any], schema: Mapping[str, Field], *,
                where: str = "") -> dict[str, Any]:
    """The fields of ``data`` that ``schema`` names, each checked (a flag left out: false); a
    :class:`SpecError` naming the field (``where`` + its name) for a wrong type, an unknown
    field or a missing needed one."""
    unknown = [name for name in data if name not in schema]
    if unknown:
        raise SpecError(message("unknown field (the fields here are {fields})",
                                fields=list(schema)), key=f"{where}{unknown[0]}")
    out: dict[str, Any] = {}
    for name, field in schema.items():
        value = data.get(name)
        if value is None:
            if field.required:
                raise SpecError(message("is missing"), key=f"{where}{name}")
            if field.type == "flag":
                out[name] = False
            continue
        out[name] = _value(value, field, f"{where}{name}")
    return out


TEXT, FLAG, WHOLE = Field("text"), Field("flag"), Field("whole")
NEEDED_TEXT = Field("text", required=True)
NUMBERS = Field("list", items=Field("number"))

#: the ranges of a template made of the drawing (``api.make_template``): m, deg, rad/s
RANGES = Field("table", fields={"lengths": Field("table", values=NUMBERS), "angle": NUMBERS,
                                "omega": NUMBERS, "step": Field("number")})

#: ``POST /api/solve`` as JSON: the exercise (the page sends its tables as ``exercise``,
#: which the server writes as this TOML: :mod:`~planmethod.studio.exercise_data`); a
#: ``draft`` is a drag's intermediate step (``api.solve``)
SOLVE = {"toml": NEEDED_TEXT, "draft": FLAG}
#: ``POST /api/open``: a file of the folder
OPEN = {"path": NEEDED_TEXT}
#: ``POST /api/save``: the exercise, or with ``template`` the template made of it
SAVE = {"path": NEEDED_TEXT, "toml": NEEDED_TEXT, "overwrite": FLAG, "template": FLAG,
        "ranges": RANGES}
#: ``POST /api/turn``: the drawing turned to a crank angle
TURN = {"toml": NEEDED_TEXT, "angle": Field("number", required=True)}
#: ``POST /api/variants``: a job drawing variants and their task sheets
VARIANTS = {"toml": NEEDED_TEXT, "ranges": RANGES, "count": WHOLE, "seed": WHOLE}
#: ``POST /api/export``: a job writing a whole teaching run into a new folder
EXPORT = {"toml": NEEDED_TEXT, "ranges": RANGES, "folder": NEEDED_TEXT,
          "formats": Field("list", items=TEXT), "count": WHOLE, "seed": WHOLE}
#: ``GET /api/job?id=…`` (a query: its values are text) and ``POST /api/cancel``
JOB = CANCEL = {"id": NEEDED_TEXT}
