"""The interactive workbook: one self-contained HTML page for a whole turn of the crank.

The page is built from plain data that the command layer computed (see
:func:`workbook_html`): for every frame (crank angle) the drawings as SVG text, drawn by the
project's own renderer, the readings of the report's ``checks``, the construction steps of
the velocity and acceleration plans, and the grading questions (value, tolerance, mistakes)
of the answer key at that angle. The page's script only shows the frame asked for; it never
computes mechanics. Grading in practice mode repeats ``grade_question``'s rules
(:mod:`planmethod.grading.answers`) on the precomputed questions.

The script is ``workbook.js`` beside this module.

Size: every distinct line of SVG (one element a line) is stored once in a string table and
the frames list the lines they are made of; the table is then compressed (gzip, base64) and
unpacked by the browser's own ``DecompressionStream``. Nothing is fetched: no script, style,
font or image comes from any address, and the page works from ``file://``.

Examples
--------
>>> table = StringTable()
>>> table.lines("<svg>\\n<line />\\n</svg>"), table.lines("<svg>\\n<circle />\\n</svg>")
([0, 1, 2], [0, 3, 2])
>>> page = workbook_html("Demo", [0.0, 90.0], ["position"], [
...     {"drawings": {"position": "<svg><title>0</title></svg>"}, "readings": [[1.0, None]],
...      "steps": {}, "questions": []},
...     {"drawings": {"position": "<svg><title>90</title></svg>"}, "readings": [[2.0, 2.1]],
...      "steps": {}, "questions": []}],
...     [{"name": "v_C", "symbol": "v", "subscript": "C", "unit": "m/s"}])
>>> 'id="angle"' in page and "http" not in page
True
"""

from __future__ import annotations

import base64
import functools
import gzip
import html
import json
import math
import re
from collections.abc import Mapping, Sequence
from typing import Any

from ..vocabulary import shown_title
from .canvas import Canvas, formula_runs
from .style import INK, SMALL_SIZE, TEXT_SIZE, num

__all__ = ["StringTable", "curve_chart", "formula_html", "inline_svg", "workbook_html"]

#: a drawing's viewBox (its four numbers)
_VIEW_BOX = re.compile(r'viewBox="([^"]+)"')

#: the XML declaration and namespace declarations, not needed inside an HTML page
_XML_HEAD = re.compile(r'<\?xml[^>]*\?>\s*')
_NAMESPACES = re.compile(r'\s+xmlns(:\w+)?="[^"]*"')
#: an svg element's start tag, where namespaces are declared
_SVG_TAG = re.compile(r"<svg\b[^>]*>")

#: chart size (px) and the colours of its curves
CHART_WIDTH, CHART_HEIGHT = 420.0, 180.0
CURVE_COLORS = ("#1f5fa8", "#c0392b", "#2e8b57", "#8e44ad", "#d35400", "#16a085", "#7f8c8d",
                "#b7950b", "#34495e", "#e84393")


class StringTable:
    """Distinct strings stored once: :meth:`lines` splits an SVG into its lines and returns
    their numbers in the table."""

    def __init__(self) -> None:
        self.strings: list[str] = []
        self.index: dict[str, int] = {}

    def add(self, text: str) -> int:
        number = self.index.get(text)
        if number is None:
            number = self.index[text] = len(self.strings)
            self.strings.append(text)
        return number

    def lines(self, svg: str) -> list[int]:
        return [self.add(line) for line in svg.strip().split("\n")]


def inline_svg(svg: str) -> str:
    """SVG text ready to sit inside HTML: no XML declaration and no namespace declarations
    (an HTML parser puts ``<svg>`` in the SVG namespace by itself).

    >>> inline_svg('<?xml version="1.0"?>\\n<svg xmlns="http://www.w3.org/2000/svg" />')
    '<svg />'
    """
    # the declarations sit in svg start tags: only those are searched, not a whole drawing
    return _SVG_TAG.sub(lambda tag: _NAMESPACES.sub("", tag.group()),
                        _XML_HEAD.sub("", svg, count=1)).strip()


def curve_chart(angles: Sequence[float], curves: Mapping[str, Sequence[float | None]], *,
                title: str, unit: str) -> tuple[str, tuple[float, float]]:
    """A full-turn chart: one polyline per curve against the crank angle, with a cursor line
    (``class="cursor"``) that the page moves to the current angle.

    Returns the SVG text and the page x (px) of the first and the last angle.

    >>> svg, (x0, x1) = curve_chart([0, 180, 360], {"v_C": [0, 1, 0]}, title="v", unit="m/s")
    >>> 'class="cursor"' in svg, x0 < x1
    (True, True)
    """
    figure = Canvas()
    finite = [float(v) for values in curves.values() for v in values
              if v is not None and math.isfinite(v)]
    low, high = (min(finite), max(finite)) if finite else (0.0, 1.0)
    if high - low < 1e-12 * max(1.0, abs(high)):
        low, high = low - 1.0, high + 1.0
    a0, a1 = float(angles[0]), float(angles[-1])
    span = (a1 - a0) or 1.0
    left, right, top, bottom = 0.0, CHART_WIDTH, 0.0, CHART_HEIGHT

    def page(angle: float, value: float) -> tuple[float, float]:
        return (left + (angle - a0) / span * (right - left),
                bottom - (value - low) / (high - low) * (bottom - top))

    figure.line((left, bottom), (right, bottom), color=INK, width=0.8, layer="marks",
                obstacle=False)
    figure.line((left, top), (left, bottom), color=INK, width=0.8, layer="marks",
                obstacle=False)
    if low < 0 < high:
        figure.line(page(a0, 0.0), page(a1, 0.0), color="#999999", width=0.6,
                    dash="3,3", layer="marks", obstacle=False)
    for angle in (a0, a1):
        figure.text((page(angle, low)[0], bottom + 14), f"{angle:g}°", size=SMALL_SIZE,
                    anchor="middle", css="axis", area=False)
    figure.text((left - 4, top + 4), f"{high:.4g}", size=SMALL_SIZE, anchor="end",
                css="axis", area=False)
    figure.text((left - 4, bottom), f"{low:.4g}", size=SMALL_SIZE, anchor="end",
                css="axis", area=False)
    figure.text((left, top - 10), f"{title}, {unit}", size=TEXT_SIZE, bold=True, css="title",
                area=False)
    legend_x = right + 12
    for number, (name, values) in enumerate(curves.items()):
        color = CURVE_COLORS[number % len(CURVE_COLORS)]
        run: list[tuple[float, float]] = []
        runs = [run]
        for angle, value in zip(angles, values, strict=True):
            if value is None or not math.isfinite(value):
                run = []
                runs.append(run)
                continue
            run.append(page(float(angle), float(value)))
        for points in runs:
            if len(points) >= 2:
                figure.polyline(points, color=color, width=1.4, obstacle=False,
                                css="curve")
        y = top + 4 + 16 * number
        figure.line((legend_x, y - 4), (legend_x + 18, y - 4), color=color, width=2.0,
                    layer="marks", obstacle=False)
        figure.text((legend_x + 24, y), name, size=SMALL_SIZE, css="legend", area=False,
                    formula=True)
    figure.line((left, top), (left, bottom), color="#d00000", width=1.2, layer="marks",
                obstacle=False, css="cursor")
    return figure.svg(f"{title} over a full turn").svg, (left, right)


@functools.lru_cache(maxsize=4096)
def formula_html(text: str) -> str:
    """A vector equation as HTML, what follows an underscore set as a subscript as the
    figures set it (:func:`planmethod.render.canvas.formula_runs`).

    >>> formula_html("v_C = v_B + v_CB")
    'v<sub>C</sub> = v<sub>B</sub> + v<sub>CB</sub>'
    """
    return "".join(f"<sub>{html.escape(part)}</sub>" if small else html.escape(part)
                   for part, small in formula_runs(text))


def _quantity_label(entry: Mapping[str, str]) -> str:
    return (f"{html.escape(entry['symbol'])}<sub>{html.escape(entry['subscript'])}</sub>")


def _panel_size(name: str, frames: Sequence[Mapping[str, Any]]) -> str:
    """A panel's size on the page: never larger than its drawing's own size (one CSS px per
    px of the drawing, its text — legends and scales at 12.5 px, the smallest at 11 px — at
    the size it was set), no wider than the page, the height following the drawing's aspect
    ratio, so that no band of the panel is empty; *two drawings to a row* halves the width.
    A drawing keeps one viewBox over the turn (render/steady.py): the first frame's is every
    frame's."""
    for frame in frames:
        found = _VIEW_BOX.search(frame["drawings"].get(name, ""))
        if found:
            width, height = (float(value) for value in found.group(1).split()[2:4])
            return (f' style="max-width:min({num(width)}px, 100% - 2px);'
                    f'aspect-ratio:{num(width)} / {num(height)}"')
    return ""


def _plan_attribute(plan: str | None, name: str = "data-plan") -> str:
    return f' {name}="{html.escape(plan)}"' if plan else ""


def _pack(data: Any) -> str:
    text = json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    # level 6: 4 % larger than 9 on a page's frames, at less than half the time
    return base64.b64encode(gzip.compress(text.encode("utf-8"), compresslevel=6,
                                          mtime=0)).decode("ascii")


def workbook_html(title: str, angles: Sequence[float], panels: Sequence[str],
                  frames: Sequence[Mapping[str, Any]], quantities: Sequence[Mapping[str, str]],
                  *, charts: Sequence[tuple[str, tuple[float, float]]] = (),
                  chart_plans: Sequence[Sequence[str]] = (), notes: Sequence[str] = (),
                  start: float | None = None, phi: str = "φ₁",
                  drawing: Mapping[str, Any] | None = None, sense: int = 1) -> str:
    """The workbook page as HTML text.

    Parameters
    ----------
    title
        The exercise's title.
    angles
        The crank angle of every frame (deg), evenly spaced.
    panels
        The drawings shown side by side, by name (``position``, ``velocity`` …).
    frames
        One mapping per angle: ``drawings`` {panel: SVG text}, ``readings`` [[exact, plan
        or None], …] in the order of ``quantities``, ``steps`` {plan: [[number, sentence,
        action, [the plan points it names]], …]}, ``equations`` {plan: [vector equation, …]}
        (sentences and equations in plain text; the page sets their subscripts) and
        ``questions`` (the answer key's questions at that angle: ``id``, ``value``,
        ``tolerance``, ``unit``, ``signed``, ``mistakes``).
    quantities
        The report's check quantities: ``name``, ``symbol``, ``subscript``, ``unit``, and
        the ``plan`` it is read off (the drawing mode hides the value until the student
        asks to see that plan; None: never hidden).
    charts
        Full-turn charts from :func:`curve_chart`.
    chart_plans
        For each chart, the plans its curves are read off (hidden alike).
    notes
        Lines shown under the title (drafting precision, where the tolerances come from).
    start
        The crank angle the page opens at (the exercise's own; the frame nearest it), else
        the first.
    phi
        The crank angle's symbol as the course writes it (φ₁).
    drawing
        The drawing mode's data (:func:`planmethod.render.workbook_draw.drawing_data`); each
        frame then holds its ``draw`` data too. None: no drawing mode.
    sense
        +1 if the crank turns counter-clockwise (ω₁ ≥ 0), −1 if clockwise: *play* turns it
        that way.
    """
    table = StringTable()
    packed_frames = []
    for frame in frames:
        drawings = [table.lines(inline_svg(frame["drawings"][name])) if name in
                    frame["drawings"] else [] for name in panels]
        steps = {plan: [[number, table.add(formula_html(text)), action, *rest]
                        for number, text, action, *rest in listed]
                 for plan, listed in frame.get("steps", {}).items()}
        equations = {plan: [table.add(formula_html(text)) for text in listed]
                     for plan, listed in frame.get("equations", {}).items()}
        packed_frames.append({"drawings": drawings, "readings": frame["readings"],
                              "steps": steps, "equations": equations,
                              "questions": frame.get("questions", [])})
    draw_html, draw_extra = "", ""
    if drawing is not None:
        from .workbook_draw import DRAW_STYLE, draw_script, drawing_section, pack_frame

        for packed, frame in zip(packed_frames, frames, strict=True):
            packed["draw"] = pack_frame(frame.get("draw", {}), drawing["extents"])
        draw_html = drawing_section(list(drawing["extents"]))
        draw_extra = f"<script>{draw_script()}</script>\n<style>{DRAW_STYLE}</style>"
    data = {"angles": [float(a) for a in angles], "panels": list(panels),
            "strings": table.strings, "frames": packed_frames,
            "quantities": [dict(q) for q in quantities],
            "charts": [list(span) for _, span in charts], "sense": -1 if sense < 0 else 1}
    if drawing is not None:
        data["draw"] = dict(drawing)
    rows = "\n".join(
        f'<tr{_plan_attribute(q.get("plan"))}><th scope="row">{_quantity_label(q)}</th>'
        f'<td class="reading" data-quantity="{html.escape(q["name"])}" data-value=""></td>'
        f'<td class="plan-reading"></td><td class="unit">{html.escape(q["unit"])}</td>'
        f'<td class="practice"><input class="answer" data-answer="{html.escape(q["name"])}"'
        f' size="10" aria-label="{html.escape(q["name"])}"></td>'
        f'<td class="tolerance" data-tolerance-for="{html.escape(q["name"])}"></td>'
        f'<td class="verdict" data-verdict-for="{html.escape(q["name"])}"></td></tr>'
        for q in quantities)
    panel_html = "\n".join(f'<figure class="panel" id="panel-{html.escape(name)}" '
                           f'data-panel="{html.escape(name)}"{_panel_size(name, frames)}>'
                           '</figure>' for name in panels)
    chart_html = "\n".join(
        f'<div class="chart" data-chart="{number}"'
        f'{_plan_attribute(" ".join(plans), "data-plans") if plans else ""}>'
        f'{inline_svg(svg)}</div>'
        for number, ((svg, _), plans) in enumerate(
            zip(charts, list(chart_plans) or [()] * len(charts), strict=True)))
    step_count = len(angles)
    low, high = angles[0], angles[-1]
    step = (angles[1] - angles[0]) if step_count > 1 else 1.0
    first = low if start is None else min(angles, key=lambda angle: (
        abs((angle - start + 180.0) % 360.0 - 180.0), angle))
    note_html = "".join(f"<p class=\"note\">{html.escape(line)}</p>" for line in notes)
    return _PAGE.format(
        title=html.escape(shown_title(title)), notes=note_html, low=num(low), high=num(high),
        first=num(first), phi=html.escape(phi),
        step=num(step), panels=panel_html, charts=chart_html, rows=rows,
        data=_pack(data), style=_STYLE, script=_script(), drawing=draw_html,
        drawing_script=draw_extra)


_STYLE = """
body{font-family:"DejaVu Sans",Verdana,Arial,sans-serif;margin:12px;color:#111}
h1{font-size:1.25em;margin:0 0 4px}
.note{margin:2px 0;color:#444;font-size:.9em}
#controls{position:sticky;top:0;background:#fff;padding:6px 0;z-index:2;
 border-bottom:1px solid #ccc;display:flex;gap:12px;align-items:center;flex-wrap:wrap}
#angle{width:360px}
#panels{display:flex;flex-wrap:wrap;gap:8px;margin-top:8px;align-items:flex-start}
.panel{margin:0;border:1px solid #ddd;width:calc(50% - 8px);min-width:320px;height:430px;
 max-width:calc(100% - 2px)}
.panel[style]{height:auto;width:100%;min-height:0;overflow:hidden}
body.compact .panel{width:calc(50% - 8px)}
.panel svg{display:block;width:100%;height:100%}
#charts{display:flex;flex-wrap:wrap;gap:12px;margin-top:8px}
.chart svg{width:520px;height:240px}
table{border-collapse:collapse;margin-top:8px}
td,th{padding:2px 8px;border-bottom:1px solid #eee;text-align:right}
th{font-weight:normal;font-style:italic;font-family:"DejaVu Serif",Georgia,serif}
.practice,.tolerance,.verdict{display:none}
body.practising .practice,body.practising .tolerance,body.practising .verdict{display:table-cell}
body.practising .reading,body.practising .plan-reading{visibility:hidden}
.verdict{text-align:left;max-width:40em}
.verdict.correct{color:#1a7f37}.verdict.wrong{color:#c0392b}
#playback{margin-top:8px}
#step-text{font-style:italic;min-height:1.3em}
.step-hidden{display:none}
.step-current line,.step-current polygon,line.step-current{stroke:#d00000!important;
 fill:#d00000}
#status{color:#c0392b}
"""

_PAGE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title} — workbook</title>
<style>{style}</style>
</head>
<body>
<h1>{title}</h1>
{notes}
<div id="controls">
<label for="angle">crank angle {phi}</label>
<input type="range" id="angle" min="{low}" max="{high}" step="{step}" value="{first}">
<output id="angle-value">{first}°</output>
<button type="button" id="play">play</button>
<label><input type="checkbox" id="practice"> practice</label>
<label><input type="checkbox" id="compact"> two drawings to a row</label>
<span>frame switch: <output id="switch-time">—</output></span>
<span id="status">loading…</span>
</div>
<div id="panels">
{panels}
</div>
{drawing}
<section id="playback">
<label>construction of the
<select id="step-plan"><option value="velocity">velocity plan</option>
<option value="acceleration">acceleration plan</option></select></label>
<button type="button" id="step-first">first</button>
<button type="button" id="step-prev">◀ step</button>
<button type="button" id="step-next">step ▶</button>
<button type="button" id="step-all">all</button>
<output id="step-number"></output>
<p id="step-text"></p>
<p id="equations"></p>
</section>
<section>
<table id="readings">
<thead><tr><th></th><td>exact</td><td>read off the plan</td><td>unit</td>
<td class="practice">your answer</td><td class="tolerance">tolerance</td>
<td class="verdict"><button type="button" id="check">check</button></td></tr></thead>
<tbody>
{rows}
</tbody>
</table>
</section>
<div id="charts">
{charts}
</div>
<script type="application/octet-stream" id="workbook-data">{data}</script>
{drawing_script}
<script>{script}</script>
</body>
</html>
"""

def _script() -> str:
    """The page's script (``workbook.js`` beside this module)."""
    from importlib.resources import files

    return files(__package__).joinpath("workbook.js").read_text(encoding="utf-8")
