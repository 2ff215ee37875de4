"""Lead policies that follow known plans (the thesis's first scenario, §3.2.9.2: a lead that knows a random
subset of Π_T and follows the best valid plan of it).

:class:`PlanFollowingLead` chooses, among the plans it knows that are still consistent with the goal area,
the one Algorithm 5 (without support) says is quickest from the current state, and follows it; it chooses
again when a step could not be finished or its plan stops being consistent. Its planning effort is the
number of plan steps it estimated.
"""

from __future__ import annotations

import time
from collections.abc import Hashable, Sequence
from typing import Generic, TypeVar

from supportive.envs.tabletop.operators import TabletopOperator
from supportive.envs.tabletop.state import TabletopState
from supportive.envs.tabletop.team import LeadStep
from supportive.envs.tabletop.world import Move, TabletopWorld
from supportive.errors import PlanningError
from supportive.planning.duration import estimate_duration
from supportive.planning.hypothetical import Hypothetical

__all__ = ["PlanFollowingLead"]

GoalT = TypeVar("GoalT")
TargetT = TypeVar("TargetT", bound=Hashable)


class PlanFollowingLead(Generic[GoalT, TargetT]):
    """Follows the quickest of the plans it knows.

    Args:
        plans: The plans the lead knows (a subset of Π_T).
    """

    def __init__(self, plans: Sequence[Sequence[TabletopOperator[TargetT]]]) -> None:
        if not plans:
            raise PlanningError("the lead must know at least one plan")
        self.plans = tuple(tuple(plan) for plan in plans)
        self.current: tuple[TabletopOperator[TargetT], ...] | None = None

    def next_step(
        self, world: TabletopWorld[GoalT, TargetT], state: TabletopState[GoalT]
    ) -> LeadStep[TargetT]:
        """The next step of the current plan; a new choice of plan first if there is none, or it no longer
        fits the goal area."""
        remaining = None if self.current is None else world.remaining_installs(state, self.current)
        if remaining:
            return LeadStep(remaining[0])
        if remaining is not None and self.current is not None:
            return LeadStep(None)
        began = time.perf_counter()
        idle = Hypothetical[TabletopState[GoalT], TabletopOperator[TargetT], Move].idle(state)
        best: tuple[float, int] | None = None
        nodes = 0
        for index, plan in enumerate(self.plans):
            steps = world.remaining_installs(state, plan)
            if steps is None:
                continue
            nodes += len(steps)
            seconds = estimate_duration(world, plan, idle, float("inf"))
            if best is None or seconds < best[0]:
                best = (seconds, index)
        elapsed = time.perf_counter() - began
        if best is None or best[0] == float("inf"):
            self.current = None
            return LeadStep(None, nodes, elapsed, replanned=True)
        self.current = self.plans[best[1]]
        steps = world.remaining_installs(state, self.current) or ()
        return LeadStep(steps[0] if steps else None, nodes, elapsed, replanned=True)

    def interrupted(self) -> None:
        """Choose again at the next step."""
        self.current = None
