"""Full-turn sweeps: exact kinematics over many crank angles, in bounded-memory chunks.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> table = sweep_table(load_exercise("exercises/compressor_slider_crank.toml"), step=90)
>>> table["angle"].tolist()
[0.0, 90.0, 180.0, 270.0]
>>> round(float(table["v_C"][1]), 6)
6.0
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator

import numpy as np

from .errors import SpecError
from .kinematics import choose_branches, solve
from .model import FRAME, Exercise
from .progress import Progress
from .scene import plan_scene
from .structure import analyse_structure
from .vectors import norm
from .vocabulary import shown_title
from .words import Message, message, number_text, plural, render

__all__ = ["CHUNK", "Extremes", "csv_rows", "sweep_angles", "sweep_chunks", "sweep_columns",
           "sweep_table"]

#: angles solved at once; memory stays bounded whatever the length of the sweep
CHUNK = 65536
#: the most crank angles one sweep solves (a 0.000036° step over a turn)
MAX_SWEEP_ANGLES = 10_000_000
#: the sweep's ends lie within this many degrees of zero
MAX_SWEEP_DEG = 36000.0


def sweep_angles(step: float, start: float = 0.0, stop: float = 360.0) -> np.ndarray:
    """Crank angles ``start, start + step, …`` below ``stop`` (deg)."""
    if not (np.isfinite(step) and step > 0):
        raise SpecError(message("--step must be a positive number of degrees, got {step}",
                                step=step))
    if not (np.isfinite(start) and np.isfinite(stop) and stop > start):
        raise SpecError(message("the sweep needs finite --from < --to, got {start} and {stop}",
                                start=start, stop=stop))
    if max(abs(start), abs(stop)) > MAX_SWEEP_DEG:
        raise SpecError(message("--from and --to must lie within ±{limit:g}°, got {start:g} and "
                                "{stop:g}", limit=MAX_SWEEP_DEG, start=start, stop=stop))
    count = math.ceil((stop - start) / step - 1e-9)
    if count > MAX_SWEEP_ANGLES:
        raise SpecError(message("--step {step:g} from {start:g}° to {stop:g}° gives {count:.3g} "
                                "crank angles; at most {limit:,} are swept (a larger --step)",
                                step=step, start=start, stop=stop, count=count,
                                limit=MAX_SWEEP_ANGLES))
    return start + step * np.arange(count, dtype=float)


def sweep_columns(exercise: Exercise) -> tuple[list[str], list[str], list[str], list[str], str]:
    """(points, links, sliding keys, curvature points, stage) a sweep reports."""
    mechanism, ask = exercise.mechanism, exercise.ask
    scene = plan_scene(exercise)
    if ask.everything:
        points = list(dict.fromkeys(p for name in mechanism.moving_links
                                    for p in mechanism.links[name].points
                                    if FRAME not in mechanism.links_with_point(p)))
        links = [link for link in mechanism.moving_links if link != mechanism.drive.link]
        return points, links, [s.key for s in mechanism.slides], [], scene.stage
    points = list(dict.fromkeys(ask.velocity + ask.acceleration + ask.curvature))
    links = list(dict.fromkeys(ask.omega + ask.epsilon))
    return points, links, list(ask.sliding), list(ask.curvature), scene.stage


def sweep_chunks(exercise: Exercise, step: float = 1.0, *, start: float = 0.0,
                 stop: float = 360.0, angles: Iterable[float] | None = None,
                 progress: bool | None = None,
                 extra: Callable | None = None) -> Iterator[dict[str, np.ndarray]]:
    """The sweep's columns (see :func:`sweep_table`) one chunk of at most :data:`CHUNK` angles
    at a time: memory stays bounded whatever the number of angles, when each chunk is written
    out or aggregated before the next (a CSV streamed to disk, running minima and maxima).

    Angles of links (``theta_L``) are unwrapped continuously across chunks.

    Parameters
    ----------
    exercise
        The exercise to sweep.
    step
        The step between crank angles, degrees.
    start
        The first crank angle, degrees.
    stop
        The last crank angle (excluded), degrees.
    angles
        The crank angles in degrees, instead of ``step``, ``start`` and ``stop``.
    progress
        Show a progress line on stderr for more than ``CHUNK`` angles (default: when stderr
        is a terminal).
    extra
        ``extra(motion) -> dict`` adds columns per chunk.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
    >>> [len(c["angle"]) for c in sweep_chunks(exercise, angles=range(0, 360, 3))]
    [120]
    """
    mechanism = exercise.mechanism
    if angles is None:
        angles = sweep_angles(step, start, stop)
    else:  # no Python list of a million floats when an array is given
        angles = np.asarray(angles if isinstance(angles, (np.ndarray, list, tuple, range))
                            else list(angles), dtype=float).ravel()
    stage, links_needed, branches = _solving(exercise, forces=extra is not None)
    points, links, slides, curvature, _ = sweep_columns(exercise)
    last_theta: dict[str, float] = {}
    with Progress(len(angles), "sweep", enabled=progress if len(angles) > CHUNK else False
                  ) as bar:
        for begin in range(0, len(angles), CHUNK):
            part = angles[begin:begin + CHUNK]
            motion = solve(mechanism, part, stage=stage, links=links_needed,
                           branches=branches)
            columns = {"angle": part} | _chunk_columns(motion, (points, links, slides, curvature),
                                                       stage == "acceleration", last_theta)
            if extra is not None:
                columns |= extra(motion)
            yield {name: np.asarray(values) for name, values in columns.items()}
            bar.advance(len(part))


def _solving(exercise: Exercise, *, forces: bool) -> tuple[str, list[str] | None, dict]:
    """How a sweep solves: to which stage, for which links (None: all, as the forces need)
    and on the branches chosen at ``drive.angle``."""
    structure = analyse_structure(exercise.mechanism)
    scene = plan_scene(exercise)
    stage = "acceleration" if forces else scene.stage
    links_needed = None if forces else scene.links
    groups = structure.groups if links_needed is None else structure.groups_needed(links_needed)
    return stage, links_needed, choose_branches(exercise.mechanism, groups)


def _chunk_columns(motion, asked: tuple[list[str], list[str], list[str], list[str]],
                   acceleration: bool, last_theta: dict[str, float]) -> dict[str, np.ndarray]:
    """A chunk's columns of the points, links, prismatic pairs and curvature points
    ``asked`` (see :func:`sweep_columns`)."""
    points, links, slides, curvature = asked
    columns: dict[str, np.ndarray] = {}
    for point in points:
        columns |= _point_columns(motion, point, acceleration)
    for link in links:
        columns |= _link_columns(motion, link, acceleration, last_theta)
    for key in slides:
        columns |= _sliding_columns(motion, key, acceleration)
    for point in curvature:
        columns[f"rho_{point}"] = motion.curvature(point).rho
    return columns


def _point_columns(motion, point: str, acceleration: bool) -> dict[str, np.ndarray]:
    """A point's columns: ``x_P y_P vx_P vy_P v_P`` (and ``ax_P ay_P a_P``)."""
    xy = motion.position(point)
    v = motion.velocity(point)
    columns = {f"x_{point}": xy[:, 0], f"y_{point}": xy[:, 1],
               f"vx_{point}": v[:, 0], f"vy_{point}": v[:, 1], f"v_{point}": norm(v)}
    if acceleration:
        a = motion.acceleration(point)
        columns |= {f"ax_{point}": a[:, 0], f"ay_{point}": a[:, 1], f"a_{point}": norm(a)}
    return columns


def _link_columns(motion, link: str, acceleration: bool, last_theta: dict[str, float]
                  ) -> dict[str, np.ndarray]:
    """A link's columns: ``theta_L`` (degrees, unwrapped continuously from the previous
    chunk's, whose last angle ``last_theta`` keeps), ``omega_L`` (and ``epsilon_L``)."""
    theta = np.degrees(np.unwrap(motion.theta(link)))
    if link in last_theta:  # continue the previous chunk's unwrapping
        theta += 360.0 * np.round((last_theta[link] - theta[0]) / 360.0)
    last_theta[link] = float(theta[-1])
    columns = {f"theta_{link}": theta, f"omega_{link}": motion.omega(link)}
    if acceleration:
        columns[f"epsilon_{link}"] = motion.epsilon(link)
    return columns


def _sliding_columns(motion, key: str, acceleration: bool) -> dict[str, np.ndarray]:
    """A prismatic pair's columns: ``s_K ds_K`` (and ``dds_K``)."""
    sliding = motion.sliding(key)
    columns = {f"s_{key}": sliding.s, f"ds_{key}": sliding.velocity}
    if acceleration:
        columns[f"dds_{key}"] = sliding.acceleration
    return columns


def sweep_table(exercise: Exercise, step: float = 1.0, *, start: float = 0.0,
                stop: float = 360.0, angles: Iterable[float] | None = None,
                progress: bool | None = None,
                extra: Callable | None = None) -> dict[str, np.ndarray]:
    """Columns of a full-turn sweep: ``angle`` and, for the scene's points, links and pairs,
    ``x_P y_P vx_P vy_P v_P ax_P ay_P a_P``, ``theta_L omega_L epsilon_L``,
    ``s_K ds_K dds_K``, ``rho_P``. The branch is the one chosen at ``drive.angle``.

    ``extra(motion) -> dict`` may add columns per chunk (the force sweep does). The whole table
    is held in memory; :func:`sweep_chunks` yields it chunk by chunk.

    Parameters
    ----------
    exercise
        The exercise to sweep.
    step
        The step between crank angles, degrees.
    start
        The first crank angle, degrees.
    stop
        The last crank angle (excluded), degrees.
    angles
        The crank angles in degrees, instead of ``step``, ``start`` and ``stop``.
    progress
        Show a progress line on stderr for more than ``CHUNK`` angles (default: when stderr
        is a terminal).
    extra
        ``extra(motion) -> dict`` adds columns per chunk.
    """
    chunks: dict[str, list[np.ndarray]] = {"angle": []}
    for columns in sweep_chunks(exercise, step, start=start, stop=stop, angles=angles,
                                progress=progress, extra=extra):
        for name, values in columns.items():
            chunks.setdefault(name, []).append(values)
    return {name: np.concatenate(parts) for name, parts in chunks.items()}


#: columns a summary leaves to the CSV (coordinates and vector components)
_COMPONENTS = ("x_", "y_", "vx_", "vy_", "ax_", "ay_")
#: rows formatted per write when streaming a CSV
ROWS_PER_WRITE = 4096


class Extremes:
    """Running minima and maxima (with their crank angles) of a sweep's columns, fed chunk by
    chunk.

    Examples
    --------
    >>> extremes = Extremes()
    >>> extremes.feed({"angle": np.array([0.0, 90.0]), "v_C": np.array([0.0, 6.0])})
    >>> extremes.table["v_C"]
    ((0.0, 0.0), (6.0, 90.0))
    """

    def __init__(self) -> None:
        self.table: dict[str, tuple | None] = {}
        self.count = 0
        self.first: float | None = None
        self.last: float | None = None

    def feed(self, chunk: dict[str, np.ndarray]) -> None:
        angles = np.asarray(chunk["angle"], dtype=float)
        if not len(angles):
            return
        self.count += len(angles)
        self.first = float(angles[0]) if self.first is None else self.first
        self.last = float(angles[-1])
        for name, values in chunk.items():
            if name == "angle" or name.startswith(_COMPONENTS):
                continue
            values = np.asarray(values, dtype=float)
            finite = np.isfinite(values)
            known = self.table.get(name)
            if not finite.any():
                self.table.setdefault(name, None)
                continue
            masked = np.where(finite, values, np.nan)
            low, high = int(np.nanargmin(masked)), int(np.nanargmax(masked))
            low = (float(values[low]), float(angles[low]))
            high = (float(values[high]), float(angles[high]))
            if known is not None:
                low = min(known[0], low, key=lambda pair: pair[0])
                high = max(known[1], high, key=lambda pair: pair[0])
            self.table[name] = (low, high)

    def describe(self, title: str, names: Callable[[str], Message | str] | None = None,
                 phi: str = "φ") -> str:
        """The extremes as a printed table, in the language spoken.

        Parameters
        ----------
        title
            The exercise's title.
        names
            Each column's name as the table prints it (the course's symbol: ω₂ for
            ``omega_BC``; words for a column that is no quantity); the column's own name
            without it.
        phi
            The crank angle's symbol (φ₁: it carries the crank's number).

        Examples
        --------
        >>> extremes = Extremes()
        >>> extremes.feed({"angle": np.array([0.0, 90.0]), "omega_BC": np.array([-2.0, 3.0])})
        >>> print(extremes.describe("Four-bar", {"omega_BC": "ω₂"}.get, "φ₁"))
        Four-bar — 2 crank angles from 0° to 90°
        <BLANKLINE>
          quantity                min    at φ₁        max    at φ₁
          ω₂                       -2       0°          3      90°
        """
        shown = {name: render((names(name) if names else None) or name) for name in self.table}
        heading = render(message("quantity"))
        width = max([16, len(heading)] + [len(text) for text in shown.values()])
        low_text, high_text = render(message("min")), render(message("max"))
        at = render(message("at {phi}", phi=phi))
        # a column is widened where its heading's translation is longer than in English
        low, high, angle = (max(10, len(low_text)), max(10, len(high_text)),
                            max(7, len(at) - 1))
        # (English says "1 crank angles", as it always did; a catalogue has every form)
        lines = [render(plural("{title} — {count} crank angles from {first:g}° to {last:g}°",
                               "{title} — {count} crank angles from {first:g}° to {last:g}°",
                               count=self.count, title=shown_title(title), first=self.first,
                               last=self.last)),
                 "", f"  {heading:<{width}} {low_text:>{low}} {at:>{angle + 1}} "
                     f"{high_text:>{high}} {at:>{angle + 1}}"]
        undefined = render(message("(undefined)"))
        for name, found in self.table.items():
            if found is None:
                lines.append(f"  {shown[name]:<{width}} {undefined}")
                continue
            (least, at_least), (most, at_most) = found
            lines.append(f"  {shown[name]:<{width}} {number_text(least, f'>{low}.5g')} "
                         f"{number_text(at_least, f'>{angle}g')}° "
                         f"{number_text(most, f'>{high}.5g')} "
                         f"{number_text(at_most, f'>{angle}g')}°")
        return "\n".join(lines)


def csv_rows(chunk: dict[str, np.ndarray]) -> Iterator[str]:
    """A chunk of a sweep as CSV lines (full precision: the shortest text that reads back to
    the same float; blank where a value is undefined)."""
    block = np.column_stack([np.asarray(values, dtype=float) for values in chunk.values()])
    for first in range(0, len(block), ROWS_PER_WRITE):
        for row in block[first:first + ROWS_PER_WRITE].tolist():
            yield ",".join(repr(v) if math.isfinite(v) else "" for v in row) + "\n"
