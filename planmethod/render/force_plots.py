"""Force curves over the full turn (seed 000's figures 8–14) and seed 003's parameter study.

Both draw with matplotlib (Agg backend, imported here only) and write through
:func:`planmethod.io.atomic_path`, the format from the file's suffix (png, svg, pdf). The style
is fixed and no date is written, so the output is reproducible.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

__all__ = ["save_force_plot", "save_study_plot"]

COLOURS = {"x": "#1f77b4", "y": "#d62728", "magnitude": "#222222", "moment": "#2ca02c"}


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3,
                         "svg.hashsalt": "planmethod", "svg.fonttype": "none"})
    return plt


def _save(figure, path) -> None:
    from ..io import atomic_path

    suffix = Path(path).suffix.lower().lstrip(".") or "png"
    metadata = {"png": {"Software": None}, "svg": {"Date": None},
                "pdf": {"CreationDate": None, "ModDate": None}}.get(suffix)
    with atomic_path(path) as temporary:
        figure.savefig(temporary, format=suffix, dpi=130, metadata=metadata)


def save_force_plot(table: dict, path, *, title: str) -> None:
    """Reaction components and magnitude per pair and the balancing moment versus crank angle,
    from the columns of ``planmethod sweep --forces`` (``Rx_K Ry_K R_K [M_K]``, ``M_b``…)."""
    plt = _pyplot()
    angles = np.asarray(table["angle"], float)
    pairs = [name[2:] for name in table if name.startswith("R_")]
    panels = len(pairs) + 1
    columns = 2
    rows = math.ceil(panels / columns)
    figure, axes = plt.subplots(rows, columns, figsize=(11, 2.4 * rows + 0.6), sharex=True,
                                squeeze=False)
    flat = axes.ravel()
    for axis, key in zip(flat, pairs, strict=False):
        axis.plot(angles, table[f"Rx_{key}"], color=COLOURS["x"], lw=1.2, label="Rx")
        axis.plot(angles, table[f"Ry_{key}"], color=COLOURS["y"], lw=1.2, label="Ry")
        axis.plot(angles, table[f"R_{key}"], color=COLOURS["magnitude"], lw=1.6, label="|R|")
        axis.set_title(f"pair {key}", loc="left")
        axis.set_ylabel("N")
        if f"M_{key}" in table:
            twin = axis.twinx()
            twin.plot(angles, table[f"M_{key}"], color=COLOURS["moment"], lw=1.0, ls="--",
                      label="couple")
            twin.set_ylabel("couple, N·m", color=COLOURS["moment"])
            twin.grid(False)
        axis.legend(loc="best", fontsize=7, ncol=3)
    axis = flat[len(pairs)]
    axis.plot(angles, table["M_b"], color="#9467bd", lw=1.8, label="M_b (groups)")
    if "M_b_system" in table:
        axis.plot(angles, table["M_b_system"], color="#ff7f0e", lw=0.9, ls=":",
                  label="M_b (whole system)")
    if "M_b_no_friction" in table:
        axis.plot(angles, table["M_b_no_friction"], color="#8c564b", lw=1.2, ls="--",
                  label="M_b without friction")
    axis.set_title("balancing moment on the crank", loc="left")
    axis.set_ylabel("N·m")
    axis.legend(loc="best", fontsize=7)
    for extra in flat[panels:]:
        extra.set_visible(False)
    for axis in axes[-1]:
        axis.set_xlabel("crank angle φ1, deg")
    for axis in flat[:panels]:
        axis.set_xlim(angles[0], angles[-1])
        axis.xaxis.set_tick_params(labelbottom=True)
    figure.suptitle(f"{title} — reactions and balancing moment over the turn", fontsize=11)
    figure.tight_layout()
    _save(figure, path)
    plt.close(figure)


def save_study_plot(study, path) -> None:
    """Seed 003's study: the largest reaction in each pair against each parameter (the other
    two at their base values), one panel per parameter."""
    plt = _pyplot()
    parameters = study.parameters
    figure, axes = plt.subplots(1, len(parameters), figsize=(4.2 * len(parameters), 4.2),
                                squeeze=False, sharey=True)
    markers = "osD^v<>p"
    for axis, parameter in zip(axes[0], parameters, strict=True):
        values = study.values[parameter.name]
        for index, pair in enumerate(study.pairs):
            axis.plot(values, study.maxima[parameter.name][pair], marker=markers[index % 8],
                      lw=1.4, label=f"R_{pair} max")
        axis.set_xlabel(f"{parameter.label}, {parameter.unit}")
        axis.set_ylabel("largest reaction over the turn, N")
        change = study.relative_change(parameter.name)
        axis.set_title(f"{parameter.label}: up to {100 * change:.0f} % change", loc="left",
                       fontsize=9)
        axis.legend(fontsize=7)
    figure.suptitle(f"{study.title}\nlargest reactions over a turn against each parameter, "
                    f"the others at the base case: {study.base_text()}", fontsize=10)
    figure.tight_layout()
    _save(figure, path)
    plt.close(figure)
