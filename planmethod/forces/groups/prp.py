"""The forces face of the PRP dyad (:mod:`planmethod.kinematics.groups.prp`): its textbook
reaction sequence, run by the group-by-group method (:mod:`planmethod.forces.group_method`).

N1, N2 from the group's polygon (each ⟂ its guide); the pin Q from L2; each reaction
couple from its link's moments.

Examples
--------
>>> from planmethod.forces import solve_forces
>>> from planmethod.kinematics import solve
>>> from planmethod.spec import load_exercise
>>> from planmethod.words import render
>>> motion = solve(load_exercise("exercises/slotted_crank_crosshead.toml").mechanism)
>>> render(solve_forces(motion).groups.groups[0].steps[0])
'force polygon of the group: ΣF + N2 + N1 = 0, each N ⟂ its guide'
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

    N1, N2 from the group's polygon (each ⟂ its guide); the pin Q from L2; each reaction
    couple from its link's moments about its slide point.
    """
    ext1, internal, ext2 = group.joints
    l1, l2 = group.links
    k1, k2 = ext1.other(l1), ext2.other(l2)
    q = solver.at(l1, internal.point)
    _, n1, ps1 = solver.guide(ext1)
    _, n2, ps2 = solver.guide(ext2)
    w1, w2 = solver.wrench[l1], solver.wrench[l2]
    big1, big2 = solver.solve2(n1, n2, -(w1.force + w2.force), group.name,
                               message("the guides of pairs {first} and {second} are parallel",
                                       first=PairNumbers(ext1.slide.link, ext1.slide.along),
                                       second=PairNumbers(ext2.slide.link,
                                                          ext2.slide.along)))
    f1, f2 = big1[..., None] * n1, big2[..., None] * n2
    r_q = -(w2.force + f2)                         # on l2 from l1
    c1 = -(w1.moment_about(ps1) + vectors.cross(q - ps1, -r_q))
    c2 = -(w2.moment_about(ps2) + vectors.cross(q - ps2, r_q))
    edges = [*solver.known_edges((l1, l2)),
             solver.edge(f"N_{ext2.slide.key}", f2, EdgeKind.COMPONENT, l2),
             solver.edge(f"N_{ext1.slide.key}", f1, EdgeKind.COMPONENT, l1)]
    keys = [solver.record(ext1, group.links, l1, k1, ps1, f1, c1).key,
            solver.record(ext2, group.links, l2, k2, ps2, f2, c2).key,
            solver.record(internal, group.links, l2, l1, q, r_q).key]
    steps = (message("force polygon of the group: ΣF + N2 + N1 = 0, each N ⟂ its guide"),
             message("{pin} from the equilibrium of link {link}",
                     pin=ForceName(f"R_{internal.point}"), link=LinkNumber(l2)),
             message("each reaction couple from its link's moments about its slide point"))
    return solver.result(group, steps, edges, keys)
