"""The known plan set Π_T of a circuit task: every loop the layout planner finds with the table's pieces,
as build-order lead plans, the quickest first (Algorithm 5 without support in s_0).

Which loops exist depends only on the board, the goal and how many pieces of each kind there are, so the
enumeration is remembered for those; the ranking depends on where the pieces lie.
"""

from __future__ import annotations

from collections import Counter
from functools import lru_cache

import numpy as np

from supportive.envs.circuits.board import BoardPose
from supportive.envs.circuits.goals import CircuitGoal
from supportive.envs.circuits.greedy import greedy_search
from supportive.envs.circuits.layout import LayoutSearch, Loop
from supportive.envs.circuits.world import CircuitState, CircuitWorld
from supportive.envs.tabletop.operators import Install, TabletopOperator
from supportive.envs.tabletop.world import Move
from supportive.errors import PlanningError
from supportive.planning.duration import estimate_duration
from supportive.planning.hypothetical import Hypothetical

__all__ = ["CircuitPlan", "known_plans", "loop_plan"]

CircuitPlan = tuple[TabletopOperator[BoardPose], ...]
"""A lead plan of the circuit world: Install steps in build order."""


def loop_plan(loop: Loop) -> CircuitPlan:
    """The lead plan that builds ``loop``: one Install per piece, level 0 first."""
    return tuple(Install(segment.kind, segment.pose) for segment in loop.build_order)


@lru_cache(maxsize=32)
def _loops(
    columns: int,
    rows: int,
    goal: CircuitGoal,
    inventory: tuple[tuple[str, int], ...],
    max_pieces: int,
    search_limit: int,
) -> tuple[Loop, ...]:
    search = LayoutSearch(columns, rows, goal, max_pieces=max_pieces, node_limit=search_limit)
    return tuple(search.loops(dict(inventory)))


def known_plans(
    world: CircuitWorld,
    quickest: int = 15,
    spread: int = 15,
    *,
    max_pieces: int = 6,
    search_limit: int,
    greedy: bool = True,
) -> tuple[CircuitPlan, ...]:
    """Π_T: a set of plans that represents the ways the task can be done, good and bad.

    Every loop of at most ``max_pieces`` pieces that the world's pieces allow is ranked by Algorithm 5 in
    s_0 without support (ties keep the search's order); Π_T holds the ``quickest`` first ones, ``spread``
    more taken evenly from the rest of the ranking down to the slowest, and (with ``greedy``) the circuit the
    greedy proximity planner of §3.2.9.2 builds from s_0, which may be larger than ``max_pieces``.

    The enumeration grows fast with ``max_pieces`` and the pieces at hand (the thesis-size table: 83,428
    pieces tried and 2,820 loops for 6 pieces, 1,650,413 and 64,548 for 8); it stops after trying
    ``search_limit`` pieces.

    Raises:
        PlanningError: when the pieces allow no circuit that meets the goal.
        SearchLimitError: when the enumeration tried ``search_limit`` pieces before it was complete.
    """
    state = world.initial_state
    inventory = tuple(sorted(Counter(item.kind for item in world.items).items()))
    loops = _loops(world.board.columns, world.board.rows, world.goal, inventory, max_pieces, search_limit)
    if not loops:
        raise PlanningError(
            f"no circuit of at most {max_pieces} pieces meets the goal ({world.goal.text}) with these pieces"
        )
    idle = Hypothetical[CircuitState, TabletopOperator[BoardPose], Move].idle(state)
    plans = [loop_plan(loop) for loop in loops]
    durations = [estimate_duration(world, plan, idle, float("inf")) for plan in plans]
    order = sorted(range(len(plans)), key=lambda i: (durations[i], i))
    chosen = order[:quickest]
    rest = order[quickest:]
    if spread and rest:
        picks = np.unique(np.linspace(0, len(rest) - 1, min(spread, len(rest))).round().astype(int))
        chosen += [rest[i] for i in picks]
    known = [plans[i] for i in chosen]
    if greedy:
        loop, _ = greedy_search(world, state)
        if loop is not None and loop_plan(loop) not in known:
            known.append(loop_plan(loop))
    return tuple(known)
