"""The dyads' closed forms, compiled once per mechanism and evaluated on plain x/y arrays.

:func:`planmethod.kinematics.solve` spends most of a small solve in Python, not in arithmetic:
reading the model, building each group's construction, choosing branches. This module does that
work once per mechanism (:func:`program`, remembered for the last few models by identity) and
then evaluates each dyad's positions, velocities and accelerations with the same formulas as
:mod:`planmethod.kinematics.dyads` and :func:`~planmethod.kinematics.solve.solve`'s vector
equations, on separate x and y arrays, skipping the terms that vanish by construction (a frame
point does not move, a pin at a link's origin has no lever arm, a zero local coordinate adds
nothing), and writing each link's origin, axes, velocity and acceleration straight into its
result arrays (a :class:`Target`). The RRR, RRP and RPR dyads run all their stages as
straight-line code on local variables (:meth:`_Dyad.evaluate`); the others place their sides
(:class:`Side`) for the generic vector equations. Results are those of the reference formulas
to rounding.

Checks stay exact: each group tests, in a few reductions over all angles, whether any angle
comes close to a position the reference code would refuse (links that cannot reach, a toggle,
coinciding pins, parallel guides); if one might, the reference :func:`~planmethod.kinematics.
dyads.dyad_positions` is run on that group to raise its error with the same angle, link and
message (or, when it does not raise, the compiled values stand).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> mechanism = load_exercise("exercises/compressor_slider_crank.toml").mechanism
>>> compiled = program(mechanism)
>>> compiled is program(mechanism), [str(group.kind) for group in compiled.structure.groups]
(True, ['RRP'])
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict

import numpy as np

from ..errors import ToggleError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Structure, analyse_structure
from .dyads import ROUNDING_UNITS, TOGGLE_SINE, dyad_positions
from .state import LinkState

__all__ = ["Evaluated", "Program", "Target", "Values", "program"]

#: how many models' compiled programs are remembered (by identity, most recent first)
CACHE_SIZE = 32
_PROGRAMS: OrderedDict[int, Program] = OrderedDict()
_LOCK = threading.Lock()
#: |vanishing factor| within this of zero (relative) is a toggle: see dyads._toggle_or_miss
_TOLERANCE = ROUNDING_UNITS * float(np.finfo(float).eps)
#: constant arrays (see :meth:`Program.constant`) are kept for solves of at most this many angles
#: (where making them costs as much as their arithmetic), and for so many counts per model
CONSTANT_COUNT = 2048
CONSTANT_KEYS = 16
#: the bounds over all angles are widened by this factor, so that the rounding of a bound
#: never hides an angle the reference check would refuse
_MARGIN = 1.0 + 1e-9


def program(mechanism: Mechanism) -> Program:
    """The compiled program of ``mechanism`` (one per model object, remembered)."""
    key = id(mechanism)
    with _LOCK:
        found = _PROGRAMS.get(key)
        if found is not None and found.mechanism is mechanism:
            _PROGRAMS.move_to_end(key)
            return found
        found = _PROGRAMS[key] = Program(mechanism)
        while len(_PROGRAMS) > CACHE_SIZE:
            _PROGRAMS.popitem(last=False)
        return found


class Program:
    """What a solve needs from the model, read once: the structure, each dyad's constants and
    the branch choice."""

    def __init__(self, mechanism: Mechanism) -> None:
        self.mechanism = mechanism
        self._structure: Structure | None = None
        self._dyads: dict[int, tuple[AssurGroup, _Dyad]] = {}
        self._branches: dict[tuple, tuple[Structure, dict]] = {}
        self._owners: dict[str, tuple[str, ...]] = {}
        self._carriers: dict[str, tuple] = {}
        self._remembered: dict[str, object] = {}
        self._locals: dict[tuple[str, str], tuple[float, float]] = {}
        self._constants: dict[tuple, object] = {}
        drive = mechanism.drive
        self.pivot = _local(mechanism, FRAME, drive.pivot)
        self.pivot_local = _local(mechanism, drive.link, drive.pivot)
        self.omega = float(drive.omega)
        self.epsilon = float(drive.epsilon)

    def local(self, link: str, point: str) -> tuple[float, float]:
        """``mechanism.local(link, point)`` as floats, remembered."""
        key = (link, point)
        found = self._locals.get(key)
        if found is None:
            found = self._locals[key] = _local(self.mechanism, link, point)
        return found

    def constant(self, key: tuple, count: int, make):
        """``make()``: arrays over ``count`` angles that are the same at every solve (the frame
        at rest, the drive's ω and ε, a frame point's position), made read-only by ``make``
        and kept per ``key`` for small counts (made anew for large ones)."""
        if count > CONSTANT_COUNT:
            return make()
        found = self._constants.get(key)
        if found is None:
            if len(self._constants) >= CONSTANT_KEYS:
                self._constants.clear()
            found = self._constants[key] = make()
        return found

    def remember(self, key: str, make):
        """``make()``, made once and remembered under ``key`` (what a solve of the whole model
        needs besides the angles)."""
        found = self._remembered.get(key)
        if found is None:
            found = self._remembered[key] = make()
        return found

    def owners(self, point: str) -> tuple[str, ...]:
        """``mechanism.links_with_point(point)``, remembered."""
        found = self._owners.get(point)
        if found is None:
            found = self._owners[point] = self.mechanism.links_with_point(point)
        return found

    def carriers(self, point: str) -> tuple[tuple[str, tuple[float, float]], ...]:
        """Each link carrying ``point`` (as :meth:`owners`) with the point's local coordinates
        on it, remembered."""
        found = self._carriers.get(point)
        if found is None:
            found = self._carriers[point] = tuple((link, self.local(link, point))
                                                  for link in self.owners(point))
        return found

    @property
    def structure(self) -> Structure:
        if self._structure is None:
            self._structure = analyse_structure(self.mechanism)
        return self._structure

    def dyad(self, group: AssurGroup) -> _Dyad:
        """The compiled dyad of ``group``."""
        found = self._dyads.get(id(group))
        if found is not None and found[0] is group:
            return found[1]
        if len(self._dyads) > 64:
            self._dyads.clear()
        compiled = _COMPILERS[group.kind](self.mechanism, group)
        self._dyads[id(group)] = (group, compiled)
        return compiled

    def branches(self, structure: Structure, groups, choose) -> dict:
        """``choose(mechanism, structure, groups)``, remembered per structure and groups."""
        key = (id(structure), tuple(group.index for group in groups))
        found = self._branches.get(key)
        if found is not None and found[0] is structure:
            return found[1]
        chosen = choose(self.mechanism, structure, groups)
        if len(self._branches) > 64:
            self._branches.clear()
        self._branches[key] = (structure, chosen)
        return chosen


# -- one link's values ---------------------------------------------------------------------------
class Values:
    """A link's pose and motion as x/y arrays (or plain floats for constants).

    ``c``, ``s`` are cos θ and sin θ; ``x``, ``y`` the origin; ``w`` the angular velocity used in
    arithmetic (a float for the drive, None for a link that does not turn) and ``omega`` its
    array; ``vx``, ``vy``, ``ax``, ``ay`` the origin's velocity and acceleration, None where
    identically zero; ``e`` and ``epsilon`` the angular acceleration; ``fixed`` for the frame.
    """

    __slots__ = ("ax", "ay", "c", "e", "epsilon", "fixed", "omega", "s", "theta", "vx", "vy",
                 "w", "x", "y")

    def __init__(self, theta, c, s, x, y, fixed: bool = False) -> None:
        self.theta, self.c, self.s, self.x, self.y, self.fixed = theta, c, s, x, y, fixed
        self.w = self.omega = self.vx = self.vy = None
        self.e = self.epsilon = self.ax = self.ay = None

    @classmethod
    def of(cls, state: LinkState) -> Values:
        """The values of a solved :class:`LinkState` (class III groups)."""
        axes = state.axes()
        values = cls(state.theta, axes[:, 0], axes[:, 1], state.origin[:, 0], state.origin[:, 1])
        if state.omega is not None:
            values.w = values.omega = state.omega
            values.vx, values.vy = state.velocity[:, 0], state.velocity[:, 1]
        if state.epsilon is not None:
            values.e = values.epsilon = state.epsilon
            values.ax, values.ay = state.acceleration[:, 0], state.acceleration[:, 1]
        return values


class Target:
    """Where a link's results go: (n, 2) arrays for its origin, axes (cos θ, sin θ), velocity
    and acceleration (None for a stage not solved)."""

    __slots__ = ("acceleration", "basis", "origin", "velocity")

    def __init__(self, origin, basis, velocity=None, acceleration=None) -> None:
        self.origin, self.basis = origin, basis
        self.velocity, self.acceleration = velocity, acceleration


def put(out: np.ndarray, x, y):
    """Write x and y (arrays, floats, or None for zero) into ``out`` (n, 2); its columns."""
    if x is None:
        out.fill(0.0)
        return out[:, 0], out[:, 1]
    first, second = out[:, 0], out[:, 1]
    if type(x) is float and x == y:  # (one fill)
        out.fill(x)
    else:
        first[...] = x
        second[...] = y
    return first, second


def turn(c, s, lx: float, ly: float):
    """The local vector (lx, ly) turned by the angle with cosine ``c`` and sine ``s``, as
    ``LinkState.place`` turns it (terms with a zero coordinate left out: they add ±0)."""
    if ly == 0.0:
        return c * lx, s * lx
    if lx == 0.0:
        return s * -ly, c * ly
    return c * lx - s * ly, c * ly + s * lx


def _turn_into(out, c, s, ca: float, sa: float):
    """(c·ca − s·sa, c·sa + s·ca) written into ``out``'s columns (``turn`` with an out)."""
    first, second = out[:, 0], out[:, 1]
    if sa == 0.0:
        np.multiply(c, ca, out=first)
        np.multiply(s, ca, out=second)
    elif ca == 0.0:
        np.multiply(s, -sa, out=first)
        np.multiply(c, sa, out=second)
    else:
        np.subtract(c * ca, s * sa, out=first)
        np.add(c * sa, s * ca, out=second)
    return first, second


def place(values: Values, local, out=None):
    """(x, y, rx, ry): the global position of a link's point and its offset from the link's
    origin (rx, ry None for the origin itself); the position written into ``out`` if given."""
    lx, ly = local
    if lx == 0.0 and ly == 0.0:
        if out is None:
            return values.x, values.y, None, None
        return (*put(out, values.x, values.y), None, None)
    if out is None:
        rx, ry = turn(values.c, values.s, lx, ly)
        return values.x + rx, values.y + ry, rx, ry
    if type(values.x) is float and values.x == 0.0 and values.y == 0.0:
        # the link's origin at the global origin: the point is r, turned straight into out
        first, second = _turn_into(out, values.c, values.s, lx, ly)
        return first, second, first, second
    rx, ry = turn(values.c, values.s, lx, ly)
    return (np.add(values.x, rx, out=out[:, 0]), np.add(values.y, ry, out=out[:, 1]), rx, ry)


def velocity_at(values: Values, rx, ry, out=None):
    """Velocity of the link's material point at origin + r: v + ω·J·r (None if zero, unless
    written into ``out``)."""
    w = values.w
    if values.fixed or rx is None or w is None:  # no turning term
        if values.fixed or values.vx is None:
            return None if out is None else put(out, None, None)
        return (values.vx, values.vy) if out is None else put(out, values.vx, values.vy)
    first, second = (None, None) if out is None else (out[:, 0], out[:, 1])
    if values.vx is None:
        if isinstance(w, float):
            return np.multiply(ry, -w, out=first), np.multiply(rx, w, out=second)
        return np.negative(ry * w, out=first), np.multiply(rx, w, out=second)
    return (np.subtract(values.vx, ry * w, out=first),
            np.add(values.vy, rx * w, out=second))


def acceleration_at(values: Values, rx, ry, out=None):
    """Acceleration of the link's material point at origin + r: a + ε·J·r − ω²·r (None if zero,
    unless written into ``out``)."""
    w, e = values.w, values.e
    if values.fixed or rx is None or (w is None and e is None):
        if values.fixed or values.ax is None:
            return None if out is None else put(out, None, None)
        return (values.ax, values.ay) if out is None else put(out, values.ax, values.ay)
    first, second = (None, None) if out is None else (out[:, 0], out[:, 1])
    if values.ax is None:
        if w is None:
            return np.negative(ry * e, out=first), np.multiply(rx, e, out=second)
        normal = -(w * w)
        if isinstance(e, float) and e == 0.0:
            return np.multiply(rx, normal, out=first), np.multiply(ry, normal, out=second)
        return (np.subtract(rx * normal, ry * e, out=first),
                np.add(rx * e, ry * normal, out=second))
    if w is None:
        tx, ty = -(ry * e), rx * e
    else:
        normal = -(w * w)
        if isinstance(e, float) and e == 0.0:
            tx, ty = rx * normal, ry * normal
        else:
            tx, ty = rx * normal - ry * e, rx * e + ry * normal
    return np.add(values.ax, tx, out=first), np.add(values.ay, ty, out=second)


#: the frame's values at every solve (``solve._fixed_values``) as far as placing a point on it
#: goes: what a pin or guide of the frame is made of is the same at every solve
_AT_REST = Values(0.0, 1.0, 0.0, 0.0, 0.0, fixed=True)


def _frame_pin(known: str, local) -> tuple | None:
    """``_pin`` of a pin of the frame (None if ``known`` is not the frame), made once."""
    if known != FRAME:
        return None
    x, y, rx, ry = place(_AT_REST, local)
    return x, y, rx, ry, complex(x, y)


def _known_pin(values: Values, local, out, at_rest: tuple | None):
    """``place(values, local, out)`` of a pin of a known link; ``at_rest`` (:func:`_frame_pin`)
    when that link is the frame."""
    if at_rest is None:
        return place(values, local, out)
    if out is not None:
        put(out, at_rest[0], at_rest[1])
    return at_rest[:4]


def _pin(values: Values, local, out, count: int, at_rest: tuple | None = None):
    """``place`` of a pin, also as complex numbers: (x, y, rx, ry, x + iy), written into
    ``out`` (an (n, 2) array, allocated when None); a fixed pin's x + iy is a Python complex
    (and is written into ``out`` when given), ``at_rest`` when that was made already
    (:func:`_frame_pin`)."""
    if values.fixed:
        found = at_rest or _frame_pin(FRAME, local)
        if out is not None:
            put(out, found[0], found[1])
        return found
    if out is None:
        out = np.empty((count, 2))
    x, y, rx, ry = place(values, local, out)
    return x, y, rx, ry, out.view(np.complex128)[:, 0]


def _largest(value) -> float:
    """The largest magnitude of an array's entries (of a float: its magnitude)."""
    if isinstance(value, float):
        return abs(value)
    return float(np.abs(value).max())


def _complex_array(value, count: int) -> np.ndarray:
    """A complex constant as an array over the angles (arrays pass through)."""
    if np.ndim(value) == 0:
        out = np.empty(count, dtype=np.complex128)
        out.fill(value)
        return out
    return value


def _rotated(c, s, angle: float):
    """(cos, sin) of θ + angle from (cos θ, sin θ)."""
    if angle == 0.0:
        return c, s
    return turn(c, s, math.cos(angle), math.sin(angle))


def _norm(x, y):
    return np.sqrt(x * x + y * y)


def _array(value, count: int):
    """A constant as an array over the angles (arrays pass through)."""
    return np.full(count, value) if np.ndim(value) == 0 else value


def _local(mechanism: Mechanism, link: str, point: str) -> tuple[float, float]:
    x, y = mechanism.local(link, point)
    return float(x), float(y)


def _group_link(joint, group: AssurGroup) -> str:
    return joint.links[0] if joint.links[0] in group.links else joint.links[1]


def _alpha(first, second) -> tuple[float, float, float]:
    """The angle of second − first in a link's frame, with its cosine and sine (as
    ``dyads._pose_from_two`` subtracts it)."""
    angle = np.arctan2(second[1] - first[1], second[0] - first[0])
    return angle, float(np.cos(angle)), float(np.sin(angle))


# -- the side data the vector equations need -----------------------------------------------------
class Side:
    """One side of v_X = v_base + u·e at the solved positions (x/y arrays).

    ``base`` is the known link whose material point at the base position (offset ``rx``,
    ``ry`` from its origin) gives the base velocity; ``px``, ``py`` the base position;
    ``dx``, ``dy`` the unit direction e; for a rotation side ``link`` turns about the base
    with radius vector (``radius_x``, ``radius_y``) of length ``length``; for a sliding side
    ``link`` is the carrier whose ω gives the Coriolis term.
    """

    __slots__ = ("base", "dx", "dy", "length", "link", "px", "py", "radius_x", "radius_y",
                 "rotation", "rx", "ry")

    def __init__(self, rotation, link, base, rx, ry, px, py, dx, dy, radius_x=None,
                 radius_y=None, length=None) -> None:
        self.rotation, self.link, self.base = rotation, link, base
        self.rx, self.ry, self.px, self.py, self.dx, self.dy = rx, ry, px, py, dx, dy
        self.radius_x, self.radius_y, self.length = radius_x, radius_y, length


class Placed:
    """A dyad at its solved positions: its links' values, X, the two sides, and how each link's
    motion is referred (``refs[link]`` = (side index or None for X, r) with r = (rx, ry) the
    link's origin minus that point, None when zero); ``targets`` where its results go."""

    __slots__ = ("bound", "det", "links", "refs", "sides", "span", "targets", "xx", "xy")

    def __init__(self, links, xx, xy, sides, refs, targets, span=None, bound=None) -> None:
        self.links, self.xx, self.xy, self.sides, self.refs = links, xx, xy, sides, refs
        self.targets, self.span, self.det = targets, span, None
        #: an upper bound of the size ratio R over all angles known without R (None: unknown)
        self.bound = bound


def _pivoted(target: Target, px, py, radius_x, radius_y, alpha, local, length=None,
             internal=None):
    """A link turning about its pin P (at px, py) with its internal pin at P + radius: θ, its
    axes and origin written into ``target``, the radius' length (computed unless given) and
    unit vector; returns (θ, c, s, origin x, origin y, r, length, ux, uy), r the origin minus P
    (None if zero). ``internal``: the internal pin's (x, y) when it is the link's origin (which
    is then that pin, and r the radius)."""
    if length is None:
        length = _norm(radius_x, radius_y)
    angle, ca, sa = alpha
    theta = np.arctan2(radius_y, radius_x)
    if angle != 0.0:
        theta = theta - angle
    basis = target.basis
    if angle == 0.0:  # (cos θ, sin θ) = the unit radius
        ux = np.divide(radius_x, length, out=basis[:, 0])
        uy = np.divide(radius_y, length, out=basis[:, 1])
        c, s = ux, uy
    else:
        ux, uy = radius_x / length, radius_y / length
        if abs(angle) == math.pi:  # the unit radius reversed
            c, s = np.negative(ux, out=basis[:, 0]), np.negative(uy, out=basis[:, 1])
        else:  # the unit radius turned by −α
            c, s = _turn_into(basis, ux, uy, ca, -sa)
    if internal is None or local == (0.0, 0.0):
        ox, oy, r = _origin(target, px, py, c, s, local)
    else:
        (ox, oy), r = put(target.origin, *internal), (radius_x, radius_y)
    return theta, c, s, ox, oy, r, length, ux, uy


def _origin(target: Target, px, py, c, s, local):
    """A link's origin from its pin at (px, py) with local coordinates ``local`` (written into
    ``target.origin``; the pin is there already when ``local`` is zero): (x, y, r)."""
    if local == (0.0, 0.0):
        origin = target.origin
        return origin[:, 0], origin[:, 1], None
    tx, ty = turn(c, s, *local)
    origin = target.origin
    return (np.subtract(px, tx, out=origin[:, 0]), np.subtract(py, ty, out=origin[:, 1]),
            (np.negative(tx), np.negative(ty)))


def _basis(target: Target, c, s):
    """Axes that were computed elsewhere, copied into ``target.basis``."""
    return put(target.basis, c, s)


# -- the per-stage limits ------------------------------------------------------------------------
#: the arithmetic's resolution (unit roundoff)
EPS = float(np.finfo(float).eps)


def refuse_digitless(estimate: np.ndarray, sine: np.ndarray, angles_deg: np.ndarray,
                      stage: str, group_name: str) -> None:
    """Raise a ToggleError at the first angle whose estimated relative error reaches 1."""
    bad = ~(estimate < 1.0)
    if np.any(bad):
        index = int(np.flatnonzero(bad)[0])
        angle = float(np.degrees(np.arcsin(min(1.0, abs(float(sine[index]))))))
        raise ToggleError(
            f"toggle position: the group's two construction lines meet at {angle:.3g}°, so "
            f"close to parallel that its {stage}s would have no correct digit",
            line_angle_deg=angle, link=group_name, angle=float(angles_deg[index]))


def error_estimate(ratio, sine: np.ndarray, stage: str) -> np.ndarray:
    """ε·R/s³ (velocities) or ε·R/s⁵ (accelerations) as ``solve._condition`` computes them (R None:
    1), with products for the powers."""
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        size = np.abs(sine)
        power = size * size * size
        if stage == "acceleration":
            power = power * size * size
        return (EPS if ratio is None else EPS * ratio) / power


def stage_clear(bounds: tuple[float, float], stage: str) -> bool:
    """Whether ε·R/s^(2k+1) < 1 at the ``bounds`` (largest R, smallest |s|): the stage's limit
    holds at every angle (false for a NaN)."""
    largest, smallest = bounds
    return EPS * largest < smallest ** (3 if stage == "velocity" else 5)


def stage_limit(bounds: tuple[float, float], ratio, sine: np.ndarray, angles_deg: np.ndarray,
           stage: str, name: str) -> None:
    """The per-stage limit of ``solve._condition``: a ToggleError where ε·R/s^(2k+1) ≥ 1. Checked on
    the ``bounds`` (largest R, smallest |s|) first; the estimates only where that fails."""
    if stage_clear(bounds, stage):
        return
    refuse_digitless(error_estimate(ratio, sine, stage), sine, angles_deg, stage, name)



def check_stage(stage: str, bound: float | None, smallest: float, sine: np.ndarray, ratio,
                angles_deg: np.ndarray, name: str):
    """The stage's limit (:func:`stage_limit`) for a dyad whose lines' sine is ``sine`` (its
    smallest magnitude ``smallest``) and size ratio ``ratio`` (None: 1; a function: computed
    only when ``bound``, an upper bound of R, does not settle it).

    Returns
    -------
    object
        The ratio, computed if the check needed it.
    """
    if bound is not None and stage_clear((bound, smallest), stage):
        return ratio  # clear of the limit even at the bound of R: R is computed when read
    if callable(ratio):
        ratio = ratio()
    stage_limit((1.0 if ratio is None else float(ratio.max()), smallest), ratio, sine,
                angles_deg, stage, name)
    return ratio


# -- compiled dyads ------------------------------------------------------------------------------
class Evaluated:
    """A dyad solved up to a stage: its links' values (vectors written into their targets) and
    its record: the unknowns, the lines' sine and its size ratio R (None where 1, or a function
    that computes it when the checks did not need it)."""

    __slots__ = ("acceleration_unknowns", "bound", "line_sine", "links", "ratio", "smallest",
                 "velocity_unknowns")

    def __init__(self, links: dict, velocity_unknowns=None, line_sine=None, ratio=None,
                 acceleration_unknowns=None) -> None:
        self.links, self.velocity_unknowns, self.line_sine = links, velocity_unknowns, line_sine
        self.ratio, self.acceleration_unknowns = ratio, acceleration_unknowns

    @classmethod
    def with_velocities(cls, links: dict, unknowns, sine: np.ndarray, ratio,
                        bound: float | None, angles_deg: np.ndarray, name: str) -> Evaluated:
        """The dyad solved to velocities, the velocity stage's limit checked
        (:func:`check_stage`; ``bound``: an upper bound of R, or None)."""
        smallest = float(np.abs(sine).min())
        ratio = check_stage("velocity", bound, smallest, sine, ratio, angles_deg, name)
        evaluated = cls(links, unknowns, sine, ratio)
        evaluated.smallest, evaluated.bound = smallest, bound
        return evaluated

    def with_accelerations(self, unknowns, angles_deg: np.ndarray, name: str) -> Evaluated:
        """The same dyad solved to accelerations, the acceleration stage's limit checked."""
        self.acceleration_unknowns = unknowns
        self.ratio = check_stage("acceleration", self.bound, self.smallest, self.line_sine,
                                 self.ratio, angles_deg, name)
        return self


class _Dyad:
    """Constants of one dyad; :meth:`evaluate` solves it."""

    group: AssurGroup
    rotating: dict
    tied: dict

    def _join(self, group: AssurGroup) -> tuple:
        """Keep the group, its links l1 and l2 (at its outer pairs) and the known links k1 and
        k2 they join; return the joints (outer of l1, internal, outer of l2)."""
        self.group = group
        ext1, internal, ext2 = group.joints
        self.l1, self.l2 = _group_link(ext1, group), _group_link(ext2, group)
        self.k1, self.k2 = ext1.other(self.l1), ext2.other(self.l2)
        return ext1, internal, ext2

    def place(self, values: dict, branch: int, count: int, targets: dict,
              careful: bool = False) -> Placed | None:
        """The dyad's positions (None near a position the reference refuses, unless
        ``careful``)."""
        raise NotImplementedError

    def evaluate(self, values: dict, branch: int, count: int, targets: dict, level: int,
                 angles_deg: np.ndarray, name: str, careful: bool = False) -> Evaluated | None:
        """The dyad's positions and, up to stage ``level``, velocities and accelerations, with
        each stage's limit checked (:func:`check_stage`) as it is solved.

        Parameters
        ----------
        values
            The known links' values (not changed).
        branch
            The assembly's sign.
        count
            How many angles.
        targets
            Where each of the group's links' vectors go.
        level
            0, 1 or 2: the last stage solved.
        angles_deg, name
            The crank angles and the group's name, for the errors.
        careful
            Evaluate even near a position the reference refuses (after it did not).

        Returns
        -------
        Evaluated or None
            None where the bounded checks flag a position the reference might refuse.
        """
        placed = self.place(values, branch, count, targets, careful)
        if placed is None:
            return None
        if level == 0:
            return Evaluated(placed.links)
        values = values | placed.links
        u1, u2, sine = velocities(self, placed, values, count)
        ratio = size_ratio_later(placed)
        evaluated = Evaluated.with_velocities(placed.links, (u1, u2), sine, ratio,
                                              placed.bound, angles_deg, name)
        if level == 2:
            evaluated.with_accelerations(accelerations(self, placed, values, (u1, u2), count),
                                    angles_deg, name)
        return evaluated

    def fallback(self, mechanism, states, branch, angles_deg) -> None:
        """Run the reference closed form: it raises the exact error where there is one."""
        dyad_positions(mechanism, self.group, states, branch, angles_deg)


class _SlideLine:
    """A prismatic pair seen from its ``unknown`` link (``dyads._slide_line``)."""

    __slots__ = ("anchor", "direction", "is_link", "known", "own", "slide")

    def __init__(self, mechanism: Mechanism, slide, unknown: str) -> None:
        self.slide = slide
        self.is_link = unknown == slide.link
        self.known = slide.along if self.is_link else slide.link
        self.direction = slide.direction_rad
        if self.is_link:
            self.anchor = _local(mechanism, slide.along, slide.through)
            self.own = _local(mechanism, slide.link, slide.point)
        else:
            self.anchor = _local(mechanism, slide.link, slide.point)
            self.own = _local(mechanism, slide.along, slide.through)

    def theta(self, known: Values):
        """The unknown link's θ."""
        if self.is_link:
            return known.theta + self.direction
        return known.theta - self.direction

    def theta_and_axes(self, known: Values):
        """The unknown link's θ and (cos θ, sin θ), and the guide's global direction d."""
        if self.is_link:
            c, s = _rotated(known.c, known.s, self.direction)
            return self.theta(known), c, s, c, s
        c, s = _rotated(known.c, known.s, -self.direction)
        return self.theta(known), c, s, known.c, known.s

    def line(self, known: Values, c, s, dx, dy):
        """(nx, ny, offset): the line n·o = offset of the unknown link's origin, n = J·d."""
        nx, ny = -dy, dx
        ax, ay, _, _ = place(known, self.anchor)
        ox, oy = turn(c, s, *self.own) if self.own != (0.0, 0.0) else (0.0, 0.0)
        return nx, ny, nx * (ax - ox) + ny * (ay - oy)


def _dot_turned(nx, ny, c, s, local):
    if local == (0.0, 0.0):
        return 0.0
    tx, ty = turn(c, s, *local)
    return nx * tx + ny * ty


class _RRR(_Dyad):
    def __init__(self, mechanism: Mechanism, group: AssurGroup) -> None:
        ext1, internal, ext2 = self._join(group)
        self.p1_known = _local(mechanism, self.k1, ext1.point)
        self.p2_known = _local(mechanism, self.k2, ext2.point)
        self.p1_local = _local(mechanism, self.l1, ext1.point)
        self.p2_local = _local(mechanism, self.l2, ext2.point)
        q1 = _local(mechanism, self.l1, internal.point)
        q2 = _local(mechanism, self.l2, internal.point)
        self.a = mechanism.links[self.l1].length(ext1.point, internal.point)
        self.b = mechanism.links[self.l2].length(ext2.point, internal.point)
        self.alpha1 = _alpha(self.p1_local, q1)
        self.alpha2 = _alpha(self.p2_local, q2)
        #: whether the internal pin Q is l1's, l2's origin
        self.q_at_origin = (q1 == (0.0, 0.0), q2 == (0.0, 0.0))
        self.frame_pins = (_frame_pin(self.k1, self.p1_known), _frame_pin(self.k2, self.p2_known))
        self.valid = self.a > 1e-12 and self.b > 1e-12

    def evaluate(self, values: dict, branch: int, count: int, targets: dict, level: int,
                 angles_deg: np.ndarray, name: str, careful: bool = False) -> Evaluated | None:
        """:meth:`_Dyad.evaluate` as straight-line code: the two rotation sides' positions,
        velocities and accelerations on local variables (the generic vector equations'
        arithmetic, in the same order)."""
        if not self.valid:
            return None
        a, b = self.a, self.b
        bound = None
        known1, known2 = values[self.k1], values[self.k2]
        target1, target2 = targets[self.l1], targets[self.l2]
        # a pin at a link's origin is placed straight into that link's origin; positions are
        # complex numbers x + iy from here on (one call for what takes two on x and y)
        p1x, p1y, r1x, r1y, p1 = _pin(known1, self.p1_known, target1.origin
                                      if self.p1_local == (0.0, 0.0) else None, count,
                                      self.frame_pins[0])
        p2x, p2y, r2x, r2y, p2 = _pin(known2, self.p2_known, target2.origin
                                      if self.p2_local == (0.0, 0.0) else None, count,
                                      self.frame_pins[1])
        if careful:
            p1, p2 = (_complex_array(point, count) for point in (p1, p2))
            p1x, p1y, p2x, p2y = p1.real, p1.imag, p2.real, p2.imag
        span = p2 - p1
        # |span| as np.abs (hypot): one call, and at least as accurate as √(x² + y²)
        d = np.abs(span)
        product = (a + b + d) * (a + b - d) * (a - b + d) * (b - a + d)
        if careful:
            product = np.maximum(product, 0.0)
        elif np.ndim(d) == 0:
            return None
        else:
            # a + b − d and d − |a − b| must stay clear of zero (dyads._rrr's checks, bounded
            # over all angles at once)
            low, high = float(np.minimum.reduce(d)), float(np.maximum.reduce(d))
            limit = _TOLERANCE * (a + b + 2.0 * high) * _MARGIN
            if not (a + b - high > limit and low - abs(a - b) > limit
                    and low > 1e-15 * (a + b) * _MARGIN):
                return None
            # R = (d + |r1| + |r2|) / min |r|, the radii's lengths a and b to rounding: twice
            # that bounds it unless a rounding error reaches a third of the shorter link
            if min(a, b) > 1e-6 * (a + b + high):
                bound = 2.0 * (a + b + high) / min(a, b)
        twice = 2 * d
        # Q = P1 + u·(x + ih), u the unit span: x along it, h across (one complex product)
        along = np.empty(count, dtype=np.complex128)
        np.divide(a * a - b * b + d * d, twice, out=along.real)
        root = np.sqrt(product)
        if branch != 1:
            root = np.multiply(root, branch, out=root)
        np.divide(root, twice, out=along.imag)
        unit = np.empty(count, dtype=np.complex128)
        np.divide(span.real, d, out=unit.real)
        np.divide(span.imag, d, out=unit.imag)
        q = np.multiply(unit, along, out=along)
        q = np.add(p1, q, out=q)
        l1, l2 = self.l1, self.l2
        # the radii Q − P, θ and the axes of each link; e = perp(unit(radius)), as
        # dyads._rotation_side
        radius1, radius2 = q - p1, q - p2
        radius1x, radius1y, radius2x, radius2y = (radius1.real, radius1.imag, radius2.real,
                                                  radius2.imag)
        theta1, c1, s1, o1x, o1y, ref1, length1, e1x, e1y = _pivoted(
            target1, p1x, p1y, radius1x, radius1y, self.alpha1, self.p1_local, np.abs(radius1),
            (q.real, q.imag) if self.q_at_origin[0] else None)
        theta2, c2, s2, o2x, o2y, ref2, length2, e2x, e2y = _pivoted(
            target2, p2x, p2y, radius2x, radius2y, self.alpha2, self.p2_local, np.abs(radius2),
            (q.real, q.imag) if self.q_at_origin[1] else None)
        state1, state2 = Values(theta1, c1, s1, o1x, o1y), Values(theta2, c2, s2, o2x, o2y)
        links = {l1: state1, l2: state2}
        if level == 0:
            return Evaluated(links)
        direction1, direction2 = (np.negative(e1y), e1x), (np.negative(e2y), e2x)
        # velocities: u1·e1 − u2·e2 = v_P2 − v_P1 (dyads.solve_pair), ω = u / |radius|; a
        # link with its pin at its origin has the pin's velocity (written there already)
        velocity1, velocity2 = target1.velocity, target2.velocity
        base1 = velocity_at(known1, r1x, r1y, velocity1 if ref1 is None else None)
        base2 = velocity_at(known2, r2x, r2y, velocity2 if ref2 is None else None)
        sine = direction1[0] * direction2[1] - direction1[1] * direction2[0]
        u1, u2 = _cramer(base2, base1, direction1, direction2, sine, count)
        w1, w2 = u1 / length1, u2 / length2
        state1.w = state1.omega = w1
        state2.w = state2.omega = w2
        state1.vx, state1.vy = _origin_velocity(base1, ref1, w1, velocity1)
        state2.vx, state2.vy = _origin_velocity(base2, ref2, w2, velocity2)
        ratio = _ratio_later([length1, length2], d, None)
        evaluated = Evaluated.with_velocities(links, (u1, u2), sine, ratio, bound, angles_deg,
                                              name)
        if level == 1:
            return evaluated
        # accelerations: u̇1·e1 − u̇2·e2 = (a_P2 − ω2²·radius2) − (a_P1 − ω1²·radius1)
        acceleration1, acceleration2 = target1.acceleration, target2.acceleration
        base1 = acceleration_at(known1, r1x, r1y, acceleration1 if ref1 is None else None)
        base2 = acceleration_at(known2, r2x, r2y, acceleration2 if ref2 is None else None)
        square1, square2 = w1 * w1, w2 * w2
        known1 = _centripetal(base1, square1, radius1x, radius1y)
        known2 = _centripetal(base2, square2, radius2x, radius2y)
        du1, du2 = _cramer(known2, known1, direction1, direction2, sine, count)
        e1, e2 = du1 / length1, du2 / length2
        state1.e = state1.epsilon = e1
        state2.e = state2.epsilon = e2
        state1.ax, state1.ay = _origin_acceleration(base1, ref1, w1, e1, acceleration1, square1)
        state2.ax, state2.ay = _origin_acceleration(base2, ref2, w2, e2, acceleration2, square2)
        return evaluated.with_accelerations((du1, du2), angles_deg, name)


def _columns(out: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The x and y columns of an (n, 2) array."""
    return out[:, 0], out[:, 1]


def _plus(base, x, y):
    """``base`` + (x, y) (``base`` None where zero)."""
    return (x, y) if base is None else (base[0] + x, base[1] + y)


def _centripetal(base, square, radius_x, radius_y):
    """a_base − ω²·radius (base None where zero)."""
    if base is None:
        return -(square * radius_x), -(square * radius_y)
    return base[0] - square * radius_x, base[1] - square * radius_y


class _RRP(_Dyad):
    def __init__(self, mechanism: Mechanism, group: AssurGroup) -> None:
        ext1, internal, ext2 = self._join(group)
        self.line = _SlideLine(mechanism, ext2.slide, self.l2)
        self.p1_known = _local(mechanism, self.k1, ext1.point)
        self.p1_local = _local(mechanism, self.l1, ext1.point)
        self.q2_local = _local(mechanism, self.l2, internal.point)
        q1 = _local(mechanism, self.l1, internal.point)
        self.a = mechanism.links[self.l1].length(ext1.point, internal.point)
        self.alpha1 = _alpha(self.p1_local, q1)
        self.valid = self.a > 1e-12
        #: a guide of the frame: its axes, direction and line, the same at every solve
        self.guide_at_rest = None
        if self.k2 == FRAME:
            _, c2, s2, dx, dy = self.line.theta_and_axes(_AT_REST)
            nx, ny, offset = self.line.line(_AT_REST, c2, s2, dx, dy)
            self.guide_at_rest = (c2, s2, dx, dy, nx, ny,
                                  offset + _dot_turned(nx, ny, c2, s2, self.q2_local))

    def evaluate(self, values: dict, branch: int, count: int, targets: dict, level: int,
                 angles_deg: np.ndarray, name: str, careful: bool = False) -> Evaluated | None:
        """:meth:`_Dyad.evaluate` as straight-line code: the rotation side P1 → X and the
        sliding side (X on the guide of k2, along d) on local variables (the generic vector
        equations' arithmetic, in the same order)."""
        if not self.valid:
            return None
        a = self.a
        l1, l2 = self.l1, self.l2
        known1, known2 = values[self.k1], values[self.k2]
        target1, target2 = targets[l1], targets[l2]
        if self.guide_at_rest is None:
            theta2, c2, s2, dx, dy = self.line.theta_and_axes(known2)
            nx, ny, offset = self.line.line(known2, c2, s2, dx, dy)
            offset = offset + _dot_turned(nx, ny, c2, s2, self.q2_local)
        else:
            theta2 = self.line.theta(known2)
            c2, s2, dx, dy, nx, ny, offset = self.guide_at_rest
        p1x, p1y, r1x, r1y = place(known1, self.p1_known, target1.origin
                                   if self.p1_local == (0.0, 0.0) else None)
        if careful:
            p1x, p1y = _array(p1x, count), _array(p1y, count)
        h = nx * p1x + ny * p1y - offset
        if careful:
            pass
        elif np.ndim(h) == 0:
            return None
        else:
            # |h| must stay below a by more than rounding (dyads._rrp's check, bounded)
            reach = max(_largest(p1x), _largest(p1y))
            limit = _TOLERANCE * (a + _largest(offset) + reach) * _MARGIN
            if not a - _largest(h) > limit:
                return None
        along = np.sqrt(a * a - h * h)
        if branch != 1:
            along = branch * along
        # X: written into the block's origin when X is its origin
        at_x = self.q2_local == (0.0, 0.0)
        qx = np.add(p1x - h * nx, along * dx, out=target2.origin[:, 0] if at_x else None)
        qy = np.add(p1y - h * ny, along * dy, out=target2.origin[:, 1] if at_x else None)
        radius_x, radius_y = qx - p1x, qy - p1y
        theta1, c1, s1, o1x, o1y, ref1, length, ex, ey = _pivoted(
            target1, p1x, p1y, radius_x, radius_y, self.alpha1, self.p1_local)
        c2, s2 = _basis(target2, c2, s2)
        if at_x:
            o2x, o2y, ref2 = qx, qy, None
        else:
            o2x, o2y, ref2 = _origin(target2, qx, qy, c2, s2, self.q2_local)
        state1, state2 = Values(theta1, c1, s1, o1x, o1y), Values(theta2, c2, s2, o2x, o2y)
        links = {l1: state1, l2: state2}
        if level == 0:
            return Evaluated(links)
        # side 1 turns about P1: e1 = J·unit(radius); side 2: X as a point of the guide's
        # carrier k2 (offset b from its origin), sliding along d
        d1x, d1y = np.negative(ey), ex
        bx, by = (None, None) if known2.fixed else (qx - known2.x, qy - known2.y)
        # velocities: u1·e1 − u2·d = v_X(k2) − v_P1 (dyads.solve_pair); the block turns with k2
        velocity1, velocity2 = target1.velocity, target2.velocity
        base1 = velocity_at(known1, r1x, r1y, velocity1 if ref1 is None else None)
        base2 = velocity_at(known2, bx, by)
        sine = d1x * dy - d1y * dx
        if np.ndim(sine) == 0:
            sine = np.full(count, sine)
        u1, u2 = _cramer(base2, base1, (d1x, d1y), (dx, dy), sine, count)
        w1 = u1 / length
        w2 = None if known2.fixed else known2.w
        state1.w = state1.omega = w1
        state2.w, state2.omega = w2, known2.omega
        state1.vx, state1.vy = _origin_velocity(base1, ref1, w1, velocity1)
        # X's velocity v_P1 + u1·e1, the block's origin's from it
        velocity_x = _plus(base1, u1 * d1x, u1 * d1y)
        state2.vx, state2.vy = _link_velocity(velocity_x, ref2, w2, velocity2)
        ratio = _ratio_later([length], None, (p1x, p1y, qx, qy))
        # R = (|X − P1| + |X − P1|) / |X − P1| = 2 exactly
        evaluated = Evaluated.with_velocities(links, (u1, u2), sine, ratio, 2.0, angles_deg,
                                              name)
        if level == 1:
            return evaluated
        # accelerations: u̇1·e1 − u̇2·d = (a_X(k2) + 2ω_k2·J·u2·d) − (a_P1 − ω1²·radius)
        acceleration1, acceleration2 = target1.acceleration, target2.acceleration
        base1 = acceleration_at(known1, r1x, r1y, acceleration1 if ref1 is None else None)
        base2 = acceleration_at(known2, bx, by)
        square1 = w1 * w1
        known_first = _centripetal(base1, square1, radius_x, radius_y)
        if w2 is None:
            known_second = base2
        else:  # Coriolis
            twice = 2 * w2
            cx, cy = twice * -(u2 * dy), twice * (u2 * dx)
            known_second = _plus(base2, cx, cy)
        du1, du2 = _cramer(known_second, known_first, (d1x, d1y), (dx, dy), sine, count)
        e1 = du1 / length
        state1.e = state1.epsilon = e1
        state2.e, state2.epsilon = None if known2.fixed else known2.e, known2.epsilon
        state1.ax, state1.ay = _origin_acceleration(base1, ref1, w1, e1, acceleration1, square1)
        acceleration_x = _plus(known_first, du1 * d1x, du1 * d1y)
        state2.ax, state2.ay = _link_acceleration(acceleration_x, ref2, w2, state2.e,
                                                  acceleration2)
        return evaluated.with_accelerations((du1, du2), angles_deg, name)


class _RPR(_Dyad):
    def __init__(self, mechanism: Mechanism, group: AssurGroup) -> None:
        ext1, internal, ext2 = self._join(group)
        slide = internal.slide
        self.p1_known = _local(mechanism, self.k1, ext1.point)
        self.p2_known = _local(mechanism, self.k2, ext2.point)
        self.p1_local = _local(mechanism, self.l1, ext1.point)
        self.p2_local = _local(mechanism, self.l2, ext2.point)
        self.direction = slide.direction_rad
        u = np.array([np.cos(slide.direction_rad), np.sin(slide.direction_rad)])
        through = np.asarray(mechanism.local(self.l2, slide.through))
        from .state import rotate

        c0 = (through - np.asarray(mechanism.local(self.l2, ext2.point))
              + rotate(np.subtract(mechanism.local(self.l1, ext1.point),
                                   mechanism.local(self.l1, slide.point)), slide.direction_rad))
        self.c0 = (float(c0[0]), float(c0[1]))
        self.u = (float(u[0]), float(u[1]))
        self.offset = float(c0[0] * u[1] - c0[1] * u[0])
        self.c0u = float(c0 @ u)
        self.frame_pins = (_frame_pin(self.k1, self.p1_known), _frame_pin(self.k2, self.p2_known))

    def evaluate(self, values: dict, branch: int, count: int, targets: dict, level: int,
                 angles_deg: np.ndarray, name: str, careful: bool = False) -> Evaluated | None:
        """:meth:`_Dyad.evaluate` as straight-line code: P1 sliding relative to l1 along the
        guide and l2 turning about P2 (l1 turns with it), on local variables (the generic
        vector equations' arithmetic, in the same order)."""
        known1, known2 = values[self.k1], values[self.k2]
        target1, target2 = targets[self.l1], targets[self.l2]
        p1x, p1y, r1x, r1y = _known_pin(known1, self.p1_known, target1.origin
                                        if self.p1_local == (0.0, 0.0) else None,
                                        self.frame_pins[0])
        p2x, p2y, r2x, r2y = _known_pin(known2, self.p2_known, target2.origin
                                        if self.p2_local == (0.0, 0.0) else None,
                                        self.frame_pins[1])
        if careful:
            p1x, p1y, p2x, p2y = (_array(v, count) for v in (p1x, p1y, p2x, p2y))
        sx, sy = p1x - p2x, p1y - p2y
        length = _norm(sx, sy)
        offset = self.offset
        if careful:
            pass
        elif np.ndim(length) == 0:
            return None
        else:
            low, high = float(length.min()), float(length.max())
            if not low > 1e-15 * _MARGIN:
                return None
            if offset != 0 and not (low - abs(offset)
                                    > _TOLERANCE * (2.0 * high + abs(offset)) * _MARGIN):
                return None
        along = np.sqrt(length * length - offset ** 2)
        if branch != 1:
            along = branch * along
        s = -self.c0u + along
        (c0x, c0y), (ux, uy) = self.c0, self.u
        theta2 = np.arctan2(sy, sx) - np.arctan2(c0y + s * uy, c0x + s * ux)
        basis2 = target2.basis
        c2, s2 = np.cos(theta2, out=basis2[:, 0]), np.sin(theta2, out=basis2[:, 1])
        theta1 = theta2 + self.direction
        if self.direction == 0.0:
            c1, s1 = _basis(target1, c2, s2)
        else:
            c1, s1 = _turn_into(target1.basis, c2, s2, math.cos(self.direction),
                                math.sin(self.direction))
        l1, l2 = self.l1, self.l2
        o1x, o1y, ref1 = _origin(target1, p1x, p1y, c1, s1, self.p1_local)
        o2x, o2y, ref2 = _origin(target2, p2x, p2y, c2, s2, self.p2_local)
        state1, state2 = Values(theta1, c1, s1, o1x, o1y), Values(theta2, c2, s2, o2x, o2y)
        links = {l1: state1, l2: state2}
        if level == 0:
            return Evaluated(links)
        # side 1: P1 slides relative to l1 along l2's guide, d = (cos, sin)(θ2 + direction);
        # side 2: turns about P2 with radius P1 − P2, e2 = J·(radius / length)
        d2x, d2y = -(sy / length), sx / length
        # velocities: u1·d − u2·e2 = v_P2 − v_P1 (dyads.solve_pair), ω = u2 / length
        velocity1, velocity2 = target1.velocity, target2.velocity
        base1 = velocity_at(known1, r1x, r1y, velocity1 if ref1 is None else None)
        base2 = velocity_at(known2, r2x, r2y, velocity2 if ref2 is None else None)
        sine = c1 * d2y - s1 * d2x
        u1, u2 = _cramer(base2, base1, (c1, s1), (d2x, d2y), sine, count)
        w = u2 / length
        state1.w = state1.omega = state2.w = state2.omega = w
        state1.vx, state1.vy = _origin_velocity(base1, ref1, w, velocity1)
        state2.vx, state2.vy = _origin_velocity(base2, ref2, w, velocity2)
        ratio = _ratio_later([length], length, None)
        # R = (span + length) / length with span = length: 2 exactly
        evaluated = Evaluated.with_velocities(links, (u1, u2), sine, ratio, 2.0, angles_deg,
                                              name)
        if level == 1:
            return evaluated
        # accelerations: u̇1·d − u̇2·e2 = (a_P2 − ω²·radius) − (a_P1 + 2ω·J·u1·d)
        acceleration1, acceleration2 = target1.acceleration, target2.acceleration
        base1 = acceleration_at(known1, r1x, r1y, acceleration1 if ref1 is None else None)
        base2 = acceleration_at(known2, r2x, r2y, acceleration2 if ref2 is None else None)
        twice = 2 * w
        cx, cy = twice * -(u1 * s1), twice * (u1 * c1)  # Coriolis
        known_first = _plus(base1, cx, cy)
        square = w * w
        known_second = _centripetal(base2, square, sx, sy)
        du1, du2 = _cramer(known_second, known_first, (c1, s1), (d2x, d2y), sine, count)
        e = du2 / length
        state1.e = state1.epsilon = state2.e = state2.epsilon = e
        state1.ax, state1.ay = _origin_acceleration(base1, ref1, w, e, acceleration1, square)
        state2.ax, state2.ay = _origin_acceleration(base2, ref2, w, e, acceleration2, square)
        return evaluated.with_accelerations((du1, du2), angles_deg, name)


class _PRP(_Dyad):
    def __init__(self, mechanism: Mechanism, group: AssurGroup) -> None:
        ext1, internal, ext2 = self._join(group)
        self.ends = [(link, known, _SlideLine(mechanism, joint.slide, link),
                      _local(mechanism, link, internal.point))
                     for joint, link, known in ((ext1, self.l1, self.k1),
                                                (ext2, self.l2, self.k2))]
        self.rotating, self.tied = {}, {self.l1: self.k1, self.l2: self.k2}

    def place(self, values, branch, count, targets, careful=False):
        lines = []
        for _, known, line, local in self.ends:
            known_values = values[known]
            theta, c, s, dx, dy = line.theta_and_axes(known_values)
            nx, ny, offset = line.line(known_values, c, s, dx, dy)
            lines.append((theta, c, s, dx, dy, nx, ny, offset + _dot_turned(nx, ny, c, s, local)))
        (*_, n1x, n1y, o1), (*_, n2x, n2y, o2) = lines
        det = n1x * n2y - n1y * n2x
        if not careful and not float(np.abs(det).min()) >= TOGGLE_SINE * _MARGIN:
            return None
        qx = (o1 * n2y - o2 * n1y) / det
        qy = (n1x * o2 - n2x * o1) / det
        if np.ndim(qx) == 0:
            qx, qy = np.full(count, qx), np.full(count, qy)
        links, refs, sides = {}, {}, []
        for (link, known, _, local), (theta, c, s, dx, dy, *_) in zip(self.ends, lines,
                                                                    strict=True):
            target = targets[link]
            c, s = _basis(target, c, s)
            if local == (0.0, 0.0):
                ox, oy = put(target.origin, qx, qy)
                ref = None
            else:
                ox, oy, ref = _origin(target, qx, qy, c, s, local)
            links[link] = Values(theta, c, s, ox, oy)
            refs[link] = (None, ref)
            known_values = values[known]
            bx, by = (None, None) if known_values.fixed else (qx - known_values.x,
                                                              qy - known_values.y)
            sides.append(Side(False, known, known_values, bx, by, qx, qy, dx, dy))
        return Placed(links, qx, qy, tuple(sides), refs, targets, bound=1.0)  # no rotation


class _RPP(_Dyad):
    def __init__(self, mechanism: Mechanism, group: AssurGroup) -> None:
        ext1, internal, ext2 = self._join(group)
        self.p1_known = _local(mechanism, self.k1, ext1.point)
        self.p1_local = _local(mechanism, self.l1, ext1.point)
        self.outer = _SlideLine(mechanism, ext2.slide, self.l2)
        self.inner = _SlideLine(mechanism, internal.slide, self.l2)
        # l1's angle from l2's through the internal pair (dyads._slide_theta)
        self.inner_sign = 1.0 if self.l1 == internal.slide.link else -1.0
        self.rotating, self.tied = {}, {self.l2: self.k2, self.l1: self.l2}

    def place(self, values, branch, count, targets, careful=False):
        known1, known2 = values[self.k1], values[self.k2]
        target1, target2 = targets[self.l1], targets[self.l2]
        theta2, c2, s2, d2x, d2y = self.outer.theta_and_axes(known2)
        turn_by = self.inner_sign * self.inner.direction
        theta1 = theta2 + turn_by
        c1, s1 = _rotated(c2, s2, turn_by)
        p1x, p1y, r1x, r1y = place(known1, self.p1_known, target1.origin
                                   if self.p1_local == (0.0, 0.0) else None)
        if self.p1_local == (0.0, 0.0):
            o1x, o1y, ref1 = p1x, p1y, None
        else:
            tx, ty = turn(c1, s1, *self.p1_local)
            o1x, o1y, ref1 = p1x - tx, p1y - ty, (-tx, -ty)
        state1 = Values(theta1, c1, s1, o1x, o1y)
        n2x, n2y, off2 = self.outer.line(known2, c2, s2, d2x, d2y)
        # the inner pair seen from l2 (unknown) against l1 (known): d from the guide's angle
        if self.inner.is_link:  # l2 slides in l1
            d1x, d1y = _rotated(c1, s1, self.inner.direction)
        else:  # l1 slides in l2: d along l2's guide
            d1x, d1y = _rotated(c2, s2, self.inner.direction)
        n1x, n1y, off1 = self.inner.line(state1, c2, s2, d1x, d1y)
        det = n1x * n2y - n1y * n2x
        if not careful and not float(np.abs(det).min()) >= TOGGLE_SINE * _MARGIN:
            return None
        o2x = (off1 * n2y - off2 * n1y) / det
        o2y = (n1x * off2 - n2x * off1) / det
        if np.ndim(o2x) == 0:
            o2x, o2y = np.full(count, o2x), np.full(count, o2y)
        state1.c, state1.s = _basis(target1, c1, s1)
        if self.p1_local != (0.0, 0.0):
            state1.x, state1.y = put(target1.origin, o1x, o1y)
        c2, s2 = _basis(target2, c2, s2)
        o2x, o2y = put(target2.origin, o2x, o2y)
        side1 = Side(False, self.l1, known1, r1x, r1y, p1x, p1y, d1x, d1y)
        bx, by = (None, None) if known2.fixed else (p1x - known2.x, p1y - known2.y)
        side2 = Side(False, self.k2, known2, bx, by, p1x, p1y, d2x, d2y)
        links = {self.l1: state1, self.l2: Values(theta2, c2, s2, o2x, o2y)}
        refs = {self.l1: (0, ref1), self.l2: (None, (o2x - p1x, o2y - p1y))}
        return Placed(links, p1x, p1y, (side1, side2), refs, targets, bound=1.0)  # no rotation


_COMPILERS = {"RRR": _RRR, "RRP": _RRP, "RPR": _RPR, "PRP": _PRP, "RPP": _RPP}


# -- the two vector equations --------------------------------------------------------------------
def _minus(first, second, count: int):
    """first − second for vectors that may be None (zero)."""
    if second is None:
        if first is None:
            zeros = np.zeros(count)
            return zeros, zeros
        return first
    if first is None:
        return -second[0], -second[1]
    return first[0] - second[0], first[1] - second[1]


def _cramer(minuend, subtrahend, first, second, det, count: int):
    """(u1, u2) with u1·e1 − u2·e2 = w, w = minuend − subtrahend (vectors None where zero), by
    Cramer's rule (``first``, ``second``: the directions (dx, dy) of e1 and e2); w =
    −subtrahend is folded into the products' order (the same values)."""
    (first_x, first_y), (second_x, second_y) = first, second
    if minuend is None and subtrahend is not None:
        # (−sx)·dy − (−sy)·dx = sy·dx − sx·dy, exactly
        sx, sy = subtrahend
        return ((sy * second_x - sx * second_y) / det,
                (sy * first_x - sx * first_y) / det)
    wx, wy = _minus(minuend, subtrahend, count)
    return (wx * second_y - wy * second_x) / det, (wx * first_y - wy * first_x) / det


def _follow_tied(tied, own: dict, values, attribute: str) -> None:
    """Give each tied link the ω (or ε) of the link it is tied to (Construction.follow_tied):
    ``own`` maps a link to (value for arithmetic, array)."""
    pending = dict(tied)
    while pending:
        for link, other in list(pending.items()):
            source = own.get(other)
            if source is None and other in values:
                known = values[other]
                array = getattr(known, attribute)
                if array is not None:
                    source = (None if known.fixed else
                              (known.w if attribute == "omega" else known.e), array)
            if source is not None:
                own[link] = source
                del pending[link]


def _straights(placed: Placed, stage: str):
    """``_straight`` for both sides."""
    out = [None, None]
    for link, (side, r) in placed.refs.items():
        if side is not None and r is None:
            out[side] = getattr(placed.targets[link], stage)
    return out


def velocities(dyad, placed: Placed, values, count: int):
    """Solve the group's velocity equations; sets ω and the origins' velocities of its links
    (written into their targets).

    Returns (u1, u2, sine): the unknown lengths and the sine of the lines' angle."""
    first, second = placed.sides
    out1, out2 = _straights(placed, "velocity")
    v1 = velocity_at(first.base, first.rx, first.ry, out1)
    v2 = velocity_at(second.base, second.rx, second.ry, out2)
    det = first.dx * second.dy - first.dy * second.dx
    if np.ndim(det) == 0:
        det = np.full(count, det)
    placed.det = det
    # u1·e1 − u2·e2 = w = v2 − v1 by Cramer's rule (dyads.solve_pair)
    u1, u2 = _cramer(v2, v1, (first.dx, first.dy), (second.dx, second.dy), det, count)
    unknowns = (u1, u2)
    own: dict = {}
    for link, index in dyad.rotating.items():
        omega = unknowns[index] / placed.sides[index].length
        own[link] = (omega, omega)
    _follow_tied(dyad.tied, own, values, "omega")
    bases = (v1, v2)
    velocity_x = None
    for link, (index, r) in placed.refs.items():
        state = placed.links[link]
        w, state.omega = own[link]
        state.w = w
        out = placed.targets[link].velocity
        if index is not None and r is None:  # written already, as its side's base velocity
            state.vx, state.vy = out[:, 0], out[:, 1]
            continue
        if index is None:
            if velocity_x is None:
                velocity_x = _plus(v1, u1 * first.dx, u1 * first.dy)
            reference = velocity_x
        else:
            reference = bases[index]
        state.vx, state.vy = _link_velocity(reference, r, w, out)
    return u1, u2, det


def _origin_velocity(base, r, w, out):
    """A link's origin's velocity: ``out`` as it is when the origin is the pin (``r`` None: the
    pin's velocity ``base`` was written there), else :func:`_link_velocity`."""
    return _columns(out) if r is None else _link_velocity(base, r, w, out)


def _origin_acceleration(base, r, w, e, out, square=None):
    """:func:`_origin_velocity` for accelerations (:func:`_link_acceleration`)."""
    return _columns(out) if r is None else _link_acceleration(base, r, w, e, out, square)


def _link_velocity(reference, r, w, out):
    """v_ref + ω·J·r (reference, w None where zero), written into ``out``."""
    if r is None or w is None:
        return put(out, *(reference or (None, None)))
    rx, ry = r
    if reference is None:
        return np.negative(ry * w, out=out[:, 0]), np.multiply(rx, w, out=out[:, 1])
    return (np.subtract(reference[0], w * ry, out=out[:, 0]),
            np.add(reference[1], w * rx, out=out[:, 1]))


def accelerations(dyad, placed: Placed, values, unknowns, count: int):
    """Solve the group's acceleration equations; sets ε and the origins' accelerations (written
    into their targets).

    Returns (du1, du2)."""
    known, bases = [], []
    outs = _straights(placed, "acceleration")
    for side, u, out in zip(placed.sides, unknowns, outs, strict=True):
        base = acceleration_at(side.base, side.rx, side.ry, out)
        bases.append(base)
        if side.rotation:
            w = placed.links[side.link].w
            known.append(_centripetal(base, w * w, side.radius_x, side.radius_y))
            continue
        carrier = placed.links[side.link] if side.link in placed.links else values[side.link]
        if carrier.fixed or carrier.w is None:
            known.append(base)
            continue
        twice = 2 * carrier.w
        cx, cy = twice * -(u * side.dy), twice * (u * side.dx)
        known.append(_plus(base, cx, cy))
    first, second = placed.sides
    du1, du2 = _cramer(known[1], known[0], (first.dx, first.dy), (second.dx, second.dy),
                       placed.det, count)
    changes = (du1, du2)
    own: dict = {}
    for link, index in dyad.rotating.items():
        epsilon = changes[index] / placed.sides[index].length
        own[link] = (epsilon, epsilon)
    _follow_tied(dyad.tied, own, values, "epsilon")
    acceleration_x = None
    for link, (index, r) in placed.refs.items():
        state = placed.links[link]
        e, state.epsilon = own[link]
        state.e = e
        out = placed.targets[link].acceleration
        if index is not None and r is None:  # written already, as its side's base
            state.ax, state.ay = out[:, 0], out[:, 1]
            continue
        if index is None:
            if acceleration_x is None:
                acceleration_x = _plus(known[0], du1 * first.dx, du1 * first.dy)
            reference = acceleration_x
        else:
            reference = bases[index]
        state.ax, state.ay = _link_acceleration(reference, r, state.w, e, out)
    return du1, du2


def _link_acceleration(reference, r, w, e, out, square=None):
    """a_ref + ε·J·r − ω²·r, in the reference's order (w, e, reference None where zero),
    written into ``out`` (``square``: ω·ω when known)."""
    if r is None or (w is None and e is None):
        return put(out, *(reference or (None, None)))
    rx, ry = r
    first, second = out[:, 0], out[:, 1]
    if reference is None:
        if w is None:
            return np.negative(e * ry, out=first), np.multiply(e, rx, out=second)
        w2 = w * w if square is None else square
        if e is None:
            return np.negative(w2 * rx, out=first), np.negative(w2 * ry, out=second)
        return (np.subtract(-(e * ry), w2 * rx, out=first),
                np.subtract(e * rx, w2 * ry, out=second))
    ax, ay = reference
    if w is None:
        return np.subtract(ax, e * ry, out=first), np.add(ay, e * rx, out=second)
    w2 = w * w if square is None else square
    if e is not None:
        ax, ay = ax - e * ry, ay + e * rx
    return np.subtract(ax, w2 * rx, out=first), np.subtract(ay, w2 * ry, out=second)


def size_ratio_later(placed: Placed):
    """R = L / l of Construction.size_ratio (None where it is 1: no rotation side), computed
    when called (keeping only the arrays it needs)."""
    radii = [side.length for side in placed.sides if side.rotation]
    if not radii:
        return lambda: None
    first, second = placed.sides
    points = None if placed.span is not None else (first.px, first.py, second.px, second.py)
    return _ratio_later(radii, placed.span, points)


def _ratio_later(radii: list, span, points):
    """R = (|span| + Σ radii) / min radii, computed when called (``span`` from ``points``, the
    two pins' x and y, when None)."""

    def ratio():
        nonlocal span
        if span is None:
            first_x, first_y, second_x, second_y = points
            span = _norm(first_x - second_x, first_y - second_y)
        total = span + sum(radii)
        return total / (radii[0] if len(radii) == 1 else np.minimum(radii[0], radii[1]))

    return ratio
