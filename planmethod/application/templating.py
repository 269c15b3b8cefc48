"""Make a template of a drawn mechanism: the drawing's links scaled to lengths drawn from
ranges, its crank angle and speed drawn from grids — the template ``planmethod variants``
draws a class's variants from (the studio's "variants" and "export").

The values a request gives are checked here with the command line's limits
(:func:`checked_number`, :func:`checked_whole`): a bad one is a
:class:`~planmethod.errors.SpecError` naming its key.

Examples
--------
>>> from planmethod.spec import read_text
>>> text = read_text("exercises/compressor_slider_crank.toml")
>>> template = make_template(text, {"lengths": {"BC": [0.16, 0.2]}, "angle": [30, 60, 5]})
>>> "l_BC = { range = [0.16, 0.2], step = 0.001 }" in template
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..errors import SpecError, value_text
from ..model import FRAME
from ..words import message, number_text, render

__all__ = ["as_drawn", "checked_number", "checked_whole", "everything_asked", "exercise_of",
           "make_template"]


def exercise_of(text: str, file: str | None = None):
    """The exercise the TOML ``text`` describes (either form)."""
    from ..spec import parse_exercise

    return parse_exercise(text, file=file)


def as_drawn(text: str, file: str | None = None) -> dict[str, Any]:
    """The tables of an exercise file, written as drawn (converted if it is in link
    frames); a template is refused (one exercise is edited at a time)."""
    from ..convert import drawn_tables, refuse_template
    from ..spec import is_drawn, parse_toml

    data = parse_toml(text, file=file)
    refuse_template(data, message("a template (it has ranges, choices or expressions) is not "
                                  "edited in the studio, one exercise is: draw one with "
                                  "`planmethod variants`"), file=file)
    if is_drawn(data):
        exercise_of(text, file)    # it must be a whole exercise
        return data
    return drawn_tables(data, file=file)


def checked_number(value: Any, key: str, *, limit: float = 1e6,
                   positive: bool = False) -> float:
    """``value`` as a finite number of magnitude at most ``limit`` (and above 0 if
    ``positive``), or a :class:`SpecError` naming ``key``."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise SpecError(message("must be a finite number, got {value}",
                                value=value_text(value)), key=key)
    if abs(value) > limit or (positive and value <= 0):
        raise SpecError(message("must be positive and at most {limit:g} in magnitude, got "
                                "{value}", limit=limit, value=value_text(value)) if positive
                        else message("must be at most {limit:g} in magnitude, got {value}",
                                     limit=limit, value=value_text(value)), key=key)
    return float(value)


def checked_whole(value: Any, key: str, low: int, high: int) -> int:
    """``value`` as a whole number in ``low`` … ``high``, or a :class:`SpecError` naming
    ``key``."""
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise SpecError(message("must be a whole number in {low}…{high}, got {value}",
                                low=low, high=high, value=value_text(value)), key=key)
    return value


def _range(value: Any, key: str, *, positive: bool = False) -> tuple[float, float]:
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SpecError(message("must be [low, high], got {value}", value=value_text(value)),
                        key=key)
    low, high = (checked_number(v, key, positive=positive) for v in value)
    if low > high:
        raise SpecError(message("low {low:g} is above high {high:g}", low=low, high=high),
                        key=key)
    return low, high


def _grid(value: Any, key: str, *, limit: float) -> tuple[float, float, float]:
    if not isinstance(value, list | tuple) or len(value) != 3:
        raise SpecError(message("must be [from, to, step], got {value}",
                                value=value_text(value)), key=key)
    low, high = _range(list(value[:2]), key)
    step = checked_number(value[2], key, positive=True)
    if max(abs(low), abs(high)) > limit:
        raise SpecError(message("must be within ±{limit:g}", limit=limit), key=key)
    if (high - low) / step > 1e6:
        raise SpecError(message("gives more than a million values (step {step:g})",
                                step=step), key=key)
    return low, high, step


def _base_length(mechanism, link: str) -> tuple[float, tuple[float, float]]:
    """(the length a range scales, the point it scales about): a moving link's first two
    points' distance (about its first point); the frame's farthest point from the crank's
    pivot (about the pivot)."""
    points = mechanism.links[link].points
    names = list(points)
    if link == FRAME:
        pivot = points[mechanism.drive.pivot]
        far = max((math.hypot(x - pivot[0], y - pivot[1]) for x, y in points.values()),
                  default=0.0)
        return far, pivot
    if len(names) < 2:
        return 0.0, (0.0, 0.0)
    (x1, y1), (x2, y2) = points[names[0]], points[names[1]]
    return math.hypot(x2 - x1, y2 - y1), points[names[0]]


def _scaled(xy, scaling) -> Any:
    """A point's coordinates as expressions scaling them about ``origin`` by ``name/base``."""
    if scaling is None:
        return xy
    name, base, origin = scaling
    out = []
    for value, centre in zip(xy, origin, strict=True):
        offset = float(value) - float(centre)
        if offset == 0:
            out.append(float(value))
        else:
            prefix = f"{float(centre)!r} + " if centre else ""
            out.append(f"= {prefix}{offset!r} * {name} / {base!r}")
    return out


def _varied_lengths(mechanism, ranges: Mapping[str, Any], variables: dict[str, Any]
                    ) -> dict[str, tuple[str, float, tuple[float, float]]]:
    """The links whose lengths are drawn (``ranges["lengths"]``: link → [low, high], m, on
    a grid of ``ranges["step"]``), each as (its variable, the length it scales, the point
    it scales about); their variables are added to ``variables``."""
    step = checked_number(ranges.get("step", 0.001), "ranges.step", positive=True)
    lengths = ranges.get("lengths") or {}
    if not isinstance(lengths, Mapping):
        raise SpecError(message("must be a table of link → [low, high]"), key="ranges.lengths")
    scaled: dict[str, tuple[str, float, tuple[float, float]]] = {}
    for link, bounds in lengths.items():
        key = f"ranges.lengths.{link}"
        if link not in mechanism.links:
            raise SpecError(message("unknown link '{link}'", link=link), key=key)
        low, high = _range(bounds, key, positive=True)
        base, origin = _base_length(mechanism, link)
        if base <= 0:
            raise SpecError(message("'{link}' has no length to vary (one point)", link=link),
                            key=key)
        name = f"l_{link}"
        variables[name] = {"range": [low, high], "step": step}
        scaled[link] = (name, base, origin)
    return scaled


def _varied_drive(frames: Mapping[str, Any], ranges: Mapping[str, Any],
                  variables: dict[str, Any]) -> dict[str, Any]:
    """The drive with its crank angle (``ranges["angle"]``: [from, to, step], deg) and its
    ω1 (``ranges["omega"]``: [low, high, step], rad/s) drawn, where a range is given; their
    variables are added to ``variables``."""
    drive = dict(frames["drive"])
    if ranges.get("angle") is not None:
        low, high, angle_step = _grid(ranges["angle"], "ranges.angle", limit=36000)
        variables["phi"] = {"range": [low, high], "step": angle_step}
        drive["angle"] = "= phi"
    if ranges.get("omega") is not None:
        low, high, omega_step = _grid(ranges["omega"], "ranges.omega", limit=1e4)
        variables["omega"] = {"range": [low, high], "step": omega_step}
        drive["omega"] = "= omega"
    return drive


def _task(mechanism, drive: Mapping[str, Any], scaled, variables) -> str:
    """The task as the student reads it, in the language spoken, with the placeholders a
    variant fills (its title, the lengths and angle drawn, the crank's symbols by its
    number)."""
    angle = "{phi:g}" if "phi" in variables else number_text(float(mechanism.drive.angle))
    omega = "{omega:g}" if "omega" in variables else number_text(mechanism.drive.omega)
    crank = message("The crank {link} turns about {pivot} at {omega_symbol} = {omega} rad/s; "
                    "at {phi_symbol} = {angle}° construct the plans and find the quantities "
                    "asked.", link=drive["link"], pivot=drive["pivot"],
                    omega_symbol="{symbol.omega}", omega=omega, phi_symbol="{symbol.phi}",
                    angle=angle)
    lengths = [f"{link.replace('_', ' ')} = {{{name}:.3f}} m"
               for link, (name, _, _) in scaled.items()]
    # the title by its placeholder (its text is never read); a length by its variable's
    return render(message("{title}. Lengths: {lengths}. {task}", title="{title}",
                          lengths=lengths, task=crank) if lengths else
                  message("{title}. {task}", title="{title}", task=crank))


def everything_asked(mechanism) -> dict[str, Any]:
    """The ``[ask]`` table that asks what a file without one asks (docs/studio.md: nothing
    ticked asks everything), written out for a template, whose students must be told what
    they are asked: v and a of every point that moves, ω and ε of every link but the drive's
    and those that only slide along the frame (they never turn), the sliding of every pair on a
    moving guide (on the frame's its slider's v and a say it), forces where masses or loads are
    given. Zero by construction is never asked: no variant could pass the rules a drawn one is
    held to.

    >>> from planmethod.spec import load_exercise
    >>> ask = everything_asked(load_exercise("exercises/compressor_slider_crank.toml").mechanism)
    >>> ask["velocity"], ask["omega"], "sliding" in ask
    (['B', 'C', 'D'], ['BC'], False)
    """
    points = list(dict.fromkeys(
        point for name, link in mechanism.links.items() if name != FRAME
        for point in link.points if FRAME not in mechanism.links_with_point(point)))
    translating = {pair.link for pair in mechanism.slides if pair.along == FRAME}
    turning = [name for name in mechanism.links
               if name not in (FRAME, mechanism.drive.link) and name not in translating]
    ask: dict[str, Any] = {"velocity": points, "acceleration": points, "omega": turning,
                           "epsilon": turning}
    sliding = [pair.key for pair in mechanism.slides if pair.along != FRAME]
    if sliding:
        ask["sliding"] = sliding
    if mechanism.masses or mechanism.loads:
        ask["forces"] = True
    return ask


def make_template(text: str, ranges: Mapping[str, Any]) -> str:
    """A template (in link frames) made of the drawing: each link listed in
    ``ranges["lengths"]`` (``{"BC": [0.16, 0.20]}``, m) scaled to a length drawn from that
    range (its first two points' distance; the frame's: its farthest point from the crank's
    pivot), the crank angle from ``ranges["angle"]`` (``[from, to, step]``, deg) and ω1 from
    ``ranges["omega"]`` (``[low, high, step]``, rad/s), each drawn on its grid. The
    assembly is picked by the drawing's points (a ``[sketch]`` at the drawn angle); the
    task's words are in the language spoken. A drawing that asks nothing asks everything
    (:func:`everything_asked`), written out."""
    from ..convert import frame_tables
    from ..grading.templates import to_toml
    from ..spec import exercise_from_dict

    if not isinstance(ranges, Mapping):
        raise SpecError(message("must be a table of ranges"), key="ranges")
    frames = frame_tables(as_drawn(text))
    mechanism = exercise_from_dict(frames).mechanism
    variables: dict[str, Any] = {}
    scaled = _varied_lengths(mechanism, ranges, variables)
    drive = _varied_drive(frames, ranges, variables)
    tables: dict[str, Any] = {"title": frames.get("title", "mechanism"),
                              "description": _task(mechanism, drive, scaled, variables),
                              "vars": variables, "template": {"max_attempts": 400}}
    for key, value in frames.items():
        if key in ("title", "description"):
            continue
        if key == "drive":
            tables["drive"] = drive
        elif key == "links":
            tables["links"] = {link: {p: _scaled(xy, scaled.get(link)) for p, xy in points.items()}
                               for link, points in value.items()}
        elif key == "mass":
            tables["mass"] = {link: (dict(props, S=_scaled(props["S"], scaled.get(link)))
                                     if isinstance(props, Mapping) and "S" in props else props)
                              for link, props in value.items()}
        else:
            tables[key] = value
    if "ask" not in frames:
        tables["ask"] = everything_asked(mechanism)
    return to_toml(tables)
