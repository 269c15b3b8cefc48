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
>>> from planmethod.words import render
>>> motion = solve(load_exercise("exercises/conveyor_sixbar.toml").mechanism)
>>> render(solve_forces(motion).groups.groups[0].steps[0])
'Rᵗ_A ⟂ AB from ΣM_B(rod) = 0'
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...structure import AssurGroup, Joint
from ...vectors import cross, norm, perp
from ...vocabulary import EdgeKind
from ...words import Message, message
from ..names import ForceName, LinkNumber, PointNames
from .base import ForceSolver, GroupForces, split

__all__ = ["reactions"]


@dataclass(frozen=True, slots=True)
class _Side:
    """A side link of the triad: its inner pin (to the central link) and outer pin (to the
    known link), the outer pin's place ``p`` and the inner's ``q``, the unit vector ``e``
    from p to q and the tangential component ``tangential`` of the outer pin's reaction
    (arrays over the crank angles)."""

    link: str
    inner: Joint
    outer: Joint
    known: str
    p: np.ndarray
    q: np.ndarray
    e: np.ndarray
    tangential: np.ndarray


def reactions(solver: ForceSolver, group: AssurGroup) -> GroupForces:
    """The textbook reaction sequence, run by the force analysis (``solver``: see
    :class:`~planmethod.forces.groups.base.ForceSolver`).

    Rᵗ of each outer pin from the side link's moments about its inner pin; Assur's special
    point S — where the lines of two side links meet — eliminates their Rⁿ: ΣM_S of the group
    gives the third Rⁿ, the polygon the other two; the inner pins from the side links.
    """
    central = group.links[0]
    sides = [_side(solver, group, link) for link in group.links[1:]]
    normals, special = _normals(solver, group, sides)
    edges = [solver.edge(f"Rᵗ_{side.outer.point}", side.tangential, EdgeKind.COMPONENT,
                         side.link) for side in sides]
    edges += solver.known_edges(group.links)
    keys = []
    for side, n_value in zip(sides, normals, strict=True):
        rn = n_value[..., None] * side.e
        edges.append(solver.edge(f"Rⁿ_{side.outer.point}", rn, EdgeKind.COMPONENT, side.link))
        r = rn + side.tangential
        keys.append(solver.record(side.outer, group.links, side.link, side.known, side.p,
                                  r).key)
        keys.append(solver.record(side.inner, group.links, central, side.link, side.q,
                                  r + solver.wrench[side.link].force).key)
    return solver.result(group, _steps(sides, central), edges, keys, special)


def _side(solver: ForceSolver, group: AssurGroup, link: str) -> _Side:
    """A side link with its pins and the tangential component of its outer pin's reaction,
    from its moments about its inner pin."""
    central = group.links[0]
    inner = next(j for j in group.joints if link in j.links and central in j.links)
    outer = next(j for j in group.joints if link in j.links and j is not inner)
    p, q = solver.at(link, outer.point), solver.at(link, inner.point)
    e, length = split(q - p)
    t = solver.wrench[link].moment_about(q) / length
    return _Side(link, inner, outer, outer.other(link), p, q, e, t[..., None] * perp(e))


def _normals(solver: ForceSolver, group: AssurGroup, sides: list[_Side]
             ) -> tuple[list[np.ndarray], np.ndarray]:
    """The normal components of the three outer pins' reactions, by Assur's special point:
    where the lines of sides j and k meet, chosen angle by angle as the pair whose lines meet
    at the largest angle; and that point at each angle."""
    total = solver.total(group.links)
    sines = []
    for i in range(3):
        j, k = [m for m in range(3) if m != i]
        sines.append(np.abs(cross(sides[j].e, sides[k].e)))
    choice = np.argmax(np.stack(sines), axis=0)
    normals = [np.zeros(solver.count) for _ in range(3)]
    special = np.zeros((solver.count, 2))
    for i in range(3):
        mask = choice == i
        if not np.any(mask):
            continue
        j, k = [m for m in range(3) if m != i]
        pj, ej, pk, ek = sides[j].p, sides[j].e, sides[k].p, sides[k].e
        det = cross(ej, ek)
        solver.singular(np.where(mask, det, 1.0), 1.0, group.name,
                        message("the lines of the three side links are parallel"))
        s = pj + (cross(pk - pj, ek) / np.where(mask, det, 1.0))[..., None] * ej
        moment = total.moment_about(s)
        for side in sides:
            moment = moment + cross(side.p - s, side.tangential)
        arm = cross(sides[i].p - s, sides[i].e)
        scale = norm(sides[i].p - s) + norm(sides[i].q - sides[i].p)
        solver.singular(np.where(mask, arm, scale), scale, group.name,
                        message("the lines of the three side links meet in one point"))
        ni = -moment / np.where(mask, arm, 1.0)
        rest = -(total.force + sum(side.tangential for side in sides)
                 + ni[..., None] * sides[i].e)
        nj, nk = solver.solve2(np.where(mask[..., None], ej, np.array([1.0, 0.0])),
                               np.where(mask[..., None], ek, np.array([0.0, 1.0])), rest,
                               group.name, message("two side links are parallel"))
        for index, value in ((i, ni), (j, nj), (k, nk)):
            normals[index] = np.where(mask, value, normals[index])
        special = np.where(mask[..., None], s, special)
    return normals, special


def _steps(sides: list[_Side], central: str) -> tuple[Message, ...]:
    """The sequence's sentences."""
    steps = tuple(message("{force} ⟂ {segment} from ΣM_{pin}({link}) = 0",
                          force=ForceName(f"Rᵗ_{side.outer.point}"),
                          segment=PointNames(side.outer.point, side.inner.point),
                          pin=PointNames(side.inner.point),
                          link=LinkNumber(side.link)) for side in sides)
    return (
        *steps,
        message("Assur's special point S where the lines of two side links (through "
                "{points}) meet: ΣM_S of the group gives the third Rⁿ",
                points=[PointNames(side.outer.point) for side in sides]),
        message("force polygon of the group: ΣRᵗ + ΣF + ΣRⁿ = 0 gives the other two Rⁿ"),
        message("the inner pins from the equilibrium of each side link (link {link} is "
                "the central link)", link=LinkNumber(central)))
