"""The forces face of the Assur triad of revolute pairs (:mod:`planmethod.kinematics.groups.
triad`): its textbook reaction sequence, run by the group-by-group method
(:mod:`planmethod.forces.group_method`).

Rᵗ of each outer pin from the side link's moments about its inner pin; Assur's special
point S — where the lines of two side links meet — eliminates their Rⁿ: ΣM_S of the group
gives the third Rⁿ, the polygon the other two; the inner pins from the side links.

Examples
--------
>>> from planmethod.forces import solve_forces
>>> from planmethod.kinematics import solve
>>> from planmethod.spec import load_exercise
>>> motion = solve(load_exercise("exercises/conveyor_sixbar.toml").mechanism)
>>> solve_forces(motion).groups.groups[0].steps[0]
'Rᵗ_A ⟂ AB from ΣM_B(rod) = 0'
"""

from __future__ import annotations

import numpy as np

from ...structure import AssurGroup
from ...vectors import cross, norm, perp
from ...vocabulary import EdgeKind
from .base import ForceSolver, GroupForces, split

__all__ = ["reactions"]


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.forces.groups.base.ForceSolver`).

    Rᵗ of each outer pin from the side link's moments about its inner pin; Assur's special
    point S — where the lines of two side links meet — eliminates their Rⁿ: ΣM_S of the group
    gives the third Rⁿ, the polygon the other two; the inner pins from the side links.
    """
    central = group.links[0]
    sides = []
    for link in group.links[1:]:
        inner = next(j for j in group.joints if link in j.links and central in j.links)
        outer = next(j for j in group.joints if link in j.links and j is not inner)
        known = outer.other(link)
        p, q = solver.at(link, outer.point), solver.at(link, inner.point)
        e, length = split(q - p)
        t = solver.wrench[link].moment_about(q) / length
        sides.append((link, inner, outer, known, p, q, e, t[..., None] * perp(e)))
    total = solver.total(group.links)
    # Assur's special point: where the lines of sides j and k meet; choose, angle by angle,
    # the pair whose lines meet at the largest angle
    sines = []
    for i in range(3):
        j, k = [m for m in range(3) if m != i]
        sines.append(np.abs(cross(sides[j][6], sides[k][6])))
    choice = np.argmax(np.stack(sines), axis=0)
    normals = [np.zeros(solver.count) for _ in range(3)]
    special = np.zeros((solver.count, 2))
    for i in range(3):
        mask = choice == i
        if not np.any(mask):
            continue
        j, k = [m for m in range(3) if m != i]
        pj, ej, pk, ek = sides[j][4], sides[j][6], sides[k][4], sides[k][6]
        det = cross(ej, ek)
        solver.singular(np.where(mask, det, 1.0), 1.0, group.name,
                      "the lines of the three side links are parallel")
        s = pj + (cross(pk - pj, ek) / np.where(mask, det, 1.0))[..., None] * ej
        moment = total.moment_about(s)
        for side in sides:
            moment = moment + cross(side[4] - s, side[7])
        arm = cross(sides[i][4] - s, sides[i][6])
        scale = norm(sides[i][4] - s) + norm(sides[i][5] - sides[i][4])
        solver.singular(np.where(mask, arm, scale), scale, group.name,
                      "the lines of the three side links meet in one point")
        ni = -moment / np.where(mask, arm, 1.0)
        rest = -(total.force + sum(side[7] for side in sides) + ni[..., None] * sides[i][6])
        nj, nk = solver.solve2(np.where(mask[..., None], ej, np.array([1.0, 0.0])),
                             np.where(mask[..., None], ek, np.array([0.0, 1.0])), rest, group.name,
                             "two side links are parallel")
        for index, value in ((i, ni), (j, nj), (k, nk)):
            normals[index] = np.where(mask, value, normals[index])
        special = np.where(mask[..., None], s, special)
    edges = [solver.edge(f"Rᵗ_{side[2].point}", side[7], EdgeKind.COMPONENT, side[0])
             for side in sides]
    edges += solver.known_edges(group.links)
    keys = []
    for (link, inner, outer, known, p, q, e, rt), n_value in zip(sides, normals,
                                                                  strict=True):
        rn = n_value[..., None] * e
        edges.append(solver.edge(f"Rⁿ_{outer.point}", rn, EdgeKind.COMPONENT, link))
        r = rn + rt
        keys.append(solver.record(outer, group.links, link, known, p, r).key)
        keys.append(solver.record(inner, group.links, central, link, q,
                                r + solver.wrench[link].force).key)
    names = [side[2].point for side in sides]
    steps = tuple(f"Rᵗ_{side[2].point} ⟂ {side[2].point}{side[1].point} from "
                  f"ΣM_{side[1].point}({side[0]}) = 0" for side in sides)
    steps += (
        f"Assur's special point S where the lines of two side links (through "
        f"{', '.join(names)}) meet: ΣM_S of the group gives the third Rⁿ",
        "force polygon of the group: ΣRᵗ + ΣF + ΣRⁿ = 0 gives the other two Rⁿ",
        f"the inner pins from the equilibrium of each side link ({central} is the central "
        "link)")
    return solver.result(group, steps, edges, keys, special)
