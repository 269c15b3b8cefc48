"""The text of ``planmethod solve``'s report that the analysis writes: the check table, the
book's values against the exact ones, the flags, and the kinetostatics — every sentence and
column heading a message (:mod:`planmethod.words`) rendered in the language spoken, every
number in its writing (a decimal comma where the language writes one), every quantity, link
and force in the course's notation (docs/notation.md: ω₂, v_B₃, R₀₁), never a report name.

A table is laid out here, after its words are rendered: a column whose heading's translation
is longer than the English heading is widened by as much, its cells with it.

Examples
--------
>>> from planmethod.report import analyse
>>> from planmethod.spec import load_exercise
>>> analysis = analyse(load_exercise("exercises/fourbar_forces.toml"))
>>> print(check_lines(analysis)[1])
  quantity         plan         exact  abs. error   rel. error  unit
>>> print("\\n".join(force_lines(analysis.forces)[:2]))
Kinetostatics (d'Alembert) at φ₁ = 60°
  link     m kg    J kg·m²   |a_S| m/s²   Fᵘ = −m·a_S (N)          Mᵘ = −J·ε N·m
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..forces import ForceAnalysis, ForceSolution
from ..forces.checks import VelocitySource
from ..forces.names import BALANCING_MOMENT, INERTIA_FORCE, INERTIA_MOMENT
from ..numbering import course_numbers
from ..report import Analysis, published_comparison
from ..vectors import norm
from ..vocabulary import numbered, point_text, slide_points, subscript, symbol, unit_words
from ..words import Message, message, number_text, plural, render
from .notation import ForceNotation

__all__ = ["check_lines", "flag_lines", "force_lines", "published_lines"]

#: a table's column: its heading, and how the heading and the cells are aligned in it
#: ("<" left, ">" right) and how wide at least (the English heading's width)
Column = tuple[Message, str, int]


def _heading(columns: Sequence[Column], lead: str = "  ") -> tuple[str, list[int]]:
    """A table's heading line, each column's heading in its width as aligned; and by how
    much each column is widened: by what its heading's translation is longer than its
    width (none in English)."""
    texts = [render(text) for text, _, _ in columns]
    extra = [max(0, len(text) - width) for text, (_, _, width) in zip(texts, columns,
                                                                       strict=True)]
    return lead + "".join(f"{text:{align}{width + more}}" for text, (_, align, width), more
                          in zip(texts, columns, extra, strict=True)), extra


def _cell(value: float | None, width: int, specification: str) -> str:
    """A table's number as the language writes it, right-aligned in ``width`` ("—" where
    there is none)."""
    return f"{'—':>{width}}" if value is None else number_text(value, f">{width}{specification}")


def check_lines(analysis: Analysis) -> list[str]:
    """The check table: each asked quantity read off the plan against the exact value, with
    the errors and the unit (its first line empty)."""
    mechanism = analysis.exercise.mechanism
    numbers, points = course_numbers(mechanism), slide_points(mechanism)
    shown = {check.quantity: symbol(check.quantity, numbers, points)
             for check in analysis.checks}
    quantity = message("quantity", context="column")
    width = max([len(text) for text in shown.values()] + [8, len(render(quantity))])
    heading, extra = _heading((
        (quantity, "<", width), (message("plan", context="column"), ">", 13),
        (message("exact", context="column"), ">", 14),
        (message("abs. error", context="column"), ">", 12),
        (message("rel. error", context="column"), ">", 13),
        (message("unit", context="column"), ">", 6)))
    lines = ["", heading]
    for check in analysis.checks:
        lines.append(f"  {shown[check.quantity]:<{width}} "
                     f"{_cell(check.plan, 12 + extra[1], '.6g')}  "
                     f"{_cell(check.analytic, 12 + extra[2], '.6g')}  "
                     f"{_cell(check.abs_error, 10 + extra[3], '.3g')}   "
                     f"{_cell(check.rel_error, 10 + extra[4], '.2e')}  "
                     f"{render(unit_words(check.unit))}")
    return lines


def published_lines(analysis: Analysis) -> list[str]:
    """The book's printed values against the exact ones, each more than 5 % off marked as
    likely a slip (its first line empty; none without ``[published]``)."""
    exercise = analysis.exercise
    if not exercise.published:
        return []
    numbers = course_numbers(exercise.mechanism)
    points = slide_points(exercise.mechanism)
    source = exercise.published_source or message("the book")
    heading, extra = _heading((
        (message("quantity", context="column"), "<", 22),
        (message("published", context="column"), ">", 12),
        (message("exact", context="column"), ">", 14),
        (message("difference", context="column"), ">", 12)))
    lines = ["", render(message("Published values ({source}) against the exact ones "
                                "(magnitudes)", source=source)), heading]
    for row in published_comparison(analysis):
        off = ("—" if row.difference_percent is None
               else number_text(row.difference_percent, "+.1f") + " %")
        slip = ("   " + render(message("likely a slip (> 5 %)")) if row.likely_slip else "")
        exact = "—" if row.exact is None else number_text(row.exact, ".6g")
        lines.append(f"  {symbol(row.quantity, numbers, points):<{22 + extra[0]}}"
                     f"{number_text(row.published, f'>{12 + extra[1]}.6g')}"
                     f"{exact:>{14 + extra[2]}}{off:>{12 + extra[3]}}{slip}")
    return lines


def flag_lines(flags: Sequence[Message | str], notation: ForceNotation | None = None
               ) -> list[str]:
    """Flags as a report lists them, each after a "!" (in the course's notation of forces
    with ``notation``)."""
    return [f"  ! {render(notation.sentence(flag) if notation else flag)}" for flag in flags]


def force_lines(forces: ForceAnalysis) -> list[str]:
    """The kinetostatics at one crank angle (``planmethod solve`` with forces): the inertia
    of each link, each group's steps, the reactions, the balancing moment and its three
    checks, Aliyev's combined force and constants, the sense of ε by the plan's rule, the
    flags — in the course's notation (R₀₁, Fᵘ₂, link 2 (BC))."""
    solution = forces.solution
    notation = ForceNotation(solution)
    crank = notation.numbers.get(solution.mechanism.drive.link, 1)
    lines = [render(message("Kinetostatics (d'Alembert) at {phi} = {angle:g}°",
                            phi=numbered("φ", crank), angle=forces.angle))]
    lines += _inertia_lines(solution, notation)
    for group in solution.groups.groups:
        lines.append("  " + render(message("{group}:", group=notation.group_name(group))))
        lines += ["    " + render(notation.sentence(step, group.links)) for step in group.steps]
    lines += _reaction_lines(forces, notation)
    lines += _moment_lines(forces, numbered("ω", crank))
    lines += _combined_lines(forces, notation)
    lines += ["  " + render(message("{symbol} by the plan's rule: {rule} (exact: {exact})",
                                    symbol=numbered("ε", notation.number(sense.link)),
                                    rule=_SENSES[sense.rule], exact=_SENSES[sense.exact]))
              for sense in forces.epsilon]
    return lines + flag_lines(forces.flags, notation)


#: the sense of ε as the plan's rule and the exact sign give it
_SENSES = {1: message("counter-clockwise"), -1: message("clockwise"), 0: message("zero"),
           None: message("undefined")}


def _inertia_lines(solution: ForceSolution, notation: ForceNotation) -> list[str]:
    """The inertia of each link with mass: m, J, |a_S|, Fᵘ = −m·a_S, Mᵘ = −J·ε."""
    if not solution.applied.inertia:
        return []

    def link(name: str) -> str:      # "2 (BC)" in a column headed "link"
        return f"{notation.number(name)} ({name.replace('_', ' ')})"

    heading = message("link")
    width = max([len(link(name)) for name in solution.applied.inertia]
                + [len(render(heading))])
    line, extra = _heading(((heading, "<", width), (message("m kg"), ">", 7),
                            (message("J kg·m²"), ">", 11), (message("|a_S| m/s²"), ">", 13),
                            (message("{symbol} = −m·a_S (N)", symbol=INERTIA_FORCE), ">", 18),
                            (message("{symbol} = −J·ε N·m", symbol=INERTIA_MOMENT), ">", 23)))
    lines = [line]
    for name, item in solution.applied.inertia.items():
        force = item.force[0]         # a vector, with the separator its language writes
        vector = render(message("({x:>10.5g}, {y:>10.5g})", x=force[0], y=force[1]))
        lines.append(f"  {link(name):<{width}} {number_text(item.mass, f'>{6 + extra[1]}.4g')} "
                     f"{number_text(item.J, f'>{10 + extra[2]}.4g')} "
                     f"{number_text(float(norm(item.acceleration[0])), f'>{11 + extra[3]}.5g')}"
                     f"   {' ' * extra[4]}{vector}   "
                     f"{number_text(float(item.moment[0]), f'>{10 + extra[5]}.5g')}")
    return lines


def _reaction_lines(forces: ForceAnalysis, notation: ForceNotation) -> list[str]:
    """The reaction in each pair: its components, magnitude and (a prismatic pair's)
    couple."""
    line, extra = _heading(((message("reaction"), "<", 10), (message("pair"), "<", 4),
                            (message("Fx N"), ">", 16), (message("Fy N"), ">", 13),
                            (message("|R| N"), ">", 13), (message("couple N·m"), ">", 15)))
    lines = [line]
    force_floor, couple_floor = _noise_floors(forces)
    for key, reaction in forces.reactions.items():
        couple = "" if reaction.moment is None else number_text(
            _beyond(float(reaction.moment), couple_floor), f">{12 + extra[5]}.6g")
        fx, fy = (_beyond(float(value), force_floor) for value in np.ravel(reaction.force)[:2])
        lines.append(f"  {notation.plain(f'R_{key}', reaction.target):<{9 + extra[0]}} "
                     f"{notation.pair_name(key):<{10 + extra[1]}} "
                     f"{number_text(fx, f'>{11 + extra[2]}.6g')} "
                     f"{number_text(fy, f'>{11 + extra[3]}.6g')} "
                     f"{number_text(float(reaction.magnitude), f'>{11 + extra[4]}.6g')} "
                     f"{couple}".rstrip())
    return lines


#: a reaction's component or couple smaller than this share of the table's largest reaction
#: (times the extent of its pairs, for a couple) is the round-off of an exact zero
NOISE_SHARE = 1e-12


def _noise_floors(forces: ForceAnalysis) -> tuple[float, float]:
    """The sizes (N, N·m) below which a reaction's component or couple is shown as 0: the
    round-off of the sums that make it (a block whose couple is zero in exact arithmetic
    prints −5.55e-17 N·m otherwise)."""
    reactions = list(forces.reactions.values())
    largest = max((float(reaction.magnitude) for reaction in reactions), default=0.0)
    points = [np.ravel(reaction.point)[:2] for reaction in reactions]
    extent = (float(np.max(np.ptp(np.array(points), axis=0))) if points else 0.0) or 1.0
    return NOISE_SHARE * largest, NOISE_SHARE * largest * extent


def _beyond(value: float, floor: float) -> float:
    """``value``, or 0 where it is within ``floor`` of zero.

    >>> _beyond(-5.55e-17, 1e-10), _beyond(0.25, 1e-10)
    (0.0, 0.25)
    """
    return 0.0 if abs(value) <= floor else value


def _moment_lines(forces: ForceAnalysis, omega: str) -> list[str]:
    """The balancing moment by the group method, and its checks: the whole-system solve,
    Zhukovsky's lever, the power balance (and the friction iteration)."""
    solution = forces.solution
    system = solution.system
    moment = BALANCING_MOMENT
    said = [message("balancing moment {symbol} = {moment:.6g} N·m (group method)",
                    symbol=moment, moment=forces.balancing_moment),
            plural("whole-system solve ({count} equation): {symbol} = {moment:.6g} N·m; "
                   "largest difference {difference:.2g} (relative)",
                   "whole-system solve ({count} equations): {symbol} = {moment:.6g} N·m; "
                   "largest difference {difference:.2g} (relative)",
                   count=system.equations, symbol=moment,
                   moment=float(system.balancing_moment[0]),
                   difference=float(solution.agreement[0])),
            _lever_line(forces, omega), _power_line(forces, omega)]
    if solution.friction is not None:
        iterations = int(solution.friction.iterations[0])
        said.append(plural("friction: converged after {count} iteration(s)",
                           "friction: converged after {count} iteration(s)", count=iterations))
    return ["  " + render(line) for line in said]


#: whose velocities Zhukovsky's lever was built from, in words
_SOURCES = {VelocitySource.PLAN: message("velocity plan"),
            VelocitySource.EXACT: message("exact velocities")}


def _lever_line(forces: ForceAnalysis, omega: str) -> Message:
    """The balancing moment by Zhukovsky's lever, against the group method's."""
    source = _SOURCES[forces.solution.lever.source]
    lever = forces.zhukovsky_moment
    if lever is None:
        return message("Zhukovsky's lever ({source}): undefined ({omega} = 0)", source=source,
                       omega=omega)
    return message("Zhukovsky's lever ({source}): {symbol} = {moment:.6g} N·m, "
                   "{difference:+.3g} from the group method", source=source,
                   symbol=BALANCING_MOMENT, moment=lever,
                   difference=lever - forces.balancing_moment)


def _power_line(forces: ForceAnalysis, omega: str) -> Message:
    """The power balance: the balancing moment it gives, and its residual."""
    by_power = float(forces.solution.power_moment[0])
    if not np.isfinite(by_power):
        return message("power balance: |ΣP|/Σ|P| = {residual:.2g}",
                       residual=forces.power_residual)
    return message("power balance: {symbol} = −ΣP/{omega} = {moment:.6g} N·m, |ΣP|/Σ|P| = "
                   "{residual:.2g}", symbol=BALANCING_MOMENT, omega=omega, moment=by_power,
                   residual=forces.power_residual)


def _combined_lines(forces: ForceAnalysis, notation: ForceNotation) -> list[str]:
    """Aliyev's combined force read off the plan, and his constants for all positions."""
    said: list[tuple[str, Message]] = []         # (indent, line)
    combined = forces.combined

    def sub(link: str) -> str:       # the link's number as a subscript (m₂, s₂, Q₂)
        return subscript(notation.number(link))

    if combined is not None:
        said.append(("  ", message("combined force Q = m·(g − a_S) (Aliyev): pole π moved "
                                   "down by Z_g = g/μa = {length:.4g} mm to π′",
                                   length=combined.gravity_image_mm)))
        said += [("    ", message("{link}: (s{sub}π′) = {length:.4g} mm → |Q{sub}| = "
                                  "{force:.6g} N", link=notation.link_name(force.link),
                                  sub=sub(force.link),
                                  length=float(norm(np.asarray(force.segment_mm))),
                                  force=float(norm(np.asarray(force.from_plan)))))
                 for force in combined.forces]
    constants = forces.constants
    if constants is not None and constants.force_moment is not None:
        said.append(("  ", message(    # (the products of scales as fields: no scale header)
            "constants for all positions (Aliyev): {scales} = {constant:.6g} N·m/mm²; "
            "{masses} N·m/mm²", scales="μF·μl", constant=constants.force_moment,
            masses=[message("m{sub}·{scales} = {value:.6g}", sub=sub(link), scales="μa·μl",
                            value=value)
                    for link, value in constants.combined_moment.items()])))
        if constants.inertia_moment:
            said.append(("    ", message("{constants} N·m/mm", constants=[
                message("J{sub}·μa/l_{points} = {value:.6g}", sub=sub(link),
                        points="".join(map(point_text, entry.points)), value=entry.constant)
                for link, entry in constants.inertia_moment.items()])))
    return [indent + render(line) for indent, line in said]
