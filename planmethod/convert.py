"""The two forms of an exercise file, each written from the other (``planmethod convert``).

*Link frames* (docs/exercise-file.md): each link's points in its own frame, a
``[sketch]`` to pick the assembly. *As drawn*: every point's global position at
``drive.angle`` in ``[points]`` and each link as the list of its points; a slide's
``direction`` and a centre of mass ``S`` are global too, and the assembly is the one drawn.
:func:`planmethod.spec.frames_from_drawn` reads the second into the first; this module writes
either from the other:

* link frames → as drawn: the mechanism is solved at ``drive.angle`` (the file's assembly) and
  every point, centre of mass and guide direction is written where it stands;
* as drawn → link frames: each link's frame derived as :mod:`planmethod.spec` derives it, and
  a ``[sketch]`` of every point the groups place, so that the same assembly is taken.

Numbers, and why a round trip is byte-stable. Every number is written as the shortest text
that reads back as the same float (``repr``). A turn of the axes is not exactly undone in
floating point, so a point that went through both forms would come back a few units in the last
place away; three rules make "as drawn → link frames → as drawn" write the same bytes:

* the link-frame form written from a drawing keeps the drawing in its ``[sketch]`` (every point
  not on the frame), and a point whose solved position is within :data:`SNAP` of the drawing's
  size of its sketched one is written where the sketch puts it (the solve agrees with the
  drawing; the difference is the noise of the last places);
* a guide's direction in the frame of the link it runs along is written as the float that,
  added to that link's angle as the drawing gives it, makes the drawn direction exactly;
* a centre of mass (which no point pins) is written as drawn to :data:`MASS_DIGITS`
  significant digits of the drawing's size: the middle of its rounding interval, far from its
  edges, so that the noise of the next pass rounds back to it.

Other numbers (positions, a link's points in its frame) are rounded to :data:`DIGITS` digits of
the drawing's size, which only takes off the noise of the last place (0.18000000000000002 is
written 0.18). The JSON reports of the two forms agree to 1e-12 (``tests/test_convert.py``).

The leading comment block of the file is kept; other comments are not (a converted file is
written by the program). The tables keep their order.

Examples
--------
>>> from planmethod.spec import read_text
>>> text = read_text("exercises/compressor_slider_crank.toml")
>>> drawn = convert_text(text, to="drawn")
>>> "[points]" in drawn and "[sketch]" not in drawn
True
>>> frames = convert_text(drawn, to="frames")
>>> convert_text(frames, to="drawn") == drawn
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from .errors import SpecError
from .model import FRAME, Mechanism
from .spec import drawing_size, exercise_from_dict, frames_from_drawn, is_drawn, parse_toml
from .vectors import angle_deg, norm
from .words.message import Message, message

__all__ = [
    "DIGITS",
    "FORMS",
    "MASS_DIGITS",
    "SNAP",
    "convert_tables",
    "convert_text",
    "drawn_tables",
    "frame_tables",
    "refuse_template",
]

#: significant digits (of the drawing's size) of a position or a point in its link's frame
DIGITS = 16
#: significant digits (of the drawing's size) of an as-drawn centre of mass
MASS_DIGITS = 14
#: a solved point this close to its sketched place (a share of the drawing's size) is written
#: where the sketch puts it
SNAP = 1e-13

#: the two forms, by the name ``--to`` takes
FORMS = ("drawn", "frames")


def _decimals(size: float, digits: int) -> int:
    """Decimal places that keep ``digits`` significant digits of ``size``.

    >>> _decimals(0.24, 14), _decimals(1.3, 14)
    (14, 13)
    """
    return digits - 1 - math.floor(math.log10(size))


def _rounded(values, decimals: int) -> list[float]:
    """Numbers rounded to ``decimals`` places (−0.0 written 0.0)."""
    return [round(float(value), decimals) + 0.0 for value in values]


def _difference(total: float, part: float) -> float:
    """The float d nearest ``total − part`` for which ``part + d`` is ``total`` exactly (in
    floating point), when one lies within a few units of the last place; else ``total − part``.

    >>> _difference(0.3, 0.1), 0.1 + _difference(0.3, 0.1) == 0.3
    (0.19999999999999998, True)
    """
    first = total - part
    if part + first == total:
        return first
    for steps in range(1, 5):
        for towards in (math.inf, -math.inf):
            candidate = first
            for _ in range(steps):
                candidate = math.nextafter(candidate, towards)
            if part + candidate == total:
                return candidate
    return first


# -- link frames → as drawn ---------------------------------------------------------------------
def _orientations(mechanism: Mechanism, orders: Mapping[str, list[str]],
                  positions: Mapping[str, np.ndarray], motion) -> dict[str, float]:
    """Global angle (deg) of each link's +x axis at ``drive.angle``, computed as
    :mod:`planmethod.spec` derives it from a drawing (so that both give the same float): 0 for
    the frame, ``drive.angle`` for the crank, a sliding link's guide angle, else the angle of
    the line through the link's first two points apart, less that line's angle in the link's
    frame."""
    angles = {FRAME: 0.0, mechanism.drive.link: float(mechanism.drive.angle)}

    def angle(link: str, seen: tuple[str, ...] = ()) -> float:
        if link in angles:
            return angles[link]
        pair = next((s for s in mechanism.slides if s.link == link and s.along not in seen),
                    None)
        if pair is not None:
            angles[link] = angle(pair.along, (*seen, link)) + pair.direction
            return angles[link]
        names, local = orders[link], mechanism.links[link].points
        origin = positions[names[0]] if names else None
        second = next((p for p in names[1:] if float(norm(positions[p] - origin)) > 0), None)
        if second is None:   # no line to turn by: the solved angle, to the noise of its digits
            angles[link] = round(math.degrees(float(motion.theta(link))), 12) + 0.0
        else:
            angles[link] = (angle_deg(positions[second] - origin)
                            - angle_deg(np.subtract(local[second], local[names[0]])))
        return angles[link]

    for link in mechanism.links:
        angle(link)
    return angles


def drawn_tables(data: Mapping[str, Any], *, file: str | None = None,
                 angle: float | None = None) -> dict[str, Any]:
    """Exercise tables in the link-frame form → the same exercise written as drawn (at
    ``drive.angle``, or turned to the crank angle ``angle``: on the assembly the file picks at
    ``drive.angle``, followed to ``angle`` as a sweep follows it).

    Raises
    ------
    SpecError, StructureError, AssemblyError, ToggleError
        If the tables are not a valid exercise or it cannot be assembled at ``drive.angle``.

    Examples
    --------
    >>> from planmethod.spec import load_exercise, parse_toml, read_text
    >>> tables = parse_toml(read_text("exercises/fourbar_coupler_point.toml"))
    >>> drawn = drawn_tables(tables)
    >>> drawn["links"]["BC"], drawn["points"]["B"]
    (['B', 'C', 'E'], [0.04, 0.0692820323027551])
    """
    from .kinematics import solve

    if is_drawn(data):
        raise SpecError(message("the file is already written as drawn ([points])"), file=file)
    exercise = exercise_from_dict(data, file=file)
    mechanism = exercise.mechanism
    if angle is None:
        motion = solve(mechanism, mechanism.drive.angle, stage="position").at(0)
    else:   # the assembly chosen at drive.angle, followed to the new angle
        motion = solve(mechanism, float(angle), stage="position").at(0)
        mechanism = replace(mechanism, drive=replace(mechanism.drive, angle=float(angle)))
    orders = {link: list(mechanism.links[link].points) for link in mechanism.links}
    points, size = _drawn_points(mechanism, orders, motion)
    positions = {name: np.array(xy) for name, xy in points.items()}
    angles = _orientations(mechanism, orders, positions, motion)
    out: dict[str, Any] = {}
    for key, value in data.items():
        if key == "links":
            out["points"] = points
            out["links"] = orders
        elif key == "sketch":
            continue
        elif key == "drive" and angle is not None:
            out["drive"] = dict(value, angle=mechanism.drive.angle)
        elif key == "slide":
            out["slide"] = [dict(table, direction=angles[pair.along] + pair.direction + 0.0)
                            for table, pair in zip(_tables(value), mechanism.slides,
                                                   strict=True)]
        elif key == "mass":
            out["mass"] = _drawn_masses(mechanism, value, motion, _decimals(size, MASS_DIGITS))
        else:
            out[key] = value
    return out


def _drawn_points(mechanism: Mechanism, orders: Mapping[str, list[str]],
                  motion) -> tuple[dict[str, list[float]], float]:
    """Every point where it stands (the frame's as written, a point within :data:`SNAP` of
    its sketched place there, any other rounded to :data:`DIGITS` of the drawing's size),
    and the drawing's size."""
    names = list(dict.fromkeys(p for order in orders.values() for p in order))
    solved = {p: np.asarray(motion.position(p), dtype=float) for p in names}
    size = drawing_size(solved.values())
    places = _decimals(size, DIGITS)
    fixed = mechanism.links[FRAME].points
    points: dict[str, list[float]] = {}
    for name in names:
        sketched = mechanism.sketch.get(name)
        if name in fixed:   # the frame's points are global already: as written
            points[name] = [float(value) for value in fixed[name]]
        elif (sketched is not None
              and float(norm(solved[name] - np.asarray(sketched))) <= SNAP * size):
            points[name] = [float(value) for value in sketched]
        else:
            points[name] = _rounded(solved[name], places)
    return points, size


def _drawn_masses(mechanism: Mechanism, tables: Mapping[str, Any], motion,
                  places: int) -> dict[str, Any]:
    """The ``[mass]`` tables with each centre of mass ``S`` where it stands, to ``places``."""
    return {link: (dict(table, S=_rounded(motion.place(link, mechanism.masses[link].S), places))
                   if isinstance(table, Mapping) and "S" in table else table)
            for link, table in tables.items()}


def _tables(value: Any) -> list:
    return [value] if isinstance(value, Mapping) else list(value)


# -- as drawn → link frames ---------------------------------------------------------------------
def frame_tables(data: Mapping[str, Any], *, file: str | None = None) -> dict[str, Any]:
    """Exercise tables written as drawn → the same exercise in the link-frame form, with a
    ``[sketch]`` of every point not on the frame (the drawn assembly).

    Raises
    ------
    SpecError, StructureError
        If the tables are not a valid exercise written as drawn.

    Examples
    --------
    >>> tables = frame_tables({
    ...     "drive": {"link": "AB", "pivot": "A", "angle": 90, "omega": 10},
    ...     "points": {"A": [0, 0], "B": [0, 0.05], "C": [0.2, 0]},
    ...     "links": {"frame": ["A"], "AB": ["A", "B"], "BC": ["B", "C"], "slider": ["C"]},
    ...     "slide": [{"link": "slider", "along": "frame", "through": "A"}]})
    >>> tables["links"]["AB"], tables["sketch"]
    ({'A': [0.0, 0.0], 'B': [0.05, 0.0]}, {'B': [0.0, 0.05], 'C': [0.2, 0.0]})
    """
    if not is_drawn(data):
        raise SpecError(message("the file is already in the link-frame form (no [points])"),
                        file=file)
    frames = frames_from_drawn(data, file=file)
    exercise_from_dict(frames, file=file)   # the whole exercise is valid
    angles = _drawn_angles(data, frames)
    size = drawing_size(tuple(value) for value in frames["sketch"].values())
    places = _decimals(size, DIGITS)

    def local(link: str, xy) -> list[float]:
        return [float(v) for v in xy] if link == FRAME else _rounded(xy, places)

    out: dict[str, Any] = {}
    for key, value in data.items():
        if key == "points":
            continue
        if key == "links":
            out["links"] = {link: {p: local(link, xy) for p, xy in points.items()}
                            for link, points in frames["links"].items()}
            if "slide" not in data:
                out["sketch"] = frames["sketch"]
        elif key == "slide":
            out["slide"] = [dict(table, direction=_difference(float(drawn["direction"]),
                                                              angles[table["along"]]))
                            if "direction" in drawn else table
                            for table, drawn in zip(frames["slide"], _tables(value),
                                                    strict=True)]
            out["sketch"] = frames["sketch"]
        elif key == "mass":
            out["mass"] = {link: (dict(table, S=_rounded(table["S"], places))
                                  if isinstance(table, Mapping) and "S" in table else table)
                           for link, table in frames["mass"].items()}
        else:
            out[key] = value
    return out


def _drawn_angles(data: Mapping[str, Any], frames: Mapping[str, Any]) -> dict[str, float]:
    """The angle (deg) of each link's +x axis as the as-drawn form gives it: the angle
    :func:`_orientations` computes again from the link-frame tables written here."""
    exercise = exercise_from_dict(frames)
    mechanism = exercise.mechanism
    positions = {p: np.array(xy, dtype=float) for p, xy in frames["sketch"].items()}
    positions |= {p: np.array(xy, dtype=float)
                  for p, xy in mechanism.links[FRAME].points.items()}
    orders = {link: list(mechanism.links[link].points) for link in mechanism.links}
    drawn = {name: np.array(xy, dtype=float) for name, xy in data["points"].items()}
    return _orientations(mechanism, orders, drawn | positions, _NoMotion())


class _NoMotion:
    """Stands for a solve where a drawing gives every angle (a one-point link's is 0)."""

    def theta(self, link: str) -> float:
        return 0.0


# -- whole files --------------------------------------------------------------------------------
def convert_tables(data: Mapping[str, Any], *, to: str | None = None,
                   file: str | None = None) -> dict[str, Any]:
    """Exercise tables in the form ``to`` (``"drawn"`` or ``"frames"``; default: the other
    form). Tables already in that form go through the other one and back, which writes them
    as this module writes them (an as-drawn file with its points on the solved assembly).

    Parameters
    ----------
    data
        The exercise file's tables, as :func:`planmethod.spec.parse_toml` reads them.
    to
        ``"drawn"`` (global points at ``drive.angle``) or ``"frames"`` (each link in its own
        frame, with a ``[sketch]``); ``None`` for the form the tables are not in.
    file
        The file's name, for error messages.

    Returns
    -------
    dict
        The tables of the same exercise in the form ``to``.

    Raises
    ------
    SpecError
        If ``to`` is unknown or the tables are not a valid exercise (naming the file and key).

    Examples
    --------
    >>> from planmethod.spec import parse_toml
    >>> data = parse_toml(open("exercises/compressor_slider_crank.toml").read())
    >>> convert_tables(data, to="drawn")["points"]["B"]
    [0.0424264068711929, 0.0424264068711928]
    """
    if to is not None and to not in FORMS:
        raise SpecError(message("unknown form {form!r}; expected one of {forms}", form=to,
                                forms=list(FORMS)), key="--to")
    drawn = is_drawn(data)
    target = to or ("frames" if drawn else "drawn")
    if target == "drawn":
        return drawn_tables(frame_tables(data, file=file) if drawn else data, file=file)
    return frame_tables(data if drawn else drawn_tables(data, file=file), file=file)


def _header(text: str) -> str:
    """The file's leading comment lines (kept by a conversion)."""
    lines = []
    for line in text.splitlines():
        if not line.startswith("#"):
            break
        lines.append(line)
    return "".join(line + "\n" for line in lines)


def convert_text(text: str, *, to: str | None = None, file: str | None = None) -> str:
    """An exercise file's text in the form ``to`` (see :func:`convert_tables`), with its
    leading comment block kept.

    Parameters
    ----------
    text
        The exercise file's TOML text.
    to
        ``"drawn"`` or ``"frames"``; ``None`` for the form the file is not in.
    file
        The file's name, for error messages.

    Returns
    -------
    str
        The TOML text of the same exercise in the form ``to``: ``planmethod convert``'s output.

    Raises
    ------
    SpecError
        If the text is not a valid exercise file, or is a template (naming the file and key).

    Examples
    --------
    >>> text = open("exercises/compressor_slider_crank.toml").read()
    >>> [line for line in convert_text(text).splitlines() if line.startswith("C =")]
    ['C = [0.2173549637165519, 0.0]']
    """
    from .grading.templates import to_toml

    data = parse_toml(text, file=file)
    refuse_template(data, message("a template (it has ranges, choices or expressions) is "
                                  "converted variant by variant: draw one with `planmethod "
                                  "variants`"), file=file)
    return _header(text) + to_toml(convert_tables(data, to=to, file=file))


def refuse_template(data: Mapping[str, Any], what: Message | str, *,
                    file: str | None = None) -> None:
    """A :class:`SpecError` if the tables are a template (``[vars]`` or ``[template]``),
    saying ``what``: the whole sentence, as a message (or, where its caller still gives
    words, what is done to a template instead: ``"is converted variant by variant"``)."""
    for name in ("vars", "template"):
        if name in data:
            said = what if isinstance(what, Message) else message(
                "a template (it has ranges, choices or expressions) {what}: draw one with "
                "`planmethod variants`", what=what)
            raise SpecError(said, file=file, key=name)
