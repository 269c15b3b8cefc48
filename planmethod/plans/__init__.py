"""Plans as a student draws them: scales, the velocity and acceleration plan emulator."""

from .construction import LinkImage, Plan, Plans, PositionPlan, Step, draw_plans, image_label
from .scales import Scales, choose_scales

__all__ = ["LinkImage", "Plan", "Plans", "PositionPlan", "Scales", "Step", "choose_scales",
           "draw_plans", "image_label"]
