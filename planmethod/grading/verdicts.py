"""The grader's rulebook in words: every verdict class of a graded answer and of a drawn plan
point, each with its message template and the named fields it is filled with.

Grading classifies first — :func:`planmethod.grading.answers.classify` gives a typed
:class:`Verdict` (its class and its fields), :func:`planmethod.grading.drawings.grade_drawing`
the classes below for each point — and renders after: a verdict's sentence is its class's
template with the verdict's fields (:meth:`Verdict.feedback`, :meth:`Verdict.hint`). A page
that grades as ``planmethod grade`` does is given these tables as data (:func:`rulebook`) and
fills the same templates with the same fields.

The tables:

* :data:`FEEDBACK` and :data:`HINTS` — an answer's sentence by its :class:`AnswerVerdict`, at
  the ``full`` level (the right value shown) and the ``hints`` level (never the right value);
* their fields' own sentences: :data:`OFF` (how far off: ``24.1 % low``), :data:`WAYS`
  (which way: ``too high``), :data:`ROUGHLY` (which way and about how far, for a hint:
  ``about 10 % too high``), :data:`SENSES` (what a sign means: ``clockwise``),
  :data:`AMOUNT`, :data:`GIVEN`, :data:`RIGHT` (a number with its unit, the answer as given,
  the right value with its tolerance), :data:`MAGNITUDE` (a negative magnitude's note);
* :data:`POINTS` — a drawn point's sentence by its :class:`PointVerdict`, and
  :data:`POINT_PARTS` — the parts the sentence of a misplaced point is made of (off a
  construction line, on it but off along it — a point of the wrong link, b₃ placed at b —,
  a reading made wrong, where a mistake puts it) and the notes on a whole drawing.

Examples
--------
>>> from planmethod.words import render
>>> verdict = Verdict(AnswerVerdict.CORRECT, (("answer", "v_C = 5.2 m/s"), ("value", 5.27),
...                                           ("tolerance", 0.094)))
>>> render(verdict.feedback())
'v_C = 5.2 m/s: correct (exact 5.27, tolerance ± 0.094)'
>>> render(verdict.hint())
'v_C = 5.2 m/s: correct'
>>> rulebook()["answers"]["correct"]["fields"]
['answer', 'tolerance', 'value']
"""

from __future__ import annotations

import string
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from ..words import Message, template

__all__ = ["AMOUNT", "AMOUNT_BARE", "FEEDBACK", "GIVEN", "HINTS", "MAGNITUDE", "OFF",
           "POINTS", "POINT_PARTS", "RIGHT", "ROUGHLY", "SENSES", "WAYS", "AnswerVerdict", "Off",
           "PointPart", "PointVerdict", "Verdict", "Way", "rulebook", "rulebook_tables"]


class AnswerVerdict(StrEnum):
    """What a graded answer is (the class that chooses its sentence)."""

    NO_ANSWER = "no_answer"
    NOT_A_NUMBER = "not_a_number"
    CORRECT = "correct"
    #: the answer a known mistake gives (told how far off it is)
    MISTAKE = "mistake"
    #: the answer of the reversed sense (a mistake that needs no "how far off")
    SENSE_MISTAKE = "sense_mistake"
    #: a known mistake's answer with the sense reversed too
    MISTAKE_AND_SENSE = "mistake_and_sense"
    #: a negative number for a magnitude
    NEGATIVE_MAGNITUDE = "negative_magnitude"
    #: the sense reversed, the magnitude right
    SENSE_REVERSED = "sense_reversed"
    #: the sense reversed and the magnitude off
    SENSE_AND_SIZE = "sense_and_size"
    WRONG = "wrong"
    #: wrong, the right value being zero (no share of it to tell)
    WRONG_OF_ZERO = "wrong_of_zero"


#: an answer's sentence at the ``full`` level, by its verdict
FEEDBACK: dict[AnswerVerdict, Message] = {
    AnswerVerdict.NO_ANSWER: template("{symbol}: no answer (right: {right})"),
    AnswerVerdict.NOT_A_NUMBER: template("{symbol}: {given!r} is not a number (right: {right})"),
    AnswerVerdict.CORRECT: template("{answer}: correct (exact {value:.6g}, tolerance ± "
                                    "{tolerance:.3g})"),
    AnswerVerdict.MISTAKE: template("{answer}: wrong, {off} — it looks as if {mistake} (that "
                                    "gives {gives:.6g}; right: {right})"),
    AnswerVerdict.SENSE_MISTAKE: template("{answer}: wrong — it looks as if {mistake} (that "
                                          "gives {gives:.6g}; right: {right})"),
    AnswerVerdict.MISTAKE_AND_SENSE: template("{answer}: wrong — it looks as if {mistake}, and "
                                              "the sense is reversed (right: {right})"),
    AnswerVerdict.NEGATIVE_MAGNITUDE: template("{answer}: wrong — {note} (right: {right})"),
    AnswerVerdict.SENSE_REVERSED: template("{answer}: wrong — the sense is reversed (the right "
                                           "answer is {sense}, {right}) and the magnitude "
                                           "{magnitude:.6g} is right"),
    AnswerVerdict.SENSE_AND_SIZE: template("{answer}: wrong — the sense is reversed (the right "
                                           "answer is {sense}, {right}) and the magnitude "
                                           "{magnitude:.6g} is {off}"),
    AnswerVerdict.WRONG: template("{answer}: wrong — {off} (off by {off_by}; right: {right} = "
                                  "± {share:.2g} %)"),
    AnswerVerdict.WRONG_OF_ZERO: template("{answer}: wrong — {off} (off by {off_by}; right: "
                                          "{right})"),
}

#: an answer's sentence at the ``hints`` level (the mistake named and which way the answer
#: is off, never the right value), by its verdict
HINTS: dict[AnswerVerdict, Message] = {
    AnswerVerdict.NO_ANSWER: template("{symbol}: no answer"),
    AnswerVerdict.NOT_A_NUMBER: template("{symbol}: {given!r} is not a number"),
    AnswerVerdict.CORRECT: template("{answer}: correct"),
    AnswerVerdict.MISTAKE: template("{answer}: wrong ({way}) — it looks as if {mistake}"),
    AnswerVerdict.SENSE_MISTAKE: template("{answer}: wrong ({way}) — it looks as if {mistake}"),
    AnswerVerdict.MISTAKE_AND_SENSE: template("{answer}: wrong — it looks as if {mistake}, and "
                                              "the sense is reversed"),
    AnswerVerdict.NEGATIVE_MAGNITUDE: template("{answer}: wrong — {note}"),
    AnswerVerdict.SENSE_REVERSED: template("{answer}: wrong ({way})"),
    AnswerVerdict.SENSE_AND_SIZE: template("{answer}: wrong ({way})"),
    AnswerVerdict.WRONG: template("{answer}: wrong ({way})"),
    AnswerVerdict.WRONG_OF_ZERO: template("{answer}: wrong ({way})"),
}


class Off(StrEnum):
    """How far off a wrong answer is (:data:`OFF`)."""

    #: the right value is zero: by how much
    BY = "by"
    #: ten times or more, a tenth or less
    TIMES = "times"
    HIGH = "high"
    LOW = "low"
    #: of a negative right value
    HIGH_IN_MAGNITUDE = "high_in_magnitude"
    LOW_IN_MAGNITUDE = "low_in_magnitude"


#: how far off a wrong answer is, by :class:`Off`
OFF: dict[Off, Message] = {
    Off.BY: template("{amount:.3g} off"),
    Off.TIMES: template("{ratio:.4g} times the right value"),
    Off.HIGH: template("{percent:.1f} % high"),
    Off.LOW: template("{percent:.1f} % low"),
    Off.HIGH_IN_MAGNITUDE: template("{percent:.1f} % high in magnitude"),
    Off.LOW_IN_MAGNITUDE: template("{percent:.1f} % low in magnitude"),
}


class Way(StrEnum):
    """Which way a wrong answer is off, without the right value (:data:`WAYS`)."""

    SENSE = "sense"
    LARGER = "larger"
    SMALLER = "smaller"
    HIGH = "high"
    LOW = "low"


#: which way a wrong answer is off, by :class:`Way`
WAYS: dict[Way, Message] = {
    Way.SENSE: template("the sense is reversed"),
    Way.LARGER: template("too large in magnitude"),
    Way.SMALLER: template("too small in magnitude"),
    Way.HIGH: template("too high"),
    Way.LOW: template("too low"),
}

#: which way a wrong answer is off and about how far, to one significant digit (never so near
#: that the hint gives the right value away): by the :class:`Way` of a wrong answer of the
#: right sign, and ``times`` for twice the right value or more, a tenth or less
ROUGHLY: dict[str, Message] = {
    Way.HIGH: template("about {percent:g} % too high"),
    Way.LOW: template("about {percent:g} % too low"),
    Way.LARGER: template("about {percent:g} % too large in magnitude"),
    Way.SMALLER: template("about {percent:g} % too small in magnitude"),
    "times": template("about {ratio:g} times what it should be"),
}

#: how the sign of a signed quantity is told, by what the quantity is of (its kind's
#: ``subject``; any other: positive or negative): a link turns counter-clockwise or clockwise;
#: a slide's travel, sliding velocity and acceleration are along or against its guide
SENSES: dict[str, tuple[Message, Message]] = {
    "link": (template("counter-clockwise"), template("clockwise")),
    "pair": (template("positive, along the guide"), template("negative, against the guide")),
    "": (template("positive"), template("negative")),
}

#: a number with its unit (``5.27 m/s``), and one without a unit
AMOUNT = template("{number:.6g} {unit}")
AMOUNT_BARE = template("{number:.6g}")
#: the answer as given: the quantity's symbol and the amount (``v_C = 5.2 m/s``)
GIVEN = template("{symbol} = {amount}")
#: the right value (an amount) with its tolerance
RIGHT = template("{amount} ± {tolerance:.3g}")
#: what a negative answer for a magnitude is told: its symbol and what the task asks
MAGNITUDE = template("{symbol} is the {question}: a magnitude, never negative")


@dataclass(frozen=True, slots=True)
class Verdict:
    """A graded answer's verdict: its class and the fields its sentences are filled with
    (``fields``: ``(name, value)`` pairs; a value is a number, text or a message)."""

    kind: AnswerVerdict
    fields: tuple[tuple[str, Any], ...] = ()

    def feedback(self) -> Message:
        """The sentence at the ``full`` level."""
        return FEEDBACK[self.kind].replace(**dict(self.fields))

    def hint(self) -> Message:
        """The sentence at the ``hints`` level."""
        return HINTS[self.kind].replace(**dict(self.fields))


class PointVerdict(StrEnum):
    """What a graded point of a drawn plan is (:data:`POINTS`)."""

    MISSING = "missing"
    WITHIN = "within"
    #: off its disc, nothing more to tell of where it lies
    OFF = "off"
    #: an intersection off one of its two lines
    OFF_LINE = "off_line"
    #: an intersection off both its lines, or on one and off along it
    OFF_LINES = "off_lines"
    #: the end of a vector laid off: the length and direction it should have
    LAID_OFF = "laid_off"
    #: an image placed by the similarity rule
    SIMILARITY = "similarity"


#: a drawn point's sentence, by :class:`PointVerdict`
POINTS: dict[PointVerdict, Message] = {
    PointVerdict.MISSING: template("{point}: not found on the drawing"),
    PointVerdict.WITHIN: template("{point}: within {radius:.2g} mm ({distance:.2g} mm off)"),
    PointVerdict.OFF: template("{point} is {distance:.1f} mm off (tolerance {radius:.2g} mm)"),
    PointVerdict.OFF_LINE: template("{point} is {distance:.1f} mm off: {line}"),
    PointVerdict.OFF_LINES: template("{point} is {distance:.1f} mm off: {line}; {other}"),
    PointVerdict.LAID_OFF: template("{point} is {distance:.1f} mm off (tolerance {radius:.2g} "
                                    "mm): ({start}{point}) should be {length:.1f} mm at "
                                    "{direction:.0f}°, it is {drawn:.1f} mm"),
    PointVerdict.SIMILARITY: template("{point} is {distance:.1f} mm off (tolerance {radius:.2g} "
                                      "mm) (placed by the similarity rule from {references})"),
}


class PointPart(StrEnum):
    """A part of a misplaced point's sentence, or a note on a whole drawing
    (:data:`POINT_PARTS`)."""

    #: off a construction line of an intersection (``line`` is the line's name, ``through``
    #: the point it is drawn through)
    OFF_THE_LINE = "off_the_line"
    #: on a construction line but off along it: the point of another link (b₃ placed at b
    #: lies on the line v_B₃B along the guide), or a slip along the line
    ON_THE_LINE = "on_the_line"
    #: a quantity read off the point is so many percent high or low
    READ_HIGH = "read_high"
    READ_LOW = "read_low"
    #: the sentence with the readings it makes wrong
    READINGS = "readings"
    #: the sentence with where the known mistakes put the point (:attr:`LIES`)
    MISTAKES = "mistakes"
    #: a point lies where mistakes put it
    LIES = "lies"
    #: where a point lies that mistakes put there (after "it lies", "lies")
    WHERE = "where"
    #: two mistakes' explanations, one or the other
    OR_WHEN = "or_when"
    #: the wrong points of a plan all lie where mistakes put them
    PLAN = "plan"
    #: the drawing's first vector far too long or short: graded as drawn
    SCALE_FAR = "scale_far"
    #: the drawing's first vector off: graded after scaling
    SCALE_FIXED = "scale_fixed"
    #: an element of an SVG drawing that is not read
    IGNORED = "ignored"


#: the parts of a misplaced point's sentence and the notes on a drawing, by :class:`PointPart`
POINT_PARTS: dict[PointPart, Message] = {
    PointPart.OFF_THE_LINE: template("it is {off:.1f} mm off the line {line} through {through}"),
    PointPart.ON_THE_LINE: template("it lies on the line {line} through {through} but "
                                    "{along:.1f} mm off along it"),
    PointPart.READ_HIGH: template("{quantity} read {percent:.0f} % high"),
    PointPart.READ_LOW: template("{quantity} read {percent:.0f} % low"),
    PointPart.READINGS: template("{sentence}: {readings}"),
    PointPart.MISTAKES: template("{sentence}; {lies}"),
    PointPart.LIES: template("it lies {where}"),
    PointPart.WHERE: template("where the construction puts it when {mistakes}"),
    PointPart.OR_WHEN: template("{first}, or when {second}"),
    PointPart.PLAN: template("the wrong points all lie where the construction puts them when "
                             "{mistakes}"),
    PointPart.SCALE_FAR: template("the drawing's scale is off: ({pole}{end}) measures "
                                  "{drawn:.4g} mm instead of {right:.1f} mm, more than "
                                  "{limit:g} times off; it was graded as drawn"),
    PointPart.SCALE_FIXED: template("the drawing's scale is off: ({pole}{end}) measures "
                                    "{drawn:.1f} mm instead of {right:.1f} mm; it was graded "
                                    "after scaling by {factor:.4g}"),
    PointPart.IGNORED: template("<{tag}> ignored"),
}


def _fields(sentence: Message) -> list[str]:
    """The names of the fields a template is filled with, sorted."""
    return sorted({name.split(".")[0].split("[")[0]
                   for form in sentence.forms
                   for _, name, _, _ in string.Formatter().parse(form) if name})


def rulebook_tables() -> dict[str, dict[str, Message]]:
    """The tables by name, each class's sentence a message (:func:`rulebook` describes them):
    what a page is sent, translated into its language.

    >>> from planmethod.words import render
    >>> render(rulebook_tables()["senses"]["link_negative"])
    'clockwise'
    """
    senses = {f"{subject or 'other'}_{sign}": sentence
              for subject, pair in SENSES.items()
              for sign, sentence in zip(("positive", "negative"), pair, strict=True)}
    tables: dict[str, dict[Any, Message]] = {
        "answers": FEEDBACK, "hints": HINTS, "off": OFF, "ways": WAYS, "roughly": ROUGHLY,
        "senses": senses,
        "points": POINTS, "parts": POINT_PARTS,
        "amounts": {"amount": AMOUNT, "bare": AMOUNT_BARE, "given": GIVEN, "right": RIGHT,
                    "magnitude": MAGNITUDE}}
    return {table: {str(name): sentence for name, sentence in sentences.items()}
            for table, sentences in tables.items()}


def rulebook() -> dict[str, dict[str, dict[str, Any]]]:
    """The tables as data for a page that grades as ``planmethod grade`` does: by table
    (``answers``, ``hints``, ``off``, ``ways``, ``roughly``, ``senses``, ``points``,
    ``parts``, and the ``amounts``: ``amount``, ``bare``, ``given``, ``right``,
    ``magnitude``), each class's English template (the catalogue's key of its translations)
    and the names of its fields.

    >>> rulebook()["parts"]["on_the_line"]["fields"]
    ['along', 'line', 'through']
    """
    return {table: {name: {"template": sentence.template, "fields": _fields(sentence)}
                    for name, sentence in sentences.items()}
            for table, sentences in rulebook_tables().items()}
