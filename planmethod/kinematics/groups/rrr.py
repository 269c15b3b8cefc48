"""RRR dyad (type 1): two links L1, L2 pinned to known links at P1, P2 and to each other at Q.

Position: Q is where the circles about P1 (radius a = P1Q) and P2 (radius b = P2Q) meet — by
Heron's form, which keeps the height accurate near the toggle (a + b ≈ |P1P2| or |a − b| ≈
|P1P2|). Branch +1 puts Q to the left of P1 → P2.

Vector equations (X = Q): v_Q = v_P1 + v_QP1 (⟂ P1Q) = v_P2 + v_QP2 (⟂ P2Q).

Its reactions: the forces face, :mod:`planmethod.forces.groups.rrr`.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/fourbar_coupler_point.toml").mechanism, 60.0).at(0)
>>> motion.position("C").round(6)
array([0.23641 , 0.168393])
"""

from __future__ import annotations

import numpy as np

__all__ = ["BRANCHES", "KIND", "place"]

from ...vocabulary import GroupKind
from ...words.message import message
from ..algebra import Body, dot, sqrt
from . import base, checks, dyad

KIND = GroupKind.RRR
BRANCHES = 2


def place(context: base.GroupInputs) -> dyad.Placed:
    group = context.group
    ext1, internal, ext2, l1, l2 = context.dyad()
    p1, p2 = context.pin(ext1), context.pin(ext2)
    q1, q2 = context.local(l1, internal.point), context.local(l2, internal.point)
    a = context.length(l1, ext1.point, internal.point)
    b = context.length(l2, ext2.point, internal.point)
    span = p2.at - p1.at
    square = dot(span, span)
    d = sqrt(square)
    # Heron's form: the product of the four factors a ± b ± d
    product = (a + b + d) * (a + b - d) * (a - b + d) * (b - a + d)
    text = message("{link1} ({point1}{joint} = {length1:g} m) and {link2} ({joint}{point2} = "
                   "{length2:g} m) cannot join {point1} and {point2}", link1=l1,
                   point1=ext1.point, joint=internal.point, length1=a, link2=l2,
                   point2=ext2.point, length2=b)

    def check(angles, x1, y1, x2, y2) -> None:
        dx, dy = np.asarray(x2) - np.asarray(x1), np.asarray(y2) - np.asarray(y1)
        distance = np.atleast_1d(np.sqrt(dx * dx + dy * dy))
        close = distance <= 1e-15 * (a + b)
        if np.any(close):
            raise checks.assembly_error(group, angles, close, checks.coinciding(ext1, ext2),
                                        0.0)
        stretched, folded = a + b - distance, distance - abs(a - b)
        vanishing = np.where(np.abs(stretched) <= np.abs(folded), stretched, folded)
        reach = np.maximum(np.abs(dx), np.abs(dy))
        checks.toggle_or_miss(group, angles, vanishing, a + b + distance + reach, text,
                       np.maximum(distance - a - b, np.maximum(abs(a - b) - distance, 0.0)))

    # where the product exceeds this, no angle is a toggle, a miss or coinciding pins
    # (docs/accuracy.md: a toggle's vanishing factor within 16ε of the terms' size)
    bound = max(192.0 * checks.EPS, 1e-30) * (a + b) ** 4 * checks.MARGIN
    context.guard(product, bound, check, p1.at.x, p1.at.y, p2.at.x, p2.at.y)
    twice = d * 2.0
    along = (a * a - b * b + square) / twice
    height = sqrt(product) / twice * context.sign
    unit = span / d
    r1 = unit * along + unit.perp() * height
    x = p1.at + r1
    r2 = x - p2.at
    body1 = Body(*dyad.axes_towards(r1, p1.local, q1, a))
    body2 = Body(*dyad.axes_towards(r2, p2.local, q2, b))
    dyad.place_origin(body1, ((p1.at, p1.local), (x, q1)))
    dyad.place_origin(body2, ((p2.at, p2.local), (x, q2)))
    return dyad.Placed(
        bodies={l1: body1, l2: body2}, point=internal.point, x=x,
        sides=(dyad.rotation_side(l1, p1, r1, a), dyad.rotation_side(l2, p2, r2, b)),
        rotating={l1: 0, l2: 1}, tied={},
        anchors={l1: dyad.Anchor(ext1.point, p1.at, p1.known, p1.offset, p1.local),
                 l2: dyad.Anchor(ext2.point, p2.at, p2.known, p2.offset, p2.local)},
        thetas={l1: base.Theta(base.ThetaKind.TWO, ext1.point, internal.point,
                               _angle(p1.local, q1)),
                l2: base.Theta(base.ThetaKind.TWO, ext2.point, internal.point,
                               _angle(p2.local, q2))},
        ratio_bound=2.0 * (a + b) / min(a, b) * checks.MARGIN, x_links=(l1, l2),
        x_local={l1: q1, l2: q2})


def _angle(first, second) -> float:
    return float(np.arctan2(second[1] - first[1], second[0] - first[0]))
