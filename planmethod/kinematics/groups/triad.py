"""The Assur triad (class III) of revolute pairs: a central link T with three inner pins Q1, Q2,
Q3, and three side links, each pinned to T at its inner pin and to a known link at its outer pin
P (the vibratory conveyor of Umbetkulov et al.: the tray with its bracket, the rod and the two
rockers).

Its pose is three numbers, the central link's q = (x, y, θ): each side link only keeps its pins
at its length, |Q_i(q) − P_i| = l_i. Newton solves these three equations (vectorised over the
crank angles, 3 × 3 by Cramer's rule; see :mod:`.higher` for the branch and the continuation).
Velocities: d_i·(v_T + ω_T·J·r_i) = d_i·v_Pi, with d_i = Q_i − P_i and r_i = Q_i − origin;
accelerations: d_i·(a_T + ε_T·J·r_i) = d_i·(a_Pi + ω_T²·r_i) − |v_Qi − v_Pi|² — the same 3 × 3
matrix; each side link's ω and ε from its pins. The lines of the three side links meeting in
one point make the matrix singular: the group's toggle. The formulas are written in the
arithmetic of :mod:`~planmethod.kinematics.algebra`, so that they are traced into the
mechanism's program like a dyad's.

Its plans are drawn by Assur's special point S* (the plans face,
:mod:`planmethod.plans.groups.triad`), and so are its reactions (the forces face,
:mod:`planmethod.forces.groups.triad`).

Every assembly at ``drive.angle`` is found by sweeping θ: for each θ the pins of two side
links fix T's origin (two circles meet), and the third side's misfit changes sign at an
assembly; each sign change is polished by Newton.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/conveyor_sixbar.toml").mechanism, 135.0).at(0)
>>> round(float(np.degrees(motion.theta("rocker_EF"))), 5)
-18.29342
"""

from __future__ import annotations

import math

import numpy as np

from ...structure import AssurGroup
from ...vectors import norm, turn_onto, unit_angle
from ...vocabulary import GroupKind, PairKind
from .. import algebra
from ..algebra import Body, Vec, absolute, cos, maximum, sin, sqrt
from .base import (
    Branch,
    GroupInputs,
    KindModel,
    SolvedGroup,
    Theta,
    ThetaKind,
)
from .higher import System, choose_with, higher_evaluate, wrap

__all__ = ["KIND", "PRIORITY", "TriadSystem", "accepts", "choose", "evaluate",
           "sides"]

KIND = GroupKind.TRIAD
PRIORITY = 10
#: samples of the central link's angle when looking for every assembly
SAMPLES = 1440


def sides(group: AssurGroup) -> list[tuple[str, object, object]] | None:
    """(side link, inner joint, outer joint) of each side link of a plain triad, else None."""
    if group.kind is not GroupKind.TRIAD or any(
            joint.kind is not PairKind.REVOLUTE for joint in group.joints):
        return None
    central = group.links[0]
    out = []
    for link in group.links[1:]:
        mine = [joint for joint in group.joints if link in joint.links]
        inner = [joint for joint in mine if central in joint.links]
        if len(mine) != 2 or len(inner) != 1:
            return None
        outer = next(joint for joint in mine if joint is not inner[0])
        if outer.other(link) in group.links:
            return None
        out.append((link, inner[0], outer))
    return out


def accepts(group: AssurGroup) -> bool:
    """A triad of revolute pairs whose central link carries the three inner pins and whose
    side links each have one outer pin on a known link."""
    return sides(group) is not None


class _Side:
    """One side link: its name, known link, the outer pin's local coordinates on the known link
    and on the side link, the inner pin's on the central link, its length and the angle of
    outer → inner in its own frame."""

    __slots__ = ("alpha", "central_local", "inner", "known", "known_local", "length", "link",
                 "outer", "outer_local", "unit")

    def __init__(self, mechanism, central: str, link: str, inner, outer) -> None:
        self.link, self.inner, self.outer = link, inner.point, outer.point
        self.known = outer.other(link)
        self.known_local = tuple(float(v) for v in mechanism.local(self.known, outer.point))
        self.central_local = tuple(float(v) for v in mechanism.local(central, inner.point))
        a = np.array(mechanism.local(link, inner.point), dtype=float)
        b = np.array(mechanism.local(link, outer.point), dtype=float)
        self.outer_local = (float(b[0]), float(b[1]))
        self.length = float(norm(a - b))
        self.alpha = math.atan2(a[1] - b[1], a[0] - b[0])
        self.unit = ((a[0] - b[0]) / self.length, (a[1] - b[1]) / self.length)


class TriadSystem(System):
    """The plain triad's three equations in q = (x, y, θ) of the central link."""

    traceable = True

    def __init__(self, context: GroupInputs) -> None:
        mechanism, group = context.mechanism, context.group
        self.mechanism, self.group = mechanism, group
        self.links = tuple(group.links)
        self.central = group.links[0]
        self.size = 3
        self.sides = [_Side(mechanism, self.central, link, inner, outer)
                      for link, inner, outer in sides(group)]
        sizes = [1e-9] + [side.length for side in self.sides]
        points = np.array(list(mechanism.links[self.central].points.values()), dtype=float)
        if len(points) > 1:
            sizes.append(float(np.max(norm(points[:, None] - points[None]))))
        self.length = max(sizes)
        self.weights = np.array([1.0, 1.0, self.length])

    # -- what is known -----------------------------------------------------------------------
    def inputs(self, bodies, level: int) -> list:
        """Each outer pin's position (and velocity, acceleration) on its known link."""
        out = []
        for side in self.sides:
            body = bodies[side.known]
            r = body.offset(*side.known_local)
            point = body.origin + r
            out += [point.x, point.y]
            if level >= 1:
                velocity = body.velocity(r)
                out += [velocity.x, velocity.y]
            if level >= 2:
                acceleration = body.acceleration(r)
                out += [acceleration.x, acceleration.y]
        return out

    def known(self, values, level: int) -> list[tuple]:
        per = 2 * (1 + min(level, 1) + max(level - 1, 0))
        return [tuple(values[per * number:per * (number + 1)]) for number in range(3)]

    # -- the equations ---------------------------------------------------------------------------
    def at(self, q: tuple, known) -> tuple:
        """(q, known, cos θ, sin θ, per side (rx, ry, dx, dy, misfit)): r = R·c the inner
        pin's offset on T, d = Q − P, misfit = (|d|² − l²)/(2l)."""
        x, y, theta = q
        c, s = cos(theta), sin(theta)
        out = []
        for side, values in zip(self.sides, known, strict=True):
            lx, ly = side.central_local
            rx, ry = Vec(lx, ly).turned(c, s)
            dx, dy = x + rx - values[0], y + ry - values[1]
            misfit = (dx * dx + dy * dy - side.length * side.length) * (0.5 / side.length)
            out.append((rx, ry, dx, dy, misfit))
        return q, known, c, s, out

    def residual(self, pose):
        (*_, m1), (*_, m2), (*_, m3) = pose[4]
        return maximum(maximum(absolute(m1), absolute(m2)), absolute(m3))

    def _rows(self, pose) -> list[tuple]:
        return [(dx, dy, algebra.cross(Vec(rx, ry), Vec(dx, dy)))
                for rx, ry, dx, dy, _ in pose[4]]

    def step(self, pose) -> tuple:
        # Φ_i = misfit_i, ∂Φ_i/∂q = (dx, dy, r × d)/l_i: the rows scaled by 1/l_i
        rows = [(dx / side.length, dy / side.length,
                 algebra.cross(Vec(rx, ry), Vec(dx, dy)) / side.length)
                for (rx, ry, dx, dy, _), side in zip(pose[4], self.sides, strict=True)]
        return _cramer(rows, [-misfit for *_, misfit in pose[4]])

    def rates(self, pose, level: int):
        _, known, _, _, geometry = pose
        rows = self._rows(pose)
        first = second = None
        if level >= 1:
            rhs = [dx * values[2] + dy * values[3]
                   for (_, _, dx, dy, _), values in zip(geometry, known, strict=True)]
            first = _cramer(rows, rhs)
        if level >= 2:
            vx, vy, omega = first
            square = omega * omega
            rhs = []
            for (rx, ry, dx, dy, _), values in zip(geometry, known, strict=True):
                wx, wy = vx - omega * ry - values[2], vy + omega * rx - values[3]
                rhs.append(dx * (values[4] + square * rx) + dy * (values[5] + square * ry)
                           - (wx * wx + wy * wy))
            second = _cramer(rows, rhs)
        return first, second

    def conditioning(self, pose):
        """|det| of the rows (d̂_i, r_i × d̂_i / L) over the product of their lengths."""
        rows, norms = [], []
        for (rx, ry, dx, dy, _), side in zip(pose[4], self.sides, strict=True):
            turn = algebra.cross(Vec(rx, ry), Vec(dx, dy)) / (side.length * self.length)
            rows.append((dx / side.length, dy / side.length, turn))
            norms.append((dx * dx + dy * dy) / (side.length * side.length) + turn * turn)
        return absolute(_det(rows)) / sqrt(norms[0] * norms[1] * norms[2])

    def stored(self, pose) -> dict:
        return {self.central: None if pose is None else pose[0][2]}

    def theta_recipes(self) -> dict:
        return {side.link: Theta(ThetaKind.TWO, side.outer, side.inner, side.alpha)
                for side in self.sides}

    def results(self, pose, rates, level: int) -> list:
        q, known, c, s, geometry = pose
        out = [c, s, q[0], q[1]]
        if level >= 1:
            vx, vy, omega = rates[0]
            out += [omega, vx, vy]
        if level >= 2:
            ax, ay, epsilon = rates[1]
            out += [epsilon, ax, ay]
        for (rx, ry, dx, dy, _), side, values in zip(geometry, self.sides, known, strict=True):
            # the side link's axes turn its own outer → inner direction onto d = Q − P
            ux, uy = side.unit
            d, u = Vec(dx, dy), Vec(ux, uy)
            sc, ss = algebra.dot(d, u) / side.length, algebra.cross(u, d) / side.length
            turned = Vec(*side.outer_local).turned(sc, ss)
            tx, ty = -turned.x, -turned.y   # origin − P
            px, py = values[0], values[1]
            out += [sc, ss, px + tx, py + ty]
            if level >= 1:
                square = dx * dx + dy * dy
                wx, wy = vx - omega * ry - values[2], vy + omega * rx - values[3]
                turn = algebra.cross(Vec(dx, dy), Vec(wx, wy)) / square
                out += [turn, values[2] - turn * ty, values[3] + turn * tx]
            if level >= 2:
                big = omega * omega
                qx = ax - epsilon * ry - big * rx - values[4]
                qy = ay + epsilon * rx - big * ry - values[5]
                spin = algebra.cross(Vec(dx, dy), Vec(qx, qy)) / square
                small = turn * turn
                out += [spin, values[4] - spin * ty - small * tx,
                        values[5] + spin * tx - small * ty]
        return out

    def poses(self, pose) -> np.ndarray:
        q, known, _, _, geometry = pose
        columns = [q[0], q[1], wrap(q[2])]
        for (_, _, dx, dy, _), side, values in zip(geometry, self.sides, known, strict=True):
            theta = wrap(np.arctan2(dy, dx) - side.alpha)
            turned = Vec(*side.outer_local).turned(np.cos(theta), np.sin(theta))
            columns += [values[0] - turned.x, values[1] - turned.y, theta]
        count = max(np.size(column) for column in columns)
        return np.stack([np.broadcast_to(np.asarray(column, dtype=float), (count,))
                         for column in columns], axis=-1)

    def assemblies(self, known) -> list[np.ndarray]:
        """Every assembly at the one angle of ``known``: for each θ the pins of the first two
        side links fix T's origin (0 or 2 ways); the third side's misfit changes sign at an
        assembly; each sign change is polished by Newton."""
        theta = -np.pi + 2.0 * np.pi * np.arange(SAMPLES + 1) / SAMPLES
        axes = unit_angle(theta)
        first, second, third = self.sides
        p1, p2, p3 = (np.array([float(np.ravel(v[0])[0]), float(np.ravel(v[1])[0])])
                      for v in known)

        def turned(local):   # (2, N): x and y apart
            return turn_onto(axes, local).T

        # T's origin o: |o + R·c1 − P1| = l1, |o + R·c2 − P2| = l2
        centre1 = p1[:, None] - turned(first.central_local)
        centre2 = p2[:, None] - turned(second.central_local)
        l1, l2, l3 = first.length, second.length, third.length
        span = centre2 - centre1
        distance = norm(span.T)
        starts = []
        with np.errstate(invalid="ignore", divide="ignore"):
            along = (l1 * l1 - l2 * l2 + distance * distance) / (2.0 * distance)
            height = np.sqrt(l1 * l1 - along * along)
            direction = span / distance
            r3 = turned(third.central_local)
            for sign in (1.0, -1.0):
                ox = centre1[0] + along * direction[0] - sign * height * direction[1]
                oy = centre1[1] + along * direction[1] + sign * height * direction[0]
                misfit = (ox + r3[0] - p3[0]) ** 2 + (oy + r3[1] - p3[1]) ** 2 - l3 * l3
                change = np.flatnonzero(np.isfinite(misfit[:-1]) & np.isfinite(misfit[1:])
                                        & (np.sign(misfit[:-1]) != np.sign(misfit[1:])))
                for index in change:
                    weight = misfit[index] / (misfit[index] - misfit[index + 1])
                    starts.append([ox[index] + weight * (ox[index + 1] - ox[index]),
                                   oy[index] + weight * (oy[index + 1] - oy[index]),
                                   theta[index] + weight * (theta[index + 1] - theta[index])])
        if not starts:
            return []
        starts = np.array(starts)
        many = [tuple(np.repeat(np.asarray(v, dtype=float).reshape(-1)[:1], len(starts))
                      for v in values) for values in known]
        q, done, _, _ = self.newton(starts, many)
        found = q[done]
        found[:, 2] = wrap(found[:, 2])
        return list(found)


def _det(rows):
    (a, b, c), (d, e, f), (g, h, i) = rows
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)


def _cramer(rows, rhs) -> tuple:
    """Solve the 3 × 3 system rows·u = rhs (numbers, arrays or traced) by Cramer's rule."""
    (a, b, c), (d, e, f), (g, h, i) = rows
    r0, r1, r2 = rhs
    minor_ei, minor_fh, minor_dh = e * i - f * h, d * i - f * g, d * h - e * g
    det = a * minor_ei - b * minor_fh + c * minor_dh
    first = r1 * i - f * r2
    second = r1 * h - e * r2
    third = d * r2 - r1 * g
    u0 = (r0 * minor_ei - b * first + c * second) / det
    u1 = (a * first - r0 * minor_fh + c * third) / det
    u2 = (-a * second - b * third + r0 * minor_dh) / det
    return u0, u1, u2


def evaluate(context: GroupInputs, level: int, model: KindModel, branch: Branch) -> SolvedGroup:
    """Solve the triad at the context's angles (see the module docstring)."""
    return higher_evaluate(context, level, model, branch, TriadSystem)


def choose(context: GroupInputs, model: KindModel) -> tuple[Branch, dict[str, Body]]:
    """The triad's assembly at ``drive.angle``."""
    return choose_with(context, model, TriadSystem)
