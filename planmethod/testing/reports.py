"""Two JSON reports compared number by number (``planmethod solve --json``, ``/api/solve``).

Two reports of the same exercise written two ways (link frames and as drawn, or the command line
and the studio) hold the same keys, the same texts and the same numbers to a relative
tolerance. :func:`report_differences` lists where they do not, one line each:

* a vector (a list of numbers: a position, a velocity, a plan point in mm) is compared as a
  whole, relative to the larger of the two lengths, so that a component that is zero in exact
  arithmetic may differ by the noise of the other component's last places;
* an error measure that is already relative (``rel_error``, ``error_estimate``,
  ``power_residual``, ``max_rel_difference``) is compared absolutely, and an ``abs_error``
  relative to its check's exact value — they are both noise of the last places;
* any other number is compared relative to the larger of the two, or to the largest number of
  its kind (its key) in the reports if that is larger: a number that is zero in exact arithmetic
  (the moment of a force through the pole, a component at a dead centre) or is the small
  difference of large ones is known to the last places of its kind's numbers, no better;
* texts must be equal, except the keys in ``ignore`` (by default a branch's ``reason``: a
  drawing pins every assembly, a file without a sketch takes the default).

Examples
--------
>>> first = {"points": {"C": {"velocity": [4.0, 1e-17]}}, "checks": [{"rel_error": 1e-16}]}
>>> second = {"points": {"C": {"velocity": [4.0, 0.0]}}, "checks": [{"rel_error": 0.0}]}
>>> report_differences(first, second)
[]
>>> report_differences(first, {"points": {"C": {"velocity": [4.1, 0.0]}}, "checks": [{}]})
['points.C.velocity: [4.0, 1e-17] against [4.1, 0.0]', 'checks[0]: keys differ: rel_error']
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

__all__ = ["report_differences"]

#: error measures that are relative already: compared absolutely
RELATIVE_MEASURES = frozenset({"rel_error", "error_estimate", "power_residual",
                               "max_rel_difference"})
#: numbers whose kind is measured on another's scale: Zhukovsky's ``difference`` is one of
#: balancing moments (N·m), a centre of curvature a position (m)
SCALE_OF = {"difference": "balancing_moment", "center": "position"}


def _number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _largest(node: Any, by_key: dict[str, float], key: str = "") -> None:
    """The largest magnitude of the numbers under each key name (the scale of that kind)."""
    if _number(node):
        by_key[key] = max(by_key.get(key, 0.0), abs(float(node)))
    elif isinstance(node, Mapping):
        for name, value in node.items():
            _largest(value, by_key, str(name))
    elif isinstance(node, list):
        if node and all(_number(v) for v in node):
            by_key[key] = max(by_key.get(key, 0.0), math.hypot(*map(float, node)))
        else:
            for value in node:
                _largest(value, by_key, key)


def report_differences(first: Any, second: Any, *, rel: float = 1e-12,
                       ignore: tuple[str, ...] = ("reason",)) -> list[str]:
    """Where two reports differ (see the module's rules), one line per difference."""
    floor: dict[str, float] = {}
    _largest(first, floor)
    _largest(second, floor)
    out: list[str] = []
    _compare(first, second, "", "", rel, ignore, floor, out, None)
    return out


def _compare(a: Any, b: Any, path: str, key: str, rel: float, ignore: tuple[str, ...],
             floor: Mapping[str, float], out: list[str], analytic: float | None) -> None:
    if isinstance(a, Mapping) and isinstance(b, Mapping):
        if set(a) != set(b):
            keys = sorted(set(a) ^ set(b))
            out.append(f"{path}: keys differ: {', '.join(keys)}")
            return
        exact = a.get("analytic") if _number(a.get("analytic")) else None
        for name in a:
            if name in ignore:
                continue
            _compare(a[name], b[name], f"{path}.{name}" if path else str(name), str(name), rel,
                     ignore, floor, out, exact)
        return
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} items against {len(b)}")
        elif a and all(_number(v) for v in a + b):
            size = max(math.hypot(*map(float, a)), math.hypot(*map(float, b)))
            allowed = rel * max(size, floor.get(key, 0.0), floor.get(SCALE_OF.get(key, key), 0.0))
            if max(abs(float(x) - float(y)) for x, y in zip(a, b, strict=True)) > allowed:
                out.append(f"{path}: {a} against {b}")
        else:
            for index, (x, y) in enumerate(zip(a, b, strict=True)):
                _compare(x, y, f"{path}[{index}]", key, rel, ignore, floor, out, analytic)
        return
    if _number(a) and _number(b):
        a, b = float(a), float(b)
        if key in RELATIVE_MEASURES:
            allowed = rel
        elif key == "abs_error":
            allowed = rel * abs(analytic or 0.0)
        else:
            allowed = rel * max(abs(a), abs(b), floor.get(key, 0.0),
                                floor.get(SCALE_OF.get(key, key), 0.0))
        if abs(a - b) > allowed:
            out.append(f"{path}: {a!r} against {b!r}")
        return
    if a != b:
        out.append(f"{path}: {a!r} against {b!r}")
