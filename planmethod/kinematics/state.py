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

import functools
from dataclasses import dataclass, field

import numpy as np

__all__ = ["LinkState", "cross", "norm", "perp", "rotate", "unit", "unit_angle"]

# Row vectors times these 2 × 2 matrices: one vectorised call instead of a stack of columns
# (the solver's hot path; the products are exact: each entry is ±1 or 0).
_TURN = np.array([[0.0, 1.0], [-1.0, 0.0]])


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of a × b for arrays of 2-vectors."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def perp(a: np.ndarray) -> np.ndarray:
    """a turned by +90° (counter-clockwise): J·a."""
    return np.asarray(a, dtype=float) @ _TURN


def norm(a: np.ndarray) -> np.ndarray:
    x, y = a[..., 0], a[..., 1]
    return np.sqrt(x * x + y * y)  # hypot is 10× slower; lengths here never over/underflow


def unit(a: np.ndarray) -> np.ndarray:
    return a / norm(a)[..., None]


def unit_angle(theta: np.ndarray) -> np.ndarray:
    """Unit vectors at angles ``theta`` (rad)."""
    theta = np.asarray(theta, dtype=float)
    out = np.empty((*theta.shape, 2))
    np.cos(theta, out=out[..., 0])
    np.sin(theta, out=out[..., 1])
    return out


@functools.lru_cache(maxsize=4096)
def _turn_matrix(x: float, y: float) -> np.ndarray:
    matrix = np.array([[x, y], [-y, x]])
    matrix.flags.writeable = False
    return matrix


def _turn_by(axes: np.ndarray, local) -> np.ndarray:
    """``local`` (2,) turned onto the unit vectors ``axes`` = (cos θ, sin θ) (N, 2)."""
    x, y = local
    return axes @ _turn_matrix(float(x), float(y))


def _complex(a: np.ndarray) -> np.ndarray:
    """A float array (..., 2) seen as complex numbers x + iy (...) — no copy when contiguous."""
    return np.ascontiguousarray(a, dtype=float).view(np.complex128)[..., 0]


def _real(z: np.ndarray) -> np.ndarray:
    """Complex numbers (...) as a float array (..., 2)."""
    return z[..., None].view(np.float64)


def rotate(local, theta: np.ndarray, axes: np.ndarray | None = None) -> np.ndarray:
    """A local vector (2,) or (N, 2) turned by ``theta`` (N,); ``axes`` (cos θ, sin θ) may be
    passed when known."""
    local = np.asarray(local, dtype=float)
    if local.ndim == 1 and np.ndim(theta) == 1:
        return _turn_by(unit_angle(theta) if axes is None else axes, local)
    c, s = (np.cos(theta), np.sin(theta)) if axes is None else (axes[..., 0], axes[..., 1])
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
            return self.origin + _turn_by(self.axes(), local)
        local = np.asarray(local, dtype=float)
        if local.ndim == 1 and np.ndim(self.theta) == 1:
            return self.origin + _turn_by(self.axes(), local)
        return self.origin + rotate(local, self.theta)

    def to_local(self, position: np.ndarray) -> np.ndarray:
        """Local coordinates of the link's material point now at ``position``."""
        return rotate(position - self.origin, -self.theta)

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
