"""Class III (and IV) Assur groups: positions by Newton, exact velocities and accelerations.

A triad (seed 000's conveyor: the tray with its bracket, the rod AB and the rockers EF, DG) has
no closed form: its 3k pose coordinates q = (x, y, θ) per link satisfy the pairs' equations
Φ(q) = 0 (:mod:`planmethod.kinematics.constraints`), solved here by Newton's method.

**Assemblies and the branch.** At ``drive.angle`` Newton starts from a grid of link angles
(origins by linear least squares for each choice of angles) and from the ``[sketch]``; every
converged, distinct assembly is kept and sorted. The group takes the assembly nearest (least
squares) to its sketched points — reason ``sketch`` — or, with no sketched point, the first one
in that order — reason ``default`` (``unique`` if only one exists). The branch's ``sign`` is
that assembly's number (1, 2, …) in the sorted list.

**Continuation.** Any crank angle φ is reached from ``drive.angle`` along the crank angle itself
(φ taken as a number, not modulo 360°): nodes every :data:`STEP_DEG` are marched in turn, each
Newton solve predicted from the node before with the exact tangent dq/dφ. A step whose Newton
solve fails, or whose correction is too large for the step (the sign of a jump to another
assembly), is halved, down to :data:`MIN_STEP_DEG`; then it is an error —
:class:`~planmethod.errors.ConvergenceError` (how far from a solution, where) or
:class:`~planmethod.errors.BranchJumpError` — never a silent flip; where the group's Jacobian
is nearly singular there, it has reached its limit (toggle) position: a
:class:`~planmethod.errors.ToggleError`. The requested angles are then solved all at once from
their nearest node, with the same jump check.

**Velocities and accelerations** are exact linear solves Φ_q·q̇ = −Φ_known·q̇_known and
Φ_q·q̈ = γ − Φ_known·q̈_known. A singular Φ_q (the group's own toggle: for a triad, the lines of
the three side links meeting in one point) is a :class:`~planmethod.errors.ToggleError`; the
reciprocal condition number of Φ_q is kept in ``GroupMotion.line_sine`` (1 = perfectly
conditioned, like the sine of the angle between a dyad's two lines).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> motion = solve(load_exercise("exercises/conveyor_sixbar.toml").mechanism, 135.0)
>>> motion.position("D").round(6)
array([ 0.793156, -0.183194])
>>> motion.branches[0].reason
'sketch'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import AssemblyError, BranchJumpError, ConvergenceError, StructureError, ToggleError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, analyse_structure
from .constraints import ConstraintSystem
from .solve import Branch, GroupMotion
from .state import LinkState, rotate

__all__ = ["MIN_STEP_DEG", "STEP_DEG", "HigherBranch", "assemblies", "choose_higher_branch",
           "solve_higher"]

#: largest continuation step (deg of crank angle)
STEP_DEG = 2.0
#: a step halved below this is given up (deg)
MIN_STEP_DEG = 1e-6
#: link angles tried per link when looking for every assembly
GRID = 8
#: Newton iterations before a start counts as failed
ITERATIONS = 30
#: Newton iterations from each of the many starts that look for every assembly
STARTS_ITERATIONS = 16
#: residual |Φ| accepted, relative to the group's size
RESIDUAL = 1e-12
#: reciprocal condition number of Φ_q below which the group is in its toggle position
SINGULAR_RCOND = 1e-12
#: … and below which a continuation that cannot go on has reached a limit position
LIMIT_RCOND = 1e-4


@dataclass(frozen=True, slots=True)
class HigherBranch(Branch):
    """A class III group's branch: ``sign`` is the assembly's number among ``count`` found at
    the crank angle ``angle`` (deg); ``reference`` its pose (x, y, θ per link, flattened);
    ``upstream`` the branches of the groups it rests on, ``((index, Branch), …)``."""

    angle: float = 0.0
    reference: tuple[float, ...] = ()
    upstream: tuple = ()
    count: int = 1


# -- the group's equations --------------------------------------------------------------------
class _Group:
    """The constraint equations of one group and its scale."""

    def __init__(self, mechanism: Mechanism, group: AssurGroup, known) -> None:
        self.mechanism = mechanism
        self.group = group
        self.links = tuple(group.links)
        self.system = ConstraintSystem.between(mechanism, self.links, known=known)
        rows, cols = self.system.size
        if rows != cols:
            raise StructureError(f"the group has {rows} constraint equations for {cols} "
                                 "unknowns", link=group.name)
        sizes = [1e-9]
        for link in self.links:
            points = np.array(list(mechanism.links[link].points.values()))
            if len(points) > 1:
                sizes.append(float(np.max(np.hypot(*(points[:, None] - points[None]).T))))
        self.length = max(sizes)
        scale = np.ones(rows)
        for index, constraint in enumerate(self.system.constraints):
            if constraint.kind == "P":
                scale[2 * index] = self.length  # the angle row, in length units
        self.row_scale = scale
        weights = np.ones(cols)
        weights[2::3] = self.length
        self.weights = weights

    def states(self, q: np.ndarray, known) -> dict[str, LinkState]:
        states = dict(known)
        for index, link in enumerate(self.links):
            states[link] = LinkState(np.ascontiguousarray(q[:, 3 * index + 2]),
                                     np.ascontiguousarray(q[:, 3 * index:3 * index + 2]))
        return states

    def norm(self, dq: np.ndarray) -> np.ndarray:
        """Size of a change of q in length units (angles × the group's size)."""
        return np.sqrt(np.sum((dq * self.weights) ** 2, axis=-1))

    def residual(self, q, known) -> np.ndarray:
        phi = self.system.residual(self.states(q, known)) * self.row_scale
        return np.abs(phi).max(axis=-1)

    def newton(self, q: np.ndarray, known, iterations: int = ITERATIONS):
        """Newton from ``q`` (N, 3k): (solution, converged mask, residual, iterations)."""
        q = np.array(q, dtype=float)
        tolerance = RESIDUAL * self.length
        residual = np.full(q.shape[0], np.inf)
        done = np.zeros(q.shape[0], dtype=bool)
        used = 0
        polished = False
        for used in range(iterations + 1):
            states = self.states(q, known)
            phi = self.system.residual(states) * self.row_scale
            residual = np.abs(phi).max(axis=-1)
            with np.errstate(invalid="ignore"):
                done = residual <= tolerance
            finished = done | ~np.isfinite(residual)
            if used == iterations or (np.all(finished) and polished):
                break
            if np.all(finished):
                polished = True  # one more step for the converged ones: full precision
            matrix = self.system.jacobian(states)[0] * self.row_scale[:, None]
            active = np.isfinite(residual) & (residual < 1e6 * self.length)  # not diverged
            step = _solve(matrix[active], -phi[active])
            q[active] += step
        with np.errstate(invalid="ignore"):
            done = np.isfinite(residual) & (residual <= tolerance)
        return q, done, residual, used

    def rcond(self, q, known) -> np.ndarray:
        matrix = self.system.jacobian(self.states(q, known))[0]
        matrix = matrix * self.row_scale[:, None] / self.weights[None, :] * self.length
        values = np.linalg.svd(matrix, compute_uv=False)
        return values[:, -1] / values[:, 0]

    def tangent(self, q, known) -> np.ndarray:
        """dq/dφ (per rad), ``known`` holding the known links' motion at ω1 = 1."""
        return self.system.velocities(self.states(q, known))


def _solve(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    try:
        return np.linalg.solve(matrix, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        return (np.linalg.pinv(matrix) @ rhs[..., None])[..., 0]


def _repeat(states, count: int) -> dict[str, LinkState]:
    def grow(array):
        return None if array is None else np.repeat(array[:1], count, axis=0)
    return {name: LinkState(grow(s.theta), grow(s.origin), grow(s.omega), grow(s.velocity),
                            grow(s.epsilon), grow(s.acceleration))
            for name, s in states.items()}


# -- every assembly at one crank angle -----------------------------------------------------------
def _located(mechanism: Mechanism, group: AssurGroup, known) -> dict[str, dict[str, np.ndarray]]:
    """Global positions known for the group's points: pins of known links (exact), else the
    sketch."""
    out: dict[str, dict[str, np.ndarray]] = {}
    for link in group.links:
        found = {}
        for point in mechanism.links[link].points:
            owners = [o for o in mechanism.links_with_point(point) if o in known and o != link]
            if owners:
                found[point] = known[owners[0]].place(mechanism.local(owners[0], point))[0]
            elif point in mechanism.sketch:
                found[point] = np.asarray(mechanism.sketch[point], float)
        out[link] = found
    return out


def _fit_angle(mechanism: Mechanism, link: str, located: dict[str, np.ndarray]) -> float | None:
    """The link angle that best lays its points onto ``located`` (least squares)."""
    if len(located) < 2:
        return None
    local = np.array([mechanism.local(link, p) for p in located])
    world = np.array(list(located.values()))
    local = local - local.mean(axis=0)
    world = world - world.mean(axis=0)
    c = float(np.sum(local * world))
    s = float(np.sum(local[:, 0] * world[:, 1] - local[:, 1] * world[:, 0]))
    if abs(c) + abs(s) < 1e-15:
        return None
    return math.atan2(s, c)


def _origins(group: _Group, thetas: np.ndarray, known) -> np.ndarray:
    """For fixed link angles (S, k), the origins that best satisfy the pairs (least squares)."""
    count = thetas.shape[0]
    q = np.zeros((count, 3 * len(group.links)))
    q[:, 2::3] = thetas
    states = group.states(q, _repeat(known, count))
    phi = group.system.residual(states) * group.row_scale
    matrix = group.system.jacobian(states)[0] * group.row_scale[:, None]
    columns = [c for c in range(matrix.shape[2]) if c % 3 != 2]
    origins = (np.linalg.pinv(matrix[:, :, columns]) @ -phi[..., None])[..., 0]
    q[:, columns] = origins
    return q


def _starts(mechanism: Mechanism, group: _Group, known) -> np.ndarray:
    located = _located(mechanism, group.group, known)
    fitted = [_fit_angle(mechanism, link, located[link]) for link in group.links]
    grid = 2 * np.pi * np.arange(GRID) / GRID
    mesh = np.stack(np.meshgrid(*([grid] * len(group.links)), indexing="ij"), axis=-1)
    thetas = [mesh.reshape(-1, len(group.links))]
    if any(angle is not None for angle in fitted):  # the sketch, the unknown angles gridded
        free = [i for i, angle in enumerate(fitted) if angle is None]
        sub = np.stack(np.meshgrid(*([grid] * len(free)), indexing="ij"), axis=-1).reshape(
            -1, len(free)) if free else np.zeros((1, 0))
        seeded = np.zeros((sub.shape[0], len(group.links)))
        for i, angle in enumerate(fitted):
            if angle is not None:
                seeded[:, i] = angle
        seeded[:, free] = sub
        thetas.insert(0, seeded)
    return _origins(group, np.concatenate(thetas), known)


def _distinct(group: _Group, solutions: np.ndarray) -> list[np.ndarray]:
    """Distinct assemblies (angles wrapped), in a fixed order."""
    wrapped = solutions.copy()
    wrapped[:, 2::3] = np.angle(np.exp(1j * wrapped[:, 2::3]))
    scaled = wrapped * group.weights / (1e-6 * group.length)
    _, first = np.unique(np.round(scaled).astype(np.int64), axis=0, return_index=True)
    picked: list[np.ndarray] = []
    for q in wrapped[np.sort(first)]:
        if any(_wrapped_norm(group, q - p) <= 1e-5 * group.length for p in picked):
            continue
        picked.append(q)

    def key(q):
        return tuple(np.round(q * group.weights / (1e-6 * group.length)).astype(int))
    return sorted(picked, key=key)


def _wrapped_norm(group: _Group, dq: np.ndarray) -> float:
    dq = dq.copy()
    dq[2::3] = np.angle(np.exp(1j * dq[2::3]))
    return float(np.sqrt(np.sum((dq * group.weights) ** 2)))


def assemblies(mechanism: Mechanism, group: AssurGroup, known) -> list[np.ndarray]:
    """Every distinct assembly of ``group`` at the single crank angle of the ``known`` states
    (each a q vector: x, y, θ per link), in a fixed order.

    Raises
    ------
    AssemblyError
        If Newton converges from none of the starts.
    """
    solver = _Group(mechanism, group, known)
    starts = _starts(mechanism, solver, known)
    q, done, residual, _ = solver.newton(starts, _repeat(known, starts.shape[0]),
                                         iterations=STARTS_ITERATIONS)
    if not np.any(done):
        best = float(np.nanmin(np.where(np.isfinite(residual), residual, np.nan))) if np.any(
            np.isfinite(residual)) else math.inf
        raise AssemblyError(
            f"the group cannot be assembled: Newton converged from none of {starts.shape[0]} "
            f"starts (smallest residual {best:.3g} m)", shortfall=best, link=group.name,
            angle=mechanism.drive.angle)
    return _distinct(solver, q[done])


def _sketch_distance(mechanism: Mechanism, group: AssurGroup, q: np.ndarray) -> float | None:
    total, used = 0.0, False
    for index, link in enumerate(group.links):
        theta, origin = q[3 * index + 2], q[3 * index:3 * index + 2]
        for name, local in mechanism.links[link].points.items():
            if name in mechanism.sketch:
                place = origin + rotate(np.asarray(local), np.array([theta]))[0]
                total += float(np.sum((place - np.asarray(mechanism.sketch[name])) ** 2))
                used = True
    return total if used else None


def _poses(group: AssurGroup, q: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    return {link: (np.array([q[3 * i + 2]]), np.array([q[3 * i:3 * i + 2]]))
            for i, link in enumerate(group.links)}


def _upstream(mechanism: Mechanism, group: AssurGroup, states) -> tuple:
    """The branches of the groups ``group`` rests on, read off their poses in ``states``."""
    from .dyads import dyad_positions

    structure = analyse_structure(mechanism)
    out = []
    angle = np.array([mechanism.drive.angle])
    for other in structure.groups_needed(group.attached_to):
        if other.index == group.index or not all(link in states for link in other.links):
            continue
        if other.is_dyad:
            chosen = Branch(1, "upstream")
            for sign in (1, -1):
                try:
                    poses = dyad_positions(mechanism, other, states, sign, angle)
                except (AssemblyError, ToggleError):
                    continue
                if all(np.allclose(poses[link][1], states[link].origin, atol=1e-9)
                       and np.allclose(np.angle(np.exp(1j * (poses[link][0]
                                                             - states[link].theta))), 0,
                                       atol=1e-9) for link in other.links):
                    chosen = Branch(sign, "upstream")
                    break
        else:
            reference = np.concatenate([np.concatenate((states[link].origin[0],
                                                        states[link].theta[:1]))
                                        for link in other.links])
            chosen = HigherBranch(0, "upstream", mechanism.drive.angle,
                                  tuple(float(v) for v in reference),
                                  _upstream(mechanism, other, states))
        out.append((other.index, chosen))
    return tuple(out)


#: assemblies already found, keyed by the model and the known links' poses (a few entries)
_CACHE: dict[tuple, list[np.ndarray]] = {}


def _cached_assemblies(mechanism: Mechanism, group: AssurGroup, states) -> list[np.ndarray]:
    """:func:`assemblies`, remembered: the multi-start search is the slow part of a solve,
    and the same model at the same angle always gives the same list."""
    key = (repr(mechanism), group.index, tuple(
        (name, state.theta.tobytes(), state.origin.tobytes())
        for name, state in sorted(states.items())))
    if key not in _CACHE:
        if len(_CACHE) >= 32:
            _CACHE.pop(next(iter(_CACHE)))
        _CACHE[key] = assemblies(mechanism, group, states)
    return [q.copy() for q in _CACHE[key]]


def choose_higher_branch(mechanism: Mechanism, group: AssurGroup, states, angle_rad=None):
    """The group's assembly at ``drive.angle``: ``(HigherBranch, {link: (theta, origin)})``.

    ``states`` holds the links solved before (at ``drive.angle``).
    """
    found = _cached_assemblies(mechanism, group, states)
    distances = [_sketch_distance(mechanism, group, q) for q in found]
    if len(found) == 1:
        index, reason = 0, "unique"
    elif distances[0] is None:
        index, reason = 0, "default"
    else:
        index = int(np.argmin(distances))
        reason = "sketch"
    q = found[index]
    branch = HigherBranch(index + 1, reason, float(mechanism.drive.angle),
                          tuple(float(v) for v in q), _upstream(mechanism, group, states),
                          len(found))
    return branch, _poses(group, q)


# -- continuation --------------------------------------------------------------------------------
class _Tracker:
    """Follows the branch from its reference angle to any crank angles."""

    def __init__(self, mechanism: Mechanism, group: AssurGroup, branch: HigherBranch,
                 known_links) -> None:
        self.mechanism = mechanism
        self.group = group
        self.branch = branch
        self.unit = replace(mechanism, drive=replace(mechanism.drive, omega=1.0, epsilon=0.0))
        self.structure = analyse_structure(mechanism)
        self.known_links = tuple(known_links)
        self.solver: _Group | None = None

    def upstream(self, angles_deg: np.ndarray) -> dict[str, LinkState]:
        """Known links at ``angles_deg``, with their velocities at ω1 = 1 (rad⁻¹)."""
        from .solve import solve

        links = [link for link in self.group.attached_to if link != FRAME]
        motion = solve(self.unit, np.asarray(angles_deg, float), stage="velocity",
                       links=links or [self.mechanism.drive.link], structure=self.structure,
                       branches=dict(self.branch.upstream))
        return {name: state for name, state in motion.links.items()
                if name in self.known_links}

    def group_solver(self, known) -> _Group:
        if self.solver is None:
            self.solver = _Group(self.mechanism, self.group, known)
        return self.solver

    def accept(self, solver: _Group, q, converged, prediction, tangent, step_rad):
        jump = solver.norm(q - prediction)
        expected = solver.norm(tangent * step_rad[..., None])
        allowed = np.minimum(0.02 * solver.length, np.maximum(0.5 * expected,
                                                               1e-4 * solver.length))
        return converged & (jump <= allowed), jump

    def advance(self, q, tangent, start: float, stop: float, known=None):
        """From the solution ``q`` at ``start`` to ``stop`` (deg), halving on trouble."""
        known = self.upstream(np.array([stop])) if known is None else known
        solver = self.group_solver(known)
        step = np.radians(np.array([stop - start]))
        prediction = q + tangent * step[:, None]
        found, converged, residual, _ = solver.newton(prediction, known)
        ok, jump = self.accept(solver, found, converged, prediction, tangent, step)
        if bool(ok[0]):
            self.check_toggle(solver, found, known, stop)
            return found, solver.tangent(found, known)
        if abs(stop - start) < MIN_STEP_DEG:
            rcond = float(solver.rcond(q, self.upstream(np.array([start])))[0])
            if rcond < LIMIT_RCOND:
                raise ToggleError(
                    f"the group reaches a limit (toggle) position near crank angle {start:.6g}°:"
                    f" its Jacobian is nearly singular (reciprocal condition number "
                    f"{rcond:.2g}); beyond it the group cannot be assembled on this branch",
                    line_angle_deg=0.0, link=self.group.name, angle=start)
            if not bool(converged[0]):
                raise ConvergenceError(
                    f"Newton did not converge: residual {float(residual[0]):.3g} m after "
                    f"{ITERATIONS} iterations (group size {solver.length:g} m), even with a "
                    f"crank-angle step of {abs(stop - start):.2g}°", residual=float(residual[0]),
                    link=self.group.name, angle=stop)
            raise BranchJumpError(
                f"the assembly would jump to another branch between crank angles {start:.9g}° "
                f"and {stop:.9g}° (the solution moves {float(jump[0]):.3g} m in a step of "
                f"{abs(stop - start):.2g}°): a toggle or branch point lies there",
                link=self.group.name, angle=stop)
        middle = 0.5 * (start + stop)
        q_mid, tangent_mid = self.advance(q, tangent, start, middle)
        return self.advance(q_mid, tangent_mid, middle, stop)

    def check_toggle(self, solver: _Group, q, known, angles) -> np.ndarray:
        rcond = solver.rcond(q, known)
        bad = ~(rcond > SINGULAR_RCOND)
        if np.any(bad):
            index = int(np.flatnonzero(bad)[0])
            angle = float(np.atleast_1d(angles)[index])
            raise ToggleError(
                f"toggle position: the group's Jacobian is singular (reciprocal condition "
                f"number {float(rcond[index]):.2g}); its motion is not determined",
                line_angle_deg=0.0, link=self.group.name, angle=angle)
        return rcond

    def track(self, angles_deg: np.ndarray, known) -> tuple[np.ndarray, np.ndarray]:
        """q at ``angles_deg`` (the outer ``known`` states are at those angles) and the
        reciprocal condition numbers."""
        reference = np.array(self.branch.reference)[None, :]
        start = self.branch.angle
        result = np.empty((angles_deg.shape[0], reference.shape[1]))
        for direction in (1.0, -1.0):
            mask = (angles_deg >= start) if direction > 0 else (angles_deg < start)
            if not np.any(mask):
                continue
            reach = float(np.max(np.abs(angles_deg[mask] - start)))
            count = math.ceil(reach / STEP_DEG - 1e-12)
            nodes = start + direction * STEP_DEG * np.arange(count + 1)
            path = self.upstream(nodes)
            node_q = [reference]
            first = {name: state.take([0]) for name, state in path.items()}
            solver = self.group_solver(first)
            node_t = [solver.tangent(reference, first)]
            for k in range(1, count + 1):
                here = {name: state.take([k]) for name, state in path.items()}
                q, tangent = self.advance(node_q[-1], node_t[-1], nodes[k - 1], nodes[k], here)
                node_q.append(q)
                node_t.append(tangent)
            node_q_array = np.concatenate(node_q)
            node_t_array = np.concatenate(node_t)
            targets = angles_deg[mask]
            nearest = np.clip(np.rint(np.abs(targets - start) / STEP_DEG).astype(int), 0, count)
            step = np.radians(targets - nodes[nearest])
            prediction = node_q_array[nearest] + node_t_array[nearest] * step[:, None]
            inner = {name: state.take(np.flatnonzero(mask)) for name, state in known.items()}
            found, converged, _, _ = solver.newton(prediction, inner)
            ok, _ = self.accept(solver, found, converged, prediction, node_t_array[nearest],
                                step)
            for bad in np.flatnonzero(~ok):  # rare: march there in smaller steps
                single = {name: state.take([bad]) for name, state in inner.items()}
                found[bad] = self.advance(node_q_array[nearest[bad]][None],
                                          node_t_array[nearest[bad]][None],
                                          float(nodes[nearest[bad]]), float(targets[bad]),
                                          single)[0][0]
            result[mask] = found
        return result


def _reference_branch(mechanism: Mechanism, group: AssurGroup, sign: int) -> HigherBranch:
    """The HigherBranch numbered ``sign`` when only a plain Branch was given."""
    from .solve import choose_branches

    structure = analyse_structure(mechanism)
    chosen = choose_branches(mechanism, structure, structure.groups_needed(group.links))
    branch = chosen[group.index]
    if sign == branch.sign or not isinstance(branch, HigherBranch):
        return branch
    from .solve import solve

    before = solve(mechanism, None, stage="position", links=list(group.attached_to) or None,
                   structure=structure)
    found = assemblies(mechanism, group, before.links)
    if not 1 <= sign <= len(found):
        raise StructureError(f"branch {sign} asked, but the group has {len(found)} assemblies "
                             f"at crank angle {mechanism.drive.angle:g}°", link=group.name)
    return replace(branch, sign=sign, reference=tuple(float(v) for v in found[sign - 1]),
                   count=len(found))


def solve_higher(mechanism: Mechanism, group: AssurGroup, states: dict, sign: int,
                 angles_deg: np.ndarray, level: int, branch: Branch | None = None
                 ) -> GroupMotion:
    """Positions (and velocities, accelerations up to ``level`` 1, 2) of a class III group at
    ``angles_deg``; each link's :class:`LinkState` is put into ``states``.

    Raises
    ------
    ConvergenceError, BranchJumpError, ToggleError
        See the module docstring.
    """
    if not isinstance(branch, HigherBranch):
        branch = _reference_branch(mechanism, group, sign)
    known = {name: state for name, state in states.items() if name not in group.links}
    tracker = _Tracker(mechanism, group, branch, known)
    q = tracker.track(np.asarray(angles_deg, float), known)
    solver = tracker.group_solver(known)
    rcond = tracker.check_toggle(solver, q, known, angles_deg)
    placed = solver.states(q, known)
    for link in group.links:
        states[link] = placed[link]
    if level >= 1:
        states.update(solver.system.moving_states(states, level))
    return GroupMotion(None, None, None, rcond)
