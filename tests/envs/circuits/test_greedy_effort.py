"""The greedy lead's search effort as the support planner sees it: exactly greedy_search's nodes, cached or
not, cut short only above a limit."""

from __future__ import annotations

import pickle

import pytest

from supportive.envs.circuits.greedy import GreedySearchEffort, greedy_search
from supportive.envs.circuits.scenario import thesis_scenario
from supportive.planning.hypothetical import hypothetical_environments
from supportive.planning.problem import SupportProblem


@pytest.mark.parametrize("layout", [0, 4])
def test_effort_is_the_greedy_search_nodes_in_every_hypothetical_environment(layout: int) -> None:
    scenario = thesis_scenario(layout, environments=40)
    world = scenario.world
    problem = SupportProblem.of(world, scenario.plans())
    states = [h.state for h in hypothetical_environments(problem, 40, seed=layout).environments]
    effort = GreedySearchEffort(world)
    direct = [greedy_search(world, s)[1] for s in states]
    assert [effort(s) for s in states] == [float(n) for n in direct]  # cold cache
    assert [effort(s) for s in states] == [float(n) for n in direct]  # warm cache
    assert len(effort._exact) < len(states)  # many moves leave the heuristic's order alone


def test_a_limit_stops_the_search_but_never_changes_an_exact_answer() -> None:
    world = thesis_scenario(2).world
    nodes = greedy_search(world, world.initial_state)[1]
    effort = GreedySearchEffort(world)
    assert effort(world.initial_state, limit=nodes // 2) > nodes // 2  # stopped early: a bound, not a value
    assert effort(world.initial_state, limit=nodes) == nodes  # exact at the limit
    assert effort(world.initial_state, limit=1) == nodes  # known exactly now: returned whatever the limit
    again = pickle.loads(pickle.dumps(effort))
    assert again._exact == {} and again(world.initial_state) == nodes  # a copy starts with an empty cache
