"""Helpers for tests and benchmarks: reference mechanisms and independent exact solvers.

* :mod:`planmethod.testing.mechanisms` — the reference mechanisms as exercise dicts
  (:func:`fourbar`, :func:`slider_crank`, :func:`slotted_lever`, :func:`scotch_yoke`,
  :func:`two_guides`, :func:`shaper`);
* :mod:`planmethod.testing.oracles` — the oracles: :func:`reference_motion` (positions by
  Newton on the whole mechanism's constraint equations, continued from the sketch at
  ``drive.angle``; velocities and accelerations by exact linear solves; none of the solver's
  code) and the 40-digit closed forms :func:`exact_fourbar` and :func:`exact_slider_crank`
  (mpmath, from the ``test`` extra, imported only when called);
* :mod:`planmethod.testing.stress` — the stress checker: a solve judged angle by angle against
  the 40-digit closed forms within stated bounds;
* :mod:`planmethod.testing.processes` — :func:`processes_holding`, the processes a command and
  its workers left.

Examples
--------
>>> from planmethod.spec import exercise_from_dict
>>> mechanism = exercise_from_dict(fourbar()).mechanism
>>> round(float(reference_motion(mechanism, [60.0])["CD"]["omega"][0]), 6)
2.448975
"""

from __future__ import annotations

from .mechanisms import (
    fourbar,
    scotch_yoke,
    shaper,
    slider_crank,
    slotted_lever,
    two_guides,
    with_changes,
)
from .oracles import (
    DIGITS,
    exact_fourbar,
    exact_slider_crank,
    reference_motion,
    reference_place,
    reference_positions,
)

__all__ = [
    "DIGITS",
    "exact_fourbar",
    "exact_slider_crank",
    "fourbar",
    "reference_motion",
    "reference_place",
    "reference_positions",
    "scotch_yoke",
    "shaper",
    "slider_crank",
    "slotted_lever",
    "two_guides",
    "with_changes",
]
