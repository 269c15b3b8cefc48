"""Exact kinematics: closed-form positions per Assur group, exact linear solves for velocities
and accelerations, vectorised over crank angles (see :mod:`planmethod.kinematics.motion`)."""

from .motion import (
    STAGES,
    Branch,
    Curvature,
    GroupMotion,
    Motion,
    MotionAt,
    Sliding,
    choose_branches,
    solve,
)

__all__ = ["STAGES", "Branch", "Curvature", "GroupMotion", "Motion", "MotionAt", "Sliding",
           "choose_branches", "solve"]
