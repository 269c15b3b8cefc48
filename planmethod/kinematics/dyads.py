"""Exact closed-form positions of the five dyads, and each dyad's pair of vector equations.

Positions come in closed form per kind (circle–circle, circle–line, line–line intersections,
or the RPR rotation about the guide). Velocities and accelerations of every dyad then follow
from one uniform statement, the one a student writes on the plan: the construction point X of
the group is reached from two known points, each by a vector of known direction and unknown
length,

    v_X = v_base1 + u1·e1 = v_base2 + u2·e2,

where a *rotation* side has e ⟂ (X − centre) and u = ω·|X − centre|, and a *sliding* side has
e along the guide and u the relative sliding velocity. The same two lines are intersected on
the velocity plan; accelerations add the normal (−ω²·r) or Coriolis (2ω × v_rel) term to the
known part. The 2 × 2 solve is exact (Cramer's rule); parallel lines are the group's toggle.

=====  ===========================  =======================  =======================
kind   construction point X         side 1                   side 2
=====  ===========================  =======================  =======================
RRR    internal pin Q               L1 turns about P1        L2 turns about P2
RRP    internal pin Q               L1 turns about P1        slides along K2's guide
RPR    P1 as a point of L2          slides relative to L1    L2 turns about P2
PRP    internal pin Q               slides along K1's guide  slides along K2's guide
RPP    P1 as a point of L2          slides relative to L1    slides along K2's guide
=====  ===========================  =======================  =======================

Examples
--------
>>> import numpy as np
>>> center, radius = np.array([[0.0, 0.0]]), 0.18
>>> circle_line(center, radius, np.array([[0.0, 1.0]]), np.array([0.04242640687]),
...             +1, np.array([1.0, 0.0]) + 0 * center).round(6)
array([[0.174929, 0.042426]])
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import AssemblyError, StructureError, ToggleError
from ..model import Mechanism, Slide
from ..structure import AssurGroup, Joint
from .state import LinkState, cross, norm, perp, rotate, unit, unit_angle

__all__ = [
    "TOGGLE_SINE",
    "Construction",
    "Side",
    "branch_count",
    "circle_line",
    "construct",
    "dyad_positions",
    "solve_pair",
]

#: Below this |sin| of the angle between two guides a PRP or RPP dyad has no definite position,
#: and a drawn intersection is never attempted. (A dyad's velocities and accelerations have
#: their own, sharper limits from the arithmetic's resolution: see ``solve``.)
TOGGLE_SINE = 1e-10


@dataclass(frozen=True, slots=True)
class Side:
    """One side of a dyad's vector equation v_X = v_base + u·e.

    ``kind`` is ``"rotation"`` (``link`` turns about the centre ``base``; e ⟂ ``radius``) or
    ``"sliding"`` (X's link translates relative to the carrier ``link`` along e).
    ``base_link`` is a link already known whose material point at ``base_position`` has the
    base velocity and acceleration.
    """

    kind: str
    link: str
    base: str
    base_link: str
    base_position: np.ndarray
    direction: np.ndarray
    radius: np.ndarray | None = None
    slide: Slide | None = None


@dataclass(frozen=True, slots=True)
class Construction:
    """The dyad's construction point X, its two sides, and how its links' ω follow.

    ``rotating`` maps a link to the index of the rotation side that gives its ω; ``tied`` maps a
    link to the link whose ω it shares (prismatic pairs forbid relative rotation); ``anchors``
    maps a link to (its known pin position, the known link through which the pin moves), or is
    missing for a link whose motion is referred to X itself.
    """

    group: AssurGroup
    point: str
    position: np.ndarray
    sides: tuple[Side, Side]
    rotating: Mapping[str, int]
    tied: Mapping[str, str]
    anchors: Mapping[str, tuple[str, np.ndarray, str]]
    x_links: tuple[str, ...]

    def reference(self, link: str) -> tuple[str, np.ndarray, str | None]:
        """(name, position, known link) of the point a group link's motion is referred to: its
        pin on a known link (whose motion gives the pin's), or X itself (known link None)."""
        if link in self.anchors:
            return self.anchors[link]
        return self.point, self.position, None

    def size_ratio(self) -> np.ndarray:
        """R = L / l: the group's size L (its radii plus the distance between its two base
        points) over its shortest radius l (R = 1 for a group without a rotation side).
        The group's conditioning near its toggle is ε·R/s^(2k+1) (see ``solve``)."""
        radii = [norm(side.radius) for side in self.sides if side.radius is not None]
        span = norm(self.sides[0].base_position - self.sides[1].base_position)
        if not radii:
            return np.ones_like(span)
        total = span + sum(radii)
        return total / np.minimum.reduce(radii)

    def follow_tied(self, values: dict, known: Callable[[str], object]) -> None:
        """Give each link whose rotation a prismatic pair ties to another link that link's ω
        (or ε): ``values`` holds the group's own, ``known(link)`` those of links already known
        (None where not known)."""
        pending = dict(self.tied)
        while pending:
            for link, other in list(pending.items()):
                source = values.get(other)
                if source is None:
                    source = known(other)
                if source is not None:
                    values[link] = source
                    del pending[link]


def branch_count(kind: str) -> int:
    """How many assemblies a dyad kind has at a generic position (2, or 1 for PRP and RPP)."""
    return 1 if kind in ("PRP", "RPP") else 2


# -- small geometric solves -------------------------------------------------------------------
def circle_line(center: np.ndarray, radius, normal: np.ndarray, offset: np.ndarray,
                branch: int, direction: np.ndarray) -> np.ndarray:
    """Intersection of the circle (center, radius) with the line normal·x = offset.

    ``branch`` +1 takes the point further along ``direction`` (a unit vector along the line).
    Returns NaN rows where the line misses the circle (callers check the discriminant first).
    """
    h = np.einsum("...i,...i->...", normal, center) - offset
    foot = center - h[..., None] * normal
    along = np.sqrt(np.asarray(radius) ** 2 - h ** 2)
    return foot + branch * along[..., None] * direction


def solve_pair(w: np.ndarray, e1: np.ndarray, e2: np.ndarray):
    """Solve u1·e1 − u2·e2 = w by Cramer's rule; returns (u1, u2, sin of the lines' angle)."""
    det = cross(e1, e2)
    return cross(w, e2) / det, cross(w, e1) / det, det


def _first_bad(mask: np.ndarray) -> int:
    return int(np.flatnonzero(mask)[0])


#: A discriminant whose vanishing factor is within this many units of its own rounding error of
#: zero is a toggle position (the two assemblies coincide), not a failure to assemble.
ROUNDING_UNITS = 16.0


def _toggle_or_miss(group, angles_deg, vanishing, scale, text, shortfall) -> None:
    """Raise at the first angle where a group cannot be assembled or is in its toggle position.

    ``vanishing`` is the factor of the discriminant that goes to zero at the toggle (e.g.
    a + b − |P1P2| for RRR), ``scale`` the size of the terms it was computed from: where
    |vanishing| ≤ ROUNDING_UNITS·eps·scale the sign is lost in rounding — a toggle (ToggleError);
    below that the links cannot reach (AssemblyError saying by how much).
    """
    tolerance = ROUNDING_UNITS * np.finfo(float).eps * scale
    toggle = np.abs(vanishing) <= tolerance
    miss = (vanishing < 0) & ~toggle
    first_toggle = np.flatnonzero(toggle)
    first_miss = np.flatnonzero(miss)
    if first_miss.size and (not first_toggle.size or first_miss[0] < first_toggle[0]):
        raise _assembly_error(group, angles_deg, miss, text, shortfall)
    if first_toggle.size:
        index = int(first_toggle[0])
        raise ToggleError(
            "toggle position: the group's links are stretched out or folded in line, its two "
            "construction lines are parallel and its motion is not determined",
            line_angle_deg=0.0, link=group.name, angle=float(angles_deg[index]))


# -- helpers on pairs -------------------------------------------------------------------------
def _group_link(joint: Joint, group: AssurGroup) -> str:
    return joint.links[0] if joint.links[0] in group.links else joint.links[1]


def _pin(mechanism: Mechanism, joint: Joint, group: AssurGroup, states) -> tuple:
    """(group link, known link, local point in the group link, global position) of a pin."""
    link = _group_link(joint, group)
    known = joint.other(link)
    return link, known, mechanism.local(link, joint.point), states[known].place(
        mechanism.local(known, joint.point))


def _slide_theta(slide: Slide, unknown: str, known_theta: np.ndarray) -> np.ndarray:
    """Orientation of ``unknown`` fixed by a prismatic pair with a link of known orientation."""
    return known_theta + slide.direction_rad if unknown == slide.link else (
        known_theta - slide.direction_rad)


def _slide_line(mechanism: Mechanism, slide: Slide, unknown: str, theta: np.ndarray,
                known_state: LinkState):
    """The prismatic pair as a line for the unknown link's origin: (n, c, d) with n·o = c.

    ``d`` is the guide's global direction and n = J·d.
    """
    if unknown == slide.link:
        d = unit_angle(known_state.theta + slide.direction_rad)
        n = perp(d)
        through = known_state.place(mechanism.local(slide.along, slide.through))
        own = rotate(mechanism.local(slide.link, slide.point), theta)
        return n, np.einsum("...i,...i->...", n, through - own), d
    d = unit_angle(theta + slide.direction_rad)
    n = perp(d)
    point = known_state.place(mechanism.local(slide.link, slide.point))
    own = rotate(mechanism.local(slide.along, slide.through), theta)
    return n, np.einsum("...i,...i->...", n, point - own), d


def _pose_from_pin(local, position, theta):
    if local[0] == 0 and local[1] == 0:  # the pin is the link's origin
        return theta, position.copy()
    return theta, position - rotate(local, theta)


def _pose_from_two(local_a, local_b, position_a, position_b):
    """Pose of a link whose points a, b are at the given global positions."""
    la, lb = np.asarray(local_a, float), np.asarray(local_b, float)
    theta = (np.arctan2(position_b[..., 1] - position_a[..., 1],
                        position_b[..., 0] - position_a[..., 0])
             - np.arctan2(lb[1] - la[1], lb[0] - la[0]))
    return _pose_from_pin(la, position_a, theta)


def _need_length(length: float, what: str, group: AssurGroup) -> None:
    if not length > 1e-12:
        raise StructureError(f"{what} has zero length: the group has no definite position",
                             link=group.name)


# -- positions ---------------------------------------------------------------------------------
def dyad_positions(mechanism: Mechanism, group: AssurGroup, states: Mapping[str, LinkState],
                   branch: int, angles_deg: np.ndarray) -> dict[str, tuple]:
    """Closed-form poses ``{link: (theta, origin)}`` of a dyad's two links.

    Raises
    ------
    AssemblyError
        At the first crank angle where the group cannot be assembled, saying by how much the
        links fall short.
    """
    solver = _POSITIONS[group.kind]
    return solver(mechanism, group, states, branch, angles_deg)


def _assembly_error(group, angles_deg, bad, text, shortfall) -> AssemblyError:
    index = _first_bad(bad)
    amount = float(np.atleast_1d(shortfall)[index])
    return AssemblyError(f"{text}: short by {amount:.6g} m", shortfall=amount,
                         link=group.name, angle=float(angles_deg[index]))


def _rrr(mechanism, group, states, branch, angles_deg):
    ext1, internal, ext2 = group.joints
    l1, _, p1_local, p1 = _pin(mechanism, ext1, group, states)
    l2, _, p2_local, p2 = _pin(mechanism, ext2, group, states)
    q1_local = mechanism.local(l1, internal.point)
    q2_local = mechanism.local(l2, internal.point)
    a = mechanism.links[l1].length(ext1.point, internal.point)
    b = mechanism.links[l2].length(ext2.point, internal.point)
    _need_length(a, f"{l1} ({ext1.point}{internal.point})", group)
    _need_length(b, f"{l2} ({ext2.point}{internal.point})", group)
    span = p2 - p1
    d = norm(span)
    # Heron's form keeps the height accurate near the toggle (a + b ≈ d or |a − b| ≈ d).
    product = (a + b + d) * (a + b - d) * (a - b + d) * (b - a + d)
    if np.any(d <= 1e-15 * (a + b)):
        raise _assembly_error(group, angles_deg, d <= 1e-15 * (a + b),
                              f"{ext1.point} and {ext2.point} coincide: the group has no "
                              "definite position", np.zeros_like(d))
    # the factor that vanishes: a + b − d (stretched out) or d − |a − b| (folded); of the
    # three factors a + b − d, a − b + d, b − a + d the one smallest in magnitude (the first
    # on a tie), computed without stacking them
    stretched, folded = a + b - d, d - abs(a - b)
    vanishing = np.where(np.abs(stretched) <= np.abs(folded), stretched, folded)
    reach = np.maximum(np.abs(span[..., 0]), np.abs(span[..., 1]))
    _toggle_or_miss(group, angles_deg, vanishing, a + b + d + reach,
                    f"{l1} ({ext1.point}{internal.point} = {a:g} m) and {l2} ({internal.point}"
                    f"{ext2.point} = {b:g} m) cannot join {ext1.point} and {ext2.point}",
                    np.maximum(d - a - b, np.maximum(abs(a - b) - d, 0.0)))
    u = span / d[..., None]
    x = (a * a - b * b + d * d) / (2 * d)
    h = np.sqrt(np.maximum(product, 0.0)) / (2 * d)
    q = p1 + x[..., None] * u + branch * h[..., None] * perp(u)
    return {l1: _pose_from_two(p1_local, q1_local, p1, q),
            l2: _pose_from_two(p2_local, q2_local, p2, q)}


def _rrp(mechanism, group, states, branch, angles_deg):
    ext1, internal, ext2 = group.joints
    l1, _, p1_local, p1 = _pin(mechanism, ext1, group, states)
    l2 = _group_link(ext2, group)
    k2 = ext2.other(l2)
    theta2 = _slide_theta(ext2.slide, l2, states[k2].theta)
    n, c, d = _slide_line(mechanism, ext2.slide, l2, theta2, states[k2])
    q2_local = mechanism.local(l2, internal.point)
    offset = c + np.einsum("...i,...i->...", n, rotate(q2_local, theta2))
    a = mechanism.links[l1].length(ext1.point, internal.point)
    _need_length(a, f"{l1} ({ext1.point}{internal.point})", group)
    h = np.einsum("...i,...i->...", n, p1) - offset
    scale = a + np.abs(offset) + np.max(np.abs(p1), axis=-1)
    _toggle_or_miss(group, angles_deg, a - np.abs(h), scale,
                    f"{l1} ({ext1.point}{internal.point} = {a:g} m) cannot reach the line of "
                    f"{internal.point} along {ext2.slide.along}'s guide", np.abs(h) - a)
    q = circle_line(p1, a, n, offset, branch, d)
    q1_local = mechanism.local(l1, internal.point)
    return {l1: _pose_from_two(p1_local, q1_local, p1, q),
            l2: _pose_from_pin(q2_local, q, theta2)}


def _rpr(mechanism, group, states, branch, angles_deg):
    ext1, internal, ext2 = group.joints
    slide = internal.slide
    l1, _, p1_local, p1 = _pin(mechanism, ext1, group, states)   # l1 == slide.link
    l2, _, p2_local, p2 = _pin(mechanism, ext2, group, states)   # l2 == slide.along
    # In l2's frame: P1 = T + s·u + R(dir)(P1_l1 − S_l1); the vector P2→P1 is c0 + s·u.
    u = np.array([np.cos(slide.direction_rad), np.sin(slide.direction_rad)])
    through = np.asarray(mechanism.local(l2, slide.through))
    c0 = (through - np.asarray(p2_local)
          + rotate(np.subtract(p1_local, mechanism.local(l1, slide.point)), slide.direction_rad))
    span = p1 - p2
    length = norm(span)
    offset = float(c0[0] * u[1] - c0[1] * u[0])
    if np.any(length <= 1e-15):
        raise _assembly_error(group, angles_deg, length <= 1e-15,
                              f"{ext1.point} and {ext2.point} coincide: the group has no "
                              "definite position", np.zeros_like(length))
    if offset != 0:
        _toggle_or_miss(group, angles_deg, length - abs(offset),
                        length + abs(offset) + np.max(np.abs(span), axis=-1),
                        f"the guide of {l2} passes {abs(offset):g} m from its pivot "
                        f"{ext2.point}; it cannot reach {ext1.point}", np.abs(offset) - length)
    s = -float(c0 @ u) + branch * np.sqrt(length ** 2 - offset ** 2)
    in_l2 = c0 + s[..., None] * u
    theta2 = (np.arctan2(span[..., 1], span[..., 0]) - np.arctan2(in_l2[..., 1], in_l2[..., 0]))
    theta1 = theta2 + slide.direction_rad
    return {l1: _pose_from_pin(p1_local, p1, theta1), l2: _pose_from_pin(p2_local, p2, theta2)}


def _prp(mechanism, group, states, branch, angles_deg):
    ext1, internal, ext2 = group.joints
    lines = []
    for joint in (ext1, ext2):
        link = _group_link(joint, group)
        known = joint.other(link)
        theta = _slide_theta(joint.slide, link, states[known].theta)
        n, c, _ = _slide_line(mechanism, joint.slide, link, theta, states[known])
        local = mechanism.local(link, internal.point)
        lines.append((link, theta, n, c + np.einsum("...i,...i->...", n, rotate(local, theta)),
                      local))
    (l1, t1, n1, c1, q1), (l2, t2, n2, c2, q2) = lines
    det = cross(n1, n2)
    bad = np.abs(det) < TOGGLE_SINE
    if np.any(bad):
        index = _first_bad(bad)
        raise ToggleError(f"the guides of {ext1.slide.key} and {ext2.slide.key} are parallel: "
                          f"{internal.point} has no definite position",
                          line_angle_deg=0.0, link=group.name, angle=float(angles_deg[index]))
    q = np.stack(((c1 * n2[..., 1] - c2 * n1[..., 1]) / det,
                  (n1[..., 0] * c2 - n2[..., 0] * c1) / det), axis=-1)
    return {l1: _pose_from_pin(q1, q, t1), l2: _pose_from_pin(q2, q, t2)}


def _rpp(mechanism, group, states, branch, angles_deg):
    ext1, internal, ext2 = group.joints
    l1, _, p1_local, p1 = _pin(mechanism, ext1, group, states)
    l2 = _group_link(ext2, group)
    k2 = ext2.other(l2)
    theta2 = _slide_theta(ext2.slide, l2, states[k2].theta)
    theta1 = _slide_theta(internal.slide, l1, theta2)
    state1 = LinkState(*_pose_from_pin(p1_local, p1, theta1))
    n2, c2, _ = _slide_line(mechanism, ext2.slide, l2, theta2, states[k2])
    n1, c1, _ = _slide_line(mechanism, internal.slide, l2, theta2, state1)
    det = cross(n1, n2)
    bad = np.abs(det) < TOGGLE_SINE
    if np.any(bad):
        index = _first_bad(bad)
        raise ToggleError(f"the guides of {internal.slide.key} and {ext2.slide.key} are "
                          f"parallel: {l2} has no definite position", line_angle_deg=0.0,
                          link=group.name, angle=float(angles_deg[index]))
    origin = np.stack(((c1 * n2[..., 1] - c2 * n1[..., 1]) / det,
                       (n1[..., 0] * c2 - n2[..., 0] * c1) / det), axis=-1)
    return {l1: (theta1, state1.origin), l2: (theta2, origin)}


_POSITIONS = {"RRR": _rrr, "RRP": _rrp, "RPR": _rpr, "PRP": _prp, "RPP": _rpp}


# -- the two vector equations -------------------------------------------------------------------
def _sliding_side(mechanism, joint: Joint, group, states, carrier: str, base: str,
                  base_link: str, base_position) -> Side:
    slide = joint.slide
    direction = unit_angle(states[slide.along].theta + slide.direction_rad)
    return Side("sliding", carrier, base, base_link, base_position, direction, slide=slide)


def _rotation_side(link: str, centre: str, centre_link: str, centre_position, x) -> Side:
    radius = x - centre_position
    return Side("rotation", link, centre, centre_link, centre_position, perp(unit(radius)),
                radius=radius)


def construct(mechanism: Mechanism, group: AssurGroup,
              states: Mapping[str, LinkState]) -> Construction:
    """The dyad's construction point and its two sides, from solved positions in ``states``
    (which must hold the group's links and the links it is attached to)."""
    ext1, internal, ext2 = group.joints
    l1, l2 = group.links
    kind = group.kind

    def pin(joint):
        link, known, _, position = _pin(mechanism, joint, group, states)
        return link, known, position

    if kind in ("RRR", "RRP", "PRP"):
        x_name = internal.point
        x = states[l1].place(mechanism.local(l1, x_name))
        x_links = (l1, l2)
    else:  # RPR, RPP: P1 taken as a point of L2
        x_name = f"{ext1.point}@{l2}"
        x = pin(ext1)[2]
        x_links = (l2,)
    anchors: dict[str, tuple[str, np.ndarray, str]] = {}
    for joint in (ext1, ext2):
        if joint.kind == "R":
            link, known, position = pin(joint)
            anchors[link] = (joint.point, position, known)

    def ext_sliding(joint):
        link = _group_link(joint, group)
        known = joint.other(link)
        return _sliding_side(mechanism, joint, group, states, known,
                             f"{x_name.partition('@')[0]}@{known}",
                             known, x)

    if kind == "RRR":
        sides = (_rotation_side(l1, ext1.point, anchors[l1][2], anchors[l1][1], x),
                 _rotation_side(l2, ext2.point, anchors[l2][2], anchors[l2][1], x))
        rotating, tied = {l1: 0, l2: 1}, {}
    elif kind == "RRP":
        sides = (_rotation_side(l1, ext1.point, anchors[l1][2], anchors[l1][1], x),
                 ext_sliding(ext2))
        rotating, tied = {l1: 0}, {l2: ext2.other(l2)}
    elif kind == "RPR":
        first = _sliding_side(mechanism, internal, group, states, l1, ext1.point,
                              anchors[l1][2], anchors[l1][1])
        sides = (first, _rotation_side(l2, ext2.point, anchors[l2][2], anchors[l2][1], x))
        rotating, tied = {l2: 1}, {l1: l2}
    elif kind == "PRP":
        sides = (ext_sliding(ext1), ext_sliding(ext2))
        rotating, tied = {}, {l1: ext1.other(l1), l2: ext2.other(l2)}
    else:  # RPP
        first = _sliding_side(mechanism, internal, group, states, l1, ext1.point,
                              anchors[l1][2], anchors[l1][1])
        sides = (first, ext_sliding(ext2))
        rotating, tied = {}, {l2: ext2.other(l2), l1: l2}
    return Construction(group, x_name, x, sides, rotating, tied, anchors, x_links)
