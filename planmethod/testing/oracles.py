"""Exact solvers independent of planmethod's own: the oracles of the tests and benchmarks.

Two oracles:

* :func:`reference_motion` recomputes velocities and accelerations of every link with the
  generic constraint Jacobian of the whole mechanism
  (:mod:`planmethod.kinematics.constraints`) — an exact linear solve independent of the
  closed-form dyads and of the plan emulator (positions from the closed-form solve).
* :func:`exact_fourbar` and :func:`exact_slider_crank` evaluate the four-bar and the
  slider-crank by their textbook closed forms in ``DIGITS``-digit arithmetic (mpmath, imported
  when they are called: it is in the ``test`` extra).

Examples
--------
>>> from planmethod.spec import exercise_from_dict
>>> from planmethod.testing.mechanisms import fourbar
>>> mechanism = exercise_from_dict(fourbar()).mechanism
>>> reference = reference_motion(mechanism, [60.0])
>>> round(float(reference["CD"]["omega"][0]), 6)
2.448975
>>> exact = exact_fourbar(60.0)          # the same four-bar, to 40 digits
>>> round(float(exact["omega_CD"]), 6)
2.448975
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..kinematics import solve
from ..kinematics.constraints import ConstraintSystem
from ..kinematics.state import LinkState
from ..model import FRAME, Mechanism

__all__ = [
    "DIGITS",
    "exact_fourbar",
    "exact_slider_crank",
    "reference_motion",
]


def reference_motion(mechanism: Mechanism, angles: Sequence[float]) -> dict[str, dict]:
    """Velocities and accelerations of every moving link by one exact linear solve of the whole
    mechanism's constraint equations (positions from the closed-form solve).

    Returns ``{link: {"omega", "epsilon", "velocity", "acceleration"}}`` (origin velocity and
    acceleration), arrays over ``angles``.
    """
    angles = np.asarray(angles, dtype=float)
    positions = solve(mechanism, angles, stage="position")
    moving = [name for name in mechanism.moving_links if name != mechanism.drive.link]
    system = ConstraintSystem.between(mechanism, moving)
    driven = solve(mechanism, angles, links=())  # no group: the frame and the drive only
    states = {FRAME: driven.links[FRAME], mechanism.drive.link: driven.links[mechanism.drive.link]}
    for name in moving:
        state = positions.links[name]
        states[name] = LinkState(state.theta, state.origin)
    moving = system.moving_states(states)
    return {name: {"omega": moving[name].omega, "velocity": moving[name].velocity,
                   "epsilon": moving[name].epsilon, "acceleration": moving[name].acceleration}
            for name in moving}


# -- 40-digit closed forms ------------------------------------------------------------------------
#: working precision of the closed forms (significant decimal digits)
DIGITS = 40


def _mpmath():
    import mpmath

    return mpmath


def _crank(mp, ax, ay, crank, phi_deg, omega, epsilon):
    phi = mp.radians(mp.mpf(phi_deg))
    c, s = mp.cos(phi), mp.sin(phi)
    b = (ax + crank * c, ay + crank * s)
    v = (-omega * crank * s, omega * crank * c)
    a = (-epsilon * crank * s - omega ** 2 * crank * c,
         epsilon * crank * c - omega ** 2 * crank * s)
    return b, v, a


def exact_fourbar(phi_deg, *, ground=(0.30, 0.0), crank=0.08, coupler=0.22, rocker=0.18,
                  omega=10.0, epsilon=0.0, above=True, digits: int = DIGITS) -> dict:
    """The four-bar A = (0, 0), D = ``ground``, AB = ``crank``, BC = ``coupler``,
    CD = ``rocker`` at crank angle ``phi_deg`` by its closed form in ``digits`` digits; C on
    the left of B→D when ``above`` (for D on +x: C above the line BD).

    The assembly is a geometric invariant fixed once (which side of the line B–D the pin C lies
    on), so a branch that flips along a sweep shows up as a large error, never as a silent
    agreement.

    Returns
    -------
    dict
        mpf values: ``B, C`` (points), ``v_B, v_C, a_B, a_C`` (vectors), ``omega_BC,
        omega_CD, epsilon_BC, epsilon_CD``, ``sine`` (sin of the angle between the two lines
        ⟂ BC and ⟂ CD intersected on the plans = sin of the angle BCD) and ``reach`` (how far
        the discriminant is from the toggle, negative when the links cannot join).

    Raises
    ------
    ValueError
        If the links cannot be assembled at this angle, or are exactly in their toggle.

    Examples
    --------
    >>> exact = exact_fourbar(60.0)        # reference case A at φ = 60°
    >>> [round(float(v), 6) for v in exact["C"]]
    [0.23641, 0.168393]
    >>> round(float(exact["omega_CD"]), 6), round(float(exact["epsilon_BC"]), 6)
    (2.448975, 19.087707)
    """
    mp = _mpmath()
    with mp.workdps(digits):
        dx, dy = (mp.mpf(g) for g in ground)
        l1, l2, l3, w, e = (mp.mpf(v) for v in (crank, coupler, rocker, omega, epsilon))
        zero = mp.mpf(0)
        b, v_b, a_b = _crank(mp, zero, zero, l1, phi_deg, w, e)
        ux, uy = dx - b[0], dy - b[1]
        d2 = ux * ux + uy * uy
        if d2 == 0:
            raise ValueError(f"B and D coincide at {phi_deg}°: no definite position")
        d = mp.sqrt(d2)
        reach = (l2 + l3 + d) * (l2 + l3 - d) * (l2 - l3 + d) * (l3 - l2 + d)
        if reach < 0:
            raise ValueError(f"the four-bar cannot be assembled at {phi_deg}°")
        x = (l2 * l2 - l3 * l3 + d2) / (2 * d)
        h = mp.sqrt(reach) / (2 * d)
        sign = 1 if above else -1
        cx = b[0] + (x * ux - sign * h * uy) / d
        cy = b[1] + (x * uy + sign * h * ux) / d
        # ω2·J(C − B) − ω3·J(C − D) = −v_B, i.e. with r2 = C − B, r3 = C − D:
        r2 = (cx - b[0], cy - b[1])
        r3 = (cx - dx, cy - dy)
        det = r2[0] * r3[1] - r2[1] * r3[0]   # = cross(r2, r3)
        if det == 0:
            raise ValueError(f"the four-bar is in its toggle position at {phi_deg}°")
        # −ω2·r2y + ω3·r3y = −vBx ;  ω2·r2x − ω3·r3x = −vBy
        den = -r2[1] * (-r3[0]) - r3[1] * r2[0]
        w2 = (-v_b[0] * (-r3[0]) - r3[1] * (-v_b[1])) / den
        w3 = (-r2[1] * (-v_b[1]) - (-v_b[0]) * r2[0]) / den
        v_c = (-w3 * r3[1], w3 * r3[0])
        # ε2·J r2 − ε3·J r3 = −a_B + ω2²·r2 − ω3²·r3
        rx = -a_b[0] + w2 ** 2 * r2[0] - w3 ** 2 * r3[0]
        ry = -a_b[1] + w2 ** 2 * r2[1] - w3 ** 2 * r3[1]
        e2 = (rx * (-r3[0]) - r3[1] * ry) / den
        e3 = (-r2[1] * ry - rx * r2[0]) / den
        a_c = (-e3 * r3[1] - w3 ** 2 * r3[0], e3 * r3[0] - w3 ** 2 * r3[1])
        sine = det / (mp.sqrt(r2[0] ** 2 + r2[1] ** 2) * mp.sqrt(r3[0] ** 2 + r3[1] ** 2))
        return {"B": b, "C": (cx, cy), "v_B": v_b, "v_C": v_c, "a_B": a_b, "a_C": a_c,
                "omega_BC": w2, "omega_CD": w3, "epsilon_BC": e2, "epsilon_CD": e3,
                "sine": sine, "reach": reach}


def exact_slider_crank(phi_deg, *, crank=0.06, rod=0.18, offset=0.0, omega=100.0, epsilon=0.0,
                       forward=True, digits: int = DIGITS) -> dict:
    """The slider-crank A = (0, 0), AB = ``crank``, BC = ``rod``, C on the horizontal line
    y = −``offset``, by its closed form in ``digits`` digits; C ahead of B (larger x) when
    ``forward``.

    Returns
    -------
    dict
        mpf values ``B, C, v_B, v_C, a_B, a_C, omega_BC, epsilon_BC``, ``sine`` (sin of the
        angle between the line ⟂ BC and the guide: (C − B)_x / BC) and ``reach`` (BC² − (height
        of B above the guide)², negative when the rod cannot reach the guide).

    Raises
    ------
    ValueError
        If the rod cannot reach the guide at this angle, or is exactly ⟂ to it (toggle).

    Examples
    --------
    >>> slider = exact_slider_crank(45.0)  # the compressor of Abduvaliev & Abduxoshimov
    >>> round(float(slider["v_C"][0]), 4), round(float(slider["a_C"][0]), 3)
    (-5.2716, -430.317)
    """
    mp = _mpmath()
    with mp.workdps(digits):
        l1, l2, off, w, e = (mp.mpf(v) for v in (crank, rod, offset, omega, epsilon))
        zero = mp.mpf(0)
        b, v_b, a_b = _crank(mp, zero, zero, l1, phi_deg, w, e)
        height = b[1] + off                       # B above the guide y = −offset
        reach = l2 * l2 - height * height
        if reach < 0:
            raise ValueError(f"the rod cannot reach the guide at {phi_deg}°")
        run = mp.sqrt(reach) * (1 if forward else -1)
        c = (b[0] + run, -off)
        r = (c[0] - b[0], c[1] - b[1])
        if r[0] == 0:
            raise ValueError(f"the rod is perpendicular to the guide at {phi_deg}° (toggle)")
        # v_C = v_B + ω2·J r, with v_C·ŷ = 0
        w2 = -v_b[1] / r[0]
        v_c = (v_b[0] - w2 * r[1], zero)
        e2 = (w2 ** 2 * r[1] - a_b[1]) / r[0]
        a_c = (a_b[0] - e2 * r[1] - w2 ** 2 * r[0], zero)
        return {"B": b, "C": c, "v_B": v_b, "v_C": v_c, "a_B": a_b, "a_C": a_c,
                "omega_BC": w2, "epsilon_BC": e2, "sine": r[0] / l2, "reach": reach}
