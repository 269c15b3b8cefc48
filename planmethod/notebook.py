"""Plans drawn inline in Jupyter: the position, velocity and acceleration plans display as SVG.

The plans (:mod:`planmethod.plans`) are data and know nothing of drawing; this module, at the
top of the import graph, tells IPython how to show them. ``import planmethod`` inside IPython or
Jupyter registers the formatters by itself (without importing any drawing library until a plan
is shown); ``%load_ext planmethod`` does the same explicitly.

Examples
--------
>>> class Formatter:
...     def __init__(self):
...         self.types = {}
...     def for_type_by_name(self, module, name, function):
...         self.types[module, name] = function
>>> class Shell:
...     class display_formatter:
...         formatters = {"image/svg+xml": Formatter()}
>>> register(Shell())
>>> sorted(name for _, name in Shell.display_formatter.formatters["image/svg+xml"].types)
['Plan', 'PositionPlan']
"""

from __future__ import annotations

from typing import Any

__all__ = ["register"]

#: the module the plan classes are defined in (named, so registering imports nothing)
_PLANS_MODULE = "planmethod.plans.construction"


def _plan_svg(plan: Any) -> str:
    from .render.svg import plan_svg

    return plan_svg(plan)


def _position_svg(position: Any) -> str:
    from .render.svg import position_svg

    return position_svg(position)


def register(shell: Any) -> None:
    """Show :class:`~planmethod.plans.Plan` and :class:`~planmethod.plans.PositionPlan` as
    SVG in the IPython ``shell``."""
    formatter = shell.display_formatter.formatters["image/svg+xml"]
    formatter.for_type_by_name(_PLANS_MODULE, "Plan", _plan_svg)
    formatter.for_type_by_name(_PLANS_MODULE, "PositionPlan", _position_svg)
