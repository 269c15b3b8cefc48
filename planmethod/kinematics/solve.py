"""Exact kinematics of a whole mechanism, group by group in build order, vectorised over angles.

:func:`solve` returns a :class:`Motion`: every solved link's pose, ω, ε and origin velocity and
acceleration at each crank angle, from which any point, any point of a link coincident with
another point (``B@lever``), sliding quantities and the curvature of a path are read.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> exercise = load_exercise("exercises/compressor_slider_crank.toml")
>>> motion = solve(exercise.mechanism)
>>> round(float(abs(motion.velocity("C")[0])), 4), round(float(motion.omega("BC")), 3)
(5.2716, -24.254)
>>> round(float(motion.curvature("D").rho), 5)
0.07377
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..errors import AssemblyError, PlanmethodError, SpecError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, Structure
from .compiled import (
    EPS,
    Evaluated,
    Program,
    Target,
    Values,
    error_estimate,
    program,
    put,
    refuse_digitless,
    turn,
)
from .compiled import place as place_point
from .dyads import Construction, construct, dyad_positions
from .state import LinkState, _complex, _real, cross, norm, perp, rotate, unit_angle

__all__ = ["STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "Sliding", "solve"]

STAGES = ("position", "velocity", "acceleration")
_LEVELS = {stage: level for level, stage in enumerate(STAGES)}
#: a key not found (None is a value: a point at its link's origin has no offset)
_MISSING = object()


@dataclass(frozen=True, slots=True)
class Branch:
    """The assembly a group takes: ``sign`` ±1 (see README, "Branches") and why."""

    sign: int
    reason: str  # "sketch", "default" or "unique"


@dataclass(frozen=True, slots=True)
class GroupMotion:
    """A solved dyad: its construction and the unknown lengths of its two vector equations.

    ``velocity_unknowns`` (u1, u2) and ``acceleration_unknowns`` (u̇1, u̇2) are the signed
    magnitudes along the sides' directions; ``line_sine`` the sine of the angle from side 1's
    line to side 2's; ``error_estimate`` the estimated relative error of the group's
    velocities and accelerations near its toggle, ε·R/s³ and ε·R/s⁵ (per stage solved).
    """

    construction: Construction | None  # None for a class III group (kinematics/higher.py)
    velocity_unknowns: tuple[np.ndarray, np.ndarray] | None = None
    acceleration_unknowns: tuple[np.ndarray, np.ndarray] | None = None
    line_sine: np.ndarray | None = None
    error_estimate: Mapping[str, np.ndarray] | None = None


@dataclass(frozen=True, slots=True)
class Sliding:
    """A prismatic pair's travel s (m), sliding velocity ds/dt and acceleration d²s/dt², and the
    Coriolis acceleration 2ω_along × v_rel (global vector)."""

    s: np.ndarray
    velocity: np.ndarray | None = None
    acceleration: np.ndarray | None = None
    coriolis: np.ndarray | None = None


@dataclass(frozen=True, slots=True)
class Curvature:
    """Radius and centre of curvature of a point's path.

    ``rho`` is NaN where it is undefined, with the reason flagged: ``straight`` (the point moves
    on a straight line by construction), ``inflection`` (v × a = 0 on a curved path) or
    ``stationary`` (v = 0).
    """

    rho: np.ndarray
    center: np.ndarray
    straight: bool
    inflection: np.ndarray
    stationary: np.ndarray


@dataclass(frozen=True)
class Motion:
    """The exact kinematics of a mechanism at one or many crank angles.

    The arrays of :attr:`links` (and of :attr:`groups`) are the solve's own and may share one
    allocation: keeping one keeps the others; those of the frame and the drive's ω and ε are
    read-only, shared by the solves of as many angles. The methods (``position``, ``velocity``,
    ``theta``, ``omega``, …) return arrays of the caller's own.
    """

    mechanism: Mechanism
    structure: Structure
    angles: np.ndarray
    scalar: bool
    stage: str
    links: Mapping[str, LinkState]
    groups: Mapping[int, GroupMotion]
    branches: Mapping[int, Branch]
    #: reference → (link, position, offset), filled on first use (positions never change): the
    #: offset of the point from its link's origin as complex numbers (None at the origin,
    #: ``_MISSING`` where computed when first needed, into ``_offsets``)
    _located: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    #: reference → its offset (complex), for the references located without one
    _offsets: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    #: link → iω and link → iε − ω² (complex): what a point's velocity and acceleration are
    #: made of
    _spins: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    _turns: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    #: the model's compiled program (set by :func:`solve`; looked up when None)
    _program: Program | None = field(default=None, init=False, repr=False, compare=False)

    # -- shaping ---------------------------------------------------------------------------
    def _out(self, array: np.ndarray) -> np.ndarray:
        return array[0] if self.scalar else array

    def _own(self, array: np.ndarray) -> np.ndarray:
        """``_out`` of a copy: the caller may keep it without keeping the solve's arrays."""
        return array[0] if self.scalar else array.copy()

    def _need(self, stage: str, what: str) -> None:
        if _LEVELS[self.stage] < _LEVELS[stage]:
            raise PlanmethodError(f"{what} needs the {stage} stage, but only the {self.stage} "
                                  "stage was solved")

    def link_state(self, link: str) -> LinkState:
        if link not in self.mechanism.links:
            raise SpecError(f"unknown link '{link}'")
        if link not in self.links:
            raise PlanmethodError(f"link {link} was not solved in this scene")
        return self.links[link]

    # -- points --------------------------------------------------------------------------------
    def _locate(self, ref: str) -> tuple[str, np.ndarray, object]:
        """(link whose material point is meant, its current global position, its offset from
        the link's origin as complex numbers: None at the origin, ``_MISSING`` if not known
        yet)."""
        found = self._located.get(ref)
        if found is None:
            found = self._located[ref] = self._find(ref)
            found[1].flags.writeable = False  # shared by later reads
        return found

    def _find(self, ref: str) -> tuple[str, np.ndarray, object]:
        name, _, on = ref.partition("@")
        compiled = self._program or program(self.mechanism)
        links = self.links
        owner = local = None
        for link, coordinates in compiled.carriers(name):
            if link in links:
                owner, local = link, coordinates
                break
        if owner is None:
            if not self.mechanism.links_with_point(name):
                raise SpecError(f"unknown point '{name}'")
            raise PlanmethodError(f"point {name} was not solved in this scene")
        state = links[owner]
        if on:
            self.link_state(on)
            return on, state.place(local), _MISSING
        if owner == FRAME:  # the frame's axes are (1, 0): the point stays at its coordinates
            count = len(state.origin)
            return owner, compiled.constant(("point", name, count), count,
                                            lambda: _at_rest(count, local)), _MISSING
        if local == (0.0, 0.0):  # the link's origin: no offset
            return owner, state.origin.copy(), None
        # r = (cos θ + i sin θ)·(x + iy) (x·(cos θ, sin θ) for a point on the link's x-axis),
        # kept as complex numbers for the velocity and acceleration reads
        if local[1] == 0.0:
            offset = state.axes() * local[0]
            return owner, offset + state.origin, offset.view(np.complex128)[:, 0]
        turned = _complex(state.axes()) * complex(*local)
        return owner, _real(turned) + state.origin, turned

    def position(self, ref: str) -> np.ndarray:
        """Global position (m) of a point (``"C"``) or of a link's point under another
        (``"B@lever"``)."""
        found = self._located.get(ref) or self._locate(ref)
        return found[1][0].copy() if self.scalar else found[1].copy()

    def _offset(self, ref: str, link: str, position: np.ndarray) -> np.ndarray:
        """The point's position minus its link's origin, as complex numbers (kept)."""
        offset = self._offsets.get(ref)
        if offset is None:
            offset = self._offsets[ref] = _complex(position - self.links[link].origin)
        return offset

    def velocity(self, ref: str) -> np.ndarray:
        """Absolute velocity (m/s) of a point."""
        if self.stage == "position":
            self._need("velocity", f"the velocity of {ref}")
        return self._rigid(ref, "velocity", self._spin)  # LinkState.velocity_at, v + ω·J·r

    def acceleration(self, ref: str) -> np.ndarray:
        """Absolute acceleration (m/s²) of a point."""
        if self.stage != "acceleration":
            self._need("acceleration", f"the acceleration of {ref}")
        # LinkState.acceleration_at, a + ε·J·r − ω²·r
        return self._rigid(ref, "acceleration", self._turn)

    def _rigid(self, ref: str, vector: str, factor) -> np.ndarray:
        """The link's ``vector`` (velocity or acceleration of its origin) plus the point's
        offset r times ``factor(link, state, r)`` (iω, or iε − ω²), as complex numbers; r and
        the factors are kept for later reads."""
        link, position, offset = self._located.get(ref) or self._locate(ref)
        if link == FRAME:  # a point of the frame does not move
            return self._out(np.zeros(position.shape))
        state = self.links[link]
        if offset is _MISSING:
            offset = self._offset(ref, link, position)
        elif offset is None:  # the link's origin
            return self._out(getattr(state, vector).copy())
        moved = np.multiply(offset, factor(link, state, offset))[..., None].view(np.float64)
        moved += getattr(state, vector)  # in place (one array fewer)
        return moved[0] if self.scalar else moved

    def _spin(self, link: str, state: LinkState, offset: np.ndarray) -> np.ndarray:
        """iω of the link (kept)."""
        spin = self._spins.get(link)
        if spin is None:
            spin = self._spins[link] = np.zeros(offset.shape, dtype=np.complex128)
            spin.imag = state.omega
        return spin

    def _turn(self, link: str, state: LinkState, offset: np.ndarray) -> np.ndarray:
        """iε − ω² of the link (kept; from iω when a velocity read made it)."""
        factor = self._turns.get(link)
        if factor is None:
            spin = self._spins.get(link)
            if spin is None:
                factor = np.empty(offset.shape, dtype=np.complex128)
                omega = state.omega
                np.multiply(omega, omega, out=factor.real)
                np.negative(factor.real, out=factor.real)
            else:  # (iω)² = −ω²
                factor = np.multiply(spin, spin)
            factor.imag = state.epsilon
            self._turns[link] = factor
        return factor

    def place(self, link: str, local) -> np.ndarray:
        """Global position of the point of ``link`` at local coordinates ``local``."""
        return self._out(self.link_state(link).place(local))

    def velocity_of(self, link: str, local) -> np.ndarray:
        self._need("velocity", f"a velocity on {link}")
        state = self.link_state(link)
        return self._out(state.velocity_at(state.place(local)))

    def acceleration_of(self, link: str, local) -> np.ndarray:
        self._need("acceleration", f"an acceleration on {link}")
        state = self.link_state(link)
        return self._out(state.acceleration_at(state.place(local)))

    # -- links ---------------------------------------------------------------------------------
    def theta(self, link: str) -> np.ndarray:
        """Global angle (rad) of the link's own +x axis."""
        return self._own(self.link_state(link).theta)

    def omega(self, link: str) -> np.ndarray:
        """Angular velocity (rad/s, counter-clockwise positive)."""
        self._need("velocity", f"ω of {link}")
        return self._own(self.link_state(link).omega)

    def epsilon(self, link: str) -> np.ndarray:
        """Angular acceleration (rad/s², counter-clockwise positive)."""
        self._need("acceleration", f"ε of {link}")
        return self._own(self.link_state(link).epsilon)

    # -- pairs and paths -------------------------------------------------------------------------
    def sliding(self, key: str) -> Sliding:
        """Travel, sliding velocity and acceleration and Coriolis term of a prismatic pair
        (``"link/along"``)."""
        slide = self.mechanism.slide(key)
        if slide is None:
            raise SpecError(f"no prismatic pair '{key}'")
        mover, guide = self.link_state(slide.link), self.link_state(slide.along)
        point = mover.place(self.mechanism.local(slide.link, slide.point))
        through = guide.place(self.mechanism.local(slide.along, slide.through))
        d = unit_angle(guide.theta + slide.direction_rad)
        s = np.einsum("...i,...i->...", point - through, d)
        if STAGES.index(self.stage) < 1:
            return Sliding(self._out(s))
        v_rel = mover.velocity_at(point) - guide.velocity_at(point)
        ds = np.einsum("...i,...i->...", v_rel, d)
        if STAGES.index(self.stage) < 2:
            return Sliding(self._out(s), self._out(ds))
        coriolis = 2 * guide.omega[..., None] * perp(v_rel)
        a_rel = mover.acceleration_at(point) - guide.acceleration_at(point) - coriolis
        dds = np.einsum("...i,...i->...", a_rel, d)
        return Sliding(self._out(s), self._out(ds), self._out(dds), self._out(coriolis))

    def moves_straight(self, ref: str) -> bool:
        """Whether the point moves on a straight line by construction: it belongs to a link
        that is held against turning by a prismatic pair with the frame."""
        name, _, on = ref.partition("@")
        carriers = (on,) if on else self.mechanism.links_with_point(name)
        return any(link == FRAME or any(FRAME in (s.link, s.along) and link in (s.link, s.along)
                                        for s in self.mechanism.slides)
                   for link in carriers)

    def curvature(self, ref: str) -> Curvature:
        """Radius ρ = v³/|v × a| and centre of curvature of the point's path."""
        self._need("acceleration", f"the curvature of {ref}'s path")
        link, position, _ = self._locate(ref)
        state = self.links[link]
        v, a = state.velocity_at(position), state.acceleration_at(position)
        speed = norm(v)
        turn = cross(v, a)
        scale = np.maximum(speed * norm(a), np.finfo(float).tiny)
        stationary = speed <= 1e-12 * np.maximum(1.0, norm(a))
        straight = self.moves_straight(ref)
        inflection = ~stationary & (np.abs(turn) <= 1e-12 * scale)
        undefined = stationary | inflection | straight
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = np.where(undefined, np.nan, speed ** 3 / np.abs(turn))
            normal = np.sign(turn)[..., None] * perp(v / speed[..., None])
            center = np.where(undefined[..., None], np.nan, position + rho[..., None] * normal)
        return Curvature(self._out(rho), self._out(center), straight,
                         self._out(inflection & (not straight)), self._out(stationary))


# -- the solve ---------------------------------------------------------------------------------
def _at_rest(count: int, local) -> np.ndarray:
    """A frame point's position at every angle, read-only (shared by the solves)."""
    position = np.empty((count, 2))
    position.view(np.complex128).fill(complex(*local))  # (one fill of x + iy)
    position.flags.writeable = False
    return position


def _frame_at_rest(count: int) -> tuple[LinkState, Values]:
    """The frame's state with read-only arrays, and its values (shared by the solves of
    ``count`` angles)."""
    frame = _frame_state(count)
    for array in (frame.theta, frame.origin, frame.velocity, frame.acceleration, frame.basis):
        array.flags.writeable = False
    return frame, _fixed_values(frame)


def _constant_rates(count: int, omega: float, epsilon: float):
    """The drive's ω and ε over ``count`` angles, read-only (shared by the solves)."""
    rates = np.empty((2, count))
    rates[0].fill(omega)
    rates[1].fill(epsilon)
    rates.flags.writeable = False
    return rates[0], rates[1]


def _frame_state(count: int, arrays=None) -> LinkState:
    """The frame at rest (its arrays taken from ``arrays`` when given: zeros (N,), three
    (N, 2) and the axes (N, 2))."""
    if arrays is None:
        zeros = np.zeros(count)
        axes = np.zeros((count, 2))
        vectors = np.zeros((count, 2)), np.zeros((count, 2)), np.zeros((count, 2))
    else:
        zeros, *vectors, axes = (next(arrays) for _ in range(5))
        for array in (zeros, *vectors, axes):
            array.fill(0.0)
    axes[:, 0] = 1.0
    return LinkState(zeros, vectors[0], zeros, vectors[1], zeros, vectors[2], axes)


def _drive_state(mechanism: Mechanism, angles_rad: np.ndarray) -> LinkState:
    drive = mechanism.drive
    pivot_local = mechanism.local(drive.link, drive.pivot)
    pivot = np.asarray(mechanism.local(FRAME, drive.pivot), float)
    axes = unit_angle(angles_rad)
    origin = pivot - rotate(pivot_local, angles_rad, axes)
    count = angles_rad.shape[0]
    omega = np.full(count, float(drive.omega))
    epsilon = np.full(count, float(drive.epsilon))
    r = origin - pivot
    turned = perp(r)
    velocity = float(drive.omega) * turned
    acceleration = float(drive.epsilon) * turned - float(drive.omega) ** 2 * r
    return LinkState(angles_rad, origin, omega, velocity, epsilon, acceleration, axes)


def _sketch_distance(mechanism: Mechanism, group: AssurGroup, poses) -> float | None:
    total, used = 0.0, False
    for link in group.links:
        theta, origin = poses[link]
        for name, local in mechanism.links[link].points.items():
            if name in mechanism.sketch:
                place = origin + rotate(local, theta)
                total += float(np.sum((place - np.asarray(mechanism.sketch[name])) ** 2))
                used = True
    return total if used else None


def _choose_branch(mechanism, group, states, angle_deg) -> tuple[Branch, dict | None]:
    """The group's branch and, when already computed, its poses on that branch."""
    if group.kind not in ("RRR", "RRP", "RPR"):
        return Branch(1, "unique"), None
    angles = np.array([angle_deg])
    candidates, poses = {}, {}
    errors = []
    for sign in (1, -1):
        try:
            poses[sign] = dyad_positions(mechanism, group, states, sign, angles)
        except AssemblyError as error:
            errors.append(error)
            continue
        candidates[sign] = _sketch_distance(mechanism, group, poses[sign])
    if not candidates:
        raise errors[0]
    plus, minus = candidates.get(1), candidates.get(-1)
    if plus is None or minus is None or abs(plus - minus) <= 1e-12 * (plus + minus) + 1e-24:
        return Branch(1, "default"), poses.get(1)
    sign = 1 if plus < minus else -1
    return Branch(sign, "sketch"), poses[sign]


def choose_branches(mechanism: Mechanism, structure: Structure | None = None,
                    groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]:
    """Pick each group's assembly at ``drive.angle``: nearest to the sketch, else the default.

    Dyads are placed on both branches by their compiled closed forms; a group whose compiled
    check flags a position the reference refuses, and every class III group, is decided by the
    reference code (which raises its errors)."""
    compiled = program(mechanism)
    structure = structure or compiled.structure
    groups = structure.groups if groups is None else tuple(groups)
    angle_deg = float(mechanism.drive.angle)
    angle = np.radians(np.array([angle_deg]))
    drive = mechanism.drive.link
    frame = _frame_state(1)
    drive_target = _targets(1, 0, [drive])[0][drive]
    drive_values = _drive_values(compiled, np.array([angle_deg]), drive_target)
    states = {FRAME: frame, drive: _link_state(drive_values, 0, drive_target)}
    values = {FRAME: _fixed_values(frame), drive: drive_values}
    branches = {}
    for group in groups:
        found = _choose_compiled(compiled, group, values) if group.is_dyad else None
        if found is not None:
            branches[group.index], placed, targets = found
            for link, link_values in placed.links.items():
                values[link] = link_values
                states[link] = _link_state(link_values, 0, targets[link])
            continue
        if not group.is_dyad:
            from .higher import choose_higher_branch  # class III groups: Newton from the sketch

            branch, poses = choose_higher_branch(mechanism, group, states, angle)
            branches[group.index] = branch
        else:
            branches[group.index], poses = _choose_branch(mechanism, group, states, angle_deg)
            if poses is None:
                poses = dyad_positions(mechanism, group, states, branches[group.index].sign,
                                       np.array([angle_deg]))
        for link, (theta, origin) in poses.items():
            states[link] = LinkState(theta, origin)
            values[link] = Values.of(states[link])
    return branches


def _choose_compiled(compiled, group: AssurGroup, values: dict):
    """(branch, placed dyad, its targets) by ``_choose_branch``'s rule, from the compiled
    closed forms at one angle; None where the reference code must decide."""
    dyad = compiled.dyad(group)
    placed = {}
    for sign in ((1, -1) if group.kind in ("RRR", "RRP", "RPR") else (1,)):
        targets = _targets(1, 0, group.links)[0]
        found = dyad.evaluate(values, sign, 1, targets, 0, None, group.name)
        if found is None:
            return None
        placed[sign] = (found, targets)
    if len(placed) == 1:
        return Branch(1, "unique"), *placed[1]
    mechanism = compiled.mechanism
    plus, minus = (_sketch_gap(mechanism, group, placed[sign][0]) for sign in (1, -1))
    if plus is None or minus is None or abs(plus - minus) <= 1e-12 * (plus + minus) + 1e-24:
        return Branch(1, "default"), *placed[1]
    sign = 1 if plus < minus else -1
    return Branch(sign, "sketch"), *placed[sign]


def _sketch_gap(mechanism: Mechanism, group: AssurGroup, placed) -> float | None:
    """``_sketch_distance`` of a placed dyad (one angle)."""
    total, used = 0.0, False
    for link in group.links:
        link_values = placed.links[link]
        for name, local in mechanism.links[link].points.items():
            if name in mechanism.sketch:
                x, y, _, _ = place_point(link_values, local)
                sketch_x, sketch_y = mechanism.sketch[name]
                total += float(np.sum((x - sketch_x) ** 2 + (y - sketch_y) ** 2))
                used = True
    return total if used else None


#: estimated relative errors above this are flagged in reports
FLAG_ERROR = 1e-6


def _condition(construction: Construction, sine: np.ndarray, angles_deg: np.ndarray,
               stage: str) -> np.ndarray:
    """The estimated relative error ε·R/s^(2k+1) of a dyad's velocities (k = 1) or
    accelerations (k = 2), s the sine of the angle between its construction lines and R its size
    ratio (:meth:`Construction.size_ratio`). Near a toggle a displacement δ of the group's
    input moves s by about δ/(l·s) while |v| grows like 1/s and |a| like 1/s³, so the crank
    angle's own rounding is amplified that much; measured errors stay 20–40 times below this
    estimate (benchmarks/stress.py). Where it reaches 1 no digit is left: a ToggleError."""
    power = 3 if stage == "velocity" else 5
    with np.errstate(divide="ignore", over="ignore"):
        estimate = EPS * construction.size_ratio() / np.abs(sine) ** power
    refuse_digitless(estimate, sine, angles_deg, stage, construction.group.name)
    return estimate


class _Estimates(Mapping):
    """A dyad's ``error_estimate``: ε·R/s³ and ε·R/s⁵ per stage solved, computed when read."""

    __slots__ = ("_ratio", "_sine", "_stages", "_values")

    def __init__(self, ratio, sine: np.ndarray, level: int) -> None:
        self._ratio, self._sine, self._stages = ratio, sine, STAGES[1:level + 1]
        self._values: dict[str, np.ndarray] = {}

    def __getitem__(self, stage: str) -> np.ndarray:
        found = self._values.get(stage)
        if found is None:
            if stage not in self._stages:
                raise KeyError(stage)
            if callable(self._ratio):  # R was not needed by the solve: computed now
                self._ratio = self._ratio()
            found = self._values[stage] = error_estimate(self._ratio, self._sine, stage)
        return found

    def __iter__(self):
        return iter(self._stages)

    def __len__(self) -> int:
        return len(self._stages)

    def __repr__(self) -> str:
        return repr(dict(self))


class _SolvedDyad(GroupMotion):
    """A solved dyad whose :class:`Construction` is built on first use (the plan emulator and
    the force drawings use it; a bare solve does not)."""

    __slots__ = ("_build",)

    def __init__(self, construction=None, velocity_unknowns=None, acceleration_unknowns=None,
                 line_sine=None, error_estimate=None, *, build=None) -> None:
        object.__setattr__(self, "_build", build)
        GroupMotion.__init__(self, construction, velocity_unknowns, acceleration_unknowns,
                             line_sine, error_estimate)

    @property
    def construction(self) -> Construction | None:
        value = _CONSTRUCTION_SLOT.__get__(self, GroupMotion)
        build = getattr(self, "_build", None)
        if value is None and build is not None:
            value = build()
            _CONSTRUCTION_SLOT.__set__(self, value)
            object.__setattr__(self, "_build", None)
        return value

    @construction.setter
    def construction(self, value) -> None:
        _CONSTRUCTION_SLOT.__set__(self, value)


_CONSTRUCTION_SLOT = GroupMotion.__dict__["construction"]


def _targets(count: int, level: int, links, extra=()):
    """Result arrays for ``links``: origin, axes (and velocity, acceleration up to ``level``)
    of each, cut from one allocation with arrays of the ``extra`` shapes after them."""
    vectors = (level + 2) * len(links)
    if extra:
        arrays = iter(_carve(count, [2] * vectors + list(extra)))
    else:  # (views of a 3-d array are cheaper to make)
        arrays = iter(np.empty((vectors, count, 2)))
    return {link: Target(next(arrays), next(arrays), next(arrays) if level >= 1 else None,
                         next(arrays) if level >= 2 else None) for link in links}, arrays


def _sliced_targets(targets: dict[str, Target], lo: int, hi: int) -> dict[str, Target]:
    def cut(array):
        return None if array is None else array[lo:hi]

    return {link: Target(cut(t.origin), cut(t.basis), cut(t.velocity), cut(t.acceleration))
            for link, t in targets.items()}


def _link_state(values: Values, level: int, target: Target) -> LinkState:
    """The state of a solved link whose vectors are in ``target``."""
    if level == 0:
        return LinkState(values.theta, target.origin, basis=target.basis)
    if level == 1:
        return LinkState(values.theta, target.origin, values.omega, target.velocity,
                         basis=target.basis)
    return LinkState(values.theta, target.origin, values.omega, target.velocity,
                     values.epsilon, target.acceleration, target.basis)


def _drive_values(compiled, angles_deg: np.ndarray, target: Target, arrays=None) -> Values:
    """The drive link's values (as ``_drive_state``), its vectors written into ``target`` (and
    θ, cos θ, sin θ, ω, ε into ``arrays`` when given)."""
    count = angles_deg.shape[0]
    if arrays is None:
        angles_rad = np.radians(angles_deg)
        # cos θ and sin θ straight into the axes' columns
        basis = target.basis
        c, s = np.cos(angles_rad, out=basis[:, 0]), np.sin(angles_rad, out=basis[:, 1])
        omega_array, epsilon_array = compiled.constant(
            ("rates", count), count,
            lambda: _constant_rates(count, compiled.omega, compiled.epsilon))
    else:
        angles_rad = np.radians(angles_deg, out=next(arrays))
        c, s = np.cos(angles_rad, out=next(arrays)), np.sin(angles_rad, out=next(arrays))
        omega_array, epsilon_array = next(arrays), next(arrays)
    if arrays is not None:
        put(target.basis, c, s)
    px, py = compiled.pivot
    if compiled.pivot_local == (0.0, 0.0):
        values = Values(angles_rad, c, s, px, py)
        put(target.origin, px, py)
        rx = ry = None
    else:
        tx, ty = turn(c, s, *compiled.pivot_local)
        values = Values(angles_rad, c, s, *put(target.origin, px - tx, py - ty))
        rx, ry = values.x - px, values.y - py
    omega, epsilon = compiled.omega, compiled.epsilon
    if arrays is not None:
        omega_array.fill(omega)
        epsilon_array.fill(epsilon)
    values.w, values.omega = omega, omega_array
    values.e, values.epsilon = epsilon, epsilon_array
    if rx is not None:
        values.vx, values.vy = omega * -ry, omega * rx
        square = omega ** 2
        values.ax, values.ay = epsilon * -ry - square * rx, epsilon * rx - square * ry
    if target.velocity is not None:
        put(target.velocity, values.vx, values.vy)
    if target.acceleration is not None:
        put(target.acceleration, values.ax, values.ay)
    return values


def _sliced(values: Values, lo: int, hi: int) -> Values:
    """The values at angles lo…hi − 1 (views)."""
    def cut(array):
        return array[lo:hi] if isinstance(array, np.ndarray) else array

    out = Values(cut(values.theta), cut(values.c), cut(values.s), cut(values.x), cut(values.y),
                 values.fixed)
    out.w, out.omega, out.vx, out.vy = values.w, cut(values.omega), cut(values.vx), cut(values.vy)
    out.e, out.epsilon, out.ax, out.ay = (values.e, cut(values.epsilon), cut(values.ax),
                                          cut(values.ay))
    return out


def _fixed_values(frame: LinkState) -> Values:
    fixed = Values(frame.theta, 1.0, 0.0, 0.0, 0.0, fixed=True)
    fixed.omega = fixed.epsilon = frame.omega
    return fixed


def _solved_dyad(record: Evaluated, level: int, build) -> GroupMotion:
    """The group motion of an evaluated dyad (its construction built when first read)."""
    if level == 0:
        return _SolvedDyad(build=build)
    return _SolvedDyad(None, record.velocity_unknowns, record.acceleration_unknowns,
                       record.line_sine, _Estimates(record.ratio, record.line_sine, level),
                       build=build)


#: angles evaluated at once: beyond this the temporaries of a solve outgrow a core's cache, so a
#: long sweep of dyads is evaluated chunk by chunk into the result arrays (each angle is
#: independent of the others, so the values are the same)
CHUNK = 8192


class _FlaggedError(Exception):
    """A chunk came near a position the reference check refuses (internal)."""


def solve(mechanism: Mechanism, angles=None, *, stage: str = "acceleration",
          links: Iterable[str] | None = None, structure: Structure | None = None,
          branches: Mapping[int, Branch] | None = None) -> Motion:
    """Exact positions, velocities and accelerations at crank angle(s) ``angles`` (deg).

    Parameters
    ----------
    mechanism
        The model.
    angles
        One crank angle or an array of them, in degrees (default: ``drive.angle``).
    stage
        ``"position"``, ``"velocity"`` or ``"acceleration"``: the last stage computed.
    links
        Only the groups on the way to these links are solved (default: all).
    structure, branches
        Reuse an earlier structural analysis and branch choice.

    Raises
    ------
    AssemblyError, ToggleError, ConvergenceError
        At the first crank angle where a group cannot be assembled, is in its toggle position,
        or (class III) does not converge.
    """
    if stage not in STAGES:
        raise ValueError(f"stage must be one of {STAGES}, got {stage!r}")
    compiled = program(mechanism)
    plan = groups = None
    if structure is None and links is None and branches is None:  # the whole model's plan
        plan = compiled.remember("plan", lambda: _plan(compiled, compiled.structure))
    else:
        structure = structure or compiled.structure
        groups = structure.groups if links is None else structure.groups_needed(links)
        if branches is None:
            branches = compiled.branches(structure, groups, choose_branches)
    if (type(angles) is np.ndarray and angles.ndim == 1 and angles.dtype == np.float64
            and angles.flags.c_contiguous):
        scalar, angles_deg = False, angles  # (what the conversion below would view)
    else:
        scalar = angles is None or np.ndim(angles) == 0
        angles_deg = np.atleast_1d(np.asarray(
            mechanism.drive.angle if angles is None else angles, dtype=float)).ravel()
    if not np.isfinite(angles_deg).all():
        raise SpecError("crank angles must be finite numbers")
    if plan is None:
        plan = _plan(compiled, structure, groups, branches)
    level = _LEVELS[stage]
    count = angles_deg.shape[0]
    run = _solve_chunked if count > CHUNK and plan.dyads_only else _solve_whole
    # the drive's and every dyad link's vectors in one allocation; chunk by chunk with the
    # frame's and the drive's arrays, the links' angles, ω, ε and the groups' records
    extra = []
    if run is _solve_chunked:
        extra = [1, 2, 2, 2, 2] + [1] * 5 + [1] * _chunked_columns(level, len(plan.steps))
    targets, singles = _targets(count, level, plan.target_links, extra)
    if extra:
        frame = _frame_state(count, singles)
        frame_values = _fixed_values(frame)
    else:  # the same arrays at every solve of this many angles (read-only)
        frame, frame_values = compiled.constant(("frame", count), count,
                                                lambda: _frame_at_rest(count))
    drive = _drive_values(compiled, angles_deg, targets[mechanism.drive.link],
                          singles if extra else None)
    try:
        states, solved = run(compiled, plan.steps, angles_deg, level, frame, frame_values,
                             drive, targets, singles)
    except (_FlaggedError, PlanmethodError):
        if run is _solve_whole:
            raise
        # near a refused position: solve as a whole, group by group, so that the first angle
        # refused is found as the reference finds it
        states, solved = _solve_whole(compiled, plan.steps, angles_deg, level, frame,
                                      frame_values, drive, targets, singles)
    motion = Motion(mechanism, plan.structure, angles_deg, scalar, stage, states, solved,
                    dict(plan.branches))
    object.__setattr__(motion, "_program", compiled)
    return motion


class _Plan:
    """What a solve needs from the model besides the angles: the structure, the groups' branches,
    the steps (each group in build order with its branch and its compiled dyad, None for a class
    III group), the links whose vectors are allocated and whether every group is a dyad."""

    __slots__ = ("branches", "dyads_only", "steps", "structure", "target_links")

    def __init__(self, structure: Structure, branches: Mapping[int, Branch], steps: tuple,
                 target_links: list[str]) -> None:
        self.structure, self.branches, self.steps = structure, branches, steps
        self.target_links = target_links
        self.dyads_only = all(dyad is not None for _, _, dyad in steps)


def _plan(compiled: Program, structure: Structure, groups=None,
          branches: Mapping[int, Branch] | None = None) -> _Plan:
    """The plan of a solve of ``groups`` (default: all of ``structure``'s) on ``branches``
    (default: the model's choice)."""
    groups = structure.groups if groups is None else groups
    if branches is None:
        branches = compiled.branches(structure, groups, choose_branches)
    steps = tuple((group, branches[group.index], compiled.dyad(group) if group.is_dyad else None)
                  for group in groups)
    target_links = [compiled.mechanism.drive.link] + [
        link for group in groups if group.is_dyad for link in group.links]
    return _Plan(structure, branches, steps, target_links)


def _solve_whole(compiled, steps, angles_deg, level, frame, frame_values, drive, targets,
                 singles=None):
    """Every group over all angles at once, in build order."""
    mechanism = compiled.mechanism
    count = angles_deg.shape[0]
    states: dict[str, LinkState] = {FRAME: frame}
    values: dict[str, Values] = {FRAME: frame_values}
    link = mechanism.drive.link
    values[link], states[link] = drive, _link_state(drive, level, targets[link])
    solved: dict[int, GroupMotion] = {}
    for group, branch, dyad in steps:
        if dyad is None:
            from .higher import solve_higher

            solved[group.index] = solve_higher(mechanism, group, states, branch.sign, angles_deg,
                                               level, branch)
            for link in group.links:
                values[link] = Values.of(states[link])
            continue
        record = dyad.evaluate(values, branch.sign, count, targets, level, angles_deg,
                               group.name)
        if record is None:  # near a position the reference refuses: let it decide
            dyad.fallback(mechanism, states, branch.sign, angles_deg)
            record = dyad.evaluate(values, branch.sign, count, targets, level, angles_deg,
                                   group.name, careful=True)
        values.update(record.links)
        for link, link_values in record.links.items():
            states[link] = _link_state(link_values, level, targets[link])
        solved[group.index] = _solved_dyad(record, level, _builder(mechanism, group, states))
    return states, solved


def _carve(count: int, shapes) -> list[np.ndarray]:
    """Arrays of ``count`` rows (``shapes``: 1 or 2 columns each) cut from one buffer: one
    large allocation is backed by huge pages, which first-touches much faster than many."""
    buffer = np.empty(count * sum(shapes))
    out, start = [], 0
    for columns in shapes:
        part = buffer[start:start + count * columns]
        out.append(part if columns == 1 else part.reshape(count, columns))
        start += count * columns
    return out


def _chunked_columns(level: int, groups: int) -> int:
    """Per group its two links' angles (and ω, ε) and its record: u1, u2, sine and the size
    ratio R (+ du1, du2)."""
    return (2 * (level + 1) + (0, 4, 6)[level]) * groups


def _solve_chunked(compiled, steps, angles_deg, level, frame, frame_values, drive, targets,
                   arrays):
    """Dyads only: all groups chunk by chunk, each written into the full result arrays (the
    vectors into ``targets``, angles, ω, ε and the groups' records into ``arrays``)."""
    mechanism = compiled.mechanism
    count = angles_deg.shape[0]
    drive_link = mechanism.drive.link
    states: dict[str, LinkState] = {FRAME: frame,
                                    drive_link: _link_state(drive, level, targets[drive_link])}
    scalars = ("theta", "omega", "epsilon")[:level + 1]
    outputs: dict[str, dict] = {}
    records: dict[int, dict] = {}
    for group, _, _ in steps:
        for link in group.links:
            outputs[link] = {name: next(arrays) for name in scalars}
        if level >= 1:
            records[group.index] = {
                "velocity_unknowns": (next(arrays), next(arrays)), "line_sine": next(arrays),
                "ratio": next(arrays)}
        if level >= 2:
            records[group.index]["acceleration_unknowns"] = (next(arrays), next(arrays))
    for lo in range(0, count, CHUNK):
        hi = min(lo + CHUNK, count)
        size = hi - lo
        values = {FRAME: _fixed_values(frame.take(slice(lo, hi))),
                  drive_link: _sliced(drive, lo, hi)}
        chunk_targets = _sliced_targets(targets, lo, hi)
        for group, branch, dyad in steps:
            evaluated = dyad.evaluate(values, branch.sign, size, chunk_targets, level,
                                      angles_deg[lo:hi], group.name)
            if evaluated is None:
                raise _FlaggedError
            values.update(evaluated.links)
            if level >= 1:
                ratio = evaluated.ratio() if callable(evaluated.ratio) else evaluated.ratio
                record = {"velocity_unknowns": evaluated.velocity_unknowns,
                          "line_sine": evaluated.line_sine,
                          "ratio": 1.0 if ratio is None else ratio}  # None: R = 1
                if level >= 2:
                    record["acceleration_unknowns"] = evaluated.acceleration_unknowns
                _fill(records[group.index], record, lo, hi)
            for link, link_values in evaluated.links.items():
                target = outputs[link]
                for name in scalars:
                    target[name][lo:hi] = getattr(link_values, name)
    solved: dict[int, GroupMotion] = {}
    for group, _, _ in steps:
        for link in group.links:
            target = targets[link]
            states[link] = LinkState(origin=target.origin, velocity=target.velocity,
                                     acceleration=target.acceleration, basis=target.basis,
                                     **outputs[link])
        record = records.get(group.index, {})
        solved[group.index] = _solved_dyad(
            Evaluated({}, record.get("velocity_unknowns"), record.get("line_sine"),
                      record.get("ratio"), record.get("acceleration_unknowns")),
            level, _builder(mechanism, group, states))
    return states, solved


def _fill(target: dict, record: dict, lo: int, hi: int) -> None:
    for key, value in record.items():
        if isinstance(value, dict):
            for name, array in value.items():
                target[key][name][lo:hi] = array
        elif isinstance(value, tuple):
            for out, array in zip(target[key], value, strict=True):
                out[lo:hi] = array
        else:
            target[key][lo:hi] = value


def _builder(mechanism: Mechanism, group: AssurGroup, states: Mapping[str, LinkState]):
    """Builds the group's construction from the solved poses, when asked."""
    return lambda: construct(mechanism, group, states)
