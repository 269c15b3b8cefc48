"""The checks that refuse a group's position: a guard's exact check, run on the arrays where its
cheap bound fails (:meth:`~planmethod.kinematics.groups.base.GroupInputs.guard`), and the
estimate of the digits a stage keeps near a group's toggle.

A position is refused as an :class:`~planmethod.errors.AssemblyError` (the links cannot reach:
by how much) or a :class:`~planmethod.errors.ToggleError` (the group's construction lines are
parallel, or so near it that a stage would have no correct digit), at the first crank angle
where it happens.

Examples
--------
>>> round(float(size_ratio(0.0, 0.0, 0.3, 0.0, 0.2, 0.1)), 12)   # (|P1P2| + a + b) / min(a, b)
6.0
>>> 1e-8 < float(error_estimate(1.0, 1e-3, "velocity")) < 1e-6     # ε·R/s³ at s = 10⁻³
True
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ...errors import AssemblyError, ToggleError
from ...structure import AssurGroup, Joint
from ...words.message import Message, message, template

__all__ = ["EPS", "MARGIN", "ROUNDING_UNITS", "TOGGLE_SINE", "assembly_error", "coinciding",
           "error_estimate", "first", "parallel_guides", "size_ratio", "stage_check",
           "toggle_or_miss"]

#: the arithmetic's resolution (unit roundoff)
EPS = float(np.finfo(float).eps)
#: a vanishing factor within this many units of its own rounding error of zero is a toggle
#: position (the two assemblies coincide), not a failure to assemble
ROUNDING_UNITS = 16.0
#: below this |sin| of the angle between two guides a PRP or RPP dyad has no definite position
TOGGLE_SINE = 1e-10
#: the margin by which a guard's bound is widened, so that its rounding never hides an angle the
#: exact check refuses
MARGIN = 1.0 + 1e-6



def first(mask) -> int:
    return int(np.flatnonzero(np.atleast_1d(mask))[0])


#: a stage's check that finds the group's lines so close to parallel that the stage would keep
#: no correct digit, by stage (the velocities and the accelerations are checked)
_NO_DIGIT = {
    "velocity": template("toggle position: the group's two construction lines meet at "
                         "{angle:.3g}°, so close to parallel that its velocities would have no "
                         "correct digit"),
    "acceleration": template("toggle position: the group's two construction lines meet at "
                             "{angle:.3g}°, so close to parallel that its accelerations would "
                             "have no correct digit")}


def coinciding(first: Joint, second: Joint) -> Message:
    """Two external pins of a dyad that coincide: the group has no definite position."""
    return message("{point1} and {point2} coincide: the group has no definite position",
                   point1=first.point, point2=second.point)


def assembly_error(group: AssurGroup, angles, bad, text: Message, shortfall) -> AssemblyError:
    index = first(bad)
    amount = float(np.broadcast_to(np.asarray(shortfall, dtype=float),
                                   np.shape(np.atleast_1d(bad)))[index])
    # two points that coincide are no shortfall: the text says what is wrong
    told = message("{reason}: short by {amount:.6g} m", reason=text,
                   amount=amount) if amount else text
    return AssemblyError(told, shortfall=amount, link=group.name,
                         angle=float(np.atleast_1d(angles)[index]))


def toggle_or_miss(group: AssurGroup, angles, vanishing, scale, text: Message,
                   shortfall) -> None:
    """Raise at the first angle where a group cannot be assembled or is in its toggle position.

    ``vanishing`` is the factor of the discriminant that goes to zero at the toggle (a + b −
    |P1P2| for RRR), ``scale`` the size of the terms it was computed from: where |vanishing| ≤
    ROUNDING_UNITS·eps·scale its sign is lost in rounding — a toggle (ToggleError); below
    that the links cannot reach (AssemblyError saying by how much)."""
    vanishing = np.atleast_1d(np.asarray(vanishing, dtype=float))
    tolerance = ROUNDING_UNITS * EPS * np.asarray(scale, dtype=float)
    toggle = np.abs(vanishing) <= tolerance
    miss = (vanishing < 0) & ~toggle
    toggles, misses = np.flatnonzero(toggle), np.flatnonzero(miss)
    if misses.size and (not toggles.size or misses[0] < toggles[0]):
        raise assembly_error(group, angles, miss, text, shortfall)
    if toggles.size:
        raise ToggleError(
            message("toggle position: the group's links are stretched out or folded in line, "
                    "its two construction lines are parallel and its motion is not "
                    "determined"),
            line_angle_deg=0.0, link=group.name,
            angle=float(np.atleast_1d(angles)[int(toggles[0])]))


def parallel_guides(group: AssurGroup, angles, det, text: Message) -> None:
    bad = ~(np.abs(np.atleast_1d(det)) >= TOGGLE_SINE)
    if np.any(bad):
        raise ToggleError(text, line_angle_deg=0.0, link=group.name,
                          angle=float(np.atleast_1d(angles)[first(bad)]))


def stage_check(group: AssurGroup, stage: str) -> Callable:
    """The exact check of a stage's digits (a guard's ``check``): ε·R/s^(2k+1) must stay below
    1, R the size ratio at each angle (:func:`size_ratio`)."""

    def check(angles, sine, x1, y1, x2, y2, length1, length2) -> None:
        ratio = size_ratio(x1, y1, x2, y2, length1, length2)
        estimate = error_estimate(ratio, np.asarray(sine), stage)
        bad = ~(np.atleast_1d(estimate) < 1.0)
        if np.any(bad):
            index = first(bad)
            value = float(np.broadcast_to(np.asarray(sine), bad.shape)[index])
            angle = math.degrees(math.asin(min(1.0, abs(value))))
            raise ToggleError(
                _NO_DIGIT[stage].replace(angle=angle), line_angle_deg=angle, link=group.name,
                angle=float(np.atleast_1d(angles)[index]))

    return check


def size_ratio(x1, y1, x2, y2, length1, length2):
    """R = L / l: the group's size L (its radii plus the distance between its two base points)
    over its shortest radius l (R = 1 for a group without a rotation side; a sliding side's
    length is given as −1). The group's conditioning near its toggle is ε·R/s^(2k+1)."""
    radii = [np.asarray(length, dtype=float) for length in (length1, length2)
             if not (np.ndim(length) == 0 and float(length) < 0)]
    if not radii:
        return np.ones(np.shape(np.asarray(x1) - np.asarray(x2)))
    span = np.hypot(np.asarray(x1) - np.asarray(x2), np.asarray(y1) - np.asarray(y2))
    return (span + sum(radii)) / np.minimum.reduce(radii)


def error_estimate(ratio, sine, stage: str):
    """ε·R/s³ (velocities) or ε·R/s⁵ (accelerations)."""
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        size = np.abs(sine)
        power = size * size * size
        if stage == "acceleration":
            power = power * size * size
        return EPS * ratio / power
