"""Following an assembly from ``drive.angle`` to another crank angle, as a sweep follows it.

A group's assembly is chosen once, at ``drive.angle`` (the sketch or the default branch,
:meth:`~planmethod.kinematics.program.Model.branches`). :func:`follow` checks that it can be
followed to another crank angle — no group whose assembly was chosen among several meets a
limit (toggle) position on the way — and :func:`pose` gives the mechanism posed there on that
assembly (see docs/continuation.md).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> mechanism = load_exercise("exercises/compressor_slider_crank.toml").mechanism
>>> posed = pose(mechanism, 100.0)
>>> posed.mechanism.drive.angle, posed.branches[0], posed.start
(100.0, Branch(sign=1, reason='sketch'), 45.0)
"""

from __future__ import annotations

import dataclasses
import heapq
import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import PlanmethodError, SpecError, ToggleError
from ..model import FRAME, Mechanism
from ..spec import MAX_ANGLE_DEG
from ..words.message import message
from .groups import kind_module
from .motion import Motion, solve
from .program import Branch, Model, model

__all__ = ["FOLLOW_FLOOR_DEG", "FOLLOW_POINTS", "FOLLOW_REFINEMENTS", "FOLLOW_STEP_DEG", "Posed",
           "follow", "pose"]

#: the crank-angle step (deg) of the sweep that follows the assembly from ``drive.angle``
FOLLOW_STEP_DEG = 1.0
#: angles per refinement of a stretch of that sweep where a group may meet its limit position
FOLLOW_POINTS = 16
#: stretches are refined down to this width (deg)
FOLLOW_FLOOR_DEG = 1e-10
#: the most stretches refined in one :func:`follow`
FOLLOW_REFINEMENTS = 256


@dataclass(frozen=True, slots=True)
class Posed:
    """A mechanism posed at another crank angle on the assembly followed from its own
    ``drive.angle`` (``start``): its ``drive.angle`` is the new angle and its sketch holds the
    followed positions of every point of its groups, so that any solve of it at its
    ``drive.angle`` takes that assembly. ``branches``: its groups' branches, each with the
    reason it was chosen for at ``start`` (``sketch``, ``default``, ``unique``)."""

    mechanism: Mechanism
    branches: Mapping[int, Branch]
    start: float


def _path_order(start: float, angles: np.ndarray) -> np.ndarray:
    return np.abs(angles - start)


def _doubtful(sine: np.ndarray) -> np.ndarray:
    """The stretches [k, k + 1] of a sweep (uniform steps) where a dyad may meet its limit
    position between the samples: its lines' sine s changes sign there, or s², extrapolated
    linearly from a neighbouring stretch over twice the step, reaches zero across it (near a
    limit position s² falls linearly with the crank angle; an ordinary minimum of s is
    resolved by the samples and extrapolates to a positive value)."""
    sine = np.asarray(sine, dtype=float)
    square = sine * sine
    doubtful = sine[:-1] * sine[1:] <= 0.0
    if sine.shape[0] >= 3:
        doubtful[1:] |= 3.0 * square[1:-1] - 2.0 * square[:-2] <= 0.0     # from the left
        doubtful[:-1] |= 3.0 * square[1:-1] - 2.0 * square[2:] <= 0.0     # from the right
    return np.flatnonzero(doubtful)


def _solvable_prefix(mechanism: Mechanism, angles: np.ndarray, links, stage: str
                     ) -> tuple[Motion | None, int, PlanmethodError | None]:
    """(the motion over the longest prefix of ``angles`` that solves, its length, the error at
    the next angle or None)."""
    try:
        return solve(mechanism, angles, stage=stage, links=links), angles.shape[0], None
    except PlanmethodError:
        pass
    good, bad = 0, angles.shape[0]          # angles[:good] solves, angles[:bad] does not
    while bad - good > 1:
        middle = (good + bad) // 2
        try:
            solve(mechanism, angles[:middle], stage=stage, links=links)
            good = middle
        except PlanmethodError:
            bad = middle
    motion = solve(mechanism, angles[:good], stage=stage, links=links) if good else None
    try:
        solve(mechanism, angles[good:good + 1], stage=stage, links=links)
    except PlanmethodError as error:
        return motion, good, error
    # the angle solves alone (a chunk's refusal): take the error of the prefix
    try:
        solve(mechanism, angles[:good + 1], stage=stage, links=links)
    except PlanmethodError as error:
        return motion, good, error
    raise PlanmethodError(message("internal error: a refused prefix solves"))  # pragma: no cover


def follow(mechanism: Mechanism, angle: float, *, links: Iterable[str] | None = None) -> None:
    """Check that each group's assembly chosen at ``drive.angle`` can be followed to crank
    angle ``angle`` (deg), turning the crank from ``drive.angle`` to ``angle`` (as numbers, not
    modulo 360°), as a sweep follows it.

    A dyad's assembly is its branch sign, the same at every angle: what is checked is that no
    group whose assembly was chosen among several (nor a group it rests on) meets a limit
    (toggle) position on the way (swept as :func:`_first_refusal` says); a class III group
    follows its own continuation path.

    Parameters
    ----------
    mechanism
        The model (its ``drive.angle`` is where the assemblies were chosen).
    angle
        The crank angle to follow the assembly to (deg).
    links
        Only the groups on the way to these links (default: all).

    Raises
    ------
    ToggleError
        Where a dyad meets a limit (toggle) position on the way: the message names the group,
        the crank angle of the limit (to 1e-9°) and why the group cannot go on.
    AssemblyError, ConvergenceError, BranchJumpError
        As :func:`solve`, where the mechanism cannot be assembled at ``drive.angle`` or a class
        III group cannot be continued.

    Examples
    --------
    >>> from planmethod.spec import exercise_from_dict
    >>> rocker = exercise_from_dict({
    ...     "drive": {"link": "AB", "pivot": "A", "angle": 60, "omega": 1},
    ...     "links": {"frame": {"A": [0, 0], "D": [0.30, 0]},
    ...               "AB": {"A": [0, 0], "B": [0.20, 0]},
    ...               "BC": {"B": [0, 0], "C": [0.22, 0]},
    ...               "CD": {"C": [0, 0], "D": [0.18, 0]}}}).mechanism
    >>> follow(rocker, 90.0)
    >>> follow(rocker, 150.0)
    Traceback (most recent call last):
    ...
    planmethod.errors.ToggleError: link BC+CD, crank angle 104.478°: the assembly chosen at \
drive.angle 60° cannot be followed to 150°: turning the crank from 60°, the group reaches \
a limit (toggle) position at crank angle 104.477512°, past which its assembly cannot be \
followed (just beyond: ... short by ... m)
    """
    start, angle = float(mechanism.drive.angle), float(angle)
    if angle == start:
        return
    found = model(mechanism)
    chosen = _chosen_among_several(found, links)
    if not chosen:
        return
    dyads = [group.index for group in found.groups(chosen) if group.is_dyad]
    failure = _first_refusal(mechanism, _way(start, angle), chosen, dyads)
    if failure is not None:
        _raise_limit(mechanism, found, chosen, start, angle, *failure)


def _chosen_among_several(found: Model, links: Iterable[str] | None) -> list[str]:
    """The links of the groups (on the way to ``links``) whose assembly was chosen among
    several: a dyad with one assembly has nothing to follow."""
    return [link for group in found.groups(links)
            if not group.is_dyad or kind_module(group).branches > 1 for link in group.links]


def _way(start: float, angle: float) -> np.ndarray:
    """The crank angles from ``start`` to ``angle``, every :data:`FOLLOW_STEP_DEG` (one turn
    at most: a dyad's positions repeat every turn), ``angle`` last if it is within a turn."""
    span = angle - start
    width = min(abs(span), 360.0)
    count = max(2, math.ceil(width / FOLLOW_STEP_DEG - 1e-9) + 1)
    grid = start + math.copysign(1.0, span) * np.linspace(0.0, width, count)
    if abs(span) <= 360.0:
        grid[-1] = angle
    return grid


def _first_refusal(mechanism: Mechanism, grid: np.ndarray, links: list[str],
                   dyads: list[int]) -> tuple[float, float, PlanmethodError] | None:
    """(the last angle solved, the first refused, its error) along the way ``grid`` from
    ``drive.angle``, or None if every angle solves. The way is solved with the compiled
    program, to the velocity stage (each dyad's sine s of the angle between its construction
    lines), and refined only where a dyad's s may reach zero between two samples
    (:func:`_doubtful`), nearest stretch first."""
    start = float(mechanism.drive.angle)
    failure: tuple[float, float, PlanmethodError] | None = None   # (last good, bad, error)
    stretches = [(0.0, 0, grid)]   # (distance along the way, tie-break, angles), nearest first
    refinements = 0
    while stretches:
        _, _, angles = heapq.heappop(stretches)
        if failure is not None:                 # only what lies before the failure found
            before = _path_order(start, angles) < _path_order(start, np.array([failure[1]]))
            angles = angles[before]
            if angles.shape[0] < 2:
                continue
        motion, good, error = _solvable_prefix(mechanism, angles, links, "velocity")
        if error is not None:
            if good == 0:   # the start of the stretch was solved before, or is drive.angle
                raise error
            failure = (float(angles[good - 1]), float(angles[good]), error)
            angles = angles[:good]
        if motion is None or angles.shape[0] < 2:
            continue
        for low, high in _doubtful_stretches(motion, dyads, angles):
            if abs(high - low) <= FOLLOW_FLOOR_DEG or refinements >= FOLLOW_REFINEMENTS:
                continue
            refinements += 1
            heapq.heappush(stretches, (abs(low - start), refinements,
                                       np.linspace(low, high, FOLLOW_POINTS + 1)))
    return failure


def _doubtful_stretches(motion: Motion, dyads: list[int], angles: np.ndarray
                        ) -> Iterator[tuple[float, float]]:
    """The stretches of ``angles`` where one of the ``dyads`` may meet its limit position."""
    for index in dyads:
        sine = np.atleast_1d(motion.groups[index].line_sine)[:angles.shape[0]]
        for k in _doubtful(sine):
            yield float(angles[k]), float(angles[k + 1])


def _raise_limit(mechanism: Mechanism, found: Model, links: list[str], start: float,
                 angle: float, good: float, bad: float, error: PlanmethodError) -> None:
    """Raise the error of a group that cannot be followed past a crank angle between ``good``
    (solved) and ``bad`` (refused with ``error``): a dyad's limit position, found to 1e-9°;
    a class III group's own continuation error as it is."""
    group = next((g for g in found.structure.groups if g.name == error.link), None)
    if group is None or not group.is_dyad:
        raise error
    stage = "velocity"
    try:   # where the links no longer reach, the limit itself is found by the positions
        solve(mechanism, bad, stage="position", links=links)
    except PlanmethodError as refused:
        stage, error = "position", refused
    while abs(bad - good) > 1e-9:
        middle = 0.5 * (good + bad)
        try:
            solve(mechanism, middle, stage=stage, links=links)
            good = middle
        except PlanmethodError as refused:
            bad, error = middle, refused
    refused_group = next((g for g in found.structure.groups if g.name == error.link), group)
    raise ToggleError(message(
        "the assembly chosen at drive.angle {start:g}° cannot be followed to {angle:g}°: "
        "turning the crank from {start:g}°, the group reaches a limit (toggle) position at "
        "crank angle {limit:.9g}°, past which its assembly cannot be followed (just beyond: "
        "{reason})", start=start, angle=angle, limit=good, reason=error.message),
        line_angle_deg=0.0, link=refused_group.name, angle=good)


def pose(mechanism: Mechanism, angle: float, *, links: Iterable[str] | None = None) -> Posed:
    """The mechanism posed at crank angle ``angle`` (deg) on the assembly chosen at its
    ``drive.angle`` and followed to ``angle`` as a sweep follows it (:func:`follow`), rather
    than chosen again there from a sketch made for ``drive.angle``.

    Parameters
    ----------
    mechanism
        The model.
    angle
        The crank angle (deg), within ±36,000° as ``drive.angle``.
    links
        Only the groups on the way to these links are followed and checked (default: all);
        the positions of the others are posed where they can be assembled.

    Raises
    ------
    SpecError
        If ``angle`` is not a finite number within ±36,000°.
    ToggleError, AssemblyError, ConvergenceError, BranchJumpError
        As :func:`follow` (an error at ``drive.angle`` says it is where the assembly is chosen).

    Examples
    --------
    A Whitworth quick-return whose sketch, made for ``drive.angle`` = 30°, is nearer the other
    assembly of its slotted lever at 250°: posed there, the lever keeps the assembly a sweep
    from 30° follows.

    >>> from planmethod.spec import load_exercise
    >>> mechanism = load_exercise("tests/data/continuation/whitworth_quick_return.toml").mechanism
    >>> posed = pose(mechanism, 250.0)
    >>> posed.mechanism.drive.angle, posed.branches[0]
    (250.0, Branch(sign=1, reason='sketch'))
    >>> solve(posed.mechanism).at(0).position("C").round(4)
    array([-0.0642, -0.1414])
    >>> solve(mechanism, 250.0).at(0).position("C").round(4)   # as a sweep from 30° finds it
    array([-0.0642, -0.1414])
    """
    start = float(mechanism.drive.angle)
    if not (math.isfinite(angle) and abs(angle) <= MAX_ANGLE_DEG):
        raise SpecError(message("the crank angle must be a finite number of degrees within "
                                "±{limit:g}°, got {angle!r}", limit=MAX_ANGLE_DEG, angle=angle))
    angle = float(angle)
    found = model(mechanism)
    groups = found.groups(links)
    original = _chosen_at_start(found, groups, angle)
    if angle == start:
        return Posed(mechanism, original, start)
    follow(mechanism, angle, links=links)
    points = _followed_points(mechanism, angle, links)
    posed = dataclasses.replace(mechanism, drive=dataclasses.replace(mechanism.drive,
                                                                     angle=angle),
                                sketch={**mechanism.sketch, **points})
    branches = {index: dataclasses.replace(branch, reason=original[index].reason)
                for index, branch in model(posed).branches(groups).items()}
    if not all(group.is_dyad for group in groups):   # a class III group's search: check it
        _check_followed(posed, links, branches, points, start)
    return Posed(posed, branches, start)


def _chosen_at_start(found: Model, groups, angle: float) -> Mapping[int, Branch]:
    """The groups' branches chosen at ``drive.angle``; an error there says that it is where
    the assembly followed to ``angle`` is chosen."""
    start = float(found.mechanism.drive.angle)
    try:
        return found.branches(groups)
    except PlanmethodError as error:
        if angle != start and error.angle == start:   # say why that angle, not the one asked
            error.message = message("{reason} (at drive.angle, where the assembly followed to "
                                    "{angle:g}° is chosen)", reason=error.message, angle=angle)
            error.args = (str(error),)
        raise


def _followed_points(mechanism: Mechanism, angle: float, links) -> dict[str, tuple[float, ...]]:
    """Every point of the groups solved at ``angle`` on the assemblies followed there (of the
    whole mechanism where it assembles, else of the groups on the way to ``links``)."""
    try:
        here = solve(mechanism, angle, stage="position")
    except PlanmethodError:
        here = solve(mechanism, angle, stage="position", links=links)
    fixed = (FRAME, mechanism.drive.link)
    return {point: tuple(float(v) for v in here.at(0).position(point))
            for link in here.solved if link not in fixed
            for point in mechanism.links[link].points}


def _check_followed(posed: Mechanism, links, branches: Mapping[int, Branch],
                    points: Mapping[str, tuple[float, ...]], start: float) -> None:
    """A :class:`PlanmethodError` unless the assemblies found at the posed mechanism's
    ``drive.angle`` with ``branches`` put every point where it was followed to (a dyad's
    assembly nearest its exact positions is that one; a class III group's is the nearest its
    search found at the angle: this makes sure it found the followed one)."""
    angle = float(posed.drive.angle)
    check = solve(posed, angle, stage="position", links=links, branches=branches,
                  reference=True)
    solved = {point for link in check.solved for point in posed.links[link].points}
    size = max(math.hypot(*xy) for xy in points.values())
    for point, xy in points.items():
        away = math.dist(check.at(0).position(point), xy) if point in solved else 0.0
        if away > 1e-9 * size:
            raise PlanmethodError(message(
                "the assembly followed from drive.angle {start:g}° is not among the "
                "assemblies found at crank angle {angle:g}° (point {point} is {away:.3g} m "
                "away)", start=start, angle=angle, point=point, away=away), angle=angle)
