"""The plans face of the Assur triad (:mod:`planmethod.kinematics.groups.triad`, and the triad
with a prismatic pair of :mod:`planmethod.kinematics.groups.higher`): drawn by Assur's special
point S*.

No point of the group has two known neighbours, but S* — where the lines of two side links
meet, taken as a point of the central link T — has: v_S = v_P + v_QP + v_SQ, both relative
terms ⟂ that side link (:func:`draw_velocity`); on the acceleration plan both normal components
of each of the two sides are laid off and the line of both tangential ones drawn through their
end (:func:`draw_acceleration`). The third side's inner pin is then a dyad-like step, and each
link's ω and ε are read off the plans.

A side link with a prismatic pair (a block on a guide) has its relative motion as in a dyad:
its "line" is the normal to the guide through its revolute pin — there the central link's
turning about that pin is along the guide, as the sliding is — so S* taken on that line moves
relative to the guide's point under the pin along the guide (v_S = v_base + v_rel + v_SQ, both
along the guide); on the acceleration plan the Coriolis component 2ω·v_rel of the carrier and
the normal component of S* about the pin are laid off, and the line of the relative and the
tangential ones (both along the guide) drawn through their end. The block turns with the link
it slides on.

Examples
--------
>>> from planmethod.plans import draw_plans
>>> from planmethod.spec import load_exercise
>>> plans = draw_plans(load_exercise("exercises/conveyor_sixbar.toml"), 135.0)
>>> SPECIAL in plans.velocity.points_mm and SPECIAL in plans.acceleration.points_mm
True
>>> plans = draw_plans(load_exercise("exercises/screen_sixbar.toml"))
>>> [step.end for step in plans.velocity.steps if step.action == "intersect"]
['s*', 'd']
"""

from __future__ import annotations

import math
import threading
import weakref
from dataclasses import dataclass

import numpy as np

from ...errors import ToggleError
from ...model import Slide
from ...structure import AssurGroup
from ...vectors import cross, norm, perp, unit
from ...vocabulary import GroupKind, PairKind
from ...words import message
from ..steps import (
    Across,
    BothSides,
    CoriolisComponent,
    Guide,
    NormalOfSegment,
    SpecialAcceleration,
    SpecialGuide,
    SpecialPoint,
    SpecialSide,
    VectorName,
    VelocityEquation,
)
from .base import PlanDrawer, PlanSheet, Reading, sense

__all__ = ["SPECIAL", "draw_acceleration", "draw_velocity", "drawable"]

#: the plan label of Assur's special point
SPECIAL = "s*"


@dataclass(frozen=True, slots=True)
class _Side:
    """One side link ``link`` of the triad, on the central link ``central`` at its inner pair
    and on the ``known`` link at its outer pair.

    ``P`` is the outer pin and ``Q`` the inner one (m), named ``outer`` and ``inner``. A side
    with a prismatic pair ``slide`` has one pin: the outer pair slides (``outer_slide``, a
    block on a guide of the known link; ``P`` is the known link's point under ``Q``), or the
    inner one (the central link slides on the side link; ``Q`` is its point under ``P``);
    ``guide`` is the guide's unit direction."""

    link: str
    known: str
    central: str
    inner: str
    outer: str
    P: np.ndarray
    Q: np.ndarray
    slide: Slide | None = None
    outer_slide: bool = False
    guide: np.ndarray | None = None

    @property
    def base(self) -> str:
        """The known point the side's relative motion starts from (report name)."""
        return f"{self.inner}@{self.known}" if self.outer_slide else self.outer

    @property
    def moving(self) -> str:
        """The central link's point the side finds (report name): its inner pin, or its
        point under the outer pin where it slides on the side link."""
        if self.slide is None or self.outer_slide:
            return self.inner
        return f"{self.outer}@{self.central}"

    @property
    def line(self) -> tuple[np.ndarray, np.ndarray]:
        """The side's line through S* (a point, a unit direction): the side link's, or the
        normal to its guide through its pin."""
        if self.slide is None:
            return self.P, unit(self.Q - self.P)
        return self.Q, perp(self.guide)

    @property
    def across(self) -> np.ndarray:
        """The direction of the unknown relative velocity: ⟂ the side link, or its guide."""
        return perp(unit(self.Q - self.P)) if self.slide is None else self.guide

    @property
    def carrier(self) -> str:
        """The link a sliding side's relative motion is taken on (its Coriolis ω)."""
        return self.known if self.outer_slide else self.link

    @property
    def turns_with(self) -> str:
        """The link a sliding side's link turns with: the one it slides on (the known link,
        or the central link sliding on it)."""
        return self.known if self.outer_slide else self.central


def _pairs(group: AssurGroup) -> tuple[str, list[tuple]] | None:
    """(central link, (side link, inner joint, outer joint) of each side) of a triad whose
    side links each have one pair with the central link and one with a known link, at most
    one of them prismatic; else None."""
    if group.kind is not GroupKind.TRIAD:
        return None
    inside = [link for link in group.links
              if sum(link in joint.links and joint.other(link) in group.links
                     for joint in group.joints) == 3]
    if len(inside) != 1:
        return None
    central, out = inside[0], []
    for link in group.links:
        if link == central:
            continue
        mine = [joint for joint in group.joints if link in joint.links]
        inner = [joint for joint in mine if central in joint.links]
        outer = [joint for joint in mine if joint.other(link) not in group.links]
        if len(mine) != 2 or len(inner) != 1 or len(outer) != 1 or all(
                joint.kind is PairKind.PRISMATIC for joint in mine):
            return None
        out.append((link, inner[0], outer[0]))
    return central, out


def drawable(group: AssurGroup) -> bool:
    """Whether the special point draws ``group``: a triad of one central link and three
    side links, each with at most one prismatic pair.

    >>> from planmethod.structure import AssurGroup
    >>> drawable(AssurGroup(0, GroupKind.TETRAD, ("A", "B", "C", "D"), (), 3, 2, ()))
    False
    """
    return _pairs(group) is not None


def _guide(emulator: PlanDrawer, slide: Slide) -> np.ndarray:
    theta = float(emulator.motion.links[slide.along].theta[0]) + slide.direction_rad
    return np.array([math.cos(theta), math.sin(theta)])


def _sides(emulator: PlanDrawer, group: AssurGroup) -> list[_Side]:
    """The triad's sides at the plan's angle (positions from the position plan)."""
    central, pairs = _pairs(group)
    out = []
    for link, inner, outer in pairs:
        slide = next((j.slide for j in (inner, outer) if j.kind is PairKind.PRISMATIC), None)
        if slide is None:
            out.append(_Side(link, outer.other(link), central, inner.point, outer.point,
                             emulator.where(link, outer.point),
                             emulator.where(link, inner.point)))
            continue
        outer_slide = outer.kind is PairKind.PRISMATIC
        pin = inner.point if outer_slide else outer.point
        at = emulator.where(link, pin)
        out.append(_Side(link, outer.other(link), central, pin, pin, at, at, slide,
                         outer_slide, _guide(emulator, slide)))
    return out


#: each motion's triad geometry, by group index (forgotten with the motion)
_GEOMETRY: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_GEOMETRY_LOCK = threading.Lock()


class _Triad:
    """Geometry of one triad at the plan's angle (global positions from the position plan)."""

    def __init__(self, emulator: PlanDrawer, group: AssurGroup) -> None:
        self.emulator = emulator
        self.group = group
        # the geometry depends on the motion alone: drawing the same position again (the
        # tolerance analysis draws it once per segment) finds it made
        with _GEOMETRY_LOCK:
            known = _GEOMETRY.get(emulator.motion, {}).get(group.index)
        if known is not None:
            self.sides, self.i, self.j, self.k, self.special = known
        else:
            self._measure(emulator, group)
            with _GEOMETRY_LOCK:
                _GEOMETRY.setdefault(emulator.motion, {})[group.index] = (
                    self.sides, self.i, self.j, self.k, self.special)
        self.central = self.sides[0].central

    def _measure(self, emulator: PlanDrawer, group: AssurGroup) -> None:
        self.sides = _sides(emulator, group)
        points = np.array([s.P for s in self.sides] + [s.Q for s in self.sides])
        size = float(np.max(norm(points[:, None] - points[None])))
        best = None
        for i in range(3):
            j, k = [m for m in range(3) if m != i]
            (pj, ej), (pk, ek) = self.sides[j].line, self.sides[k].line
            sine = abs(cross(ej, ek))
            if sine < 1e-9:
                continue
            special = pj + cross(pk - pj, ek) / cross(ej, ek) * ej
            near = float(norm(special - self.sides[i].Q)) / size
            far = float(norm(special - points.mean(axis=0))) / size
            score = sine * min(1.0, near) * min(1.0, 5.0 / max(far, 1e-12))
            if best is None or score > best[0]:
                best = (score, i, j, k, special)
        if best is None or best[0] < 1e-9:
            raise ToggleError(message("the lines of the triad's side links are parallel: "
                                      "Assur's special point is at infinity"), line_angle_deg=0.0,
                              link=group.name, angle=emulator.angle)
        _, self.i, self.j, self.k, self.special = best

    def pin_label(self, side: _Side, sheet: PlanSheet) -> str:
        """The label of the side's known point on ``sheet`` (placed if new)."""
        emulator = self.emulator
        return emulator.image_of(sheet, side.known, side.P, emulator.label(side.base, sheet))

    def moving_label(self, side: _Side, sheet: PlanSheet) -> str:
        """The label of the central link's point the side finds (placed, once the central
        link's image is known, if new)."""
        emulator = self.emulator
        return emulator.image_of(sheet, self.central, side.Q,
                                 emulator.label(side.moving, sheet))


def _triad(emulator: PlanDrawer, group: AssurGroup) -> _Triad:
    key = ("triad", group.index)
    if key not in emulator.memo:
        emulator.memo[key] = _Triad(emulator, group)
    return emulator.memo[key]


def _special_line(emulator: PlanDrawer, sheet: PlanSheet, side: _Side, through: str,
                  group: AssurGroup) -> int:
    """The line of S*'s unknown motion relative to the side's known point, through
    ``through``: ⟂ the side link, or along its guide."""
    if side.slide is None:
        velocity = sheet is emulator.v
        return sheet.line(through, side.across,
                          component="relative" if velocity else "tangential",
                          group=group.index, along=SpecialSide(side.outer, side.inner),
                          vector=VectorName("v" if velocity else "aᵗ", "S*", side.outer))
    return sheet.line(through, side.guide, component="relative", group=group.index,
                      vector=VectorName("v" if sheet is emulator.v else "aʳ", "S*", side.base),
                      along=SpecialGuide(side.slide.link, side.slide.along, side.inner))


def _side_line(emulator: PlanDrawer, sheet: PlanSheet, side: _Side, through: str,
               group: AssurGroup) -> int:
    """The line of the third side's unknown relative motion through ``through``: ⟂ the side
    link (tangential), or along its guide (relative)."""
    moving, velocity = side.moving, sheet is emulator.v
    if side.slide is None:
        return sheet.line(through, side.across,
                          component="relative" if velocity else "tangential",
                          group=group.index, along=Across(moving, side.base),
                          vector=VectorName("v" if velocity else "aᵗ", moving, side.base))
    return sheet.line(through, side.guide, component="relative", group=group.index,
                      vector=VectorName("v" if velocity else "aʳ", moving, side.base),
                      along=Guide(side.slide.link, side.slide.along))


def draw_velocity(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Draw the triad on the velocity plan by Assur's special point S*: it lies on the lines of
    two side links, so s is where the lines ⟂ those links (along a sliding side's guide)
    through their known points' images meet; the third side is then a dyad-like step
    (v_Q = v_S + v_QS = v_P + v_QP)."""
    triad = _triad(emulator, group)
    v, mu_v, mu_l = emulator.v, emulator.scales.mu_v, emulator.scales.mu_l
    special = triad.special
    lines = [_special_line(emulator, v, triad.sides[index], triad.pin_label(
        triad.sides[index], v), group) for index in (triad.j, triad.k)]
    v.intersect(*lines, SPECIAL, group=group, angle=emulator.angle,
                solves=SpecialPoint(float(special[0]), float(special[1]), triad.central,
                                    triad.sides[triad.j].link, triad.sides[triad.k].link))
    third = triad.sides[triad.i]
    moving = third.moving
    q_label = emulator.label(moving, v)
    base = triad.pin_label(third, v)
    first = v.line(SPECIAL, perp(unit(third.Q - special)), component="relative",
                   group=group.index, vector=VectorName("v", moving, "S*"),
                   along=Across(moving, "S*"))
    second = _side_line(emulator, v, third, base, group)
    v.intersect(first, second, q_label, group=group, angle=emulator.angle,
                solves=VelocityEquation(moving, ("S*", third.base)))
    omega = _read_turn(emulator, v, SPECIAL, q_label, special, third.Q, triad.central,
                       mu_v / mu_l, "omega")
    emulator.fix_velocity(triad.central, third.Q, q_label, omega)
    for side in triad.sides:
        if side.slide is not None:
            _sliding_velocity(emulator, triad, side)
            continue
        p_label = triad.pin_label(side, v)
        q_side = emulator.label(side.inner, v)
        omega = _read_turn(emulator, v, p_label, q_side, side.P, side.Q, side.link,
                           mu_v / mu_l, "omega")
        emulator.fix_velocity(side.link, side.P, p_label, omega)


def _sliding_velocity(emulator: PlanDrawer, triad: _Triad, side: _Side) -> None:
    """A sliding side on the velocity plan, once the central link's image is known: its
    link turns with its carrier; its relative velocity read off, from the known point's image
    to the moving one's (kept for the pair's readings)."""
    v = emulator.v
    base, moving = triad.pin_label(side, v), triad.moving_label(side, v)
    omega = emulator.omega(side.turns_with)
    emulator.fix_velocity(side.link, side.P, moving if side.outer_slide else base, omega)
    sign = sense(v.points[moving] - v.points[base], side.guide)
    v.read(base, moving, quantity=f"v_{side.moving}{side.base}", sign=sign,
           factor=emulator.scales.mu_v, relative=VectorName("v", side.moving, side.base))
    # the side draws the moving point relative to the carrier; the pair's reading wants
    # `link` relative to `along`, the reverse when the carrier is the pair's `link`
    emulator.slid(side.slide.key, {"v": (base, moving),
                                   "reverse": side.carrier == side.slide.link})


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


def _coriolis(emulator: PlanDrawer, triad: _Triad, side: _Side, group: AssurGroup) -> str:
    """Lay off a sliding side's Coriolis component 2ω·v_rel (v_rel read off the velocity
    plan, turned 90° in the sense of the carrier's ω) from its known point's image; returns
    its end k (kept for the pair's readings)."""
    v, a, scales = emulator.v, emulator.a, emulator.scales
    base_v, moving_v = triad.pin_label(side, v), emulator.label(side.moving, v)
    segment = v.points[moving_v] - v.points[base_v]
    relative = sense(segment, side.guide) * emulator.drawn_length(v, base_v, moving_v)
    omega = emulator.omega(side.carrier)
    coriolis = (np.asarray(2 * omega * relative * scales.mu_v / scales.mu_a)[..., None]
                * perp(side.guide))
    base, k_label = triad.pin_label(side, a), f"k_{side.moving}"
    a.lay_off(base, k_label, coriolis, component="coriolis", group=group.index,
              vector=VectorName("aᵏ", side.moving, side.base),
              known=CoriolisComponent(side.carrier, bool(np.any(omega))))
    return k_label


def _special_acceleration_line(emulator: PlanDrawer, triad: _Triad, side: _Side,
                               group: AssurGroup) -> int:
    """One side through S* on the acceleration plan: its known components laid off from its
    known point's image (both normal ones; or the Coriolis one and S*'s normal one about the
    pin), the line of the unknown ones through their end."""
    v, a = emulator.v, emulator.a
    q_v = emulator.label(side.moving, v)
    if side.slide is None:
        start = f"n_{side.inner}{side.outer}"
        _normal(emulator, triad.pin_label(side, a), start, side.P, side.Q,
                triad.pin_label(side, v), q_v, group, VectorName("aⁿ", side.inner, side.outer))
    else:
        start = _coriolis(emulator, triad, side, group)
    end = f"n_S*{side.inner}"
    _normal(emulator, start, end, side.Q, triad.special, q_v, SPECIAL, group,
            VectorName("aⁿ", "S*", side.inner))
    return _special_line(emulator, a, side, end, group)


def draw_acceleration(emulator: PlanDrawer, group: AssurGroup) -> None:
    """Draw the triad on the acceleration plan (after :func:`draw_velocity`): for each of the two
    side links through S*, both normal components laid off from the outer pin's image (a
    sliding side: the Coriolis component, then S*'s normal one about the pin) and the line of
    the unknown ones (⟂ the side link, or along the guide) through their end; their
    intersection is s; then the third side's inner pin from both of its sides."""
    triad = _triad(emulator, group)
    a = emulator.a
    mu_a, mu_l = emulator.scales.mu_a, emulator.scales.mu_l
    lines = [_special_acceleration_line(emulator, triad, triad.sides[index], group)
             for index in (triad.j, triad.k)]
    a.intersect(*lines, SPECIAL, group=group, angle=emulator.angle,
                solves=SpecialAcceleration())
    q_label, n_central = _third_side_acceleration(emulator, triad, group)
    third = triad.sides[triad.i]
    epsilon = _read_turn(emulator, a, n_central, q_label, triad.special, third.Q,
                         triad.central, mu_a / mu_l, "epsilon")
    omega = emulator.omega(triad.central)
    emulator.fix_acceleration(triad.central, third.Q, q_label, omega, epsilon)
    for side in triad.sides:
        if side.slide is not None:
            _sliding_acceleration(emulator, triad, side)
            continue
        p_label = triad.pin_label(side, a)
        q_side = emulator.label(side.inner, a)
        start = f"n_{side.inner}{side.outer}"  # laid off above for every side
        epsilon = _read_turn(emulator, a, start, q_side, side.P, side.Q, side.link,
                             mu_a / mu_l, "epsilon")
        omega = emulator.omega(side.link)
        emulator.fix_acceleration(side.link, side.P, p_label, omega, epsilon)


def _sliding_acceleration(emulator: PlanDrawer, triad: _Triad, side: _Side) -> None:
    """A sliding side on the acceleration plan, once the central link's image is known: its
    link turns with its carrier; its relative acceleration read off, from the end of its
    Coriolis component to the moving point's image."""
    a = emulator.a
    base, moving = triad.pin_label(side, a), triad.moving_label(side, a)
    turns_with = side.turns_with
    emulator.fix_acceleration(side.link, side.P, moving if side.outer_slide else base,
                              emulator.omega(turns_with), emulator.epsilon(turns_with))
    k_label = f"k_{side.moving}"
    sign = sense(a.points[moving] - a.points[k_label], side.guide)
    a.read(k_label, moving, quantity=f"a_rel_{side.moving}{side.base}", sign=sign,
           factor=emulator.scales.mu_a, relative=VectorName("aʳ", side.moving, side.base))
    emulator.slid(side.slide.key, {"a": (base, k_label, moving)})


def _third_side_acceleration(emulator: PlanDrawer, triad: _Triad, group: AssurGroup
                             ) -> tuple[str, str]:
    """The third side's inner pin Q on the acceleration plan, from S* (aⁿ and the line of aᵗ of
    Q about S*) and from its known point (aⁿ and the line of aᵗ of Q about it; a sliding side:
    aᵏ and the line of aʳ); returns its label and the end of its normal component about S*."""
    v, a = emulator.v, emulator.a
    third, special = triad.sides[triad.i], triad.special
    moving = third.moving
    q_label, q_v = emulator.label(moving, a), emulator.label(moving, v)
    n_central = f"n_{moving}S*" if "@" not in moving else f"n_{moving}"
    _normal(emulator, SPECIAL, n_central, special, third.Q, SPECIAL, q_v, group,
            VectorName("aⁿ", moving, "S*"))
    first = a.line(n_central, perp(unit(third.Q - special)), component="tangential",
                   group=group.index, vector=VectorName("aᵗ", moving, "S*"),
                   along=Across(moving, "S*"))
    if third.slide is None:
        start = f"n_{third.inner}{third.outer}"
        _normal(emulator, triad.pin_label(third, a), start, third.P, third.Q,
                triad.pin_label(third, v), q_v, group,
                VectorName("aⁿ", third.inner, third.outer))
    else:
        start = _coriolis(emulator, triad, third, group)
    second = _side_line(emulator, a, third, start, group)
    a.intersect(first, second, q_label, group=group, angle=emulator.angle,
                solves=BothSides(moving))
    return q_label, n_central
