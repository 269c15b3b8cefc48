"""PRP dyad (type 4): L1 and L2 pinned together at Q, each sliding along a guide of a known link
(a slotted crank driving a crosshead).

Position: Q is where the two guide lines meet (one assembly); parallel guides are the toggle.

Vector equations (X = Q): v_Q = v_Q@K1 + v_rel1 (along guide 1) = v_Q@K2 + v_rel2 (along
guide 2).

Its reactions: the forces face, :mod:`planmethod.forces.groups.prp`.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/slotted_crank_crosshead.toml").mechanism).at(0)
>>> motion.position("Q").round(6)
array([0.175279, 0.530906])
"""

from __future__ import annotations

from ...vocabulary import GroupKind
from ...words.message import message
from ..algebra import Body, Vec, cross, dot
from . import base, checks, dyad

__all__ = ["BRANCHES", "KIND", "place"]

KIND = GroupKind.PRP
BRANCHES = 1


def place(context: base.GroupInputs) -> dyad.Placed:
    group = context.group
    ext1, internal, ext2, l1, l2 = context.dyad()
    lines = []
    for joint in (ext1, ext2):
        link = context.group_link(joint)
        c, s = context.slide_axes(joint.slide, link)
        _, n, line = context.guide(joint.slide, link)
        local = context.local(link, internal.point)
        turned = Body(c, s).offset(*local)
        lines.append((link, Body(c, s), n, line + dot(n, turned), local,
                      turned))
    (_, body1, n1, c1, q1, t1), (_, body2, n2, c2, q2, t2) = lines
    det = cross(n1, n2)
    text = message("the guides of {pair1} and {pair2} are parallel: {point} has no definite "
                   "position", pair1=ext1.slide.key, pair2=ext2.slide.key, point=internal.point)

    def check(angles, value) -> None:
        checks.parallel_guides(group, angles, value, text)

    context.guard(det * det, checks.TOGGLE_SINE * checks.TOGGLE_SINE, check, det)
    x = Vec((c1 * n2.y - c2 * n1.y) / det, (n1.x * c2 - n2.x * c1) / det)
    for body, turned, local in ((body1, t1, q1), (body2, t2, q2)):
        origin = x if local == (0.0, 0.0) else x - turned
        body.x, body.y = origin.x, origin.y
    placed = {l1: body1, l2: body2}
    k1, k2 = ext1.other(l1), ext2.other(l2)
    sides = tuple(dyad.sliding_side(context, joint.slide, known, f"{internal.point}@{known}", known,
                               x, placed) for joint, known in ((ext1, k1), (ext2, k2)))

    def delta(joint, link) -> float:
        return joint.slide.direction_rad if link == joint.slide.link else (
            -joint.slide.direction_rad)

    return dyad.Placed(
        bodies=placed, point=internal.point, x=x, sides=sides,
        rotating={}, tied={l1: k1, l2: k2},
        anchors={},
        thetas={l1: base.Theta(base.ThetaKind.TIED, alpha=delta(ext1, l1), link=k1),
                l2: base.Theta(base.ThetaKind.TIED, alpha=delta(ext2, l2), link=k2)},
        ratio_bound=1.0, x_links=(l1, l2), x_local={l1: q1, l2: q2})
