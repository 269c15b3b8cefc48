"""A mechanism's solve, built once: its structure, its branches and its compiled programs.

:func:`model` returns the :class:`Model` of a mechanism — one per mechanism *value* (an equal
mechanism built again finds the same one). A model chooses each group's assembly at
``drive.angle`` once (:meth:`Model.branches`) and compiles, per stage and set of groups, one
straight-line numpy function of the crank angles (:meth:`Model.program`): :func:`build` runs the
drive and every group kind's formulas in build order on traced values
(:mod:`~planmethod.kinematics.tracing`), and the recorded operations become the function. The
same :func:`build` run on numpy arrays is the direct evaluation (the reference path,
:meth:`Model.direct`).

What a program computes is described by its :class:`Schema`, made once per program: for each
solved link the rows of its axes (cos θ, sin θ) and origin and, with the stages, of its ω, its
origin's velocity, its ε and its origin's acceleration (:class:`LinkRows`); for each named point
(as a point of the first link in file order that carries it) the rows of its position, velocity
and acceleration (:class:`PointRows`); the rows of θ of the drive and of links whose θ Newton
solves; how every other link's θ is read from the points (:class:`~planmethod.kinematics.groups.
base.Theta`); and for each group the row of the sine of the angle between its two construction
lines. A :class:`Result` — what a program wrote at some crank angles — is read through it.

Examples
--------
>>> import numpy as np
>>> from planmethod.spec import load_exercise
>>> mechanism = load_exercise("exercises/compressor_slider_crank.toml").mechanism
>>> found = model(mechanism)
>>> found is model(load_exercise("exercises/compressor_slider_crank.toml").mechanism)
True
>>> found.branches()[0]
Branch(sign=1, reason='sketch')
>>> result = found.program(STAGES.index("velocity")).run(np.array([45.0]))
>>> result.read(result.schema.points["C"].velocity).round(4)
array([[-5.2716,  0.    ]])
"""

from __future__ import annotations

import dataclasses
import math
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..errors import AssemblyError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, analyse_structure
from .algebra import Body, Number, Vec, cos, sin
from .groups import kind_module
from .groups.base import Branch, GroupInputs, Theta
from .groups.checks import stage_check
from .groups.dyad import evaluate_dyad
from .tracing import Compiled, Layout, Tracer

__all__ = ["STAGES", "Branch", "LinkRows", "Model", "PointRows", "Program", "Result", "Schema",
           "Slot", "build", "model"]

STAGES = ("position", "velocity", "acceleration")
#: models remembered (most recent first)
CACHE_SIZE = 64
_MODELS: OrderedDict[Mechanism, Model] = OrderedDict()
_LOCK = threading.Lock()


#: the dyads' programs of mechanisms alike but for ``drive.angle`` and the sketch (a mechanism
#: posed at another crank angle and the one it was posed from), most recent first
_DYAD_PROGRAMS: OrderedDict[Mechanism, tuple[dict, threading.Lock]] = OrderedDict()


def _remembered(table: OrderedDict, key, make):
    """``table[key]``, made by ``make()`` (outside the lock) the first time; the most recently
    used :data:`CACHE_SIZE` entries are kept."""
    with _LOCK:
        found = table.get(key)
        if found is not None:
            table.move_to_end(key)
            return found
    made = make()
    with _LOCK:
        found = table.setdefault(key, made)
        table.move_to_end(key)
        while len(table) > CACHE_SIZE:
            table.popitem(last=False)
    return found


def _dyad_programs(mechanism: Mechanism) -> tuple[dict, threading.Lock]:
    """The programs (and their lock) that every mechanism alike but for ``drive.angle`` and
    the sketch shares: a dyad's formulas read neither (the angles are the program's input, the
    assembly is its branch), so their traced program is the same."""
    key = dataclasses.replace(mechanism, sketch={},
                              drive=dataclasses.replace(mechanism.drive, angle=0.0))
    return _remembered(_DYAD_PROGRAMS, key, lambda: ({}, threading.Lock()))


def model(mechanism: Mechanism) -> Model:
    """The model of ``mechanism`` (made once per mechanism value, remembered)."""
    return _remembered(_MODELS, mechanism, lambda: Model(mechanism))


# -- the schema of a program's outputs ----------------------------------------------------------
#: the kinds of :class:`Slot`
ROW, PAIR, CONSTANT = 0, 1, 2


class Slot(NamedTuple):
    """Where one output of a program is: in row ``where`` of the result (``ROW``; for the
    direct evaluation that row holds a vector's (N, 2) array itself), in rows ``where`` and
    ``where`` + 1 as x and y (``PAIR``), or a ``CONSTANT`` never computed (``where`` is its
    number, or its pair of numbers)."""

    kind: int
    where: int | float | tuple[float, float]


class LinkRows(NamedTuple):
    """Where a solved link's values are: its axes (cos θ, sin θ), its origin, and — solved to
    the velocities, to the accelerations — its ω and its origin's velocity, its ε and its
    origin's acceleration (None for a stage not solved)."""

    axes: Slot
    origin: Slot
    omega: Slot | None = None
    velocity: Slot | None = None
    epsilon: Slot | None = None
    acceleration: Slot | None = None


class PointRows(NamedTuple):
    """Where a named point's position, velocity and acceleration are (None: not solved)."""

    position: Slot
    velocity: Slot | None = None
    acceleration: Slot | None = None


@dataclass(frozen=True)
class Schema:
    """What a program computes and where (see the module docstring): the ``level`` solved
    (an index of :data:`STAGES`), the ``groups``; ``links``: each solved link's rows in build
    order (the frame, the drive, the groups' links); ``points``: each named point of the solved
    links, with its ``owners`` (the first link in file order that carries it); ``thetas``: the
    links whose θ has a row of its own (the drive, links Newton solves), ``recipes`` how every
    other moving link's θ is read; ``sines``: each group's construction lines' sine (solved to
    the velocities)."""

    level: int
    groups: tuple[AssurGroup, ...]
    links: Mapping[str, LinkRows]
    points: Mapping[str, PointRows]
    owners: Mapping[str, str]
    thetas: Mapping[str, Slot]
    recipes: Mapping[str, Theta]
    sines: Mapping[int, Slot]

    @property
    def solved(self) -> tuple[str, ...]:
        """The solved links, in build order."""
        return tuple(self.links)


class Result:
    """What a program wrote at N crank angles, read through its :class:`Schema`: each value
    a read-only array over the angles ((N,), or (N, 2) for a vector)."""

    __slots__ = ("_constants", "_rows", "count", "schema")

    def __init__(self, schema: Schema, rows: np.ndarray | list[np.ndarray], count: int,
                 constants: dict[tuple[int, int], np.ndarray]) -> None:
        self.schema, self._rows, self.count, self._constants = schema, rows, count, constants

    def read(self, slot: Slot) -> np.ndarray:
        """The value at ``slot`` (a read-only view; a constant over the angles, made once per
        program and number of angles)."""
        kind = slot.kind
        if kind == ROW:
            return self._rows[slot.where]
        if kind == PAIR:
            return self._rows[slot.where:slot.where + 2].T
        key = (id(slot), self.count)     # (a slot lives as long as its program)
        found = self._constants.get(key)
        if found is None:
            found = np.empty((self.count, 2) if isinstance(slot.where, tuple) else (self.count,))
            found[...] = slot.where
            found.flags.writeable = False
            if len(self._constants) > 256:
                self._constants.clear()
            self._constants[key] = found
        return found

    def body(self, link: str) -> Body:
        """A solved link's :class:`~planmethod.kinematics.algebra.Body` (arrays)."""
        rows, read = self.schema.links[link], self.read
        axes, origin = read(rows.axes), read(rows.origin)
        body = Body(axes[:, 0], axes[:, 1], origin[:, 0], origin[:, 1])
        if rows.omega is not None:
            velocity = read(rows.velocity)
            body.omega, body.vx, body.vy = read(rows.omega), velocity[:, 0], velocity[:, 1]
        if rows.epsilon is not None:
            acceleration = read(rows.acceleration)
            body.epsilon, body.ax, body.ay = (read(rows.epsilon), acceleration[:, 0],
                                              acceleration[:, 1])
        return body


# -- what build() writes: named rows ------------------------------------------------------------
class _Writer:
    """Names :func:`build`'s results by what they are (a link's ω, a point's position …): each
    becomes one output of the tracer or of the direct evaluation, under a name of its own
    (``omega:BC``, ``p:C``: the tracer's :class:`~planmethod.kinematics.tracing.Layout` keeps
    them), in the order written. :meth:`schema` then gives each link and point its rows."""

    def __init__(self) -> None:
        self._links: dict[str, tuple[str | None, ...]] = {}
        self._points: dict[str, tuple[str | None, ...]] = {}
        self._thetas: dict[str, str] = {}
        self._sines: dict[int, str] = {}

    def scalar(self, name: str, value: Number) -> None:
        raise NotImplementedError

    def vector(self, name: str, vec: Vec) -> None:
        raise NotImplementedError

    def theta(self, link: str, value: Number) -> None:
        """θ of a link whose angle is a result of its own (the drive, a link Newton solves)."""
        self._thetas[link] = name = f"theta:{link}"
        self.scalar(name, value)

    def sine(self, group: int, value: Number) -> None:
        """The sine of the angle between a group's two construction lines."""
        self._sines[group] = name = f"sine:{group}"
        self.scalar(name, value)

    def link(self, link: str, body: Body, level: int) -> None:
        """A solved link's axes, origin and, to ``level``, motion."""
        names = [f"axes:{link}", f"origin:{link}", None, None, None, None]
        self.vector(names[0], Vec(body.cos, body.sin))
        self.vector(names[1], body.origin)
        if level >= 1:
            names[2:4] = f"omega:{link}", f"velocity:{link}"
            self.scalar(names[2], body.omega)
            self.vector(names[3], Vec(body.vx, body.vy))
        if level >= 2:
            names[4:6] = f"epsilon:{link}", f"acceleration:{link}"
            self.scalar(names[4], body.epsilon)
            self.vector(names[5], Vec(body.ax, body.ay))
        self._links[link] = tuple(names)

    def point(self, point: str, position: Vec, velocity: Vec | None,
              acceleration: Vec | None, level: int) -> None:
        """A named point's position and, to ``level``, its velocity and acceleration."""
        names = [f"p:{point}", None, None]
        self.vector(names[0], position)
        if level >= 1:
            names[1] = f"v:{point}"
            self.vector(names[1], velocity)
        if level >= 2:
            names[2] = f"a:{point}"
            self.vector(names[2], acceleration)
        self._points[point] = tuple(names)

    def schema(self, level: int, groups: tuple[AssurGroup, ...], recipes: Mapping[str, Theta],
               owners: Mapping[str, str], slot: Callable[[str], Slot]) -> Schema:
        """The schema of what was written, ``slot(name)`` telling where each output is."""
        def slots(names):
            return tuple(None if name is None else slot(name) for name in names)

        return Schema(level, groups,
                      {link: LinkRows(*slots(names)) for link, names in self._links.items()},
                      {point: PointRows(*slots(names)) for point, names in self._points.items()},
                      dict(owners), {link: slot(name) for link, name in self._thetas.items()},
                      dict(recipes), {group: slot(name) for group, name in self._sines.items()})


class _TracedWriter(_Writer):
    def __init__(self, tracer: Tracer) -> None:
        super().__init__()
        self.tracer = tracer

    def scalar(self, name: str, value: Number) -> None:
        self.tracer.output(name, value)

    def vector(self, name: str, vec: Vec) -> None:
        self.tracer.output_vector(name, vec.x, vec.y)


class _DirectWriter(_Writer):
    """The direct evaluation's outputs: read-only arrays over the angles, by name."""

    def __init__(self, count: int) -> None:
        super().__init__()
        self.count = count
        self.values: dict[str, np.ndarray] = {}

    def _array(self, value: Number) -> np.ndarray:
        if (type(value) is np.ndarray and value.dtype == np.float64
                and value.shape == (self.count,)):
            return value.view()    # (a view of its own: it is made read-only)
        return np.broadcast_to(np.asarray(value, dtype=float), (self.count,))

    def scalar(self, name: str, value: Number) -> None:
        self.values[name] = self._array(value)

    def vector(self, name: str, vec: Vec) -> None:
        out = np.empty((self.count, 2))
        out[:, 0], out[:, 1] = self._array(vec.x), self._array(vec.y)
        self.values[name] = out

    def result(self, level: int, groups: tuple[AssurGroup, ...], recipes: Mapping[str, Theta],
               owners: Mapping[str, str]) -> Result:
        rows = list(self.values.values())
        for array in rows:
            if array.flags.writeable:
                array.flags.writeable = False
        index = {name: number for number, name in enumerate(self.values)}
        schema = self.schema(level, groups, recipes, owners,
                             lambda name: Slot(ROW, index[name]))
        return Result(schema, rows, self.count, {})


def _layout_slot(layout: Layout) -> Callable[[str], Slot]:
    """Where an output of a compiled program is, from its layout."""
    def slot(name: str) -> Slot:
        where = layout.rows.get(name)
        if where is None:
            return Slot(CONSTANT, layout.constants[name])
        if isinstance(where, tuple):
            return Slot(PAIR, where[0])
        return Slot(ROW, where)

    return slot


# -- the model and its programs -------------------------------------------------------------------
class Model:
    """What every solve of one mechanism shares (see the module docstring).

    ``compilations`` counts the programs compiled for it (each stage and set of groups once);
    ``carriers`` maps each point to the links that carry it, in file order; ``memo`` holds
    what the higher group kinds keep per model (their assemblies and continuation paths).
    """

    def __init__(self, mechanism: Mechanism) -> None:
        self.mechanism = mechanism
        self.structure = analyse_structure(mechanism)
        self.compilations = 0
        self._branches: dict[tuple, dict[int, Branch]] = {}
        self._programs: dict[tuple, Program] = {}
        #: the program of every group on the branches chosen at drive.angle, per level
        self._whole: dict[int, Program] = {}
        self._lock = threading.Lock()
        #: the programs shared with the mechanism's posed copies (found at the first use)
        self._dyad_programs: tuple[dict, threading.Lock] | None = None
        self.carriers: dict[str, tuple[str, ...]] = {}
        for name, link in mechanism.links.items():
            for point in link.points:
                self.carriers[point] = (*self.carriers.get(point, ()), name)
        self.memo: dict[Hashable, object] = {}

    def sibling(self, mechanism: Mechanism) -> Model:
        """The model of another mechanism (e.g. this one at unit crank speed)."""
        return model(mechanism)

    def groups(self, links: Iterable[str] | None = None) -> tuple[AssurGroup, ...]:
        """The groups on the way to ``links`` (default: all), in build order."""
        if links is None:
            return self.structure.groups
        return self.structure.groups_needed(links)

    def branches(self, groups: Iterable[AssurGroup] | None = None) -> dict[int, Branch]:
        """Each group's assembly at ``drive.angle`` (chosen once)."""
        groups = self.structure.groups if groups is None else tuple(groups)
        key = tuple(group.index for group in groups)
        found = self._branches.get(key)
        if found is None:
            found = self._branches[key] = _branches_at_drive_angle(self, groups)
        return found

    def program(self, level: int, groups: tuple[AssurGroup, ...] | None = None,
                branches: Mapping[int, Branch] | None = None) -> Program:
        """The compiled :class:`Program` of ``groups`` (default: all) up to stage ``level`` on
        ``branches`` (default: those chosen at ``drive.angle``)."""
        whole = groups is None and branches is None
        if whole:
            found = self._whole.get(level)
            if found is not None:
                return found
        groups = self.structure.groups if groups is None else groups
        branches = self.branches(groups) if branches is None else branches
        key = (level, tuple(group.index for group in groups),
               tuple(branches[group.index] for group in groups))
        # a higher group's program follows its path from drive.angle: its model's own
        if not all(group.is_dyad for group in groups):
            programs, lock = self._programs, self._lock
        else:
            if self._dyad_programs is None:
                self._dyad_programs = _dyad_programs(self.mechanism)
            programs, lock = self._dyad_programs
        found = programs.get(key)
        if found is None:
            with lock:
                found = programs.get(key)
                if found is None:
                    found = self._compile(level, groups, branches)
                    if len(programs) > 64:
                        programs.clear()
                    programs[key] = found
        if whole:
            self._whole[level] = found
        return found

    def _compile(self, level: int, groups: tuple[AssurGroup, ...],
                 branches: Mapping[int, Branch]) -> Program:
        tracer = Tracer()
        writer = _TracedWriter(tracer)
        recipes, owned = build(self, groups, branches, level, tracer.angles(), writer)
        compiled = tracer.compile()
        self.compilations += 1
        schema = writer.schema(level, groups, recipes, owned, _layout_slot(compiled.layout))
        return Program(self, dict(branches), compiled, schema)

    def _evaluate(self, level: int, groups: tuple[AssurGroup, ...],
                  branches: Mapping[int, Branch], angles_deg: np.ndarray
                  ) -> tuple[_DirectWriter, dict[str, Theta], dict[str, str]]:
        writer = _DirectWriter(angles_deg.shape[0])
        recipes, owned = build(self, groups, branches, level, angles_deg, writer)
        return writer, recipes, owned

    def direct(self, level: int, groups: tuple[AssurGroup, ...],
               branches: Mapping[int, Branch], angles_deg: np.ndarray) -> Result:
        """The direct evaluation (numpy arrays, no tracing) of ``groups`` to stage ``level``
        on ``branches`` at ``angles_deg``: what their program computes, by the same formulas
        (it raises the errors of the first angle refused, group by group in build order)."""
        writer, recipes, owned = self._evaluate(level, groups, branches, angles_deg)
        return writer.result(level, groups, recipes, owned)

    def bodies(self, level: int, groups: tuple[AssurGroup, ...],
               branches: Mapping[int, Branch], angles_deg: np.ndarray) -> dict[str, Body]:
        """Every solved link's :class:`~planmethod.kinematics.algebra.Body` by the direct
        evaluation (see :meth:`direct`)."""
        result = self.direct(level, groups, branches, angles_deg)
        return {link: result.body(link) for link in result.schema.links}


@dataclass(frozen=True, eq=False)
class Program:
    """A compiled program of some groups on their ``branches`` to a stage: its ``compiled``
    function and the :class:`Schema` of what it writes. :meth:`run` evaluates it; a chunk of
    angles where a guard hands the evaluation back (:class:`~planmethod.kinematics.tracing.
    Redo`) is evaluated again directly (by the ``model`` it was compiled for)."""

    model: Model
    branches: Mapping[int, Branch]
    compiled: Compiled
    schema: Schema
    _constants: dict = field(default_factory=dict, repr=False)

    def run(self, angles_deg: np.ndarray) -> Result:
        """The program's outputs at ``angles_deg`` (a 1-D float64 array; read-only)."""
        rows = np.empty((self.compiled.layout.count, angles_deg.shape[0]))
        self.compiled.run(angles_deg, list(rows), self._redo)
        rows.flags.writeable = False
        return Result(self.schema, rows, angles_deg.shape[0], self._constants)

    def direct(self, angles_deg: np.ndarray) -> Result:
        """The direct evaluation of the same groups (see :meth:`Model.direct`)."""
        return self.model.direct(self.schema.level, self.schema.groups, self.branches,
                                 angles_deg)

    def _redo(self, angles_deg: np.ndarray, rows) -> None:
        """Evaluate a chunk again by the direct evaluation, into the program's result rows."""
        writer, _, _ = self.model._evaluate(self.schema.level, self.schema.groups,
                                            self.branches, angles_deg)
        values = writer.values
        for name, where in self.compiled.layout.rows.items():
            if isinstance(where, tuple):
                rows[where[0]][...] = values[name][:, 0]
                rows[where[1]][...] = values[name][:, 1]
            else:
                rows[where][...] = values[name]


# -- building ------------------------------------------------------------------------------------
#: degrees → radians: the factor np.radians multiplies by (the same bits, one plain multiply)
RADIAN = math.pi / 180.0


def _radians(angles):
    return angles * RADIAN


def drive_body(mechanism: Mechanism, angles) -> tuple[Body, Number]:
    """The drive link's body at crank angles ``angles`` (deg), and θ (rad)."""
    drive = mechanism.drive
    theta = _radians(angles)
    c, s = cos(theta), sin(theta)
    pivot_local = mechanism.local(drive.link, drive.pivot)
    px, py = (float(v) for v in mechanism.local(FRAME, drive.pivot))
    body = Body(c, s)
    turned = body.offset(float(pivot_local[0]), float(pivot_local[1]))
    body.x, body.y = px - turned.x, py - turned.y
    omega, epsilon = float(drive.omega), float(drive.epsilon)
    r = Vec(-turned.x, -turned.y)   # the origin's offset from the pivot
    body.omega, body.epsilon = omega, epsilon
    v = r.perp() * omega
    body.vx, body.vy = v.x, v.y
    a = r.perp() * epsilon - r * (omega * omega)
    body.ax, body.ay = a.x, a.y
    return body, theta


def _bounds(mechanism: Mechanism) -> dict[str, float]:
    """Upper bounds of the distance of the frame's and the drive link's points from the global
    origin, at any crank angle."""
    drive = mechanism.drive
    bounds = {name: math.hypot(*local) for name, local in mechanism.links[FRAME].points.items()}
    pivot = bounds.get(drive.pivot, 0.0)
    here = mechanism.links[drive.link]
    for name in here.points:
        bounds[name] = min(bounds.get(name, math.inf),
                           pivot + here.length(drive.pivot, name))
    return bounds


def _spread(mechanism: Mechanism, links: Iterable[str], bounds: dict[str, float]) -> None:
    """Every point of a link lies within the link's size of any of its points: bound the
    points of ``links`` from those already bounded."""
    for _ in range(2):
        for link in links:
            points = mechanism.links[link].points
            for name in points:
                if name not in bounds:
                    continue
                for other in points:
                    reach = bounds[name] + mechanism.links[link].length(name, other)
                    if reach < bounds.get(other, math.inf):
                        bounds[other] = reach


def owners(mechanism: Mechanism, solved: Iterable[str]) -> dict[str, str]:
    """Each point of the solved links → the first link (in file order) that carries it."""
    solved = set(solved)
    out: dict[str, str] = {}
    for name, link in mechanism.links.items():
        if name not in solved:
            continue
        for point in link.points:
            out.setdefault(point, name)
    return out


def build(model: Model, groups: tuple[AssurGroup, ...], branches: Mapping[int, Branch],
          level: int, angles, writer: _Writer) -> tuple[dict[str, Theta], dict[str, str]]:
    """Run the drive and each group's formulas up to stage ``level`` at ``angles`` (traced or
    arrays), writing the results to ``writer``; returns how the links' θ are read (the
    groups' recipes) and each named point's owner (see :func:`owners`)."""
    mechanism = model.mechanism
    bodies: dict[str, Body] = {FRAME: Body()}
    drive, theta = drive_body(mechanism, angles)
    bodies[mechanism.drive.link] = drive
    writer.theta(mechanism.drive.link, theta)
    bounds = _bounds(mechanism)
    recipes: dict[str, Theta] = {}
    named: dict[str, tuple] = {}   # point → (position, velocity, acceleration) from a group
    for group in groups:
        kind = kind_module(group)
        context = GroupInputs(mechanism, group, bodies, branches[group.index].sign, angles, bounds)
        if kind.closed_form:
            placed = kind.place(context)
            rates = evaluate_dyad(context, placed, level,
                                  stage_check(group, STAGES[max(level, 1)]))
            if rates.sine is not None:
                writer.sine(group.index, rates.sine)
            if placed.point in mechanism.links[placed.x_links[0]].points:
                named[placed.point] = (placed.x, rates.velocity, rates.acceleration)
            recipes.update(placed.thetas)
        else:
            solved = kind.evaluate(context, level, model, branches[group.index])
            for link, value in solved.thetas.items():
                writer.theta(link, value)
            writer.sine(group.index, solved.sine)
            recipes.update(solved.recipes)
        _spread(mechanism, group.links, bounds)
    solved_links = [FRAME, mechanism.drive.link] + [link for g in groups for link in g.links]
    for link in solved_links:
        writer.link(link, bodies[link], level)
    owned = owners(mechanism, solved_links)
    for point, link in owned.items():
        body = bodies[link]
        if point in named:
            position, velocity, acceleration = named[point]
        else:
            r = body.offset(*(float(v) for v in mechanism.local(link, point)))
            position = body.origin + r
            velocity = body.velocity(r) if level >= 1 else None
            acceleration = body.acceleration(r) if level >= 2 else None
        writer.point(point, position, velocity, acceleration, level)
    return recipes, owned


# -- the branch choice ---------------------------------------------------------------------------
def _sketch_distance(mechanism: Mechanism, links, bodies: Mapping[str, Body]) -> float | None:
    total, used = 0.0, False
    for link in links:
        body = bodies[link]
        for name, local in mechanism.links[link].points.items():
            if name in mechanism.sketch:
                place = body.point(float(local[0]), float(local[1]))
                sx, sy = mechanism.sketch[name]
                total += float(np.sum((np.asarray(place.x) - sx) ** 2
                                      + (np.asarray(place.y) - sy) ** 2))
                used = True
    return total if used else None


def _branches_at_drive_angle(model: Model, groups: Iterable[AssurGroup]
                             ) -> dict[int, Branch]:
    """Pick each group's assembly at ``drive.angle``: nearest (least squares) to the group's
    sketched points, else the default (+1 for a dyad; see docs/exercise-file.md)."""
    mechanism = model.mechanism
    angles = np.array([float(mechanism.drive.angle)])
    bodies: dict[str, Body] = {FRAME: Body()}
    bodies[mechanism.drive.link] = drive_body(mechanism, angles)[0]
    bounds = _bounds(mechanism)
    chosen: dict[int, Branch] = {}
    for group in groups:
        kind = kind_module(group)
        if not kind.closed_form:
            branch, placed_bodies = kind.choose(
                GroupInputs(mechanism, group, dict(bodies), 1.0, angles, bounds), model)
            chosen[group.index] = branch
            bodies.update(placed_bodies)
            _spread(mechanism, group.links, bounds)
            continue
        candidates: dict[int, dict[str, Body]] = {}
        errors = []
        for sign in ((1, -1) if kind.branches == 2 else (1,)):
            context = GroupInputs(mechanism, group, dict(bodies), sign, angles, bounds)
            try:
                candidates[sign] = kind.place(context).bodies
            except AssemblyError as error:
                errors.append(error)
        if not candidates:
            raise errors[0]
        if kind.branches == 1:
            branch = Branch(1, "unique")
        else:
            plus, minus = (None if sign not in candidates else
                           _sketch_distance(mechanism, group.links, candidates[sign])
                           for sign in (1, -1))
            if plus is None or minus is None or abs(plus - minus) <= (
                    1e-12 * (plus + minus) + 1e-24):
                branch = Branch(1 if 1 in candidates else -1, "default")
            else:
                branch = Branch(1 if plus < minus else -1, "sketch")
        chosen[group.index] = branch
        bodies.update(candidates[branch.sign])
        _spread(mechanism, group.links, bounds)
    return chosen
