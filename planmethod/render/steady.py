"""Steady frames: one zoom and one page per panel for a whole turn of the crank.

A workbook page or an animation shows the same panel at every crank angle. Drawn one by one,
each drawing would fit its own content: the zoom would change from frame to frame and the fixed
pivots and the poles would wander. :func:`steady_views` instead fixes each panel's zoom and the
box its content stays in from the exact motion over the whole turn (positions, and the images
of every point of every link on the velocity and acceleration plans at the plans' own scales),
so that the frame furniture — title, legend, scales — and the SVG's viewBox are the same at
every angle: the mechanism turns, the plans breathe round a pole that stays put.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> views = steady_views(load_exercise("exercises/compressor_slider_crank.toml"),
...                      [0.0, 90.0, 180.0, 270.0])
>>> sorted(views), views["velocity"].zoom == views["velocity"].zoom
(['acceleration', 'lever', 'position', 'velocity'], True)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..model import FRAME
from ..vectors import norm
from ..vocabulary import PlanKind
from .style import MECHANISM_SIZE, PLAN_SIZE

if TYPE_CHECKING:
    from ..model import Exercise

__all__ = ["SteadyView", "steady_views"]

#: room (px) kept round the content's box for labels beyond its outermost points
LABEL_ROOM = 34.0
#: room (px) kept round the mechanism's points for what is drawn beyond them: guides and
#: their hatching past a slider, ground symbols, tangents and normals of a path
MECHANISM_ROOM = 72.0


@dataclass(frozen=True, slots=True)
class SteadyView:
    """A panel kept steady over a turn: its zoom (px per mm of the drawing), the box
    ``(x0, y0, x1, y1)`` (page px, y down) its content stays in at every angle, and for a
    force polygon the force scale μF (N/mm) of the whole turn."""

    zoom: float
    box: tuple[float, float, float, float]
    scale: float | None = None


def _view(points_mm: np.ndarray, size: float, pad: bool, scale: float | None = None
          ) -> SteadyView:
    """The zoom that draws the points' longest side ``size`` px long, and their box on the
    page with the construction lines' pad (plans) and room for labels."""
    points = np.asarray(points_mm, dtype=float).reshape(-1, 2)
    points = points[np.all(np.isfinite(points), axis=1)]
    low, high = points.min(axis=0), points.max(axis=0)
    extent = float(max(high - low))
    zoom = size / extent if extent > 1e-9 else 10.0
    x0, x1 = low[0] * zoom, high[0] * zoom
    y0, y1 = -high[1] * zoom, -low[1] * zoom          # the page's y runs down
    room = LABEL_ROOM + (max(0.16 * extent * zoom, 40.0) if pad else MECHANISM_ROOM)
    return SteadyView(float(zoom), (float(x0 - room), float(y0 - room), float(x1 + room),
                                    float(y1 + room)), scale)


def steady_views(exercise: Exercise, angles: Sequence[float]) -> dict[str, SteadyView]:
    """Each panel's :class:`SteadyView` over ``angles``: ``position`` (the mechanism at μl, with
    the centres of curvature it draws), ``velocity`` and ``acceleration`` (every point's image,
    pole at the origin), ``lever`` (the velocity plan turned onto the mechanism), and with
    forces each group's polygon ``forces_<n>`` (at one force scale for the turn) and
    ``combined_force``."""
    from ..kinematics import solve
    from ..plans import choose_scales
    from ..scene import plan_scene
    mechanism = exercise.mechanism
    scales = choose_scales(exercise)
    scene = plan_scene(exercise)
    acceleration = exercise.ask.needs_acceleration or scene.forces
    motion = solve(mechanism, np.asarray(angles, dtype=float),
                   stage="acceleration" if acceleration else "velocity")
    where, velocity, accel = [], [np.zeros((1, 2))], [np.zeros((1, 2))]
    for name, link in mechanism.links.items():
        if name not in motion.links:
            continue
        state = motion.link_state(name)
        for local in link.points.values():
            where.append(motion.place(name, local))
            if name != FRAME:
                velocity.append(motion.velocity_of(name, local))
                if acceleration:
                    accel.append(motion.acceleration_of(name, local))
    for slide in mechanism.slides:           # the point of the guide under the slider (b₃)
        if slide.link in motion.links and slide.along in motion.links:
            state = motion.link_state(slide.along)
            at = motion.place(slide.link, mechanism.local(slide.link, slide.point))
            velocity.append(state.velocity_at(at))
            if acceleration:
                accel.append(state.acceleration_at(at))
            where.append(motion.place(slide.along, mechanism.local(slide.along, slide.through)))
    position_mm = np.concatenate(where) / scales.mu_l
    centres = _curvature_centres(exercise, motion, scales.mu_l, position_mm)
    velocity_mm = np.concatenate(velocity) / scales.mu_v
    views = {PlanKind.POSITION.value: _view(np.concatenate([position_mm, centres]),
                                            MECHANISM_SIZE, False),
             PlanKind.VELOCITY.value: _view(velocity_mm, PLAN_SIZE, True)}
    if acceleration:
        views[PlanKind.ACCELERATION.value] = _view(np.concatenate(accel) / scales.mu_a,
                                                   PLAN_SIZE, True)
    pivot = np.asarray(mechanism.local(FRAME, mechanism.drive.pivot)) / scales.mu_l
    turned = pivot + velocity_mm @ np.array([[0.0, -1.0], [1.0, 0.0]])   # (x, y) → (y, −x)
    views["lever"] = _view(np.concatenate([position_mm, turned]), MECHANISM_SIZE, True)
    if scene.forces:
        views |= _force_views(exercise, motion, scales.mu_a)
    return views


def _force_views(exercise, motion, mu_a: float) -> dict[str, SteadyView]:
    """The force polygons' views over the turn, at the one force scale that draws the
    largest force of the turn as long as ``force_mm`` asks; the combined-force figure's."""
    from ..forces import solve_forces
    from ..forces.analysis import FORCE_MM
    from ..plans.scales import standard

    solution = solve_forces(motion)
    groups = solution.groups.groups
    largest = max((float(norm(edge.vector).max()) for group in groups for edge in group.polygon),
                  default=0.0)
    plan = exercise.plan
    mu_f = plan.mu_f if plan.mu_f is not None else (
        1.0 if largest <= 0 else largest / (plan.force_mm or FORCE_MM) if plan.exact_mm
        else standard(largest / (plan.force_mm or FORCE_MM)))
    views = {}
    for number, group in enumerate(groups, start=1):
        vectors = np.stack([edge.vector for edge in group.polygon], axis=1) / mu_f  # (N, E, 2)
        corners = np.concatenate([np.zeros((vectors.shape[0], 1, 2)),
                                  np.cumsum(vectors, axis=1)], axis=1)
        views[f"forces_{number}"] = _view(corners, PLAN_SIZE, False, mu_f)
    gravity = exercise.mechanism.gravity or 0.0
    if gravity:
        images = [np.zeros((1, 2)), np.array([[0.0, -gravity / mu_a]])]
        for link, props in exercise.mechanism.masses.items():
            if link in motion.links:
                images.append(motion.acceleration_of(link, props.S) / mu_a)
        for link, points in ((name, link.points) for name, link in
                             exercise.mechanism.links.items() if name in motion.links):
            for local in points.values():
                images.append(motion.acceleration_of(link, local) / mu_a)
        views["combined_force"] = _view(np.concatenate(images), PLAN_SIZE, True)
    return views


def _curvature_centres(exercise, motion, mu_l: float, position_mm: np.ndarray) -> np.ndarray:
    """The centres of curvature the position plan draws over the turn (mm): those of the
    points whose ρ is asked, where ρ is within the sheet (as the plan draws them)."""
    ask = exercise.ask
    if not ask.curvature or motion.stage != "acceleration":
        return np.empty((0, 2))
    extent = float(max(position_mm.max(axis=0) - position_mm.min(axis=0)))
    out = []
    for point in ask.curvature:
        p, v, a = (motion.position(point), motion.velocity(point), motion.acceleration(point))
        speed = norm(v)
        along = (a * v).sum(axis=-1) / np.where(speed > 0, speed, 1.0)
        normal = a - along[:, None] * v / np.where(speed > 0, speed, 1.0)[:, None]
        size = norm(normal)
        with np.errstate(divide="ignore", invalid="ignore"):
            centre = p + (speed ** 2 / size ** 2)[:, None] * normal
        rho_mm = np.where(size > 0, speed ** 2 / np.where(size > 0, size, 1.0), np.inf) / mu_l
        out.append((centre / mu_l)[rho_mm <= 1.6 * extent])
    return np.concatenate(out) if out else np.empty((0, 2))
