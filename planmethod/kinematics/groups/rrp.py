"""RRP dyad (type 2): L1 pinned to a known link at P1 and to L2 at Q; L2 slides along a guide
of a known link (the slider of a slider-crank).

Position: Q is where the circle about P1 (radius a = P1Q) meets the line of Q along the guide;
branch +1 takes the point further along the guide's direction.

Vector equations (X = Q): v_Q = v_P1 + v_QP1 (⟂ P1Q) = v_Q@K + v_rel (along the guide), K the
known link of the guide (Coriolis 2ω_K × v_rel where K turns).

Its reactions: the forces face, :mod:`planmethod.forces.groups.rrp`.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/compressor_slider_crank.toml").mechanism).at(0)
>>> round(float(motion.velocity("C")[0]), 4)
-5.2716
"""

from __future__ import annotations

import numpy as np

from ...vocabulary import GroupKind
from ...words.message import message
from ..algebra import Body, dot, sqrt
from . import base, checks, dyad

__all__ = ["BRANCHES", "KIND", "place"]

KIND = GroupKind.RRP
BRANCHES = 2


def place(context: base.GroupInputs) -> dyad.Placed:
    group = context.group
    ext1, internal, ext2, l1, l2 = context.dyad()
    slide = ext2.slide
    k2 = ext2.other(l2)
    p1 = context.pin(ext1)
    q1, q2 = context.local(l1, internal.point), context.local(l2, internal.point)
    a = context.length(l1, ext1.point, internal.point)
    c2, s2 = context.slide_axes(slide, l2)
    d, n, c = context.guide(slide, l2)
    turned = Body(c2, s2).offset(*q2)
    offset = c + dot(n, turned)   # the line of Q: n·Q = offset
    h = dot(n, p1.at) - offset
    square = a * a - h * h
    text = message("{link} ({point}{joint} = {length:g} m) cannot reach the line of {joint} "
                   "along {along}'s guide", link=l1, point=ext1.point, joint=internal.point,
                   length=a, along=slide.along)

    def check(angles, x1, y1, height, line) -> None:
        size = np.maximum(np.abs(x1), np.abs(y1))
        checks.toggle_or_miss(group, angles, a - np.abs(height), a + np.abs(line) + size, text,
                       np.abs(height) - a)

    # a² − h² = (a − |h|)(a + |h|): where it exceeds 2a·16ε·(scale) no angle is a toggle or a
    # miss; the scale a + |offset| + |P1| is at most 2a + 2|P1| while |h| < a (|P1| unbounded:
    # the check runs at every angle)
    far = np.inf if p1.bound is None else p1.bound
    bound = 2.0 * a * 16.0 * checks.EPS * (2.0 * a + 2.0 * far) * 1.01 * checks.MARGIN
    context.guard(square, bound, check, p1.at.x, p1.at.y, h, offset)
    along = sqrt(square) * context.sign
    r1 = d * along - n * h
    x = p1.at + r1
    body1 = Body(*dyad.axes_towards(r1, p1.local, q1, a))
    dyad.place_origin(body1, ((p1.at, p1.local), (x, q1)))
    body2 = Body(c2, s2)
    origin2 = x if q2 == (0.0, 0.0) else x - turned
    body2.x, body2.y = origin2.x, origin2.y
    placed = {l1: body1, l2: body2}
    sides = (dyad.rotation_side(l1, p1, r1, a),
             dyad.sliding_side(context, slide, k2, f"{internal.point}@{k2}", k2, x, placed))
    delta = slide.direction_rad if l2 == slide.link else -slide.direction_rad
    return dyad.Placed(
        bodies=placed, point=internal.point, x=x, sides=sides,
        rotating={l1: 0}, tied={l2: k2},
        anchors={l1: dyad.Anchor(ext1.point, p1.at, p1.known, p1.offset, p1.local)},
        thetas={l1: base.Theta(base.ThetaKind.TWO, ext1.point, internal.point,
                          float(np.arctan2(q1[1] - p1.local[1], q1[0] - p1.local[0]))),
                l2: base.Theta(base.ThetaKind.TIED, alpha=delta, link=k2)},
        ratio_bound=2.0 * checks.MARGIN, x_links=(l1, l2), x_local={l1: q1, l2: q2})
