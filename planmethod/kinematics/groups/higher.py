"""Class III and IV groups: positions by Newton, continued from ``drive.angle``; exact velocities
and accelerations by linear solves.

A higher group has no closed form. Its unknown pose coordinates q satisfy the pairs' equations
Φ(q) = 0; this module holds what every such group shares, over a :class:`System` (the group's
equations), and the general system of any shape — a triad with prismatic pairs, a tetrad — on
the generic constraint equations (:mod:`planmethod.kinematics.constraints`). The plain Assur
triad of revolute pairs has a smaller system of its own (:mod:`.triad`).

**Assemblies and the branch.** At ``drive.angle`` every distinct assembly is found (by the
system's own search) and sorted; the group takes the one nearest (least squares) to its sketched
points — reason ``sketch`` — or, with no sketched point, the first one — reason ``default``
(``unique`` if only one exists). The branch's ``sign`` is that assembly's number (1, 2, …).

**Continuation, once per mechanism.** From ``drive.angle`` a path of nodes every
:data:`STEP_DEG` is marched outward (along the crank angle as a number, not modulo 360°) as far
as any solve has needed, and kept with the model: at each node q, and its first and second
derivatives with respect to the crank angle (exact linear solves at unit crank speed). A step
whose Newton solve fails, or whose solution moves further from its prediction than the step
allows (the sign of a jump to another assembly), is halved, down to :data:`MIN_STEP_DEG`; then
it is an error — :class:`~planmethod.errors.ConvergenceError` (how far from a solution, where)
or :class:`~planmethod.errors.BranchJumpError` — never a silent flip; where the group's
Jacobian is nearly singular there, it has reached its limit (toggle) position: a
:class:`~planmethod.errors.ToggleError`.

**Any crank angles at once.** Each angle is predicted from its nearest node by the node's
second-order Taylor expansion and corrected by Newton's method on all angles together
(vectorised); the same jump check applies; an angle that fails it is marched to from its node
in smaller steps. A system written in the arithmetic of :mod:`planmethod.kinematics.algebra`
(the plain triad) is traced into the mechanism's program: the prediction, one Newton step and
the checks that it converged and did not jump run as straight-line code, and a chunk of angles
where a check fails is evaluated again by the iterating path above. Velocities and
accelerations solve Φ_q·q̇ = −Φ_known·q̇_known and Φ_q·q̈ = γ − Φ_known·q̈_known exactly.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/conveyor_sixbar.toml").mechanism, 135.0)
>>> motion.at(0).position("D").round(6)
array([ 0.793156, -0.183194])
>>> motion.branches[0].reason, motion.branches[0].count
('sketch', 4)
"""

from __future__ import annotations

import dataclasses
import math
import threading
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import AssemblyError, BranchJumpError, ConvergenceError, StructureError, ToggleError
from ...model import FRAME, Mechanism
from ...structure import AssurGroup
from ...vectors import rotate
from ...vocabulary import GroupKind, PairKind
from ...words.message import message, plural
from ..algebra import Body, maximum, minimum, sqrt
from ..constraints import ConstraintSystem
from ..state import LinkState
from ..tracing import Redo, Traced
from .base import Branch, GroupInputs, KindModel, SolvedGroup

__all__ = ["ITERATIONS", "KINDS", "MIN_STEP_DEG", "RESIDUAL", "STEP_DEG", "HigherBranch",
           "System", "accept", "choose", "choose_with", "evaluate", "higher_evaluate"]

KINDS = (GroupKind.TRIAD, GroupKind.TETRAD)
PRIORITY = 0

#: the spacing of the continuation's nodes (deg of crank angle)
STEP_DEG = 1.0
#: a step halved below this is given up (deg)
MIN_STEP_DEG = 1e-6
#: Newton iterations before a solve counts as failed
ITERATIONS = 30
#: residual |Φ| accepted, relative to the group's size
RESIDUAL = 1e-12
#: a residual below this share of the accepted one needs no polishing step (the next would only
#: remove rounding): what the straight-line evaluation of one Newton step must reach
POLISHED = 1e-3
#: the Jacobian's normalised determinant below which the group is in its toggle position …
SINGULAR = 1e-12
#: … and below which a continuation that cannot go on has reached a limit position
LIMIT = 1e-4


@dataclass(frozen=True, slots=True)
class HigherBranch(Branch):
    """A higher group's branch: ``sign`` is the assembly's number among ``count`` found at
    ``drive.angle``."""

    count: int = 1


def accept(length: float, q: np.ndarray, converged: np.ndarray, prediction: np.ndarray,
           expected: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Whether each corrected solution is the continuation of its prediction: it converged, and
    it moved from the prediction by less than the step allows (more is the sign of a jump to
    another assembly). Returns (accepted, how far it moved)."""
    jump = np.sqrt(np.sum(((q - prediction) * weights) ** 2, axis=-1))
    return converged & (jump <= allowed(length, expected)), jump


def allowed(length: float, expected):
    """How far a solution may move from its prediction, ``expected`` the prediction's own
    step (numbers, arrays or traced values): half that step, but at least 10⁻⁴ and at most
    2 % of the group's size ``length``.

    >>> allowed(2.0, 0.01), allowed(2.0, 1e-6), allowed(2.0, 1.0)
    (0.005, 0.0002, 0.04)
    """
    return minimum(0.02 * length, maximum(0.5 * expected, 1e-4 * length))


class System:
    """A higher group's equations in the unknowns q: what the continuation needs. A pose is
    made by :meth:`at` from q given as a tuple of its coordinates; results are tuples too.
    Subclasses: :class:`GeneralSystem` here, the plain triad's in :mod:`.triad`."""

    group: AssurGroup
    links: tuple[str, ...]
    size: int
    length: float
    weights: np.ndarray
    #: the system is written in the arithmetic of :mod:`~planmethod.kinematics.algebra`
    traceable: bool = False

    def inputs(self, bodies: Mapping[str, Body], level: int) -> list:
        """The known links' values the system reads (traced or arrays), in a fixed order."""
        raise NotImplementedError

    def known(self, values: Sequence, level: int) -> Any:
        """The known links' values from :meth:`inputs` (arrays or traced values)."""
        raise NotImplementedError

    def at(self, q: tuple, known) -> Any:
        """What the methods below read at the pose q (a tuple of its coordinates)."""
        raise NotImplementedError

    def residual(self, pose):
        """max |Φ| at each angle (length units)."""
        raise NotImplementedError

    def step(self, pose) -> tuple:
        """Newton's step −Φ_q⁻¹·Φ."""
        raise NotImplementedError

    def rates(self, pose, level: int):
        """(q̇, q̈) from the known links' motion (None for stages not solved)."""
        raise NotImplementedError

    def conditioning(self, pose):
        """Φ_q's normalised determinant at each angle, 1 at best, 0 at a toggle."""
        raise NotImplementedError

    def results(self, pose, rates, level: int) -> list:
        """Per group link its c, s, x, y (+ ω, vx, vy, + ε, ax, ay): the bodies' values."""
        raise NotImplementedError

    def stored(self, pose) -> dict:
        """The angles θ that are results of their own (link → value)."""
        raise NotImplementedError

    def theta_recipes(self) -> dict:
        """link → :class:`~planmethod.kinematics.groups.base.Theta` of the links whose angle
        is read from their points."""
        return {}

    def poses(self, pose) -> np.ndarray:
        """(x, y, θ) of each group link's origin (N, 3·links), θ wrapped."""
        raise NotImplementedError

    def assemblies(self, known) -> list[np.ndarray]:
        """Every distinct assembly at the one angle of ``known`` (each q of shape (size,))."""
        raise NotImplementedError

    # -- shared ----------------------------------------------------------------------------
    def newton(self, q: np.ndarray, known, iterations: int = ITERATIONS):
        """Newton from ``q`` (N, size): (solution, converged mask, residual, its pose)."""
        q = np.array(q, dtype=float)
        tolerance = RESIDUAL * self.length
        polished = np.zeros(q.shape[0], dtype=bool)
        pose = self.at(tuple(q.T), known)
        residual = np.asarray(self.residual(pose))
        for _ in range(iterations):
            with np.errstate(invalid="ignore"):
                done = residual <= tolerance
                polished |= residual <= POLISHED * tolerance
            if np.all(done & polished) or not np.any(np.isfinite(residual)):
                break
            # every angle steps (a converged one by next to nothing), but one that diverged
            active = np.isfinite(residual) & (residual < 1e6 * self.length)
            polished |= done  # one more step for the converged ones: full precision
            with np.errstate(all="ignore"):
                step = stack(self.step(pose))
            q += np.where(active[:, None] & np.isfinite(step), step, 0.0)
            pose = self.at(tuple(q.T), known)
            residual = np.asarray(self.residual(pose))
        with np.errstate(invalid="ignore"):
            done = np.isfinite(residual) & (residual <= tolerance)
        return q, done, residual, pose

    def norm(self, dq: np.ndarray) -> np.ndarray:
        return np.sqrt(np.sum((dq * self.weights) ** 2, axis=-1))


def stack(values: Sequence) -> np.ndarray:
    """Coordinates (arrays or numbers) as an (N, k) array."""
    return np.stack(np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values)),
                    axis=-1)


def _take(known, mask):
    """The known values at some of the angles."""
    if isinstance(known, dict):
        return {key: _take(value, mask) for key, value in known.items()}
    if isinstance(known, (list, tuple)):
        return type(known)(_take(value, mask) for value in known)
    if isinstance(known, LinkState):
        return known.take(mask)
    if isinstance(known, np.ndarray) and known.ndim >= 1:
        return known[mask]
    return known


def wrap(angle):
    """An angle in [−π, π] (unchanged where it is there already)."""
    angle = np.asarray(angle, dtype=float)
    outside = np.abs(angle) > np.pi
    if not np.any(outside):
        return angle
    return np.where(outside, np.remainder(angle + np.pi, 2.0 * np.pi) - np.pi, angle)


# -- the path of nodes ----------------------------------------------------------------------------
class Path:
    """The continuation of one group's branch from ``drive.angle``: nodes every STEP_DEG in
    each direction, each with q, dq/dφ and d²q/dφ² (per rad)."""

    def __init__(self, system: System, start: float, q0: np.ndarray, upstream) -> None:
        self.system, self.start, self.upstream = system, start, upstream
        self.lock = threading.Lock()
        first, second = self._derivatives(q0[None, :], upstream(np.array([start])))
        node = (q0[None, :], first, second)
        self.nodes = {1: [node], -1: [node]}
        #: the nodes of each side joined into arrays (q, q', q''), with the count they hold
        self.stacked: dict[int, tuple[int, tuple[np.ndarray, ...]]] = {}

    def _derivatives(self, q: np.ndarray, known):
        first, second = self.system.rates(self.system.at(tuple(q.T), known), 2)
        return stack(first), stack(second)

    def arrays(self, direction: int, count: int):
        with self.lock:
            nodes = self.nodes[direction]
            if len(nodes) <= count:
                angles = self.start + direction * STEP_DEG * np.arange(len(nodes), count + 1)
                ahead = self.upstream(angles)
                for index, angle in enumerate(angles):
                    before = float(self.start + direction * STEP_DEG * (len(nodes) - 1))
                    nodes.append(self.advance(nodes[-1], before, float(angle),
                                              _take(ahead, np.array([index]))))
            stacked = self.stacked.get(direction)
            if stacked is None or stacked[0] != len(nodes):  # joined once per growth
                stacked = (len(nodes), tuple(np.concatenate(parts)
                                             for parts in zip(*nodes, strict=True)))
                self.stacked[direction] = stacked
        return tuple(part[:count + 1] for part in stacked[1])

    def advance(self, node, start: float, stop: float, known=None):
        """From ``node`` at ``start`` to ``stop`` (deg), halving on trouble."""
        system = self.system
        q, first, second = node
        known = self.upstream(np.array([stop])) if known is None else known
        step = math.radians(stop - start)
        prediction = q + first * step + 0.5 * second * step * step
        found, converged, residual, pose = system.newton(prediction, known)
        ok, jump = accept(system.length, found, converged, prediction,
                          system.norm(first * step), system.weights)
        if bool(ok[0]):
            health = float(np.ravel(system.conditioning(pose))[0])
            if not health > SINGULAR:
                raise _toggle(system, health, stop)
            return (found, *self._derivatives(found, known))
        if abs(stop - start) < MIN_STEP_DEG:
            here = self.upstream(np.array([start]))
            health = float(np.ravel(system.conditioning(system.at(tuple(q.T), here)))[0])
            name = system.group.name
            if health < LIMIT:
                raise ToggleError(message(
                    "the group reaches a limit (toggle) position near crank angle {angle:.6g}°: "
                    "its Jacobian is nearly singular (normalised determinant {health:.2g}); "
                    "beyond it the group cannot be assembled on this branch", angle=start,
                    health=health), line_angle_deg=0.0, link=name, angle=start)
            if not bool(converged[0]):
                raise ConvergenceError(message(
                    "Newton did not converge: residual {residual:.3g} m after {iterations} "
                    "iterations (group size {size:g} m), even with a crank-angle step of "
                    "{step:.2g}°", residual=float(residual[0]), iterations=ITERATIONS,
                    size=system.length, step=abs(stop - start)),
                    residual=float(residual[0]), link=name, angle=stop)
            raise BranchJumpError(message(
                "the assembly would jump to another branch between crank angles {start:.9g}° "
                "and {stop:.9g}° (the solution moves {moved:.3g} m in a step of {step:.2g}°): "
                "a toggle or branch point lies there", start=start, stop=stop,
                moved=float(jump[0]), step=abs(stop - start)), link=name, angle=stop)
        middle = 0.5 * (start + stop)
        return self.advance(self.advance(node, start, middle), middle, stop)

    def predict(self, angles_deg: np.ndarray):
        """Each angle's prediction from its nearest node on its side of ``drive.angle``, the
        prediction's step (q'·Δφ), the nearest nodes and where they are."""
        system = self.system
        offsets = angles_deg - self.start
        direction = np.where(offsets >= 0.0, 1, -1)
        nearest = np.rint(np.abs(offsets) / STEP_DEG).astype(int)
        count = angles_deg.shape[0]
        node_q = np.empty((count, system.size))
        slope = np.empty((count, system.size))
        curve = np.empty((count, system.size))
        for side in (1, -1):
            mask = direction == side
            if not np.any(mask):
                continue
            here = nearest[mask]
            nodes_q, first, second = self.arrays(side, int(here.max()))
            node_q[mask], slope[mask], curve[mask] = nodes_q[here], first[here], second[here]
        step = np.radians(offsets - direction * STEP_DEG * nearest)[:, None]
        moved = slope * step
        prediction = node_q + moved + (0.5 * step * step) * curve
        return prediction, moved, (node_q, slope, curve, direction, nearest)

    def predict_into(self, angles_deg: np.ndarray, predictions, steps) -> None:
        """:meth:`predict`'s prediction and step written row by row (one row per unknown, as
        the traced program keeps them) into ``predictions`` and ``steps``: the same arithmetic,
        with one gather per row from the nodes of both sides laid end to end."""
        offsets = angles_deg - self.start
        nearest = np.rint(offsets / STEP_DEG).astype(np.intp)   # signed: the side and node
        behind = self.arrays(-1, max(-int(nearest.min()), 0))
        ahead = self.arrays(1, max(int(nearest.max()), 0))
        first = behind[0].shape[0] - 1        # the column of the start node
        node_q, slope, curve = (np.concatenate([back[:0:-1], front]).T
                                for back, front in zip(behind, ahead, strict=True))
        index = nearest + first
        step = np.radians(offsets - STEP_DEG * nearest)
        half_square = 0.5 * step * step
        for row in range(self.system.size):
            moved = steps[row]
            prediction = predictions[row]
            np.multiply(slope[row].take(index), step, out=moved)
            np.add(node_q[row].take(index), moved, out=prediction)
            prediction += half_square * curve[row].take(index)

    def solve(self, angles_deg: np.ndarray, known) -> tuple[np.ndarray, Any]:
        """q and its pose at ``angles_deg`` (``known`` at those angles): all angles corrected by
        Newton together; one that fails the checks is marched to from its node."""
        system = self.system
        prediction, moved, (node_q, slope, curve, direction, nearest) = self.predict(
            angles_deg)
        found, converged, _, pose = system.newton(prediction, known)
        ok, _ = accept(system.length, found, converged, prediction, system.norm(moved),
                       system.weights)
        if not np.all(ok):
            for bad in np.flatnonzero(~ok):  # rare: march there in smaller steps
                node = (node_q[bad][None], slope[bad][None], curve[bad][None])
                start = float(self.start + direction[bad] * STEP_DEG * nearest[bad])
                found[bad] = self.advance(node, start, float(angles_deg[bad]),
                                          _take(known, np.array([bad])))[0][0]
            pose = system.at(tuple(found.T), known)
        return found, pose


def _toggle(system: System, health: float, angle: float) -> ToggleError:
    return ToggleError(message(
        "toggle position: the group's Jacobian is singular (normalised determinant "
        "{health:.2g}); its motion is not determined", health=health), line_angle_deg=0.0,
        link=system.group.name, angle=angle)


# -- the branch ----------------------------------------------------------------------------------
def _sketch_distance(mechanism: Mechanism, system: System, poses: np.ndarray) -> float | None:
    total, used = 0.0, False
    for index, link in enumerate(system.links):
        x, y, theta = poses[3 * index:3 * index + 3]
        for name, local in mechanism.links[link].points.items():
            if name in mechanism.sketch:
                place = np.array([x, y]) + rotate(np.asarray(local), np.array([theta]))[0]
                total += float(np.sum((place - np.asarray(mechanism.sketch[name])) ** 2))
                used = True
    return total if used else None


def sort_assemblies(system: System, found: list[np.ndarray], known) -> list[np.ndarray]:
    """Distinct assemblies in a fixed order (by their links' poses, angles wrapped)."""
    scale = system.length * 1e-6
    weights = np.tile([1.0, 1.0, system.length], len(system.links))
    keyed: dict[tuple, tuple] = {}
    for q in found:
        poses = system.poses(system.at(tuple(q[None, :].T), known))[0]
        key = tuple(np.round(poses * weights / scale).astype(np.int64))
        if any(np.sqrt(np.sum(((poses - other[1]) * weights) ** 2)) <= 1e-5 * system.length
               for other in keyed.values()):
            continue
        keyed[key] = (q, poses)
    return [keyed[key][0] for key in sorted(keyed)]


def _arrays(values: Sequence, count: int) -> list[np.ndarray]:
    return [np.broadcast_to(np.asarray(value, dtype=float), (count,)) for value in values]


def choose_with(context: GroupInputs, model: KindModel,
                make_system: Callable[[GroupInputs], System]) -> tuple[Branch, dict[str, Body]]:
    """The group's assembly at ``drive.angle`` and its links' bodies there."""
    mechanism, group = context.mechanism, context.group
    system = make_system(context)
    known = system.known(_arrays(system.inputs(context.bodies, 0), 1), 0)
    found = model.memo.get(("assemblies", group.index))
    if found is None:
        found = sort_assemblies(system, system.assemblies(known), known)
        model.memo[("assemblies", group.index)] = found
    if not found:
        raise AssemblyError(message("the group cannot be assembled at this crank angle: no "
                                    "assembly found"), shortfall=None, link=group.name,
                            angle=float(mechanism.drive.angle))
    distances = [_sketch_distance(mechanism, system,
                                  system.poses(system.at(tuple(q[None, :].T), known))[0])
                 for q in found]
    if len(found) == 1:
        index, reason = 0, "unique"
    elif distances[0] is None:
        index, reason = 0, "default"
    else:
        index, reason = int(np.argmin(distances)), "sketch"
    values = system.results(system.at(tuple(found[index][None, :].T), known), None, 0)
    bodies = {}
    for number, link in enumerate(system.links):
        c, s, x, y = (np.asarray(v, dtype=float).reshape(1) for v in values[4 * number:
                                                                           4 * number + 4])
        bodies[link] = Body(c, s, x, y)
    return HigherBranch(index + 1, reason, len(found)), bodies


# -- the path of a model ------------------------------------------------------------------------
def _path(context: GroupInputs, model: KindModel, branch: Branch, system: System) -> Path:
    """The model's path for this group and branch (made once)."""
    key = ("path", context.group.index, branch.sign)
    found = model.memo.get(key)
    if found is not None:
        return found
    mechanism, group = context.mechanism, context.group
    assemblies = model.memo.get(("assemblies", group.index))
    if assemblies is None:
        choose_with(GroupInputs(mechanism, group, _upstream_bodies(
            model, group, np.array([float(mechanism.drive.angle)]), 0), 1.0,
            np.array([float(mechanism.drive.angle)]), {}), model, lambda _: system)
        assemblies = model.memo[("assemblies", group.index)]
    if not 1 <= branch.sign <= len(assemblies):
        raise StructureError(plural(
            "branch {branch} asked, but the group has {count} assembly at crank angle "
            "{angle:g}°", "branch {branch} asked, but the group has {count} assemblies at "
            "crank angle {angle:g}°", count=len(assemblies), branch=branch.sign,
            angle=mechanism.drive.angle), link=group.name)

    def upstream(angles: np.ndarray):
        """The known values at unit crank speed: derivatives by the crank angle."""
        bodies = _upstream_bodies(model, group, np.asarray(angles, dtype=float), 2, unit=True)
        return system.known(_arrays(system.inputs(bodies, 2), len(angles)), 2)

    found = Path(system, float(mechanism.drive.angle), assemblies[branch.sign - 1], upstream)
    model.memo[key] = found
    return found


def _upstream_bodies(model: KindModel, group: AssurGroup, angles: np.ndarray, level: int,
                     unit: bool = False) -> dict[str, Body]:
    """The links the group rests on, by the direct evaluation at ``angles`` (``unit``: with
    the crank turning at 1 rad/s)."""
    mechanism = model.mechanism
    source = model
    if unit:
        source = model.sibling(dataclasses.replace(mechanism, drive=dataclasses.replace(
            mechanism.drive, omega=1.0, epsilon=0.0)))
    links = [link for link in group.attached_to if link != FRAME] or [mechanism.drive.link]
    groups = tuple(g for g in model.structure.groups_needed(links) if g.index != group.index)
    return source.bodies(level, groups, model.branches(groups), angles)


# -- the evaluation -----------------------------------------------------------------------------
def higher_evaluate(context: GroupInputs, level: int, model: KindModel, branch: Branch,
                    make_system: Callable[[GroupInputs], System]) -> SolvedGroup:
    """Solve a higher group at the context's angles and put its links' bodies into the
    context."""
    system = make_system(context)
    inputs = system.inputs(context.bodies, level)
    if isinstance(context.angles, Traced) and system.traceable:
        values, stored, health = _traced(context, level, model, branch, system, inputs)
    elif isinstance(context.angles, Traced):
        values, stored, health = _called(context, level, model, branch, system, inputs)
    else:
        values, stored, health = _direct(context, level, model, branch, system, inputs)
    per = 4 + 3 * min(level, 1) + 3 * max(level - 1, 0)
    for number, link in enumerate(system.links):
        part = values[per * number:per * (number + 1)]
        body = Body(*part[:4])
        if level >= 1:
            body.omega, body.vx, body.vy = part[4:7]
        if level >= 2:
            body.epsilon, body.ax, body.ay = part[7:10]
        context.bodies[link] = body
    return SolvedGroup(stored, system.theta_recipes(), health)


def _direct(context, level, model, branch, system, inputs):
    """The iterating evaluation on arrays (and the errors)."""
    angles = np.asarray(context.angles, dtype=float)
    known = system.known(_arrays(inputs, angles.shape[0]), level)
    _, pose = _path(context, model, branch, system).solve(angles, known)
    health = np.broadcast_to(np.asarray(system.conditioning(pose), dtype=float),
                             angles.shape)
    bad = ~(health > SINGULAR)
    if np.any(bad):
        index = int(np.flatnonzero(bad)[0])
        raise _toggle(system, float(health[index]), float(angles[index]))
    rates = system.rates(pose, level) if level else None
    return system.results(pose, rates, level), system.stored(pose), health


def _called(context, level, model, branch, system, inputs):
    """A system not written for tracing: its direct evaluation recorded as one call."""
    per = 4 + 3 * min(level, 1) + 3 * max(level - 1, 0)
    count = len(system.links) * per
    stored_links = list(system.stored(None))

    def compute(angles_deg, arrays, out) -> None:
        inner = GroupInputs(context.mechanism, context.group, {}, context.sign,
                        np.asarray(angles_deg, dtype=float), {})
        values, stored, health = _direct(inner, level, model, branch, system, list(arrays))
        results = [*values, *(stored[link] for link in stored_links), health]
        for row, value in zip(out, results, strict=True):
            row[...] = value

    results = context.angles.tracer.call(compute, inputs, count + len(stored_links) + 1)
    stored = dict(zip(stored_links, results[count:-1], strict=True))
    return results[:count], stored, results[-1]


def _traced(context, level, model, branch, system, inputs):
    """The straight-line evaluation: the prediction from the path (one call), one Newton step
    and its checks, then the exact rates — traced; a chunk that fails a check is redone."""
    tracer = context.angles.tracer

    def predict(angles_deg, arrays, out) -> None:
        path = _path(context, model, branch, system)
        path.predict_into(np.asarray(angles_deg, dtype=float), out[:system.size],
                          out[system.size:])

    values = tracer.call(predict, [], 2 * system.size)
    start, moved = tuple(values[:system.size]), values[system.size:]
    known = system.known(inputs, level)
    step = system.step(system.at(start, known))
    q = tuple(a + b for a, b in zip(start, step, strict=True))
    pose = system.at(q, known)
    tolerance = RESIDUAL * system.length

    def redo(angles, *values) -> None:
        raise Redo

    # converged (no polishing needed), did not jump, not at a toggle: else the chunk is redone
    context.guard(POLISHED * tolerance - system.residual(pose), 0.0, redo)
    weights = system.weights
    jump = sqrt(sum(((a - b) * w) * ((a - b) * w) for a, b, w in zip(q, start, weights,
                                                                      strict=True)))
    expected = sqrt(sum((m * w) * (m * w) for m, w in zip(moved, weights, strict=True)))
    context.guard(allowed(system.length, expected) - jump, 0.0, redo)
    health = system.conditioning(pose)
    context.guard(health, SINGULAR, redo)
    rates = system.rates(pose, level) if level else None
    return system.results(pose, rates, level), system.stored(pose), health


# -- the general system: any higher group, on the generic constraint equations ---------------
class GeneralSystem(System):
    """Any higher group on :class:`~planmethod.kinematics.constraints.ConstraintSystem`:
    q = (x, y, θ) of each group link (numpy only: evaluated as one call when traced)."""

    def __init__(self, context: GroupInputs) -> None:
        mechanism, group = context.mechanism, context.group
        self.mechanism, self.group = mechanism, group
        self.links = tuple(group.links)
        self.known_links = tuple(dict.fromkeys(j.other(_inside(j, group)) for j in group.joints
                                               if not set(j.links) <= set(group.links)))
        self.constraints = ConstraintSystem.between(
            mechanism, self.links, known=self.known_links)
        rows, cols = self.constraints.size
        if rows != cols:
            raise StructureError(message("the group has {rows} constraint equations for "
                                         "{columns} unknowns", rows=rows, columns=cols),
                                 link=group.name)
        sizes = [1e-9]
        for link in self.links:
            points = np.array(list(mechanism.links[link].points.values()))
            if len(points) > 1:
                sizes.append(float(np.max(np.hypot(*(points[:, None] - points[None]).T))))
        self.length = max(sizes)
        self.size = cols
        self.row_scale = np.ones(rows)
        for index, constraint in enumerate(self.constraints.constraints):
            if constraint.kind is PairKind.PRISMATIC:
                self.row_scale[2 * index] = self.length
        self.weights = np.tile([1.0, 1.0, self.length], len(self.links))

    def inputs(self, bodies, level: int) -> list:
        out = []
        for link in self.known_links:
            body = bodies[link]
            values = [body.cos, body.sin, body.x, body.y]
            if level >= 1:
                values += [body.omega, body.vx, body.vy]
            if level >= 2:
                values += [body.epsilon, body.ax, body.ay]
            out += values
        return out

    def known(self, values, level: int) -> dict[str, LinkState]:
        per = 4 + 3 * min(level, 1) + 3 * max(level - 1, 0)
        states = {}
        for number, link in enumerate(self.known_links):
            part = values[per * number:per * (number + 1)]
            c, s, x, y = part[:4]
            axes = np.stack((c, s), axis=-1)
            state = LinkState(np.arctan2(s, c), np.stack((x, y), axis=-1), basis=axes)
            if level >= 1:
                state = state.moving(part[4], np.stack(part[5:7], axis=-1))
            if level >= 2:
                state = state.moving(state.omega, state.velocity, part[7],
                                     np.stack(part[8:10], axis=-1))
            states[link] = state
        return states

    def at(self, q, known):
        q = stack(q)
        states = dict(known)
        for index, link in enumerate(self.links):
            states[link] = LinkState(np.ascontiguousarray(q[:, 3 * index + 2]),
                                     np.ascontiguousarray(q[:, 3 * index:3 * index + 2]))
        return q, known, states

    def residual(self, pose) -> np.ndarray:
        phi = self.constraints.residual(pose[2]) * self.row_scale
        return np.abs(phi).max(axis=-1)

    def step(self, pose) -> tuple:
        states = pose[2]
        phi = self.constraints.residual(states) * self.row_scale
        matrix = self.constraints.jacobian(states)[0] * self.row_scale[:, None]
        try:
            found = np.linalg.solve(matrix, -phi[..., None])[..., 0]
        except np.linalg.LinAlgError:
            found = (np.linalg.pinv(matrix) @ -phi[..., None])[..., 0]
        return tuple(found.T)

    def rates(self, pose, level: int):
        states = dict(pose[2])
        first = second = None
        if level >= 1:
            first = self.constraints.velocities(states)
            for index, link in enumerate(self.links):
                states[link] = states[link].moving(
                    np.ascontiguousarray(first[:, 3 * index + 2]),
                    np.ascontiguousarray(first[:, 3 * index:3 * index + 2]))
            first = tuple(first.T)
        if level >= 2:
            second = tuple(self.constraints.accelerations(states).T)
        return first, second

    def conditioning(self, pose) -> np.ndarray:
        matrix = self.constraints.jacobian(pose[2])[0]
        matrix = matrix * self.row_scale[:, None] / self.weights[None, :] * self.length
        rows = np.sqrt(np.sum(matrix * matrix, axis=-1))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.abs(np.linalg.det(matrix)) / np.prod(rows, axis=-1)

    def stored(self, pose) -> dict:
        if pose is None:
            return dict.fromkeys(self.links)
        q = pose[0]
        return {link: q[:, 3 * index + 2] for index, link in enumerate(self.links)}

    def poses(self, pose) -> np.ndarray:
        out = np.array(pose[0], dtype=float)
        out[:, 2::3] = wrap(out[:, 2::3])
        return out

    def results(self, pose, rates, level: int) -> list:
        q = pose[0]
        out = []
        for index in range(len(self.links)):
            theta = q[:, 3 * index + 2]
            out += [np.cos(theta), np.sin(theta), q[:, 3 * index], q[:, 3 * index + 1]]
            if level >= 1:
                first = rates[0]
                out += [first[3 * index + 2], first[3 * index], first[3 * index + 1]]
            if level >= 2:
                second = rates[1]
                out += [second[3 * index + 2], second[3 * index], second[3 * index + 1]]
        return out

    def assemblies(self, known) -> list[np.ndarray]:
        starts = self._starts(known)
        many = _take(known, np.zeros(starts.shape[0], dtype=int))
        q, done, _, _ = self.newton(starts, many, iterations=16)
        return [row for row in q[done]]

    def _starts(self, known) -> np.ndarray:
        grid = 2 * np.pi * np.arange(8) / 8
        mesh = np.stack(np.meshgrid(*([grid] * len(self.links)), indexing="ij"), axis=-1)
        thetas = mesh.reshape(-1, len(self.links))
        count = thetas.shape[0]
        q = np.zeros((count, self.size))
        q[:, 2::3] = thetas
        many = _take(known, np.zeros(count, dtype=int))
        states = self.at(tuple(q.T), many)[2]
        phi = self.constraints.residual(states) * self.row_scale
        matrix = self.constraints.jacobian(states)[0] * self.row_scale[:, None]
        columns = [c for c in range(matrix.shape[2]) if c % 3 != 2]
        q[:, columns] = (np.linalg.pinv(matrix[:, :, columns]) @ -phi[..., None])[..., 0]
        return q


def _inside(joint, group: AssurGroup) -> str:
    return joint.links[0] if joint.links[0] in group.links else joint.links[1]


def evaluate(context: GroupInputs, level: int, model: KindModel, branch: Branch) -> SolvedGroup:
    """Solve a higher group of any shape (see the module docstring)."""
    return higher_evaluate(context, level, model, branch, GeneralSystem)


def choose(context: GroupInputs, model: KindModel) -> tuple[Branch, dict[str, Body]]:
    """The group's assembly at ``drive.angle`` (see the module docstring)."""
    return choose_with(context, model, GeneralSystem)
