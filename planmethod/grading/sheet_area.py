"""The gridded drawing area of a printed plan sheet (A4, portrait: :mod:`planmethod.grading.
paper`) and the room a plan has in it: what a variant's plan must fit into for the class's
booklet to print it (:func:`planmethod.grading.templates.plan_problem`).

>>> PLAN_ROOM_MM
(162.0, 194.0)
>>> plan_size_mm({"p": (0.0, 0.0), "b": (40.0, 30.0), "c": (-10.0, 5.0)})
(50.0, 30.0)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

__all__ = ["DRAWING_MM", "PLAN_MARGIN_MM", "PLAN_ROOM_MM", "plan_size_mm"]

#: the gridded drawing area (left, top, right, bottom; mm)
DRAWING_MM = (12.0, 40.0, 198.0, 258.0)
#: the room (mm) kept between a plan's points and the drawing area's edge, for labels
PLAN_MARGIN_MM = 12.0
#: the width and height (mm) a plan's points may span on its sheet
PLAN_ROOM_MM = (DRAWING_MM[2] - DRAWING_MM[0] - 2 * PLAN_MARGIN_MM,
                DRAWING_MM[3] - DRAWING_MM[1] - 2 * PLAN_MARGIN_MM)


def plan_size_mm(points_mm: Mapping[str, Iterable[float]]) -> tuple[float, float]:
    """The width and height (mm) a plan's points span, its pole (the origin) with them."""
    xs = [0.0, *(float(x) for x, _ in points_mm.values())]
    ys = [0.0, *(float(y) for _, y in points_mm.values())]
    return (max(xs) - min(xs), max(ys) - min(ys))
