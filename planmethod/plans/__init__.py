"""Plans as a student draws them: scales, the velocity and acceleration plan emulator, and the
construction steps it records (:mod:`.steps`)."""

from .construction import (
                           LinkImage,
                           Plan,
                           Plans,
                           PositionPlan,
                           draw_plans,
                           image_label,
                           position_plan,
)
from .scales import Scales, choose_scales
from .steps import DropSteps, KeepSteps, Step, StepRecorder

__all__ = ["DropSteps", "KeepSteps", "LinkImage", "Plan", "Plans", "PositionPlan", "Scales",
           "Step", "StepRecorder", "choose_scales", "draw_plans", "image_label", "position_plan"]
