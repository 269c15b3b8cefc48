"""Planar vectors on numpy arrays: the one place the package's vector arithmetic is written.

Every function takes a vector's coordinates from the last axis, so the same call serves one
vector (2,), one per crank angle (N, 2), or one per copy and angle (M, N, 2). The tracer's
symbolic :class:`planmethod.kinematics.algebra.Vec` is its own type and does not use these.

Examples
--------
>>> import numpy as np
>>> a, b = np.array([3.0, 4.0]), np.array([0.0, 1.0])
>>> float(cross(a, b)), float(dot(a, b)), float(norm(a))
(3.0, 4.0, 5.0)
>>> perp(a), unit(a)
(array([-4.,  3.]), array([0.6, 0.8]))
>>> rotate(a, np.pi / 2).round(12)
array([-4.,  3.])
"""

from __future__ import annotations

import functools
import math

import numpy as np

__all__ = ["angle_deg", "cross", "dot", "norm", "perp", "rotate", "turn_onto", "unit",
           "unit_angle", "unit_or_zero"]

# Row vectors times this 2 × 2 matrix turn them by +90°: one vectorised call instead of a stack
# of columns (the solver's hot path; the products are exact: each entry is ±1 or 0).
_TURN = np.array([[0.0, 1.0], [-1.0, 0.0]])


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z-component of a × b.

    >>> float(cross(np.array([1.0, 0.0]), np.array([0.0, 2.0])))
    2.0
    """
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a · b.

    >>> float(dot(np.array([1.0, 2.0]), np.array([3.0, 4.0])))
    11.0
    """
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def perp(a: np.ndarray) -> np.ndarray:
    """a turned by +90° (counter-clockwise): J·a.

    >>> perp(np.array([1.0, 0.0]))
    array([0., 1.])
    """
    return np.asarray(a, dtype=float) @ _TURN


def norm(a: np.ndarray) -> np.ndarray:
    """|a| as √(x² + y²) (``np.hypot`` is 10× slower; lengths here never over- or underflow:
    the exercise file's limits keep them within 1e-6…1e6 m).

    >>> float(norm(np.array([3.0, 4.0])))
    5.0
    """
    x, y = a[..., 0], a[..., 1]
    return np.sqrt(x * x + y * y)


def unit(a: np.ndarray) -> np.ndarray:
    """a / |a| (a zero vector gives NaN: use :func:`unit_or_zero` where zero is possible).

    >>> unit(np.array([0.0, 2.0]))
    array([0., 1.])
    """
    return a / norm(a)[..., None]


def unit_or_zero(a: np.ndarray, length: np.ndarray | float | None = None) -> np.ndarray:
    """a / |a|, and a zero vector where |a| = 0; ``length`` may be passed when known.

    >>> unit_or_zero(np.array([[3.0, 4.0], [0.0, 0.0]]))
    array([[0.6, 0.8],
           [0. , 0. ]])
    """
    length = norm(a) if length is None else length
    return a / np.asarray(np.where(length > 0, length, 1.0))[..., None]


def unit_angle(theta: np.ndarray | float) -> np.ndarray:
    """Unit vectors at angles ``theta`` (rad): (cos θ, sin θ).

    >>> unit_angle(np.array([0.0])).round(12)
    array([[1., 0.]])
    """
    theta = np.asarray(theta, dtype=float)
    out = np.empty((*theta.shape, 2))
    np.cos(theta, out=out[..., 0])
    np.sin(theta, out=out[..., 1])
    return out


def angle_deg(a: np.ndarray) -> float:
    """The direction of one vector (2,), degrees from +x, in (−180, 180].

    >>> angle_deg(np.array([0.0, -1.0]))
    -90.0
    """
    return math.degrees(math.atan2(a[1], a[0]))


def inside_span(start, end, box) -> tuple[float, float] | None:
    """The parameters ``(low, high)`` of the part of the segment ``start + t·(end − start)``,
    0 ≤ t ≤ 1, that lies inside the box ``(x0, y0, x1, y1)``, or None where none of it does
    (Liang–Barsky clipping).

    Examples
    --------
    >>> inside_span((-5.0, 0.0), (5.0, 0.0), (0.0, -1.0, 2.0, 1.0))
    (0.5, 0.7)
    >>> inside_span((-5.0, 3.0), (5.0, 3.0), (0.0, -1.0, 2.0, 1.0)) is None
    True
    """
    (sx, sy), (ex, ey) = start, end
    dx, dy = ex - sx, ey - sy
    x0, y0, x1, y1 = box
    low, high = 0.0, 1.0
    for p, q in ((-dx, sx - x0), (dx, x1 - sx), (-dy, sy - y0), (dy, y1 - sy)):
        if p == 0:
            if q < 0:
                return None
            continue
        if p < 0:
            low = max(low, q / p)
        else:
            high = min(high, q / p)
    return (low, high) if high > low else None


@functools.lru_cache(maxsize=4096)
def _turn_matrix(x: float, y: float) -> np.ndarray:
    matrix = np.array([[x, y], [-y, x]])
    matrix.flags.writeable = False
    return matrix


def turn_onto(axes: np.ndarray, local) -> np.ndarray:
    """One local vector (2,) turned onto unit vectors ``axes`` = (cos θ, sin θ) (N, 2).

    >>> turn_onto(np.array([[0.0, 1.0]]), (2.0, 0.0))
    array([[0., 2.]])
    """
    x, y = local
    return axes @ _turn_matrix(float(x), float(y))


def rotate(local, theta: np.ndarray | float, axes: np.ndarray | None = None) -> np.ndarray:
    """A vector (2,) or (N, 2) turned by ``theta`` (rad; a number or (N,)); ``axes``
    (cos θ, sin θ) may be passed when known.

    >>> rotate(np.array([1.0, 0.0]), np.array([np.pi])).round(12)
    array([[-1.,  0.]])
    """
    local = np.asarray(local, dtype=float)
    if local.ndim == 1 and np.ndim(theta) == 1:
        return turn_onto(unit_angle(theta) if axes is None else axes, local)
    c, s = (np.cos(theta), np.sin(theta)) if axes is None else (axes[..., 0], axes[..., 1])
    x, y = local[..., 0], local[..., 1]
    return np.stack((c * x - s * y, s * x + c * y), axis=-1)
