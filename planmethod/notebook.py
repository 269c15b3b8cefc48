"""Plans drawn inline in Jupyter: the position, velocity and acceleration plans display as SVG,
and an exercise — the model's, or the Python API's (``planmethod.load``) — displays as its
interactive workbook (``planmethod workbook``, built by the application layer).

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
...         formatters = {"image/svg+xml": Formatter(), "text/html": Formatter()}
>>> register(Shell())
>>> sorted(name for _, name in Shell.display_formatter.formatters["image/svg+xml"].types)
['Plan', 'PositionPlan']
>>> sorted(Shell.display_formatter.formatters["text/html"].types)
[('planmethod.application.api', 'Exercise'), ('planmethod.model', 'Exercise')]
"""

from __future__ import annotations

from typing import Any

__all__ = ["register"]

#: the module the plan classes are defined in (named, so registering imports nothing)
_PLANS_MODULE = "planmethod.plans.construction"

#: the module of :class:`~planmethod.model.Exercise`
_MODEL_MODULE = "planmethod.model"

#: the module of the Python API's :class:`~planmethod.application.api.Exercise`
_API_MODULE = "planmethod.application.api"

#: crank-angle step (deg) of the workbook shown inline
NOTEBOOK_STEP = 10.0


def _plan_svg(plan: Any) -> str:
    from .render.svg import plan_svg

    return plan_svg(plan)


def _position_svg(position: Any) -> str:
    from .render.svg import position_svg

    return position_svg(position)


def _exercise_html(exercise: Any) -> str:
    """The exercise's workbook in an ``<iframe>`` (its own document: its ids, style and
    script stay apart from the notebook's)."""
    import html

    from .application.workbook import build_workbook

    page = build_workbook(exercise, NOTEBOOK_STEP)
    return (f'<iframe srcdoc="{html.escape(page, quote=True)}" '
            'style="width:100%;height:900px;border:1px solid #ddd"></iframe>')


def _api_exercise_html(exercise: Any) -> str:
    """The workbook of the API's exercise (a plain exercise: a template has none), in its
    language."""
    from .words import speaking

    if exercise.model is None:
        import html

        return f"<pre>{html.escape(repr(exercise.template.source))}</pre>"
    with speaking(exercise.spoken):
        return _exercise_html(exercise.model)


def register(shell: Any) -> None:
    """Show :class:`~planmethod.plans.Plan` and :class:`~planmethod.plans.PositionPlan` as
    SVG, and :class:`~planmethod.model.Exercise` as its workbook, in the IPython ``shell``."""
    formatters = shell.display_formatter.formatters
    formatter = formatters["image/svg+xml"]
    formatter.for_type_by_name(_PLANS_MODULE, "Plan", _plan_svg)
    formatter.for_type_by_name(_PLANS_MODULE, "PositionPlan", _position_svg)
    if "text/html" in formatters:
        formatters["text/html"].for_type_by_name(_MODEL_MODULE, "Exercise", _exercise_html)
        formatters["text/html"].for_type_by_name(_API_MODULE, "Exercise", _api_exercise_html)
