"""A workshop world (the "materials retrieval" class of §3.1): a lead assembles in an area of its own, a
support agent stages parts and tools on the table — the second world of the support planner, beside the
circuits."""

from supportive.envs.workshop.chair import CHAIR_PARTS, CHAIR_TOOLS, CHAIR_TYPES, chair_plans, chair_workshop
from supportive.envs.workshop.world import Assembly, WorkshopWorld, tool_slot

__all__ = [
    "CHAIR_PARTS",
    "CHAIR_TOOLS",
    "CHAIR_TYPES",
    "Assembly",
    "WorkshopWorld",
    "chair_plans",
    "chair_workshop",
    "tool_slot",
]
