"""The greedy planner heuristic of §3.2.9.2: pieces most proximal to the board in their current
orientations first.

The layout search (:mod:`.layout`) takes candidates in the order this heuristic gives: the lead's seconds
from the board's centre to the nearest piece of a kind it can reach, plus turning it to the rotation the
candidate needs. The first circuit found is the greedy planner's, whatever it costs.

:class:`GreedySearchEffort` is that planner's effort in a state (the search nodes it expands), for a support
agent that knows the lead's heuristic (§3.2.5's "expected search complexity").
"""

from __future__ import annotations

import math

from supportive.envs.circuits.board import Board, BoardPose
from supportive.envs.circuits.layout import LayoutSearch, Loop
from supportive.envs.circuits.world import CircuitWorld
from supportive.envs.tabletop.geometry import distance
from supportive.envs.tabletop.items import quarter_turns
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.errors import PlanningError

__all__ = ["GreedySearchEffort", "greedy_search", "proximity_order"]


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


def greedy_search(
    world: CircuitWorld, state: TabletopState[Board], max_pieces: int = 8, node_limit: int = 200_000
) -> tuple[Loop | None, int]:
    """The first circuit the greedy proximity planner finds from ``state`` (completing what is on the board),
    and the search nodes it expanded; None when it finds none within ``node_limit``."""
    cost = proximity_order(world, state)
    search = LayoutSearch(
        world.board.columns, world.board.rows, world.goal, max_pieces=max_pieces, node_limit=node_limit
    )

    def order(kind: str, pose: BoardPose) -> float:
        return cost.get((kind, pose.rotation), float("inf"))

    try:
        loop = next(search.loops(world.inventory(state), state.goal, order), None)
    except PlanningError:
        loop = None
    return loop, search.nodes


class GreedySearchEffort:
    """The greedy lead's search effort in a state: the nodes :func:`greedy_search` expands there, a
    :class:`~supportive.planning.world.LeadSearch` for the support planner.

    The search sees a state only through the board, the pieces at hand and the *order* the heuristic puts
    (kind, rotation) pairs in — their costs are only ever compared — so results are cached by those: most
    hypothetical environments move a piece without changing that order. A search asked to stop at ``limit``
    nodes is cached as a lower bound. The cache is per object (a copy sent to a worker process starts
    empty) and never changes a result.

    Args:
        world: The circuit world.
        max_pieces: The largest circuit the lead considers (as :class:`~.leads.GreedyCircuitLead`).
        node_limit: Nodes it may expand per search (as the lead).

    >>> from supportive.envs.circuits.scenario import thesis_scenario
    >>> world = thesis_scenario(0).world
    >>> effort = GreedySearchEffort(world)
    >>> nodes = greedy_search(world, world.initial_state)[1]
    >>> effort(world.initial_state) == nodes, effort(world.initial_state, limit=nodes - 1) > nodes - 1
    (True, True)
    """

    def __init__(self, world: CircuitWorld, max_pieces: int = 8, node_limit: int = 200_000) -> None:
        self.world = world
        self.max_pieces = max_pieces
        self.node_limit = node_limit
        self._exact: dict[tuple[object, ...], int] = {}
        self._above: dict[tuple[object, ...], int] = {}

    def __call__(self, state: TabletopState[Board], limit: float = math.inf) -> float:
        """Search nodes the greedy lead expands in ``state`` to find its next circuit, when at most
        ``limit``; otherwise a number above ``limit`` (the search stops there)."""
        key = self._key(state)
        exact = self._exact.get(key)
        if exact is not None:
            return float(exact)
        cap = self.node_limit if limit >= self.node_limit else math.floor(limit)
        above = self._above.get(key)
        if above is not None and above > cap:
            return float(above)
        loop, nodes = greedy_search(self.world, state, self.max_pieces, cap)
        if loop is None and nodes > cap and cap < self.node_limit:
            self._above[key] = nodes  # stopped at the cap: more than cap nodes
        else:
            self._exact[key] = nodes
        return float(nodes)

    def _key(self, state: TabletopState[Board]) -> tuple[object, ...]:
        cost = proximity_order(self.world, state)
        ranks = {value: rank for rank, value in enumerate(sorted(set(cost.values())))}
        return (
            state.goal,
            tuple(sorted(self.world.inventory(state).items())),
            tuple(sorted((pair, ranks[value]) for pair, value in cost.items())),
        )

    def __getstate__(self) -> dict[str, object]:
        return {**self.__dict__, "_exact": {}, "_above": {}}
