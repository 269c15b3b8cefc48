"""The rulebook a page receives: ``planmethod grade``'s rules as data, in the page's language.

The workbook page grades a typed answer and a drawn plan point in the browser. It does so
with the rules of :mod:`planmethod.grading` — never with rules of its own — sent to it as data
(:func:`page_rules`, :meth:`PageRules.as_dict`) that its script (``page_rules.js`` beside this
module, with ``page_words.js``) applies:

* the grammar of a typed number (:func:`planmethod.grading.reading.number_grammar`: the one
  :func:`~planmethod.grading.reading.read_number` of ``grade`` reads too);
* how a text that is no number is quoted back (Python's ``repr``: the unprintable code points,
  :func:`unprintable_points`);
* grading's verdict table (:func:`planmethod.grading.verdicts.rulebook_tables`: every class of
  an answer and of a drawn point, with its sentence), one template per class, by the ids
  ``<table>.<class>`` (``answers.correct``, ``parts.on_the_line``) — the page's script
  classifies as :func:`~planmethod.grading.answers.classify` and
  :func:`~planmethod.grading.drawings.grade_drawing` do and fills the class's template with
  the same fields;
* the page's own words (:data:`PAGE_WORDS`: a point not yet placed, a plan's count of right
  points, the controls), every template already translated into the page's language by the
  catalogue, fields kept (:func:`template_text`), and the language's decimal sign.

The page's sentences are ``grade``'s and ``grade --drawing``'s to the byte: tests/page_golden.py
writes what they say of many cases and the page's script is held to it, under Node and in
Chromium (tests/test_page_rules.py, tests/test_browser.py).

Examples
--------
>>> rules = page_rules("en")
>>> rules.templates["answers.correct"]
'{answer}: correct (exact {value:.6g}, tolerance ± {tolerance:.3g})'
>>> rules.templates["amounts.right"], rules.decimal
('{amount} ± {tolerance:.3g}', '.')
>>> quoted("it's", unprintable_points()), quoted("a\\x00", unprintable_points())
('"it\\'s"', "'a\\\\x00'")
"""

from __future__ import annotations

import functools
import string
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..grading.plan_points import plan_sentence
from ..grading.reading import NumberGrammar, number_grammar
from ..grading.verdicts import rulebook_tables
from ..words import Message, current, render, template
from ..words.render import DECIMAL_SIGN
from .canvas import formula_grammar

__all__ = ["PAGE_WORDS", "PageRules", "page_rules", "plan_summary", "quoted", "rule_templates",
           "template_text", "unprintable_points"]


#: the page's own words, by id (grade's sentences are the rulebook's: :func:`rule_templates`)
PAGE_WORDS: dict[str, Message] = {
    # a drawn point not placed that grade leaves out, and a plan's count after a check
    "point_missing_helper": template("{point}: not placed (a construction point: checked "
                                     "when placed)"),
    "plan_right_velocity": template("{right} of {total} points of the velocity plan right"),
    "plan_right_acceleration": template("{right} of {total} points of the acceleration plan "
                                        "right"),
    "plan_summary_mistakes": template("{count}; {mistakes}"),
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
    "kept_restored": template("your drawing at {phi} = {angle:g}° is back as this browser kept "
                              "it"),
    "next_acceleration": template("the velocity plan is right: now draw the acceleration "
                                  "plan"),
    "plans_right": template("every plan at {phi} = {angle:g}° is right: choose another angle "
                            "to draw"),
}


class _Kept:
    """A field left to fill: formats as itself, ``{name:spec}``."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __format__(self, specification: str) -> str:
        return "{" + self.name + (":" + specification if specification else "") + "}"

    def __repr__(self) -> str:   # a field quoted as Python quotes it: {given!r}
        return "{" + self.name + "!r}"


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
    the ``number`` grammar, the ``unprintable`` ranges and the ``templates`` in the language
    (grading's rulebook by ``<table>.<class>``, and the page's own words); the page sets a
    sentence's symbols (v_C, n_CB) with real subscripts by the figures' ``formula`` grammar
    (:func:`~planmethod.render.canvas.formula_grammar`)."""

    language: str
    decimal: str
    number: NumberGrammar
    unprintable: tuple[int, ...]
    templates: Mapping[str, str | dict[str, Any]]

    def as_dict(self) -> dict[str, Any]:
        """The rules as JSON data, for the page's script."""
        return {"language": self.language, "decimal": self.decimal,
                "number": self.number.as_dict(), "unprintable": list(self.unprintable),
                "templates": dict(self.templates), "formula": formula_grammar()}


def rule_templates() -> dict[str, Message]:
    """Grading's rulebook (:func:`~planmethod.grading.verdicts.rulebook_tables`) as one table
    of templates by ``<table>.<class>``: what the page fills as ``grade`` does.

    >>> render(rule_templates()["parts.on_the_line"].replace(line="v_B₃B ∥ guide",
    ...                                                      through="b", along=6.93))
    'it lies on the line v_B₃B ∥ guide through b but 6.9 mm off along it'
    """
    return {f"{table}.{name}": sentence for table, sentences in rulebook_tables().items()
            for name, sentence in sentences.items()}


def page_rules(language: str | None = None) -> PageRules:
    """The rulebook of a page in ``language`` (default: the one spoken now): grading's number
    grammar and verdict table, and the page's own words."""
    language = language or current()
    templates = {**PAGE_WORDS, **rule_templates()}
    return PageRules(
        language=language, decimal=render(DECIMAL_SIGN, language), number=number_grammar(),
        unprintable=unprintable_points(),
        templates={name: template_text(text, language) for name, text in templates.items()})


def plan_summary(plan: str, right: int, total: int, common: Sequence[str]) -> Message:
    """The plan's summary after a check as the page gives it (``planSummary``): how many of
    its ``total`` points are ``right``, and — as ``grade --drawing`` notes it — the mistakes
    every wrong point is named with (``common``:
    :func:`~planmethod.grading.plan_points.common_mistakes`).

    >>> render(plan_summary("velocity", 2, 3, []))
    '2 of 3 points of the velocity plan right'
    >>> render(plan_summary("acceleration", 0, 3, ["no_coriolis"]))[:46]
    '0 of 3 points of the acceleration plan right; '
    """
    count = PAGE_WORDS[f"plan_right_{plan}"].replace(right=right, total=total)
    if not common:
        return count
    return PAGE_WORDS["plan_summary_mistakes"].replace(count=count,
                                                      mistakes=plan_sentence(common))
