"""The forces face of the RPR dyad (:mod:`planmethod.kinematics.groups.rpr`): its textbook
reaction sequence, run by the group-by-group method (:mod:`planmethod.forces.group_method`).

R at P1 along the guide from the block's projection on the guide, across it from
ΣM_P2 of the group; the normal force and couple of the slide from the block; R at P2 from the
polygon of L2.

Examples
--------
>>> from planmethod.forces import solve_forces
>>> from planmethod.kinematics import solve
>>> from planmethod.spec import load_exercise
>>> from planmethod.words import render
>>> motion = solve(load_exercise("exercises/slotted_lever.toml").mechanism)
>>> render(solve_forces(motion).groups.groups[0].steps[0])
"R_B along the guide from link block's projection on the guide"
"""

from __future__ import annotations

from ... import vectors
from ...structure import AssurGroup
from ...vocabulary import EdgeKind
from ...words import message
from ..names import ForceName, LinkNumber, PairNumbers, PointNames
from .base import ForceSolver, GroupForces

__all__ = ["reactions"]


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.forces.groups.base.ForceSolver`).

    R at P1 along the guide from the block's projection on the guide, across it from
    ΣM_P2 of the group; the slide's normal force and couple from the block; R at P2 from L2.
    """
    ext1, internal, ext2 = group.joints
    l1, l2 = group.links          # l1 is the block (the slide's link), l2 its guide
    k1, k2 = ext1.other(l1), ext2.other(l2)
    p1, p2 = solver.at(l1, ext1.point), solver.at(l2, ext2.point)
    d, n, ps = solver.guide(internal)
    w1, w2 = solver.wrench[l1], solver.wrench[l2]
    along = -vectors.dot(w1.force, d)
    arm = p1 - p2
    lever = vectors.cross(arm, n)
    solver.singular(lever, vectors.norm(arm) + 1e-300, group.name,
                    message("{point} lies on the normal to the guide through {other}",
                            point=ext1.point, other=ext2.point))
    across = -((w1 + w2).moment_about(p2) + along * vectors.cross(arm, d)) / lever
    r_along, r_across = along[..., None] * d, across[..., None] * n
    r1 = r_along + r_across
    inner = -(r1 + w1.force)                       # on the block from the guide
    couple = -(w1.moment_about(ps) + vectors.cross(p1 - ps, r1))
    r2 = inner - w2.force
    edges = [solver.edge(f"R∥_{ext1.point}", r_along, EdgeKind.COMPONENT, l1),
             solver.edge(f"R⊥_{ext1.point}", r_across, EdgeKind.COMPONENT, l1),
             *solver.known_edges((l1, l2)),
             solver.edge(f"R_{ext2.point}", r2, EdgeKind.REACTION, l2)]
    keys = [solver.record(ext1, group.links, l1, k1, p1, r1).key,
            solver.record(internal, group.links, l1, l2, ps, inner, couple).key,
            solver.record(ext2, group.links, l2, k2, p2, r2).key]
    first = ForceName(f"R_{ext1.point}")
    steps = (message("{reaction} along the guide from link {link}'s projection on the guide",
                     reaction=first, link=LinkNumber(l1)),
             message("{reaction} ⟂ the guide from ΣM_{point} of the group = 0",
                     reaction=first, point=PointNames(ext2.point)),
             message("the normal force and couple of pair {pair} from link {link}",
                     pair=PairNumbers(internal.slide.link, internal.slide.along),
                     link=LinkNumber(l1)),
             message("{reaction} from the force polygon of link {link}",
                     reaction=ForceName(f"R_{ext2.point}"), link=LinkNumber(l2)))
    return solver.result(group, steps, edges, keys)
