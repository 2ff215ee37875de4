"""The thesis's second lead (§3.2.9.2): it solves the task online with a greedy planner heuristic.

Before every step it searches for a circuit that completes what is already on the board, trying pieces in
order of how near the board the nearest piece of a kind lies and how far it would have to be turned — "pieces
most proximal to the board in their current orientations, before branching out to explore more spatially or
rotationally distant alternatives" — and takes the first circuit it finds, whatever it costs. Its planning
effort is the search nodes it expands, over the whole task.
"""

from __future__ import annotations

import time

from supportive.envs.circuits.board import Board, BoardPose
from supportive.envs.circuits.layout import LayoutSearch
from supportive.envs.circuits.plans import loop_plan
from supportive.envs.circuits.world import CircuitWorld
from supportive.envs.tabletop.geometry import distance
from supportive.envs.tabletop.items import quarter_turns
from supportive.envs.tabletop.operators import Install
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.envs.tabletop.team import LeadStep
from supportive.envs.tabletop.world import TabletopWorld
from supportive.errors import PlanningError

__all__ = ["GreedyCircuitLead", "proximity_order"]


def proximity_order(world: CircuitWorld, state: TabletopState[Board]) -> dict[tuple[str, int], float]:
    """The greedy heuristic's cost of placing a piece of each kind at each rotation: the lead's seconds from
    the board's centre to the nearest piece of that kind it can reach, plus turning it; kinds it cannot reach
    are left out."""
    arm = world.lead_arm
    centre = world.board.area.center
    cost: dict[tuple[str, int], float] = {}
    for index, item in enumerate(world.items):
        pose = state.poses[index]
        if (
            state.status[index] is not Status.TABLE
            or pose is None
            or not world.reachable(state, "lead", index)
        ):
            continue
        symmetric = world.types[item.kind].symmetric
        reach = distance(centre, pose.point) / (arm.speed * arm.speed_factor)
        for rotation in range(4):
            value = reach + arm.handling(turns=quarter_turns(pose.rotation, rotation, symmetric))
            key = (item.kind, rotation)
            cost[key] = min(cost.get(key, value), value)
    return cost


class GreedyCircuitLead:
    """A lead that plans online with the proximity heuristic (see the module docstring).

    Args:
        max_pieces: The largest circuit it considers.
        node_limit: Search nodes it may expand per step before it gives up.
    """

    def __init__(self, max_pieces: int = 8, node_limit: int = 200_000) -> None:
        self.max_pieces = max_pieces
        self.node_limit = node_limit

    def next_step(
        self, world: TabletopWorld[Board, BoardPose], state: TabletopState[Board]
    ) -> LeadStep[BoardPose]:
        """Search for a circuit completing the board; its first piece still to place.

        Raises:
            PlanningError: when ``world`` is not a circuit world.
        """
        if not isinstance(world, CircuitWorld):
            raise PlanningError("the greedy circuit lead plans in a circuit world")
        began = time.perf_counter()
        cost = proximity_order(world, state)
        search = LayoutSearch(
            world.board.columns,
            world.board.rows,
            world.goal,
            max_pieces=self.max_pieces,
            node_limit=self.node_limit,
        )

        def order(kind: str, pose: BoardPose) -> float:
            return cost.get((kind, pose.rotation), float("inf"))

        try:
            loop = next(search.loops(world.inventory(state), state.goal, order), None)
        except PlanningError:
            loop = None
        elapsed = time.perf_counter() - began
        if loop is None:
            return LeadStep(None, search.nodes, elapsed, replanned=True)
        steps = world.remaining_installs(state, loop_plan(loop)) or ()
        first: Install[BoardPose] | None = steps[0] if steps else None
        return LeadStep(first, search.nodes, elapsed, replanned=True)

    def interrupted(self) -> None:
        """Nothing to forget: it plans afresh at every step."""
