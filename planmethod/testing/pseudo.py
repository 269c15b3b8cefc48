"""Pseudo-translation: a catalogue that marks every message, to prove that no sentence
bypasses the catalogue.

:func:`pseudo_catalogue` writes the catalogue of a made-up language, ``qps``, in which every
template of the package is translated to itself inside ``⟦…⟧`` (fields kept, so the numbers
and names still appear). Text made while ``qps`` is spoken then shows every translated
sentence marked; :func:`unmarked_words` finds the English words left outside the marks — a
sentence built without a template, or shown without rendering. Numbers, symbols and the
names of the exercise's points and links are no words of the messages and are not reported.

Examples
--------
>>> unmarked_words("⟦angle φ₁ of link 2⟧ = 45°; crank angle", {"angle", "crank", "link"})
['crank', 'angle']
>>> texts_of_svg('<svg xmlns="http://www.w3.org/2000/svg"><text>a <tspan>b</tspan></text>'
...              '<title>c</title></svg>')
['a', 'b', 'c']
"""

from __future__ import annotations

import re
import string
from collections.abc import Iterable
from html.parser import HTMLParser
from pathlib import Path

from ..words.catalogue import DOMAIN, package_templates

__all__ = ["PSEUDO", "message_words", "pseudo_catalogue", "texts_of_html", "texts_of_svg",
           "unmarked_words"]

#: the made-up language's code
PSEUDO = "qps"
OPEN, CLOSE = "⟦", "⟧"

_WORD = re.compile(r"[^\W\d_]{3,}")
_MARKED = re.compile(f"{OPEN}[^{OPEN}{CLOSE}]*{CLOSE}")


def pseudo_catalogue(folder: Path) -> Path:
    """Write the ``qps`` catalogue of every template under ``folder`` (for
    ``PLANMETHOD_LOCALE_DIR``); returns the compiled file."""
    from babel.messages import catalog, mofile

    pseudo = catalog.Catalog(locale="en", domain=DOMAIN, charset="utf-8")
    for found in package_templates():
        if not all(found.forms):
            continue
        if len(found.forms) > 1:
            pseudo.add(found.forms, tuple(OPEN + form + CLOSE for form in found.forms),
                       context=found.context)
        elif found.context == "decimal sign":
            pseudo.add(found.template, found.template, context=found.context)
        else:
            pseudo.add(found.template, OPEN + found.template + CLOSE, context=found.context)
    target = folder / PSEUDO / "LC_MESSAGES" / f"{DOMAIN}.mo"
    target.parent.mkdir(parents=True, exist_ok=True)
    with open(target, "wb") as file:
        mofile.write_mo(file, pseudo)
    return target


def message_words() -> set[str]:
    """The English words the templates use (three letters or more, Latin letters only — a
    symbol such as μφv is no word —, in lower case, fields left out): what must never show
    outside a mark."""
    words = set()
    for found in package_templates():
        for form in found.forms:
            literal = "".join(text for text, _, _, _ in string.Formatter().parse(form)
                              if text) if form else ""
            words.update(word.lower() for word in _WORD.findall(literal) if word.isascii())
    return words


def unmarked_words(text: str, words: Iterable[str], names: Iterable[str] = ()) -> list[str]:
    """The words of ``words`` that ``text`` shows outside ``⟦…⟧`` (nested marks included), in
    order; ``names`` (the exercise's points and links, the file's title) are not counted."""
    outside = text
    while True:
        stripped = _MARKED.sub(" ", outside)
        if stripped == outside:
            break
        outside = stripped
    for name in sorted(names, key=len, reverse=True):
        if name:
            outside = outside.replace(name, " ")
    vocabulary = {word.lower() for word in words}
    return [word for word in _WORD.findall(outside) if word.lower() in vocabulary]


def texts_of_svg(svg: str) -> list[str]:
    """The text runs a person sees in an SVG: each ``text``/``tspan`` run, titles and
    descriptions."""
    from defusedxml import ElementTree

    runs = []
    for element in ElementTree.fromstring(svg).iter():
        tag = element.tag.rpartition("}")[2]
        if tag in ("text", "tspan", "title", "desc") and element.text and element.text.strip():
            runs.append(element.text.strip())
        if tag == "tspan" and element.tail and element.tail.strip():
            runs.append(element.tail.strip())
    return runs


#: inputs whose ``value`` a person neither sees nor hears (a radio button's is its label's job)
_UNSEEN = frozenset({"radio", "checkbox", "hidden", "range"})


class _PageText(HTMLParser):
    """Collects the text runs of a page: data outside scripts and styles, and the attributes
    a person sees or hears."""

    def __init__(self) -> None:
        super().__init__()
        self.runs: list[str] = []
        self.hidden = 0

    def handle_starttag(self, tag: str, attributes: list[tuple[str, str | None]]) -> None:
        if tag in ("script", "style"):
            self.hidden += 1
        kind = dict(attributes).get("type") or "text"
        for name, value in attributes:
            if value and (name in ("title", "alt", "placeholder", "aria-label")
                          or (tag == "input" and name == "value" and kind not in _UNSEEN)):
                self.runs.append(value.strip())

    def handle_endtag(self, tag: str) -> None:
        if tag in ("script", "style"):
            self.hidden = max(0, self.hidden - 1)

    def handle_data(self, data: str) -> None:
        if not self.hidden and data.strip():
            self.runs.append(data.strip())


def texts_of_html(html: str) -> list[str]:
    """The text runs a person sees or hears in an HTML page: text outside scripts and styles,
    and the ``title``, ``alt``, ``placeholder``, ``aria-label`` and ``value`` of inputs (not
    of radio buttons, check boxes, ranges and hidden inputs, whose value nobody sees)."""
    reader = _PageText()
    reader.feed(html)
    return reader.runs
