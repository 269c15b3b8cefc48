"""Generic constraint equations Φ(q) = 0 of links and pairs, their Jacobian and the γ term.

Each link has coordinates q = (x, y, θ): the global position of its frame's origin and the
angle of its +x axis. A revolute pair at point P between links i and j gives two rows
r_i + R_i·p_i − r_j − R_j·p_j = 0; a prismatic pair gives θ_link − θ_along − direction = 0 and
n·(S − T) = 0 (the slide point on the guide line). Velocities solve Φ_q·q̇ = −Φ_known·q̇_known
and accelerations Φ_q·q̈ = γ − Φ_known·q̈_known exactly.

This is the machinery for class III groups (Newton on positions), for the whole-mechanism
force system (Φ_qᵀ·λ gives the reactions), and an independent check of the closed-form dyads.

Examples
--------
>>> import numpy as np
>>> from planmethod.spec import load_exercise
>>> from planmethod.kinematics import solve
>>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
>>> motion = solve(exercise.mechanism)
>>> system = ConstraintSystem.between(exercise.mechanism, ["BC", "slider"])
>>> float(np.abs(system.residual(motion.links)).max()) < 1e-15
True
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..model import Mechanism, Slide
from ..vectors import dot, perp, rotate, unit_angle
from ..vocabulary import PairKind
from .state import LinkState

__all__ = ["Constraint", "ConstraintSystem"]


@dataclass(frozen=True, slots=True)
class Constraint:
    """A revolute pair (``point`` joining ``first`` and ``second``) or a prismatic ``slide``."""

    kind: PairKind
    point: str
    first: str
    second: str
    slide: Slide | None = None

    @property
    def rows(self) -> int:
        return 2

    @property
    def label(self) -> str:
        return self.point if self.kind is PairKind.REVOLUTE else self.slide.key


@dataclass(frozen=True)
class ConstraintSystem:
    """Constraints among ``links``: the unknowns are (x, y, θ) of each link in ``unknown``."""

    mechanism: Mechanism
    constraints: tuple[Constraint, ...]
    unknown: tuple[str, ...]

    @classmethod
    def between(cls, mechanism: Mechanism, unknown: Sequence[str],
                known: Iterable[str] | None = None) -> ConstraintSystem:
        """The pairs of the ``unknown`` links with each other and with ``known`` links (default:
        every other link). A point shared by k links gives k − 1 revolute pairs."""
        unknown = tuple(unknown)
        allowed = set(unknown) | (set(mechanism.links) if known is None else set(known))
        constraints: list[Constraint] = []
        for pair in mechanism.revolutes:
            members = [link for link in pair.links if link in allowed]
            if not any(link in unknown for link in members) or len(members) < 2:
                continue
            anchor = next((link for link in members if link not in unknown), members[0])
            for link in members:
                if link != anchor and (link in unknown or anchor in unknown):
                    constraints.append(Constraint(PairKind.REVOLUTE, pair.point, link, anchor))
        for slide in mechanism.slides:
            ends = (slide.link, slide.along)
            if all(end in allowed for end in ends) and any(end in unknown for end in ends):
                constraints.append(Constraint(PairKind.PRISMATIC, slide.point, slide.link,
                                              slide.along, slide))
        return cls(mechanism, tuple(constraints), unknown)

    @property
    def size(self) -> tuple[int, int]:
        """(rows, unknowns)."""
        return 2 * len(self.constraints), 3 * len(self.unknown)

    def column(self, link: str) -> int | None:
        return 3 * self.unknown.index(link) if link in self.unknown else None

    # -- evaluation -----------------------------------------------------------------------------
    def _parts(self, constraint: Constraint, states: Mapping[str, LinkState]):
        m = self.mechanism
        if constraint.kind is PairKind.REVOLUTE:
            first, second = states[constraint.first], states[constraint.second]
            p1 = rotate(m.local(constraint.first, constraint.point), first.theta)
            p2 = rotate(m.local(constraint.second, constraint.point), second.theta)
            return first, second, p1, p2
        slide = constraint.slide
        mover, guide = states[slide.link], states[slide.along]
        s = rotate(m.local(slide.link, slide.point), mover.theta)
        t = rotate(m.local(slide.along, slide.through), guide.theta)
        return mover, guide, s, t

    def residual(self, states: Mapping[str, LinkState]) -> np.ndarray:
        """Φ at the states' poses, shape (N, rows)."""
        rows = []
        for constraint in self.constraints:
            first, second, p1, p2 = self._parts(constraint, states)
            if constraint.kind is PairKind.REVOLUTE:
                gap = first.origin + p1 - second.origin - p2
                rows += [gap[..., 0], gap[..., 1]]
            else:
                slide = constraint.slide
                turn = first.theta - second.theta - slide.direction_rad
                rows.append(np.angle(np.exp(1j * turn)))
                d = unit_angle(second.theta + slide.direction_rad)
                rows.append(dot(perp(d), first.origin + p1 - second.origin - p2))
        return np.stack(rows, axis=-1)

    def jacobian(self, states: Mapping[str, LinkState]) -> tuple[np.ndarray, np.ndarray]:
        """(Φ_q for the unknown links (N, rows, 3u), Φ_q·q̇ of the known links (N, rows))
        — the second needs the known links' velocities; it is zero where they are None."""
        count = next(iter(states.values())).theta.shape[0]
        rows, cols = self.size
        matrix = np.zeros((count, rows, cols))
        known_rate = np.zeros((count, rows))
        for index, constraint in enumerate(self.constraints):
            r = 2 * index
            first, second, p1, p2 = self._parts(constraint, states)
            if constraint.kind is PairKind.REVOLUTE:
                blocks = ((constraint.first, first, 1.0, perp(p1)),
                          (constraint.second, second, -1.0, perp(p2)))
                for link, state, sign, lever in blocks:
                    column = self.column(link)
                    if column is not None:
                        matrix[:, r, column] = sign
                        matrix[:, r + 1, column + 1] = sign
                        matrix[:, r:r + 2, column + 2] = sign * lever
                    elif state.velocity is not None:
                        known_rate[:, r:r + 2] += sign * (state.velocity
                                                          + state.omega[..., None] * lever)
                continue
            slide = constraint.slide
            d = unit_angle(second.theta + slide.direction_rad)
            n = perp(d)
            gap = first.origin + p1 - second.origin - p2
            entries = (
                (slide.link, first, (1.0, None), (n, dot(n, perp(p1)))),
                (slide.along, second, (-1.0, None), (-n, -dot(d, gap) - dot(n, perp(p2)))),
            )
            for link, state, (turn, _), (along_r, along_theta) in entries:
                column = self.column(link)
                if column is not None:
                    matrix[:, r, column + 2] = turn
                    matrix[:, r + 1, column:column + 2] = along_r
                    matrix[:, r + 1, column + 2] = along_theta
                elif state.velocity is not None:
                    known_rate[:, r] += turn * state.omega
                    known_rate[:, r + 1] += dot(along_r, state.velocity) + (
                        along_theta * state.omega)
        return matrix, known_rate

    def gamma(self, states: Mapping[str, LinkState]) -> np.ndarray:
        """γ with Φ_q·q̈ = γ over *all* links (unknown and known), shape (N, rows); needs
        every link's ω and origin velocity in ``states``."""
        rows = []
        for constraint in self.constraints:
            first, second, p1, p2 = self._parts(constraint, states)
            if constraint.kind is PairKind.REVOLUTE:
                g = ((first.omega ** 2)[..., None] * p1 - (second.omega ** 2)[..., None] * p2)
                rows += [g[..., 0], g[..., 1]]
                continue
            slide = constraint.slide
            d = unit_angle(second.theta + slide.direction_rad)
            n = perp(d)
            gap = first.origin + p1 - second.origin - p2
            v_s = first.velocity + first.omega[..., None] * perp(p1)
            v_t = second.velocity + second.omega[..., None] * perp(p2)
            wa, wl = second.omega, first.omega
            rest = (-(wa ** 2) * dot(n, gap) + 2 * wa * dot(-d, v_s - v_t)
                    + dot(n, -(wl ** 2)[..., None] * p1 + (wa ** 2)[..., None] * p2))
            rows += [np.zeros_like(wa), -rest]
        return np.stack(rows, axis=-1)

    def known_acceleration_term(self, states: Mapping[str, LinkState]) -> np.ndarray:
        """Φ_known·q̈_known (N, rows) from the known links' ε and origin accelerations."""
        accelerated = {name: LinkState(s.theta, s.origin, s.epsilon, s.acceleration)
                       for name, s in states.items() if s.acceleration is not None}
        for link in self.unknown:
            state = states[link]
            accelerated[link] = LinkState(state.theta, state.origin,
                                          np.zeros_like(state.theta),
                                          np.zeros_like(state.origin))
        return self.jacobian(accelerated)[1]

    # -- solves ---------------------------------------------------------------------------------
    def velocities(self, states: Mapping[str, LinkState]) -> np.ndarray:
        """q̇ of the unknown links (N, 3u) from the known links' motion."""
        matrix, known = self.jacobian(states)
        return np.linalg.solve(matrix, -known[..., None])[..., 0]

    def accelerations(self, states: Mapping[str, LinkState]) -> np.ndarray:
        """q̈ of the unknown links (N, 3u); ``states`` must hold every link's velocity."""
        matrix, _ = self.jacobian(states)
        rhs = self.gamma(states) - self.known_acceleration_term(states)
        return np.linalg.solve(matrix, rhs[..., None])[..., 0]

    def moving_states(self, states: Mapping[str, LinkState], level: int = 2
                      ) -> dict[str, LinkState]:
        """The unknown links' states with ω and origin velocity (``level`` ≥ 1) and ε and
        origin acceleration (``level`` 2) by the exact linear solves; ``states`` holds every
        link's pose and the known links' motion (velocities, and accelerations for level 2)."""
        states = dict(states)

        def column(values, index, width=1):
            part = values[:, index] if width == 1 else values[:, index:index + width]
            return np.ascontiguousarray(part)

        if level >= 1:
            rates = self.velocities(states)
            for index, link in enumerate(self.unknown):
                states[link] = states[link].moving(column(rates, 3 * index + 2),
                                                   column(rates, 3 * index, 2))
        if level >= 2:
            second = self.accelerations(states)
            for index, link in enumerate(self.unknown):
                state = states[link]
                states[link] = state.moving(state.omega, state.velocity,
                                            column(second, 3 * index + 2),
                                            column(second, 3 * index, 2))
        return {link: states[link] for link in self.unknown}
