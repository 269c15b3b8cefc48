"""Drawing scales μl, μv, μa (and μF) chosen the way the textbook chooses them.

Each scale is set by the drawn length of the drive link's scale point B: μl = l_AB/(AB),
μv = v_B/(pb), μa = a_B/(πb), or given directly. At the crank scale (all three lengths equal)
μv = ω1·μl and μa = ω1²·μl. The analogue scales are μφv = μv/ω1 and μφa = μa/ω1², as in
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

import math
from dataclasses import dataclass

from ..errors import SpecError
from ..model import Exercise, Mechanism, PlanSettings
from ..vocabulary import SCALES

__all__ = ["Scales", "choose_scales", "scale_point"]


@dataclass(frozen=True, slots=True)
class Scales:
    """Plan scales: μl (m/mm), μv ((m/s)/mm), μa ((m/s²)/mm), μF (N/mm, if set)."""

    mu_l: float
    mu_v: float
    mu_a: float
    omega1: float
    epsilon1: float
    scale_point: str
    mu_f: float | None = None

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

    def describe(self) -> list[str]:
        """The scales as printed on a drawing, with units."""
        lines = [_scale_text(name, getattr(self, name)) for name in ("mu_l", "mu_v", "mu_a")]
        if self.omega1:
            lines += [f"μφv = μv/ω1 = {self.mu_phi_v:.6g} m/mm",
                      f"μφa = μa/ω1² = {self.mu_phi_a:.6g} m/mm"]
        if self.mu_f is not None:
            lines.append(_scale_text("mu_f", self.mu_f))
        return lines


def _scale_text(name: str, value: float) -> str:
    """``μv = 0.2 (m/s)/mm``: a scale as printed, with its unit."""
    symbol, unit = SCALES[name]
    return f"{symbol} = {value:.6g} {unit}"


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
        raise SpecError(f"the scale point {point} coincides with the pivot {drive.pivot}",
                        file=exercise.source, key="plan.scale_point")
    v_b = abs(drive.omega) * length
    a_b = length * math.hypot(drive.omega ** 2, drive.epsilon)

    def pick(direct, drawn, value, key, what):
        if direct is not None:
            return direct
        if drawn is None:
            raise SpecError(f"give {key} or the matching *_mm length", file=exercise.source,
                            key=f"plan.{key}")
        if value == 0:
            raise SpecError(f"{what} of {point} is zero, so a drawn length cannot set the "
                            f"scale; give plan.{key} instead", file=exercise.source,
                            key=f"plan.{key}")
        return value / drawn

    mu_l = pick(settings.mu_l, settings.crank_mm, length, "mu_l", "the length")
    mu_v = pick(settings.mu_v, settings.velocity_mm, v_b, "mu_v", "the velocity")
    mu_a = pick(settings.mu_a, settings.acceleration_mm, a_b, "mu_a", "the acceleration")
    return Scales(mu_l, mu_v, mu_a, drive.omega, drive.epsilon, point, settings.mu_f)
