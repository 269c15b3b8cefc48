"""The points of a drawn plan as an answer key gives them: which points a student places,
where each belongs with its tolerance disc, and where the known mistakes put it.

Three graders read these from the key (``plans.<plan>`` of :func:`~planmethod.grading.keys.
build_key`): the workbook page's drawing mode (:func:`drawing_frame` packs them per crank
angle; the page compares, it never computes mechanics), the PrairieLearn question's
``grade()`` and ``planmethod grade --drawing``. A misplaced point is named with every mistake
whose position of it lies within the point's own tolerance radius (:func:`named_mistakes`),
in the sentence of :data:`~planmethod.grading.verdicts.POINT_PARTS` (:func:`mistake_sentence`).
:func:`named_mistakes` and :func:`word_mistakes` are plain Python without imports: an
exported PrairieLearn ``server.py`` carries their very source, and the page's script
(``render/workbook_draw.js``) repeats their one comparison and one sentence, with the
wording (:func:`page_wording`: the same templates, rendered) and the mistakes' texts given
to it as data. The construction lines a point is the intersection of, with the name the
sentences give each (:func:`point_lines`), are data of the same rulebook.

Examples
--------
>>> entry = {"pole": "p", "points_mm": {"p": [0, 0], "o": [0, 0], "b": [0, 30]},
...          "steps": [{"action": "coincide", "start": "p", "end": "o"}]}
>>> drawn_labels(entry)
['b']
>>> named_mistakes([["sense", 0.0, -30.0], ["scale_ten", 0.0, 3.0]], 0.1, -29.8, 0.5)
['sense']
>>> from planmethod.words import render
>>> render(mistake_sentence(["sense"]))  # doctest: +ELLIPSIS
"it lies where the construction puts it when the crank's sense of rotation was reversed (..."
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..vocabulary import subscript, symbol
from ..words import Message, render
from .mistakes import REGISTRY, drawn_explanation
from .verdicts import POINT_PARTS, PointPart

__all__ = ["DRAWN_MISTAKES", "ConstructionLine", "common_mistakes", "drawing_frame",
           "drawn_labels", "graded_labels", "helper_labels", "mistake_sentence", "named_mistakes",
           "page_wording", "placing_steps", "plan_extent", "plan_sentence",
           "point_lines", "read_steps", "vector_name", "where_mistakes", "word_mistakes"]

#: the mistakes a drawn point can be named with, in the registry's order (the page refers to
#: them by their index here)
DRAWN_MISTAKES: tuple[str, ...] = tuple(REGISTRY)

#: a length of a plan shorter than this (mm) is none: a vector of zero laid off is not drawn,
#: a quantity read off it is zero (no share of it to tell)
ZERO_MM = 1e-9


def drawn_labels(entry: Mapping[str, Any]) -> list[str]:
    """The points a student places on a plan of a key (``key["plans"][plan]``): the points
    the construction really draws. Not the pole, nor a point the construction puts where
    another already is (a ``coincide`` step: a fixed point's image at the pole, c₀, or a
    Coriolis point whose term is zero, k_C on c₀), nor the end of a vector laid off with
    zero length (a Coriolis term that vanishes at this angle): those are neither drawn
    nor named.

    >>> drawn_labels({"pole": "π", "points_mm": {"π": [0, 0], "k_C": [0, 0], "c": [1, 0],
    ...                                         "k_B": [2, 2], "b": [2, 2]},
    ...               "steps": [{"action": "coincide", "start": "c@frame", "end": "k_C"},
    ...                         {"action": "lay_off", "start": "b", "end": "k_B",
    ...                          "length_mm": 0.0}]})
    ['c', 'b']
    """
    pole = entry["pole"]
    undrawn = {step.get("end") for step in entry["steps"]
               if step.get("action") == "coincide"
               or (step.get("action") == "lay_off" and step.get("length_mm") is not None
                   and abs(step["length_mm"]) < ZERO_MM)}
    return [label for label in entry["points_mm"] if label != pole and label not in undrawn]


def graded_labels(plan: Mapping[str, Any]) -> list[str]:
    """The points a drawn plan is scored on (``plan`` = ``key["plans"][name]``): the images
    of the mechanism's points away from the pole — ends of lay-offs, intersections and
    similarity steps. Helper points (n_CB, k_C) are checked when drawn, not required.

    >>> graded_labels({"pole": "p", "points_mm": {"p": [0, 0], "b": [0, 30], "n_CB": [1, 2],
    ...                                           "c@frame": [0, 0]}})
    ['b']
    """
    out = []
    pole = plan["pole"]
    for label, xy in plan["points_mm"].items():
        if label == pole or "_" in label or "@frame" in label:
            continue
        if math.hypot(*xy) < 1e-9:
            continue
        out.append(label)
    return out


def helper_labels(plan: Mapping[str, Any]) -> list[str]:
    """The helper points of a drawn plan (``plan`` = ``key["plans"][name]``) that are checked
    when drawn but never scored: the points of the construction named with an underscore
    (n_CB, k_C) that are not among :func:`graded_labels`.

    >>> helper_labels({"pole": "p", "points_mm": {"p": [0, 0], "b": [0, 30], "n_CB": [1, 2]}})
    ['n_CB']
    """
    graded = set(graded_labels(plan))
    return [label for label in plan["points_mm"] if label not in graded and "_" in label]


# the next two functions go into PrairieLearn's server.py as their source text, which a
# mutant cannot reach: they are not mutated (docs/contributing.md, mutation testing)
# pragma: no mutate start
def named_mistakes(candidates, x, y, radius):
    """The mistakes whose position of a point lies within ``radius`` of the drawn point
    (``x``, ``y``): ``candidates`` are ``[mistake, x, y]`` (mm); each mistake named once, in
    the candidates' order."""
    out = []
    for mistake, mistake_x, mistake_y in candidates:
        if ((x - mistake_x) ** 2 + (y - mistake_y) ** 2) ** 0.5 <= radius \
                and mistake not in out:
            out.append(mistake)
    return out


def common_mistakes(named):
    """The mistakes named on every wrong point of a plan, when two or more points are wrong
    (``named``: each wrong point's named mistakes, from :func:`named_mistakes`), in the
    first point's order; none for fewer (one point's own verdict already names its
    mistakes: a single misplaced point is no whole-plan mistake).

    >>> common_mistakes([["no_coriolis", "sense"], ["sense", "no_coriolis"]])
    ['no_coriolis', 'sense']
    >>> common_mistakes([["no_normal"]]), common_mistakes([["no_normal"], []])
    ([], [])
    """
    if len(named) < 2:
        return []
    return [mistake for mistake in named[0] if all(mistake in other for other in named[1:])]


def word_mistakes(mistakes, texts, wording):
    """Where a point lies that ``mistakes`` put there, in words: ``texts`` maps a mistake to
    what the student is told, ``wording`` is where it lies (``{}``: the mistakes) and the
    joint between two (planmethod's ``page_wording()[:2]``).

    >>> word_mistakes(["a", "b"], {"a": "A was done", "b": "B was not"},
    ...               ("where the construction puts it when {}", ", or when "))
    'where the construction puts it when A was done, or when B was not'
    """
    sentence, joint = wording
    return sentence.format(joint.join(texts[mistake] for mistake in mistakes))
# pragma: no mutate end


def _or_when(mistakes: Sequence[str]) -> Message:
    """The mistakes' explanations of a drawn point, one or the other."""
    sentence = drawn_explanation(mistakes[0])
    for mistake in mistakes[1:]:
        sentence = POINT_PARTS[PointPart.OR_WHEN].replace(first=sentence,
                                                          second=drawn_explanation(mistake))
    return sentence


def where_mistakes(mistakes: Sequence[str]) -> Message:
    """Where a point lies that ``mistakes`` put there (``where the construction puts it when
    …``)."""
    return POINT_PARTS[PointPart.WHERE].replace(mistakes=_or_when(mistakes))


def mistake_sentence(mistakes: Sequence[str]) -> Message:
    """What a student is told of a point that lies where ``mistakes`` put it."""
    return POINT_PARTS[PointPart.LIES].replace(where=where_mistakes(mistakes))


def plan_sentence(mistakes: Sequence[str]) -> Message:
    """What a student is told of a plan whose wrong points all lie where ``mistakes`` put
    them (:func:`common_mistakes`).

    >>> render(plan_sentence(["no_coriolis"])).endswith("puts them when the Coriolis "
    ...                                                 "component aᵏ was left out")
    True
    """
    return POINT_PARTS[PointPart.PLAN].replace(mistakes=_or_when(mistakes))


def page_wording() -> tuple[str, str, str]:
    """The sentences that name a drawn point's mistakes, in the language spoken, for a page
    (and a PrairieLearn question) that words them itself: where a point lies (``{}``: the
    mistakes), the joint between two mistakes, and the plan's sentence when every wrong point
    is named with them (``{}``: the mistakes) — :data:`~planmethod.grading.verdicts.
    POINT_PARTS`' ``where``, ``or_when`` and ``plan``, rendered.

    >>> page_wording()[1]
    ', or when '
    """
    parts = POINT_PARTS
    return (render(parts[PointPart.WHERE].replace(mistakes="{}")),
            render(parts[PointPart.OR_WHEN].replace(first="", second="")),
            render(parts[PointPart.PLAN].replace(mistakes="{}")))


#: the digits of a point's name in a label (``o2``, ``n_BO2``), set as subscripts
_DIGITS = re.compile(r"(?<=[A-Za-z])[0-9]+")


def vector_name(name: str, numbers: Mapping[str, int] | None = None) -> str:
    """A quantity or a vector a plan reads, as the course writes it: a quantity by its symbol
    (``omega_lever`` → ω₃, :func:`~planmethod.vocabulary.symbol`), a point taken as a point of
    a link with the link's number (``v_B@yokeB`` → v_B₃B), a relative acceleration by aʳ
    (``a_rel_CC@frame`` → aʳ_CC₀).

    >>> numbers = {"frame": 0, "crank": 1, "block": 2, "yoke": 3}
    >>> vector_name("a_rel_B@yokeB@frame", numbers), vector_name("omega_yoke", numbers)
    ('aʳ_B₃B₀', 'ω₃')
    """
    if numbers and "@" in name:
        for link in sorted(numbers, key=len, reverse=True):   # the longest name first
            name = name.replace(f"@{link}", subscript(str(numbers[link])))
    head, relative, rest = name.partition("a_rel_")
    if relative and not head:
        return "aʳ_" + _DIGITS.sub(lambda match: subscript(match.group(0)), rest)
    return symbol(name, numbers)


@dataclass(frozen=True, slots=True)
class ConstructionLine:
    """A construction line a plan point is an intersection of: its step's ``number``, the
    point it is drawn through (``through``, a label), its direction (degrees) and the words
    its step names it with (``name``: ``v_CB ⟂ CB``)."""

    number: int
    through: str
    direction_deg: float
    name: str


def line_name(step: Mapping[str, Any]) -> str:
    """The name of a key's line step (``v_CB ⟂ CB``): its ``line``; a key written before
    keys kept it names it in its sentence, after the point it is drawn through.

    >>> line_name({"text": "through b: v_CB ⟂ CB", "start": "b", "line": "v_CB ⟂ CB"})
    'v_CB ⟂ CB'
    >>> line_name({"text": "through b: v_CB ⟂ CB", "start": "b"})
    'v_CB ⟂ CB'
    """
    if "line" in step:
        return str(step["line"])
    # words: an older key's sentence (every line step's sentence is "through {start}: {line}")
    return str(step.get("text", "")).partition(": ")[2]


def point_lines(entry: Mapping[str, Any]) -> dict[str, tuple[ConstructionLine, ...]]:
    """The construction lines each intersection point of a key's plan (``key["plans"][plan]``)
    lies on, in the order of its step: what a point's sentence measures it from (off the
    line, or on it and off along it: a point of the wrong link — b₃ placed at b — lies on the
    line v_B₃B along the guide).

    >>> entry = {"steps": [{"number": 1, "action": "line", "start": "b", "direction_deg": 90.0,
    ...                     "text": "through b: v_CB ⟂ CB", "line": "v_CB ⟂ CB"},
    ...                    {"number": 2, "action": "intersect", "end": "c", "lines": [1, 5]}]}
    >>> point_lines(entry)["c"][0].name
    'v_CB ⟂ CB'
    """
    lines = {step["number"]: step for step in entry["steps"] if step.get("action") == "line"}
    out: dict[str, tuple[ConstructionLine, ...]] = {}
    for step in entry["steps"]:
        if step.get("action") != "intersect" or not step.get("end") or step["end"] in out:
            continue
        out[step["end"]] = tuple(
            ConstructionLine(number, lines[number]["start"],
                             float(lines[number]["direction_deg"]), line_name(lines[number]))
            for number in step.get("lines", ()) if number in lines)
    return out


def _exact(values: Sequence[float]) -> list[float]:
    """Numbers of a key as the page compares them: the key's own, to the last bit (the page's
    sentences are ``grade --drawing``'s, whose distances are told to two digits however
    small), never −0.0."""
    return [float(value) + 0.0 for value in values]


def placing_steps(steps: Sequence[Mapping[str, Any]]) -> dict[str, Mapping[str, Any]]:
    """The step that places each point of a key's plan (its first ``lay_off``, ``intersect``
    or ``similarity`` step that ends there): what a misplaced point's sentence tells of it.

    >>> placing_steps([{"action": "lay_off", "start": "p", "end": "b"},
    ...                {"action": "read", "start": "p", "end": "b"}])["b"]["action"]
    'lay_off'
    """
    out: dict[str, Mapping[str, Any]] = {}
    for step in steps:
        if step.get("end") and step["action"] in ("lay_off", "intersect", "similarity"):
            out.setdefault(step["end"], step)
    return out


def read_steps(entry: Mapping[str, Any], asked: set[str]) -> list[Mapping[str, Any]]:
    """The steps of a key's plan that read a quantity ``asked`` off a length that is not zero
    (:data:`ZERO_MM`): what a misplaced point that is one of their ends makes wrong.

    >>> [step["quantity"] for step in read_steps({"steps": [
    ...     {"action": "read", "quantity": "v_C", "length_mm": 30.0},
    ...     {"action": "read", "quantity": "omega_BC", "length_mm": 3e-15}]},
    ...     {"v_C", "omega_BC"})]
    ['v_C']
    """
    return [step for step in entry["steps"]
            if step["action"] == "read" and step.get("quantity") in asked
            and abs(step.get("length_mm") or 0.0) >= ZERO_MM]


def _sentence_data(entry: Mapping[str, Any], labels: Sequence[str], asked: set[str],
                   numbers: Mapping[str, int] | None) -> dict[str, Any]:
    """What the page needs to say of a misplaced point what ``grade --drawing`` says: the
    lines each intersection lies on (:func:`point_lines`: [through, direction, name]), the
    step that places each point ([``lay_off``, start, length, direction], [``similarity``,
    references] or [``intersect``]), the readings of the quantities asked ([symbol, start,
    end, length]) and where the other points these name belong (``others``: the pole, a
    point the construction puts on another)."""
    lines = point_lines(entry)
    placing = placing_steps(entry["steps"])
    placed: dict[str, list[Any]] = {}
    for label in labels:
        step = placing.get(label)
        if step is None:
            continue
        placed[label] = ([step["action"], step["start"], float(step["length_mm"]),
                          float(step["direction_deg"])] if step["action"] == "lay_off" else
                         ["similarity", list(step.get("references", []))]
                         if step["action"] == "similarity" else ["intersect"])
    reads = [[symbol(step["quantity"], numbers), step["start"], step["end"],
              float(step["length_mm"])] for step in read_steps(entry, asked)]
    named = {line.through for label in labels for line in lines.get(label, ())}
    named |= {one[1] for one in placed.values() if one[0] == "lay_off"}
    named |= {reference for one in placed.values() if one[0] == "similarity"
              for reference in one[1]}
    return {"lines": {label: [[line.through, line.direction_deg, line.name]
                              for line in lines[label]] for label in labels if lines.get(label)},
            "placed": placed, "reads": reads,
            "others": {label: _exact(entry["points_mm"][label])
                       for label in sorted(named - set(labels)) if label in entry["points_mm"]}}


def drawing_frame(key: Mapping[str, Any], numbers: Mapping[str, int] | None = None
                  ) -> dict[str, Any]:
    """One crank angle's drawing data for the workbook page, from its answer key: per plan,
    ``points`` {label: [x, y, tolerance radius]} (mm, y up, the pole at the origin) of the
    points a student places (:func:`drawn_labels`), ``required`` (those ``grade --drawing``
    scores), ``helpers`` (those it checks when placed: n, k …; any other — a point at the pole
    — it leaves out), ``mistakes`` {label:
    [[index in :data:`DRAWN_MISTAKES`, x, y], …]}, the plan's ``scale`` (as text) and
    ``unit``, and what a misplaced point's sentence tells of it (``lines``, ``placed``,
    ``reads``, ``others``: the quantities read named as the links' ``numbers`` name them).

    Examples
    --------
    >>> from planmethod.grading.keys import build_key
    >>> from planmethod.grading.templates import draw_variant, load_template
    >>> key = build_key(draw_variant(load_template("exercises/slotted_lever.toml")))
    >>> frame = drawing_frame(key)["acceleration"]
    >>> frame["required"]
    ['b', 'b@lever', 'c']
    >>> [DRAWN_MISTAKES[index] for index, *_ in frame["mistakes"]["b@lever"]][:3]
    ['no_normal', 'no_coriolis', 'coriolis_reversed']
    >>> [through for through, *_ in frame["lines"]["b@lever"]], frame["placed"]["c"]
    (['k_B@lever', 'n_B@lever'], ['similarity', ['o2']])
    """
    out: dict[str, Any] = {}
    index = {mistake: number for number, mistake in enumerate(DRAWN_MISTAKES)}
    asked = {question["id"] for question in key.get("questions", ())}
    for plan in ("velocity", "acceleration"):
        entry = key["plans"].get(plan)
        if entry is None:
            continue
        labels = drawn_labels(entry)
        required, helpers = set(graded_labels(entry)), set(helper_labels(entry))
        radii = entry["tolerance_mm"]
        wrong = entry.get("mistake_points", {})
        out[plan] = {
            "pole": entry["pole"], "scale": f"{entry['scale']:.6g}", "unit": entry["unit"],
            "points": {label: _exact([*entry["points_mm"][label], radii.get(label, 0.5)])
                       for label in labels},
            "required": [label for label in labels if label in required],
            "helpers": [label for label in labels if label in helpers],
            "mistakes": {label: [[index[mistake], x, y] for mistake, x, y in wrong[label]]
                         for label in labels if wrong.get(label)},
            **_sentence_data(entry, labels, asked, numbers),
        }
    return out


def plan_extent(frames: Sequence[Mapping[str, Any]], plan: str, margin: float = 15.0
                ) -> tuple[float, float, float, float]:
    """(left, bottom, right, top) in mm, y up, of a plan's points over all ``frames`` (their
    :func:`drawing_frame` data) and the pole, widened by ``margin`` and rounded out to 10 mm:
    one sheet for the whole turn.

    >>> plan_extent([{"velocity": {"points": {"b": [12.0, -3.0, 0.5]}}}], "velocity")
    (-20.0, -20.0, 30.0, 20.0)
    """
    xs, ys = [0.0], [0.0]
    for frame in frames:
        for x, y, _ in frame.get(plan, {}).get("points", {}).values():
            xs.append(x)
            ys.append(y)
    return (10.0 * math.floor((min(xs) - margin) / 10.0),
            10.0 * math.floor((min(ys) - margin) / 10.0),
            10.0 * math.ceil((max(xs) + margin) / 10.0),
            10.0 * math.ceil((max(ys) + margin) / 10.0))
