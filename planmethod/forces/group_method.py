"""Reactions group by group, from the last Assur group back to the drive link (d'Alembert).

This is the textbook kinetostatics (Jobborova et al.; Umbetkulov et al.): each group, loaded
by its known forces (weights, inertia forces and moments, external loads) and by the reactions
of the groups already solved, is statically determinate by itself. Each group kind has its own
sequence, its forces face (``reactions`` of :mod:`planmethod.forces.groups.rrr` …,
:mod:`~planmethod.forces.groups.triad`: Assur's special point); this module is the solver those
sequences run on (:class:`~planmethod.forces.groups.base.ForceSolver`). A kind without a
textbook sequence (:mod:`~planmethod.forces.groups.higher`) is solved by its linear system.
Last the drive link: ΣM about its pivot gives the balancing moment M_b, its polygon the
pivot's reaction.

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

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import ForceError
from ..kinematics.state import LinkState
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Joint, Structure
from ..vectors import cross, norm, perp, unit_angle
from ..vocabulary import EdgeKind, GroupKind, PairKind, group_kind_words
from ..words import Message, message
from .applied import AppliedLoads, Wrench
from .groups import reactions_of
from .groups.base import GroupForces, PolygonEdge
from .names import BALANCING_MOMENT, ForceName, LinkNumber, PointNames
from .reactions import Reaction, canonical, pair_key
from .system import group_linear_reactions

__all__ = ["GroupForces", "GroupSolution", "PolygonEdge", "solve_by_groups"]

#: |sin| of the angle between two lines of a force polygon below which it is singular
SINGULAR_SINE = 1e-10


@dataclass(frozen=True, slots=True)
class GroupSolution:
    """Reactions by pair key, the balancing moment (N·m, arrays over angles) and the groups in
    the order solved (last group first, the drive link last)."""

    reactions: Mapping[str, Reaction]
    balancing_moment: np.ndarray
    groups: tuple[GroupForces, ...]


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
                self.edges[item.link].append(PolygonEdge(item.name, item.force, EdgeKind.KNOWN,
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

    def singular(self, value: np.ndarray, scale, group: str, what: Message) -> None:
        bad = ~(np.abs(value) > SINGULAR_SINE * scale)
        if np.any(bad):
            index = int(np.flatnonzero(bad)[0])
            angle = None if self.angles is None else float(self.angles[index])
            raise ForceError(message("the force system is singular: {why}", why=what),
                             link=group, angle=angle)

    def solve2(self, e1, e2, w, group: str, what: Message):
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
                         None if joint.kind is PairKind.REVOLUTE else moment, joint.slide)
        self.reactions[key] = found.oriented(*canonical(joint, group_links))
        if source not in group_links:
            self.wrench[source] = self.wrench[source] - found.wrench()
            self.edges[source].append(PolygonEdge(f"R_{key}", -force, EdgeKind.TRANSMITTED, source))
        return found

    def known_edges(self, links) -> list[PolygonEdge]:
        return [edge for link in links for edge in self.edges[link]]

    def edge(self, label: str, vector: np.ndarray, kind: EdgeKind, link: str) -> PolygonEdge:
        return PolygonEdge(label, vector, kind, link)

    def total(self, links) -> Wrench:
        """The sum of the links' known wrenches."""
        total = Wrench.zero(self.count)
        for link in links:
            total = total + self.wrench[link]
        return total

    def result(self, group: AssurGroup, steps, edges, keys, special=None) -> GroupForces:
        return GroupForces(group.name, group.kind, group.links, tuple(steps), tuple(edges),
                           tuple(keys), special)

    # -- the groups ---------------------------------------------------------------------------
    def group(self, group: AssurGroup) -> GroupForces:
        """The group's reactions by its kind's forces face (:mod:`planmethod.forces.groups`)."""
        return reactions_of(group)(self, group)

    def linear(self, group: AssurGroup) -> GroupForces:
        """A group's 3k equilibrium equations solved at once (a higher group of another
        shape)."""
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
                edges.append(PolygonEdge(f"R_{key}", vector, EdgeKind.REACTION,
                                         reaction.target if reaction.target in group.links
                                         else reaction.source))
        steps = (message("{kind} of links {links}: its 3·{count} equilibrium equations solved "
                         "at once (the group's linear system)", kind=group_kind_words(group.kind),
                         links=list(group.links), count=len(group.links)),)
        return GroupForces(group.name, group.kind, group.links, steps, tuple(edges),
                           tuple(keys))

    def driver(self) -> tuple[np.ndarray, GroupForces]:
        drive = self.mechanism.drive
        link = drive.link
        pivot = self.at(link, drive.pivot)
        w = self.wrench[link]
        balancing = -w.moment_about(pivot) + 0.0  # no negative zero
        reaction = -w.force
        joint = Joint(PairKind.REVOLUTE, drive.pivot, (link, FRAME))
        edges = [*self.known_edges((link,)),
                 PolygonEdge(f"R_{drive.pivot}", reaction, EdgeKind.REACTION, link)]
        key = self.record(joint, (link,), link, FRAME, pivot, reaction).key
        steps = (message("{moment} from ΣM_{pivot}({link}) = 0", moment=BALANCING_MOMENT,
                         pivot=PointNames(drive.pivot), link=LinkNumber(link)),
                 message("{reaction} from the force polygon of link {link}",
                         reaction=ForceName(f"R_{drive.pivot}"), link=LinkNumber(link)))
        return balancing, GroupForces(link, GroupKind.DRIVE, (link,), steps, tuple(edges), (key,))


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
