"""The tabletop world on the circuit table: binding, operators, prohibited moves, and the team simulation
agreeing with Algorithm 5 when the lead works alone."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.envs.circuits.scenario import thesis_scenario
from supportive.envs.tabletop import Install, Pick, PlanFollowingLead, Put, Status, TablePose, run_team
from supportive.envs.tabletop.items import quarter_turns
from supportive.errors import PlanningError
from supportive.planning import Hypothetical, SupportPlanner, SupportProblem, estimate_duration
from supportive.planning.prototypes import Prototype, matching


def test_install_binds_the_object_reached_soonest(thesis_table: tuple[Any, Any]) -> None:
    scenario, plans = thesis_table
    world = scenario.world
    state = world.initial_state
    op = plans[0][0]
    item = world.bind(state, op)
    assert item is not None and world.items[item].kind == op.kind
    others = [i for i, it in enumerate(world.items) if it.kind == op.kind and i != item]
    for other in others:  # moving the other piece of that kind next to the target makes it the one bound
        target = world.target_point(op.target)
        near = world.nearest_free_pose(state, other, (target[0], target[1] - 14), op.target.rotation)
        assert near is not None
        closer = state.changed(other, near, Status.TABLE)
        assert world.bind(closer, op) == other


def test_an_installs_duration_is_the_agents_travel_to_the_bound_object_and_on_to_its_target(
    thesis_table: tuple[Any, Any],
) -> None:
    scenario, plans = thesis_table
    world = scenario.world
    state = world.initial_state
    op = plans[0][0]
    target = world.target_point(op.target)
    symmetric = world.types[op.kind].symmetric

    def expected(state: Any, agent: str) -> float:  # from the definitions, for the object the lead binds
        pose = state.poses[world.bind(state, op)]
        arm, hand = (world.lead_arm, state.hands[0]) if agent == "lead" else (world.support_arm, state.hands[1])
        speed = arm.speed * arm.speed_factor
        turns = quarter_turns(pose.rotation, op.target.rotation, symmetric)
        handling = (arm.grasp + turns * arm.turn + arm.release) / arm.speed_factor
        return float(math.dist(hand, pose.point) / speed + math.dist(pose.point, target) / speed + handling)

    for agent in ("lead", "support"):
        assert world.duration(state, op, agent) == pytest.approx(expected(state, agent), rel=1e-12)
    item = world.bind(state, op)
    pose = state.poses[item]
    turned = state.changed(item, TablePose(pose.x, pose.y, (pose.rotation + 1) % 4), Status.TABLE)
    assert world.duration(turned, op, "lead") == pytest.approx(expected(turned, "lead"), rel=1e-12)
    assert world.duration(turned, op, "lead") != world.duration(state, op, "lead")  # nothing kept from another state


def test_a_plan_applied_step_by_step_reaches_the_goal(thesis_table: tuple[Any, Any]) -> None:
    scenario, plans = thesis_table
    world = scenario.world
    for plan in plans[:5]:
        state = world.initial_state
        for op in plan:
            assert world.preconditions_hold(state, op, "lead")
            state = world.apply(state, op, "lead")
        assert world.goal_reached(state) and world.remaining_installs(state, plan) == ()
        assert len(state.goal) == len(plan)


def test_support_operators_and_their_effects(thesis_table: tuple[Any, Any]) -> None:
    scenario, plans = thesis_table
    world = scenario.world
    state = world.apply(world.initial_state, plans[0][0], "lead")
    on_board = next(i for i, s in enumerate(state.status) if s is Status.GOAL)
    name = world.items[on_board].id
    assert world.holds(state, ("on_board", name)) and world.holds(state, ("removable", name))
    effects = world.effects(state, Pick(on_board), "support")
    assert matching(effects, [Prototype.parse("on_board(*)")])
    free = next(i for i, s in enumerate(state.status) if s is Status.TABLE)
    assert not matching(world.effects(state, Pick(free), "support"), [Prototype.parse("on_board(*)")])
    held = world.apply(state, Pick(free), "support")
    assert world.holds(held, ("holding", "support", world.items[free].id))
    spot = world.nearest_free_pose(held, free, (10.0, 60.0), 0)
    assert spot is not None and world.preconditions_hold(held, Put(free, spot), "support")
    x, y = world.board.area.center
    assert not world.preconditions_hold(held, Put(free, TablePose(x, y, 0)), "support")
    with pytest.raises(PlanningError, match="unknown predicate"):
        world.holds(state, ("floating", name))


@settings(max_examples=8)
@given(seed=st.integers(0, 10_000), scheme=st.sampled_from(["conservative", "greedy", "aggressive"]))
def test_prohibited_operators_are_never_chosen(seed: int, scheme: str) -> None:
    """With pieces on the board, the support agent never plans to touch them under P = on_board(*), though
    it samples them; with P empty such moves are attainable."""
    scenario = thesis_scenario(seed % 7, environments=40, scheme=scheme)
    plans = scenario.plans()
    world = scenario.world
    state = world.initial_state
    for op in plans[0][:2]:
        state = world.apply(state, op, "lead")
    problem = SupportProblem.of(world, plans, state)
    decision = SupportPlanner[Any, Any, Any](scheme, environments=40).fit(problem).decide(problem, seed)
    touched = {op.item for env in decision.candidates.environments for op in env.plan}
    assert not touched & {i for i, s in enumerate(state.status) if s is Status.GOAL}
    # whether 40 samples propose a prohibited move depends on the draw; with 400 they always do
    many = SupportPlanner[Any, Any, Any](scheme, environments=400).fit(problem).decide(problem, seed)
    assert many.candidates.discarded.get("prohibited", 0) > 0
    free = SupportProblem.of(world, plans, state, prohibited=[])
    found = SupportPlanner[Any, Any, Any](scheme, environments=400).fit(free).decide(free, seed).candidates
    assert any(
        state.status[op.item] is Status.GOAL
        for env in found.environments
        for op in env.plan
        if isinstance(op, Pick)
    )


def test_decisions_are_the_same_for_the_same_seed_in_process_or_in_two_processes(
    thesis_table: tuple[Any, Any],
) -> None:
    scenario, plans = thesis_table
    problem = SupportProblem.of(scenario.world, plans)
    alone = SupportPlanner[Any, Any, Any]("conservative", environments=40).fit(problem).decide(problem, seed=5)
    again = SupportPlanner[Any, Any, Any]("conservative", environments=40).fit(problem).decide(problem, seed=5)
    with SupportPlanner[Any, Any, Any]("conservative", environments=40, workers=2).fit(problem) as planner:
        shared = planner.decide(problem, seed=5)
    assert alone.scores == again.scores == shared.scores and alone.chosen == shared.chosen


def test_alone_the_simulated_makespan_is_algorithm_5s_estimate(thesis_table: tuple[Any, Any]) -> None:
    """A plan-following lead alone moves exactly as the motion model says: the simulated makespan equals
    Algorithm 5 without support, up to one clock tick."""
    scenario, plans = thesis_table
    for lead_speed in (1.0, 1 / 3):
        world = scenario.world.with_speeds(lead_speed, 1.0)
        result = run_team(world, PlanFollowingLead(plans))
        best = min(estimate_duration(world, p, Hypothetical.idle(world.initial_state), np.inf) for p in plans)
        assert result.completed and abs(result.makespan - best) <= 0.05 + 1e-9
        assert result.lead_steps == 4 and result.support_actions == 0 and not result.conflicts


def test_with_support_the_run_finishes_and_is_deterministic(thesis_table: tuple[Any, Any]) -> None:
    scenario, plans = thesis_table
    world = scenario.world.with_speeds(1 / 3, 1.0)
    runs = []
    for _ in range(2):
        with SupportPlanner[Any, Any, Any]("conservative", environments=40).fit(SupportProblem.of(world, plans)) as planner:
            runs.append(run_team(world, PlanFollowingLead(plans), planner, plans, seed=3, record=True))
    first, second = runs
    assert first.completed and first.support_actions > 0 and first.support_decisions >= first.support_actions
    assert (first.makespan, first.events, first.final) == (second.makespan, second.events, second.final)
    assert all(world.goal_reached(r.final) for r in runs if r.final is not None)


def test_the_support_agent_yields_to_the_lead_in_a_collision(thesis_table: tuple[Any, Any]) -> None:
    """Arms of 60 cm buffer always collide once both are out: the support agent gives way, the lead never."""
    scenario, plans = thesis_table
    world = scenario.world.with_speeds(1 / 3, 1.0)
    with SupportPlanner[Any, Any, Any]("conservative", environments=40).fit(SupportProblem.of(world, plans)) as planner:
        result = run_team(world, PlanFollowingLead(plans), planner, plans, seed=3, buffer=60.0)
    assert (
        result.completed and result.conflicts["support yielded"] > 0 and result.conflicts["lead yielded"] == 0
    )


def test_bad_simulation_settings(thesis_table: tuple[Any, Any]) -> None:
    scenario, plans = thesis_table
    with pytest.raises(PlanningError):
        run_team(scenario.world, PlanFollowingLead(plans), dt=0.0)
    with pytest.raises(PlanningError, match="at least one plan"):
        PlanFollowingLead([])


def test_install_operators_name_their_prototype(thesis_table: tuple[Any, Any]) -> None:
    scenario, plans = thesis_table
    op = plans[0][0]
    assert isinstance(op, Install) and op.name == "install" and Pick(0).name == "pick"
    assert scenario.world.describe(op).startswith(f"install a {op.kind} at (")
