"""Every plot of planmethod, drawn with matplotlib's object API (imported only when used).

* :func:`save_sweep_plot` — the kinematic curves of a sweep table over the full turn;
* :func:`save_force_plot` — the reactions per pair and the balancing moment over the turn
  (``planmethod sweep --forces``), as the figures 8–14 of Umbetkulov et al., "Dynamic force
  analysis of a six-link planar mechanism";
* :func:`save_study_plot` — the parameter study of Jobborova et al., "Study of the load on
  kinematic pairs of a four-bar linkage mechanism".

Figures are :class:`matplotlib.figure.Figure` objects drawn on their own Agg canvas: pyplot is
never imported, and the caller's backend and rcParams are neither read nor changed (the style is
applied inside :func:`matplotlib.style.context` from matplotlib's defaults, and restored when
the figure is saved), so a user's notebook settings are the same before and after a plot, and
a plot looks the same whatever the caller set.

:func:`save_sweep_plot` in detail:

:func:`save_sweep_plot` groups the columns of :func:`planmethod.sweep.sweep_table` into panels
against the crank angle: speeds |v| of points, accelerations |a| of points, ω and ε of links,
travel s, sliding velocity ds/dt and acceleration d²s/dt² of prismatic pairs, radii of curvature
ρ (log scale; a straight stretch is a gap), and every other numeric column (forces and moments
added by the force sweep, for instance) in a last panel. The coordinate and component columns
(``x_``, ``y_``, ``vx_``, ``vy_``, ``ax_``, ``ay_``, ``theta_``) are left to the CSV.

The style is fixed and no date or version is written into the file, so the same table gives
the same picture; the file is written whole or not at all.

Examples
--------
>>> import numpy as np, tempfile, pathlib
>>> angle = np.arange(0.0, 360.0, 10.0)
>>> table = {"angle": angle, "v_C": np.abs(np.sin(np.radians(angle))),
...          "omega_BC": np.cos(np.radians(angle))}
>>> target = pathlib.Path(tempfile.mkdtemp()) / "curves.png"
>>> save_sweep_plot(table, target, title="demo")
>>> target.stat().st_size > 1000
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from ..errors import PlanmethodError
from ..forces.names import BALANCING_MOMENT
from ..io import atomic_path
from ..vocabulary import QUANTITY_KINDS, numbered, quantity, shown_title, symbol
from ..words import Message, message, render

__all__ = ["FORMATS", "Panel", "panels", "plot_format", "save_class_report_plot",
           "save_force_plot", "save_study_plot", "save_sweep_plot"]

#: file formats by suffix
FORMATS = {".png": "png", ".svg": "svg", ".pdf": "pdf"}

#: (column prefix, panel title, y-axis label) of each kind of quantity that has a panel
#: (:data:`planmethod.vocabulary.QUANTITY_KINDS`: the title a message, rendered when drawn in
#: the language spoken then; the unit: words: vocabulary); a column joins the panel of its
#: prefix
_PANELS = tuple((f"{kind.prefix}_", kind.plotted, kind.unit)
                for kind in QUANTITY_KINDS.values() if kind.plotted is not None)
#: the prefix of the radii of curvature, drawn on a log scale where they span decades
_RADIUS = "rho_"
_LEFT_TO_CSV = ("x_", "y_", "vx_", "vy_", "ax_", "ay_", "theta_")

_STYLE = {
    "font.family": "DejaVu Sans",
    "font.size": 9.0,
    "axes.grid": True,
    "grid.alpha": 0.35,
    "lines.linewidth": 1.6,
    "svg.hashsalt": "planmethod",
    "svg.fonttype": "path",
    "pdf.compression": 6,
}
_COLOURS = ("#1f5fbf", "#c0392b", "#1b8a3a", "#7b3fa0", "#d17a00", "#17848f", "#7a7a7a",
            "#b0306e", "#4b5d16", "#333333")
_METADATA = {"png": {"Software": None}, "svg": {"Date": None, "Creator": None},
             "pdf": {"CreationDate": None, "ModDate": None, "Creator": None,
                     "Producer": None}}


def plot_format(path: str | Path) -> str:
    """The matplotlib format of a plot file from its suffix, or a :class:`PlanmethodError`
    naming the file and the formats that are supported.

    Examples
    --------
    >>> plot_format("curves.PNG")
    'png'
    >>> try:
    ...     plot_format("curves.txt")
    ... except PlanmethodError as error:
    ...     print(error)
    curves.txt: plot format '.txt' not supported; use .png, .svg or .pdf
    >>> try:
    ...     plot_format("curves")
    ... except PlanmethodError as error:
    ...     print(error)
    curves: a plot file needs a suffix for its format; use .png, .svg or .pdf
    """
    path = Path(path)
    form = FORMATS.get(path.suffix.lower())
    if form is None and path.suffix:
        raise PlanmethodError(message("plot format '{suffix}' not supported; use {formats}",
                                      suffix=path.suffix, formats=_FORMATS_TEXT),
                              file=str(path))
    if form is None:
        raise PlanmethodError(message("a plot file needs a suffix for its format; use "
                                      "{formats}", formats=_FORMATS_TEXT), file=str(path))
    return form


#: the plot formats an error offers
_FORMATS_TEXT = message("{first}, {second} or {third}", first=".png", second=".svg",
                        third=".pdf")


def _plain_text(text: str) -> str:
    r"""Text from a file (a title, a question, a mistake's name) as matplotlib shows it as
    written: each ``$`` escaped, so that no pair of them is read as mathtext (``"Mechanism
    $^^^$"`` would stop the plot with a parse error, ``"$5 and $6"`` would be set as math).
    A title is first cut as every figure shows it (:func:`~planmethod.vocabulary.shown_title`).

    >>> _plain_text("$5 and $6"), _plain_text(r"a \$ b")
    ('\\$5 and \\$6', 'a \\\\$ b')
    """
    return text.replace("$", r"\$")


def _style_context(style: Mapping[str, Any]):
    """matplotlib's defaults with ``style`` on top, for the figures made inside the block;
    the caller's rcParams are restored on leaving it (the backend is never touched)."""
    import matplotlib.style
    from cycler import cycler

    return matplotlib.style.context(
        ["default", dict(style, **{"axes.prop_cycle": cycler(color=list(_COLOURS))})])


def _new_figure(**keywords: Any):
    """A :class:`~matplotlib.figure.Figure` on its own Agg canvas (no pyplot)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(**keywords)
    FigureCanvasAgg(figure)
    return figure


def _save(figure, path: Path, form: str) -> None:
    """Write the figure whole or not at all, without a date or a version in it."""
    with atomic_path(path) as temporary:
        figure.savefig(temporary, format=form, metadata=_METADATA[form])


class Panel(NamedTuple):
    """A panel of a sweep's plot: its title, the unit of its y axis and its columns."""

    title: Message | str
    unit: Message | str
    columns: list[str]


def panels(table: Mapping[str, np.ndarray]) -> list[Panel]:
    """The panels a table is drawn in, empty panels left out.

    Examples
    --------
    >>> [(render(title), render(unit), columns) for title, unit, columns in panels(
    ...     {"angle": [0, 1], "v_C": [1, 2], "a_C": [0, 0], "x_C": [0, 0], "Mb": [1, 1]})]
    [('speed of points |v|', 'm/s', ['v_C']), ('acceleration of points |a|', 'm/s²', \
['a_C']), ('other columns', 'SI units', ['Mb'])]
    """
    grouped: dict[str, list[str]] = {prefix: [] for prefix, _, _ in _PANELS}
    other: list[str] = []
    for name, values in table.items():
        if name == "angle" or name.startswith(_LEFT_TO_CSV):
            continue
        array = np.asarray(values)
        if not (np.issubdtype(array.dtype, np.floating)
                or np.issubdtype(array.dtype, np.integer)):
            continue
        # longest matching prefix wins: dds_ before ds_ before s_
        prefix = max((p for p, _, _ in _PANELS if name.startswith(p)), key=len, default=None)
        (grouped[prefix] if prefix else other).append(name)
    out = [Panel(title, unit, grouped[prefix]) for prefix, title, unit in _PANELS
           if grouped[prefix]]
    if other:
        out.append(Panel(message("other columns"), message("SI units"), other))
    return out


def curve_label(name: str, numbers: Mapping[str, int] | None = None) -> Message | str:
    """A column's name in a plot's legend, in a course's notation: a link's quantity by the
    link's number with its name (ω₃ (rod)), a point's with the point as a subscript; a column
    that is no quantity keeps its name.

    Examples
    --------
    >>> numbers = {"frame": 0, "crank": 1, "rod": 2}
    >>> [render(curve_label(name, numbers)) for name in ("omega_rod", "v_C", "a_B@rod")]
    ['ω₂ (rod)', 'v$_{\\\\mathregular{C}}$', 'a$_{\\\\mathregular{B}_{2}}$ (on rod)']
    """
    try:
        found = quantity(name)
    except KeyError:
        return name
    if found.kind.subject == "link" and numbers and found.subject in numbers:
        return f"{symbol(name, dict(numbers))} ({found.subject})"
    if found.kind.subject == "point":
        point, _, link = found.subject.partition("@")   # B@lever: B of the lever, B₄
        if point.isalnum() and not link:
            return f"{found.symbol}$_{{\\mathregular{{{point}}}}}$"
        if point.isalnum() and numbers and link in numbers:
            return message("{symbol} (on {link})", link=link, symbol=(
                f"{found.symbol}$_{{\\mathregular{{{point}}}_{{{numbers[link]}}}}}$"))
    return symbol(name)


def save_sweep_plot(table: Mapping[str, np.ndarray], path: str | Path, *, title: str,
                    numbers: Mapping[str, int] | None = None, crank: int = 1) -> None:
    """Draw a sweep table's curves against the crank angle into ``path`` (.png, .svg, .pdf).
    The legends name the curves in a course's notation (:func:`curve_label`; ``numbers`` are
    the links' numbers, :func:`planmethod.numbering.course_numbers`; ``crank`` the crank's,
    which φ carries) and list only the curves drawn: a column with no finite value is left
    out.

    Raises
    ------
    PlanmethodError
        If the suffix is not one of png, svg, pdf, the table has no ``angle`` column or no
        column to draw, or the file cannot be written. No file is left behind.
    """
    path = Path(path)
    form = plot_format(path)
    angle, groups = _sweep_panels(table, path)
    count = len(groups)
    columns_of_panels = 1 if count == 1 else 2
    rows = -(-count // columns_of_panels)
    with _style_context(_STYLE):
        figure = _new_figure(figsize=(6.0 * columns_of_panels, 2.6 * rows + 0.6), dpi=120,
                             layout="constrained")
        axes = figure.subplots(rows, columns_of_panels, squeeze=False, sharex=True)
        for index, panel in enumerate(groups):
            _draw_panel(axes[index // columns_of_panels][index % columns_of_panels], table,
                        angle, panel, numbers)
        for index in range(count, rows * columns_of_panels):
            axes[index // columns_of_panels][index % columns_of_panels].set_visible(False)
        crank_axis = render(message("crank angle {phi}, °", phi=numbered("φ", crank)))
        for ax in axes[-1]:
            ax.set_xlabel(crank_axis)
        if count > 1 and count % 2 == 1:
            axes[-2][1].set_xlabel(crank_axis)
            axes[-2][1].xaxis.set_tick_params(labelbottom=True)
        if angle.min() >= 0 and angle.max() <= 360 and np.ptp(angle) >= 90:
            axes[0][0].set_xticks(np.arange(0.0, 361.0, 45.0))     # shared by every panel
        figure.suptitle(render(message("{title} — full turn",
                                       title=_plain_text(shown_title(title)))),
                        fontsize=11, fontweight="bold")
        _save(figure, path, form)


def _sweep_panels(table: Mapping[str, np.ndarray], path: Path
                  ) -> tuple[np.ndarray, list[Panel]]:
    """The crank angles of a sweep table and the panels its columns are drawn in; a
    :class:`PlanmethodError` naming ``path`` for a table without angles, with nothing to
    draw, or with a column of another length."""
    if "angle" not in table:
        raise PlanmethodError(message("the sweep table has no 'angle' column"), file=str(path))
    angle = np.asarray(table["angle"], dtype=float)
    groups = panels(table)
    if angle.size == 0 or not groups:
        raise PlanmethodError(message("the sweep table has nothing to plot"), file=str(path))
    for name in (name for panel in groups for name in panel.columns):
        if np.shape(table[name]) != angle.shape:
            raise PlanmethodError(message("column {name!r} has {count} values for {angles} "
                                          "angles", name=name, count=int(np.size(table[name])),
                                          angles=angle.size), file=str(path))
    return angle, groups


def _draw_panel(ax, table: Mapping[str, np.ndarray], angle: np.ndarray, panel: Panel,
                numbers: Mapping[str, int] | None) -> None:
    """One panel of a sweep's plot: its curves (radii of curvature by magnitude, on a log
    scale where they span decades), title, axis label and legend. A curve that repeats one
    drawn before it over the whole turn (a block turning with its lever: ω₂ = ω₃) is dashed,
    so that the one beneath shows through."""
    radius = all(name.startswith(_RADIUS) for name in panel.columns)
    drawn: list[np.ndarray] = []
    for name in panel.columns:
        values = np.asarray(table[name], dtype=float)
        if radius:
            values = np.where(np.isfinite(values) & (np.abs(values) > 0), np.abs(values),
                              np.nan)
        if not np.isfinite(values).any():
            continue                      # nothing drawn: not in the legend
        repeats = any(_same_curve(values, earlier) for earlier in drawn)
        ax.plot(angle, values, label=render(curve_label(name, numbers)),
                ls=(0, (4, 3)) if repeats else "-")
        drawn.append(values)
    if radius:
        radii = np.abs(np.asarray([table[c] for c in panel.columns], dtype=float))
        radii = radii[np.isfinite(radii) & (radii > 0)]
        if radii.size and radii.max() > 30 * radii.min():   # spans decades
            ax.set_yscale("log")
    ax.set_title(render(panel.title), fontsize=9.5)
    ax.set_ylabel(render(message("|ρ|, m")) if radius else render(panel.unit))
    ax.legend(fontsize=7.5, loc="best", ncols=min(3, len(panel.columns)), frameon=False)
    ax.set_xlim(float(angle.min()), float(angle.max()) if angle.size > 1
                else float(angle.min()) + 1.0)


def _same_curve(values: np.ndarray, other: np.ndarray) -> bool:
    """Whether two curves of a panel are the same over the whole turn (to rounding: 1e-9 of
    the larger's span), undefined at the same angles.

    >>> a = np.array([1.0, 2.0, np.nan])
    >>> _same_curve(a, a + 1e-12), _same_curve(a, a * 1.01), _same_curve(a, np.ones(3))
    (True, False, False)
    """
    if values.shape != other.shape or not np.array_equal(np.isnan(values), np.isnan(other)):
        return False
    finite = np.isfinite(values)
    span = max(float(np.ptp(values[finite])), float(np.ptp(other[finite])), 1e-300)
    return bool(np.all(np.abs(values[finite] - other[finite]) <= 1e-9 * span + 1e-300))


#: colours of the force curves
_FORCE_COLOURS = {"x": "#1f77b4", "y": "#d62728", "magnitude": "#222222", "moment": "#2ca02c"}
_FORCE_STYLE = {"font.family": "DejaVu Sans", "font.size": 9.0, "axes.grid": True,
                "grid.alpha": 0.3, "svg.hashsalt": "planmethod", "svg.fonttype": "none",
                "pdf.compression": 6}


_SENSE_COLOUR = "#7f7f7f"


def sense_changes(table: Mapping[str, np.ndarray]) -> dict[str, list[float]]:
    """Per pair with friction, the crank angles where its friction changes sense: where the
    ``friction_sense_K`` column turns from +1 to −1 or back (a rest, 0, in between is passed
    over). The angle is the first one of the new sense.

    >>> sense_changes({"angle": np.array([0., 10, 20, 30]),
    ...                "friction_sense_B": np.array([1., 0, -1, -1])})
    {'B': [20.0]}
    """
    angles = np.asarray(table["angle"], float)
    found: dict[str, list[float]] = {}
    for name, column in table.items():
        if not name.startswith("friction_sense_"):
            continue
        sense = np.asarray(column, float)
        moving = np.flatnonzero(sense != 0)
        flips = moving[1:][np.diff(sense[moving]) != 0]
        if flips.size:
            found[name.removeprefix("friction_sense_")] = [float(a) for a in angles[flips]]
    return found


def save_force_plot(table: Mapping[str, np.ndarray], path: str | Path, *, title: str,
                    marks: Sequence[tuple[float, float]] = (),
                    names: Mapping[str, str] | None = None, crank: int = 1) -> None:
    """Reaction components and magnitude per pair and the balancing moment versus crank angle,
    from the columns of ``planmethod sweep --forces`` (``Rx_K Ry_K R_K [M_K]``, ``M_b``…),
    on a landscape page. ``marks`` are (crank angle, M_b) of the positions the exercise solves,
    marked on the M_b curve with their values; with friction the frictionless M_b is drawn
    beside it and each sense change of the friction is marked. ``names`` titles each pair's
    panel as a course writes its reaction (``R₁₂``), by pair key; ``crank`` is the crank's
    number, which φ carries.

    Raises
    ------
    PlanmethodError
        If the suffix is not png, svg or pdf, or the file cannot be written.
    """
    path = Path(path)
    form = plot_format(path)
    angles = np.asarray(table["angle"], float)
    pairs = [name[2:] for name in table if name.startswith("R_")]
    changes = sense_changes(table)
    count = len(pairs) + 1
    columns = 2
    rows = math.ceil(count / columns)
    phi = numbered("φ", crank)
    with _style_context(_FORCE_STYLE):
        # landscape, page-width: at most A4 landscape (11.7 × 8.3 in), however many pairs
        figure = _new_figure(figsize=(11.7, min(8.3, 2.2 * rows + 0.8)), dpi=130,
                             layout="tight")
        axes = figure.subplots(rows, columns, sharex=True, squeeze=False)
        flat = axes.ravel()
        for axis, key in zip(flat, pairs, strict=False):
            _draw_pair(axis, table, angles, key, (names or {}).get(key), changes.get(key, ()))
        _draw_balancing(flat[len(pairs)], table, angles, changes, marks, phi)
        for extra in flat[count:]:
            extra.set_visible(False)
        for axis in axes[-1]:
            axis.set_xlabel(render(message("crank angle {phi}, °", phi=phi)))
        for axis in flat[:count]:
            axis.set_xlim(angles[0], angles[-1])
            axis.xaxis.set_tick_params(labelbottom=True)
        figure.suptitle(render(message("{title} — reactions and balancing moment over the turn",
                                       title=_plain_text(shown_title(title)))), fontsize=11)
        _save(figure, path, form)


#: the legend entry of the lines where a pair's friction changes sense
_SENSE_CHANGE = message("friction changes sense")


def _draw_pair(axis, table: Mapping[str, np.ndarray], angles: np.ndarray, key: str,
               shown: str | None, changes: Sequence[float]) -> None:
    """A pair's panel: its reaction's components and magnitude (and its couple, on an axis
    of its own), each sense change of its friction marked."""
    axis.plot(angles, table[f"Rx_{key}"], color=_FORCE_COLOURS["x"], lw=1.2, label="Rx")
    axis.plot(angles, table[f"Ry_{key}"], color=_FORCE_COLOURS["y"], lw=1.2, label="Ry")
    axis.plot(angles, table[f"R_{key}"], color=_FORCE_COLOURS["magnitude"], lw=1.6,
              label="|R|")
    axis.set_title(render(message("{reaction} (pair {pair})", reaction=shown, pair=key)
                          if shown else message("pair {pair}", pair=key)), loc="left")
    axis.set_ylabel(render(message("N", context="unit")))
    if f"M_{key}" in table:
        twin = axis.twinx()
        twin.plot(angles, table[f"M_{key}"], color=_FORCE_COLOURS["moment"], lw=1.0,
                  ls="--", label=render(message("couple")))
        twin.set_ylabel(render(message("couple, N·m")), color=_FORCE_COLOURS["moment"])
        twin.grid(False)
    for number, angle in enumerate(changes):
        axis.axvline(angle, color=_SENSE_COLOUR, lw=0.8, ls=":",
                     label=render(_SENSE_CHANGE) if number == 0 else None)
    axis.legend(loc="best", fontsize=7, ncol=2 if changes else 3)


def _draw_balancing(axis, table: Mapping[str, np.ndarray], angles: np.ndarray,
                    changes: Mapping[str, list[float]], marks: Sequence[tuple[float, float]],
                    phi: str) -> None:
    """The balancing moment's panel: M_b by the groups (by the whole system, without
    friction), the solved positions marked with their values, and each sense change of any
    pair's friction marked and named by its pair at the top of the axis (M_b jumps there)."""
    moment = render(BALANCING_MOMENT)
    axis.plot(angles, table["M_b"], color="#9467bd", lw=1.8,
              label=render(message("{symbol} (groups)", symbol=moment)))
    named: dict[float, list[str]] = {}
    for key, found in changes.items():
        for angle in found:
            named.setdefault(angle, []).append(key)
    for number, angle in enumerate(sorted(named)):
        axis.axvline(angle, color=_SENSE_COLOUR, lw=0.8, ls=":",
                     label=render(_SENSE_CHANGE) if number == 0 else None)
        late = angle > angles[0] + 0.85 * (angles[-1] - angles[0])   # name to the left
        axis.annotate(", ".join(named[angle]), (angle, 1.0),
                      xycoords=("data", "axes fraction"), xytext=(-2 if late else 2, -9),
                      textcoords="offset points", fontsize=7, color=_SENSE_COLOUR,
                      ha="right" if late else "left")
    if "M_b_system" in table:
        axis.plot(angles, table["M_b_system"], color="#ff7f0e", lw=0.9, ls=":",
                  label=render(message("{symbol} (whole system)", symbol=moment)))
    if "M_b_no_friction" in table:
        axis.plot(angles, np.asarray(table["M_b_no_friction"], float), color="#8c564b",
                  lw=1.2, ls="--", label=render(message("{symbol} without friction",
                                                        symbol=moment)))
    for angle, value in marks:
        axis.plot([angle], [value], "o", color="#9467bd", ms=5)
        axis.annotate(render(message("{phi} = {angle:g}°: {symbol} = {moment:.4g} N·m",
                                     phi=phi, angle=angle, symbol=moment, moment=value)),
                      (angle, value), textcoords="offset points", xytext=(6, 6), fontsize=7)
    axis.set_title(render(message("balancing moment on the crank")), loc="left")
    axis.set_ylabel(render(message("N·m", context="unit")))
    axis.legend(loc="best", fontsize=7)


def save_study_plot(study: Any, path: str | Path) -> None:
    """The parameter study of Jobborova et al.: the largest reaction in each pair against each
    parameter (the other two at their base values), one panel per parameter.

    Raises
    ------
    PlanmethodError
        If the suffix is not png, svg or pdf, or the file cannot be written.
    """
    path = Path(path)
    form = plot_format(path)
    parameters = study.parameters
    with _style_context(_FORCE_STYLE):
        figure = _new_figure(figsize=(4.2 * len(parameters), 4.2), dpi=130, layout="tight")
        axes = figure.subplots(1, len(parameters), squeeze=False, sharey=True)
        markers = "osD^v<>p"
        for axis, parameter in zip(axes[0], parameters, strict=True):
            values = study.values[parameter.name]
            for index, pair in enumerate(study.pairs):
                axis.plot(values, study.maxima[parameter.name][pair],
                          marker=markers[index % 8], lw=1.4,
                          label=render(message("R_{pair} max", pair=pair)))
            axis.set_xlabel(render(message("{parameter}, {unit}", parameter=parameter.label,
                                           unit=parameter.unit)))
            axis.set_ylabel(render(message("largest reaction over the turn, N")))
            change = study.relative_change(parameter.name)
            axis.set_title(render(message("{parameter}: up to {change:.0f} % change",
                                          parameter=parameter.label, change=100 * change)),
                           loc="left", fontsize=9)
            axis.legend(fontsize=7)
        figure.suptitle(render(message("{title}\nlargest reactions over a turn against each "
                                       "parameter, the others at the base case: {base}",
                                       title=_plain_text(shown_title(study.title)),
                                       base=study.base_values())), fontsize=10)
        _save(figure, path, form)


def save_class_report_plot(rows: Sequence[Any], path: str | Path, *,
                           title: str, symbols: Mapping[str, str] | None = None,
                           mistakes: Mapping[str, str] | None = None) -> None:
    """The class report as a bar chart: per question, the share of the class right, each
    named mistake and the unexplained wrong answers, stacked to 100 %. ``rows`` are the
    class report's (:func:`planmethod.grading.report.class_statistics`). ``symbols`` prints
    the questions as the course writes them (ω₃), ``mistakes`` names each mistake in words.

    Raises
    ------
    PlanmethodError
        If the suffix is not png, svg or pdf, or the file cannot be written.
    """
    path = Path(path)
    form = plot_format(path)
    questions = [row.question for row in rows]
    names = sorted({name for row in rows for name in row.mistakes})
    with _style_context(_STYLE):
        figure = _new_figure(figsize=(11.0, 4.8), dpi=130, layout="constrained")
        axis = figure.subplots()
        positions = np.arange(len(questions))
        bottom = np.zeros(len(questions))
        series = [(render(message("right")), [row.correct for row in rows], "#1b8a3a")]
        series += [(_plain_text(render((mistakes or {}).get(name, name.replace("_", " ")))),
                    [row.mistakes.get(name, 0.0) for row in rows], None) for name in names]
        series.append((render(message("wrong, no mistake named")),
                       [row.unexplained for row in rows], "#b0b0b0"))
        for label, shares, colour in series:
            values = 100.0 * np.asarray(shares, dtype=float)
            if not values.any():
                continue           # the legend lists only what is drawn
            axis.bar(positions, values, bottom=bottom, label=label, color=colour,
                     edgecolor="white", linewidth=0.6)
            bottom += values
        axis.set_axisbelow(True)
        axis.set_xticks(positions, [_plain_text((symbols or {}).get(q, q)) for q in questions])
        axis.set_ylabel(render(message("share of the class, %")))
        axis.set_ylim(0, 100)
        axis.legend(fontsize=7.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
        axis.set_title(render(message("{title} — answers by question: right, and which "
                                      "mistake", title=_plain_text(shown_title(title)))),
                       fontsize=10.5, loc="left")
        _save(figure, path, form)
