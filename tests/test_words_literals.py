"""No English sentence a user reads is built outside the message table: a walk of the
package's string literals (issue 36 §3, docs/languages.md).

Every literal that reads as English words (two words of two letters or more, fields left
out) must be one of: a template at a ``message``/``plural``/``template`` call (the catalogue
is read from those calls); a docstring; text a program reads — markup and style sheets, a
regular expression, a keyword argument that names a style, a class or a placement
(``css=``, ``layer=``, matplotlib's ``textcoords=``…), the value of an enumeration (a JSON
report's machine words), a literal compared with or matched against another text; the
words of an error for developers (``ValueError``, ``TypeError``… raised with it), or a
line (or a statement whose first line, or the comment line above it, is) marked
``# words: <why>`` that says why the text is not a message (for example the
catalogue tool, which speaks English because it makes the catalogues). ``planmethod.testing``
is for developers and not walked.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "planmethod"

#: calls whose literal arguments are templates of the message table
TEMPLATE_CALLS = {"message", "plural", "template"}
#: exceptions for developers: their words are not a user's
DEVELOPER_ERRORS = {"ValueError", "TypeError", "KeyError", "AssertionError", "RuntimeError",
                    "NotImplementedError", "IndexError", "AttributeError", "LookupError",
                    "TimeoutError", "ImportError"}
#: keyword arguments whose text names a style, a class, a place or a coordinate system
PROGRAM_KEYWORDS = {"css", "layer", "anchor", "textcoords", "xycoords", "loc", "kind",
                    "class_", "mode", "dtype", "encoding", "errors", "method"}
#: methods whose literal arguments are compared with another text
MATCHING = {"startswith", "endswith", "find", "index", "count", "replace", "split"}
ENUMS = {"Enum", "StrEnum", "IntEnum", "Flag"}

_WORDS = re.compile(r"[a-z]{2,} [a-z]{2,}")
_MARKUP = re.compile(r"<[a-zA-Z/!?]|=\"|[{};]\s*[a-z-]+\s*:|^\s*#!|^\s*#|\\\(|\(\?")


def _reads_as_english(text: str) -> bool:
    without_fields = re.sub(r"\{[^{}]*\}", " ", text)
    return bool(_WORDS.search(without_fields)) and not _MARKUP.search(text)


def _name(node: ast.AST) -> str | None:
    return node.id if isinstance(node, ast.Name) else \
        node.attr if isinstance(node, ast.Attribute) else None


def _exempt(tree: ast.AST, lines: list[str]) -> set[int]:
    """The ids of the literal nodes the rules above let stand."""
    exempt: set[int] = set()

    def cover(node: ast.AST) -> None:
        exempt.update(id(inner) for inner in ast.walk(node))

    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr):
            cover(body[0])                                     # a docstring
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant):
            cover(node)                                        # an attribute's docstring
        if isinstance(node, ast.Call):
            called = _name(node.func)
            if called in TEMPLATE_CALLS or called in DEVELOPER_ERRORS:
                cover(node)
            elif called in MATCHING:
                for argument in node.args:
                    cover(argument)
            for keyword in node.keywords:
                if keyword.arg in PROGRAM_KEYWORDS:
                    cover(keyword.value)
        if isinstance(node, ast.Compare):
            cover(node)
        if isinstance(node, ast.ClassDef) and {_name(base) for base in node.bases} & ENUMS:
            cover(node)
        if isinstance(node, ast.Assign | ast.AnnAssign | ast.Return | ast.Expr) and any(
                "# words:" in lines[number - 1] for number in (node.lineno - 1, node.lineno)
                if number >= 1 and (number == node.lineno
                                    or lines[number - 1].lstrip().startswith("#"))):
            cover(node)                                        # a statement marked whole
        if isinstance(node, ast.Call) and _name(node.func) in ("compile", "search", "match",
                                                                 "fullmatch", "sub"):
            cover(node)                                        # a regular expression
    return exempt


def english_literals(path: Path) -> list[str]:
    """The literals of ``path`` that read as English outside the message table, each as
    ``file:line: text``."""
    source = path.read_text(encoding="utf-8")
    lines = source.splitlines()
    tree = ast.parse(source)
    exempt = _exempt(tree, lines)
    found = []
    for node in ast.walk(tree):
        if id(node) in exempt or not isinstance(node, ast.Constant) \
                or not isinstance(node.value, str) or not _reads_as_english(node.value):
            continue
        marked = any("# words:" in lines[number - 1]
                     for number in range(node.lineno, (node.end_lineno or node.lineno) + 1))
        if not marked:
            found.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno}: "
                         f"{node.value[:70]!r}")
    return found


def test_no_english_sentence_is_built_outside_the_message_table():
    found = [line for path in sorted(PACKAGE.rglob("*.py"))
             if "testing" not in path.relative_to(PACKAGE).parts
             for line in english_literals(path)]
    assert found == [], "\n".join(found)


def test_the_walk_finds_a_sentence_made_as_plain_text(tmp_path):
    """The walk can fail: a sentence in an f-string, or returned as it is, is found; the
    same words as a template, a docstring, a style or a developer's error are not."""
    source = tmp_path / "sample.py"
    source.write_text('"""A module\'s docstring is for developers."""\n'
                      'def said(link):\n'
                      '    """Its docstring."""\n'
                      '    text = f"the link {link} cannot turn"\n'
                      '    plain = "the link cannot turn"\n'
                      '    kept = message("the link {link} cannot turn", link=link)\n'
                      '    figure.text(css="scale bar")\n'
                      '    raise ValueError("the link cannot turn")\n', encoding="utf-8")
    found = english_literals_of(source)
    assert sorted(line.split(": ", 1)[1] for line in found) == [
        "' cannot turn'", "'the link '", "'the link cannot turn'"]


def english_literals_of(path: Path) -> list[str]:
    """:func:`english_literals` of a file outside the package (its path as given)."""
    global PACKAGE
    saved, PACKAGE = PACKAGE, path.parent / "package"
    try:
        return [line.replace(f"{path.parent.name}/", "", 1)
                for line in english_literals(path)]
    finally:
        PACKAGE = saved
