"""RPR dyad (type 3): a block L1 pinned to a known link at P1 slides in a guide link L2 that
turns about its pivot P2 on a known link (the crank and slotted lever).

Position: in L2's frame the pin P1 lies on the guide line, P2→P1 = c0 + s·u (u the guide's
direction, s the travel); |P2P1| fixes s, branch +1 the larger root.

Vector equations (X = P1 taken as a point of L2, ``B@lever``): v_X = v_P1 + v_rel (along the
guide) = v_P2 + v_XP2 (⟂ P2P1); the Coriolis term 2ω_L2 × v_rel.

Its reactions: the forces face, :mod:`planmethod.forces.groups.rpr`.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/slotted_lever.toml").mechanism).at(0)
>>> round(float(motion.omega("lever")), 6)
1.923077
"""

from __future__ import annotations

import math

import numpy as np

from ...vocabulary import GroupKind
from ...words.message import message
from ..algebra import Body, Vec, cross, dot, sqrt
from . import base, checks, dyad

__all__ = ["BRANCHES", "KIND", "place"]

KIND = GroupKind.RPR
BRANCHES = 2


def place(context: base.GroupInputs) -> dyad.Placed:
    group = context.group
    ext1, internal, ext2, l1, l2 = context.dyad()   # l1 is the block (the slide's link)
    slide = internal.slide
    p1, p2 = context.pin(ext1), context.pin(ext2)
    angle = slide.direction_rad
    u = Vec(math.cos(angle), math.sin(angle))
    through = context.local(l2, slide.through)
    block = context.local(l1, slide.point)
    turned = Vec(p1.local[0] - block[0], p1.local[1] - block[1]).turned(*u)
    c0 = Vec(through[0] - p2.local[0] + turned.x, through[1] - p2.local[1] + turned.y)
    offset = cross(c0, u)      # the guide's distance from the pivot
    span = p1.at - p2.at
    square = dot(span, span)
    length = sqrt(square)
    text = message("the guide of {link} passes {offset:g} m from its pivot {pivot}; it cannot "
                   "reach {point}", link=l2, offset=abs(offset), pivot=ext2.point,
                   point=ext1.point)

    def check(angles, distance, sx, sy) -> None:
        distance = np.atleast_1d(np.asarray(distance, dtype=float))
        close = distance <= 1e-15
        if np.any(close):
            raise checks.assembly_error(group, angles, close, checks.coinciding(ext1, ext2),
                                        0.0)
        if offset != 0:
            size = np.maximum(np.abs(np.asarray(sx)), np.abs(np.asarray(sy)))
            checks.toggle_or_miss(group, angles, distance - abs(offset),
                           distance + abs(offset) + size, text, abs(offset) - distance)

    # |P1P2| − |offset| must exceed 16ε·(|P1P2| + |offset| + |span|) ≤ 16ε·(3|P1P2| + |offset|)
    # (and 1e-15 m): a margin proportional to the length itself
    rounding = 16.0 * checks.EPS * checks.MARGIN
    gap = length * (1.0 - 3.0 * rounding) - abs(offset) * (1.0 + rounding)
    context.guard(gap, 1e-15, check, length, span.x, span.y)
    projection = -dot(c0, u)
    s = projection + sqrt(square - offset * offset) * context.sign
    inside = c0 + u * s    # P2 → P1 in L2's frame
    # L2's axes turn `inside` onto `span`: (cos, sin) of angle(span) − angle(inside)
    c2 = dot(inside, span) / square
    s2 = cross(inside, span) / square
    body2 = Body(c2, s2)
    c1, s1 = Vec(c2, s2).turned(u.x, u.y)
    body1 = Body(c1, s1)
    for body, pin in ((body1, p1), (body2, p2)):
        origin = pin.at - body.offset(*pin.local)
        body.x, body.y = origin.x, origin.y
    placed = {l1: body1, l2: body2}
    x = p1.at
    sides = (dyad.pinned_sliding_side(context, slide, l1, p1, placed),
             dyad.rotation_side(l2, p2, span, length))
    return dyad.Placed(
        bodies=placed, point=f"{ext1.point}@{l2}", x=x, sides=sides,
        rotating={l2: 1}, tied={l1: l2},
        anchors={l1: dyad.Anchor(ext1.point, p1.at, p1.known, p1.offset, p1.local),
                 l2: dyad.Anchor(ext2.point, p2.at, p2.known, p2.offset, p2.local)},
        thetas={l2: base.Theta(base.ThetaKind.SPAN, ext1.point, ext2.point, link=l2),
                l1: base.Theta(base.ThetaKind.TIED, alpha=angle, link=l2)},
        ratio_bound=2.0 * checks.MARGIN, x_links=(l2,))
