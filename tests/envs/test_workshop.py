"""The workshop world: the support planner's core, unchanged, staging the chair's parts and tools."""

from __future__ import annotations

from typing import Any

import pytest

from supportive.envs.tabletop import Install, PlanFollowingLead, Status, run_team
from supportive.envs.workshop import CHAIR_PARTS, CHAIR_TOOLS, chair_plans, chair_workshop, tool_slot
from supportive.envs.workshop.chair import WorkshopPlan
from supportive.envs.workshop.world import WorkshopWorld
from supportive.errors import PlanningError
from supportive.planning import SupportPlanner, SupportProblem

Chair = tuple[WorkshopWorld, tuple[WorkshopPlan, ...]]


@pytest.fixture(scope="module")
def chair() -> Chair:
    return chair_workshop(0, lead=1 / 3), chair_plans(12, 0)


def test_every_plan_fetches_each_part_once_and_a_tool_before_it_is_needed(chair: Chair) -> None:
    world, plans = chair
    for plan in plans:
        slots = [op.target for op in plan if isinstance(op, Install)]
        assert sorted(s for s in slots if not s.startswith("tool:")) == sorted(CHAIR_PARTS)
        for action, tool in CHAIR_TOOLS.items():
            assert slots.index(tool_slot(tool)) < slots.index(action)
        state = world.initial_state
        for op in plan:
            assert world.preconditions_hold(state, op, "lead")
            state = world.apply(state, op, "lead")
        assert world.goal_reached(state)


def test_a_step_waits_for_its_tool(chair: Chair) -> None:
    world, _ = chair
    state = world.initial_state
    assert not world.preconditions_hold(state, Install("nut", "tighten_nut_fl"), "lead")
    with_key = world.apply(state, Install("hex_key", tool_slot("hex_key")), "lead")
    assert world.preconditions_hold(with_key, Install("nut", "tighten_nut_fl"), "lead")
    assert not world.preconditions_hold(with_key, Install("bolt", "tighten_nut_fl"), "lead")


def test_the_support_agent_stages_materials_and_never_touches_the_assembly(chair: Chair) -> None:
    world, plans = chair
    state = world.initial_state
    for op in plans[0][:3]:
        state = world.apply(state, op, "lead")
    problem = SupportProblem.of(world, plans, state)
    decision = SupportPlanner[Any, Any, Any]("conservative", environments=80).fit(problem).decide(problem, seed=2)
    assembled = {i for i, s in enumerate(state.status) if s is Status.GOAL}
    assert decision.helps and decision.expected_saving > 0
    assert all(op.item not in assembled for env in decision.candidates.environments for op in env.plan)
    assert decision.candidates.discarded.get("precondition", 0) > 0  # assembled parts cannot be picked up
    target = world.layout.goal_area
    before = state.poses[decision.chosen.plan[0].item]
    after = decision.chosen.plan[1].pose
    assert before is not None

    def gap(point: tuple[float, float]) -> float:
        return float(max(target.x0 - point[0], point[0] - target.x1, 0) + max(target.y0 - point[1], point[1] - target.y1, 0))

    assert gap(after.point) < gap(before.point)  # the part comes nearer the assembly area


def test_with_support_the_slow_assembler_finishes_sooner(chair: Chair) -> None:
    world, plans = chair
    alone = run_team(world, PlanFollowingLead(plans))
    problem = SupportProblem.of(world, plans)
    with SupportPlanner[Any, Any, Any]("conservative", environments=60).fit(problem) as planner:
        helped = run_team(world, PlanFollowingLead(plans), planner, plans, seed=1)
    assert alone.completed and helped.completed and helped.support_actions > 0
    assert helped.makespan < alone.makespan


def test_assembled_parts_stay(chair: Chair) -> None:
    world, plans = chair
    state = world.apply(world.initial_state, plans[0][0], "lead")
    item = next(i for i, s in enumerate(state.status) if s is Status.GOAL)
    assert not world.can_release(state.goal, item)
    with pytest.raises(PlanningError, match="stays"):
        world.release(state.goal, item)
