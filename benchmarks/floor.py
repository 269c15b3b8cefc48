"""The numpy floor: the case A four-bar and Abduvaliev & Abduxoshimov's slider-crank, hand-fused.

Not planmethod and not general — one function per mechanism, structure of arrays (x and y in
separate arrays), every formula written out once — it shows what plain numpy (no numba) costs
for the same full-turn analysis, positions, velocities and accelerations of every point: the
room left between planmethod's general group-by-group solver and the arithmetic itself.

Examples
--------
>>> import numpy as np
>>> out = fourbar(np.radians([60.0]))
>>> [round(float(out[k][0]), 6) for k in ("cx", "vcx", "acx", "omega_CD", "epsilon_BC")]
[0.23641, -0.412391, -7.464211, 2.448975, 19.087707]
>>> out = slider_crank(np.radians([45.0]))
>>> round(float(out["vcx"][0]), 4), round(float(out["acx"][0]), 3)
(-5.2716, -430.317)
"""

from __future__ import annotations

import numpy as np


def fourbar(phi, crank=0.08, coupler=0.22, rocker=0.18, dx=0.30, dy=0.0, omega=10.0,
            epsilon=0.0, sign=1.0) -> dict:
    """A = (0, 0), D = (dx, dy); C on the left of B→D for ``sign`` = 1."""
    c, s = np.cos(phi), np.sin(phi)
    bx, by = crank * c, crank * s
    vbx, vby = -omega * by, omega * bx
    abx, aby = -epsilon * by - omega * omega * bx, epsilon * bx - omega * omega * by
    ux, uy = dx - bx, dy - by
    d2 = ux * ux + uy * uy
    d = np.sqrt(d2)
    heron = ((coupler + rocker + d) * (coupler + rocker - d) * (coupler - rocker + d)
             * (rocker - coupler + d))
    if np.any(heron <= 0):
        raise ValueError("the four-bar cannot be assembled (or is at its toggle)")
    x = (coupler * coupler - rocker * rocker + d2) / (2 * d)
    h = np.sqrt(heron) / (2 * d)
    cx = bx + (x * ux - sign * h * uy) / d
    cy = by + (x * uy + sign * h * ux) / d
    r2x, r2y, r3x, r3y = cx - bx, cy - by, cx - dx, cy - dy
    det = r2x * r3y - r2y * r3x
    # ω2·J r2 − ω3·J r3 = −v_B
    w2 = -(vbx * r3x + vby * r3y) / det
    w3 = -(vbx * r2x + vby * r2y) / det
    vcx, vcy = -w3 * r3y, w3 * r3x
    # ε2·J r2 − ε3·J r3 = −a_B + ω2²·r2 − ω3²·r3
    qx = -abx + w2 * w2 * r2x - w3 * w3 * r3x
    qy = -aby + w2 * w2 * r2y - w3 * w3 * r3y
    e2 = (qx * r3x + qy * r3y) / det
    e3 = (qx * r2x + qy * r2y) / det
    acx, acy = -e3 * r3y - w3 * w3 * r3x, e3 * r3x - w3 * w3 * r3y
    return {"bx": bx, "by": by, "vbx": vbx, "vby": vby, "abx": abx, "aby": aby,
            "cx": cx, "cy": cy, "vcx": vcx, "vcy": vcy, "acx": acx, "acy": acy,
            "omega_BC": w2, "omega_CD": w3, "epsilon_BC": e2, "epsilon_CD": e3}


def slider_crank(phi, crank=0.06, rod=0.18, omega=100.0, epsilon=0.0, forward=1.0) -> dict:
    """A = (0, 0), C on the x-axis; D the rod's midpoint."""
    c, s = np.cos(phi), np.sin(phi)
    bx, by = crank * c, crank * s
    vbx, vby = -omega * by, omega * bx
    abx, aby = -epsilon * by - omega * omega * bx, epsilon * bx - omega * omega * by
    reach = rod * rod - by * by
    if np.any(reach <= 0):
        raise ValueError("the rod cannot reach the guide (or is at its toggle)")
    rx = forward * np.sqrt(reach)
    ry = -by
    w2 = -vby / rx
    e2 = (w2 * w2 * ry - aby) / rx
    vcx = vbx - w2 * ry
    acx = abx - e2 * ry - w2 * w2 * rx
    # D, the midpoint: half of the rod's terms
    return {"bx": bx, "by": by, "vbx": vbx, "vby": vby, "abx": abx, "aby": aby,
            "cx": bx + rx, "vcx": vcx, "acx": acx,
            "dx": bx + 0.5 * rx, "dy": 0.5 * by,
            "vdx": 0.5 * (vbx + vcx), "vdy": 0.5 * vby,
            "adx": 0.5 * (abx + acx), "ady": 0.5 * aby,
            "omega_BC": w2, "epsilon_BC": e2}


RUNNERS = {"fourbar": fourbar, "slider_crank": slider_crank}
