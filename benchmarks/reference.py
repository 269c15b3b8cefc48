"""High-precision reference kinematics (mpmath) of the four-bar and the slider-crank.

Independent of planmethod: positions by the textbook closed forms evaluated at ``DIGITS``
significant digits, velocities and accelerations by the exact 2 × 2 linear solves of the
differentiated loop equations, in the same working precision. The assembly branch is a
geometric invariant fixed once (which side of the line B–D the pin C lies on; which side of B
the slider is), so a branch that flips along a sweep shows up as a large error, never as a
silent agreement.

Used by ``tests/test_stress.py`` (the stress suite) and by the benchmarks.

Examples
--------
>>> exact = fourbar(60.0)        # REFERENCE_CASES case A at φ = 60°
>>> [round(float(v), 6) for v in exact["C"]]
[0.23641, 0.168393]
>>> round(float(exact["omega_CD"]), 6), round(float(exact["epsilon_BC"]), 6)
(2.448975, 19.087707)
>>> slider = slider_crank(45.0)  # seed 001
>>> round(float(slider["v_C"][0]), 4), round(float(slider["a_C"][0]), 3)
(-5.2716, -430.317)
"""

from __future__ import annotations

import mpmath

__all__ = ["DIGITS", "fourbar", "slider_crank"]

#: working precision (significant decimal digits)
DIGITS = 40


def _crank(ax, ay, crank, phi_deg, omega, epsilon):
    phi = mpmath.radians(mpmath.mpf(phi_deg))
    c, s = mpmath.cos(phi), mpmath.sin(phi)
    b = (ax + crank * c, ay + crank * s)
    v = (-omega * crank * s, omega * crank * c)
    a = (-epsilon * crank * s - omega ** 2 * crank * c,
         epsilon * crank * c - omega ** 2 * crank * s)
    return b, v, a


def _mp(*values):
    return [mpmath.mpf(value) for value in values]


def fourbar(phi_deg, *, ground=(0.30, 0.0), crank=0.08, coupler=0.22, rocker=0.18,
            omega=10.0, epsilon=0.0, above=True, digits: int = DIGITS) -> dict:
    """The four-bar A = (0, 0), D = ``ground``, AB = ``crank``, BC = ``coupler``,
    CD = ``rocker`` at crank angle ``phi_deg``; C on the left of B→D when ``above`` (for D on
    +x: C above the line BD).

    Returns mpf values: ``B, C`` (points), ``v_B, v_C, a_B, a_C`` (vectors), ``omega_BC,
    omega_CD, epsilon_BC, epsilon_CD``, ``sine`` (sin of the angle between the two lines
    ⟂ BC and ⟂ CD intersected on the plans = sin of the angle BCD) and ``reach`` (how far the
    discriminant is from the toggle, negative when the links cannot join).

    Raises
    ------
    ValueError
        If the links cannot be assembled at this angle, or are exactly in their toggle.
    """
    with mpmath.workdps(digits):
        dx, dy = _mp(*ground)
        l1, l2, l3, w, e = _mp(crank, coupler, rocker, omega, epsilon)
        zero = mpmath.mpf(0)
        b, v_b, a_b = _crank(zero, zero, l1, phi_deg, w, e)
        ux, uy = dx - b[0], dy - b[1]
        d2 = ux * ux + uy * uy
        if d2 == 0:
            raise ValueError(f"B and D coincide at {phi_deg}°: no definite position")
        d = mpmath.sqrt(d2)
        reach = (l2 + l3 + d) * (l2 + l3 - d) * (l2 - l3 + d) * (l3 - l2 + d)
        if reach < 0:
            raise ValueError(f"the four-bar cannot be assembled at {phi_deg}°")
        x = (l2 * l2 - l3 * l3 + d2) / (2 * d)
        h = mpmath.sqrt(reach) / (2 * d)
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
        w2 = (-v_b[0] * (-r3[0]) - r3[1] * (-v_b[1])) / (-r2[1] * (-r3[0]) - r3[1] * r2[0])
        w3 = (-r2[1] * (-v_b[1]) - (-v_b[0]) * r2[0]) / (-r2[1] * (-r3[0]) - r3[1] * r2[0])
        v_c = (-w3 * r3[1], w3 * r3[0])
        # ε2·J r2 − ε3·J r3 = −a_B + ω2²·r2 − ω3²·r3
        rx = -a_b[0] + w2 ** 2 * r2[0] - w3 ** 2 * r3[0]
        ry = -a_b[1] + w2 ** 2 * r2[1] - w3 ** 2 * r3[1]
        den = -r2[1] * (-r3[0]) - r3[1] * r2[0]
        e2 = (rx * (-r3[0]) - r3[1] * ry) / den
        e3 = (-r2[1] * ry - rx * r2[0]) / den
        a_c = (-e3 * r3[1] - w3 ** 2 * r3[0], e3 * r3[0] - w3 ** 2 * r3[1])
        sine = det / (mpmath.sqrt(r2[0] ** 2 + r2[1] ** 2) * mpmath.sqrt(r3[0] ** 2 + r3[1] ** 2))
        return {"B": b, "C": (cx, cy), "v_B": v_b, "v_C": v_c, "a_B": a_b, "a_C": a_c,
                "omega_BC": w2, "omega_CD": w3, "epsilon_BC": e2, "epsilon_CD": e3,
                "sine": sine, "reach": reach}


def slider_crank(phi_deg, *, crank=0.06, rod=0.18, offset=0.0, omega=100.0, epsilon=0.0,
                 forward=True, digits: int = DIGITS) -> dict:
    """The slider-crank A = (0, 0), AB = ``crank``, BC = ``rod``, C on the horizontal line
    y = −``offset``; C ahead of B (larger x) when ``forward``.

    Returns mpf values ``B, C, v_B, v_C, a_B, a_C, omega_BC, epsilon_BC``, ``sine`` (sin of the
    angle between the line ⟂ BC and the guide: (C − B)_x / BC) and ``reach`` (BC² − (height of
    B above the guide)², negative when the rod cannot reach the guide).

    Raises
    ------
    ValueError
        If the rod cannot reach the guide at this angle, or is exactly ⟂ to it (toggle).
    """
    with mpmath.workdps(digits):
        l1, l2, off, w, e = _mp(crank, rod, offset, omega, epsilon)
        zero = mpmath.mpf(0)
        b, v_b, a_b = _crank(zero, zero, l1, phi_deg, w, e)
        height = b[1] + off                       # B above the guide y = −offset
        reach = l2 * l2 - height * height
        if reach < 0:
            raise ValueError(f"the rod cannot reach the guide at {phi_deg}°")
        run = mpmath.sqrt(reach) * (1 if forward else -1)
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
