"""The state of a moving link (pose, ω, ε, velocity and acceleration).

All arrays carry the crank angles on the leading axis: scalars have shape (N,), vectors (N, 2).

Examples
--------
>>> import numpy as np
>>> state = LinkState(theta=np.array([np.pi / 2]), origin=np.zeros((1, 2)),
...                   omega=np.array([2.0]), velocity=np.zeros((1, 2)))
>>> state.place((1.0, 0.0)).round(12)
array([[0., 1.]])
>>> state.velocity_at(state.place((1.0, 0.0))).round(12)
array([[-2.,  0.]])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..vectors import rotate, turn_onto, unit_angle

__all__ = ["LinkState"]


def _complex(a: np.ndarray) -> np.ndarray:
    """A float array (..., 2) seen as complex numbers x + iy (...) — no copy when contiguous."""
    return np.ascontiguousarray(a, dtype=float).view(np.complex128)[..., 0]


def _real(z: np.ndarray) -> np.ndarray:
    """Complex numbers (...) as a float array (..., 2)."""
    return z[..., None].view(np.float64)


@dataclass(frozen=True, slots=True)
class LinkState:
    """Pose and motion of one link over N crank angles.

    ``origin`` is the global position of the link frame's origin and ``theta`` the global angle
    of its +x axis; ``velocity`` and ``acceleration`` are those of the origin (as a point of the
    link). Motion fields are None until that stage has been solved.
    """

    theta: np.ndarray
    origin: np.ndarray
    omega: np.ndarray | None = None
    velocity: np.ndarray | None = None
    epsilon: np.ndarray | None = None
    acceleration: np.ndarray | None = None
    #: (cos θ, sin θ), shape (N, 2): computed once, on first use (see :meth:`axes`)
    basis: np.ndarray | None = field(default=None, repr=False, compare=False)

    def axes(self) -> np.ndarray:
        """The unit vector of the link's +x axis at each angle, (cos θ, sin θ), computed once."""
        if self.basis is None:
            object.__setattr__(self, "basis", unit_angle(self.theta))
        return self.basis

    def place(self, local) -> np.ndarray:
        """Global position of the link's point with local coordinates ``local``."""
        if isinstance(local, tuple) and len(local) == 2 and np.ndim(self.theta) == 1:
            if local[0] == 0 and local[1] == 0:
                return self.origin.copy()
            return self.origin + turn_onto(self.axes(), local)
        local = np.asarray(local, dtype=float)
        if local.ndim == 1 and np.ndim(self.theta) == 1:
            return self.origin + turn_onto(self.axes(), local)
        return self.origin + rotate(local, self.theta)

    def moving(self, omega=None, velocity=None, epsilon=None, acceleration=None) -> LinkState:
        """The same pose with motion fields set (the cached axes are kept)."""
        return LinkState(self.theta, self.origin, omega, velocity, epsilon, acceleration,
                         self.basis)

    def velocity_at(self, position: np.ndarray) -> np.ndarray:
        """Velocity of the link's material point now at ``position``: v + ω·J·r."""
        # complex form, r·(iω): one vectorised product instead of a stack of columns
        turn = _complex(position - self.origin) * (1j * self.omega)
        return self.velocity + _real(turn)

    def acceleration_at(self, position: np.ndarray) -> np.ndarray:
        """Acceleration of the link's material point now at ``position``: a + ε·J·r − ω²·r."""
        factor = self.epsilon * 1j - self.omega * self.omega
        return self.acceleration + _real(_complex(position - self.origin) * factor)

    def take(self, index) -> LinkState:
        """The state at some of the angles (``index`` into the leading axis)."""
        def pick(array):
            return None if array is None else array[index]
        return LinkState(pick(self.theta), pick(self.origin), pick(self.omega),
                         pick(self.velocity), pick(self.epsilon), pick(self.acceleration),
                         pick(self.basis))
