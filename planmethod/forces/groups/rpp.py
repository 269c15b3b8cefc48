"""The forces face of the RPP dyad (:mod:`planmethod.kinematics.groups.rpp`): its textbook
reaction sequence, run by the group-by-group method (:mod:`planmethod.forces.group_method`).

N of the outer guide from L2's projection on the inner guide; R at P1 from the
group's polygon; the inner normal force and couple from L1, the outer couple from ΣM(L2).

Examples
--------
>>> from planmethod.forces import solve_forces
>>> from planmethod.kinematics import solve
>>> from planmethod.spec import load_exercise
>>> from planmethod.words import render
>>> motion = solve(load_exercise("exercises/scotch_yoke.toml").mechanism)
>>> render(solve_forces(motion).groups.groups[0].steps[0])
"N of pair yoke/frame from link yoke's projection on the guide of pair block/yoke"
"""

from __future__ import annotations

from ... import vectors
from ...structure import AssurGroup
from ...vocabulary import EdgeKind
from ...words import message
from ..names import ForceName, LinkNumber, PairNumbers
from .base import ForceSolver, GroupForces

__all__ = ["reactions"]


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.forces.groups.base.ForceSolver`).

    N of the outer guide from L2's projection on the inner guide; R at P1 from the group's
    polygon; the inner normal force and couple from L1, the outer couple from ΣM(L2).
    """
    ext1, internal, ext2 = group.joints
    inner_pair = PairNumbers(internal.slide.link, internal.slide.along)
    outer_pair = PairNumbers(ext2.slide.link, ext2.slide.along)
    l1, l2 = group.links
    k1, k2 = ext1.other(l1), ext2.other(l2)
    p1 = solver.at(l1, ext1.point)
    di, _, psi = solver.guide(internal)
    _, n2, ps2 = solver.guide(ext2)
    w1, w2 = solver.wrench[l1], solver.wrench[l2]
    across = vectors.dot(n2, di)
    solver.singular(across, 1.0, group.name,
                    message("the guides of pairs {first} and {second} are parallel",
                            first=inner_pair, second=outer_pair))
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
    steps = (message("N of pair {pair} from link {link}'s projection on the guide of pair "
                     "{inner}", pair=outer_pair, link=LinkNumber(l2), inner=inner_pair),
             message("{reaction} from the force polygon of the group",
                     reaction=ForceName(f"R_{ext1.point}")),
             message("the normal force and couple of pair {pair} from link {link}",
                     pair=inner_pair, link=LinkNumber(l1)),
             message("the couple of pair {pair} from ΣM({link}) = 0", pair=outer_pair,
                     link=LinkNumber(l2)))
    return solver.result(group, steps, edges, keys)
