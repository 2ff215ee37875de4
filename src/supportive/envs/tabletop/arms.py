"""How fast an arm moves: the motion model behind every duration estimate (§3.2.8's "rapidly computable,
low-fidelity approximation": the end effector's straight-line travel, plus fixed times to grasp, turn and
release).

The thesis pairs agents that are fast (100 % speed) or slow (33 %): ``speed_factor`` scales every motion of
an arm, travel and handling alike.

>>> arm = ArmModel("lead", home=(0.0, 0.0), speed=20.0)
>>> arm.travel((0, 0), (30, 40)), round(arm.slowed(1 / 3).travel((0, 0), (30, 40)), 6)
(2.5, 7.5)
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from supportive.envs.tabletop.geometry import Point, distance
from supportive.errors import PlanningError

__all__ = ["ArmModel"]


@dataclass(frozen=True)
class ArmModel:
    """An arm's base and motion times.

    Attributes:
        name: The agent the arm belongs to.
        home: Its base, just off the table: where it waits and the root of its arm when checking collisions.
        speed: End-effector speed at 100 %, cm/s.
        grasp: Seconds to grasp an object at 100 %.
        release: Seconds to put one down at 100 %.
        turn: Seconds per quarter turn of a held object at 100 %.
        speed_factor: 1 for a fast agent, 1/3 for a slow one; divides every duration.
    """

    name: str
    home: Point
    speed: float = 30.0
    grasp: float = 0.8
    release: float = 0.6
    turn: float = 0.8
    speed_factor: float = 1.0

    def __post_init__(self) -> None:
        if self.speed <= 0 or self.speed_factor <= 0:
            raise PlanningError(f"arm {self.name}: speed and speed_factor must be > 0")
        if min(self.grasp, self.release, self.turn) < 0:
            raise PlanningError(f"arm {self.name}: grasp, release and turn times must be >= 0")

    def slowed(self, factor: float) -> ArmModel:
        """The same arm at ``factor`` of its speed (1/3: the thesis's slow agent)."""
        return replace(self, speed_factor=factor)

    def travel(self, start: Point, end: Point) -> float:
        """Seconds to move the end effector from ``start`` to ``end``."""
        return distance(start, end) / (self.speed * self.speed_factor)

    def handling(self, grasps: int = 0, turns: int = 0, releases: int = 0) -> float:
        """Seconds for the given numbers of grasps, quarter turns and releases."""
        return (grasps * self.grasp + turns * self.turn + releases * self.release) / self.speed_factor
