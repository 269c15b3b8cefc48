"""The arithmetic the group kinds are written in: one formula, three kinds of number.

Every closed form in :mod:`planmethod.kinematics.groups` is written once, with the operators
and the functions of this module, over numbers that are

* Python floats (constants of the model: link lengths, local coordinates, ω1 of the drive),
* numpy arrays over the crank angles (the *direct* evaluation: the reference path, used for the
  branch choice, the plans' constructions and exact error checks), or
* :class:`~planmethod.kinematics.tracing.Traced` values, which record each operation instead of
  doing it (the *traced* evaluation: the formulas of a whole mechanism turned into one
  straight-line numpy function, see :mod:`planmethod.kinematics.tracing`).

Because the same expressions run in both evaluations, in the same order, the fast path and the
reference path give the same numbers.

:class:`Vec` is a plane vector of two such numbers (structure of arrays: x and y apart), and
:class:`Body` a link's pose and motion: its axes (cos θ, sin θ), origin, ω, ε and its origin's
velocity and acceleration.

Examples
--------
>>> import numpy as np
>>> crank = Body(cos=np.array([0.0]), sin=np.array([1.0]), x=0.0, y=0.0, omega=10.0)
>>> b = crank.offset(0.08, 0.0)
>>> [float(v[0]) for v in (b.x, b.y)], [float(v[0]) for v in crank.velocity(b)]
([0.0, 0.08], [-0.8, 0.0])
>>> sqrt(4.0), sqrt(np.array([9.0]))
(2.0, array([3.]))
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["Body", "Vec", "absolute", "atan2", "cos", "cross", "dot", "is_zero", "maximum",
           "minimum", "norm", "sin", "sqrt"]

Number = Any  # float | np.ndarray | Traced


def _traced(value) -> bool:
    return hasattr(value, "tracer")


def _unary(name: str, scalar: Callable, array: Callable) -> Callable[[Number], Number]:
    """The function ``name`` of one number: ``scalar`` on a Python number, recorded on a traced
    value, ``array`` on an array."""

    def function(value: Number) -> Number:
        """The function of a float, an array or a traced value (recorded)."""
        if isinstance(value, float | int):
            return scalar(value)
        if _traced(value):
            return value.tracer.apply(name, value)
        return array(value)

    function.__name__ = array.__name__
    return function


def _binary(name: str, scalar: Callable, array: Callable) -> Callable[[Number, Number], Number]:
    """The function ``name`` of two numbers (see :func:`_unary`): recorded where either is
    traced."""

    def function(a: Number, b: Number) -> Number:
        """The function of floats, arrays or traced values (recorded where either is)."""
        if isinstance(a, float | int) and isinstance(b, float | int):
            return scalar(a, b)
        if _traced(a) or _traced(b):
            return (a if _traced(a) else b).tracer.apply(name, a, b)
        return array(a, b)

    function.__name__ = array.__name__
    return function


sqrt = _unary("sqrt", math.sqrt, np.sqrt)
cos = _unary("cos", math.cos, np.cos)
sin = _unary("sin", math.sin, np.sin)
absolute = _unary("abs", abs, np.abs)
atan2 = _binary("arctan2", math.atan2, np.arctan2)
maximum = _binary("maximum", max, np.maximum)
minimum = _binary("minimum", min, np.minimum)


def is_zero(value: Number) -> bool:
    """Whether ``value`` is the constant zero (a float 0; never an array or a traced value)."""
    return isinstance(value, float | int) and value == 0


class Vec:
    """A plane vector (x, y) of numbers (floats, arrays or traced values)."""

    __slots__ = ("x", "y")

    def __init__(self, x: Number, y: Number) -> None:
        self.x, self.y = x, y

    def __add__(self, other: Vec) -> Vec:
        return Vec(self.x + other.x, self.y + other.y)

    def __sub__(self, other: Vec) -> Vec:
        return Vec(self.x - other.x, self.y - other.y)

    def __neg__(self) -> Vec:
        return Vec(-self.x, -self.y)

    def __mul__(self, factor: Number) -> Vec:
        return Vec(self.x * factor, self.y * factor)

    __rmul__ = __mul__

    def __truediv__(self, divisor: Number) -> Vec:
        return Vec(self.x / divisor, self.y / divisor)

    def perp(self) -> Vec:
        """The vector turned by +90°: J·v = (−y, x)."""
        return Vec(-self.y, self.x)

    def turned(self, c: Number, s: Number) -> Vec:
        """The vector turned by the angle whose cosine and sine are ``c``, ``s``."""
        return Vec(self.x * c - self.y * s, self.x * s + self.y * c)

    def __iter__(self):
        return iter((self.x, self.y))

    def __repr__(self) -> str:
        return f"Vec({self.x!r}, {self.y!r})"


def dot(a: Vec, b: Vec) -> Number:
    return a.x * b.x + a.y * b.y


def cross(a: Vec, b: Vec) -> Number:
    """z-component of a × b."""
    return a.x * b.y - a.y * b.x


def norm(a: Vec) -> Number:
    return sqrt(a.x * a.x + a.y * a.y)


class Body:
    """A link's pose and motion: its axes (``cos``, ``sin``) = (cos θ, sin θ), its origin
    (``x``, ``y``), its angular velocity ``omega`` and acceleration ``epsilon``, its origin's
    velocity (``vx``, ``vy``) and acceleration (``ax``, ``ay``). Motion not (yet) known is zero;
    the frame is all constants. (Mutable: a group kind fills a body's motion in stage by stage.)
    """

    __slots__ = ("ax", "ay", "cos", "epsilon", "omega", "sin", "vx", "vy", "x", "y")

    def __init__(self, cos: Number = 1.0, sin: Number = 0.0, x: Number = 0.0, y: Number = 0.0,
                 omega: Number = 0.0, vx: Number = 0.0, vy: Number = 0.0,
                 epsilon: Number = 0.0, ax: Number = 0.0, ay: Number = 0.0) -> None:
        self.cos, self.sin, self.x, self.y = cos, sin, x, y
        self.omega, self.vx, self.vy = omega, vx, vy
        self.epsilon, self.ax, self.ay = epsilon, ax, ay

    @property
    def origin(self) -> Vec:
        return Vec(self.x, self.y)

    def offset(self, lx: float, ly: float) -> Vec:
        """The local vector (lx, ly) turned onto the link's axes (a point's offset from the
        origin)."""
        return Vec(lx, ly).turned(self.cos, self.sin)

    def point(self, lx: float, ly: float) -> Vec:
        """Global position of the link's point with local coordinates (lx, ly)."""
        return self.origin + self.offset(lx, ly)

    def velocity(self, r: Vec) -> Vec:
        """Velocity of the link's material point at offset ``r`` from the origin:
        v + ω·J·r."""
        return Vec(self.vx - self.omega * r.y, self.vy + self.omega * r.x)

    def acceleration(self, r: Vec) -> Vec:
        """Acceleration of the material point at offset ``r``: a + ε·J·r − ω²·r."""
        square = self.omega * self.omega
        return Vec(self.ax - self.epsilon * r.y - square * r.x,
                   self.ay + self.epsilon * r.x - square * r.y)
