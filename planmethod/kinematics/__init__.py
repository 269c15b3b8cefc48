"""Exact kinematics: closed-form positions per Assur group, exact linear solves for velocities
and accelerations, vectorised over crank angles (see :mod:`planmethod.kinematics.solve`)."""

from .solve import STAGES, Branch, Curvature, GroupMotion, Motion, Sliding, choose_branches, solve

__all__ = ["STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "Sliding", "choose_branches",
           "solve"]
