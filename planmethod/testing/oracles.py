"""Exact solvers independent of planmethod's own: the oracles of the tests and benchmarks.

Two oracles, sharing no formula with the group kinds of :mod:`planmethod.kinematics.groups`:

* :func:`reference_motion` solves the **whole mechanism's constraint equations** Φ(q) = 0 (the
  generic :class:`~planmethod.kinematics.constraints.ConstraintSystem`, q = (x, y, θ) of every
  moving link but the drive): positions by Newton's method, started at ``drive.angle`` from the
  exercise's sketch and carried to every other crank angle by continuation along the crank
  angle (each step started from its neighbour's solution); then velocities and accelerations
  by the two exact linear solves Φ_q·q̇ = −Φ_known·q̇_known and Φ_q·q̈ = γ − Φ_known·q̈_known.
  It never starts from :func:`~planmethod.kinematics.solve`'s answer.
* :func:`exact_fourbar` and :func:`exact_slider_crank` evaluate the four-bar and the
  slider-crank by their textbook closed forms in ``DIGITS``-digit arithmetic (mpmath, imported
  when they are called: it is in the ``test`` extra).

Examples
--------
>>> from planmethod.spec import exercise_from_dict
>>> from planmethod.testing.mechanisms import fourbar
>>> mechanism = exercise_from_dict(fourbar()).mechanism
>>> reference = reference_motion(mechanism, [60.0, 200.0])
>>> [round(float(value), 6) for value in reference["CD"]["omega"]]
[2.448975, 0.24989]
>>> exact = exact_fourbar(60.0)          # the same four-bar, to 40 digits
>>> round(float(exact["omega_CD"]), 6)
2.448975
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Mapping, Sequence

import numpy as np

from ..kinematics.constraints import ConstraintSystem
from ..kinematics.state import LinkState
from ..model import FRAME, Mechanism
from ..vectors import cross, dot, norm, perp, rotate

__all__ = [
    "DIGITS",
    "exact_fourbar",
    "exact_slider_crank",
    "reference_motion",
    "reference_place",
    "reference_positions",
]

#: the largest continuation step (deg)
STEP = 5.0
#: the smallest continuation step before giving up (deg)
SMALLEST_STEP = 1e-6
#: Newton stops when its correction is below this (relative to the mechanism's size; rad)
CORRECTION = 1e-14


# -- the whole mechanism's constraint equations -------------------------------------------------
def _size(mechanism: Mechanism) -> float:
    """The mechanism's length scale: the largest coordinate of any point (m)."""
    return max([abs(v) for link in mechanism.links.values() for p in link.points.values()
                for v in p] + [1e-300])


def _driven(mechanism: Mechanism, angles: np.ndarray) -> dict[str, LinkState]:
    """The frame and the drive link at crank angles ``angles`` (deg), with their motion."""
    drive = mechanism.drive
    count = angles.shape[0]
    zero, zeros = np.zeros(count), np.zeros((count, 2))
    theta = np.radians(angles)
    pivot = np.array(mechanism.local(FRAME, drive.pivot))
    x, y = mechanism.local(drive.link, drive.pivot)
    arm = -rotate(np.array([x, y], dtype=float), theta)   # pivot → the drive's origin
    turned = perp(arm)
    omega, epsilon = np.full(count, drive.omega), np.full(count, drive.epsilon)
    return {
        FRAME: LinkState(zero, zeros, zero, zeros, zero, zeros),
        drive.link: LinkState(theta, pivot + arm, omega, drive.omega * turned, epsilon,
                              drive.epsilon * turned - drive.omega ** 2 * arm),
    }


def _states(system: ConstraintSystem, fixed: Mapping[str, LinkState], q: np.ndarray
            ) -> dict[str, LinkState]:
    states = dict(fixed)
    for index, link in enumerate(system.unknown):
        states[link] = LinkState(np.ascontiguousarray(q[:, 3 * index + 2]),
                                 np.ascontiguousarray(q[:, 3 * index:3 * index + 2]))
    return states


def _scaled(q: np.ndarray, size: float) -> np.ndarray:
    """q with the positions divided by the mechanism's size (angles as they are)."""
    out = np.array(q, dtype=float)
    out[:, 0::3] /= size
    out[:, 1::3] /= size
    return out


def _newton(system: ConstraintSystem, fixed: Mapping[str, LinkState], q: np.ndarray,
            size: float, iterations: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on Φ(q) = 0 from ``q`` (N, 3u), every row at once; returns the solution
    and whether each row converged (its correction fell below ``CORRECTION``, then one more
    step was taken)."""
    q = np.array(q, dtype=float)
    converged = np.zeros(q.shape[0], dtype=bool)
    settled = np.zeros(q.shape[0], dtype=bool)
    for _ in range(iterations):
        states = _states(system, fixed, q)
        residual = system.residual(states)
        matrix, _ = system.jacobian(states)
        with np.errstate(all="ignore"):
            try:
                step = np.linalg.solve(matrix, residual[..., None])[..., 0]
            except np.linalg.LinAlgError:   # a singular row: solve the others one by one
                step = np.full_like(q, np.nan)
                for row in range(q.shape[0]):
                    with contextlib.suppress(np.linalg.LinAlgError):
                        step[row] = np.linalg.solve(matrix[row], residual[row])
        finite = np.all(np.isfinite(step), axis=1)
        step[~finite] = 0.0
        q = q - step
        converged |= settled & finite
        settled = finite & (np.abs(_scaled(step, size)).max(axis=1) <= CORRECTION)
        if converged.all():
            break
    return q, converged


def _tangent(system: ConstraintSystem, fixed: Mapping[str, LinkState], q: np.ndarray
             ) -> np.ndarray:
    """dq/dφ (per radian of crank angle) at ``q``: the velocities at a unit drive rate."""
    mechanism = system.mechanism
    states = _states(system, fixed, q)
    turning = states[mechanism.drive.link]
    arm = turning.origin - np.array(mechanism.local(FRAME, mechanism.drive.pivot))
    states[mechanism.drive.link] = LinkState(
        turning.theta, turning.origin, np.ones_like(turning.theta),
        perp(arm))
    with np.errstate(all="ignore"):
        return system.velocities(states)


def _fit(pairs: list[tuple[tuple[float, float], np.ndarray]]) -> tuple[float, np.ndarray]:
    """The pose (θ, origin) that lays the local points onto the global ones, least squares."""
    local = np.array([p for p, _ in pairs], dtype=float)
    world = np.array([g for _, g in pairs], dtype=float)
    a, b = local - local.mean(axis=0), world - world.mean(axis=0)
    theta = math.atan2(float(np.sum(cross(a, b))), float(np.sum(dot(a, b))))
    origin = world.mean(axis=0) - rotate(local.mean(axis=0), theta)
    return theta, origin


def _guess(mechanism: Mechanism, unknown: Sequence[str], fixed: Mapping[str, LinkState],
           near: Mapping[str, Sequence[float]]) -> np.ndarray:
    """A start for Newton at ``drive.angle``, (1, 3u): each unknown link laid onto the points
    whose places are known (the frame's, the drive's, then ``near``'s, then the links placed
    before it) — by two or more points, or by one point and the angle a prismatic pair gives
    it; a slide whose point and guide point are both known turns its guide along the line
    between them (the travel positive)."""
    layout = _Layout(mechanism)
    for link, state in fixed.items():
        layout.poses[link] = (float(state.theta[0]), state.origin[0])
    for name, point in near.items():
        layout.places[name] = np.array(point, dtype=float)
    for link in fixed:
        layout.put(link, *layout.poses[link])
    waiting = list(unknown)
    while waiting:
        placed = [link for link in waiting if layout.place_one(link, loose=False)]
        if not placed:
            placed = [waiting[0]] if layout.place_one(waiting[0], loose=True) else []
        waiting = [link for link in waiting if link not in placed]
    return np.array([[*layout.poses[link][1], layout.poses[link][0]]
                     for link in unknown]).reshape(1, -1)


class _Layout:
    """The links laid so far for :func:`_guess`: each placed link's pose (angle, origin)
    and the places of the points known."""

    def __init__(self, mechanism: Mechanism) -> None:
        self.mechanism = mechanism
        self.places: dict[str, np.ndarray] = {}
        self.poses: dict[str, tuple[float, np.ndarray]] = {}

    def put(self, link: str, theta: float, origin: np.ndarray) -> None:
        """Place ``link`` at the pose, and so its points."""
        self.poses[link] = (theta, origin)
        for name, local in self.mechanism.links[link].points.items():
            self.places[name] = origin + rotate(local, theta)

    def turn_of(self, link: str) -> float | None:
        """The angle a prismatic pair with a placed link gives ``link``."""
        for slide in self.mechanism.slides:
            if slide.link == link and slide.along in self.poses:
                return self.poses[slide.along][0] + slide.direction_rad
            if slide.along == link and slide.link in self.poses:
                return self.poses[slide.link][0] - slide.direction_rad
        return None

    def along_line(self, link: str) -> float | None:
        """The angle of ``link`` from a slide whose point and guide point are both placed."""
        places, poses = self.places, self.poses
        for slide in self.mechanism.slides:
            if link in (slide.link, slide.along) and slide.point in places and (
                    slide.through in places) and slide.link not in poses and (
                    slide.along not in poses):
                gap = places[slide.point] - places[slide.through]
                if norm(gap) > 0:
                    line = math.atan2(gap[1], gap[0])
                    return line if link == slide.link else line - slide.direction_rad
        return None

    def place_one(self, link: str, loose: bool) -> bool:
        """Place ``link`` if what is known allows (``loose``: by any means), and say so."""
        points = self.mechanism.links[link].points
        known = [(local, self.places[name]) for name, local in points.items()
                 if name in self.places]
        if len(known) >= 2:
            self.put(link, *_fit(known))
            return True
        theta = self.turn_of(link)
        if theta is None:
            theta = self.along_line(link)
        if theta is None and not loose:
            return False
        theta = 0.0 if theta is None else theta
        if known:
            (x, y), world = known[0]
        elif loose:   # no point known: put the link's origin among the known places
            (x, y), world = (0.0, 0.0), np.mean(list(self.places.values()), axis=0)
        else:
            return False
        self.put(link, theta, world - rotate((x, y), theta))
        return True


def _unknown(mechanism: Mechanism) -> list[str]:
    return [name for name in mechanism.moving_links if name != mechanism.drive.link]


def _start(mechanism: Mechanism, system: ConstraintSystem, size: float,
           near: Mapping[str, Sequence[float]] | None) -> np.ndarray:
    """The assembly at ``drive.angle``: Newton from :func:`_guess`."""
    angle = np.array([float(mechanism.drive.angle)])
    fixed = _driven(mechanism, angle)
    points = dict(mechanism.sketch if near is None else near)
    q, converged = _newton(system, fixed, _guess(mechanism, system.unknown, fixed, points),
                           size)
    if not converged.all():
        raise ValueError(f"Newton found no assembly at the drive angle {angle[0]:g}°")
    return q


def _step(system: ConstraintSystem, size: float, here, q: np.ndarray, tangent: np.ndarray,
          ahead: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton at the angles ``ahead`` (deg, (M,)), each predicted from ``q`` at ``here`` along
    ``tangent`` (one row, or a row per angle); returns the solutions and which are accepted:
    converged, and corrected by less than a quarter of the predicted move plus a quarter of
    the turn (scaled), so that a correction onto another assembly is refused."""
    turn = np.radians(ahead - here)[:, None]
    moved = tangent * turn
    predicted = q + moved
    solved, converged = _newton(system, _driven(system.mechanism, ahead), predicted, size,
                                iterations=12)
    jump = np.abs(_scaled(solved - predicted, size)).max(axis=1)
    allowed = 0.25 * (np.abs(_scaled(moved, size)).max(axis=1) + np.abs(turn[:, 0])) + 1e-12
    return solved, converged & (jump <= allowed)


def _walk(system: ConstraintSystem, size: float, here: float, q: np.ndarray, target: float,
          step: float) -> tuple[list[float], list[np.ndarray], list[np.ndarray]]:
    """Continuation from ``q`` (1, 3u) at ``here`` to ``target`` (deg) in steps of at most
    ``step``, each halved while it is refused (down to ``SMALLEST_STEP``) and doubled again
    after each accepted one; returns the angles,
    positions and tangents of the points on the way (``here`` first)."""
    angles, positions = [here], [q]
    tangents = [_tangent(system, _driven(system.mechanism, np.array([here])), q)]
    length = step
    while here != target:
        while True:
            ahead = target if abs(target - here) <= length else here + math.copysign(
                length, target - here)
            solved, accepted = _step(system, size, here, q, tangents[-1], np.array([ahead]))
            if accepted.all():
                break
            length /= 2.0
            if length < SMALLEST_STEP:
                raise ValueError(f"no continuation from {here:.9g}° towards {target:g}°: "
                                 "the mechanism does not assemble there, or reaches a toggle")
        length = min(step, 2.0 * length)
        here, q = ahead, solved
        angles.append(here)
        positions.append(q)
        tangents.append(_tangent(system, _driven(system.mechanism, np.array([here])), q))
    return angles, positions, tangents


def _continue(system: ConstraintSystem, size: float, start: np.ndarray, targets: np.ndarray,
              step: float) -> np.ndarray:
    """Positions at ``targets`` (deg, all on one side of ``drive.angle``) by continuation from
    ``start`` at ``drive.angle``: a walk to the farthest target in steps of at most ``step``,
    then every target at once by Newton from the last point of the walk before it (predicted
    along the tangent there); a target refused that way is walked to from that point."""
    drive = float(system.mechanism.drive.angle)
    farthest = float(targets[np.argmax(np.abs(targets - drive))])
    angles, positions, tangents = _walk(system, size, drive, start, farthest, step)
    walked = np.array(angles)
    behind = np.searchsorted(np.abs(walked - drive), np.abs(targets - drive), side="right") - 1
    out, accepted = _step(system, size, walked[behind], np.concatenate(positions)[behind],
                          np.concatenate(tangents)[behind], targets)
    for row in np.flatnonzero(~accepted):
        index = behind[row]
        out[row] = _walk(system, size, angles[index], positions[index], float(targets[row]),
                         step)[1][-1][0]
    return out


def _turned_by_slides(mechanism: Mechanism) -> bool:
    """Whether every link's angle follows from the drive's through prismatic pairs alone: then
    the constraint equations are linear in the links' places and the assembly is unique."""
    turned = {FRAME, mechanism.drive.link}
    grown = True
    while grown:
        grown = False
        for slide in mechanism.slides:
            ends = {slide.link, slide.along}
            if len(ends & turned) == 1:
                turned |= ends
                grown = True
    return turned >= set(mechanism.links)


def _direct(system: ConstraintSystem, size: float, angles: np.ndarray) -> np.ndarray:
    """Positions of a mechanism with a unique assembly: Newton at every angle at once, each
    from the places the frame, the drive and the prismatic pairs give (no continuation: it
    could not pass where the solution runs off to infinity, as two parallel guides do)."""
    mechanism = system.mechanism
    starts = np.concatenate([_guess(mechanism, system.unknown,
                                    _driven(mechanism, np.array([angle])), {})
                             for angle in angles]) if angles.size else (
        np.empty((0, 3 * len(system.unknown))))
    q, converged = _newton(system, _driven(mechanism, angles), starts, size)
    if not converged.all():
        bad = float(angles[np.flatnonzero(~converged)[0]])
        raise ValueError(f"Newton found no assembly at {bad:g}°")
    return q


def reference_positions(mechanism: Mechanism, angles: Sequence[float], *,
                        near: Mapping[str, Sequence[float]] | None = None,
                        step: float = STEP) -> tuple[tuple[str, ...], np.ndarray]:
    """Positions of every moving link but the drive by Newton on the whole mechanism's
    constraint equations, continued from ``drive.angle`` along the crank angle.

    Where every link's angle follows from the drive's through prismatic pairs (the PRP and
    RPP dyads), the assembly is unique and each angle is solved directly, without
    continuation.

    Parameters
    ----------
    mechanism
        The model.
    angles
        Crank angles (deg), taken as numbers (not modulo 360°): −10° is reached from
        ``drive.angle`` going down.
    near
        Rough places of some points at ``drive.angle`` that pick the assembly (default: the
        mechanism's sketch), as the sketch does for the solver. Without them a link is laid
        as the known points and the prismatic pairs suggest (a guide through a known point
        turned towards its slider's known point).
    step
        The largest continuation step (deg).

    Returns
    -------
    (links, q)
        The links, and their (x, y, θ) at each angle, shape (N, 3·len(links)).

    Raises
    ------
    ValueError
        If Newton finds no assembly, or the continuation cannot reach an angle.

    Examples
    --------
    >>> from planmethod.spec import exercise_from_dict
    >>> from planmethod.testing.mechanisms import slider_crank
    >>> links, q = reference_positions(exercise_from_dict(slider_crank()).mechanism, [0.0])
    >>> links, [round(float(v), 12) for v in q[0]]
    (('BC', 'slider'), [0.06, 0.0, 0.0, 0.24, 0.0, 0.0])
    """
    angles = np.asarray(angles, dtype=float).ravel()
    system = ConstraintSystem.between(mechanism, _unknown(mechanism))
    rows, columns = system.size
    if rows != columns:
        raise ValueError(f"the constraint equations are {rows} for {columns} unknowns")
    size = _size(mechanism)
    if _turned_by_slides(mechanism):
        return system.unknown, _direct(system, size, angles)
    start = _start(mechanism, system, size, near)
    q = np.empty((angles.shape[0], start.shape[1]))
    drive = float(mechanism.drive.angle)
    for upward in (True, False):
        chosen = np.flatnonzero(angles >= drive if upward else angles < drive)
        if chosen.size:
            q[chosen] = _continue(system, size, start, angles[chosen], step)
    return system.unknown, q


def reference_motion(mechanism: Mechanism, angles: Sequence[float], *,
                     near: Mapping[str, Sequence[float]] | None = None,
                     step: float = STEP) -> dict[str, dict]:
    """Poses, velocities and accelerations of every moving link but the drive, from the whole
    mechanism's constraint equations alone.

    Positions by :func:`reference_positions` (Newton, continued from ``drive.angle``; ``near``
    and ``step`` as there), then velocities and accelerations by one exact linear solve each
    at those positions.

    Returns
    -------
    dict
        ``{link: {"theta", "origin", "omega", "velocity", "epsilon", "acceleration"}}``
        (θ in rad, not unwrapped; the origin's place, velocity and acceleration), arrays over
        ``angles``.
    """
    angles = np.asarray(angles, dtype=float).ravel()
    links, q = reference_positions(mechanism, angles, near=near, step=step)
    system = ConstraintSystem.between(mechanism, links)
    moving = system.moving_states(_states(system, _driven(mechanism, angles), q))
    return {name: {"theta": state.theta, "origin": state.origin,
                   "omega": state.omega, "velocity": state.velocity,
                   "epsilon": state.epsilon, "acceleration": state.acceleration}
            for name, state in moving.items()}


def reference_place(mechanism: Mechanism, reference: Mapping[str, dict], point: str
                    ) -> np.ndarray:
    """The global place of ``point`` in a :func:`reference_motion` result, (N, 2), from the
    first of its links there (not the frame or the drive: they are not in the result).

    Examples
    --------
    >>> from planmethod.spec import exercise_from_dict
    >>> from planmethod.testing.mechanisms import slider_crank
    >>> mechanism = exercise_from_dict(slider_crank()).mechanism
    >>> places = reference_place(mechanism, reference_motion(mechanism, [0.0, 180.0]), "C")
    >>> (places.round(12) + 0.0).tolist()
    [[0.24, 0.0], [0.12, 0.0]]
    """
    for link in mechanism.links_with_point(point):
        if link in reference:
            theta, origin = reference[link]["theta"], reference[link]["origin"]
            return origin + rotate(mechanism.local(link, point), theta)
    raise KeyError(f"{point} is on no link of the reference (the frame or the drive only?)")


# -- 40-digit closed forms ------------------------------------------------------------------------
#: working precision of the closed forms (significant decimal digits)
DIGITS = 40


def _mpmath():
    import mpmath

    return mpmath


def _crank(mp, ax, ay, crank, phi_deg, omega, epsilon):
    phi = mp.radians(mp.mpf(phi_deg))
    c, s = mp.cos(phi), mp.sin(phi)
    b = (ax + crank * c, ay + crank * s)
    v = (-omega * crank * s, omega * crank * c)
    a = (-epsilon * crank * s - omega ** 2 * crank * c,
         epsilon * crank * c - omega ** 2 * crank * s)
    return b, v, a


def exact_fourbar(phi_deg, *, ground=(0.30, 0.0), crank=0.08, coupler=0.22, rocker=0.18,
                  omega=10.0, epsilon=0.0, above=True, digits: int = DIGITS) -> dict:
    """The four-bar A = (0, 0), D = ``ground``, AB = ``crank``, BC = ``coupler``,
    CD = ``rocker`` at crank angle ``phi_deg`` by its closed form in ``digits`` digits; C on
    the left of B→D when ``above`` (for D on +x: C above the line BD).

    The assembly is a geometric invariant fixed once (which side of the line B–D the pin C lies
    on), so a branch that flips along a sweep shows up as a large error, never as a silent
    agreement.

    Returns
    -------
    dict
        mpf values: ``B, C`` (points), ``v_B, v_C, a_B, a_C`` (vectors), ``omega_BC,
        omega_CD, epsilon_BC, epsilon_CD``, ``sine`` (sin of the angle between the two lines
        ⟂ BC and ⟂ CD intersected on the plans = sin of the angle BCD) and ``reach`` (how far
        the discriminant is from the toggle, negative when the links cannot join).

    Raises
    ------
    ValueError
        If the links cannot be assembled at this angle, or are exactly in their toggle.

    Examples
    --------
    >>> exact = exact_fourbar(60.0)        # reference case A at φ = 60°
    >>> [round(float(v), 6) for v in exact["C"]]
    [0.23641, 0.168393]
    >>> round(float(exact["omega_CD"]), 6), round(float(exact["epsilon_BC"]), 6)
    (2.448975, 19.087707)
    """
    mp = _mpmath()
    with mp.workdps(digits):
        dx, dy = (mp.mpf(g) for g in ground)
        l1, l2, l3, w, e = (mp.mpf(v) for v in (crank, coupler, rocker, omega, epsilon))
        zero = mp.mpf(0)
        b, v_b, a_b = _crank(mp, zero, zero, l1, phi_deg, w, e)
        (cx, cy), reach = _fourbar_pin(mp, b, (dx, dy), l2, l3, above, phi_deg)
        r2 = (cx - b[0], cy - b[1])     # with r2 = C − B, r3 = C − D
        r3 = (cx - dx, cy - dy)
        det = r2[0] * r3[1] - r2[1] * r3[0]   # = cross(r2, r3)
        if det == 0:
            raise ValueError(f"the four-bar is in its toggle position at {phi_deg}°")
        w2, w3, e2, e3 = _fourbar_rates(r2, r3, v_b, a_b)
        v_c = (-w3 * r3[1], w3 * r3[0])
        a_c = (-e3 * r3[1] - w3 ** 2 * r3[0], e3 * r3[0] - w3 ** 2 * r3[1])
        sine = det / (mp.sqrt(r2[0] ** 2 + r2[1] ** 2) * mp.sqrt(r3[0] ** 2 + r3[1] ** 2))
        return {"B": b, "C": (cx, cy), "v_B": v_b, "v_C": v_c, "a_B": a_b, "a_C": a_c,
                "omega_BC": w2, "omega_CD": w3, "epsilon_BC": e2, "epsilon_CD": e3,
                "sine": sine, "reach": reach}


def _fourbar_pin(mp, b, d_point, l2, l3, above: bool, phi_deg):
    """The pin C at ``l2`` from B and ``l3`` from D on the chosen side of B→D, and the
    reach (negative when the links cannot join)."""
    ux, uy = d_point[0] - b[0], d_point[1] - b[1]
    d2 = ux * ux + uy * uy
    if d2 == 0:
        raise ValueError(f"B and D coincide at {phi_deg}°: no definite position")
    d = mp.sqrt(d2)
    reach = (l2 + l3 + d) * (l2 + l3 - d) * (l2 - l3 + d) * (l3 - l2 + d)
    if reach < 0:
        raise ValueError(f"the four-bar cannot be assembled at {phi_deg}°")
    x = (l2 * l2 - l3 * l3 + d2) / (2 * d)
    h = mp.sqrt(reach) / (2 * d)
    sign = 1 if above else -1
    return (b[0] + (x * ux - sign * h * uy) / d, b[1] + (x * uy + sign * h * ux) / d), reach


def _fourbar_rates(r2, r3, v_b, a_b):
    """ω2, ω3, ε2, ε3 of the coupler and rocker (r2 = C − B, r3 = C − D) by Cramer's rule."""
    # ω2·J r2 − ω3·J r3 = −v_B:  −ω2·r2y + ω3·r3y = −vBx ;  ω2·r2x − ω3·r3x = −vBy
    den = -r2[1] * (-r3[0]) - r3[1] * r2[0]
    w2 = (-v_b[0] * (-r3[0]) - r3[1] * (-v_b[1])) / den
    w3 = (-r2[1] * (-v_b[1]) - (-v_b[0]) * r2[0]) / den
    # ε2·J r2 − ε3·J r3 = −a_B + ω2²·r2 − ω3²·r3
    rx = -a_b[0] + w2 ** 2 * r2[0] - w3 ** 2 * r3[0]
    ry = -a_b[1] + w2 ** 2 * r2[1] - w3 ** 2 * r3[1]
    return w2, w3, (rx * (-r3[0]) - r3[1] * ry) / den, (-r2[1] * ry - rx * r2[0]) / den


def exact_slider_crank(phi_deg, *, crank=0.06, rod=0.18, offset=0.0, omega=100.0, epsilon=0.0,
                       forward=True, digits: int = DIGITS) -> dict:
    """The slider-crank A = (0, 0), AB = ``crank``, BC = ``rod``, C on the horizontal line
    y = −``offset``, by its closed form in ``digits`` digits; C ahead of B (larger x) when
    ``forward``.

    Returns
    -------
    dict
        mpf values ``B, C, v_B, v_C, a_B, a_C, omega_BC, epsilon_BC``, ``sine`` (sin of the
        angle between the line ⟂ BC and the guide: (C − B)_x / BC) and ``reach`` (BC² − (height
        of B above the guide)², negative when the rod cannot reach the guide).

    Raises
    ------
    ValueError
        If the rod cannot reach the guide at this angle, or is exactly ⟂ to it (toggle).

    Examples
    --------
    >>> slider = exact_slider_crank(45.0)  # the compressor of Abduvaliev & Abduxoshimov
    >>> round(float(slider["v_C"][0]), 4), round(float(slider["a_C"][0]), 3)
    (-5.2716, -430.317)
    """
    mp = _mpmath()
    with mp.workdps(digits):
        l1, l2, off, w, e = (mp.mpf(v) for v in (crank, rod, offset, omega, epsilon))
        zero = mp.mpf(0)
        b, v_b, a_b = _crank(mp, zero, zero, l1, phi_deg, w, e)
        height = b[1] + off                       # B above the guide y = −offset
        reach = l2 * l2 - height * height
        if reach < 0:
            raise ValueError(f"the rod cannot reach the guide at {phi_deg}°")
        run = mp.sqrt(reach) * (1 if forward else -1)
        c = (b[0] + run, -off)
        r = (c[0] - b[0], c[1] - b[1])
        if r[0] == 0:
            raise ValueError(f"the rod is perpendicular to the guide at {phi_deg}° (toggle)")
        # v_C = v_B + ω2·J r, with v_C·ŷ = 0
        w2 = -v_b[1] / r[0]
        v_c = (v_b[0] - w2 * r[1], zero)
        e2 = (w2 ** 2 * r[1] - a_b[1]) / r[0]
        a_c = (a_b[0] - e2 * r[1] - w2 ** 2 * r[0], zero)
        return {"B": b, "C": c, "v_B": v_b, "v_C": v_c, "a_B": a_b, "a_C": a_c,
                "omega_BC": w2, "epsilon_BC": e2, "sine": r[0] / l2, "reach": reach}
