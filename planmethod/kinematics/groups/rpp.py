"""RPP dyad (type 5): L1 pinned to a known link at P1 slides in L2, which slides along a guide
of a known link (the Scotch yoke).

Position: L1 turns with L2, L2 with its guide's link; L2's origin is where the line of the
inner guide (through the block) meets the line of the outer guide (one assembly); parallel
guides are the toggle.

Vector equations (X = P1 taken as a point of L2, ``B@yoke``): v_X = v_P1 + v_rel (along the
slot) = v_X@K + v_rel2 (along the fixed guide).

Reactions: N of the outer guide from L2's projection on the inner guide; R at P1 from the
group's polygon; the inner normal force and couple from L1, the outer couple from ΣM(L2).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/scotch_yoke.toml").mechanism).at(0)
>>> round(float(motion.omega("yoke")), 6)
0.0
"""

from __future__ import annotations

from ... import vectors
from ...structure import AssurGroup
from ...vocabulary import EdgeKind, GroupKind
from ..algebra import Body, cross
from . import base, checks, dyad

__all__ = ["BRANCHES", "KIND", "place", "reactions"]

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
    text = (f"the guides of {inner.key} and {ext2.slide.key} are parallel: {l2} has no "
            "definite position")

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


# -- the reactions ---------------------------------------------------------------------------
def reactions(solver: base.ForceSolver, group: AssurGroup):
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.kinematics.groups.base.ForceSolver`).

    N of the outer guide from L2's projection on the inner guide; R at P1 from the group's
    polygon; the inner normal force and couple from L1, the outer couple from ΣM(L2).
    """
    ext1, internal, ext2 = group.joints
    l1, l2 = group.links
    k1, k2 = ext1.other(l1), ext2.other(l2)
    p1 = solver.at(l1, ext1.point)
    di, _, psi = solver.guide(internal)
    _, n2, ps2 = solver.guide(ext2)
    w1, w2 = solver.wrench[l1], solver.wrench[l2]
    across = vectors.dot(n2, di)
    solver.singular(across, 1.0, group.name,
                  f"the guides of {internal.slide.key} and {ext2.slide.key} are parallel")
    big2 = -vectors.dot(w2.force, di) / across
    f2 = big2[..., None] * n2
    r1 = -(w1.force + w2.force + f2)
    inner = -(r1 + w1.force)                       # on l1 from l2
    c_inner = -(w1.moment_about(psi) + vectors.cross(p1 - psi, r1))
    c2 = -(w2.moment_about(ps2) + vectors.cross(psi - ps2, -inner) - c_inner)
    edges = [solver.edge(f"N_{ext2.slide.key}", f2, EdgeKind.COMPONENT, l2),
             *solver.known_edges((l1, l2)),
             solver.edge(f"R_{ext1.point}", r1, EdgeKind.REACTION, l1)]
    keys = [solver.record(ext1, group.links, l1, k1, p1, r1).key,
            solver.record(internal, group.links, l1, l2, psi, inner, c_inner).key,
            solver.record(ext2, group.links, l2, k2, ps2, f2, c2).key]
    steps = (f"N of {ext2.slide.key} from {l2}'s projection on the guide of "
             f"{internal.slide.key}",
             f"R_{ext1.point} from the force polygon of the group",
             f"the normal force and couple of {internal.slide.key} from {l1}",
             f"the couple of {ext2.slide.key} from ΣM({l2}) = 0")
    return solver.result(group, steps, edges, keys)
