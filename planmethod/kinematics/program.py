"""A mechanism's solve, built once: its structure, its branches and its compiled programs.

:func:`model` returns the :class:`Model` of a mechanism — one per mechanism *value* (an equal
mechanism built again finds the same one). A model chooses each group's assembly at
``drive.angle`` once (:meth:`Model.branches`) and compiles, per stage and set of groups, one
straight-line numpy function of the crank angles (:meth:`Model.program`): :func:`build` runs the
drive and every group kind's formulas in build order on traced values
(:mod:`~planmethod.kinematics.tracing`), and the recorded operations become the function. The
same :func:`build` run on numpy arrays is the direct evaluation (the reference path).

What a program writes (its :class:`~planmethod.kinematics.tracing.Layout`): for each solved
link ``axes:L`` (cos θ, sin θ), ``origin:L``, and with the stages ``omega:L``, ``velocity:L``
(of its origin), ``epsilon:L``, ``acceleration:L``; for each named point ``p:P``, ``v:P``,
``a:P`` (as a point of the first link in file order that carries it); ``theta:L`` of the drive
(and of links whose θ is solved by Newton); ``sine:i``, the sine of the angle between group i's
two construction lines.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> mechanism = load_exercise("exercises/compressor_slider_crank.toml").mechanism
>>> found = model(mechanism)
>>> found is model(load_exercise("exercises/compressor_slider_crank.toml").mechanism)
True
>>> found.branches()[0]
Branch(sign=1, reason='sketch')
"""

from __future__ import annotations

import dataclasses
import math
import threading
from collections import OrderedDict
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from ..errors import AssemblyError
from ..model import FRAME, Mechanism
from ..structure import AssurGroup, analyse_structure
from .algebra import Body, Vec, cos, sin
from .groups import kind_module
from .groups.base import Branch, GroupInputs, evaluate_dyad, stage_check
from .tracing import Compiled, Tracer

__all__ = ["STAGES", "Branch", "Model", "build", "model"]

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


class Model:
    """What every solve of one mechanism shares (see the module docstring).

    ``compilations`` counts the programs compiled for it (each stage and set of groups once).
    """

    def __init__(self, mechanism: Mechanism) -> None:
        self.mechanism = mechanism
        self.structure = analyse_structure(mechanism)
        self.compilations = 0
        self._branches: dict[tuple, dict[int, Branch]] = {}
        self._programs: dict[tuple, Compiled] = {}
        self._lock = threading.Lock()
        #: the programs shared with the mechanism's posed copies (found at the first use)
        self._dyad_programs: tuple[dict, threading.Lock] | None = None
        #: point → the links that carry it, in file order
        self.carriers: dict[str, tuple[str, ...]] = {}
        for name, link in mechanism.links.items():
            for point in link.points:
                self.carriers[point] = (*self.carriers.get(point, ()), name)
        #: stage level → (groups, branches, program, thetas, solved links, point owners) of a
        #: whole solve
        self.whole: dict[int, tuple] = {}
        self.memo: dict[Any, Any] = {}  # per-model values of the higher group kinds

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

    def program(self, level: int, groups: tuple[AssurGroup, ...],
                branches: Mapping[int, Branch]) -> Compiled:
        """The compiled program of ``groups`` up to stage ``level`` on ``branches``."""
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
                    tracer = Tracer()
                    placements = build(self, groups, branches, level, tracer.angles(),
                                       _TracedOutputs(tracer))
                    compiled = tracer.compile()
                    compiled.redo = _Redo(self, level, groups, branches, compiled)
                    found = (compiled, _thetas(placements))
                    self.compilations += 1
                    if len(programs) > 64:
                        programs.clear()
                    programs[key] = found
        return found

    def direct(self, level: int, groups: tuple[AssurGroup, ...],
               branches: Mapping[int, Branch], angles_deg: np.ndarray) -> tuple[dict, dict]:
        """The direct evaluation (numpy arrays, no tracing): the outputs by name, and how each
        link's θ is read."""
        outputs = _DirectOutputs(angles_deg.shape[0])
        placements = build(self, groups, branches, level, angles_deg, outputs)
        return outputs.values, _thetas(placements)


class _Redo:
    """Evaluates a chunk again by the direct evaluation, into the program's result rows."""

    def __init__(self, model: Model, level: int, groups, branches, compiled: Compiled) -> None:
        self.model, self.level, self.groups, self.branches = model, level, groups, branches
        self.layout = compiled.layout

    def __call__(self, angles_deg: np.ndarray, rows) -> None:
        values, _ = self.model.direct(self.level, self.groups, self.branches, angles_deg)
        for name, where in self.layout.rows.items():
            if isinstance(where, tuple):
                rows[where[0]][...] = values[name][:, 0]
                rows[where[1]][...] = values[name][:, 1]
            else:
                rows[where][...] = values[name]


def _thetas(placements: Mapping[int, Any]) -> dict:
    out = {}
    for placed in placements.values():
        out.update(getattr(placed, "thetas", None) or {})
    return out


class _TracedOutputs:
    def __init__(self, tracer: Tracer) -> None:
        self.tracer = tracer

    def scalar(self, name: str, value) -> None:
        self.tracer.output(name, value)

    def vector(self, name: str, vec: Vec) -> None:
        self.tracer.output_vector(name, vec.x, vec.y)


class _DirectOutputs:
    def __init__(self, count: int) -> None:
        self.count = count
        self.values: dict[str, np.ndarray] = {}

    def _array(self, value) -> np.ndarray:
        if (type(value) is np.ndarray and value.dtype == np.float64
                and value.shape == (self.count,)):
            return value.view()    # (a view of its own: a reader may make it read-only)
        return np.broadcast_to(np.asarray(value, dtype=float), (self.count,))

    def scalar(self, name: str, value) -> None:
        self.values[name] = self._array(value)

    def vector(self, name: str, vec: Vec) -> None:
        out = np.empty((self.count, 2))
        out[:, 0], out[:, 1] = self._array(vec.x), self._array(vec.y)
        self.values[name] = out


# -- building ------------------------------------------------------------------------------------
#: degrees → radians: the factor np.radians multiplies by (the same bits, one plain multiply)
RADIAN = math.pi / 180.0


def _radians(angles):
    return angles * RADIAN


def drive_body(mechanism: Mechanism, angles) -> tuple[Body, Any]:
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
          level: int, angles, outputs) -> dict[int, Any]:
    """Run the drive and each group's formulas up to stage ``level`` at ``angles`` (traced or
    arrays), naming the results in ``outputs``; returns each group's placement."""
    mechanism = model.mechanism
    bodies: dict[str, Body] = {FRAME: Body()}
    drive, theta = drive_body(mechanism, angles)
    bodies[mechanism.drive.link] = drive
    outputs.scalar(f"theta:{mechanism.drive.link}", theta)
    bounds = _bounds(mechanism)
    placements: dict[int, Any] = {}
    named: dict[str, tuple] = {}   # point → (position, velocity, acceleration) from a group
    for group in groups:
        kind = kind_module(group)
        context = GroupInputs(mechanism, group, bodies, branches[group.index].sign, angles, bounds)
        if kind.closed_form:
            placed = kind.place(context)
            found = evaluate_dyad(context, placed, level,
                                  stage_check(group, STAGES[max(level, 1)]))
            if "sine" in found:
                outputs.scalar(f"sine:{group.index}", found["sine"])
            if placed.point in mechanism.links[placed.x_links[0]].points:
                named[placed.point] = (placed.x, found.get("v_x"), found.get("a_x"))
            placements[group.index] = placed
        else:
            found = kind.evaluate(context, level, model, branches[group.index], outputs)
            placements[group.index] = found
        _spread(mechanism, group.links, bounds)
    solved = [FRAME, mechanism.drive.link] + [link for g in groups for link in g.links]
    for link in solved:
        body = bodies[link]
        outputs.vector(f"axes:{link}", Vec(body.cos, body.sin))
        outputs.vector(f"origin:{link}", body.origin)
        if level >= 1:
            outputs.scalar(f"omega:{link}", body.omega)
            outputs.vector(f"velocity:{link}", Vec(body.vx, body.vy))
        if level >= 2:
            outputs.scalar(f"epsilon:{link}", body.epsilon)
            outputs.vector(f"acceleration:{link}", Vec(body.ax, body.ay))
    for point, link in owners(mechanism, solved).items():
        body = bodies[link]
        if point in named:
            position, velocity, acceleration = named[point]
        else:
            r = body.offset(*(float(v) for v in mechanism.local(link, point)))
            position = body.origin + r
            velocity = body.velocity(r) if level >= 1 else None
            acceleration = body.acceleration(r) if level >= 2 else None
        outputs.vector(f"p:{point}", position)
        if level >= 1:
            outputs.vector(f"v:{point}", velocity)
        if level >= 2:
            outputs.vector(f"a:{point}", acceleration)
    return placements


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
        candidates: dict[int, Any] = {}
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
