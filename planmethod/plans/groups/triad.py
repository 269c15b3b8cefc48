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
            raise ToggleError("the lines of the triad's side links are parallel: Assur's "
                              "special point is at infinity", line_angle_deg=0.0,
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
                            vector=f"v_S*{side['outer']}",
                            text=f"through {base}: v_S* − v_{side['outer']} ⟂ "
                                 f"{side['outer']}{side['inner']} (S* lies on the line "
                                 f"{side['outer']}{side['inner']})"))
    v.intersect(*lines, SPECIAL, group_name=group.name, group=group.index, angle=emulator.angle,
                text=f"{SPECIAL}: Assur's special point S* = ({special[0]:.6g}, "
                     f"{special[1]:.6g}) m of {triad.central}, where the lines of "
                     f"{triad.sides[triad.j]['link']} and {triad.sides[triad.k]['link']} meet")
    third = triad.sides[triad.i]
    q_label = emulator.label(third["inner"], v)
    base = triad.pin_label(third, v)
    first = v.line(SPECIAL, perp(unit(third["Q"] - special)), component="relative",
                   group=group.index, vector=f"v_{third['inner']}S*",
                   text=f"through {SPECIAL}: v_{third['inner']}S* ⟂ {third['inner']}S*")
    second = v.line(base, perp(unit(third["Q"] - third["P"])), component="relative",
                    group=group.index, vector=f"v_{third['inner']}{third['outer']}",
                    text=f"through {base}: v_{third['inner']}{third['outer']} ⟂ "
                         f"{third['inner']}{third['outer']}")
    v.intersect(first, second, q_label, group_name=group.name, group=group.index,
                angle=emulator.angle,
                text=f"{q_label}: v_{third['inner']} = v_S* + v_{third['inner']}S* = "
                     f"v_{third['outer']} + v_{third['inner']}{third['outer']}")
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
            v_from: str, v_to: str, group: AssurGroup, vector: str) -> None:
    """Lay off aⁿ of ``point`` about ``centre`` from ``start``: (v-plan segment)²·μv² /
    ((length)·μl·μa), from the point towards the centre."""
    scales = emulator.scales
    a = emulator.a
    segment = emulator.drawn_length(emulator.v, v_from, v_to)
    length_mm = emulator.radius_mm(centre, point)
    magnitude = segment ** 2 * scales.mu_v ** 2 / (length_mm * scales.mu_l * scales.mu_a)
    a.lay_off(start, end, np.asarray(magnitude)[..., None] * unit(centre - point),
              component="normal",
              group=group.index, vector=vector,
              text=f"{vector} from {start}: ({v_from}{v_to})²·μv²/(length·μl·μa), towards the "
                   "centre")


def draw_acceleration(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Draw the triad on the acceleration plan (after :func:`draw_velocity`): for each of the two
    side links through S*, both normal components laid off from the outer pin's image and the
    line of both tangential ones (⟂ the side link) through their end; their intersection is
    s; then the third side's inner pin from both of its sides."""
    triad = _triad(emulator, group)
    v, a = emulator.v, emulator.a
    mu_a, mu_l = emulator.scales.mu_a, emulator.scales.mu_l
    special = triad.special
    lines = []
    for index in (triad.j, triad.k):
        side = triad.sides[index]
        base = triad.pin_label(side, a)
        p_v = triad.pin_label(side, v)
        q_v = emulator.label(side["inner"], v)
        first = f"n_{side['inner']}{side['outer']}"
        _normal(emulator, base, first, side["P"], side["Q"], p_v, q_v, group,
                f"aⁿ_{side['inner']}{side['outer']}")
        second = f"n_S*{side['inner']}"
        _normal(emulator, first, second, side["Q"], special, q_v, SPECIAL, group,
                f"aⁿ_S*{side['inner']}")
        lines.append(a.line(second, perp(unit(side["Q"] - side["P"])), component="tangential",
                            group=group.index, vector=f"aᵗ_S*{side['outer']}",
                            text=f"through {second}: aᵗ_{side['inner']}{side['outer']} + "
                                 f"aᵗ_S*{side['inner']} ⟂ {side['outer']}{side['inner']}"))
    a.intersect(*lines, SPECIAL, group_name=group.name, group=group.index, angle=emulator.angle,
                text=f"{SPECIAL}: a_S* from the two sides through the special point")
    third = triad.sides[triad.i]
    q_label = emulator.label(third["inner"], a)
    q_v = emulator.label(third["inner"], v)
    n_central = f"n_{third['inner']}S*"
    _normal(emulator, SPECIAL, n_central, special, third["Q"], SPECIAL, q_v, group,
            f"aⁿ_{third['inner']}S*")
    first = a.line(n_central, perp(unit(third["Q"] - special)), component="tangential",
                   group=group.index, vector=f"aᵗ_{third['inner']}S*",
                   text=f"through {n_central}: aᵗ_{third['inner']}S* ⟂ {third['inner']}S*")
    base = triad.pin_label(third, a)
    p_v = triad.pin_label(third, v)
    n_side = f"n_{third['inner']}{third['outer']}"
    _normal(emulator, base, n_side, third["P"], third["Q"], p_v, q_v, group,
            f"aⁿ_{third['inner']}{third['outer']}")
    second = a.line(n_side, perp(unit(third["Q"] - third["P"])), component="tangential",
                    group=group.index, vector=f"aᵗ_{third['inner']}{third['outer']}",
                    text=f"through {n_side}: aᵗ_{third['inner']}{third['outer']} ⟂ "
                         f"{third['inner']}{third['outer']}")
    a.intersect(first, second, q_label, group_name=group.name, group=group.index,
                angle=emulator.angle, text=f"{q_label}: a_{third['inner']} from both sides")
    epsilon = _read_turn(emulator, a, n_central, q_label, special, third["Q"], triad.central,
                         mu_a / mu_l, "epsilon")
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
