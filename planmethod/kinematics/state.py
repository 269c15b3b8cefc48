"""Vector helpers and the state of a moving link (pose, ω, ε, velocity and acceleration).

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

from dataclasses import dataclass

import numpy as np

__all__ = ["LinkState", "cross", "norm", "perp", "rotate", "unit", "unit_angle"]


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of a × b for arrays of 2-vectors."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def perp(a: np.ndarray) -> np.ndarray:
    """a turned by +90° (counter-clockwise): J·a."""
    return np.stack((-a[..., 1], a[..., 0]), axis=-1)


def norm(a: np.ndarray) -> np.ndarray:
    return np.hypot(a[..., 0], a[..., 1])


def unit(a: np.ndarray) -> np.ndarray:
    return a / norm(a)[..., None]


def unit_angle(theta: np.ndarray) -> np.ndarray:
    """Unit vectors at angles ``theta`` (rad)."""
    return np.stack((np.cos(theta), np.sin(theta)), axis=-1)


def rotate(local, theta: np.ndarray) -> np.ndarray:
    """A local vector (2,) or (N, 2) turned by ``theta`` (N,)."""
    local = np.asarray(local, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    x, y = local[..., 0], local[..., 1]
    return np.stack((c * x - s * y, s * x + c * y), axis=-1)


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

    def place(self, local) -> np.ndarray:
        """Global position of the link's point with local coordinates ``local``."""
        return self.origin + rotate(local, self.theta)

    def to_local(self, position: np.ndarray) -> np.ndarray:
        """Local coordinates of the link's material point now at ``position``."""
        return rotate(position - self.origin, -self.theta)

    def velocity_at(self, position: np.ndarray) -> np.ndarray:
        """Velocity of the link's material point now at ``position``."""
        return self.velocity + self.omega[..., None] * perp(position - self.origin)

    def acceleration_at(self, position: np.ndarray) -> np.ndarray:
        """Acceleration of the link's material point now at ``position``."""
        r = position - self.origin
        return (self.acceleration + self.epsilon[..., None] * perp(r)
                - (self.omega ** 2)[..., None] * r)

    def take(self, index) -> LinkState:
        """The state at some of the angles (``index`` into the leading axis)."""
        def pick(array):
            return None if array is None else array[index]
        return LinkState(pick(self.theta), pick(self.origin), pick(self.omega),
                         pick(self.velocity), pick(self.epsilon), pick(self.acceleration))
