"""The rulebook a page receives: ``planmethod grade``'s rules as data, in the page's language.

The workbook page grades a typed answer and a drawn plan point in the browser. It does so
with the rules written here and in :mod:`planmethod.grading` — never with rules of its own —
sent to it as data (:func:`page_rules`, :meth:`PageRules.as_dict`) that its script
(``page_rules.js`` beside this module, with ``page_words.js``) applies:

* the grammar of a typed number (:func:`planmethod.grading.reading.number_grammar`: the one
  :func:`~planmethod.grading.reading.read_number` of ``grade`` reads too);
* how a text that is no number is quoted back (Python's ``repr``: the unprintable code points,
  :func:`unprintable_points`);
* the verdict classes of an answer in the order they are tried (:data:`ANSWER_CLASSES`), each
  with its feedback and hint templates;
* every template the page fills (:data:`PAGE_TEMPLATES`: the verdicts, their parts, the
  sentences of a drawn point and the page's own words), already translated into the page's
  language by the catalogue, fields kept (:func:`template_text`), and the language's decimal
  sign.

The verdicts' English is ``grade``'s to the byte (tests/test_page_rules.py and the golden
file tests/page_golden.py checks the page against it, under Node and in Chromium).

Where the templates come from: ``grade_question`` (:mod:`planmethod.grading.answers`) still
writes its sentences with f-strings, and the drawn points' wording is
:data:`~planmethod.grading.plan_points.MISTAKE_WORDING` and ``PLAN_WORDING``; the templates
here say the same words with named fields (the tests hold them equal). When grading's own
table of verdict templates lands, :func:`page_rules` reads it instead of
:data:`PAGE_TEMPLATES`' verdict entries — this function is the one place to switch.

Examples
--------
>>> rules = page_rules("en")
>>> [verdict.name for verdict in rules.answers][:3]
['no_answer', 'not_a_number', 'correct']
>>> rules.templates["right"], rules.decimal
('{value:.6g} {unit} ± {tolerance:.3g}', '.')
>>> quoted("it's", unprintable_points()), quoted("a\\x00", unprintable_points())
('"it\\'s"', "'a\\\\x00'")
"""

from __future__ import annotations

import functools
import math
import string
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..grading.answers import sense_words
from ..grading.reading import NumberGrammar, number_grammar
from ..words import Message, current, render, template
from ..words.render import DECIMAL_SIGN

__all__ = ["ANSWER_CLASSES", "PAGE_TEMPLATES", "AnswerClass", "PageRules", "PointVerdict",
           "mistakes_message", "page_rules", "plan_summary", "point_verdict", "quoted",
           "template_text", "unprintable_points"]


@dataclass(frozen=True)
class AnswerClass:
    """One verdict class of a typed answer: its name (the page's ``verdict``) and the ids of
    its feedback (with the right value) and hint (without it) templates."""

    name: str
    feedback: str
    hint: str


#: the verdict classes, in the order ``grade_question`` tries them: the first that holds is
#: the verdict
ANSWER_CLASSES = (
    AnswerClass("no_answer", "no_answer", "no_answer_hint"),
    AnswerClass("not_a_number", "not_a_number", "not_a_number_hint"),
    AnswerClass("correct", "correct", "correct_hint"),
    AnswerClass("sense_mistake", "sense_mistake", "mistake_hint"),
    AnswerClass("mistake", "mistake", "mistake_hint"),
    AnswerClass("mistake_and_sense", "mistake_and_sense", "mistake_and_sense_hint"),
    AnswerClass("negative_magnitude", "negative_magnitude", "negative_magnitude_hint"),
    AnswerClass("sense_reversed", "sense_reversed", "wrong_hint"),
    AnswerClass("wrong", "wrong", "wrong_hint"),
)

#: every template the workbook page fills, by id
PAGE_TEMPLATES: dict[str, Message] = {
    # a typed answer's verdicts (the words of planmethod.grading.answers.grade_question)
    "no_answer": template("{name}: no answer (right: {right})"),
    "no_answer_hint": template("{name}: no answer"),
    "not_a_number": template("{name}: {text} is not a number (right: {right})"),
    "not_a_number_hint": template("{name}: {text} is not a number"),
    "correct": template("{shown}: correct (exact {value:.6g}, tolerance ± {tolerance:.3g})"),
    "correct_hint": template("{shown}: correct"),
    "sense_mistake": template("{shown}: wrong — it looks as if {explanation} (that gives "
                              "{given:.6g}; right: {right})"),
    "mistake": template("{shown}: wrong, {off} — it looks as if {explanation} (that gives "
                        "{given:.6g}; right: {right})"),
    "mistake_hint": template("{shown}: wrong ({way}) — it looks as if {explanation}"),
    "mistake_and_sense": template("{shown}: wrong — it looks as if {explanation}, and the "
                                  "sense is reversed (right: {right})"),
    "mistake_and_sense_hint": template("{shown}: wrong — it looks as if {explanation}, and "
                                       "the sense is reversed"),
    "negative_magnitude": template("{shown}: wrong — {note} (right: {right})"),
    "negative_magnitude_hint": template("{shown}: wrong — {note}"),
    "sense_reversed": template("{shown}: wrong — the sense is reversed (the right answer is "
                               "{direction}, {right}) and the magnitude {magnitude:.6g} is "
                               "{size}"),
    "wrong": template("{shown}: wrong — {off} (off by {amount}; right: {right})"),
    "wrong_hint": template("{shown}: wrong ({way})"),
    # their parts
    "right": template("{value:.6g} {unit} ± {tolerance:.3g}"),
    "right_unitless": template("{value:.6g} ± {tolerance:.3g}"),
    "right_relative": template("{right} = ± {relative:.2g} %"),
    "shown": template("{name} = {answer:.6g} {unit}"),
    "shown_unitless": template("{name} = {answer:.6g}"),
    "amount": template("{amount:.6g} {unit}"),
    "amount_unitless": template("{amount:.6g}"),
    "off_zero": template("{difference:.3g} off"),
    "off_times": template("{ratio:.4g} times the right value"),
    "off_high": template("{percent:.1f} % high"),
    "off_low": template("{percent:.1f} % low"),
    "off_high_magnitude": template("{percent:.1f} % high in magnitude"),
    "off_low_magnitude": template("{percent:.1f} % low in magnitude"),
    "way_reversed": template("the sense is reversed"),
    "way_larger": template("too large in magnitude"),
    "way_smaller": template("too small in magnitude"),
    "way_high": template("too high"),
    "way_low": template("too low"),
    "size_right": template("right", context="a magnitude that is right"),
    # a drawn point (the words of planmethod.grading.plan_points: mistake_sentence,
    # plan_sentence)
    "point_missing": template("{name}: not placed"),
    "point_missing_helper": template("{name}: not placed (a construction point: checked when "
                                     "placed)"),
    "point_right": template("{name}: right — {distance:.2f} mm from where the construction "
                            "puts it, within its tolerance of {radius:.2f} mm"),
    "point_off": template("{name} is {distance:.1f} mm off (tolerance {radius:.2f} mm)"),
    "point_off_mistakes": template("{name} is {distance:.1f} mm off (tolerance {radius:.2f} "
                                   "mm); {mistakes}"),
    "point_mistakes": template("it lies where the construction puts it when {mistakes}"),
    "mistakes_joint": template(", or when "),
    "plan_right_velocity": template("{right} of {total} points of the velocity plan right"),
    "plan_right_acceleration": template("{right} of {total} points of the acceleration plan "
                                        "right"),
    "plan_summary_mistakes": template("{count}; {mistakes}"),
    "plan_mistakes": template("the wrong points all lie where the construction puts them "
                              "when {mistakes}"),
    # the page's own words
    "angle_shown": template("{angle:g}°"),
    "switch_time": template("{time:.1f} ms"),
    "play": template("play"),
    "pause": template("pause"),
    "step_of": template("step {number} of {count}"),
    "step_sentence": template("step {number} of {count}: {sentence}"),
    "no_plan_velocity": template("no velocity plan at this angle"),
    "no_plan_acceleration": template("no acceleration plan at this angle"),
    "tolerance_shown": template("± {tolerance:.3g} {unit}"),
    "tolerance_shown_unitless": template("± {tolerance:.3g}"),
    "not_graded": template("not graded at this angle"),
    "needs_decompression": template("this page needs a browser with {feature}: {error}"),
    "kept_unreadable": template("a drawing kept in this browser could not be read and is "
                                "ignored ({error})"),
    "kept_by_another": template("a drawing kept in this browser for “{title}” at {phi} = "
                                "{angle:g}° was made on the page of another exercise with this "
                                "title (another variant, or another version of it) and is not "
                                "shown here; it stays kept for that page"),
    "kept_for_another": template("a drawing kept in this browser for “{title}” at {phi} = "
                                 "{angle:g}° belongs to another exercise (or another version "
                                 "of it) and is ignored; drawing here replaces it"),
    "not_kept": template("this browser does not keep the drawing ({error}); download it "
                         "instead"),
    "sheet_scale": template("pole {pole}, {symbol} = {scale} {unit}; one small square is 1 mm"),
    "plan_point": template("a point of the plan"),
    "construction_point": template("a construction point (checked when placed)"),
    "moved": template("moved since the last check: check again"),
    "zoom": template("{zoom} px/mm"),
}


class _Kept:
    """A field left to fill: formats as itself, ``{name:spec}``."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __format__(self, specification: str) -> str:
        return "{" + self.name + (":" + specification if specification else "") + "}"


class _KeptCount(int):
    """The count of a plural sentence: chooses the form as its value, formats as itself."""

    def __format__(self, specification: str) -> str:
        return "{count" + (":" + specification if specification else "") + "}"


#: the counts whose forms a page receives (a larger count takes the form of 100 + its last
#: two digits: page_words.js)
PLURAL_COUNTS = 200


def template_text(text: Message, language: str | None = None) -> str | dict[str, Any]:
    """A message's template as ``language``'s catalogue translates it, its fields left to
    fill (``{value:.6g}``): what a page fills in. A translation that does not fit the fields
    gives the English template, as :func:`~planmethod.words.render` does. A plural sentence
    gives its forms and which form each count takes (``forms``, ``plural``, ``count``).

    >>> template_text(template("{count} draws rejected at {angle:g}°"))
    '{count} draws rejected at {angle:g}°'
    >>> from planmethod.words import plural
    >>> shown = template_text(plural("{count} variant", "{count} variants", count=0))
    >>> shown["forms"], shown["plural"][:3]
    (['{count} variants', '{count} variant'], [0, 1, 0])
    """
    if any(brace in form for form in text.forms for brace in ("{{", "}}")):
        raise ValueError(f"a page's template has no literal braces: {text.template!r}")
    names = {name.split(".")[0].split("[")[0] for form in text.forms
             for _, name, _, _ in string.Formatter().parse(form) if name}
    kept = text.replace(**{name: _Kept(name) for name in names if name != text.count})
    if text.count is None:
        return render(kept, language)
    forms: list[str] = []
    plural = []
    for count in range(PLURAL_COUNTS):
        form = render(kept.replace(**{text.count: _KeptCount(count)}), language)
        if form not in forms:
            forms.append(form)
        plural.append(forms.index(form))
    return {"forms": forms, "plural": plural, "count": text.count}


@functools.cache
def unprintable_points() -> tuple[int, ...]:
    """The code points Python's ``repr`` writes as an escape (``str.isprintable`` is false),
    as ranges: first, last, first, last…"""
    out: list[int] = []
    start = None
    for point in range(sys.maxunicode + 2):
        printable = point > sys.maxunicode or chr(point).isprintable()
        if not printable and start is None:
            start = point
        elif printable and start is not None:
            out += [start, point - 1]
            start = None
    return tuple(out)


def quoted(text: str, unprintable: Sequence[int]) -> str:
    """``text`` quoted as Python's ``repr`` quotes it, by the data the page has: the
    ``unprintable`` ranges of :func:`unprintable_points` (the test holds it to ``repr``)."""
    import bisect

    starts = unprintable[0::2]

    def printable(point: int) -> bool:
        index = bisect.bisect_right(starts, point) - 1
        return index < 0 or unprintable[2 * index + 1] < point

    quote = '"' if "'" in text and '"' not in text else "'"
    named = {"\t": "\\t", "\n": "\\n", "\r": "\\r"}
    out = []
    for character in text:
        point = ord(character)
        if character in (quote, "\\"):
            out.append("\\" + character)
        elif character in named:
            out.append(named[character])
        elif point < 0x20 or point == 0x7F:
            out.append(f"\\x{point:02x}")
        elif point < 0x7F or printable(point):
            out.append(character)
        else:
            out.append(f"\\x{point:02x}" if point <= 0xFF else
                       f"\\u{point:04x}" if point <= 0xFFFF else f"\\U{point:08x}")
    return quote + "".join(out) + quote


@dataclass(frozen=True)
class PageRules:
    """What a page grades with (see the module): the ``language`` and its ``decimal`` sign,
    the ``number`` grammar, the ``unprintable`` ranges, the ``answers`` verdict classes in
    order, the ``templates`` in the language, and what a sign means where a quantity does
    not say (``senses``)."""

    language: str
    decimal: str
    number: NumberGrammar
    unprintable: tuple[int, ...]
    answers: tuple[AnswerClass, ...]
    templates: Mapping[str, str | dict[str, Any]]
    senses: tuple[str, str]

    def as_dict(self) -> dict[str, Any]:
        """The rules as JSON data, for the page's script."""
        return {"language": self.language, "decimal": self.decimal,
                "number": self.number.as_dict(), "unprintable": list(self.unprintable),
                "answers": [{"name": one.name, "feedback": one.feedback, "hint": one.hint}
                            for one in self.answers],
                "templates": dict(self.templates), "senses": list(self.senses)}


def page_rules(language: str | None = None) -> PageRules:
    """The rulebook of a page in ``language`` (default: the one spoken now).

    Reads grading's current rules: the number grammar, and — until grading's own verdict
    table lands — the templates of :data:`PAGE_TEMPLATES`, which say grade's words."""
    language = language or current()
    return PageRules(
        language=language, decimal=render(DECIMAL_SIGN, language), number=number_grammar(),
        unprintable=unprintable_points(), answers=ANSWER_CLASSES,
        templates={name: template_text(text, language) for name, text in PAGE_TEMPLATES.items()},
        senses=tuple(render(word, language) for word in sense_words("")))


@dataclass(frozen=True)
class PointVerdict:
    """A drawn point's verdict as the page gives it: placed, right (None for a construction
    point not placed), the mistakes named, and the sentence."""

    placed: bool
    ok: bool | None
    mistakes: tuple[str, ...]
    message: Message


def point_verdict(name: str, entry: Sequence[float], drawn: Sequence[float] | None,
                  required: bool, candidates: Sequence[Sequence[Any]],
                  texts: Mapping[str, str]) -> PointVerdict:
    """The verdict the page gives a drawn point (``page_rules.js`` ``pointVerdict``): where
    it belongs (``entry``: x, y, tolerance radius in mm), where it is drawn (None: not
    placed), whether the plan is scored on it, the mistakes' positions of it (``candidates``:
    ``[mistake, x, y]``) and what each mistake tells (``texts``).

    >>> verdict = point_verdict("b", [0, 30, 0.5], [0.1, -29.8], True,
    ...                         [["sense", 0.0, -30.0]], {"sense": "ω₁ was reversed"})
    >>> verdict.ok, verdict.mistakes
    (False, ('sense',))
    >>> render(verdict.message)  # doctest: +NORMALIZE_WHITESPACE
    'b is 59.8 mm off (tolerance 0.50 mm); it lies where the construction puts it when ω₁ was
    reversed'
    """
    from ..grading.plan_points import named_mistakes

    x, y, radius = entry
    if drawn is None:
        return PointVerdict(False, False if required else None, (), PAGE_TEMPLATES[
            "point_missing" if required else "point_missing_helper"].replace(name=name))
    distance = math.hypot(drawn[0] - x, drawn[1] - y)
    if distance <= radius:
        return PointVerdict(True, True, (), PAGE_TEMPLATES["point_right"].replace(
            name=name, distance=distance, radius=radius))
    named = named_mistakes(candidates, drawn[0], drawn[1], radius)
    if not named:
        return PointVerdict(True, False, (), PAGE_TEMPLATES["point_off"].replace(
            name=name, distance=distance, radius=radius))
    return PointVerdict(True, False, tuple(named), PAGE_TEMPLATES["point_off_mistakes"].replace(
        name=name, distance=distance, radius=radius, mistakes=mistakes_message(named, texts)))


def mistakes_message(mistakes: Sequence[str], texts: Mapping[str, str],
                     which: str = "point_mistakes") -> Message:
    """Where a point lies (``point_mistakes``), or the plan's wrong points
    (``plan_mistakes``), that ``mistakes`` put there."""
    joint = render(PAGE_TEMPLATES["mistakes_joint"])
    return PAGE_TEMPLATES[which].replace(mistakes=joint.join(texts[one] for one in mistakes))


def plan_summary(plan: str, right: int, total: int, common: Sequence[str],
                 texts: Mapping[str, str]) -> Message:
    """The plan's summary after a check as the page gives it (``planSummary``): how many of
    its ``total`` points are ``right``, and the mistakes every wrong point is named with
    (``common``: :func:`~planmethod.grading.plan_points.common_mistakes`).

    >>> render(plan_summary("velocity", 2, 3, [], {}))
    '2 of 3 points of the velocity plan right'
    """
    count = PAGE_TEMPLATES[f"plan_right_{plan}"].replace(right=right, total=total)
    if not common:
        return count
    return PAGE_TEMPLATES["plan_summary_mistakes"].replace(
        count=count, mistakes=mistakes_message(common, texts, "plan_mistakes"))
