"""The plans face of the Assur triad of revolute pairs
(:mod:`planmethod.kinematics.groups.triad`): drawn by Assur's special point S*.

No point of the group has two known neighbours, but S* — where the lines of two side links
meet, taken as a point of the central link T — has: v_S = v_P + v_QP + v_SQ, both relative
terms ⟂ that side link (:func:`draw_velocity`); on the acceleration plan both normal components
of each of the two sides are laid off and the line of both tangential ones drawn through their
end (:func:`draw_acceleration`). The third side's inner pin is then a dyad-like step, and each
link's ω and ε are read off the plans.

Examples
--------
>>> from planmethod.plans import draw_plans
>>> from planmethod.spec import load_exercise
>>> plans = draw_plans(load_exercise("exercises/conveyor_sixbar.toml"), 135.0)
>>> SPECIAL in plans.velocity.points_mm and SPECIAL in plans.acceleration.points_mm
True
"""

from __future__ import annotations

import threading
import weakref

import numpy as np

from ...errors import ToggleError
from ...kinematics.groups.triad import sides
from ...structure import AssurGroup
from ...vectors import cross, norm, perp, unit
from ...words import message
from ..steps import (
    Across,
    BothSides,
    NormalOfSegment,
    SpecialAcceleration,
    SpecialPoint,
    SpecialSide,
    VectorName,
    VelocityEquation,
)
from .base import PlanDrawer, PlanSheet, Reading, sense

__all__ = ["SPECIAL", "draw_acceleration", "draw_velocity"]

#: the plan label of Assur's special point
SPECIAL = "s*"


#: each motion's triad geometry, by group index (forgotten with the motion)
_GEOMETRY: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_GEOMETRY_LOCK = threading.Lock()


class _Triad:
    """Geometry of one triad at the plan's angle (global positions from the position plan)."""

    def __init__(self, emulator: PlanDrawer, group: AssurGroup) -> None:
        self.emulator = emulator
        self.group = group
        self.central = group.links[0]
        # the geometry depends on the motion alone: drawing the same position again (the
        # tolerance analysis draws it once per segment) finds it made
        with _GEOMETRY_LOCK:
            known = _GEOMETRY.get(emulator.motion, {}).get(group.index)
        if known is not None:
            self.sides, self.i, self.j, self.k, self.special = known
            return
        self._measure(emulator, group)
        with _GEOMETRY_LOCK:
            _GEOMETRY.setdefault(emulator.motion, {})[group.index] = (
                self.sides, self.i, self.j, self.k, self.special)

    def _measure(self, emulator: PlanDrawer, group: AssurGroup) -> None:
        self.sides = []
        for link, inner, outer in sides(group):
            known = outer.other(link)
            self.sides.append({"link": link, "inner": inner.point, "outer": outer.point,
                               "known": known, "P": emulator.where(link, outer.point),
                               "Q": emulator.where(link, inner.point)})
        points = np.array([s["P"] for s in self.sides] + [s["Q"] for s in self.sides])
        size = float(np.max(norm(points[:, None] - points[None])))
        best = None
        for i in range(3):
            j, k = [m for m in range(3) if m != i]
            pj, qj, pk, qk = (self.sides[j]["P"], self.sides[j]["Q"], self.sides[k]["P"],
                              self.sides[k]["Q"])
            ej, ek = unit(qj - pj), unit(qk - pk)
            sine = abs(cross(ej, ek))
            if sine < 1e-9:
                continue
            special = pj + cross(pk - pj, ek) / cross(ej, ek) * ej
            near = float(norm(special - self.sides[i]["Q"])) / size
            far = float(norm(special - points.mean(axis=0))) / size
            score = sine * min(1.0, near) * min(1.0, 5.0 / max(far, 1e-12))
            if best is None or score > best[0]:
                best = (score, i, j, k, special)
        if best is None or best[0] < 1e-9:
            raise ToggleError(message("the lines of the triad's side links are parallel: "
                                      "Assur's special point is at infinity"), line_angle_deg=0.0,
                              link=group.name, angle=emulator.angle)
        _, self.i, self.j, self.k, self.special = best

    def pin_label(self, side, sheet: PlanSheet) -> str:
        emulator = self.emulator
        return emulator.image_of(sheet, side["known"], side["P"],
                                 emulator.label(side["outer"], sheet))


def _triad(emulator: PlanDrawer, group: AssurGroup) -> _Triad:
    key = ("triad", group.index)
    if key not in emulator.memo:
        emulator.memo[key] = _Triad(emulator, group)
    return emulator.memo[key]


def draw_velocity(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Draw the triad on the velocity plan by Assur's special point S*: it lies on the lines of
    two side links, so s is where the lines ⟂ those links through their outer pins' images
    meet; the third side is then a dyad-like step (v_Q = v_S + v_QS = v_P + v_QP)."""
    triad = _triad(emulator, group)
    v, mu_v, mu_l = emulator.v, emulator.scales.mu_v, emulator.scales.mu_l
    special = triad.special
    lines = []
    for index in (triad.j, triad.k):
        side = triad.sides[index]
        base = triad.pin_label(side, v)
        direction = perp(unit(side["Q"] - side["P"]))
        lines.append(v.line(base, direction, component="relative", group=group.index,
                            vector=VectorName("v", "S*", side["outer"]),
                            along=SpecialSide(side["outer"], side["inner"])))
    v.intersect(*lines, SPECIAL, group=group, angle=emulator.angle,
                solves=SpecialPoint(float(special[0]), float(special[1]), triad.central,
                                    triad.sides[triad.j]["link"], triad.sides[triad.k]["link"]))
    third = triad.sides[triad.i]
    inner, outer = third["inner"], third["outer"]
    q_label = emulator.label(inner, v)
    base = triad.pin_label(third, v)
    first = v.line(SPECIAL, perp(unit(third["Q"] - special)), component="relative",
                   group=group.index, vector=VectorName("v", inner, "S*"),
                   along=Across(inner, "S*"))
    second = v.line(base, perp(unit(third["Q"] - third["P"])), component="relative",
                    group=group.index, vector=VectorName("v", inner, outer),
                    along=Across(inner, outer))
    v.intersect(first, second, q_label, group=group, angle=emulator.angle,
                solves=VelocityEquation(inner, ("S*", outer)))
    omega = _read_turn(emulator, v, SPECIAL, q_label, special, third["Q"], triad.central,
                       mu_v / mu_l, "omega")
    emulator.fix_velocity(triad.central, third["Q"], q_label, omega)
    for side in triad.sides:
        p_label = triad.pin_label(side, v)
        q_side = emulator.label(side["inner"], v)
        omega = _read_turn(emulator, v, p_label, q_side, side["P"], side["Q"], side["link"],
                           mu_v / mu_l, "omega")
        emulator.fix_velocity(side["link"], side["P"], p_label, omega)


def _read_turn(emulator: PlanDrawer, sheet: PlanSheet, start: str, end: str,
               centre: np.ndarray, point: np.ndarray, link: str, factor: float,
               what: str) -> Reading:
    """ω (or ε) of ``link`` read off the segment start→end, ⟂ centre→point."""
    segment = sheet.points[end] - sheet.points[start]
    direction = perp(unit(point - centre))
    sign = sense(segment, direction)
    length_mm = emulator.radius_mm(centre, point)
    return sheet.read(start, end, quantity=f"{what}_{link}", sign=sign,
                      factor=factor / length_mm)


def _normal(emulator: PlanDrawer, start: str, end: str, centre: np.ndarray, point: np.ndarray,
            v_from: str, v_to: str, group: AssurGroup, vector: VectorName) -> None:
    """Lay off aⁿ of ``point`` about ``centre`` from ``start``: (v-plan segment)²·μv² /
    ((length)·μl·μa), from the point towards the centre."""
    scales = emulator.scales
    segment = emulator.drawn_length(emulator.v, v_from, v_to)
    length_mm = emulator.radius_mm(centre, point)
    magnitude = segment ** 2 * scales.mu_v ** 2 / (length_mm * scales.mu_l * scales.mu_a)
    emulator.a.lay_off(start, end, np.asarray(magnitude)[..., None] * unit(centre - point),
                       component="normal", group=group.index, vector=vector,
                       known=NormalOfSegment(v_from, v_to))


def draw_acceleration(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Draw the triad on the acceleration plan (after :func:`draw_velocity`): for each of the two
    side links through S*, both normal components laid off from the outer pin's image and the
    line of both tangential ones (⟂ the side link) through their end; their intersection is
    s; then the third side's inner pin from both of its sides."""
    triad = _triad(emulator, group)
    v, a = emulator.v, emulator.a
    mu_a, mu_l = emulator.scales.mu_a, emulator.scales.mu_l
    lines = []
    for index in (triad.j, triad.k):
        side = triad.sides[index]
        inner, outer = side["inner"], side["outer"]
        q_v = emulator.label(inner, v)
        first, second = f"n_{inner}{outer}", f"n_S*{inner}"
        _normal(emulator, triad.pin_label(side, a), first, side["P"], side["Q"],
                triad.pin_label(side, v), q_v, group, VectorName("aⁿ", inner, outer))
        _normal(emulator, first, second, side["Q"], triad.special, q_v, SPECIAL, group,
                VectorName("aⁿ", "S*", inner))
        lines.append(a.line(second, perp(unit(side["Q"] - side["P"])), component="tangential",
                            group=group.index, vector=VectorName("aᵗ", "S*", outer),
                            along=SpecialSide(outer, inner)))
    a.intersect(*lines, SPECIAL, group=group, angle=emulator.angle,
                solves=SpecialAcceleration())
    q_label = _third_side_acceleration(emulator, triad, group)
    third = triad.sides[triad.i]
    epsilon = _read_turn(emulator, a, f"n_{third['inner']}S*", q_label, triad.special,
                         third["Q"], triad.central, mu_a / mu_l, "epsilon")
    omega = emulator.omega(triad.central)
    emulator.fix_acceleration(triad.central, third["Q"], q_label, omega, epsilon)
    for side in triad.sides:
        p_label = triad.pin_label(side, a)
        q_side = emulator.label(side["inner"], a)
        start = f"n_{side['inner']}{side['outer']}"  # laid off above for every side
        epsilon = _read_turn(emulator, a, start, q_side, side["P"], side["Q"], side["link"],
                             mu_a / mu_l, "epsilon")
        omega = emulator.omega(side["link"])
        emulator.fix_acceleration(side["link"], side["P"], p_label, omega, epsilon)


def _third_side_acceleration(emulator: PlanDrawer, triad: _Triad, group: AssurGroup) -> str:
    """The third side's inner pin Q on the acceleration plan, from S* (aⁿ and the line of aᵗ of
    Q about S*) and from its outer pin (aⁿ and the line of aᵗ of Q about it); returns its
    label."""
    v, a = emulator.v, emulator.a
    third, special = triad.sides[triad.i], triad.special
    inner, outer = third["inner"], third["outer"]
    q_label, q_v = emulator.label(inner, a), emulator.label(inner, v)
    n_central = f"n_{inner}S*"
    _normal(emulator, SPECIAL, n_central, special, third["Q"], SPECIAL, q_v, group,
            VectorName("aⁿ", inner, "S*"))
    first = a.line(n_central, perp(unit(third["Q"] - special)), component="tangential",
                   group=group.index, vector=VectorName("aᵗ", inner, "S*"),
                   along=Across(inner, "S*"))
    n_side = f"n_{inner}{outer}"
    _normal(emulator, triad.pin_label(third, a), n_side, third["P"], third["Q"],
            triad.pin_label(third, v), q_v, group, VectorName("aⁿ", inner, outer))
    second = a.line(n_side, perp(unit(third["Q"] - third["P"])), component="tangential",
                    group=group.index, vector=VectorName("aᵗ", inner, outer),
                    along=Across(inner, outer))
    a.intersect(first, second, q_label, group=group, angle=emulator.angle,
                solves=BothSides(inner))
    return q_label
