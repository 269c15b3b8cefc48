"""Exercise files (TOML) → :class:`~planmethod.model.Exercise`, with file- and key-precise errors.

The format is described in README, "The exercise file". Every problem is
reported as a :class:`~planmethod.errors.SpecError` naming the file and the dotted key, e.g.
``slider.toml: drive.omega: must be a finite number, got nan``.

Examples
--------
>>> text = '''
... [drive]
... link = "AB"
... pivot = "A"
... angle = 45
... omega = 100
... [links]
... frame = { A = [0, 0] }
... AB = { A = [0, 0], B = [0.06, 0] }
... BC = { B = [0, 0], C = [0.18, 0] }
... slider = { C = [0, 0] }
... [[slide]]
... link = "slider"
... along = "frame"
... through = "A"
... '''
>>> exercise = parse_exercise(text, file="compressor.toml")
>>> exercise.mechanism.slides[0].key
'slider/frame'
>>> parse_exercise(text.replace("omega = 100", "omega = nan"), file="x.toml")
Traceback (most recent call last):
...
planmethod.errors.SpecError: x.toml: drive.omega: must be a finite number, got nan
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .errors import SpecError
from .model import (
    FRAME,
    Ask,
    Drive,
    Exercise,
    Link,
    Load,
    MassProperties,
    Mechanism,
    PlanSettings,
    Revolute,
    Slide,
)
from .vocabulary import quantity

__all__ = ["POINT_NAME", "exercise_from_dict", "load_exercise", "parse_exercise", "parse_toml",
           "read_text"]

POINT_NAME = re.compile(r"^[A-Z][0-9]*$")
LINK_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")

TOP_LEVEL_KEYS = (
    "title", "description", "drive", "links", "slide", "sketch", "plan", "ask",
    "mass", "gravity", "load", "friction", "grading", "published",
)
PLAN_KEYS = (
    "crank_mm", "velocity_mm", "acceleration_mm", "mu_l", "mu_v", "mu_a", "force_mm", "mu_f",
    "scale_point", "precision_mm", "min_angle_deg", "exact_mm",
)
ASK_KEYS = ("velocity", "acceleration", "omega", "epsilon", "curvature", "sliding", "forces")


def load_exercise(path: str | Path) -> Exercise:
    """Read an exercise file.

    Parameters
    ----------
    path
        The TOML file.

    Raises
    ------
    SpecError
        If the file cannot be read, is not valid TOML, or breaks the exercise-file contract.
    """
    path = Path(path)
    return parse_exercise(read_text(path), file=str(path))


def parse_exercise(text: str, *, file: str | None = None) -> Exercise:
    """Parse the text of an exercise file (see :func:`load_exercise`).

    Parameters
    ----------
    text
        The TOML text of the exercise file.
    file
        The file name that error messages name (default: none).
    """
    return exercise_from_dict(parse_toml(text, file=file), file=file)


def read_text(path: str | Path) -> str:
    """The UTF-8 text of a file, or a :class:`SpecError` naming it."""
    try:
        return Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SpecError("no such file", file=str(path)) from None
    except (OSError, UnicodeDecodeError) as error:
        raise SpecError(f"cannot read the file ({error})", file=str(path)) from None


#: input limits (README, "Bad input"): what the stress suite covers, and no more
#: — coordinates and lengths (m), the crank's ω (rad/s) and ε (rad/s²), crank angles (°)
MAX_COORDINATE_M = 1e6
MAX_OMEGA = 1e4
MAX_EPSILON = 1e8
MAX_ANGLE_DEG = 36000.0
#: any other number (masses, forces, moments, g)
MAX_MAGNITUDE = 1e12
#: tables and arrays nested deeper than this are refused before they are read
MAX_NESTING = 32
#: the friction iteration's largest allowed count
MAX_FRICTION_ITERATIONS = 10_000
#: a friction coefficient above this is not a joint's
MAX_FRICTION_COEFFICIENT = 2.0


def nesting_depth(text: str) -> int:
    """How deep brackets and braces nest in TOML or JSON text (strings skipped), found without
    a parser, so that a file nested 100,000 deep is refused before it can exhaust the stack.

    Examples
    --------
    >>> nesting_depth('a = [[1, 2], {b = "[[["}]  # [[[[')
    2
    """
    depth = deepest = 0
    quote = None
    escaped = comment = False
    for char in text:
        if comment:
            comment = char != "\n"
        elif quote is not None:
            if escaped:
                escaped = False
            elif char == "\\" and quote == '"':
                escaped = True
            elif char == quote:
                quote = None
        elif char in "\"'":
            quote = char
        elif char in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif char in "]}":
            depth = max(depth - 1, 0)
        elif char == "#":           # a TOML comment, to the end of the line
            comment = True
    return deepest


def check_nesting(text: str, *, file: str | None = None) -> None:
    """A :class:`SpecError` if ``text`` nests deeper than :data:`MAX_NESTING`."""
    depth = nesting_depth(text)
    if depth > MAX_NESTING:
        raise SpecError(f"tables or arrays nested {depth} deep; at most {MAX_NESTING} are "
                        "read", file=file)


def parse_toml(text: str, *, file: str | None = None) -> dict[str, Any]:
    """TOML text → tables, or a :class:`SpecError` naming the file, line and column."""
    check_nesting(text, file=file)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        message = str(error).replace("Cannot overwrite a value", "a key is given twice")
        raise SpecError(f"not valid TOML: {message}", file=file) from None


def exercise_from_dict(data: Mapping[str, Any], *, file: str | None = None) -> Exercise:
    """Build an :class:`~planmethod.model.Exercise` from the parsed TOML tables."""
    return _Reader(file).exercise(data)


def _mechanism_size(links: Mapping[str, Link]) -> float:
    """The largest extent of any link (m), at least 1 mm."""
    size = 1e-3
    for link in links.values():
        xs = [p[0] for p in link.points.values()]
        ys = [p[1] for p in link.points.values()]
        if xs:
            size = max(size, max(xs) - min(xs), max(ys) - min(ys))
    return size


def _distance_to_points(point, points) -> float:
    return min(math.hypot(point[0] - x, point[1] - y) for x, y in points)


def _suggest(word: str, choices) -> str:
    close = difflib.get_close_matches(word, list(choices), n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


class _Reader:
    """Reads the tables with a file name at hand for every error."""

    def __init__(self, file: str | None) -> None:
        self.file = file

    def error(self, key: str, message: str) -> SpecError:
        return SpecError(message, file=self.file, key=key)

    # -- scalar readers ---------------------------------------------------------------------
    def number(self, value: Any, key: str, *, positive: bool = False,
               non_negative: bool = False, limit: float = MAX_MAGNITUDE,
               what: str = "") -> float:
        """A finite number of magnitude at most ``limit`` (``what`` names the limit)."""
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(key, f"must be a finite number, got {value!r}")
        try:
            value = float(value)
        except OverflowError:   # an integer too large for a float
            raise self.error(key, f"must be at most {limit:g} in magnitude{what}") from None
        if not math.isfinite(value):
            raise self.error(key, f"must be a finite number, got {value}")
        if abs(value) > limit:
            raise self.error(key, f"must be at most {limit:g} in magnitude{what}, got "
                                  f"{value:g}")
        if positive and value <= 0:
            raise self.error(key, f"must be positive, got {value:g}")
        if non_negative and value < 0:
            raise self.error(key, f"must not be negative, got {value:g}")
        return value

    def vector(self, value: Any, key: str, *, limit: float = MAX_MAGNITUDE,
               what: str = "") -> tuple[float, float]:
        if not isinstance(value, list | tuple) or len(value) != 2:
            raise self.error(key, f"must be a pair of numbers [x, y], got {value!r}")
        return (self.number(value[0], f"{key}[0]", limit=limit, what=what),
                self.number(value[1], f"{key}[1]", limit=limit, what=what))

    def coordinates(self, value: Any, key: str) -> tuple[float, float]:
        """A point's coordinates (m), within the range the stress suite covers."""
        return self.vector(value, key, limit=MAX_COORDINATE_M,
                           what=" (m; the range planmethod is tested on)")

    def string(self, value: Any, key: str) -> str:
        if not isinstance(value, str) or not value:
            raise self.error(key, f"must be a non-empty string, got {value!r}")
        return value

    def table(self, value: Any, key: str) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            raise self.error(key, f"must be a table, got {value!r}")
        return value

    def only_keys(self, table: Mapping[str, Any], allowed, key: str) -> None:
        for name in table:
            if name not in allowed:
                raise self.error(f"{key}.{name}" if key else name,
                                 f"unknown key{_suggest(name, allowed)}; expected one of "
                                 f"{', '.join(allowed)}")

    # -- the exercise -----------------------------------------------------------------------
    def exercise(self, data: Mapping[str, Any]) -> Exercise:
        for name in ("vars", "template"):
            if name in data:
                raise self.error(name, "this is an exercise template (it has ranges, choices "
                                       "or expressions): draw exercises from it with "
                                       "`planmethod variants`")
        self.only_keys(data, TOP_LEVEL_KEYS, "")
        title = data.get("title", Path(self.file).stem if self.file else "mechanism")
        title = self.string(title, "title")
        links = self.links(data)
        revolutes = self.revolutes(links)
        slides = self.slides(data, links)
        drive = self.drive(data, links)
        sketch = self.sketch(data, links)
        masses = self.masses(data, links)
        gravity = self.gravity(data)
        loads = self.loads(data, links)
        friction = self.friction(data, links, revolutes, slides)
        mechanism = Mechanism(
            title=title, links=links, revolutes=revolutes, slides=slides, drive=drive,
            sketch=sketch, masses=masses, gravity=gravity, loads=loads, friction=friction,
        )
        plan = self.plan(data, mechanism)
        ask = self.ask(data, mechanism)
        published, published_source = self.published(data)
        return Exercise(mechanism=mechanism, plan=plan, ask=ask, source=self.file,
                        published=published, published_source=published_source)

    def published(self, data: Mapping[str, Any]) -> tuple[dict[str, float], str | None]:
        """``[published]``: the values a book prints (``v_C = 4.0``, SI units), with an
        optional ``source = "…"`` naming the book."""
        table = self.table(data.get("published", {}), "published")
        values: dict[str, float] = {}
        source = None
        for name, value in table.items():
            if name == "source":
                source = self.string(value, "published.source")
                continue
            try:
                quantity(name)
            except KeyError:
                raise self.error(f"published.{name}", "is not a quantity (v_C, a_C, omega_BC, "
                                                      "epsilon_BC, rho_D, …)") from None
            values[name] = self.number(value, f"published.{name}")
        return values, source

    def links(self, data: Mapping[str, Any]) -> dict[str, Link]:
        if "links" not in data:
            raise self.error("links", "missing the [links] table")
        table = self.table(data["links"], "links")
        if FRAME not in table:
            raise self.error("links", f"missing the fixed link '{FRAME}'"
                                      f"{_suggest(FRAME, table)}")
        links: dict[str, Link] = {}
        seen_lower: dict[str, str] = {}
        for name, points in table.items():
            key = f"links.{name}"
            if not LINK_NAME.match(name):
                raise self.error(key, "a link name must be an identifier (letters, digits, _)")
            if name.lower() in seen_lower:
                raise self.error(key, f"duplicate link name (also '{seen_lower[name.lower()]}')")
            seen_lower[name.lower()] = name
            points = self.table(points, key)
            if not points and name != FRAME:
                raise self.error(key, "a link needs at least one point")
            parsed = {}
            for point, xy in points.items():
                if not POINT_NAME.match(point):
                    raise self.error(f"{key}.{point}", "a point name is a capital letter, "
                                     "optionally followed by digits (A, O2, C4)")
                parsed[point] = self.coordinates(xy, f"{key}.{point}")
            links[name] = Link(name, parsed)
        if len(links) < 2:
            raise self.error("links", "a mechanism needs the frame and at least one moving link")
        return links

    def revolutes(self, links: Mapping[str, Link]) -> tuple[Revolute, ...]:
        owners: dict[str, list[str]] = {}
        for name, link in links.items():
            for point in link.points:
                owners.setdefault(point, []).append(name)
        return tuple(Revolute(point, tuple(names)) for point, names in owners.items()
                     if len(names) >= 2)

    def slides(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> tuple[Slide, ...]:
        raw = data.get("slide", [])
        if isinstance(raw, Mapping):
            raw = [raw]
        if not isinstance(raw, list):
            raise self.error("slide", "must be an array of tables ([[slide]])")
        slides = []
        for number, table in enumerate(raw, start=1):
            key = f"slide[{number}]"
            table = self.table(table, key)
            self.only_keys(table, ("link", "along", "through", "direction", "point"), key)
            for needed in ("link", "along", "through"):
                if needed not in table:
                    raise self.error(f"{key}.{needed}", "missing")
            link = self.link_name(table["link"], f"{key}.link", links)
            along = self.link_name(table["along"], f"{key}.along", links)
            if link == along:
                raise self.error(f"{key}.along", f"a link cannot slide along itself ('{link}')")
            through = self.string(table["through"], f"{key}.through")
            if through not in links[along].points:
                raise self.error(f"{key}.through", f"'{through}' is not a point of '{along}'"
                                 f"{_suggest(through, links[along].points)}")
            direction = self.number(table.get("direction", 0.0), f"{key}.direction")
            if "point" in table:
                point = self.string(table["point"], f"{key}.point")
                if point not in links[link].points:
                    raise self.error(f"{key}.point", f"'{point}' is not a point of '{link}'"
                                     f"{_suggest(point, links[link].points)}")
            elif len(links[link].points) == 1:
                point = next(iter(links[link].points))
            else:
                raise self.error(f"{key}.point", f"'{link}' has several points "
                                 f"({', '.join(links[link].points)}): name the one on the guide")
            pair = Slide(link, along, through, direction, point, number)
            if any(s.key == pair.key or s.key == f"{along}/{link}" for s in slides):
                raise self.error(key, f"duplicate prismatic pair between '{link}' and '{along}'")
            slides.append(pair)
        return tuple(slides)

    def link_name(self, value: Any, key: str, links: Mapping[str, Link]) -> str:
        name = self.string(value, key)
        if name not in links:
            raise self.error(key, f"unknown link '{name}'{_suggest(name, links)}")
        return name

    def drive(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> Drive:
        if "drive" not in data:
            raise self.error("drive", "missing the [drive] table (link, pivot, angle, omega)"
                             f"{_suggest('drive', [k for k in data if k not in TOP_LEVEL_KEYS])}")
        table = self.table(data["drive"], "drive")
        self.only_keys(table, ("link", "pivot", "angle", "omega", "epsilon"), "drive")
        for needed in ("link", "pivot", "angle", "omega"):
            if needed not in table:
                raise self.error(f"drive.{needed}", "missing")
        link = self.link_name(table["link"], "drive.link", links)
        if link == FRAME:
            raise self.error("drive.link", "the frame cannot be the drive link")
        pivot = self.string(table["pivot"], "drive.pivot")
        if pivot not in links[link].points:
            raise self.error("drive.pivot", f"'{pivot}' is not a point of '{link}'"
                             f"{_suggest(pivot, links[link].points)}")
        if pivot not in links[FRAME].points:
            raise self.error("drive.pivot", f"'{pivot}' must also be a point of '{FRAME}' "
                             "(the drive turns about a fixed pivot)")
        if len(links[link].points) < 2:
            raise self.error(f"links.{link}", "the drive link needs a point besides its pivot")
        return Drive(
            link=link, pivot=pivot,
            angle=self.number(table["angle"], "drive.angle", limit=MAX_ANGLE_DEG,
                              what=" (degrees)"),
            omega=self.number(table["omega"], "drive.omega", limit=MAX_OMEGA,
                              what=" (rad/s; the range planmethod is tested on)"),
            epsilon=self.number(table.get("epsilon", 0.0), "drive.epsilon", limit=MAX_EPSILON,
                                what=" (rad/s²; the range planmethod is tested on)"),
        )

    def sketch(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> dict:
        table = self.table(data.get("sketch", {}), "sketch")
        known = {p for link in links.values() for p in link.points}
        sketch = {}
        for point, xy in table.items():
            if point not in known:
                raise self.error(f"sketch.{point}", f"unknown point '{point}'"
                                 f"{_suggest(point, known)}")
            sketch[point] = self.coordinates(xy, f"sketch.{point}")
        return sketch

    def masses(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> dict:
        table = self.table(data.get("mass", {}), "mass")
        masses = {}
        for name, props in table.items():
            key = f"mass.{name}"
            if name not in links:
                raise self.error(key, f"unknown link '{name}'{_suggest(name, links)}")
            if name == FRAME:
                raise self.error(key, "the frame does not move: it needs no mass")
            props = self.table(props, key)
            self.only_keys(props, ("m", "J", "S"), key)
            if "m" not in props:
                raise self.error(f"{key}.m", "missing")
            m = self.number(props["m"], f"{key}.m", positive=True)
            J = self.number(props.get("J", 0.0), f"{key}.J", non_negative=True)
            points = links[name].points
            if "S" in props:
                S = self.coordinates(props["S"], f"{key}.S")
            else:  # centroid of the link's points
                S = (sum(p[0] for p in points.values()) / len(points),
                     sum(p[1] for p in points.values()) / len(points))
            if _distance_to_points(S, points.values()) > 10 * _mechanism_size(links):
                raise self.error(f"{key}.S", f"centre of mass {S} lies more than 10 times the "
                                 f"mechanism's size ({_mechanism_size(links):g} m) from the "
                                 "link's points")
            masses[name] = MassProperties(name, m, J, S)
        return masses

    def gravity(self, data: Mapping[str, Any]) -> float | None:
        if "gravity" not in data:
            return None
        table = self.table(data["gravity"], "gravity")
        self.only_keys(table, ("g",), "gravity")
        return self.number(table.get("g", 9.81), "gravity.g", non_negative=True)

    def loads(self, data: Mapping[str, Any], links: Mapping[str, Link]) -> tuple[Load, ...]:
        raw = data.get("load", [])
        if isinstance(raw, Mapping):
            raw = [raw]
        if not isinstance(raw, list):
            raise self.error("load", "must be an array of tables ([[load]])")
        loads = []
        for number, table in enumerate(raw, start=1):
            key = f"load[{number}]"
            table = self.table(table, key)
            self.only_keys(table, ("link", "point", "force", "moment", "oppose_velocity", "name"),
                           key)
            if "link" not in table:
                raise self.error(f"{key}.link", "missing")
            link = self.link_name(table["link"], f"{key}.link", links)
            if link == FRAME:
                raise self.error(f"{key}.link", "a load on the frame does nothing")
            has_force, has_moment = "force" in table, "moment" in table
            if has_force == has_moment:
                raise self.error(key, "give exactly one of `force = [fx, fy]` or `moment = m`")
            point = None
            if has_force:
                if "point" not in table:
                    raise self.error(f"{key}.point", "a force needs the point it acts on")
                point = self.string(table["point"], f"{key}.point")
                if point not in links[link].points:
                    raise self.error(f"{key}.point", f"'{point}' is not a point of '{link}'"
                                     f"{_suggest(point, links[link].points)}")
            oppose = table.get("oppose_velocity", False)
            if not isinstance(oppose, bool):
                raise self.error(f"{key}.oppose_velocity", f"must be true or false, got {oppose!r}")
            name = None
            if "name" in table:
                name = self.string(table["name"], f"{key}.name")
                if not re.fullmatch(r"[^\W\d][\w,′']{0,15}", name):
                    raise self.error(f"{key}.name", f"{name!r} is not a symbol: a letter, then up "
                                     "to 15 letters, digits or _ (P, P_c, F_res)")
            loads.append(Load(
                link=link, point=point,
                force=self.vector(table["force"], f"{key}.force") if has_force else None,
                moment=self.number(table["moment"], f"{key}.moment") if has_moment else None,
                oppose_velocity=oppose, index=number, name=name,
            ))
        return tuple(loads)

    def friction(self, data, links, revolutes, slides) -> dict:
        """``[friction]``: ``f`` (coefficient, all pairs), ``pin_radius`` (m, all revolute
        pairs), and per-pair overrides ``[friction.pairs."B"]`` or
        ``[friction.pairs."slider/frame"]`` with ``f`` and ``pin_radius``. Validated here; used
        by the force module."""
        if "friction" not in data:
            return {}
        table = self.table(data["friction"], "friction")
        self.only_keys(table, ("f", "pin_radius", "pairs", "tolerance", "max_iterations"),
                       "friction")
        result: dict[str, Any] = {}
        limits = {"f": (MAX_FRICTION_COEFFICIENT, " (a friction coefficient)"),
                  "pin_radius": (MAX_COORDINATE_M, " (m)"), "tolerance": (MAX_MAGNITUDE, "")}
        for name in ("f", "pin_radius", "tolerance"):
            if name in table:
                limit, what = limits[name]
                result[name] = self.number(table[name], f"friction.{name}", non_negative=True,
                                           limit=limit, what=what)
        if "max_iterations" in table:
            value = table["max_iterations"]
            if (isinstance(value, bool) or not isinstance(value, int)
                    or not 1 <= value <= MAX_FRICTION_ITERATIONS):
                raise self.error("friction.max_iterations", f"must be an integer from 1 to "
                                 f"{MAX_FRICTION_ITERATIONS}, got {value!r}")
            result["max_iterations"] = value
        pair_keys = {pair.point for pair in revolutes} | {pair.key for pair in revolutes}
        pair_keys |= {pair.key for pair in slides}
        pairs = {}
        for name, props in self.table(table.get("pairs", {}), "friction.pairs").items():
            key = f"friction.pairs.{name}"
            if name not in pair_keys:
                raise self.error(key, f"unknown pair '{name}'{_suggest(name, pair_keys)}")
            props = self.table(props, key)
            self.only_keys(props, ("f", "pin_radius"), key)
            pairs[name] = {k: self.number(v, f"{key}.{k}", non_negative=True)
                           for k, v in props.items()}
        result["pairs"] = pairs
        return result

    def plan(self, data: Mapping[str, Any], mechanism: Mechanism) -> PlanSettings:
        table = self.table(data.get("plan", {}), "plan")
        self.only_keys(table, PLAN_KEYS, "plan")
        values: dict[str, Any] = {}
        for drawn, direct in (("crank_mm", "mu_l"), ("velocity_mm", "mu_v"),
                              ("acceleration_mm", "mu_a"), ("force_mm", "mu_f")):
            if drawn in table and direct in table:
                raise self.error(f"plan.{direct}", f"give either {drawn} or {direct}, not both")
            if direct in table:
                values[direct] = self.number(table[direct], f"plan.{direct}", positive=True)
                values[drawn] = None
            elif drawn in table:
                values[drawn] = self.number(table[drawn], f"plan.{drawn}", positive=True)
        if "scale_point" in table:
            point = self.string(table["scale_point"], "plan.scale_point")
            drive_points = mechanism.links[mechanism.drive.link].points
            if point not in drive_points or point == mechanism.drive.pivot:
                raise self.error("plan.scale_point", f"'{point}' must be a point of the drive "
                                 f"link '{mechanism.drive.link}' other than its pivot")
            values["scale_point"] = point
        if "precision_mm" in table:
            values["precision_mm"] = self.number(table["precision_mm"], "plan.precision_mm",
                                                 non_negative=True)
        if "min_angle_deg" in table:
            values["min_angle_deg"] = self.number(table["min_angle_deg"], "plan.min_angle_deg",
                                                  non_negative=True)
        if "exact_mm" in table:
            if not isinstance(table["exact_mm"], bool):
                raise self.error("plan.exact_mm", f"must be true or false, got "
                                                  f"{table['exact_mm']!r}")
            values["exact_mm"] = table["exact_mm"]
        return PlanSettings(**values)

    def ask(self, data: Mapping[str, Any], mechanism: Mechanism) -> Ask:
        if "ask" not in data:
            return Ask(everything=True, forces=bool(mechanism.masses or mechanism.loads))
        table = self.table(data["ask"], "ask")
        self.only_keys(table, ASK_KEYS, "ask")
        points = {p for link in mechanism.links.values() for p in link.points}
        values: dict[str, Any] = {}
        for name in ("velocity", "acceleration", "curvature"):
            values[name] = tuple(self.point_ref(item, f"ask.{name}[{i}]", points, mechanism)
                                 for i, item in enumerate(self.names(table, name)))
        for name in ("omega", "epsilon"):
            items = self.names(table, name)
            for i, item in enumerate(items):
                if item not in mechanism.links:
                    raise self.error(f"ask.{name}[{i}]", f"unknown link '{item}'"
                                     f"{_suggest(item, mechanism.links)}")
            values[name] = tuple(items)
        keys = [pair.key for pair in mechanism.slides]
        items = self.names(table, "sliding")
        for i, item in enumerate(items):
            if item not in keys:
                raise self.error(f"ask.sliding[{i}]", f"no prismatic pair '{item}'"
                                 f"{_suggest(item, keys)}; the pairs are {keys or 'none'}")
        values["sliding"] = tuple(items)
        forces = table.get("forces", False)
        if not isinstance(forces, bool):
            raise self.error("ask.forces", f"must be true or false, got {forces!r}")
        values["forces"] = forces
        return Ask(**values)

    def names(self, table: Mapping[str, Any], name: str) -> list[str]:
        items = table.get(name, [])
        if isinstance(items, str):
            items = [items]
        if not isinstance(items, list):
            raise self.error(f"ask.{name}", f"must be a list of names, got {items!r}")
        for i, item in enumerate(items):
            self.string(item, f"ask.{name}[{i}]")
        return items

    def point_ref(self, item: str, key: str, points, mechanism: Mechanism) -> str:
        """A point name, or ``X@link`` for the point of ``link`` coincident with X."""
        name, _, link = item.partition("@")
        if name not in points:
            raise self.error(key, f"unknown point '{name}'{_suggest(name, points)}")
        if link and link not in mechanism.links:
            raise self.error(key, f"unknown link '{link}'{_suggest(link, mechanism.links)}")
        return item
