"""The state of a tabletop world: where every object is, what the goal area holds, where the hands are.

States are immutable; operators make new ones. An object is on a surface (with a pose), in the goal area,
or held by an agent (keeping the pose it was picked from, which is what its turns are counted from).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from typing import Generic, TypeVar

from supportive.envs.tabletop.geometry import Point
from supportive.envs.tabletop.items import TablePose

__all__ = ["Status", "TabletopState"]

GoalT = TypeVar("GoalT")


class Status(IntEnum):
    """Where an object is."""

    TABLE = 0
    GOAL = 1
    HELD_LEAD = 2
    HELD_SUPPORT = 3


@dataclass(frozen=True)
class TabletopState(Generic[GoalT]):
    """A tabletop world's state.

    Attributes:
        poses: Each object's pose on a surface (its last one while it is held; None once in the goal area).
        status: Each object's :class:`Status`.
        goal: What the goal area holds (a snap board, the assembled parts): the world's own type.
        hands: The lead's and the support agent's end-effector positions.
    """

    poses: tuple[TablePose | None, ...]
    status: tuple[Status, ...]
    goal: GoalT
    hands: tuple[Point, Point]

    def moved(self, item: int, pose: TablePose | None, status: Status) -> TabletopState[GoalT]:
        """The state with object ``item`` at ``pose`` with ``status``."""
        return self.changed(item, pose, status)

    def changed(
        self,
        item: int,
        pose: TablePose | None,
        status: Status,
        goal: GoalT | None = None,
        hand: tuple[bool, Point] | None = None,
    ) -> TabletopState[GoalT]:
        """The state with object ``item`` at ``pose`` with ``status`` and, when given, a new goal area and
        one hand (``(True, point)`` for the lead's, ``(False, point)`` for the support agent's) moved."""
        poses = (*self.poses[:item], pose, *self.poses[item + 1 :])
        statuses = (*self.status[:item], status, *self.status[item + 1 :])
        hands = self.hands
        if hand is not None:
            hands = (hand[1], hands[1]) if hand[0] else (hands[0], hand[1])
        return TabletopState(poses, statuses, self.goal if goal is None else goal, hands)

    def held_by(self, status: Status) -> int | None:
        """The object held with ``status`` (HELD_LEAD or HELD_SUPPORT), if any."""
        try:
            return self.status.index(status)
        except ValueError:
            return None
