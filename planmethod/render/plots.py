"""Full-turn curves of a sweep table, drawn with matplotlib (Agg, imported only when used).

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

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ..errors import PlanmethodError
from ..io import atomic_path

__all__ = ["FORMATS", "panels", "save_sweep_plot"]

#: file formats by suffix
FORMATS = {".png": "png", ".svg": "svg", ".pdf": "pdf"}

#: (column prefix, panel title, y-axis label); a column joins the first panel whose prefix
#: it has
_PANELS = (
    ("v_", "speed of points |v|", "m/s"),
    ("a_", "acceleration of points |a|", "m/s²"),
    ("omega_", "angular velocity ω of links", "rad/s"),
    ("epsilon_", "angular acceleration ε of links", "rad/s²"),
    ("s_", "travel s of prismatic pairs", "m"),
    ("ds_", "sliding velocity ds/dt", "m/s"),
    ("dds_", "sliding acceleration d²s/dt²", "m/s²"),
    ("rho_", "radius of curvature ρ", "m"),
)
_LEFT_TO_CSV = ("x_", "y_", "vx_", "vy_", "ax_", "ay_", "theta_")

_STYLE = {
    "font.family": "DejaVu Sans",
    "font.size": 9.0,
    "axes.grid": True,
    "grid.alpha": 0.35,
    "axes.prop_cycle": None,       # set below from a fixed colour list
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


def panels(table: Mapping[str, np.ndarray]) -> list[tuple[str, str, list[str]]]:
    """The panels a table is drawn in: ``(title, unit, columns)``, empty panels left out.

    Examples
    --------
    >>> panels({"angle": [0, 1], "v_C": [1, 2], "a_C": [0, 0], "x_C": [0, 0], "Mb": [1, 1]})
    [('speed of points |v|', 'm/s', ['v_C']), ('acceleration of points |a|', 'm/s²', \
['a_C']), ('other columns', 'SI units', ['Mb'])]
    """
    grouped: dict[str, list[str]] = {prefix: [] for prefix, _, _ in _PANELS}
    other: list[str] = []
    for name, values in table.items():
        if name == "angle" or name.startswith(_LEFT_TO_CSV):
            continue
        array = np.asarray(values)
        if array.dtype.kind not in "fiu":
            continue
        # longest matching prefix wins: dds_ before ds_ before s_
        prefix = max((p for p, _, _ in _PANELS if name.startswith(p)), key=len, default=None)
        (grouped[prefix] if prefix else other).append(name)
    out = [(title, unit, grouped[prefix]) for prefix, title, unit in _PANELS
           if grouped[prefix]]
    if other:
        out.append(("other columns", "SI units", other))
    return out


def save_sweep_plot(table: Mapping[str, np.ndarray], path: str | Path, *, title: str) -> None:
    """Draw a sweep table's curves against the crank angle into ``path`` (.png, .svg, .pdf).

    Raises
    ------
    PlanmethodError
        If the suffix is not one of png, svg, pdf, the table has no ``angle`` column or no
        column to draw, or the file cannot be written. No file is left behind.
    """
    path = Path(path)
    form = FORMATS.get(path.suffix.lower())
    if form is None:
        raise PlanmethodError(f"a plot is written as .png, .svg or .pdf, got "
                              f"'{path.suffix or path.name}'", file=str(path))
    if "angle" not in table:
        raise PlanmethodError("the sweep table has no 'angle' column", file=str(path))
    angle = np.asarray(table["angle"], dtype=float)
    groups = panels(table)
    if angle.size == 0 or not groups:
        raise PlanmethodError("the sweep table has nothing to plot", file=str(path))
    for _, _, columns in groups:
        for name in columns:
            if np.shape(table[name]) != angle.shape:
                raise PlanmethodError(f"column {name!r} has {np.size(table[name])} values for "
                                      f"{angle.size} angles", file=str(path))

    import matplotlib

    matplotlib.use("Agg", force=False)
    from cycler import cycler
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    style = dict(_STYLE, **{"axes.prop_cycle": cycler(color=list(_COLOURS))})
    count = len(groups)
    columns_of_panels = 1 if count == 1 else 2
    rows = -(-count // columns_of_panels)
    with matplotlib.rc_context(style):
        figure = Figure(figsize=(6.0 * columns_of_panels, 2.6 * rows + 0.6), dpi=120,
                        layout="constrained")
        FigureCanvasAgg(figure)
        axes = figure.subplots(rows, columns_of_panels, squeeze=False, sharex=True)
        for index, (panel, unit, columns) in enumerate(groups):
            ax = axes[index // columns_of_panels][index % columns_of_panels]
            for name in columns:
                values = np.asarray(table[name], dtype=float)
                if panel.startswith("radius"):
                    values = np.where(np.isfinite(values) & (np.abs(values) > 0),
                                      np.abs(values), np.nan)
                ax.plot(angle, values, label=name)
            if panel.startswith("radius"):
                radii = np.abs(np.asarray([table[c] for c in columns], dtype=float))
                radii = radii[np.isfinite(radii) & (radii > 0)]
                if radii.size and radii.max() > 30 * radii.min():   # spans decades
                    ax.set_yscale("log")
            ax.set_title(panel, fontsize=9.5)
            ax.set_ylabel(unit if not panel.startswith("radius") else "|ρ|, m")
            ax.legend(fontsize=7.5, loc="best", ncols=min(3, len(columns)), frameon=False)
            ax.set_xlim(float(angle.min()), float(angle.max()) if angle.size > 1
                        else float(angle.min()) + 1.0)
        for index in range(count, rows * columns_of_panels):
            axes[index // columns_of_panels][index % columns_of_panels].set_visible(False)
        for ax in axes[-1]:
            ax.set_xlabel("crank angle φ₁, °")
        if count > 1 and count % 2 == 1:
            axes[-2][1].set_xlabel("crank angle φ₁, °")
            axes[-2][1].xaxis.set_tick_params(labelbottom=True)
        if angle.min() >= 0 and angle.max() <= 360 and np.ptp(angle) >= 90:
            axes[0][0].set_xticks(np.arange(0.0, 361.0, 45.0))     # shared by every panel
        figure.suptitle(f"{title} — full turn", fontsize=11, fontweight="bold")
        with atomic_path(path) as temporary:
            figure.savefig(temporary, format=form, metadata=_METADATA[form])
