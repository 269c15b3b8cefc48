"""The words of the plans: each construction step's sentence, each flag's, each plan's title
and scale lines, written from message templates with named fields.

The plan emulator records typed steps (:mod:`planmethod.plans.steps`) and holds no sentence;
this module is where each kind of step, and each reason it gives (what a vector laid off is,
what gives a line its direction, what an intersection solves), has its template
(:data:`STEP_MESSAGES`). The fields are the step's own, in the course's notation computed with
:mod:`planmethod.vocabulary` — a point of a link by the link's number (``b@lever`` → b₃), a
quantity by its symbol (``omega_BC`` → ω₂), a Coriolis point without its side's index
(``k1_Q`` → k_Q), the digits of a point's name as subscripts (O₂) — so that a catalogue
translates the sentence and the notation stays. The JSON report's steps (:func:`plan_dict`)
keep their fields and carry the sentence, rendered, as ``text``.

Examples
--------
>>> from planmethod.plans.steps import Read, VectorName
>>> from planmethod.words import render
>>> step = Read(number=9, start="b", end="b@lever", length_mm=12.313, quantity="v_B@leverB",
...             value=-0.3078, relative=VectorName("v", "B@lever", "B"))
>>> render(step_message(step, "velocity", {"lever": 3}))
'(bb₃) = 12.31 mm → v_B₃B = -0.3078'
>>> label_text("k1_Q"), label_text("n_B@lever", {"lever": 3}), label_text("o2")
('k_Q', 'n_B₃', 'o₂')
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from ..plans.steps import (
    Across,
    BothEquations,
    BothSides,
    Coincide,
    CoriolisComponent,
    CrankNormal,
    CrankTangential,
    CrankVelocity,
    FixedPivot,
    FrameImage,
    Guide,
    Intersect,
    LayOff,
    Line,
    NormalComponent,
    NormalOfSegment,
    Pole,
    PoorIntersection,
    Project,
    Read,
    ReadRadius,
    Similarity,
    SpecialAcceleration,
    SpecialGuide,
    SpecialPoint,
    SpecialSide,
    Step,
    VectorName,
    VelocityEquation,
)
from ..vocabulary import (
    PlanKind,
    coriolis_letter,
    links_text,
    numbered,
    point_name,
    point_text,
    scale_text,
    subscript,
    symbol,
)
from ..words import Message, message, render

if TYPE_CHECKING:
    from ..plans import Plan, Scales

__all__ = ["LINE_MESSAGES", "STEP_MESSAGES", "flag_message", "label_text", "line_text",
           "plan_dict", "plan_title", "scale_lines", "step_dict", "step_message", "step_text",
           "vector_text"]

Numbers = Mapping[str, int]


# -- notation ---------------------------------------------------------------------------------
def label_text(label: str, numbers: Numbers | None = None) -> str:
    """A plan point's label as a course writes it: the image of a point of a link with the
    link's number (``c@frame`` → c₀, ``n_B@lever`` → n_B₃), a Coriolis point without its
    side's index (``k1_Q``, ``k2_Q`` → k_Q, k′_Q), the digits of a name as subscripts (o₂).

    >>> label_text("c@frame", {"frame": 0}), label_text("k2_Q"), label_text("n_BO2")
    ('c₀', 'k′_Q', 'n_BO₂')
    """
    name, at, link = label.partition("@")
    head, underscore, rest = name.partition("_")
    if underscore and head[:1] == "k" and head[1:].isdigit():
        head = coriolis_letter(head[1:])
    text = point_text(head) + underscore + point_text(rest) if underscore else point_text(head)
    if not at:
        return text
    return text + (subscript(str(numbers[link])) if numbers and link in numbers else at + link)


def vector_text(vector: VectorName, numbers: Numbers | None = None) -> str:
    """A vector as a course writes it: its symbol, the point, the base of a relative motion
    (``aⁿ_B@leverO2`` → aⁿ_B₃O₂).

    >>> vector_text(VectorName("aʳ", "C", "C@frame"), {"frame": 0})
    'aʳ_CC₀'
    """
    return f"{vector.symbol}_{point_name(vector.point, numbers)}{_point(vector.base, numbers)}"


def _point(name: str, numbers: Numbers | None) -> str:
    return point_name(name, numbers) if name else ""


def _words(link: str) -> str:
    """A link's name in words (an underscore a space)."""
    return link.replace("_", " ")


def _number(link: str, numbers: Numbers) -> int | str:
    """A link by its number (by its name in words where it has none)."""
    return numbers[link] if link in numbers else _words(link)


def _rate(letter: str, link: str, numbers: Numbers) -> str:
    """A link's ω or ε by the link's number (ω₂)."""
    return numbered(letter, numbers[link]) if link in numbers else f"{letter}_{_words(link)}"


def _read_symbol(step: Read, numbers: Numbers, slides: Mapping[str, str] | None = None
                 ) -> str:
    """What a reading gives, as a course writes it: a relative motion by its vector, a
    quantity by its symbol (``a_rel_…`` by aʳ; a slide's sliding velocity by its point's
    relative velocity, v_B₃B₂, where ``slides`` has the point and the segment read joins two
    images of it)."""
    if step.relative is not None:
        return vector_text(step.relative, numbers)
    point = (slides or {}).get(step.quantity.partition("_")[2])
    if point is None or not all(_of_point(label, point) for label in (step.start, step.end)):
        return symbol(step.quantity, numbers)
    return symbol(step.quantity, numbers, slides)


def _of_point(label: str, point: str) -> bool:
    """Whether a plan label is an image of ``point`` (``b``, ``b@lever``) or the end of its
    Coriolis component (``k_B@lever``, ``k2_B``)."""
    name = re.sub(r"^k\d*_", "", label.partition("@")[0])
    return name in (point, point.lower())


# -- the steps' sentences ---------------------------------------------------------------------
class _Fields:
    """What every template of a step may name: its plan points, vector and numbers, in the
    course's notation."""

    def __init__(self, step: Step, kind: str, numbers: Numbers,
                 slides: Mapping[str, str] | None = None) -> None:
        self.step, self.kind, self.numbers, self.slides = step, kind, numbers, slides
        self.start = label_text(step.start, numbers) if step.start else ""
        self.end = label_text(step.end, numbers) if step.end else ""

    @property
    def vector(self) -> str:
        return vector_text(self.step.vector, self.numbers)

    def point(self, name: str) -> str:
        return point_name(name, self.numbers)


def _crank_velocity(known: CrankVelocity, at: _Fields) -> Message:
    return message("{vector} = {omega}·l_{pivot}{point} = {speed:.6g} m/s, ⟂ {pivot}{point} "
                   "in the sense of {omega}", vector=at.vector,
                   omega=_rate("ω", known.link, at.numbers), pivot=at.point(known.pivot),
                   point=at.point(known.point), speed=known.speed)


def _crank_normal(known: CrankNormal, at: _Fields) -> Message:
    omega = _rate("ω", known.link, at.numbers)
    pivot, point = at.point(known.pivot), at.point(known.point)
    if known.whole:
        return message("{vector} = aⁿ = {omega}²·l = {value:.6g} m/s², from {point} towards "
                       "{pivot}", vector=at.vector, omega=omega, value=known.magnitude,
                       point=point, pivot=pivot)
    return message("aⁿ = {omega}²·l = {value:.6g} m/s², from {point} towards {pivot}",
                   omega=omega, value=known.magnitude, point=point, pivot=pivot)


def _crank_tangential(known: CrankTangential, at: _Fields) -> Message:
    return message("aᵗ = {epsilon}·l = {value:.6g} m/s², ⟂ {pivot}{point} in the sense of "
                   "{epsilon}", epsilon=_rate("ε", known.link, at.numbers),
                   value=known.magnitude, pivot=at.point(known.pivot),
                   point=at.point(known.point))


def _normal_component(known: NormalComponent, at: _Fields) -> Message:
    return message("{vector} from {start}: ({start}{end}) = (v-plan segment)²·μv²/"
                   "(({point}{centre})·μl·μa), from {point} towards {centre}",
                   vector=at.vector, start=at.start, end=at.end, point=at.point(known.point),
                   centre=at.point(known.centre))


def _normal_of_segment(known: NormalOfSegment, at: _Fields) -> Message:
    return message("{vector} from {start}: ({first}{second})²·μv²/(length·μl·μa), towards "
                   "the centre", vector=at.vector, start=at.start,
                   first=label_text(known.first, at.numbers),
                   second=label_text(known.second, at.numbers))


def _coriolis(known: CoriolisComponent, at: _Fields) -> Message:
    if known.turns:
        return message("aᵏ = 2·{omega}·v_rel from {start}, v_rel turned 90° in the sense of "
                       "{omega}", omega=_rate("ω", known.carrier, at.numbers), start=at.start)
    return message("aᵏ = 0: {link} does not turn; {end} coincides with {start}",
                   link=_words(known.carrier), end=at.end, start=at.start)


def _fixed_pivot(known: FixedPivot, at: _Fields) -> Message:
    return message("{end} at the pole: {point} is fixed", end=at.end,
                   point=at.point(known.point))


def _frame_image(known: FrameImage, at: _Fields) -> Message:
    return message("{end} at the pole: the frame does not move", end=at.end)


def _across(along: Across, at: _Fields) -> Message:
    return message("{vector} ⟂ {first}{second}", vector=at.vector, first=at.point(along.first),
                   second=at.point(along.second))


def _guide(along: Guide, at: _Fields) -> Message:
    first, second = _number(along.link, at.numbers), _number(along.along, at.numbers)
    if at.kind == PlanKind.VELOCITY:
        return message("{vector} along the guide of pair {first}–{second}", vector=at.vector,
                       first=first, second=second)
    return message("{vector} (relative) along the guide of pair {first}–{second}",
                   vector=at.vector, first=first, second=second)


def _special_side(along: SpecialSide, at: _Fields) -> Message:
    outer, inner = at.point(along.outer), at.point(along.inner)
    if at.kind == PlanKind.VELOCITY:
        return message("v_S* − v_{outer} ⟂ {outer}{inner} (S* lies on the line {outer}{inner})",
                       outer=outer, inner=inner)
    return message("aᵗ_{inner}{outer} + aᵗ_S*{inner} ⟂ {outer}{inner}", outer=outer,
                   inner=inner)


def _special_guide(along: SpecialGuide, at: _Fields) -> Message:
    first, second = _number(along.link, at.numbers), _number(along.along, at.numbers)
    if at.kind == PlanKind.VELOCITY:
        return message("{vector} along the guide of pair {first}–{second} (S* lies on the "
                       "normal to the guide through {pin})", vector=at.vector, first=first,
                       second=second, pin=at.point(along.pin))
    return message("aʳ + aᵗ_S*{pin} along the guide of pair {first}–{second}",
                   pin=at.point(along.pin), first=first, second=second)


#: the name of a construction line — what it is drawn as, a drawn point's sentence names it
#: by it —, by what gives the line its direction
LINE_MESSAGES: dict[type, Callable[[Any, _Fields], Message]] = {
    Across: _across, Guide: _guide, SpecialSide: _special_side, SpecialGuide: _special_guide,
}


def _through(along: Across | Guide | SpecialSide | SpecialGuide, at: _Fields) -> Message:
    """A line step's sentence: the point it is drawn through, and the line's name."""
    return message("through {start}: {line}", start=at.start,
                   line=LINE_MESSAGES[type(along)](along, at))


def _velocity_equation(solves: VelocityEquation, at: _Fields) -> Message:
    point, numbers = solves.point, at.numbers
    sides = [f"v_{_point(base, numbers)} + {vector_text(VectorName('v', point, base), numbers)}"
             for base in solves.bases]
    return message("{end}: {equation}", end=at.end,
                   equation=" = ".join([f"v_{at.point(point)}", *sides]))


def _both_equations(solves: BothEquations, at: _Fields) -> Message:
    return message("{end}: a_{point} from both vector equations", end=at.end,
                   point=at.point(solves.point))


def _special_point(solves: SpecialPoint, at: _Fields) -> Message:
    return message("{end}: Assur's special point S* = ({x:.6g}, {y:.6g}) m of {central}, where "
                   "the lines of {first} and {second} meet", end=at.end, x=solves.x,
                   y=solves.y, central=_words(solves.central), first=_words(solves.first),
                   second=_words(solves.second))


def _special_acceleration(solves: SpecialAcceleration, at: _Fields) -> Message:
    return message("{end}: a_S* from the two sides through the special point", end=at.end)


def _both_sides(solves: BothSides, at: _Fields) -> Message:
    return message("{end}: a_{point} from both sides", end=at.end,
                   point=at.point(solves.point))


#: the sentence of what a vector laid off (or coinciding) is, what gives a line its
#: direction, what an intersection solves: by the reason's type
REASON_MESSAGES: dict[type, Callable[[Any, _Fields], Message]] = {
    CrankVelocity: _crank_velocity, CrankNormal: _crank_normal,
    CrankTangential: _crank_tangential, NormalComponent: _normal_component,
    NormalOfSegment: _normal_of_segment, CoriolisComponent: _coriolis,
    FixedPivot: _fixed_pivot, FrameImage: _frame_image,
    Across: _through, Guide: _through, SpecialSide: _through, SpecialGuide: _through,
    VelocityEquation: _velocity_equation, BothEquations: _both_equations,
    SpecialPoint: _special_point, SpecialAcceleration: _special_acceleration,
    BothSides: _both_sides,
}


def _pole(step: Pole, at: _Fields) -> Message:
    return message("pole {pole}", pole=at.end)


def _similarity(step: Similarity, at: _Fields) -> Message:
    return message("{end} by similarity on link {link} from {start}", end=at.end,
                   link=_number(step.link, at.numbers), start=at.start)


def _project(step: Project, at: _Fields) -> Message:
    return message("project π{start} on the normal to the path of {point} (⟂ p{speed}): {end}",
                   start=at.start, point=point_text(step.point),
                   speed=label_text(step.speed, at.numbers), end=at.end)


def _read(step: Read, at: _Fields) -> Message:
    return message("({start}{end}) = {length:.4g} mm → {quantity} = {value:.6g}",
                   start=at.start, end=at.end, length=step.length_mm,
                   quantity=_read_symbol(step, at.numbers, at.slides), value=step.value)


def _read_radius(step: ReadRadius, at: _Fields) -> Message:
    return message("ρ_{point} = (p{speed})²·μv²/((π{end})·μa) = {value:.6g} m",
                   point=point_text(step.point), speed=label_text(step.speed, at.numbers),
                   end=at.end, value=step.value)


def _reason(field: str) -> Callable[[Step, _Fields], Message]:
    """A step's sentence is its reason's (``known``, ``along``, ``solves``)."""
    def sentence(step: Step, at: _Fields) -> Message:
        reason = getattr(step, field)
        return REASON_MESSAGES[type(reason)](reason, at)
    return sentence


#: each step's sentence, by the step's type
STEP_MESSAGES: dict[type, Callable[[Any, _Fields], Message]] = {
    Pole: _pole, LayOff: _reason("known"), Coincide: _reason("known"),
    Line: _reason("along"), Intersect: _reason("solves"), Similarity: _similarity,
    Project: _project, Read: _read, ReadRadius: _read_radius,
}


def step_message(step: Step, kind: str, numbers: Numbers | None = None,
                 slides: Mapping[str, str] | None = None) -> Message:
    """The sentence of a construction ``step`` of the plan of ``kind`` (velocity or
    acceleration), its fields in the course's notation (``numbers``: the links' numbers;
    ``slides``: each prismatic pair's point, :func:`planmethod.vocabulary.slide_points`)."""
    return STEP_MESSAGES[type(step)](step, _Fields(step, kind, numbers or {}, slides))


def step_text(step: Step, plan: Plan) -> str:
    """The sentence of ``step`` of ``plan``, as text in the language spoken now."""
    return render(step_message(step, plan.kind, plan.numbers, plan.slides))


def line_text(step: Step, plan: Plan) -> str | None:
    """The name of the line a line step of ``plan`` draws (``v_CB ⟂ CB``: its sentence
    without the point it is drawn through), as text in the language spoken now; None for
    another step.

    >>> from planmethod.plans import draw_plans
    >>> from planmethod.spec import load_exercise
    >>> plan = draw_plans(load_exercise("exercises/compressor_slider_crank.toml")).velocity
    >>> [(step_text(s, plan), line_text(s, plan)) for s in plan.steps if line_text(s, plan)][0]
    ('through b: v_CB ⟂ CB', 'v_CB ⟂ CB')
    """
    along = getattr(step, "along", None)
    if type(along) not in LINE_MESSAGES:
        return None
    return render(LINE_MESSAGES[type(along)](along, _Fields(step, plan.kind, plan.numbers)))


def step_dict(step: Step, plan: Plan) -> dict:
    """A step of ``plan`` as the JSON report writes it (docs/json-report.md, "Plan steps"):
    ``number``, ``action``, its sentence as ``text``, then its fields."""
    fields = step.as_dict()
    return {"number": fields.pop("number"), "action": fields.pop("action"),
            "text": step_text(step, plan), **fields}


# -- flags, titles, scales --------------------------------------------------------------------
def flag_message(flag: PoorIntersection | Message | str, numbers: Numbers | None = None
                 ) -> Message | str:
    """A plan's flag as a sentence (a message or text given is returned as it is).

    >>> from planmethod.words import render
    >>> flag = PoorIntersection(PlanKind.VELOCITY, ("block", "yoke"), 0.7, 1.0, "b@yoke")
    >>> render(flag_message(flag, {"block": 2, "yoke": 3}))
    'velocity plan, group of links 2, 3 (block, yoke): the lines meet at 0.7° (below 1°): \
point b₃ is poorly defined'
    """
    if not isinstance(flag, PoorIntersection):
        return flag
    links = links_text(flag.links, numbers)          # words: vocabulary
    point = label_text(flag.point, numbers)
    if flag.plan == PlanKind.VELOCITY:
        return message("velocity plan, group of {links}: the lines meet at {angle:.3g}° (below "
                       "{limit:g}°): point {point} is poorly defined", links=links,
                       angle=flag.angle_deg, limit=flag.limit_deg, point=point)
    return message("acceleration plan, group of {links}: the lines meet at {angle:.3g}° (below "
                   "{limit:g}°): point {point} is poorly defined", links=links,
                   angle=flag.angle_deg, limit=flag.limit_deg, point=point)


def plan_title(plan: Plan) -> Message:
    """A velocity or acceleration plan's title: the mechanism's, the plan's, the crank
    angle by the crank's φ."""
    phi = numbered("φ", plan.crank)
    if plan.kind == PlanKind.VELOCITY:
        return message("{title} — velocity plan, {phi} = {angle:g}°", title=plan.title,
                       phi=phi, angle=plan.angle)
    return message("{title} — acceleration plan, {phi} = {angle:g}°", title=plan.title,
                   phi=phi, angle=plan.angle)


def scale_lines(scales: Scales) -> list[Message | str]:
    """The scales as a drawing prints them, with units: μl, μv, μa, the analogue scales
    μφv = μv/ω₁, μφa = μa/ω₁² (the crank's ω by its number), μF if set.

    >>> from planmethod.plans import Scales
    >>> from planmethod.words import render
    >>> render(scale_lines(Scales(0.002, 0.2, 20.0, 100.0, "B", crank=2))[3])
    'μφv = μv/ω₂ = 0.002 m/mm'
    """
    lines: list[Message | str] = [scale_text(name, getattr(scales, name))  # words: vocabulary
                                  for name in ("mu_l", "mu_v", "mu_a")]
    if scales.omega1:
        omega = numbered("ω", scales.crank)
        lines += [message("μφv = μv/{omega} = {scale:.6g} m/mm", omega=omega,
                          scale=scales.mu_phi_v),
                  message("μφa = μa/{omega}² = {scale:.6g} m/mm", omega=omega,
                          scale=scales.mu_phi_a)]
    if scales.mu_f is not None:
        lines.append(scale_text("mu_f", scales.mu_f))     # words: vocabulary
    return lines


def plan_dict(plan: Plan) -> dict:
    """A velocity or acceleration plan as the JSON report writes it: pole, scale, unit,
    points, steps (each with its sentence), flags (as sentences)."""
    return {"pole": plan.pole, "scale": plan.scale, "unit": plan.unit,
            "points_mm": {k: list(v) for k, v in plan.points_mm.items()},
            "steps": [step_dict(step, plan) for step in plan.steps],
            "flags": [render(flag_message(flag, plan.numbers)) for flag in plan.flags]}
