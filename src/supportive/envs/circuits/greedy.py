"""The greedy planner heuristic of §3.2.9.2: pieces most proximal to the board in their current
orientations first.

The layout search (:mod:`.layout`) takes candidates in the order this heuristic gives: the lead's seconds
from the board's centre to the nearest piece of a kind it can reach, plus turning it to the rotation the
candidate needs. The first circuit found is the greedy planner's, whatever it costs.
"""

from __future__ import annotations

from supportive.envs.circuits.board import Board, BoardPose
from supportive.envs.circuits.layout import LayoutSearch, Loop
from supportive.envs.circuits.world import CircuitWorld
from supportive.envs.tabletop.geometry import distance
from supportive.envs.tabletop.items import quarter_turns
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.errors import PlanningError

__all__ = ["greedy_search", "proximity_order"]


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
