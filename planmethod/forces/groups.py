"""Reactions group by group, from the last Assur group back to the drive link (d'Alembert).

This is the textbook kinetostatics (Jobborova et al.; Umbetkulov et al.): each group, loaded
by its known forces (weights, inertia forces and moments, external loads) and by the reactions
of the groups already solved, is statically determinate by itself. Each group kind has its own
sequence:

RRR (pins P1–Q–P2)
    Rᵗ at P1 ⟂ P1Q from ΣM_Q(L1) = 0, Rᵗ at P2 from ΣM_Q(L2) = 0; the group's force polygon
    Rᵗ1 + ΣF + Rᵗ2 + Rⁿ2 + Rⁿ1 = 0 with Rⁿ along the links gives Rⁿ1, Rⁿ2; the pin Q from the
    equilibrium of L1.
RRP (pins P1–Q, slide of L2)
    Rᵗ at P1 from ΣM_Q(L1) = 0; the polygon Rᵗ1 + ΣF + N + Rⁿ1 = 0 with N ⟂ the guide; the pin Q
    from L1; the reaction couple of the guide from ΣM(L2) = 0 about the slide point.
RPR (pin P1 on the block L1, slide of L1 on L2, pin P2)
    R1 along the guide from the block's projection on the guide; R1 ⟂ the guide from ΣM_P2 of
    the group; the normal force and couple in the slide from the block; R2 from L2's polygon.
PRP (slide of L1, pin Q, slide of L2)
    N1, N2 from the group's polygon (both ⟂ their guides); the pin Q from L2; each reaction
    couple from its link's moments.
RPP (pin P1 on L1, slide L1–L2, slide of L2)
    N2 from L2's projection on the inner guide; R1 from the group's polygon; the inner normal
    force from L1, its couple from ΣM(L1), the outer couple from ΣM(L2).
Class III triad (central link, three side links each with an inner and an outer pin)
    Rᵗ of each outer pin from the side link's moments about its inner pin; Assur's special point
    S — where the lines of two side links meet — eliminates their Rⁿ: ΣM_S of the group gives the
    third Rⁿ, the polygon the other two; the inner pins from the side links.
The drive link: ΣM about its pivot gives the balancing moment M_b, its polygon the pivot's
reaction.

A group whose force system is singular (its toggle, or a triad whose three side lines meet in a
point) raises :class:`~planmethod.errors.ForceError` at the first such crank angle. Class III and
IV groups of other shapes (prismatic pairs in a triad, tetrads) are solved by the group's own
linear system (the same equations, solved at once), and say so.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> from planmethod.forces.applied import applied_loads
>>> exercise = load_exercise("exercises/fourbar_forces.toml")
>>> motion = solve(exercise.mechanism, [0.0, 60.0, 150.0])
>>> solution = solve_by_groups(exercise.mechanism, motion.structure, motion.links,
...                            applied_loads(exercise.mechanism, motion.links))
>>> solution.balancing_moment.round(6)
array([-0.910965,  0.642055, -0.577299])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ForceError
from ..kinematics.state import LinkState, cross, norm, perp, unit_angle
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Joint, Structure
from .applied import AppliedLoads, Wrench
from .reactions import Reaction, pair_key

__all__ = ["GroupForces", "GroupSolution", "PolygonEdge", "solve_by_groups"]

#: |sin| of the angle between two lines of a force polygon below which it is singular
SINGULAR_SINE = 1e-10


@dataclass(frozen=True, slots=True)
class PolygonEdge:
    """One vector of a group's force polygon, in drawing order (head to tail).

    ``kind``: ``known`` (weight, inertia, load, friction), ``transmitted`` (a reaction from a
    group solved before), ``component`` (a part of an unknown reaction: Rᵗ, Rⁿ, N…), or
    ``reaction`` (a whole reaction found from the polygon's closure).
    """

    label: str
    vector: np.ndarray
    kind: str
    link: str


@dataclass(frozen=True, slots=True)
class GroupForces:
    """One group's solve: the steps as a course writes them, its force polygon (closing to
    zero), the reactions it found and, for a triad, Assur's special point used (N × 2)."""

    name: str
    kind: str
    links: tuple[str, ...]
    steps: tuple[str, ...]
    polygon: tuple[PolygonEdge, ...]
    reactions: tuple[str, ...]
    special_point: np.ndarray | None = None


@dataclass(frozen=True, slots=True)
class GroupSolution:
    """Reactions by pair key, the balancing moment (N·m, arrays over angles) and the groups in
    the order solved (last group first, the drive link last)."""

    reactions: Mapping[str, Reaction]
    balancing_moment: np.ndarray
    groups: tuple[GroupForces, ...]


def _unit(vector: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    length = norm(vector)
    return vector / length[..., None], length


def canonical(joint: Joint, group_links: Sequence[str]) -> tuple[str, str]:
    """(from, on) of a pair in the report (see :mod:`planmethod.forces.reactions`)."""
    if joint.kind == "P":
        return joint.slide.along, joint.slide.link
    first, second = joint.links
    if first in group_links and second in group_links:
        return first, second
    inside = first if first in group_links else second
    return joint.other(inside), inside


class _Solver:
    def __init__(self, mechanism: Mechanism, states: Mapping[str, LinkState],
                 applied: AppliedLoads, angles: np.ndarray | None) -> None:
        self.mechanism = mechanism
        self.states = states
        self.count = applied.count
        self.angles = angles
        links = [FRAME, *mechanism.moving_links]
        self.wrench = applied.wrenches(links)
        self.edges: dict[str, list[PolygonEdge]] = {link: [] for link in links}
        for item in applied.items:
            if item.force is not None and item.link in self.edges:
                self.edges[item.link].append(PolygonEdge(item.name, item.force, "known",
                                                         item.link))
        self.reactions: dict[str, Reaction] = {}

    # -- geometry --------------------------------------------------------------------------
    def at(self, link: str, point: str) -> np.ndarray:
        return self.states[link].place(self.mechanism.local(link, point))

    def guide(self, joint: Joint) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(d, n, slide point) of a prismatic pair: guide direction, its normal, the point."""
        slide = joint.slide
        d = unit_angle(self.states[slide.along].theta + slide.direction_rad)
        return d, perp(d), self.at(slide.link, slide.point)

    def singular(self, value: np.ndarray, scale, group: str, what: str) -> None:
        bad = ~(np.abs(value) > SINGULAR_SINE * scale)
        if np.any(bad):
            index = int(np.flatnonzero(bad)[0])
            angle = None if self.angles is None else float(self.angles[index])
            raise ForceError(f"the force system is singular: {what}", link=group, angle=angle)

    def solve2(self, e1, e2, w, group: str, what: str):
        """u1·e1 + u2·e2 = w (Cramer)."""
        det = cross(e1, e2)
        self.singular(det, norm(e1) * norm(e2), group, what)
        return cross(w, e2) / det, cross(e1, w) / det

    # -- recording ----------------------------------------------------------------------------
    def record(self, joint: Joint, group_links, target: str, source: str, point: np.ndarray,
               force: np.ndarray, moment: np.ndarray | None = None) -> Reaction:
        """Store the reaction on ``target`` from ``source``; pass its opposite to ``source`` if
        that link is solved later (outside the group)."""
        key = pair_key(self.mechanism, joint.kind, joint.point, *canonical(joint, group_links),
                       joint.slide)
        found = Reaction(key, joint.kind, source, target, point, force,
                         None if joint.kind == "R" else moment, joint.slide)
        self.reactions[key] = found.oriented(*canonical(joint, group_links))
        if source not in group_links:
            self.wrench[source] = self.wrench[source] - found.wrench()
            self.edges[source].append(PolygonEdge(f"R_{key}", -force, "transmitted", source))
        return found

    def known_edges(self, links) -> list[PolygonEdge]:
        return [edge for link in links for edge in self.edges[link]]

    # -- the groups ---------------------------------------------------------------------------
    def group(self, group: AssurGroup) -> GroupForces:
        kind = group.kind
        if kind in ("RRR", "RRP", "RPR", "PRP", "RPP"):
            return getattr(self, f"_{kind.lower()}")(group)
        if kind == "triad" and _plain_triad(group):
            return self._triad(group)
        return self._linear(group)

    def _rrr(self, group: AssurGroup) -> GroupForces:
        ext1, internal, ext2 = group.joints
        l1, l2 = group.links
        k1, k2 = ext1.other(l1), ext2.other(l2)
        p1, q, p2 = self.at(l1, ext1.point), self.at(l1, internal.point), self.at(l2, ext2.point)
        w1, w2 = self.wrench[l1], self.wrench[l2]
        e1, a = _unit(q - p1)
        e2, b = _unit(q - p2)
        t1 = w1.moment_about(q) / a
        t2 = w2.moment_about(q) / b
        rt1, rt2 = t1[..., None] * perp(e1), t2[..., None] * perp(e2)
        known = w1.force + w2.force
        n1, n2 = self.solve2(e1, e2, -(rt1 + rt2 + known), group.name,
                             f"{l1} and {l2} are in line (toggle)")
        rn1, rn2 = n1[..., None] * e1, n2[..., None] * e2
        r1, r2 = rn1 + rt1, rn2 + rt2
        edges = [PolygonEdge(f"Rᵗ_{ext1.point}", rt1, "component", l1),
                 *self.known_edges((l1, l2)),
                 PolygonEdge(f"Rᵗ_{ext2.point}", rt2, "component", l2),
                 PolygonEdge(f"Rⁿ_{ext2.point}", rn2, "component", l2),
                 PolygonEdge(f"Rⁿ_{ext1.point}", rn1, "component", l1)]
        keys = [self.record(ext1, group.links, l1, k1, p1, r1).key,
                self.record(ext2, group.links, l2, k2, p2, r2).key,
                self.record(internal, group.links, l2, l1, q, r1 + w1.force).key]
        P1, Q, P2 = ext1.point, internal.point, ext2.point
        steps = (f"Rᵗ_{P1} ⟂ {P1}{Q} from ΣM_{Q}({l1}) = 0: Rᵗ_{P1} = ΣM_{Q}/{P1}{Q}",
                 f"Rᵗ_{P2} ⟂ {P2}{Q} from ΣM_{Q}({l2}) = 0: Rᵗ_{P2} = ΣM_{Q}/{P2}{Q}",
                 f"force polygon of the group: Rᵗ_{P1} + ΣF + Rᵗ_{P2} + Rⁿ_{P2} + Rⁿ_{P1} = 0, "
                 f"Rⁿ_{P1} ∥ {P1}{Q}, Rⁿ_{P2} ∥ {P2}{Q}",
                 f"R_{Q} from the equilibrium of {l1}: R_{Q} = R_{P1} + ΣF({l1})")
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def _rrp(self, group: AssurGroup) -> GroupForces:
        ext1, internal, ext2 = group.joints
        l1, l2 = group.links
        k1, k2 = ext1.other(l1), ext2.other(l2)
        p1, q = self.at(l1, ext1.point), self.at(l1, internal.point)
        _, n, ps = self.guide(ext2)
        w1, w2 = self.wrench[l1], self.wrench[l2]
        e1, a = _unit(q - p1)
        t1 = w1.moment_about(q) / a
        rt1 = t1[..., None] * perp(e1)
        n1, normal = self.solve2(e1, n, -(rt1 + w1.force + w2.force), group.name,
                                 f"{l1} is perpendicular to the guide of {ext2.slide.key}")
        rn1, big_n = n1[..., None] * e1, normal[..., None] * n
        r1 = rn1 + rt1
        r_q = r1 + w1.force
        couple = -(w2.moment_about(ps) + cross(q - ps, r_q))
        edges = [PolygonEdge(f"Rᵗ_{ext1.point}", rt1, "component", l1),
                 *self.known_edges((l1, l2)),
                 PolygonEdge(f"N_{ext2.slide.key}", big_n, "component", l2),
                 PolygonEdge(f"Rⁿ_{ext1.point}", rn1, "component", l1)]
        keys = [self.record(ext1, group.links, l1, k1, p1, r1).key,
                self.record(ext2, group.links, l2, k2, ps, big_n, couple).key,
                self.record(internal, group.links, l2, l1, q, r_q).key]
        P1, Q = ext1.point, internal.point
        steps = (f"Rᵗ_{P1} ⟂ {P1}{Q} from ΣM_{Q}({l1}) = 0",
                 f"force polygon: Rᵗ_{P1} + ΣF + N + Rⁿ_{P1} = 0, N ⟂ the guide of "
                 f"{ext2.slide.key}, Rⁿ_{P1} ∥ {P1}{Q}",
                 f"R_{Q} from the equilibrium of {l1}",
                 f"the reaction couple of {ext2.slide.key} from ΣM({l2}) = 0 about "
                 f"{ext2.slide.point}")
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def _rpr(self, group: AssurGroup) -> GroupForces:
        ext1, internal, ext2 = group.joints
        l1, l2 = group.links          # l1 is the block (the slide's link), l2 its guide
        k1, k2 = ext1.other(l1), ext2.other(l2)
        p1, p2 = self.at(l1, ext1.point), self.at(l2, ext2.point)
        d, n, ps = self.guide(internal)
        w1, w2 = self.wrench[l1], self.wrench[l2]
        along = -np.einsum("...i,...i->...", w1.force, d)
        arm = p1 - p2
        lever = cross(arm, n)
        self.singular(lever, norm(arm) + 1e-300, group.name,
                      f"{ext1.point} lies on the normal to the guide through {ext2.point}")
        across = -((w1 + w2).moment_about(p2) + along * cross(arm, d)) / lever
        r_along, r_across = along[..., None] * d, across[..., None] * n
        r1 = r_along + r_across
        inner = -(r1 + w1.force)                       # on the block from the guide
        couple = -(w1.moment_about(ps) + cross(p1 - ps, r1))
        r2 = inner - w2.force
        edges = [PolygonEdge(f"R∥_{ext1.point}", r_along, "component", l1),
                 PolygonEdge(f"R⊥_{ext1.point}", r_across, "component", l1),
                 *self.known_edges((l1, l2)),
                 PolygonEdge(f"R_{ext2.point}", r2, "reaction", l2)]
        keys = [self.record(ext1, group.links, l1, k1, p1, r1).key,
                self.record(internal, group.links, l1, l2, ps, inner, couple).key,
                self.record(ext2, group.links, l2, k2, p2, r2).key]
        P1, P2 = ext1.point, ext2.point
        steps = (f"R_{P1} along the guide from the block {l1}: projection on the guide",
                 f"R_{P1} ⟂ the guide from ΣM_{P2} of the group = 0",
                 f"the normal force and couple of {internal.slide.key} from the block {l1}",
                 f"R_{P2} from the force polygon of {l2}")
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def _prp(self, group: AssurGroup) -> GroupForces:
        ext1, internal, ext2 = group.joints
        l1, l2 = group.links
        k1, k2 = ext1.other(l1), ext2.other(l2)
        q = self.at(l1, internal.point)
        _, n1, ps1 = self.guide(ext1)
        _, n2, ps2 = self.guide(ext2)
        w1, w2 = self.wrench[l1], self.wrench[l2]
        big1, big2 = self.solve2(n1, n2, -(w1.force + w2.force), group.name,
                                 f"the guides of {ext1.slide.key} and {ext2.slide.key} are "
                                 "parallel")
        f1, f2 = big1[..., None] * n1, big2[..., None] * n2
        r_q = -(w2.force + f2)                         # on l2 from l1
        c1 = -(w1.moment_about(ps1) + cross(q - ps1, -r_q))
        c2 = -(w2.moment_about(ps2) + cross(q - ps2, r_q))
        edges = [*self.known_edges((l1, l2)),
                 PolygonEdge(f"N_{ext2.slide.key}", f2, "component", l2),
                 PolygonEdge(f"N_{ext1.slide.key}", f1, "component", l1)]
        keys = [self.record(ext1, group.links, l1, k1, ps1, f1, c1).key,
                self.record(ext2, group.links, l2, k2, ps2, f2, c2).key,
                self.record(internal, group.links, l2, l1, q, r_q).key]
        steps = ("force polygon of the group: ΣF + N2 + N1 = 0, each N ⟂ its guide",
                 f"R_{internal.point} from the equilibrium of {l2}",
                 "each reaction couple from its link's moments about its slide point")
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def _rpp(self, group: AssurGroup) -> GroupForces:
        ext1, internal, ext2 = group.joints
        l1, l2 = group.links
        k1, k2 = ext1.other(l1), ext2.other(l2)
        p1 = self.at(l1, ext1.point)
        di, _, psi = self.guide(internal)
        _, n2, ps2 = self.guide(ext2)
        w1, w2 = self.wrench[l1], self.wrench[l2]
        across = np.einsum("...i,...i->...", n2, di)
        self.singular(across, 1.0, group.name,
                      f"the guides of {internal.slide.key} and {ext2.slide.key} are parallel")
        big2 = -np.einsum("...i,...i->...", w2.force, di) / across
        f2 = big2[..., None] * n2
        r1 = -(w1.force + w2.force + f2)
        inner = -(r1 + w1.force)                       # on l1 from l2
        c_inner = -(w1.moment_about(psi) + cross(p1 - psi, r1))
        c2 = -(w2.moment_about(ps2) + cross(psi - ps2, -inner) - c_inner)
        edges = [PolygonEdge(f"N_{ext2.slide.key}", f2, "component", l2),
                 *self.known_edges((l1, l2)),
                 PolygonEdge(f"R_{ext1.point}", r1, "reaction", l1)]
        keys = [self.record(ext1, group.links, l1, k1, p1, r1).key,
                self.record(internal, group.links, l1, l2, psi, inner, c_inner).key,
                self.record(ext2, group.links, l2, k2, ps2, f2, c2).key]
        steps = (f"N of {ext2.slide.key} from {l2}'s projection on the guide of "
                 f"{internal.slide.key}",
                 f"R_{ext1.point} from the force polygon of the group",
                 f"the normal force and couple of {internal.slide.key} from {l1}",
                 f"the couple of {ext2.slide.key} from ΣM({l2}) = 0")
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def _triad(self, group: AssurGroup) -> GroupForces:
        central = group.links[0]
        sides = []
        for link in group.links[1:]:
            inner = next(j for j in group.joints if link in j.links and central in j.links)
            outer = next(j for j in group.joints if link in j.links and j is not inner)
            known = outer.other(link)
            p, q = self.at(link, outer.point), self.at(link, inner.point)
            e, length = _unit(q - p)
            t = self.wrench[link].moment_about(q) / length
            sides.append((link, inner, outer, known, p, q, e, t[..., None] * perp(e)))
        total = Wrench.zero(self.count)
        for link in group.links:
            total = total + self.wrench[link]
        # Assur's special point: where the lines of sides j and k meet; choose, angle by angle,
        # the pair whose lines meet at the largest angle
        sines = []
        for i in range(3):
            j, k = [m for m in range(3) if m != i]
            sines.append(np.abs(cross(sides[j][6], sides[k][6])))
        choice = np.argmax(np.stack(sines), axis=0)
        normals = [np.zeros(self.count) for _ in range(3)]
        special = np.zeros((self.count, 2))
        for i in range(3):
            mask = choice == i
            if not np.any(mask):
                continue
            j, k = [m for m in range(3) if m != i]
            pj, ej, pk, ek = sides[j][4], sides[j][6], sides[k][4], sides[k][6]
            det = cross(ej, ek)
            self.singular(np.where(mask, det, 1.0), 1.0, group.name,
                          "the lines of the three side links are parallel")
            s = pj + (cross(pk - pj, ek) / np.where(mask, det, 1.0))[..., None] * ej
            moment = total.moment_about(s)
            for side in sides:
                moment = moment + cross(side[4] - s, side[7])
            arm = cross(sides[i][4] - s, sides[i][6])
            scale = norm(sides[i][4] - s) + norm(sides[i][5] - sides[i][4])
            self.singular(np.where(mask, arm, scale), scale, group.name,
                          "the lines of the three side links meet in one point")
            ni = -moment / np.where(mask, arm, 1.0)
            rest = -(total.force + sum(side[7] for side in sides) + ni[..., None] * sides[i][6])
            nj, nk = self.solve2(np.where(mask[..., None], ej, _E1),
                                 np.where(mask[..., None], ek, _E2), rest, group.name,
                                 "two side links are parallel")
            for index, value in ((i, ni), (j, nj), (k, nk)):
                normals[index] = np.where(mask, value, normals[index])
            special = np.where(mask[..., None], s, special)
        edges = [PolygonEdge(f"Rᵗ_{side[2].point}", side[7], "component", side[0])
                 for side in sides]
        edges += self.known_edges(group.links)
        keys = []
        for (link, inner, outer, known, p, q, e, rt), n_value in zip(sides, normals,
                                                                      strict=True):
            rn = n_value[..., None] * e
            edges.append(PolygonEdge(f"Rⁿ_{outer.point}", rn, "component", link))
            r = rn + rt
            keys.append(self.record(outer, group.links, link, known, p, r).key)
            keys.append(self.record(inner, group.links, central, link, q,
                                    r + self.wrench[link].force).key)
        names = [side[2].point for side in sides]
        steps = tuple(f"Rᵗ_{side[2].point} ⟂ {side[2].point}{side[1].point} from "
                      f"ΣM_{side[1].point}({side[0]}) = 0" for side in sides)
        steps += (
            f"Assur's special point S where the lines of two side links (through "
            f"{', '.join(names)}) meet: ΣM_S of the group gives the third Rⁿ",
            "force polygon of the group: ΣRᵗ + ΣF + ΣRⁿ = 0 gives the other two Rⁿ",
            f"the inner pins from the equilibrium of each side link ({central} is the central "
            "link)")
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys), special)

    def _linear(self, group: AssurGroup) -> GroupForces:
        """A higher group of another shape: its 3k equilibrium equations solved at once."""
        from .system import group_linear_reactions

        found = group_linear_reactions(self.mechanism, group, self.states, self.wrench,
                                       self.angles)
        keys = []
        for joint, (target, source, point, force, moment) in found:
            keys.append(self.record(joint, group.links, target, source, point, force,
                                    moment).key)
        edges = list(self.known_edges(group.links))
        for key in keys:
            reaction = self.reactions[key]
            outside = reaction.source not in group.links or reaction.target not in group.links
            if outside:
                vector = reaction.force if reaction.target in group.links else -reaction.force
                edges.append(PolygonEdge(f"R_{key}", vector, "reaction",
                                         reaction.target if reaction.target in group.links
                                         else reaction.source))
        steps = (f"{group.kind} of links {', '.join(group.links)}: its 3·{len(group.links)} "
                 "equilibrium equations solved at once (the group's linear system)",)
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def driver(self) -> tuple[np.ndarray, GroupForces]:
        drive = self.mechanism.drive
        link = drive.link
        pivot = self.at(link, drive.pivot)
        w = self.wrench[link]
        balancing = -w.moment_about(pivot) + 0.0  # no negative zero
        reaction = -w.force
        joint = Joint("R", drive.pivot, (link, FRAME))
        edges = [*self.known_edges((link,)),
                 PolygonEdge(f"R_{drive.pivot}", reaction, "reaction", link)]
        key = self.record(joint, (link,), link, FRAME, pivot, reaction).key
        steps = (f"M_b from ΣM_{drive.pivot}({link}) = 0",
                 f"R_{drive.pivot} from the force polygon of {link}")
        return balancing, GroupForces(link, "drive", (link,), steps, tuple(edges), (key,))


_E1 = np.array([1.0, 0.0])
_E2 = np.array([0.0, 1.0])


def _plain_triad(group: AssurGroup) -> bool:
    """A triad of revolute pairs whose central link carries the three inner pins and whose
    side links each have one outer pin."""
    if any(joint.kind != "R" for joint in group.joints):
        return False
    central = group.links[0]
    for link in group.links[1:]:
        mine = [j for j in group.joints if link in j.links]
        inner = [j for j in mine if central in j.links]
        if len(mine) != 2 or len(inner) != 1:
            return False
    return True


def solve_by_groups(mechanism: Mechanism, structure: Structure,
                    states: Mapping[str, LinkState], applied: AppliedLoads, *,
                    angles: np.ndarray | None = None) -> GroupSolution:
    """Reactions in every pair and the balancing moment, group by group from the last.

    Parameters
    ----------
    mechanism, structure
        The model and its Assur groups.
    states
        Exact motion of every link (``Motion.links``, accelerations solved).
    applied
        The known forces (:func:`~planmethod.forces.applied.applied_loads`), friction included.
    angles
        Crank angles (deg), for error messages.

    Raises
    ------
    ForceError
        If a group's force system is singular at some crank angle.
    """
    solver = _Solver(mechanism, states, applied, angles)
    solved = []
    for group in reversed(structure.groups):
        solved.append(solver.group(group))
    balancing, drive = solver.driver()
    solved.append(drive)
    order = list(drive.reactions)  # the report lists the pairs in build order
    for group in structure.groups:
        order += [pair_key(mechanism, joint.kind, joint.point, *canonical(joint, group.links),
                           joint.slide) for joint in group.joints]
    reactions = {key: solver.reactions[key] for key in order}
    return GroupSolution(reactions, balancing, tuple(solved))
