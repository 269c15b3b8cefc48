"""Drawing scales μl, μv, μa (and μF) chosen the way the textbook chooses them.

Each scale is set by the drawn length of the drive link's scale point B, or given directly. A
scale set by a length is the value of the standard series (mantissa 1, 1.5, 2, 2.5, 4, 5,
7.5 × 10ᵏ, :func:`standard`: the round scales the shipped exercises and course guides use, of
the round series 1, 1.5, 2, 2.5, 3, 4, 5, 6, 7.5, 8 × 10ᵏ) nearest to what the length asks —
μl ≈ l_AB/(AB), μv ≈ v_B/(pb), μa ≈ a_B/(πb) — and the drawn length then follows from the
scale, as course guides ask. At the crank scale (all three lengths equal: the textbook's
(pb) = (πb) = (AB), and the default without a ``[plan]`` table) μl is standard and μv, μa are
the standard values nearest ω1·μl and ω1²·μl (exactly those where they are round already);
with ε1 ≠ 0 the crank pin's acceleration is longer than ω1²·l_AB, and μa is the standard value
nearest a_B/(πb) (the crank's acceleration then drawn at its true length at that scale). A
scale a student reads off a sheet is never 0.0135 (m/s)/mm. ``exact_mm = true`` in ``[plan]`` keeps
the lengths exactly as written (the scales then follow from them unrounded); a ``mu_*`` given is
used as it is. The analogue scales are μφv = μv/ω1 and μφa = μa/ω1², as in
U. A. Abduvaliev and J. U. Abduxoshimov, "Kinematic study of a four-link mechanism for the
purpose of its use in the design of new machines".

Examples
--------
>>> from planmethod.spec import load_exercise
>>> scales = choose_scales(load_exercise("exercises/compressor_slider_crank.toml"))
>>> (round(scales.mu_l, 6), round(scales.mu_v, 6), round(scales.mu_a, 6))
(0.002, 0.2, 20.0)
>>> round(scales.mu_phi_v, 6), round(scales.mu_phi_a, 6)
(0.002, 0.002)
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from ..errors import SpecError
from ..model import Exercise, Mechanism, PlanSettings
from ..numbering import course_numbers
from ..words import message

__all__ = ["ROUND_MANTISSAS", "STANDARD_MANTISSAS", "Scales", "choose_scales", "is_round",
           "scale_point", "standard"]

#: the mantissas of the standard series of drawing scales (× 10ᵏ): the round values the
#: shipped exercises and the course guides use
STANDARD_MANTISSAS = (1.0, 1.5, 2.0, 2.5, 4.0, 5.0, 7.5)
#: the mantissas of every round scale (× 10ᵏ): a scale given directly may be any of them
ROUND_MANTISSAS = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 7.5, 8.0)


@functools.lru_cache(maxsize=256)     # a figure asks for the same scales many times
def standard(value: float) -> float:
    """The value of the standard series of drawing scales (1, 1.5, 2, 2.5, 4, 5, 7.5 × 10ᵏ)
    nearest to ``value`` (by ratio; a tie goes to the smaller, which draws larger).

    Examples
    --------
    >>> standard(0.00942478), standard(0.0592176), standard(0.00333333), standard(0.002)
    (0.01, 0.05, 0.004, 0.002)
    >>> standard(0.0135), standard(0.024), standard(0.0375)
    (0.015, 0.025, 0.04)
    """
    if not (math.isfinite(value) and value > 0):
        return value
    exponent = math.floor(math.log10(value))
    best, distance = value, math.inf
    for power in (exponent - 1, exponent, exponent + 1):
        for mantissa in STANDARD_MANTISSAS:
            candidate = float(f"{mantissa}e{power}")     # exact decimal, no 10**k rounding
            gap = abs(math.log(candidate / value))
            if gap < distance - 1e-12:
                best, distance = candidate, gap
    return best


def is_round(value: float) -> bool:
    """Whether ``value`` is a round scale: 1, 1.5, 2, 2.5, 3, 4, 5, 6, 7.5 or 8 × 10ᵏ.

    >>> is_round(0.015), is_round(0.0135), is_round(6e-5), is_round(0.0)
    (True, False, True, False)
    """
    if not (math.isfinite(value) and value > 0):
        return False
    exponent = math.floor(math.log10(value))
    return any(abs(value - float(f"{mantissa}e{power}")) <= 1e-12 * value
               for power in (exponent - 1, exponent, exponent + 1)
               for mantissa in ROUND_MANTISSAS)


@dataclass(frozen=True, slots=True)
class Scales:
    """Plan scales: μl (m/mm), μv ((m/s)/mm), μa ((m/s²)/mm), μF (N/mm, if set); ``crank``
    is the crank's number in the course's notation (the ω of μφv = μv/ω₁ carries it)."""

    mu_l: float
    mu_v: float
    mu_a: float
    omega1: float
    scale_point: str
    mu_f: float | None = None
    crank: int = 1

    @property
    def mu_phi_v(self) -> float:
        """Scale of the velocity-analogue plan, μv/|ω1| (m/mm)."""
        return self.mu_v / abs(self.omega1) if self.omega1 else math.nan

    @property
    def mu_phi_a(self) -> float:
        """Scale of the acceleration-analogue plan, μa/ω1² (m/mm)."""
        return self.mu_a / self.omega1 ** 2 if self.omega1 else math.nan

    def as_dict(self) -> dict[str, float]:
        out = {"mu_l": self.mu_l, "mu_v": self.mu_v, "mu_a": self.mu_a}
        if self.omega1:
            out |= {"mu_phi_v": self.mu_phi_v, "mu_phi_a": self.mu_phi_a}
        if self.mu_f is not None:
            out["mu_f"] = self.mu_f
        return out


def scale_point(mechanism: Mechanism, settings: PlanSettings) -> str:
    """The drive-link point the *_mm lengths refer to (default: its first point after the
    pivot)."""
    if settings.scale_point:
        return settings.scale_point
    drive = mechanism.drive
    return next(p for p in mechanism.links[drive.link].points if p != drive.pivot)


def choose_scales(exercise: Exercise, settings: PlanSettings | None = None) -> Scales:
    """The plan scales of an exercise (``settings`` overrides its ``[plan]`` table).

    Raises
    ------
    SpecError
        If a scale cannot be set (zero crank length, or a velocity or acceleration plan
        scaled by a zero v_B or a_B).
    """
    mechanism = exercise.mechanism
    settings = settings or exercise.plan
    drive = mechanism.drive
    point = scale_point(mechanism, settings)
    length = mechanism.links[drive.link].length(drive.pivot, point)
    if length <= 0:
        raise SpecError(message("the scale point {point} coincides with the pivot {pivot}",
                                point=point, pivot=drive.pivot),
                        file=exercise.source, key="plan.scale_point")
    v_b = abs(drive.omega) * length
    a_b = length * math.hypot(drive.omega ** 2, drive.epsilon)

    def pick(direct, drawn, value, key):
        if direct is not None:
            return direct
        if drawn is None:
            raise SpecError(message("give {key} or the matching *_mm length", key=key),
                            file=exercise.source, key=f"plan.{key}")
        if value == 0:
            raise SpecError({
                "mu_l": message("the length of {point} is zero, so a drawn length cannot set "
                                "the scale; give plan.mu_l instead", point=point),
                "mu_v": message("the velocity of {point} is zero, so a drawn length cannot "
                                "set the scale; give plan.mu_v instead", point=point),
                "mu_a": message("the acceleration of {point} is zero, so a drawn length "
                                "cannot set the scale; give plan.mu_a instead", point=point),
            }[key], file=exercise.source, key=f"plan.{key}")
        return value / drawn

    exact = settings.exact_mm

    def rounded(direct, value):
        return value if direct is not None or exact else standard(value)

    mu_l = rounded(settings.mu_l, pick(settings.mu_l, settings.crank_mm, length, "mu_l"))
    crank_scale = (not exact and settings.mu_l is None and settings.mu_v is None
                   and settings.mu_a is None and settings.crank_mm is not None
                   and settings.crank_mm == settings.velocity_mm == settings.acceleration_mm)
    mu_v = pick(settings.mu_v, settings.velocity_mm, v_b, "mu_v")
    mu_a = pick(settings.mu_a, settings.acceleration_mm, a_b, "mu_a")
    if crank_scale:   # (pb) = (πb) = (AB): μv and μa follow from the standard μl, rounded
        mu_v = standard(abs(drive.omega) * mu_l)
        # with ε1 ≠ 0 the crank pin's acceleration is longer than ω1²·l: the standard value
        # nearest a_B/(πb) instead
        mu_a = standard(drive.omega ** 2 * mu_l if drive.epsilon == 0 else mu_a)
    else:
        mu_v, mu_a = rounded(settings.mu_v, mu_v), rounded(settings.mu_a, mu_a)
    crank = course_numbers(mechanism)[drive.link]
    return Scales(mu_l, mu_v, mu_a, drive.omega, point, settings.mu_f, crank)
