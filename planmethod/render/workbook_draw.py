"""The workbook's drawing mode: the student draws the plans of the current angle on a
millimetre grid, and the page grades each point (docs/workbook-drawing.md).

This module adds to the page (:func:`planmethod.render.workbook.workbook_html`) its markup
(:func:`drawing_section`), style (:data:`DRAW_STYLE`), script (``workbook_draw.js`` beside this
module) and data (:func:`drawing_data`, :func:`pack_frame`). The data are computed in Python
from each angle's answer key (:func:`planmethod.grading.plan_points.drawing_frame`); the script
only compares a drawn point with them.

The markup is stable (the browser tests and any course tooling rely on it):
``svg[data-draw="velocity"]`` / ``svg[data-draw="acceleration"]`` have the plan's millimetres
as user units with the pole at (0, 0), so a point (x, y) of ``plans.<plan>.points_mm`` of
``planmethod solve --json`` is at user coordinates (x, −y); ``[data-place="<plan>:<point>"]``
chooses the point to place next; ``[data-check="<plan>"]`` grades; each point's verdict is in
``[data-verdict-for="<plan>:<point>"]`` with ``data-ok="true|false"``; ``[data-download=
"<plan>"]`` saves the drawing as the JSON ``planmethod grade --drawing`` reads.

Examples
--------
>>> markup = drawing_section(["velocity", "acceleration"])
>>> 'svg data-draw="velocity"' in markup and 'data-check="acceleration"' in markup
True
>>> pack_frame({"velocity": {"points": {"b": [1.0, 2.0, 0.5]}, "required": ["b"],
...             "mistakes": {"b": [[0, -1.0, -2.0], [3, 900.0, 0.0]]}}},
...            {"velocity": (-20.0, -20.0, 20.0, 20.0)})["velocity"]["mistakes"]
{'b': [[0, -1.0, -2.0]]}
"""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence
from typing import Any

from ..words import Message, message, render, template
from .canvas import empty_svg

__all__ = ["DRAW_STYLE", "draw_mode_html", "draw_script", "drawing_data", "drawing_section",
           "pack_frame"]

#: what each plan is called on the page, and its scale's symbol
PLAN_TITLES = {"velocity": (template("velocity plan"), "μv"),
               "acceleration": (template("acceleration plan"), "μa")}

#: the words of a plan's sheet and tools (as HTML)
_TOOLS = {
    "place": template("place points"),
    "line": template("draw a construction line"),
    "unline": template("remove the last line"),
    "clear": template("clear", context="a drawing"),
    "check": template("check", context="a button"),
    "step": template("show the construction (next step)"),
    "right": template("show the right plan"),
    "download": template("download the drawing"),
}


def _said(text: Message) -> str:
    return html.escape(render(text), quote=False)


def _plan_block(plan: str) -> str:
    """One plan's sheet, its tools and its verdicts' places."""
    name = html.escape(plan)
    title = PLAN_TITLES[plan][0]
    words = {key: _said(text) for key, text in _TOOLS.items()}
    sheet = empty_svg({"data-draw": plan, "tabindex": "0", "role": "img",
                       "aria-label": render(message(
                           "your {plan}: millimetre grid, the pole at the origin",
                           plan=title))})
    return f"""<div class="draw-plan" data-plan="{name}">
<h3>{_said(title)} <span class="draw-scale"></span></h3>
<div class="draw-tools">
<button type="button" data-tool="point" aria-pressed="true">{words["place"]}</button>
<button type="button" data-tool="line" aria-pressed="false">{words["line"]}</button>
<button type="button" data-unline="{name}">{words["unline"]}</button>
<button type="button" data-clear="{name}">{words["clear"]}</button>
</div>
<div class="draw-sheet">{sheet}</div>
<ol class="draw-points"></ol>
<div class="draw-actions">
<button type="button" data-check="{name}">{words["check"]}</button>
<button type="button" data-show-step="{name}">{words["step"]}</button>
<button type="button" data-show-plan="{name}">{words["right"]}</button>
<button type="button" data-download="{name}">{words["download"]}</button>
</div>
<p class="draw-summary"></p>
<p class="draw-step"></p>
</div>"""


def draw_mode_html() -> str:
    """The drawing mode's place in the page's mode bar: a radio button of the ``mode``
    group (``#draw-mode``)."""
    return ('<label class="mode"><input type="radio" name="mode" id="draw-mode" value="draw">'
            f' {_said(template("draw", context="a mode of the page"))}</label>')


def drawing_section(plans: Sequence[str]) -> str:
    """The drawing mode's markup: how to draw, the zoom, and per plan a sheet with its
    tools."""
    how = _said(template("(the plans' drawings and the values read off them are hidden; a "
                         "click or a tap places the chosen\npoint, however near another; a "
                         "press on a placed point's mark, or Alt + a press near it,\ndrags "
                         "it, a finger's point shown magnified above it; on a chosen sheet "
                         "Enter places the chosen\npoint at the sheet's middle, the arrow keys "
                         "move it 0.5 mm, Shift + an arrow key 0.1 mm,\nControl + an arrow "
                         "key 5 mm, + and − zoom; Delete removes it; with the line tool\n"
                         "Enter draws a line through the chosen point, the arrow keys turn it)"))
    zoom_out = html.escape(render(template("zoom out")))
    zoom_in = html.escape(render(template("zoom in")))
    return f"""<section id="drawing" aria-labelledby="drawing-heading">
<h2 id="drawing-heading">{_said(template("Draw the plans"))}</h2>
<p class="draw-how">{how}</p>
<p class="draw-zoom">{_said(template("zoom"))} <button type="button" data-zoom="-1" \
aria-label="{zoom_out}">−</button>
<output id="draw-zoom"></output>
<button type="button" data-zoom="1" aria-label="{zoom_in}">+</button></p>
<p id="draw-kept" role="status"></p>
<p id="draw-status" role="status"></p>
<p id="draw-notice" role="status"></p>
<div class="draw-plans">
{chr(10).join(_plan_block(plan) for plan in plans)}
</div>
<div class="draw-loupe" aria-hidden="true"></div>
</section>"""


def drawing_data(*, title: str, exercise: str, names: Mapping[str, str],
                 runs: Mapping[str, Sequence[tuple[str, str]]] | None = None,
                 poles: Mapping[str, str], extents: Mapping[str, Sequence[float]],
                 mistakes: Sequence[tuple[str, str]], file_format: str,
                 phi: str = "φ₁") -> dict[str, Any]:
    """What the drawing mode needs besides each frame's points: the exercise's ``title`` and
    digest (``exercise``: a kept drawing of another exercise is ignored), each point's
    course name in its sentences (``names``: b₃, n_CB) and typeset on its button and its
    mark (``runs``: [text, kind] as :func:`planmethod.render.labels.label_runs` sets it —
    ``main``, a ``sub`` subscript, an ``upright`` subscript), the poles, one sheet per plan
    for the whole turn (``extents``: left, bottom, right, top in mm, y up), the mistakes
    by index with what the student is told, the ``format`` of a downloaded drawing, and the
    crank angle's symbol (``phi``: φ₁). The sentences the page says of a point are the
    rulebook's (:mod:`planmethod.render.page_rules`).

    >>> data = drawing_data(title="T", exercise="0f", names={"b@lever": "b₃"},
    ...                     poles={"velocity": "p"}, extents={"velocity": (-20, -20, 20, 20)},
    ...                     mistakes=[("sense", "ω1 reversed")],
    ...                     file_format="planmethod-drawing")
    >>> data["scales"], data["extents"]["velocity"]
    ({'velocity': 'μv'}, [-20.0, -20.0, 20.0, 20.0])
    """
    return {"title": title, "exercise": exercise, "names": dict(names),
            "runs": {label: [[text, str(kind)] for text, kind in parts]
                     for label, parts in (runs or {}).items()}, "poles": dict(poles),
            "scales": {plan: PLAN_TITLES[plan][1] for plan in poles},
            "extents": {plan: [float(v) for v in extent] for plan, extent in extents.items()},
            "mistakes": [list(pair) for pair in mistakes], "format": file_format, "phi": phi}


def pack_frame(draw: Mapping[str, Any], extents: Mapping[str, Sequence[float]]
               ) -> dict[str, Any]:
    """One frame's drawing data for the page, without the mistakes' positions that fall off
    the plan's sheet (nobody can click there)."""
    out = {}
    for plan, entry in draw.items():
        left, bottom, right, top = extents[plan]
        mistakes = {}
        for label, candidates in entry["mistakes"].items():
            kept = [candidate for candidate in candidates
                    if left <= candidate[1] <= right and bottom <= candidate[2] <= top]
            if kept:
                mistakes[label] = kept
        out[plan] = {**entry, "mistakes": mistakes}
    return out


def draw_script() -> str:
    """The drawing mode's script (``workbook_draw.js`` beside this module)."""
    from importlib.resources import files

    return files(__package__).joinpath("workbook_draw.js").read_text(encoding="utf-8")


DRAW_STYLE = """
#drawing{margin-top:10px;border-top:1px solid #ccc}
#drawing h2{font-size:1.1em;margin:6px 0}
.draw-plans,.draw-zoom,.draw-how,#draw-status,#draw-kept{display:none}
body.drawing .draw-plans{display:flex;flex-wrap:wrap;gap:16px}
body.drawing :is(.draw-zoom,.draw-how,#draw-status,#draw-kept){display:block}
#draw-status{color:#1a5f2a;font-weight:bold}
#readings tr.concealed.revealed td.reading,
#readings tr.concealed.revealed td.plan-reading{visibility:visible}
body.drawing .panel[data-panel]:not([data-panel="position"]):not(.revealed){display:none}
#readings tr.concealed td.reading,#readings tr.concealed td.plan-reading{visibility:hidden}
#charts .chart.concealed{display:none}
body.drawing:not(.shown-acceleration) #panel-position :is(.rho,.centre,[data-points^="rho_"],
 [data-points^="O_"]){visibility:hidden}
body.drawing #playback :is(label,button,#step-number,#step-text){display:none}
body.drawing .panel.stepwise circle.point{visibility:hidden}
.draw-plan{flex:1 1 560px;min-width:min(320px,100%);max-width:100%}
.draw-plan.absent{display:none}
.draw-plan h3{font-size:1em;margin:4px 0}
.draw-scale{font-weight:normal;color:#444}
.draw-sheet{overflow:auto;max-height:min(720px,70vh);border:1px solid #bbb;margin:4px 0;
 max-width:100%}
.draw-sheet svg{display:block;background:#fff;cursor:crosshair;touch-action:none}
.draw-sheet svg:focus{outline:2px solid #1f5fa8}
:is(.draw-sheet,.draw-loupe) .minor{stroke:#e3e7f0;stroke-width:1px;fill:none}
:is(.draw-sheet,.draw-loupe) .major{stroke:#b8c0d8;stroke-width:1px;fill:none}
:is(.draw-sheet,.draw-loupe) .construction{stroke:#7a7a7a;stroke-width:1px;stroke-dasharray:6 3}
:is(.draw-sheet,.draw-loupe) .pole circle{fill:#000}
:is(.draw-sheet,.draw-loupe) .placed circle{fill:#1f5fa8}
:is(.draw-sheet,.draw-loupe) .placed.selected circle{fill:#d35400}
:is(.draw-sheet,.draw-loupe) .placed.ok circle{fill:#1a7f37}
:is(.draw-sheet,.draw-loupe) .placed.off circle{fill:#c0392b}
:is(.draw-sheet,.draw-loupe) .right-point circle{fill:none;stroke:#2e8b57;stroke-width:1px;
 vector-effect:non-scaling-stroke}
:is(.draw-sheet,.draw-loupe) .right-point text{fill:#2e8b57}
:is(.draw-sheet,.draw-loupe) text{font-family:"DejaVu Serif",Georgia,serif;font-style:italic;
 pointer-events:none;user-select:none}
.draw-points{display:flex;flex-direction:column;gap:2px;padding-left:1.5em;margin:4px 0}
.draw-points button{font-family:"DejaVu Serif",Georgia,serif;font-style:italic;min-width:4em;
 min-height:44px}
.draw-tools,.draw-actions{display:flex;flex-wrap:wrap;gap:4px}
.draw-loupe{display:none;position:fixed;width:120px;height:120px;border-radius:50%;
 border:2px solid #1f5fa8;background:#fff;overflow:hidden;pointer-events:none;z-index:5;
 box-shadow:0 2px 8px rgba(0,0,0,.35)}
.draw-loupe.on{display:block}
.draw-loupe svg{width:100%;height:100%;display:block}
.draw-loupe .cross{stroke:#d35400;vector-effect:non-scaling-stroke;stroke-width:1px}
.draw-points button.placed{background:#e8f0fb}
.course-name sub{font-size:.75em;line-height:0}
.course-name sub.upright{font-style:normal}
.draw-points button.selected{outline:2px solid #d35400}
.draw-verdict[data-ok="true"]{color:#1a7f37}
.draw-verdict[data-ok="false"]{color:#c0392b}
.draw-tools button[aria-pressed="true"]{background:#dde7f5}
#draw-notice{color:#c0392b}
.draw-step{font-style:italic}
"""
