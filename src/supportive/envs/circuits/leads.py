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
from supportive.envs.circuits.greedy import greedy_search
from supportive.envs.circuits.plans import loop_plan
from supportive.envs.circuits.world import CircuitWorld
from supportive.envs.tabletop.operators import Install
from supportive.envs.tabletop.state import TabletopState
from supportive.envs.tabletop.team import LeadStep
from supportive.envs.tabletop.world import TabletopWorld
from supportive.errors import PlanningError

__all__ = ["GreedyCircuitLead"]


class GreedyCircuitLead:
    """A lead that plans online with the proximity heuristic (see the module docstring).

    Args:
        max_pieces: The largest circuit it considers.
        node_limit: Search nodes it may expand per step before it gives up (and waits to try again).
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
        loop, nodes = greedy_search(world, state, self.max_pieces, self.node_limit)
        elapsed = time.perf_counter() - began
        steps = () if loop is None else world.remaining_installs(state, loop_plan(loop)) or ()
        first: Install[BoardPose] | None = steps[0] if steps else None
        return LeadStep(first, nodes, elapsed, replanned=True)

    def interrupted(self) -> None:
        """Nothing to forget: it plans afresh at every step."""
