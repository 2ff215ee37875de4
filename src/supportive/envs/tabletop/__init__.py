"""Tabletop worlds for supportive-behavior planning: a lead building in a goal area of its own, a support
agent rearranging the shared table around it (§3.2.9.1), and the two working at once."""

from supportive.envs.tabletop.arms import ArmModel
from supportive.envs.tabletop.geometry import Point, Rect, distance, segment_distance
from supportive.envs.tabletop.items import Item, ItemType, TablePose, quarter_turns
from supportive.envs.tabletop.layout import TableLayout
from supportive.envs.tabletop.leads import PlanFollowingLead
from supportive.envs.tabletop.operators import Install, Pick, Put, TabletopOperator
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.envs.tabletop.team import Event, LeadPolicy, LeadStep, TeamResult, run_team
from supportive.envs.tabletop.world import Move, TabletopWorld

__all__ = [
    "ArmModel",
    "Event",
    "Install",
    "Item",
    "ItemType",
    "LeadPolicy",
    "LeadStep",
    "Move",
    "Pick",
    "PlanFollowingLead",
    "Point",
    "Put",
    "Rect",
    "Status",
    "TableLayout",
    "TablePose",
    "TabletopOperator",
    "TabletopState",
    "TabletopWorld",
    "TeamResult",
    "distance",
    "quarter_turns",
    "run_team",
    "segment_distance",
]
