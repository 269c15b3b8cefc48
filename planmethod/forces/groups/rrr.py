"""The forces face of the RRR dyad (:mod:`planmethod.kinematics.groups.rrr`): its textbook
reaction sequence, run by the group-by-group method (:mod:`planmethod.forces.group_method`).

Rᵗ at P1 ⟂ P1Q from ΣM_Q(L1) = 0, Rᵗ at P2 from ΣM_Q(L2) = 0; the group's force
polygon Rᵗ1 + ΣF + Rᵗ2 + Rⁿ2 + Rⁿ1 = 0 with the Rⁿ along the links; the pin Q from L1.

Examples
--------
>>> from planmethod.forces import solve_forces
>>> from planmethod.kinematics import solve
>>> from planmethod.spec import load_exercise
>>> from planmethod.words import render
>>> motion = solve(load_exercise("exercises/fourbar_forces.toml").mechanism)
>>> render(solve_forces(motion).groups.groups[0].steps[0])
'Rᵗ_B ⟂ BC from ΣM_C(BC) = 0: Rᵗ_B = ΣM_C/BC'
"""

from __future__ import annotations

from ...structure import AssurGroup
from ...vectors import perp
from ...vocabulary import EdgeKind
from ...words import message
from ..names import ForceName, LinkNumber, PointNames
from .base import ForceSolver, GroupForces, split

__all__ = ["reactions"]


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.forces.groups.base.ForceSolver`).

    Rᵗ at P1 ⟂ P1Q from ΣM_Q(L1) = 0, Rᵗ at P2 from ΣM_Q(L2) = 0; the group's polygon
    Rᵗ1 + ΣF + Rᵗ2 + Rⁿ2 + Rⁿ1 = 0 with the Rⁿ along the links; the pin Q from L1.
    """
    ext1, internal, ext2 = group.joints
    l1, l2 = group.links
    k1, k2 = ext1.other(l1), ext2.other(l2)
    p1, q, p2 = solver.at(l1, ext1.point), solver.at(l1, internal.point), solver.at(l2, ext2.point)
    w1, w2 = solver.wrench[l1], solver.wrench[l2]
    e1, a = split(q - p1)
    e2, b = split(q - p2)
    t1 = w1.moment_about(q) / a
    t2 = w2.moment_about(q) / b
    rt1, rt2 = t1[..., None] * perp(e1), t2[..., None] * perp(e2)
    known = w1.force + w2.force
    n1, n2 = solver.solve2(e1, e2, -(rt1 + rt2 + known), group.name,
                           message("{first} and {second} are in line (toggle)", first=l1,
                                   second=l2))
    rn1, rn2 = n1[..., None] * e1, n2[..., None] * e2
    r1, r2 = rn1 + rt1, rn2 + rt2
    edges = [solver.edge(f"Rᵗ_{ext1.point}", rt1, EdgeKind.COMPONENT, l1),
             *solver.known_edges((l1, l2)),
             solver.edge(f"Rᵗ_{ext2.point}", rt2, EdgeKind.COMPONENT, l2),
             solver.edge(f"Rⁿ_{ext2.point}", rn2, EdgeKind.COMPONENT, l2),
             solver.edge(f"Rⁿ_{ext1.point}", rn1, EdgeKind.COMPONENT, l1)]
    keys = [solver.record(ext1, group.links, l1, k1, p1, r1).key,
            solver.record(ext2, group.links, l2, k2, p2, r2).key,
            solver.record(internal, group.links, l2, l1, q, r1 + w1.force).key]
    return solver.result(group, _steps(ext1.point, internal.point, ext2.point, l1, l2), edges,
                         keys)


def _steps(p1: str, q: str, p2: str, l1: str, l2: str) -> tuple:
    """The sequence's sentences: the outer pins P1, P2 of the links L1, L2, the inner pin Q."""
    first, second = ForceName(f"Rᵗ_{p1}"), ForceName(f"Rᵗ_{p2}")
    pin = PointNames(q)
    return (message("{force} ⟂ {segment} from ΣM_{pin}({link}) = 0: {force} = ΣM_{pin}/"
                    "{segment}", force=first, segment=PointNames(p1, q), pin=pin,
                    link=LinkNumber(l1)),
            message("{force} ⟂ {segment} from ΣM_{pin}({link}) = 0: {force} = ΣM_{pin}/"
                    "{segment}", force=second, segment=PointNames(p2, q), pin=pin,
                    link=LinkNumber(l2)),
            message("force polygon of the group: {first} + ΣF + {second} + {second_normal} + "
                    "{first_normal} = 0, {first_normal} ∥ {first_segment}, {second_normal} ∥ "
                    "{second_segment}", first=first, second=second,
                    first_normal=ForceName(f"Rⁿ_{p1}"), second_normal=ForceName(f"Rⁿ_{p2}"),
                    first_segment=PointNames(p1, q), second_segment=PointNames(p2, q)),
            message("{pin} from the equilibrium of link {number}: {pin} = {outer} + "
                    "ΣF({number})", pin=ForceName(f"R_{q}"), outer=ForceName(f"R_{p1}"),
                    number=LinkNumber(l1)))
