"""Velocity and acceleration plans of a class III triad by Assur's special point.

A triad (a central link T with three inner pins Q1, Q2, Q3, and three side links, each with an
outer pin P on a known link) cannot be drawn by intersecting two lines from known points as a
dyad can: no point of the group has two known neighbours. Assur's special point S removes the
difficulty: take S where the lines P_jQ_j and P_kQ_k of two side links meet, as a point of T.

Velocities. v_S = v_Pj + v_QjPj + v_SQj, and both relative velocities are ⟂ P_jQ_j because S
lies on that line: s lies on the line through p_j ⟂ P_jQ_j; likewise on the line through p_k ⟂
P_kQ_k — their intersection is s. Then the third side is a dyad-like step: v_Qi = v_S + v_QiS
(⟂ SQ_i) = v_Pi + v_QiPi (⟂ P_iQ_i) gives q_i. T's image is now known (s and q_i): ω_T, and q_j,
q_k by similarity; each side link's ω from its segment p q.

Accelerations. a_S = a_Pj + aⁿ_QjPj + aⁿ_SQj + (aᵗ_QjPj + aᵗ_SQj), the two tangential terms
both ⟂ P_jQ_j: lay off the two normal components from π's image of P_j (each
(v-plan segment)²·μv²/((length)·μl·μa)) and draw the line ⟂ P_jQ_j; likewise for side k;
intersect: s. Then q_i as for velocities with the normal terms ω_T²·SQ_i and ω_i²·P_iQ_i. ε_T,
the images of T, and each side link's ε follow as on a dyad's plan.

The pair j, k is chosen so that their lines meet at a good angle and S is not too close to
Q_i. The special point is labelled ``s*`` on both plans. Triads with prismatic pairs, and
tetrads, are not drawn (a :class:`~planmethod.errors.PlanmethodError` saying so; their exact
kinematics is still reported).

Examples
--------
>>> from planmethod.plans import draw_plans
>>> from planmethod.spec import load_exercise
>>> plans = draw_plans(load_exercise("exercises/conveyor_sixbar.toml"))
>>> round(plans.readings["omega_tray"], 6), round(plans.readings["epsilon_tray"], 6)
(-0.009438, 0.062473)
"""

from __future__ import annotations

import numpy as np

from ..errors import PlanmethodError
from ..structure import AssurGroup
from .construction import LinkImage, Segment, _acceleration_offset, _velocity_offset

__all__ = ["SPECIAL", "PlansUnavailableError", "acceleration_triad", "triad_sides",
           "velocity_triad"]

#: the plan label of Assur's special point
SPECIAL = "s*"


class PlansUnavailableError(PlanmethodError):
    """The plans of a group cannot be drawn (its exact kinematics is still available)."""


def _perp(vector: np.ndarray) -> np.ndarray:
    return np.array([-vector[1], vector[0]])


def _unit(vector: np.ndarray) -> np.ndarray:
    return vector / float(np.hypot(*vector))


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def triad_sides(mechanism, group: AssurGroup):
    """``(central, [(side link, inner joint, outer joint), …])`` of a triad of revolute pairs.

    Raises
    ------
    PlansUnavailableError
        If the group is not such a triad.
    """
    if group.kind != "triad" or any(j.kind != "R" for j in group.joints):
        raise PlansUnavailableError(
            f"plans are drawn for class III triads of revolute pairs only; this {group.kind} "
            "has other pairs — its exact kinematics is reported (planmethod solve --json)",
            link=group.name)
    central = group.links[0]
    sides = []
    for link in group.links[1:]:
        mine = [j for j in group.joints if link in j.links]
        inner = [j for j in mine if central in j.links]
        outer = [j for j in mine if central not in j.links]
        if len(inner) != 1 or len(outer) != 1:
            raise PlansUnavailableError("the triad's side links must each have one inner and one "
                                  "outer pin to be drawn", link=group.name)
        sides.append((link, inner[0], outer[0]))
    return central, sides


class _Triad:
    """Geometry of one triad at the plan's angle (global positions from the position plan)."""

    def __init__(self, emulator, group: AssurGroup) -> None:
        self.emulator = emulator
        self.group = group
        self.central, sides = triad_sides(emulator.mechanism, group)
        self.sides = []
        for link, inner, outer in sides:
            known = outer.other(link)
            self.sides.append({"link": link, "inner": inner.point, "outer": outer.point,
                               "known": known, "P": emulator.where(link, outer.point),
                               "Q": emulator.where(link, inner.point)})
        points = np.array([s["P"] for s in self.sides] + [s["Q"] for s in self.sides])
        size = float(np.max(np.hypot(*(points[:, None] - points[None]).T)))
        best = None
        for i in range(3):
            j, k = [m for m in range(3) if m != i]
            pj, qj, pk, qk = (self.sides[j]["P"], self.sides[j]["Q"], self.sides[k]["P"],
                              self.sides[k]["Q"])
            ej, ek = _unit(qj - pj), _unit(qk - pk)
            sine = abs(_cross(ej, ek))
            if sine < 1e-9:
                continue
            special = pj + _cross(pk - pj, ek) / _cross(ej, ek) * ej
            near = float(np.hypot(*(special - self.sides[i]["Q"]))) / size
            far = float(np.hypot(*(special - points.mean(axis=0)))) / size
            score = sine * min(1.0, near) * min(1.0, 5.0 / max(far, 1e-12))
            if best is None or score > best[0]:
                best = (score, i, j, k, special)
        if best is None or best[0] < 1e-9:
            raise PlanmethodError("the lines of the triad's side links are parallel: Assur's "
                                  "special point is at infinity", link=group.name,
                                  angle=emulator.angle)
        _, self.i, self.j, self.k, self.special = best

    def pin_label(self, side, sheet, images) -> str:
        emulator = self.emulator
        return emulator.image_at(sheet, images, side["known"], side["P"],
                                 emulator.label(side["outer"], sheet))


def _triad(emulator, group: AssurGroup) -> _Triad:
    store = emulator.__dict__.setdefault("_triads", {})
    if group.index not in store:
        store[group.index] = _Triad(emulator, group)
    return store[group.index]


def velocity_triad(emulator, group: AssurGroup) -> None:
    """Draw the triad on the velocity plan (see the module docstring)."""
    triad = _triad(emulator, group)
    v, mu_v, mu_l = emulator.v, emulator.scales.mu_v, emulator.scales.mu_l
    special = triad.special
    lines = []
    for index in (triad.j, triad.k):
        side = triad.sides[index]
        base = triad.pin_label(side, v, emulator.vimages)
        direction = _perp(_unit(side["Q"] - side["P"]))
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
    base = triad.pin_label(third, v, emulator.vimages)
    first = v.line(SPECIAL, _perp(_unit(third["Q"] - special)), component="relative",
                   group=group.index, vector=f"v_{third['inner']}S*",
                   text=f"through {SPECIAL}: v_{third['inner']}S* ⟂ {third['inner']}S*")
    second = v.line(base, _perp(_unit(third["Q"] - third["P"])), component="relative",
                    group=group.index, vector=f"v_{third['inner']}{third['outer']}",
                    text=f"through {base}: v_{third['inner']}{third['outer']} ⟂ "
                         f"{third['inner']}{third['outer']}")
    v.intersect(first, second, q_label, group_name=group.name, group=group.index,
                angle=emulator.angle,
                text=f"{q_label}: v_{third['inner']} = v_S* + v_{third['inner']}S* = "
                     f"v_{third['outer']} + v_{third['inner']}{third['outer']}")
    omega = _read_turn(emulator, v, SPECIAL, q_label, special, third["Q"], triad.central,
                       mu_v / mu_l, "omega")
    emulator.readings[f"omega_{triad.central}"] = omega
    emulator.vimages[triad.central] = LinkImage(third["Q"], v.points[q_label], q_label, omega)
    emulator.image_points(triad.central, v, emulator.vimages[triad.central], _velocity_offset,
                          mu_v)
    for side in triad.sides:
        p_label = triad.pin_label(side, v, emulator.vimages)
        q_side = emulator.label(side["inner"], v)
        omega = _read_turn(emulator, v, p_label, q_side, side["P"], side["Q"], side["link"],
                           mu_v / mu_l, "omega")
        emulator.readings[f"omega_{side['link']}"] = omega
        emulator.vimages[side["link"]] = LinkImage(side["P"], v.points[p_label], p_label, omega)
        emulator.image_points(side["link"], v, emulator.vimages[side["link"]],
                              _velocity_offset, mu_v)


def _read_turn(emulator, sheet, start: str, end: str, centre, point, link: str, factor: float,
               what: str) -> float:
    """ω (or ε) of ``link`` read off the segment start→end, ⟂ centre→point."""
    segment = sheet.points[end] - sheet.points[start]
    direction = _perp(_unit(point - centre))
    sign = 1.0 if float(segment @ direction) >= 0 else -1.0
    length_mm = emulator.length_mm(centre, point)
    return sheet.read(start, end, quantity=f"{what}_{link}", sign=sign,
                      factor=factor / length_mm)


def _normal(emulator, start: str, end: str, centre, point, v_from: str, v_to: str,
            group: AssurGroup, vector: str) -> None:
    """Lay off aⁿ of ``point`` about ``centre`` from ``start``: (v-plan segment)²·μv² /
    ((length)·μl·μa), from the point towards the centre."""
    scales = emulator.scales
    v, a = emulator.v, emulator.a
    segment = v.round(float(np.hypot(*(v.points[v_to] - v.points[v_from]))),
                      Segment("velocity", "read", "relative"))
    length_mm = emulator.length_mm(centre, point)
    magnitude = segment ** 2 * scales.mu_v ** 2 / (length_mm * scales.mu_l * scales.mu_a)
    a.lay_off(start, end, magnitude * _unit(centre - point), component="normal",
              group=group.index, vector=vector,
              text=f"{vector} from {start}: ({v_from}{v_to})²·μv²/(length·μl·μa), towards the "
                   "centre")


def acceleration_triad(emulator, group: AssurGroup) -> None:
    """Draw the triad on the acceleration plan (after :func:`velocity_triad`)."""
    triad = _triad(emulator, group)
    v, a = emulator.v, emulator.a
    mu_a, mu_l = emulator.scales.mu_a, emulator.scales.mu_l
    special = triad.special
    lines = []
    for index in (triad.j, triad.k):
        side = triad.sides[index]
        base = triad.pin_label(side, a, emulator.aimages)
        p_v = triad.pin_label(side, v, emulator.vimages)
        q_v = emulator.label(side["inner"], v)
        first = f"n_{side['inner']}{side['outer']}"
        _normal(emulator, base, first, side["P"], side["Q"], p_v, q_v, group,
                f"aⁿ_{side['inner']}{side['outer']}")
        second = f"n_S*{side['inner']}"
        _normal(emulator, first, second, side["Q"], special, q_v, SPECIAL, group,
                f"aⁿ_S*{side['inner']}")
        lines.append(a.line(second, _perp(_unit(side["Q"] - side["P"])), component="tangential",
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
    first = a.line(n_central, _perp(_unit(third["Q"] - special)), component="tangential",
                   group=group.index, vector=f"aᵗ_{third['inner']}S*",
                   text=f"through {n_central}: aᵗ_{third['inner']}S* ⟂ {third['inner']}S*")
    base = triad.pin_label(third, a, emulator.aimages)
    p_v = triad.pin_label(third, v, emulator.vimages)
    n_side = f"n_{third['inner']}{third['outer']}"
    _normal(emulator, base, n_side, third["P"], third["Q"], p_v, q_v, group,
            f"aⁿ_{third['inner']}{third['outer']}")
    second = a.line(n_side, _perp(_unit(third["Q"] - third["P"])), component="tangential",
                    group=group.index, vector=f"aᵗ_{third['inner']}{third['outer']}",
                    text=f"through {n_side}: aᵗ_{third['inner']}{third['outer']} ⟂ "
                         f"{third['inner']}{third['outer']}")
    a.intersect(first, second, q_label, group_name=group.name, group=group.index,
                angle=emulator.angle, text=f"{q_label}: a_{third['inner']} from both sides")
    epsilon = _read_turn(emulator, a, n_central, q_label, special, third["Q"], triad.central,
                         mu_a / mu_l, "epsilon")
    omega = emulator.readings[f"omega_{triad.central}"]
    emulator.readings[f"epsilon_{triad.central}"] = epsilon
    emulator.aimages[triad.central] = LinkImage(third["Q"], a.points[q_label], q_label, omega,
                                                epsilon)
    emulator.image_points(triad.central, a, emulator.aimages[triad.central],
                          _acceleration_offset, mu_a)
    for side in triad.sides:
        p_label = triad.pin_label(side, a, emulator.aimages)
        q_side = emulator.label(side["inner"], a)
        start = f"n_{side['inner']}{side['outer']}"  # laid off above for every side
        epsilon = _read_turn(emulator, a, start, q_side, side["P"], side["Q"], side["link"],
                             mu_a / mu_l, "epsilon")
        omega = emulator.readings[f"omega_{side['link']}"]
        emulator.readings[f"epsilon_{side['link']}"] = epsilon
        emulator.aimages[side["link"]] = LinkImage(side["P"], a.points[p_label], p_label,
                                                   omega, epsilon)
        emulator.image_points(side["link"], a, emulator.aimages[side["link"]],
                              _acceleration_offset, mu_a)
