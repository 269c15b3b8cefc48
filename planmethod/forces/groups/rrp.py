"""The forces face of the RRP dyad (:mod:`planmethod.kinematics.groups.rrp`): its textbook
reaction sequence, run by the group-by-group method (:mod:`planmethod.forces.group_method`).

Rᵗ at P1 from ΣM_Q(L1) = 0; the polygon Rᵗ1 + ΣF + N + Rⁿ1 = 0 with N ⟂ the guide;
the pin Q from L1; the guide's reaction couple from ΣM(L2) = 0 about the slide point.

Examples
--------
>>> from planmethod.forces import solve_forces
>>> from planmethod.kinematics import solve
>>> from planmethod.spec import load_exercise
>>> from planmethod.words import render
>>> motion = solve(load_exercise("exercises/combined_force_slider_crank.toml").mechanism)
>>> render(solve_forces(motion).groups.groups[0].steps[0])
'Rᵗ_B ⟂ BC from ΣM_C(BC) = 0'
"""

from __future__ import annotations

from ...structure import AssurGroup
from ...vectors import cross, perp
from ...vocabulary import EdgeKind
from ...words import message
from ..names import ForceName, LinkNumber, PairNumbers, PointNames
from .base import ForceSolver, GroupForces, split

__all__ = ["reactions"]


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.forces.groups.base.ForceSolver`).

    Rᵗ at P1 from ΣM_Q(L1) = 0; the polygon Rᵗ1 + ΣF + N + Rⁿ1 = 0 with N ⟂ the guide;
    the pin Q from L1; the guide's reaction couple from ΣM(L2) = 0 about the slide point.
    """
    ext1, internal, ext2 = group.joints
    l1, l2 = group.links
    k1, k2 = ext1.other(l1), ext2.other(l2)
    p1, q = solver.at(l1, ext1.point), solver.at(l1, internal.point)
    _, n, ps = solver.guide(ext2)
    w1, w2 = solver.wrench[l1], solver.wrench[l2]
    e1, a = split(q - p1)
    t1 = w1.moment_about(q) / a
    rt1 = t1[..., None] * perp(e1)
    n1, normal = solver.solve2(e1, n, -(rt1 + w1.force + w2.force), group.name,
                               message("{link} is perpendicular to the guide of pair {pair}",
                                       link=l1, pair=PairNumbers(ext2.slide.link,
                                                                 ext2.slide.along)))
    rn1, big_n = n1[..., None] * e1, normal[..., None] * n
    r1 = rn1 + rt1
    r_q = r1 + w1.force
    couple = -(w2.moment_about(ps) + cross(q - ps, r_q))
    edges = [solver.edge(f"Rᵗ_{ext1.point}", rt1, EdgeKind.COMPONENT, l1),
             *solver.known_edges((l1, l2)),
             solver.edge(f"N_{ext2.slide.key}", big_n, EdgeKind.COMPONENT, l2),
             solver.edge(f"Rⁿ_{ext1.point}", rn1, EdgeKind.COMPONENT, l1)]
    keys = [solver.record(ext1, group.links, l1, k1, p1, r1).key,
            solver.record(ext2, group.links, l2, k2, ps, big_n, couple).key,
            solver.record(internal, group.links, l2, l1, q, r_q).key]
    p1, pin, guide = ext1.point, internal.point, ext2.slide
    tangential, normal_part = ForceName(f"Rᵗ_{p1}"), ForceName(f"Rⁿ_{p1}")
    pair = PairNumbers(guide.link, guide.along)
    steps = (message("{force} ⟂ {segment} from ΣM_{pin}({link}) = 0", force=tangential,
                     segment=PointNames(p1, pin), pin=PointNames(pin), link=LinkNumber(l1)),
             message("force polygon: {tangential} + ΣF + N + {normal} = 0, N ⟂ the guide of "
                     "pair {pair}, {normal} ∥ {segment}", tangential=tangential,
                     normal=normal_part, pair=pair, segment=PointNames(p1, pin)),
             message("{pin} from the equilibrium of link {link}", pin=ForceName(f"R_{pin}"),
                     link=LinkNumber(l1)),
             message("the reaction couple of pair {pair} from ΣM({link}) = 0 about {point}",
                     pair=pair, link=LinkNumber(l2), point=PointNames(guide.point)))
    return solver.result(group, steps, edges, keys)
