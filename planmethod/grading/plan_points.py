"""The points of a drawn plan as an answer key gives them: which points a student places,
where each belongs with its tolerance disc, and where the known mistakes put it.

Three graders read these from the key (``plans.<plan>`` of :func:`~planmethod.grading.keys.
build_key`): the workbook page's drawing mode (:func:`drawing_frame` packs them per crank
angle; the page compares, it never computes mechanics), the PrairieLearn question's
``grade()`` and ``planmethod grade --drawing``. A misplaced point is named with every mistake
whose position of it lies within the point's own tolerance radius (:func:`named_mistakes`,
worded by :func:`word_mistakes`). Those two are plain Python without imports: an exported
PrairieLearn ``server.py`` carries their very source, and the page's script
(``render/workbook_draw.js``) repeats their one comparison and one sentence, with the
wording and the mistakes' texts given to it as data.

Examples
--------
>>> entry = {"pole": "p", "points_mm": {"p": [0, 0], "o": [0, 0], "b": [0, 30]},
...          "steps": [{"action": "coincide", "start": "p", "end": "o"}]}
>>> drawn_labels(entry)
['b']
>>> named_mistakes([["sense", 0.0, -30.0], ["scale_ten", 0.0, 3.0]], 0.1, -29.8, 0.5)
['sense']
>>> mistake_sentence(["sense"])  # doctest: +ELLIPSIS
"it lies where the construction puts it when the crank's sense of rotation was reversed (..."
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from .mistakes import REGISTRY, drawn_explanation

__all__ = ["DRAWN_MISTAKES", "MISTAKE_WORDING", "PLAN_WORDING", "common_mistakes",
           "drawing_frame", "drawn_labels", "graded_labels", "mistake_sentence",
           "named_mistakes", "plan_extent", "plan_sentence", "word_mistakes"]

#: the mistakes a drawn point can be named with, in the registry's order (the page refers to
#: them by their index here)
DRAWN_MISTAKES: tuple[str, ...] = tuple(REGISTRY)

#: how named mistakes are worded: where the point lies, and the joint between two mistakes
MISTAKE_WORDING = ("where the construction puts it when {}", ", or when ")

#: how the mistakes named on every wrong point of a plan are worded (joined as
#: :data:`MISTAKE_WORDING` joins them)
PLAN_WORDING = "the wrong points all lie where the construction puts them when {}"

#: decimals of a millimetre kept of the right points and radii in the page
RIGHT_DECIMALS = 3


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
                   and abs(step["length_mm"]) < 1e-9)}
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
    what the student is told, ``wording`` is :data:`MISTAKE_WORDING`.

    >>> word_mistakes(["a", "b"], {"a": "A was done", "b": "B was not"}, MISTAKE_WORDING)
    'where the construction puts it when A was done, or when B was not'
    """
    sentence, joint = wording
    return sentence.format(joint.join(texts[mistake] for mistake in mistakes))
# pragma: no mutate end


def mistake_sentence(mistakes: Sequence[str]) -> str:
    """What a student is told of a point that lies where ``mistakes`` put it."""
    texts = {mistake: drawn_explanation(mistake) for mistake in mistakes}
    return "it lies " + word_mistakes(mistakes, texts, MISTAKE_WORDING)


def plan_sentence(mistakes: Sequence[str]) -> str:
    """What a student is told of a plan whose wrong points all lie where ``mistakes`` put
    them (:func:`common_mistakes`).

    >>> plan_sentence(["no_coriolis"]).endswith("puts them when the Coriolis component aᵏ "
    ...                                        "was left out")
    True
    """
    return PLAN_WORDING.format(MISTAKE_WORDING[1].join(drawn_explanation(mistake)
                                                       for mistake in mistakes))


def _rounded(values: Sequence[float], decimals: int = RIGHT_DECIMALS) -> list[float]:
    return [round(float(value), decimals) + 0.0 for value in values]   # no −0.0


def drawing_frame(key: Mapping[str, Any]) -> dict[str, Any]:
    """One crank angle's drawing data for the workbook page, from its answer key: per plan,
    ``points`` {label: [x, y, tolerance radius]} (mm, y up, the pole at the origin) of the
    points a student places (:func:`drawn_labels`), ``required`` (those ``grade --drawing``
    scores; the others — n, k … — are checked when placed), ``mistakes`` {label:
    [[index in :data:`DRAWN_MISTAKES`, x, y], …]}, and the plan's ``scale`` (as text) and
    ``unit``.

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
    """
    out: dict[str, Any] = {}
    index = {mistake: number for number, mistake in enumerate(DRAWN_MISTAKES)}
    for plan in ("velocity", "acceleration"):
        entry = key["plans"].get(plan)
        if entry is None:
            continue
        labels = drawn_labels(entry)
        required = set(graded_labels(entry))
        radii = entry["tolerance_mm"]
        wrong = entry.get("mistake_points", {})
        out[plan] = {
            "pole": entry["pole"], "scale": f"{entry['scale']:.6g}", "unit": entry["unit"],
            "points": {label: _rounded([*entry["points_mm"][label], radii.get(label, 0.5)])
                       for label in labels},
            "required": [label for label in labels if label in required],
            "mistakes": {label: [[index[mistake], x, y] for mistake, x, y in wrong[label]]
                         for label in labels if wrong.get(label)},
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
