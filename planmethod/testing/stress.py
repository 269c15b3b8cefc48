"""The stress checker: the exact kinematics judged against a 40-digit reference, angle by angle.

Every case is a four-bar or a slider-crank at a set of crank angles. At each angle planmethod
must give either

* positions, velocities and accelerations of C within the **stated bound** of the 40-digit
  :func:`~planmethod.testing.oracles.exact_fourbar` or
  :func:`~planmethod.testing.oracles.exact_slider_crank` (same branch, fixed by the sketch at
  the drive angle), or
* a **named error** that the reference confirms: :class:`~planmethod.errors.AssemblyError` where
  the links do not reach (or reach only within rounding), :class:`~planmethod.errors.ToggleError`
  where the group is at (or within rounding of) its toggle,

and never a NaN, a silently wrong value or a flipped branch.

The stated bound, with ε the double-precision unit roundoff, s = |sin| of the angle between the
two construction lines the group's point is found from (the angle BCD for the four-bar, the
rod against the guide's normal for the slider-crank; ``GroupMotion.line_sine``), L the sum of
the link lengths (and of |AD| or the guide offset), R = L / (the group's shortest link),
V₀ = |ω|·L and A₀ = (ω² + |ε|)·L the crank's scales, and V, A the sizes of the terms C's
velocity and acceleration are sums of at that position (V = |v_B| + Σ|ω_i|·l_i,
A = |a_B| + Σ(ω_i² + |ε_i|)·l_i over the group's links)::

    |ΔC| ≤ K·ε·L/s
    |Δv_C| ≤ K·ε·R·max(V₀/s³, V/s²)
    |Δa_C| ≤ K·ε·R·max(A₀/s⁵, A/s²)          K = 16

Both terms are the condition of the problem itself, not of the method: the crank angle given
in degrees, and B = l·(cos φ, sin φ), are known to ε only — B to ε·L, which is ε·R of the
group's own size. Near a toggle a displacement δ of B moves s by about δ/(l·s) while |v| grows
like V₀/s and |a| like A₀/s³, so δv ≈ ε·R·V₀/s³ and δa ≈ ε·R·A₀/s⁵; away from it the terms
V, A of the sums move by the same relative ε·R, amplified by the 2 × 2 solve (1/s) and by the
error of its directions (1/s). The reference is evaluated at the exact angle in degrees the user
gave. K is empirical: the long run's worst error is 2.7·ε·R·A/s² (a crank 256 to 65,536 times
its rod, near its dead centre, where the rod turns R times faster than the crank), a sixth of
K; the ratio error/bound of every scenario is in the results. (An earlier model without R in
the second terms, with K = 256, failed for a crank 256 times its rod — found by hypothesis —
and by 15× for one 4,096 times its rod.)

Scenarios: crank dead centres approached to 1e-12 rad, group toggles approached to 1e-12 rad,
Grashof-limit (change-point) four-bars and links that only just reach, link-length ratios from
1e-6 to 1e6 and absolute sizes from 1e-6 to 1e6 m, ω up to 1e4 rad/s with ε up to 1e8 rad/s²,
and random mechanisms over full turns (:func:`scenarios`, :func:`random_case`).
``python -m benchmarks.run --only stress`` is the long run (``benchmarks/stress.py``);
``tests/test_stress.py`` runs a fast subset.

Examples
--------
>>> rows = check(fourbar_case(), [0.0, 60.0, 150.0])
>>> [row["status"] for row in rows]
['ok', 'ok', 'ok']
>>> max(row["ratio"] for row in rows) < 1
True
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np

from ..errors import AssemblyError, PlanmethodError, ToggleError
from ..kinematics import solve
from ..spec import exercise_from_dict
from ..vectors import cross, norm
from .oracles import exact_fourbar as fourbar_reference
from .oracles import exact_slider_crank as slider_reference

__all__ = [
    "EPS",
    "NEAR_SINGULAR",
    "Case",
    "CaseKind",
    "K",
    "assemblable",
    "check",
    "exercise_of",
    "fourbar_case",
    "random_case",
    "scenarios",
    "slider_case",
    "summary",
    "term_sizes",
    "toggle_fourbar",
    "toggle_slider",
    "well_posed",
]

#: the constant of the stated bounds
K = 16.0
EPS = float(np.finfo(float).eps)
#: a named error is confirmed when the reference is this close to the singular position:
#: |s| below it for a toggle, the discriminant below it (relative) for "cannot reach"
NEAR_SINGULAR = 1e-6


class CaseKind(StrEnum):
    """The two mechanisms the stress suite knows exactly."""

    FOURBAR = "fourbar"
    SLIDER = "slider"


@dataclass(frozen=True)
class Case:
    """A mechanism of the stress suite: ``kind`` "fourbar" or "slider", its parameters (those of
    :func:`planmethod.testing.exact_fourbar` / ``exact_slider_crank``), the drive angle at which the
    sketch fixes the branch, a name, and the branch."""

    kind: CaseKind
    params: dict = field(default_factory=dict)
    drive_angle: float = 60.0
    name: str = ""
    branch: bool = True  # four-bar: C on the left of B→D; slider-crank: C ahead of B

    @property
    def length(self) -> float:
        p = self.params
        if self.kind is CaseKind.FOURBAR:
            return (p["crank"] + p["coupler"] + p["rocker"] + math.hypot(*p["ground"]))
        return p["crank"] + p["rod"] + abs(p.get("offset", 0.0))

    @property
    def group_length(self) -> float:
        """The shortest link of the driven group (BC, CD; or the rod)."""
        p = self.params
        return min(p["coupler"], p["rocker"]) if self.kind is CaseKind.FOURBAR else p["rod"]

    def reference(self, angle: float, branch: bool) -> dict:
        if self.kind is CaseKind.FOURBAR:
            return fourbar_reference(angle, above=branch, **self.params)
        return slider_reference(angle, forward=branch, **self.params)


def fourbar_case(*, crank=0.08, coupler=0.22, rocker=0.18, ground=(0.30, 0.0), omega=10.0,
                 epsilon=0.0, drive_angle=60.0, above=True, name="case A") -> Case:
    """A four-bar A = (0, 0), D = ``ground``; the branch: C on the left of B→D when ``above``."""
    params = {"crank": crank, "coupler": coupler, "rocker": rocker,
              "ground": tuple(float(g) for g in ground), "omega": omega, "epsilon": epsilon}
    return Case(CaseKind.FOURBAR, params, drive_angle, name, above)


def slider_case(*, crank=0.06, rod=0.18, offset=0.0, omega=100.0, epsilon=0.0,
                drive_angle=45.0, forward=True, name="compressor slider-crank") -> Case:
    """A slider-crank A = (0, 0), C on the line y = −``offset``; C ahead of B when
    ``forward``."""
    params = {"crank": crank, "rod": rod, "offset": offset, "omega": omega,
              "epsilon": epsilon}
    return Case(CaseKind.SLIDER, params, drive_angle, name, forward)


def exercise_of(case: Case):
    """The planmethod exercise of a case; its sketch is the reference's C at the drive angle on
    the case's branch (the sketch picks the branch, as in an exercise file)."""
    exact = case.reference(case.drive_angle, case.branch)
    sketch = [float(exact["C"][0]), float(exact["C"][1])]
    p = case.params
    if case.kind is CaseKind.FOURBAR:
        data = {"title": case.name or "four-bar",
                "drive": {"link": "AB", "pivot": "A", "angle": case.drive_angle,
                          "omega": p["omega"], "epsilon": p["epsilon"]},
                "links": {"frame": {"A": [0, 0], "D": list(p["ground"])},
                          "AB": {"A": [0, 0], "B": [p["crank"], 0]},
                          "BC": {"B": [0, 0], "C": [p["coupler"], 0]},
                          "CD": {"C": [0, 0], "D": [p["rocker"], 0]}},
                "sketch": {"C": sketch}}
    else:
        data = {"title": case.name or "slider-crank",
                "drive": {"link": "AB", "pivot": "A", "angle": case.drive_angle,
                          "omega": p["omega"], "epsilon": p["epsilon"]},
                "links": {"frame": {"A": [0, 0], "G": [0, -p["offset"]]},
                          "AB": {"A": [0, 0], "B": [p["crank"], 0]},
                          "BC": {"B": [0, 0], "C": [p["rod"], 0]},
                          "slider": {"C": [0, 0]}},
                "slide": [{"link": "slider", "along": "frame", "through": "G",
                           "direction": 0}],
                "sketch": {"C": sketch}}
    return exercise_from_dict(data)


def _vector(value) -> np.ndarray:
    return np.array([float(value[0]), float(value[1])])


def _classify(case: Case, angle: float) -> dict:
    """The reference's view of one angle: assemblable or not, and how close to singular."""
    try:
        exact = case.reference(angle, case.branch)
    except ValueError:
        exact = None
    p = case.params
    if case.kind is CaseKind.FOURBAR:
        scale = (p["coupler"] + p["rocker"]) ** 4 + 1e-300
    else:
        scale = p["rod"] ** 2 + 1e-300
    if exact is None:  # the discriminant (negative, or zero at the toggle) for the report
        return {"exact": None, "reach": float(_reach(case, angle) / scale), "sine": 0.0}
    return {"exact": exact, "reach": float(exact["reach"] / scale),
            "sine": abs(float(exact["sine"]))}


def _reach(case: Case, angle: float):
    """The discriminant where the links cannot be assembled (negative)."""
    import mpmath

    p = case.params
    with mpmath.workdps(40):
        phi = mpmath.radians(mpmath.mpf(angle))
        bx, by = p["crank"] * mpmath.cos(phi), p["crank"] * mpmath.sin(phi)
        if case.kind is CaseKind.FOURBAR:
            d = mpmath.sqrt((p["ground"][0] - bx) ** 2 + (p["ground"][1] - by) ** 2)
            b, c = mpmath.mpf(p["coupler"]), mpmath.mpf(p["rocker"])
            return (b + c + d) * (b + c - d) * (b - c + d) * (c - b + d)
        height = by + p["offset"]
        return p["rod"] ** 2 - height ** 2


def term_sizes(case: Case, exact: dict) -> tuple[float, float]:
    """(V, A): the sizes of the terms C's velocity and acceleration are sums of."""
    import mpmath

    p = case.params
    links = ((("omega_BC", "epsilon_BC", p["coupler"]), ("omega_CD", "epsilon_CD", p["rocker"]))
             if case.kind is CaseKind.FOURBAR else (("omega_BC", "epsilon_BC", p["rod"]),))
    speed = float(mpmath.hypot(*exact["v_B"]))
    accel = float(mpmath.hypot(*exact["a_B"]))
    for omega, epsilon, length in links:
        speed += abs(float(exact[omega])) * length
        accel += (float(exact[omega]) ** 2 + abs(float(exact[epsilon]))) * length
    return speed, accel


def check(case: Case, angles, *, mechanism=None) -> list[dict]:
    """Solve the case at each angle and judge each result against the reference.

    Each row: ``angle``, ``status`` (``ok``, ``assembly``, ``toggle``), ``sine`` (the reference's
    condition), the errors of C's position, velocity and acceleration, ``ratio`` (the largest
    error over its stated bound; ≤ 1 passes) and ``violation`` (None, or what went wrong).
    ``mechanism`` is what is solved (default: the case's own, :func:`exercise_of`) — another
    one shows what the checker says of a wrong solve.
    """
    if mechanism is None:
        mechanism = exercise_of(case).mechanism
    angles = [float(a) for a in angles]
    try:
        solved = solve(mechanism, np.array(angles))
    except PlanmethodError:
        solved = None
    return [_judge(case, mechanism, angle, solved, k) for k, angle in enumerate(angles)]


def _judge(case: Case, mechanism, angle: float, solved, index: int) -> dict:
    """One angle's row of :func:`check`: the motion of all angles ``solved`` at once (its
    ``index``), or, where that failed, this angle solved alone."""
    reference = _classify(case, angle)
    row = {"case": case.name, "kind": case.kind, "angle": angle, "sine": reference["sine"],
           "reach": reference["reach"], "violation": None, "ratio": 0.0}
    try:
        motion = solved if solved is not None else solve(mechanism, np.array([angle]))
        index = index if solved is not None else 0
        values = [motion.position("C")[index], motion.velocity("C")[index],
                  motion.acceleration("C")[index]]
        group = next(iter(motion.groups.values()))
        line_sine = float(np.abs(group.line_sine[index]))
    except AssemblyError as error:
        row.update(status="assembly", message=str(error))
        if reference["exact"] is not None and reference["reach"] > NEAR_SINGULAR:
            row["violation"] = "AssemblyError where the reference assembles"
        return row
    except ToggleError as error:
        row.update(status="toggle", message=str(error))
        # the solver refuses where ε·R/s⁵ ≥ 1 (accelerations with no correct digit)
        limit = max(NEAR_SINGULAR, 2.0 * (EPS * case.length / case.group_length) ** 0.2)
        if reference["exact"] is not None and reference["sine"] > limit:
            row["violation"] = "ToggleError away from the toggle"
        return row
    row.update(status="ok", line_sine=line_sine)
    if not all(np.all(np.isfinite(v)) for v in values):
        row["violation"] = "NaN or infinity in a result"
    elif reference["exact"] is None:
        row["violation"] = "a result where the links cannot be assembled"
    else:
        _judge_errors(case, angle, reference, values, row)
    return row


def _judge_errors(case: Case, angle: float, reference: dict, values: list, row: dict) -> None:
    """Add to ``row`` the errors of C's position, velocity and acceleration, their bounds,
    and a violation where an error is above its bound (a flipped branch, if the other
    branch is nearer)."""
    p, length = case.params, case.length
    speed = abs(p["omega"]) * length
    accel = (p["omega"] ** 2 + abs(p["epsilon"])) * length
    exact = reference["exact"]
    s = max(reference["sine"], 1e-300)
    terms_v, terms_a = term_sizes(case, exact)
    ratio = length / case.group_length
    bounds = (K * EPS * length / s,
              K * EPS * ratio * max(speed / s ** 3, terms_v / s ** 2),
              K * EPS * ratio * max(accel / s ** 5, terms_a / s ** 2))
    errors = [float(norm(value - _vector(exact[key])))
              for value, key in zip(values, ("C", "v_C", "a_C"), strict=True)]
    row["errors"] = errors
    row["bounds"] = list(bounds)
    row["relative"] = [errors[0] / length, errors[1] / max(speed, 1e-300),
                       errors[2] / max(accel, 1e-300)]
    row["ratio"] = max(e / b for e, b in zip(errors, bounds, strict=True))
    if row["ratio"] > 1.0:
        row["violation"] = "error above the stated bound"
        other = case.reference(angle, not case.branch)
        if other is not None and float(norm(values[0] - _vector(other["C"]))) < errors[0]:
            row["violation"] = "flipped branch"


# -- scenarios -----------------------------------------------------------------------------------
def _approach(center_deg: float, exponents) -> list[float]:
    """Angles center ± 10^-k rad (in degrees), and the centre itself."""
    out = [center_deg]
    for k in exponents:
        delta = math.degrees(10.0 ** -k)
        out += [center_deg - delta, center_deg + delta]
    return out


def _crank_dead_centre_fourbar() -> float:
    """Case A's crank angle where A, B, C are in line (B between A and C): an ordinary
    position of the RRR group (its own toggle is B, C, D in line)."""
    case = fourbar_case()

    def alignment(phi):   # OB × OC in the reference's digits: zero with A, B, C in line
        exact = case.reference(float(phi), True)
        return float(cross(np.array(exact["B"], dtype=object), np.array(exact["C"], dtype=object)))

    angles = np.arange(0.0, 360.0, 1.0)
    values = [alignment(a) for a in angles]
    for k in range(len(angles) - 1):
        if values[k] == 0 or values[k] * values[k + 1] < 0:
            low, high = angles[k], angles[k + 1]
            for _ in range(80):
                middle = 0.5 * (low + high)
                if alignment(low) * alignment(middle) <= 0:
                    high = middle
                else:
                    low = middle
            return 0.5 * (low + high)
    raise RuntimeError("no dead centre found")


def toggle_fourbar(phi_star: float = 120.0, *, stretched: bool = True) -> Case:
    """A four-bar whose RRR group reaches its toggle at ``phi_star``: the rocker is chosen so
    that BC + CD = |BD| (stretched) or |BC − CD| = |BD| (folded) there."""
    crank, coupler, ground = 0.08, 0.22, (0.30, 0.0)
    phi = math.radians(phi_star)
    d = math.hypot(ground[0] - crank * math.cos(phi), ground[1] - crank * math.sin(phi))
    rocker = d - coupler if stretched else coupler + d
    name = f"toggle four-bar ({'stretched' if stretched else 'folded'} at {phi_star:g}°)"
    for drive in (phi_star - 30.0, phi_star + 30.0):  # the side where it assembles
        case = fourbar_case(crank=crank, coupler=coupler, rocker=rocker, ground=ground,
                            drive_angle=drive, name=name)
        if assemblable(case):
            return case
    raise RuntimeError("no assembled side")


def toggle_slider() -> Case:
    """A slider-crank whose rod only just reaches the guide at φ = 90° (rod ⟂ guide)."""
    return slider_case(crank=0.06, rod=0.10, offset=0.04, drive_angle=0.0,
                       name="slider whose rod just reaches the guide at 90°")


def scenarios(quick: bool = False) -> list[tuple[str, Case, list[float]]]:
    exponents = range(1, 13) if not quick else (2, 6, 9, 12)
    dead = _crank_dead_centre_fourbar()
    out = [
        ("slider-crank dead centres ±1e-k rad", slider_case(),
         _approach(0.0, exponents) + _approach(180.0, exponents)),
        ("four-bar crank–coupler dead centre ±1e-k rad", fourbar_case(),
         _approach(dead, exponents)),
        ("four-bar toggle (stretched) ±1e-k rad", toggle_fourbar(), _approach(120.0, exponents)),
        ("four-bar toggle (folded) ±1e-k rad", toggle_fourbar(200.0, stretched=False),
         _approach(200.0, exponents)),
        ("slider rod just reaching the guide ±1e-k rad", toggle_slider(),
         _approach(90.0, exponents)),
    ]
    turn = list(np.arange(0.0, 360.0, 5.0 if quick else 0.5))
    # Grashof limit: s + l = p + q exactly (a change-point four-bar), and ± 1e-12 relative
    for change in (0.0, 1e-12, -1e-12):
        rocker = 0.20 * (1 + change)
        out.append((f"Grashof limit (s + l − p − q = {change:g}·p)",
                    fourbar_case(crank=0.10, coupler=0.30, rocker=rocker, ground=(0.40, 0.0),
                                 drive_angle=90.0, name=f"change-point {change:g}"), turn))
    for crank, rod in ((0.06e-6, 0.18), (0.06e-3, 0.18), (0.06, 180.0), (0.06, 180e3)):
        out.append((f"slider-crank rod/crank = {rod / crank:.0e} (crank {crank:g} m)",
                    slider_case(crank=crank, rod=rod, name=f"rod/crank {rod / crank:g}"), turn))
    # a crank far longer than its rod assembles only near its dead centres, where the rod turns
    # fast: B's rounding (ε·|AB|) is a large share of the rod (found by hypothesis)
    for power in (8, 12, 16):
        rod, offset = 0.0390625, 0.03125
        crank = rod * 2.0 ** power
        reach = math.degrees(math.asin((rod - offset) / crank))
        near = [180.0 + reach * f for f in np.linspace(-0.999, 0.999, 9 if quick else 41)]
        out.append((f"slider-crank crank/rod = 2^{power}, offset 0.8 rod, near 180°",
                    slider_case(crank=crank, rod=rod, offset=offset, omega=-1.0,
                                drive_angle=180.0, forward=False,
                                name=f"crank/rod 2^{power}"), near))
    for ratio in (1e-6, 1e-3):
        out.append((f"four-bar crank/rest = {ratio:g}",
                    fourbar_case(crank=0.08 * ratio, coupler=0.22, rocker=0.18,
                                 ground=(0.30, 0.0), name=f"tiny crank {ratio:g}"), turn))
    for size in (1e-6, 1e6):
        out.append((f"four-bar of absolute size ×{size:g}",
                    fourbar_case(crank=0.08 * size, coupler=0.22 * size, rocker=0.18 * size,
                                 ground=(0.30 * size, 0.0), name=f"size {size:g}"), turn))
    for omega, epsilon in ((1e4, 0.0), (1e4, 1e8), (-1e4, -1e6), (1e-4, 0.0)):
        out.append((f"four-bar ω = {omega:g}, ε = {epsilon:g}",
                    fourbar_case(omega=omega, epsilon=epsilon, name=f"omega {omega:g}"), turn))
        out.append((f"slider-crank ω = {omega:g}, ε = {epsilon:g}",
                    slider_case(omega=omega, epsilon=epsilon, name=f"omega {omega:g}"), turn))
    return out


def random_case(generator: random.Random) -> Case:
    """A random four-bar or slider-crank: lengths log-uniform over three decades, any ground
    direction, either branch, ω and ε of either sign up to 1e4 and 1e6."""
    def length():
        return 10.0 ** generator.uniform(-1.5, 1.5)

    omega = generator.choice((-1, 1)) * 10.0 ** generator.uniform(-2, 4)
    epsilon = generator.choice((-1, 0, 1)) * 10.0 ** generator.uniform(-2, 6)
    branch = generator.random() < 0.5
    angle = generator.uniform(0.0, 360.0)
    if generator.random() < 0.5:
        direction = generator.uniform(0, 2 * math.pi)
        ground = length()
        return fourbar_case(crank=length(), coupler=length(), rocker=length(),
                            ground=(ground * math.cos(direction), ground * math.sin(direction)),
                            omega=omega, epsilon=epsilon, drive_angle=angle, above=branch,
                            name="random four-bar")
    return slider_case(crank=length(), rod=length(), offset=generator.uniform(-1, 1) * length(),
                       omega=omega, epsilon=epsilon, drive_angle=angle, forward=branch,
                       name="random slider-crank")


def assemblable(case: Case) -> bool:
    """Whether the case's links can be assembled at its drive angle."""
    try:
        case.reference(case.drive_angle, True)
    except ValueError:
        return False
    return True


def well_posed(case: Case) -> bool:
    """Whether the case's sketch can pick a branch: the links assemble at its drive angle, and
    not within rounding of a singular position there (B on D, the links only just reaching,
    or a toggle), where the solver rightly refuses to choose.

    Examples
    --------
    >>> well_posed(fourbar_case()), well_posed(fourbar_case(crank=0.3, drive_angle=1e-170))
    (True, False)
    """
    if not assemblable(case):
        return False
    view = _classify(case, case.drive_angle)
    return view["reach"] > NEAR_SINGULAR and view["sine"] > NEAR_SINGULAR


def summary(rows: list[dict]) -> dict:
    ok = [r for r in rows if r["status"] == "ok"]
    return {"angles": len(rows), "ok": len(ok),
            "assembly_errors": sum(r["status"] == "assembly" for r in rows),
            "toggle_errors": sum(r["status"] == "toggle" for r in rows),
            "violations": sum(r["violation"] is not None for r in rows),
            "worst_ratio": max((r["ratio"] for r in ok), default=0.0),
            "smallest_sine_solved": min((r["sine"] for r in ok), default=None),
            "worst_relative": [max((r["relative"][i] for r in ok), default=0.0)
                               for i in range(3)]}
