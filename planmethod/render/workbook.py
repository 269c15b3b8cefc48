"""The interactive workbook: one self-contained HTML page for a whole turn of the crank.

The page is built from plain data that the command layer computed (a :class:`WorkbookPage`,
see :func:`workbook_html`): for every frame (crank angle) the drawings as SVG text, drawn by
the project's own renderer, the readings of the report's ``checks``, the construction steps of
the velocity and acceleration plans, and the grading questions (value, tolerance, mistakes)
of the answer key at that angle. The page's script only shows the frame asked for; it never
computes mechanics. Practice and drawing modes grade by ``planmethod grade``'s rules, which
the page receives as data with every template it fills, in the page's language
(:mod:`planmethod.render.page_rules`): the scripts classify, they write no sentence.

The scripts are beside this module: ``page_words.js`` (templates and numbers),
``page_rules.js`` (the rulebook), ``workbook.js`` (the page) and ``workbook_draw.js`` (the
drawing mode: :mod:`planmethod.render.workbook_draw`).

Size: every distinct line of SVG (one element a line) is stored once in a string table and
the frames list the lines they are made of; the table is then compressed (gzip, base64) and
unpacked by the browser's own ``DecompressionStream``. Nothing is fetched: no script, style,
font or image comes from any address, and the page works from ``file://``.

Examples
--------
>>> chart = curve_chart([0.0, 90.0], {"v_C": [1.0, 2.0]}, title="velocities", unit="m/s")
>>> chart.span
(0.0, 420.0)
"""

from __future__ import annotations

import base64
import functools
import html
import json
import math
import re
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..grading.answers import ANSWERS_FORMAT
from ..vocabulary import shown_title
from ..words import Message, message, number_text, render, template
from .canvas import Canvas, formula_runs
from .page_rules import PageRules, page_rules
from .style import INK, SMALL_SIZE, TEXT_SIZE, num

__all__ = ["Chart", "PageData", "PageQuantity", "StringTable", "WorkbookPage", "curve_chart",
           "formula_html", "inline_svg", "marked_html", "page_script", "workbook_html"]

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


@dataclass(frozen=True)
class Chart:
    """A full-turn chart of the page (:func:`curve_chart`): its SVG, the page x (px) of the
    first and the last angle (the cursor moves between them), and the plans its curves are
    read off (the drawing mode hides it until they are shown)."""

    svg: str
    span: tuple[float, float]
    plans: tuple[str, ...] = ()


@dataclass(frozen=True)
class _ChartArea:
    """Where a chart draws: its angles' and values' ranges on the page."""

    first: float
    last: float
    low: float
    high: float

    def page(self, angle: float, value: float) -> tuple[float, float]:
        """The page point (px) of a value at an angle: the chart's left at 0, its top at 0."""
        span = (self.last - self.first) or 1.0
        return (0.0 + (angle - self.first) / span * (CHART_WIDTH - 0.0),
                CHART_HEIGHT - (value - self.low) / (self.high - self.low) * (CHART_HEIGHT - 0.0))


def _chart_area(angles: Sequence[float], curves: Mapping[str, Sequence[float | None]]
                ) -> _ChartArea:
    finite = [float(v) for values in curves.values() for v in values
              if v is not None and math.isfinite(v)]
    low, high = (min(finite), max(finite)) if finite else (0.0, 1.0)
    if high - low < 1e-12 * max(1.0, abs(high)):
        low, high = low - 1.0, high + 1.0
    return _ChartArea(float(angles[0]), float(angles[-1]), low, high)


def _chart_axes(figure: Canvas, area: _ChartArea, title: str, unit: str) -> None:
    """The axes, the zero line, the end angles, the values' range and the title."""
    bottom = CHART_HEIGHT
    figure.line((0.0, bottom), (CHART_WIDTH, bottom), color=INK, width=0.8, layer="marks",
                obstacle=False)
    figure.line((0.0, 0.0), (0.0, bottom), color=INK, width=0.8, layer="marks",
                obstacle=False)
    if area.low < 0 < area.high:
        figure.line(area.page(area.first, 0.0), area.page(area.last, 0.0), color="#999999",
                    width=0.6, dash="3,3", layer="marks", obstacle=False)
    for angle in (area.first, area.last):
        figure.text((area.page(angle, area.low)[0], bottom + 14),
                    render(message("{angle:g}°", angle=angle)), size=SMALL_SIZE,
                    anchor="middle", css="axis", area=False)
    figure.text((-4, 4), number_text(area.high, ".4g"), size=SMALL_SIZE, anchor="end",
                css="axis", area=False)
    figure.text((-4, bottom), number_text(area.low, ".4g"), size=SMALL_SIZE, anchor="end",
                css="axis", area=False)
    figure.text((0.0, -10), render(message("{title}, {unit}", title=title, unit=unit)),
                size=TEXT_SIZE, bold=True, css="title", area=False)


def _chart_curve(figure: Canvas, area: _ChartArea, angles: Sequence[float],
                 values: Sequence[float | None], color: str) -> None:
    """One curve: a polyline for each run of finite values."""
    run: list[tuple[float, float]] = []
    runs = [run]
    for angle, value in zip(angles, values, strict=True):
        if value is None or not math.isfinite(value):
            run = []
            runs.append(run)
            continue
        run.append(area.page(float(angle), float(value)))
    for points in runs:
        if len(points) >= 2:
            figure.polyline(points, color=color, width=1.4, obstacle=False, css="curve")


def curve_chart(angles: Sequence[float], curves: Mapping[str, Sequence[float | None]], *,
                title: str, unit: str, plans: Sequence[str] = ()) -> Chart:
    """A full-turn chart: one polyline per curve against the crank angle, with a cursor line
    (``class="cursor"``) that the page moves to the current angle; ``plans``: the plans its
    curves are read off.

    >>> chart = curve_chart([0, 180, 360], {"v_C": [0, 1, 0]}, title="v", unit="m/s")
    >>> 'class="cursor"' in chart.svg, chart.span[0] < chart.span[1]
    (True, True)
    """
    figure = Canvas()
    area = _chart_area(angles, curves)
    _chart_axes(figure, area, title, unit)
    legend_x = CHART_WIDTH + 12
    for number, (name, values) in enumerate(curves.items()):
        color = CURVE_COLORS[number % len(CURVE_COLORS)]
        _chart_curve(figure, area, angles, values, color)
        y = 4 + 16 * number
        figure.line((legend_x, y - 4), (legend_x + 18, y - 4), color=color, width=2.0,
                    layer="marks", obstacle=False)
        figure.text((legend_x + 24, y), name, size=SMALL_SIZE, css="legend", area=False,
                    formula=True)
    figure.line((0.0, 0.0), (0.0, CHART_HEIGHT), color="#d00000", width=1.2, layer="marks",
                obstacle=False, css="cursor")
    drawn = figure.svg(render(message("{title} over a full turn", title=title))).svg
    return Chart(drawn, (0.0, CHART_WIDTH), tuple(plans))


@functools.lru_cache(maxsize=4096)
def formula_html(text: str) -> str:
    """A vector equation as HTML, what follows an underscore set as a subscript as the
    figures set it (:func:`planmethod.render.canvas.formula_runs`).

    >>> formula_html("v_C = v_B + v_CB")
    'v<sub>C</sub> = v<sub>B</sub> + v<sub>CB</sub>'
    """
    return "".join(f"<sub>{html.escape(part)}</sub>" if small else html.escape(part)
                   for part, small in formula_runs(text))


@dataclass(frozen=True)
class PageQuantity:
    """A check quantity of the page: its id (``name``), course ``symbol`` and ``subscript``
    (ω and 2), ``unit``, the ``plan`` it is read off (the drawing mode hides its value until
    the student asks to see that plan; None: never hidden), what a negative answer for it is
    told when it is a magnitude (``negative``:
    :func:`~planmethod.grading.answers.magnitude_note`) and what its signs mean (``senses``:
    :func:`~planmethod.grading.answers.sense_words`)."""

    name: str
    symbol: str
    subscript: str
    unit: str
    plan: str | None = None
    negative: Message | str | None = None
    senses: tuple[Message | str, Message | str] = ("positive", "negative")

    def as_dict(self, language: str | None = None) -> dict[str, Any]:
        """The quantity as the page's data, its words in ``language``."""
        return {"name": self.name, "symbol": self.symbol, "subscript": self.subscript,
                "unit": self.unit, "plan": self.plan,
                "negative": None if self.negative is None else render(self.negative, language),
                "senses": [render(sense, language) for sense in self.senses]}


@dataclass(frozen=True)
class WorkbookPage:
    """What a workbook page shows (:func:`workbook_html`).

    Parameters
    ----------
    title
        The exercise's title.
    angles
        The crank angle of every frame (deg), evenly spaced.
    panels
        The drawings shown side by side, by name (``position``, ``velocity`` …).
    frames
        One mapping per angle, the page's data of it: ``drawings`` {panel: SVG text},
        ``readings`` [[exact, plan or None], …] in the order of ``quantities``, ``steps``
        {plan: [[number, sentence, action, [the plan points it names]], …]}, ``equations``
        {plan: [vector equation, …]} (sentences and equations in plain text; the page sets
        their subscripts), ``questions`` (the answer key's questions at that angle: ``id``,
        ``symbol``, ``value``, ``tolerance``, ``unit``, ``signed``, ``mistakes``) and, with a
        drawing mode, ``draw`` (:func:`planmethod.grading.plan_points.drawing_frame`).
    quantities
        The report's check quantities, in the order of the readings.
    charts
        Full-turn charts (:func:`curve_chart`).
    notes
        Lines shown under the title (drafting precision, where the tolerances come from).
    start
        The crank angle the page opens at (the exercise's own; the frame nearest it), else
        the first.
    phi
        The crank angle's symbol as the course writes it (φ₁).
    drawing
        The drawing mode's data (:func:`planmethod.render.workbook_draw.drawing_data`); None:
        no drawing mode.
    sense
        +1 if the crank turns counter-clockwise (ω₁ ≥ 0), −1 if clockwise: *play* turns it
        that way.
    """

    title: str
    angles: Sequence[float]
    panels: Sequence[str]
    frames: Sequence[Mapping[str, Any]]
    quantities: Sequence[PageQuantity]
    charts: Sequence[Chart] = ()
    notes: Sequence[Message | str] = ()
    start: float | None = None
    phi: str = "φ₁"
    drawing: Mapping[str, Any] | None = None
    sense: int = 1

    def opening(self) -> float:
        """The angle the page opens at: the frame nearest :attr:`start`, else the first."""
        if self.start is None:
            return self.angles[0]
        return min(self.angles, key=lambda angle: (
            abs((angle - self.start + 180.0) % 360.0 - 180.0), angle))


def _quantity_label(quantity: PageQuantity) -> str:
    return f"{html.escape(quantity.symbol)}<sub>{html.escape(quantity.subscript)}</sub>"


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


def _json(data: Any) -> str:
    """``data`` as the page's JSON: compact, not escaped to ASCII, no NaN."""
    return json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False)


def _gzip() -> Any:
    """A gzip stream (level 6: 4 % larger than 9 on a page's frames, at less than half the
    time; no time in its header): the same bytes whether the text comes at once or in parts."""
    return zlib.compressobj(6, zlib.DEFLATED, 31)


def _pack(data: Any) -> str:
    stream = _gzip()
    packed = stream.compress(_json(data).encode("utf-8")) + stream.flush()
    return base64.b64encode(packed).decode("ascii")


def _packed_frame(frame: Mapping[str, Any], panels: Sequence[str], table: StringTable
                  ) -> dict[str, Any]:
    """A frame as the page's data: its drawings' lines and its sentences by their numbers in
    ``table``, typeset (:func:`formula_html`); its drawing-mode data is added apart (it needs
    the whole turn's extents)."""
    drawings = [table.lines(inline_svg(frame["drawings"][name])) if name in
                frame["drawings"] else [] for name in panels]
    steps = {plan: [[number, table.add(formula_html(text)), action, *rest]
                    for number, text, action, *rest in listed]
             for plan, listed in frame.get("steps", {}).items()}
    equations = {plan: [table.add(formula_html(text)) for text in listed]
                 for plan, listed in frame.get("equations", {}).items()}
    return {"drawings": drawings, "readings": frame["readings"], "steps": steps,
            "equations": equations, "questions": frame.get("questions", [])}


def _packed_frames(page: WorkbookPage, table: StringTable,
                   packed: list[dict[str, Any]] | None = None) -> list[dict[str, Any]]:
    """Each frame as the page's data (:func:`_packed_frame`; ``packed``: already so), with
    its drawing-mode data."""
    if packed is None:
        packed = [_packed_frame(frame, page.panels, table) for frame in page.frames]
    if page.drawing is not None:
        from .workbook_draw import pack_frame

        for one, frame in zip(packed, page.frames, strict=True):
            one["draw"] = pack_frame(frame.get("draw", {}), page.drawing["extents"])
    return packed


def _page_data(page: WorkbookPage, rules: PageRules, table: StringTable | None = None,
               packed: list[dict[str, Any]] | None = None) -> dict[str, Any]:
    """Everything the page's script reads, as JSON data (``table`` and ``packed``: the string
    table and the frames packed so far, see :class:`PageData`)."""
    table = StringTable() if table is None else table
    frames = _packed_frames(page, table, packed)
    data = {"angles": [float(a) for a in page.angles], "panels": list(page.panels),
            "strings": table.strings, "frames": frames,
            "quantities": [quantity.as_dict(rules.language) for quantity in page.quantities],
            "charts": [list(chart.span) for chart in page.charts],
            "sense": -1 if page.sense < 0 else 1, "rules": rules.as_dict(),
            # what the page keeps in the browser is kept under the exercise's title and
            # digest (two variants of a template share a title)
            "key": [page.title, (page.drawing or {}).get("exercise", "")],
            # the answers the page downloads are an answers file planmethod grade reads
            "answers_format": ANSWERS_FORMAT}
    if page.drawing is not None:
        data["draw"] = dict(page.drawing)
    return data


class PageData:
    """A page's data packed as its frames come, in order: each frame's lines and sentences
    entered in the string table, and the strings found so far written as JSON and
    compressed — the page's serial part, done while the frames that follow are solved.
    :meth:`packed` then adds the rest; the text is that of the whole page packed at once
    (as :func:`workbook_html` packs a page whose frames are not those added here).

    >>> frame = {"drawings": {"position": "<svg>\\n</svg>"}, "readings": [], "steps": {}}
    >>> page = WorkbookPage("Demo", [0.0, 90.0], ["position"], [frame, frame], [])
    >>> data = PageData(page.angles, page.panels)
    >>> data.add(page.frames[:1]), data.add(page.frames[1:])
    (None, None)
    >>> data.packed(page, page_rules()) == _pack(_page_data(page, page_rules()))
    True
    """

    def __init__(self, angles: Sequence[float], panels: Sequence[str]) -> None:
        self.angles = [float(angle) for angle in angles]
        self.panels = list(panels)
        self.table = StringTable()
        self.frames: list[Mapping[str, Any]] = []
        self._packed: list[dict[str, Any]] = []
        self._stream = _gzip()
        # the data's first keys, in the order _page_data writes them: the strings come last
        head = f'{{"angles":{_json(self.angles)},"panels":{_json(self.panels)},"strings":['
        self._out = [self._stream.compress(head.encode("utf-8"))]
        self._written = 0
        self._done: str | None = None

    def add(self, frames: Sequence[Mapping[str, Any]]) -> None:
        """The next ``frames`` of the page, packed; the strings they bring, compressed."""
        for frame in frames:
            self.frames.append(frame)
            self._packed.append(_packed_frame(frame, self.panels, self.table))
        fresh = self.table.strings[self._written:]
        if fresh:
            text = _json(fresh)[1:-1]
            self._out.append(self._stream.compress(
                (("," if self._written else "") + text).encode("utf-8")))
            self._written = len(self.table.strings)

    def holds(self, page: WorkbookPage) -> bool:
        """Whether ``page``'s angles, panels and frames (the very ones, in order) are those
        packed here."""
        return (self.angles == [float(angle) for angle in page.angles]
                and self.panels == list(page.panels) and len(self.frames) == len(page.frames)
                and all(one is other for one, other in zip(self.frames, page.frames,
                                                           strict=True)))

    def packed(self, page: WorkbookPage, rules: PageRules) -> str:
        """The page's data packed (gzip, base64), as :func:`_pack` of :func:`_page_data`; the
        page must be one this holds (:meth:`holds`)."""
        if self._done is None:          # (the stream ends here: packed once, kept)
            data = _page_data(page, rules, self.table, self._packed)
            rest = {key: value for key, value in data.items()
                    if key not in ("angles", "panels", "strings")}
            tail = "]," + _json(rest)[1:]
            self._out += [self._stream.compress(tail.encode("utf-8")), self._stream.flush()]
            self._done = base64.b64encode(b"".join(self._out)).decode("ascii")
        return self._done


def _rows_html(quantities: Sequence[PageQuantity], reveal: str) -> str:
    """The readings table's rows: the exact value, the plan's, the unit, the answer typed
    with its *show the answer* button (``reveal``: the button's words, HTML), its tolerance
    and its verdict."""
    return "\n".join(
        f'<tr{_plan_attribute(q.plan)}><th scope="row" id="quantity-{number}">'
        f'{_quantity_label(q)}</th>'
        f'<td class="reading" data-quantity="{html.escape(q.name)}" data-value=""></td>'
        f'<td class="plan-reading"></td><td class="unit">{html.escape(q.unit)}</td>'
        f'<td class="practice"><input class="answer" data-answer="{html.escape(q.name)}"'
        f' size="10" aria-labelledby="quantity-{number}">'   # its symbol, never its id
        f' <button type="button" class="reveal" data-reveal="{html.escape(q.name)}"'
        f' aria-describedby="quantity-{number}">{reveal}</button></td>'
        f'<td class="tolerance" data-tolerance-for="{html.escape(q.name)}"></td>'
        f'<td class="verdict" data-verdict-for="{html.escape(q.name)}"></td></tr>'
        for number, q in enumerate(quantities))


def _figures_html(page: WorkbookPage) -> tuple[str, str]:
    """The panels (empty: the script fills them) and the charts."""
    panels = "\n".join(f'<figure class="panel" id="panel-{html.escape(name)}" '
                       f'data-panel="{html.escape(name)}"{_panel_size(name, page.frames)}>'
                       '</figure>' for name in page.panels)
    charts = "\n".join(
        f'<div class="chart" data-chart="{number}"'
        f'{_plan_attribute(" ".join(chart.plans), "data-plans") if chart.plans else ""}>'
        f'{inline_svg(chart.svg)}</div>' for number, chart in enumerate(page.charts))
    return panels, charts


def marked_html(text: Message, markup: Mapping[str, str], language: str | None = None) -> str:
    """A message as HTML in ``language``: its text escaped, the fields named in ``markup``
    set as that markup (a control inside a label's sentence).

    >>> marked_html(message("press {button} & go"), {"button": "<b>here</b>"})
    'press <b>here</b> &amp; go'
    """
    marks = {name: f"\x00{number}\x00" for number, name in enumerate(markup)}
    shown = html.escape(render(text.replace(**marks), language), quote=False)
    for name, mark in marks.items():
        shown = shown.replace(mark, markup[name])
    return shown


def _words(page: WorkbookPage, rules: PageRules) -> dict[str, str]:
    """The page's own words in its language, as HTML."""
    from .workbook_draw import PLAN_TITLES

    language = rules.language

    def said(text: Message) -> str:
        return html.escape(render(text, language), quote=False)

    words = {name: said(text) for name, text in _CHROME.items()}
    options = "\n".join(f'<option value="{plan}">{said(title)}</option>'
                        for plan, (title, _) in PLAN_TITLES.items())
    words["construction"] = marked_html(
        _CONSTRUCTION, {"plan": f'<select id="step-plan">{options}</select>'}, language)
    words["switch"] = marked_html(_SWITCH, {"time": '<output id="switch-time">—</output>'},
                                  language)
    words["failed"] = html.escape(rules.templates["needs_decompression"].replace(
        "{feature}", "DecompressionStream"))
    words["play"] = html.escape(rules.templates["play"], quote=False)
    words["crank"] = said(message("crank angle {phi}", phi=page.phi))
    words["heading"] = said(message("{title} — workbook", title=shown_title(page.title)))
    return words


def workbook_html(page: WorkbookPage, rules: PageRules | None = None,
                  data: PageData | None = None) -> str:
    """The workbook page of ``page`` as HTML text, with the rules it grades by (default:
    :func:`~planmethod.render.page_rules.page_rules` in the language spoken now); ``data``:
    the page's frames already packed as they came (:class:`PageData`).

    Examples
    --------
    >>> table = StringTable()
    >>> table.lines("<svg>\\n<line />\\n</svg>"), table.lines("<svg>\\n<circle />\\n</svg>")
    ([0, 1, 2], [0, 3, 2])
    >>> text = workbook_html(WorkbookPage("Demo", [0.0, 90.0], ["position"], [
    ...     {"drawings": {"position": "<svg><title>0</title></svg>"}, "readings": [[1.0, None]],
    ...      "steps": {}, "questions": []},
    ...     {"drawings": {"position": "<svg><title>90</title></svg>"},
    ...      "readings": [[2.0, 2.1]], "steps": {}, "questions": []}],
    ...     [PageQuantity("v_C", "v", "C", "m/s")]))
    >>> 'id="angle"' in text and "http" not in text
    True
    """
    rules = rules or page_rules()
    draw_html, draw_extra, draw_mode = "", "", ""
    if page.drawing is not None:
        from .workbook_draw import DRAW_STYLE, draw_mode_html, draw_script, drawing_section

        draw_html = drawing_section(list(page.drawing["extents"]))
        draw_extra = f"<script>{draw_script()}</script>\n<style>{DRAW_STYLE}</style>"
        draw_mode = draw_mode_html()
    words = _words(page, rules)
    angles = page.angles
    step = (angles[1] - angles[0]) if len(angles) > 1 else 1.0
    panels, charts = _figures_html(page)
    notes = "".join(f"<p class=\"note\">{html.escape(render(line, rules.language))}</p>"
                    for line in page.notes)
    return _PAGE.format(
        language=html.escape(rules.language), title=html.escape(shown_title(page.title)),
        notes=notes, low=num(angles[0]), high=num(angles[-1]), first=num(page.opening()),
        step=num(step), panels=panels, charts=charts,
        rows=_rows_html(page.quantities, words["show_answer"]),
        data=(data.packed(page, rules) if data is not None and data.holds(page)
              else _pack(_page_data(page, rules))),
        style=_STYLE, script=_script(),
        drawing=draw_html, drawing_script=draw_extra, draw_mode=draw_mode, **words)


#: the page's own words (its controls, the table's heads)
_CHROME = {
    "modes": template("mode", context="of the page"),
    "watch": template("watch", context="a mode of the page"),
    "practice": template("practise", context="a mode of the page"),
    "compact": template("two drawings to a row"),
    "loading": template("loading…"),
    "first_step": template("first", context="the first step"),
    "previous": template("◀ step"),
    "next": template("step ▶"),
    "all": template("all", context="every step"),
    "quantity": template("quantity", context="a table's column"),
    "exact": template("exact", context="a value"),
    "read": template("read off the plan"),
    "unit": template("unit"),
    "answer": template("your answer"),
    "tolerance": template("tolerance"),
    "check": template("check", context="a button"),
    "readings": template("the values at this angle", context="a table's caption"),
    "show_answer": template("show the answer", context="a button"),
    "download_answers": template("download my answers", context="a button"),
}
_CONSTRUCTION = template("construction of the\n{plan}")
_SWITCH = template("frame switch: {time}")


_STYLE = """
body{font-family:"DejaVu Sans",Verdana,Arial,sans-serif;margin:12px;color:#111}
h1{font-size:1.25em;margin:0 0 4px}
.note{margin:2px 0;color:#444;font-size:.9em}
#controls{position:sticky;top:0;background:#fff;padding:4px 0;z-index:2;
 border-bottom:1px solid #ccc;display:flex;gap:4px 12px;align-items:center;flex-wrap:wrap}
#modes{display:flex;gap:4px;align-items:center;border:0;margin:0;padding:0;flex-wrap:wrap}
#modes legend{float:left;margin-right:4px;color:#444}
.mode{display:inline-flex;align-items:center;gap:4px;min-height:44px;min-width:44px;
 padding:0 10px;border:1px solid #8a9bb8;border-radius:6px;box-sizing:border-box;
 cursor:pointer;background:#f4f7fb}
.mode:has(input:checked){background:#1f5fa8;color:#fff;border-color:#1f5fa8}
.mode:has(input:focus-visible){outline:3px solid #d35400;outline-offset:1px}
.angle-control{display:inline-flex;align-items:center;gap:6px;flex-wrap:wrap;max-width:100%}
#angle{width:min(360px,calc(100vw - 48px));min-height:44px}
button,select{min-height:44px;min-width:44px}
.option{display:inline-flex;align-items:center;gap:4px;min-height:44px}
.option input{width:24px;height:24px}
#panels{display:flex;flex-wrap:wrap;gap:8px;margin-top:8px;align-items:flex-start}
.panel{margin:0;border:1px solid #ddd;width:calc(50% - 8px);min-width:min(320px,100%);
 height:430px;max-width:calc(100% - 2px);box-sizing:border-box}
.panel[style]{height:auto;width:100%;min-height:0;overflow:hidden}
body.compact .panel{width:calc(50% - 8px)}
.panel svg{display:block;width:100%;height:100%}
#charts{display:flex;flex-wrap:wrap;gap:12px;margin-top:8px}
.chart{max-width:100%}
.chart svg{width:520px;height:240px;max-width:100%}
section.readings{overflow-x:auto;max-width:100%}
table{border-collapse:collapse;margin-top:8px}
caption{text-align:left;font-weight:bold;padding:2px 8px}
td,th{padding:2px 8px;border-bottom:1px solid #eee;text-align:right}
th{font-weight:normal;font-style:italic;font-family:"DejaVu Serif",Georgia,serif}
input.answer{min-height:40px;font-size:1em;max-width:8em}
.practice,.tolerance,.verdict{display:none}
body.practising .practice,body.practising .tolerance,body.practising .verdict,
body.drawing .practice,body.drawing .tolerance,body.drawing .verdict{display:table-cell}
body.practising .reading,body.practising .plan-reading{visibility:hidden}
body.practising #readings tr.revealed td.reading,
body.practising #readings tr.revealed td.plan-reading{visibility:visible}
body.practising #charts,body.practising #playback{display:none}
#readings tr.revealed button.reveal{visibility:hidden}
.panel .asked-hidden{visibility:hidden}
.verdict{text-align:left;max-width:40em}
.verdict.correct{color:#1a7f37}.verdict.wrong{color:#c0392b}
#playback{margin-top:8px}
#step-text{font-style:italic;min-height:1.3em}
.step-hidden{display:none}
.step-current line,.step-current polygon,line.step-current{stroke:#d00000!important;
 fill:#d00000}
#status{color:#c0392b}
.switch{display:none}
@media (max-width:600px){
 body{margin:6px}
 .option{display:none}
 #modes legend{position:absolute;width:1px;height:1px;overflow:hidden;clip-path:inset(50%)}
 .mode{padding:0 8px}
 .angle-control{flex:1 1 100%;gap:2px 6px}
 .angle-control label{flex:1 1 100%;font-size:.9em}
 #angle{flex:1 1 120px;width:auto}
 .panel,body.compact .panel{width:100%}
 body.practising #readings :is(.reading,.plan-reading,.reading-head,.plan-head){display:none}
 td,th{padding:2px 4px}
}
"""

_PAGE = """<!DOCTYPE html>
<html lang="{language}">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{heading}</title>
<style>{style}</style>
</head>
<body>
<main>
<h1>{title}</h1>
{notes}
<div id="controls">
<fieldset id="modes"><legend>{modes}</legend>
<label class="mode"><input type="radio" name="mode" id="watch" value="watch" checked> \
{watch}</label>
<label class="mode"><input type="radio" name="mode" id="practice" value="practise"> \
{practice}</label>
{draw_mode}
</fieldset>
<span class="angle-control"><label for="angle">{crank}</label>
<input type="range" id="angle" min="{low}" max="{high}" step="{step}" value="{first}">
<output id="angle-value" for="angle">{first}°</output>
<button type="button" id="play">{play}</button></span>
<label class="option"><input type="checkbox" id="compact"> {compact}</label>
<span class="switch">{switch}</span>
<span id="status" data-failed="{failed}">{loading}</span>
</div>
<div id="panels">
{panels}
</div>
{drawing}
<section id="playback">
<label>{construction}</label>
<button type="button" id="step-first">{first_step}</button>
<button type="button" id="step-prev">{previous}</button>
<button type="button" id="step-next">{next}</button>
<button type="button" id="step-all">{all}</button>
<output id="step-number"></output>
<p id="step-text"></p>
<p id="equations"></p>
</section>
<section class="readings" aria-labelledby="readings-caption">
<table id="readings">
<caption id="readings-caption">{readings}</caption>
<thead><tr><th scope="col">{quantity}</th><td class="reading-head">{exact}</td>
<td class="plan-head">{read}</td><td>{unit}</td>
<td class="practice">{answer}</td><td class="tolerance">{tolerance}</td>
<td class="verdict"><button type="button" id="check">{check}</button>
<button type="button" id="download-answers">{download_answers}</button></td></tr></thead>
<tbody>
{rows}
</tbody>
</table>
</section>
<div id="charts">
{charts}
</div>
</main>
<script type="application/octet-stream" id="workbook-data">{data}</script>
{drawing_script}
<script>{script}</script>
</body>
</html>
"""

def page_script(name: str) -> str:
    """A page's script file beside this module (``workbook.js``, ``page_words.js`` …)."""
    from importlib.resources import files

    return files(__package__).joinpath(name).read_text(encoding="utf-8")


def _script() -> str:
    """The page's script: the words' filler and the rulebook (``page_words.js``,
    ``page_rules.js``), then the page's own (``workbook.js``)."""
    return "\n".join(page_script(name) for name in ("page_words.js", "page_rules.js",
                                                    "workbook.js"))
