"""Joint friction by fixed-point iteration on the reactions (the "iterative procedure" of
Umbetkulov et al., "Dynamic force analysis of a six-link planar mechanism").

Exercise-file keys (validated by :mod:`planmethod.spec`)::

    [friction]
    f = 0.1                # friction coefficient of every pair (default 0)
    pin_radius = 0.01      # m, journal radius of every revolute pair (default: no friction
                           # circle, so no friction in revolute pairs)
    tolerance = 1e-9       # stop when no reaction changes by more than tolerance × the largest
    max_iterations = 50    # give up after this many solves (ConvergenceError)
    [friction.pairs."B"]   # per-pair overrides, keyed by point, `B:AB/BC` or `link/along`
    f = 0.15
    pin_radius = 0.012

Models. A revolute pair with reaction R and journal radius r has the friction circle of radius
ρ = f·r: the friction moment on ``on`` is −f·r·|R|·sign(ω_on − ω_from), the opposite one on
``from``. A prismatic pair with normal force N (the reaction's part ⟂ the guide) has the friction
force −f·|N|·sign(v_rel) along the guide on the slide's link at the slide point, the opposite on
its guide (the reaction couple's extra edge pressure is not modelled). Where a pair's relative
motion vanishes the sense of friction is undefined: it is taken as zero there and flagged.

Each iteration solves the frictionless problem with the friction loads of the previous
reactions as known loads (iteration 0 has none) until no reaction and no balancing moment
changes by more than ``tolerance`` times the largest reaction (times the crank length for
moments). For the small coefficients of real joints the map is a contraction and converges in a
few iterations; Umbetkulov et al. report one.

Examples
--------
>>> settings = friction_settings({"f": 0.1, "pin_radius": 0.01, "pairs": {}})
>>> settings.lookup("B", "B")
(0.1, 0.01)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import ConvergenceError
from ..kinematics.state import LinkState
from ..model import Mechanism
from ..structure import Structure
from ..vectors import dot, norm, unit_angle
from ..vocabulary import AppliedKind, PairKind
from ..words import Message, message
from .applied import REST_SPEED, AppliedItem, AppliedLoads
from .group_method import GroupSolution, solve_by_groups
from .names import PairNumbers, crank_angles

__all__ = ["FrictionResult", "FrictionSettings", "friction_items", "friction_settings",
           "solve_with_friction"]


@dataclass(frozen=True, slots=True)
class FrictionSettings:
    """Coefficients and radii of the ``[friction]`` table, and the iteration's controls."""

    f: float
    pin_radius: float | None
    tolerance: float
    max_iterations: int
    pairs: Mapping[str, Mapping[str, float]]

    def lookup(self, key: str, point: str, revolute_key: str | None = None
               ) -> tuple[float, float | None]:
        """(f, pin radius) of a pair, with its per-pair overrides."""
        f, radius = self.f, self.pin_radius
        for name in (point, revolute_key, key):
            if name and name in self.pairs:
                override = self.pairs[name]
                f = override.get("f", f)
                radius = override.get("pin_radius", radius)
        return f, radius


def friction_settings(table: Mapping) -> FrictionSettings | None:
    """The settings of a parsed ``[friction]`` table (``Mechanism.friction``), None if absent."""
    if not table:
        return None
    return FrictionSettings(float(table.get("f", 0.0)), table.get("pin_radius"),
                            float(table.get("tolerance", 1e-9)),
                            int(table.get("max_iterations", 50)), dict(table.get("pairs", {})))


@dataclass(frozen=True, slots=True)
class FrictionResult:
    """The converged solve: the group solution, the friction loads, the iterations each angle
    needed, the largest change at each iteration (history), and flags."""

    solution: GroupSolution
    items: tuple[AppliedItem, ...]
    iterations: np.ndarray
    history: tuple[float, ...]
    flags: tuple[Message, ...]
    losses: Mapping[str, np.ndarray]
    #: per pair with friction, the sense of the relative motion (+1, −1, 0 at rest): the
    #: friction load, and the reactions with it, jump where it changes
    senses: Mapping[str, np.ndarray] = field(default_factory=dict)


def _sense(relative: np.ndarray, rest: float) -> np.ndarray:
    return np.where(np.abs(relative) > rest, np.sign(relative), 0.0)


def _where(mask: np.ndarray, angles) -> Message:
    """Where a pair is at rest, as its flag says it: its first four crank angles."""
    if angles is None:
        return message("at some angles")
    shown = crank_angles(np.asarray(angles)[mask][:4])
    if int(mask.sum()) > 4:
        return message("at crank angle {angles}…", angles=shown)
    return message("at crank angle {angles}", angles=shown)


def friction_items(mechanism: Mechanism, states: Mapping[str, LinkState], solution: GroupSolution,
                   settings: FrictionSettings, angles=None
                   ) -> tuple[list[AppliedItem], dict, list[Message], dict]:
    """Friction moments and forces from the reactions of ``solution``: (items, power lost per
    pair, flags, sense of the relative motion per pair)."""
    drive = mechanism.drive
    crank = mechanism.links[drive.link]
    length = max(crank.length(drive.pivot, p) for p in crank.points) or 1.0
    rest_omega = REST_SPEED * abs(drive.omega)
    rest_speed = rest_omega * length
    items: list[AppliedItem] = []
    losses: dict[str, np.ndarray] = {}
    senses: dict[str, np.ndarray] = {}
    flags: list[Message] = []
    for key, reaction in solution.reactions.items():
        on, source = states[reaction.target], states[reaction.source]
        if reaction.kind is PairKind.REVOLUTE:
            pair = mechanism.revolute_at(key.partition(":")[0])
            f, radius = settings.lookup(key, key.partition(":")[0], pair.key if pair else None)
            if not f or not radius:
                continue
            relative = on.omega - source.omega
            sense = _sense(relative, rest_omega)
            moment = -f * radius * reaction.magnitude * sense
            for link, sign in ((reaction.target, 1.0), (reaction.source, -1.0)):
                items.append(AppliedItem(link, f"M_f,{key}", AppliedKind.FRICTION,
                                         moment=sign * moment))
            losses[key] = moment * relative
            senses[key] = sense
            if np.any(sense == 0):
                flags.append(message("pair {pair}: no relative rotation {where}, friction "
                                     "taken as zero there", pair=key,
                                     where=_where(sense == 0, angles)))
            continue
        slide = reaction.slide
        f, _ = settings.lookup(key, slide.point)
        if not f:
            continue
        d = unit_angle(states[slide.along].theta + slide.direction_rad)
        point = reaction.point
        v_rel = dot(on.velocity_at(point) - source.velocity_at(point), d)
        along = dot(reaction.force, d)
        normal = norm(reaction.force - along[..., None] * d)
        sense = _sense(v_rel, rest_speed)
        force = (-f * normal * sense)[..., None] * d
        items.append(AppliedItem(reaction.target, f"F_f,{key}", AppliedKind.FRICTION, point, force,
                                 label=slide.point))
        items.append(AppliedItem(reaction.source, f"F_f,{key}", AppliedKind.FRICTION, point, -force,
                                 label=slide.point))
        losses[key] = dot(force, d) * v_rel
        senses[key] = sense
        if np.any(sense == 0):
            flags.append(message("pair {pair}: no relative sliding {where}, friction taken "
                                 "as zero there", pair=PairNumbers(slide.link, slide.along),
                                 where=_where(sense == 0, angles)))
    return items, losses, flags, senses


def solve_with_friction(mechanism: Mechanism, structure: Structure,
                        states: Mapping[str, LinkState], applied: AppliedLoads,
                        settings: FrictionSettings, *, angles=None) -> FrictionResult:
    """Iterate: reactions → friction loads → reactions, until nothing changes.

    Raises
    ------
    ConvergenceError
        If ``max_iterations`` solves do not bring the change below the tolerance (the message
        says how far it stopped and at which crank angle).
    """
    drive = mechanism.drive
    crank = mechanism.links[drive.link]
    length = max(crank.length(drive.pivot, p) for p in crank.points) or 1.0
    solution = solve_by_groups(mechanism, structure, states, applied, angles=angles)
    count = applied.count
    iterations = np.zeros(count, dtype=int)
    done = np.zeros(count, dtype=bool)
    history: list[float] = []
    items: list[AppliedItem] = []
    losses: dict = {}
    senses: dict = {}
    flags: list[Message] = []
    for iteration in range(1, settings.max_iterations + 1):
        items, losses, flags, senses = friction_items(mechanism, states, solution, settings,
                                               angles)
        if not items:
            return FrictionResult(solution, (), iterations, (0.0,), tuple(flags), losses,
                                  senses)
        updated = solve_by_groups(mechanism, structure, states, applied.with_items(items),
                                  angles=angles)
        scale = np.max(np.stack([r.magnitude for r in updated.reactions.values()]), axis=0)
        scale = np.maximum(scale, 1e-300)
        change = np.zeros(count)
        for key, reaction in updated.reactions.items():
            change = np.maximum(change, norm(reaction.force - solution.reactions[key].force))
            if reaction.moment is not None:
                change = np.maximum(change, np.abs(reaction.moment
                                                   - solution.reactions[key].moment) / length)
        change = np.maximum(change, np.abs(updated.balancing_moment
                                           - solution.balancing_moment) / length)
        relative = change / scale
        history.append(float(relative.max()))
        newly = ~done & (relative <= settings.tolerance)
        iterations[newly] = iteration
        done |= newly
        solution = updated
        if np.all(done):  # the loads that gave this solution are returned with it
            return FrictionResult(solution, tuple(items), iterations, tuple(history),
                                  tuple(flags), losses, senses)
    index = int(np.flatnonzero(~done)[0])
    angle = None if angles is None else float(np.asarray(angles)[index])
    raise ConvergenceError(
        message("the friction iteration did not converge in {count} iterations: the "
                "reactions still change by {change:.3g} of the largest (tolerance "
                "{tolerance:g})", count=settings.max_iterations, change=history[-1],
                tolerance=settings.tolerance),
        residual=history[-1], angle=angle, link=", ".join(mechanism.moving_links))
