"""The parameter study of M. A. Jobborova, M. O'. Xakimova and Sh. A. Kulturayeva, "Study of the
load on kinematic pairs of a four-bar linkage mechanism": how the rocker's weight, the crank
speed and the resisting moment change the largest reactions in the pairs of a four-bar.

One parameter at a time is stepped over its range while the other two keep their base values
(the exercise's own): the rocker weight G4 (the rocker's mass m = G4/g, its J scaled with m so
that its radius of gyration stays), the crank speed ω1, and the magnitude of the resisting
moment Mc on the rocker (its sense as in the exercise). For each value the full turn is solved
and the largest reaction magnitude of every pair over the turn recorded.

The paper's two conclusions are then put to the numbers:

1. "The weight of the rocker does not significantly affect the reactions" — confirmed when no
   pair's largest reaction changes by more than :data:`NOT_SIGNIFICANT` (5 %) over G4's range;
2. "The moment of technological resistance Mc has the greatest influence on the reactions" —
   confirmed when Mc changes the largest reactions more than either other parameter does
   (relative change (max − min)/min over its range, the largest over the pairs).

Examples
--------
>>> from planmethod.spec import load_exercise
>>> study = run_study(load_exercise("exercises/fourbar_study.toml"), step=10.0)
>>> [p.name for p in study.parameters], study.pairs
(['weight', 'omega', 'moment'], ('A', 'B', 'C', 'D'))
>>> study.relative_change("weight") < study.relative_change("omega")
True
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from ..errors import SpecError
from ..kinematics import choose_branches, solve
from ..model import Exercise, Load
from ..numbering import course_numbers
from ..vocabulary import QUANTITY_KINDS, numbered
from ..words import Message, message
from .analysis import solve_forces

__all__ = ["NOT_SIGNIFICANT", "Conclusion", "Parameter", "Study", "moment_load", "run_study",
           "study_variant"]

#: a relative change of the largest reactions below this counts as "not significant"
NOT_SIGNIFICANT = 0.05

WEIGHTS = (20.0, 40.0, 60.0, 80.0, 100.0)
OMEGAS = (10.0, 20.0, 30.0, 40.0, 50.0)
MOMENTS = (80.0, 100.0, 120.0, 140.0, 160.0)


@dataclass(frozen=True, slots=True)
class Parameter:
    """A parameter the study steps: its name, its label in words with its symbol as the
    field ``symbol`` (``rocker weight G₃``: the symbol carries the link's number in the
    course's notation), unit, the values and the base case's value."""

    name: str
    label: Message
    unit: Message | str
    values: tuple[float, ...]
    base: float

    @property
    def symbol(self) -> str:
        """The symbol its label names (G₃, ω₁, Mc)."""
        return self.label.field("symbol")


class Conclusion(NamedTuple):
    """One of the paper's conclusions put to the numbers: the paper's statement, whether the
    numbers support it, and the numbers that say so."""

    statement: Message
    confirmed: bool
    evidence: Message


@dataclass(frozen=True)
class Study:
    """The study's results: for each parameter, its values, the largest reaction of every pair
    over the turn at each value (``maxima[name][pair]``), and the largest |M_b|."""

    title: str
    rocker: str
    parameters: tuple[Parameter, ...]
    pairs: tuple[str, ...]
    values: Mapping[str, np.ndarray]
    maxima: Mapping[str, Mapping[str, np.ndarray]]
    balancing: Mapping[str, np.ndarray]

    def relative_change(self, name: str, pair: str | None = None) -> float:
        """(max − min)/min of the largest reaction over the parameter's range (of ``pair``, or
        the largest over the pairs)."""
        pairs = [pair] if pair else self.pairs
        changes = []
        for key in pairs:
            values = np.asarray(self.maxima[name][key])
            changes.append(float((values.max() - values.min()) / values.min()))
        return max(changes)

    def base_values(self) -> list[Message]:
        """The base case, parameter by parameter (``rocker weight G₃ = 60 N``)."""
        return [message("{label} = {value:g} {unit}", label=p.label, value=p.base, unit=p.unit)
                for p in self.parameters]

    def conclusions(self, names: Mapping[str, str] | None = None) -> list[Conclusion]:
        """The paper's two conclusions against the numbers; ``names`` are the pairs'
        reactions as the course writes them (R₀₁ for the pair A)."""
        return [self._weight_conclusion(), self._moment_conclusion(names or {})]

    def _weight_conclusion(self) -> Conclusion:
        """"The weight of the rocker does not significantly affect the reactions"."""
        weight = self.relative_change("weight")
        parameter = self._parameter("weight")
        return Conclusion(
            message("The weight of the rocker does not significantly affect the reactions"),
            weight <= NOT_SIGNIFICANT,
            message("over {symbol} = {first:g}…{last:g} {unit} the largest reactions change by "
                    "up to {change:.1f} % (threshold {threshold:g} %; {symbol} also sets the "
                    "rocker's mass, so its inertia grows with it)", symbol=parameter.symbol,
                    first=parameter.values[0], last=parameter.values[-1],
                    unit=parameter.unit, change=100 * weight,
                    threshold=100 * NOT_SIGNIFICANT))

    def _moment_conclusion(self, names: Mapping[str, str]) -> Conclusion:
        """"The resisting moment Mc has the greatest influence on the reactions"."""
        changes = {p.name: self.relative_change(p.name) for p in self.parameters}
        labels = {p.name: p.label for p in self.parameters}
        ranking = [message("{label} {change:.0f} %", label=labels[name], change=100 * value)
                   for name, value in sorted(changes.items(), key=lambda kv: -kv[1])]
        per_pair = [message("{reaction}: {label}", reaction=names.get(pair, pair), label=labels[
            max(changes, key=lambda n, p=pair: self.relative_change(n, p))])
            for pair in self.pairs]
        symbol = self._parameter("weight").symbol
        if changes["moment"] > changes["weight"]:
            evidence = message("largest change of the maximum reactions over each range: "
                               "{ranking} (most influential per pair — {per_pair}); against "
                               "{symbol} alone Mc changes them more", ranking=ranking,
                               per_pair=per_pair, symbol=symbol)
        else:
            evidence = message("largest change of the maximum reactions over each range: "
                               "{ranking} (most influential per pair — {per_pair}); against "
                               "{symbol} alone Mc does not", ranking=ranking,
                               per_pair=per_pair, symbol=symbol)
        return Conclusion(
            message("The resisting moment Mc has the greatest influence on the reactions"),
            max(changes, key=changes.get) == "moment", evidence)

    def _parameter(self, name: str) -> Parameter:
        return next(p for p in self.parameters if p.name == name)


def moment_load(exercise: Exercise, rocker: str | None) -> tuple[int, Load]:
    """The resisting moment the study varies: (its index among the loads, the load) — the first
    moment on ``rocker`` (on any link where None).

    Raises
    ------
    SpecError
        If the exercise has no such moment.

    Examples
    --------
    >>> from planmethod.spec import load_exercise
    >>> index, load = moment_load(load_exercise("exercises/fourbar_study.toml"), None)
    >>> index, load.link, load.moment
    (0, 'CD', -120.0)
    """
    loads = exercise.mechanism.loads
    for index, load in enumerate(loads):
        if load.moment is not None and (rocker is None or load.link == rocker):
            return index, load
    if rocker is None:
        raise SpecError(message("the study needs a resisting moment on the rocker: a [[load]] "
                                "with `moment` on a link"), file=exercise.source, key="load")
    raise SpecError(message("the study needs a resisting moment on the rocker: a [[load]] with "
                            "`moment` on {link}", link=rocker), file=exercise.source, key="load")


def study_variant(exercise: Exercise, rocker: str, index: int, *, weight: float, omega: float,
             moment: float) -> Exercise:
    """The exercise with the rocker's weight G (its mass and moment of inertia scaled
    together), the crank's ω1 and the resisting moment's magnitude (load ``index``, its sense
    kept) set to the given values.

    >>> from planmethod.spec import load_exercise
    >>> exercise = load_exercise("exercises/fourbar_study.toml")
    >>> changed = study_variant(exercise, "CD", 0, weight=40.0, omega=20.0, moment=100.0)
    >>> changed.mechanism.loads[0].moment, changed.mechanism.drive.omega
    (-100.0, 20.0)
    """
    mechanism = exercise.mechanism
    g = mechanism.gravity
    props = mechanism.masses[rocker]
    mass = weight / g
    masses = dict(mechanism.masses)
    masses[rocker] = replace(props, m=mass, J=props.J * mass / props.m)
    loads = list(mechanism.loads)
    sense = 1.0 if loads[index].moment >= 0 else -1.0
    loads[index] = replace(loads[index], moment=sense * moment)
    drive = replace(mechanism.drive, omega=omega)
    return replace(exercise, mechanism=replace(mechanism, masses=masses, loads=tuple(loads),
                                               drive=drive))


def _parameters(mechanism, rocker: str, base: Mapping[str, float],
                values: tuple[Sequence[float], Sequence[float], Sequence[float]]
                ) -> tuple[Parameter, ...]:
    """The rocker weight G, the crank speed ω and the resisting moment Mc, each with the
    ``values`` it steps over and its ``base`` value; G and ω carry their links' numbers."""
    numbers = course_numbers(mechanism)
    weights, omegas, moments = values
    return (Parameter("weight", message("rocker weight {symbol}",
                                        symbol=numbered("G", numbers[rocker])),
                      message("N", context="unit"), tuple(weights), base["weight"]),
            Parameter("omega", message("crank speed {symbol}",
                                       symbol=numbered("ω", numbers[mechanism.drive.link])),
                      QUANTITY_KINDS["omega"].unit,     # words: vocabulary
                      tuple(omegas), base["omega"]),
            Parameter("moment", message("resisting moment {symbol}", symbol="Mc"),
                      message("N·m", context="unit"), tuple(moments), base["moment"]))


def run_study(exercise: Exercise, *, rocker: str | None = None,
              weights: Sequence[float] = WEIGHTS, omegas: Sequence[float] = OMEGAS,
              moments: Sequence[float] = MOMENTS, step: float = 2.0) -> Study:
    """Run the study of Jobborova et al. on ``exercise`` (see the module docstring).

    Raises
    ------
    SpecError
        Without gravity, without a mass on the rocker, or without a resisting moment on it; for
        a non-positive weight or moment or an empty range.
    """
    mechanism = exercise.mechanism
    index, load = moment_load(exercise, rocker)
    rocker = load.link
    if not mechanism.gravity:
        raise SpecError(message("the study varies the rocker's weight: give [gravity]"),
                        file=exercise.source, key="gravity")
    if rocker not in mechanism.masses:
        raise SpecError(message("the rocker {link} needs a mass ([mass.{link}])", link=rocker),
                        file=exercise.source, key=f"mass.{rocker}")
    for name, values in (("weights", weights), ("omegas", omegas), ("moments", moments)):
        if not values or any(not (np.isfinite(v) and v > 0) for v in values):
            raise SpecError(message("the study's {name} must be positive numbers, got "
                                    "{values}", name=name, values=str(list(values))))
    base = {"weight": mechanism.masses[rocker].m * mechanism.gravity,
            "omega": mechanism.drive.omega, "moment": abs(load.moment)}
    parameters = _parameters(mechanism, rocker, base, (weights, omegas, moments))
    branches = choose_branches(mechanism)
    angles = np.arange(0.0, 360.0, step)
    positions = None
    maxima: dict = {}
    balancing: dict = {}
    pairs: tuple[str, ...] = ()
    for parameter in parameters:
        maxima[parameter.name] = {}
        balancing[parameter.name] = []
        for value in parameter.values:
            settings = dict(base) | {parameter.name: value}
            variant = study_variant(exercise, rocker, index, **settings)
            motion = solve(variant.mechanism, angles, branches=branches)
            if positions is None:
                positions = motion
            solution = solve_forces(motion, file=exercise.source)
            pairs = tuple(solution.reactions)
            for key, reaction in solution.reactions.items():
                maxima[parameter.name].setdefault(key, []).append(
                    float(reaction.magnitude.max()))
            balancing[parameter.name].append(float(np.abs(solution.balancing_moment).max()))
    values = {p.name: np.asarray(p.values) for p in parameters}
    maxima = {name: {key: np.asarray(v) for key, v in table.items()}
              for name, table in maxima.items()}
    return Study(mechanism.title, rocker, parameters, pairs, values, maxima,
                 {name: np.asarray(v) for name, v in balancing.items()})
