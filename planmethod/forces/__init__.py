"""Kinetostatics: inertia and the combined force, reactions group by group, the balancing
moment, and three checks (the whole-system solve, Zhukovsky's lever, the power balance).

:func:`analyse_forces` is what :func:`planmethod.report.analyse` calls for one crank angle;
:func:`solve_forces` works over any array of angles; :func:`force_columns` feeds
``planmethod sweep --forces``. See docs/kinetostatics.md.
"""

from .analysis import ForceAnalysis, ForceSolution, analyse_forces, force_columns, solve_forces

__all__ = ["ForceAnalysis", "ForceSolution", "analyse_forces", "force_columns", "solve_forces"]
