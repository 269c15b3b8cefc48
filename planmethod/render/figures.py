"""Every figure of one crank angle, by file name: what ``planmethod solve --svg DIR`` writes.

This module assembles the drawings of :mod:`planmethod.render.svg` (position, velocity,
acceleration, lever) and of :mod:`planmethod.render.force_svg` (force polygons, combined force)
so that neither of those imports the other.

Examples
--------
>>> from planmethod.spec import load_exercise
>>> from planmethod.plans import draw_plans
>>> plans = draw_plans(load_exercise("exercises/compressor_slider_crank.toml"))
>>> sorted(plan_files(plans))
['acceleration.svg', 'lever.svg', 'position.svg', 'velocity.svg']
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from .force_svg import force_files
from .steady import SteadyView
from .svg import lever_svg, plan_svg, position_svg

if TYPE_CHECKING:
    from ..plans import Plans

__all__ = ["plan_files"]


def plan_files(plans: Plans, forces: Any = None, *, details: bool = True,
               loaded: bool = True, views: Mapping[str, SteadyView] | None = None
               ) -> dict[str, str]:
    """Every drawing of one crank angle: ``{"position.svg": …, "velocity.svg": …,
    "acceleration.svg": … (if drawn), "lever.svg": …}`` plus the force drawings if
    ``forces`` (an analysis's :class:`~planmethod.forces.ForceAnalysis`) is given.
    ``details`` draws the enlarged details of dense regions, ``loaded`` the loaded
    mechanism (a page of many frames, the workbook, leaves both out).

    Parameters
    ----------
    plans
        The plans of one crank angle.
    forces
        Its force analysis, for the force drawings (optional).
    details
        Draw the enlarged details of dense plan regions.
    loaded
        Draw the loaded mechanism.
    views
        Zoom and page by panel (:func:`planmethod.render.steady.steady_views`): each panel
        keeps them at every angle of a turn.
    """
    views = views or {}
    files = {"position.svg": position_svg(plans.position, plans=plans,
                                          view=views.get("position"), details=details),
             "velocity.svg": plan_svg(plans.velocity, details=details,
                                      view=views.get("velocity"))}
    if plans.acceleration is not None:
        files["acceleration.svg"] = plan_svg(plans.acceleration, details=details,
                                             view=views.get("acceleration"))
    files["lever.svg"] = lever_svg(plans, view=views.get("lever"), details=details)
    if forces is not None:
        files.update(force_files(forces, plans, loaded=loaded, details=details,
                                 views=views or None))
    return files
