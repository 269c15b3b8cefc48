"""RPP dyad (type 5): L1 pinned to a known link at P1 slides in L2, which slides along a guide
of a known link (the Scotch yoke).

Position: L1 turns with L2, L2 with its guide's link; L2's origin is where the line of the
inner guide (through the block) meets the line of the outer guide (one assembly); parallel
guides are the toggle.

Vector equations (X = P1 taken as a point of L2, ``B@yoke``): v_X = v_P1 + v_rel (along the
slot) = v_X@K + v_rel2 (along the fixed guide).

Its reactions: the forces face, :mod:`planmethod.forces.groups.rpp`.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/scotch_yoke.toml").mechanism).at(0)
>>> round(float(motion.omega("yoke")), 6)
0.0
"""

from __future__ import annotations

from ...vocabulary import GroupKind
from ...words.message import message
from ..algebra import Body, cross
from . import base, checks, dyad

__all__ = ["BRANCHES", "KIND", "place"]

KIND = GroupKind.RPP
BRANCHES = 1


def place(context: base.GroupInputs) -> dyad.Placed:
    group = context.group
    ext1, internal, ext2, l1, l2 = context.dyad()
    k2 = ext2.other(l2)
    p1 = context.pin(ext1)
    c2, s2 = context.slide_axes(ext2.slide, l2)
    body2 = Body(c2, s2)
    inner = internal.slide
    angle = inner.direction_rad if l1 == inner.link else -inner.direction_rad
    body1 = Body(*base.turned_axes(c2, s2, angle))
    origin1 = p1.at - body1.offset(*p1.local)
    body1.x, body1.y = origin1.x, origin1.y
    _, n2, line2 = context.guide(ext2.slide, l2)
    _, n1, line1 = context.guide(inner, l2, body1)
    det = cross(n1, n2)
    text = message("the guides of {pair1} and {pair2} are parallel: {link} has no definite "
                   "position", pair1=inner.key, pair2=ext2.slide.key, link=l2)

    def check(angles, value) -> None:
        checks.parallel_guides(group, angles, value, text)

    context.guard(det * det, checks.TOGGLE_SINE * checks.TOGGLE_SINE, check, det)
    body2.x = (line1 * n2.y - line2 * n1.y) / det
    body2.y = (n1.x * line2 - n2.x * line1) / det
    placed = {l1: body1, l2: body2}
    x = p1.at
    x_name = f"{ext1.point}@{l2}"
    sides = (dyad.pinned_sliding_side(context, inner, l1, p1, placed),
             dyad.sliding_side(context, ext2.slide, k2, f"{ext1.point}@{k2}", k2, x, placed))
    outer = ext2.slide.direction_rad if l2 == ext2.slide.link else -ext2.slide.direction_rad
    return dyad.Placed(
        bodies=placed, point=x_name, x=x, sides=sides,
        rotating={}, tied={l2: k2, l1: l2},
        anchors={l1: dyad.Anchor(ext1.point, p1.at, p1.known, p1.offset, p1.local)},
        thetas={l2: base.Theta(base.ThetaKind.TIED, alpha=outer, link=k2),
                l1: base.Theta(base.ThetaKind.TIED, alpha=angle, link=l2)},
        ratio_bound=1.0, x_links=(l2,))
