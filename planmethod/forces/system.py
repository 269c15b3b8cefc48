"""The whole mechanism's force system in one linear solve (the D·g = b of Umbetkulov et al.).

Every moving link i has coordinates q_i = (x_i, y_i, θ_i); the pairs give the constraint
equations Φ(q) = 0 (:mod:`planmethod.kinematics.constraints`) and the drive adds one more,
θ_drive − φ(t) = 0. d'Alembert's principle for all links at once reads

    Φ_qᵀ·λ = Q,

where Q holds, per link, the resultant of the known forces (weights, inertia, loads) and its
moment about the link's origin. The constraint force on link i from pair c is −Φ_c,q_iᵀ·λ_c,
and the drive constraint's multiplier gives the balancing moment M_b = −λ_drive. The matrix is
square (3n × 3n for W = 1); a singular one is a :class:`~planmethod.errors.ForceError`.

Nothing of the group-by-group method is used here, so the two are an independent pair of
answers to the same question.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> from planmethod.forces.applied import applied_loads
>>> exercise = load_exercise("exercises/fourbar_forces.toml")
>>> motion = solve(exercise.mechanism, [0.0, 60.0, 150.0])
>>> found = solve_whole_system(exercise.mechanism, motion.structure, motion.links,
...                            applied_loads(exercise.mechanism, motion.links))
>>> found.balancing_moment.round(6)
array([-0.910965,  0.642055, -0.577299])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ForceError
from ..kinematics.constraints import Constraint, ConstraintSystem
from ..kinematics.state import LinkState
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Joint, Structure
from ..vectors import cross
from ..vocabulary import PairKind
from ..words import Message, message
from .applied import AppliedLoads, Wrench
from .reactions import Reaction, canonical, pair_key

__all__ = ["SystemSolution", "group_linear_reactions", "solve_whole_system"]

#: reciprocal condition number below which the force system counts as singular
SINGULAR_RCOND = 1e-13


@dataclass(frozen=True, slots=True)
class SystemSolution:
    """Reactions by pair key and the balancing moment from the whole-mechanism solve, with the
    size of the system (``equations``) and the reciprocal condition number per angle."""

    reactions: Mapping[str, Reaction]
    balancing_moment: np.ndarray
    equations: int
    rcond: np.ndarray


def _constraint(joint: Joint) -> Constraint:
    if joint.kind is PairKind.PRISMATIC:
        slide = joint.slide
        return Constraint(PairKind.PRISMATIC, slide.point, slide.link, slide.along, slide)
    return Constraint(PairKind.REVOLUTE, joint.point, joint.links[0], joint.links[1])


def _generalized(wrench: Wrench, state: LinkState) -> np.ndarray:
    """(Fx, Fy, M about the link's origin) of a wrench, shape (N, 3)."""
    moment = wrench.moment_about(state.origin)
    return np.concatenate((wrench.force, moment[..., None]), axis=-1)


def _solve(mechanism: Mechanism, joints: Sequence[Joint], unknown: Sequence[str],
           states: Mapping[str, LinkState], wrenches: Mapping[str, Wrench],
           angles, where: Message | str, link: str, drive: bool):
    system = ConstraintSystem(mechanism, tuple(_constraint(j) for j in joints), tuple(unknown))
    matrix, _ = system.jacobian(states)
    count = matrix.shape[0]
    if drive:
        row = np.zeros((count, 1, matrix.shape[2]))
        row[:, 0, system.column(mechanism.drive.link) + 2] = 1.0
        matrix = np.concatenate((matrix, row), axis=1)
    rows, cols = matrix.shape[1:]
    if rows != cols:
        raise ForceError(message("the force system of {system} has {rows} equations for "
                                 "{columns} unknowns", system=where, rows=rows, columns=cols),
                         link=link)
    load = np.concatenate([_generalized(wrenches[link], states[link]) for link in unknown],
                          axis=-1)
    transposed = np.swapaxes(matrix, 1, 2)
    singular_values = np.linalg.svd(transposed, compute_uv=False)
    rcond = singular_values[:, -1] / singular_values[:, 0]
    bad = ~(rcond > SINGULAR_RCOND)
    if np.any(bad):
        index = int(np.flatnonzero(bad)[0])
        angle = None if angles is None else float(np.asarray(angles)[index])
        raise ForceError(message("the force system of {system} is singular (reciprocal "
                                 "condition number {rcond:.3g}): the mechanism is in a toggle "
                                 "position", system=where, rcond=float(rcond[index])),
                         link=link, angle=angle)
    multipliers = np.linalg.solve(transposed, load[..., None])[..., 0]
    return system, matrix, multipliers, rcond


def _reaction_on(mechanism, system, matrix, multipliers, index: int, link: str,
                 states) -> Wrench:
    """The constraint wrench of pair ``index`` on ``link`` (a moving link)."""
    column = system.column(link)
    block = matrix[:, 2 * index:2 * index + 2, column:column + 3]
    generalized = -np.einsum("nrc,nr->nc", block, multipliers[:, 2 * index:2 * index + 2])
    force = generalized[..., :2]
    moment = generalized[..., 2] + cross(states[link].origin, force)
    return Wrench(force, moment)


def _as_reaction(mechanism, joint: Joint, source: str, target: str, system, matrix,
                 multipliers, index, states, key) -> Reaction:
    moving = target if target != FRAME else source
    wrench = _reaction_on(mechanism, system, matrix, multipliers, index, moving, states)
    if joint.kind is PairKind.PRISMATIC:
        slide = joint.slide
        point = states[slide.link].place(mechanism.local(slide.link, slide.point))
    else:
        point = states[moving].place(mechanism.local(moving, joint.point))
    couple = wrench.moment_about(point)
    prismatic = joint.kind is PairKind.PRISMATIC
    found = Reaction(key, joint.kind, source if moving == target else target, moving, point,
                     wrench.force, couple if prismatic else None, joint.slide)
    return found.oriented(source, target)


def _pairs(mechanism: Mechanism, structure: Structure):
    """Every pair with its (from, on) orientation, as the group method keys them."""
    pairs = []
    for group in structure.groups:
        for joint in group.joints:
            pairs.append((joint, canonical(joint, group.links)))
    drive = mechanism.drive
    pairs.append((Joint(PairKind.REVOLUTE, drive.pivot, (drive.link, FRAME)), (FRAME, drive.link)))
    return pairs


def solve_whole_system(mechanism: Mechanism, structure: Structure,
                       states: Mapping[str, LinkState], applied: AppliedLoads, *,
                       angles=None) -> SystemSolution:
    """All reactions and the balancing moment from one linear solve Φ_qᵀ·λ = Q.

    Raises
    ------
    ForceError
        If the system is singular at some crank angle.
    """
    unknown = [link for link in mechanism.moving_links if link in states]
    wrenches = applied.wrenches(unknown)
    pairs = _pairs(mechanism, structure)
    joints = [joint for joint, _ in pairs]
    system, matrix, multipliers, rcond = _solve(mechanism, joints, unknown, states, wrenches,
                                                angles, message("the whole mechanism"),
                                                ", ".join(unknown), drive=True)
    reactions = {}
    for index, (joint, (source, target)) in enumerate(pairs):
        key = pair_key(mechanism, joint.kind, joint.point, source, target, joint.slide)
        reactions[key] = _as_reaction(mechanism, joint, source, target, system, matrix,
                                      multipliers, index, states, key)
    balancing = -multipliers[:, -1]
    return SystemSolution(reactions, balancing, matrix.shape[1], rcond)


def group_linear_reactions(mechanism: Mechanism, group: AssurGroup,
                           states: Mapping[str, LinkState], wrenches: Mapping[str, Wrench],
                           angles=None):
    """Reactions of one group from its own 3k equations: ``[(joint, (target, source, point,
    force, moment))]`` with each force on the group's link (or the pair's second link)."""
    system, matrix, multipliers, _ = _solve(mechanism, group.joints, group.links, states,
                                            wrenches, angles, group.name, group.name,
                                            drive=False)
    out = []
    for index, joint in enumerate(group.joints):
        source, target = canonical(joint, group.links)
        key = pair_key(mechanism, joint.kind, joint.point, source, target, joint.slide)
        found = _as_reaction(mechanism, joint, source, target, system, matrix, multipliers,
                             index, states, key)
        inside = found if found.target in group.links else found.reversed()
        out.append((joint, (inside.target, inside.source, inside.point, inside.force,
                            inside.moment)))
    return out
