"""Each thing written once, read from the source: every SVG element is written by the canvas
(``planmethod/render/canvas.py``), every drawing scale's header and every plot panel's title
comes from ``planmethod/vocabulary.py``, and no module of the renderer writes its own planar
vector helper."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "planmethod"
CANVAS = PACKAGE / "render" / "canvas.py"

#: the elements an SVG drawing is made of
SVG_TAGS = ("svg", "g", "path", "line", "polyline", "polygon", "circle", "ellipse", "rect",
            "text", "tspan", "defs", "clipPath", "pattern", "marker", "use")
#: markup of one of them inside a string: ``<line``, ``</g>`` (``<text>`` is left to the
#: element checks: Moodle's quiz XML has a ``<text>`` of its own)
MARKUP = re.compile(r"</?(?:" + "|".join(tag for tag in SVG_TAGS if tag != "text") + r")\b")


def _not_written(tree: ast.AST) -> set[int]:
    """The ids of the string constants that write nothing: docstrings (their doctests may
    show SVG), what a comparison reads (``"<svg" in text``), an error's message and the
    pattern a regular expression is compiled from (``re.compile(r"<svg\\b[^>]*>")``: it
    reads SVG)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value,
                                                                     ast.Constant):
                found.add(id(body[0].value))
        elif isinstance(node, ast.Compare | ast.Raise):
            found.update(id(inner) for inner in ast.walk(node))
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "compile" and isinstance(node.func.value, ast.Name)
              and node.func.value.id == "re" and node.args):
            found.update(id(inner) for inner in ast.walk(node.args[0]))
    return found


def svg_written_outside_the_canvas(source: str, name: str = "<source>") -> list[str]:
    """Where ``source`` writes an SVG element itself: markup in a string (not a docstring), an
    element tuple ``("line", {…}, …)`` or a raw ``.add(layer, "line", …)`` /
    ``.define("pattern", …)`` call of the canvas."""
    tree = ast.parse(source)
    skip = _not_written(tree)
    found = []
    for node in ast.walk(tree):
        line = getattr(node, "lineno", 0)
        if isinstance(node, ast.Constant) and isinstance(node.value, str) \
                and id(node) not in skip and MARKUP.search(node.value):
            found.append(f"{name}:{line}: SVG markup in a string")
        elif isinstance(node, ast.JoinedStr) and id(node) not in skip and any(
                isinstance(part, ast.Constant) and MARKUP.search(str(part.value))
                for part in node.values):
            found.append(f"{name}:{line}: SVG markup in an f-string")
        elif isinstance(node, ast.Tuple) and len(node.elts) >= 2 \
                and isinstance(node.elts[0], ast.Constant) and node.elts[0].value in SVG_TAGS \
                and isinstance(node.elts[1], ast.Dict):
            found.append(f"{name}:{line}: an element tuple ({node.elts[0].value!r}, {{…}})")
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in ("add", "define") and any(
                    isinstance(arg, ast.Constant) and arg.value in SVG_TAGS
                    for arg in node.args[:2]):
            found.append(f"{name}:{line}: a raw .{node.func.attr}() of an SVG element")
    return found


def test_no_svg_element_is_written_outside_the_canvas():
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path != CANVAS:
            found += svg_written_outside_the_canvas(path.read_text(encoding="utf-8"),
                                                    str(path.relative_to(ROOT)))
    assert not found, "\n".join(found)


@pytest.mark.parametrize("source", [
    'svg = f"<svg width=\'{w}\'>"',
    'parts.append("</g>")',
    'item = ("rect", {"x": "0"}, [])',
    'figure.add("marks", "polygon", {"points": []})',
    'canvas.define("pattern", {"id": "grid"})',
])
def test_the_writer_check_finds_svg_written_by_hand(source):
    assert svg_written_outside_the_canvas(source)


def test_the_writer_check_passes_docstrings_reads_messages_and_html():
    source = ('def f(text):\n    """>>> f("<svg><line /></svg>")"""\n'
              '    if "<svg" not in text:\n'
              '        raise ValueError(f"not <svg>: {text}")\n'
              '    return "<p>text</p><title>page</title>" + "<table>"\n'
              'TAG = re.compile(r"<svg\\b[^>]*>")\n')
    assert not svg_written_outside_the_canvas(source)
    # a pattern is read only where it is compiled: the same string written is markup
    assert svg_written_outside_the_canvas('TAG = "<svg>"\n')


#: a drawing scale's header written by hand: ``μv = {…} (m/s)/mm``
SCALE_HEADER = re.compile(r"(?<![/\w])μ[lvaF] = \{")


def test_scale_headers_and_panels_come_from_the_vocabulary():
    found = []
    for path in [*sorted((PACKAGE / "render").glob("*.py")), PACKAGE / "grading" / "sheets.py"]:
        text = path.read_text(encoding="utf-8")
        for number, line in enumerate(text.splitlines(), start=1):
            if SCALE_HEADER.search(line):
                found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert not found, "\n".join(found)

    from planmethod.render.plots import panels
    from planmethod.vocabulary import QUANTITY_KINDS
    from planmethod.words import render

    table = {"angle": [0.0], **{f"{prefix}_X": [1.0] for prefix in QUANTITY_KINDS}}
    titles = {render(title) for title, _, _ in panels(table)}
    assert titles == {render(kind.panel) for kind in QUANTITY_KINDS.values() if kind.panel} | {
        "other columns"}


#: a function or lambda of planar vector arithmetic, by its name
VECTOR_HELPER = re.compile(r"^(cross|dot|perp|norm|unit|unit_vector|vector_length|difference|"
                           r"translate|rotate|hypot|length)$")


def test_the_renderer_writes_no_vector_helper_of_its_own():
    found = []
    for path in sorted((PACKAGE / "render").glob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef) and VECTOR_HELPER.match(node.name):
                found.append(f"{path.relative_to(ROOT)}:{node.lineno}: def {node.name}")
    assert not found, "\n".join(found)
