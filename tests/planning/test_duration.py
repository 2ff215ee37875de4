"""Algorithm 5 on hand-computed cases (the line world: the lead fetches to 0 at 1 unit/s)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from supportive.errors import PlanningError
from supportive.planning.duration import GeometricDecay, estimate_duration, no_decay
from supportive.planning.hypothetical import Hypothetical
from supportive.planning.problem import SupportProblem
from supportive.planning.world import SUPPORT

PENALTY = 1000.0


def support(world: Any, state: Any, plan: tuple[Any, ...]) -> Hypothetical[Any, Any, Any]:
    """ξ for ``plan`` executed by the support agent from ``state``, computed by hand from the world."""
    seconds = 0.0
    used: frozenset[Any] = frozenset()
    for op in plan:
        seconds += world.duration(state, op, SUPPORT)
        used |= world.resources(state, op, SUPPORT)
        state = world.apply(state, op, SUPPORT)
    return Hypothetical(plan, seconds, state, used)


def test_without_support_every_step_takes_its_time(line_world_type: Any) -> None:
    world = line_world_type(["a", "b"], [4.0, 6.0])
    fetch = world.plans()
    plan = (fetch[0][0], fetch[1][0])
    # a: 0 → 4 → 0 (8 s), then b: 0 → 6 → 0 (12 s)
    assert estimate_duration(world, plan, Hypothetical.idle(world.initial_state), PENALTY) == 20.0


def test_a_step_sharing_nothing_runs_while_the_support_plan_runs(line_world_type: Any) -> None:
    """The support agent (hand at 10) moves b from 6 to 1: 4 + 5 = 9 s. Fetching a shares nothing, takes 8 s,
    and leaves 1 s of the support plan; fetching b must wait that 1 s, then takes 1 + 1 s: 8 + 3 = 11."""
    world = line_world_type(["a", "b"], [4.0, 6.0])
    fetch_a, fetch_b = (p[0] for p in world.plans())
    pick, put = world.support_plan(world.initial_state, _move(world, 1, 1.0))
    xi = support(world, world.initial_state, (pick, put))
    assert xi.duration == 9.0
    assert estimate_duration(world, (fetch_a, fetch_b), xi, PENALTY) == 11.0


def test_shared_space_makes_the_lead_wait_for_the_whole_support_plan(line_world_type: Any) -> None:
    """With cells of 5 units, a (at 4) and b's new place (1) share cell 0: fetching a waits 9 s, then takes
    8 s; the support plan is over by then and fetching b takes 2 s: 9 + 8 + 2 = 19."""
    world = line_world_type(["a", "b"], [4.0, 6.0], cell=5.0)
    fetch_a, fetch_b = (p[0] for p in world.plans())
    xi = support(world, world.initial_state, world.support_plan(world.initial_state, _move(world, 1, 1.0)))
    assert estimate_duration(world, (fetch_a, fetch_b), xi, PENALTY) == 19.0


def test_a_failed_precondition_nullifies_the_plan(line_world_type: Any) -> None:
    """Moving b beyond the lead's reach (15) makes every plan with b impossible."""
    world = line_world_type(["a", "b"], [4.0, 6.0])
    fetch_a, fetch_b = (p[0] for p in world.plans())
    xi = support(world, world.initial_state, world.support_plan(world.initial_state, _move(world, 1, 18.0)))
    assert estimate_duration(world, (fetch_a, fetch_b), xi, PENALTY) == PENALTY
    assert estimate_duration(world, (fetch_a,), xi, PENALTY) == 8.0


def test_decay_weights_later_steps_less(line_world_type: Any) -> None:
    world = line_world_type(["a", "b"], [4.0, 6.0])
    fetch_a, fetch_b = (p[0] for p in world.plans())
    idle = Hypothetical[Any, Any, Any].idle(world.initial_state)
    assert (
        estimate_duration(world, (fetch_a, fetch_b), idle, PENALTY, GeometricDecay(0.5)) == 8.0 + 0.5 * 12.0
    )
    assert no_decay(7) == 1.0


def test_done_steps_are_skipped_and_a_contradicting_state_is_penalised(line_world_type: Any) -> None:
    world = line_world_type(["a", "b", "c"], [4.0, 6.0, 2.0])
    fetch_a, fetch_b, fetch_c = (p[0] for p in world.plans())
    after_a = world.apply(world.initial_state, fetch_a, "lead")
    assert estimate_duration(world, (fetch_a, fetch_b), Hypothetical.idle(after_a), PENALTY) == 12.0
    assert estimate_duration(world, (fetch_c, fetch_b), Hypothetical.idle(after_a), PENALTY) == PENALTY


def test_decay_rate_must_be_a_fraction() -> None:
    with pytest.raises(PlanningError, match="decay rate"):
        GeometricDecay(1.5)


def test_the_problem_needs_plans(line_world_type: Any) -> None:
    world = line_world_type(["a"], [4.0])
    with pytest.raises(PlanningError, match="Π_T is empty"):
        SupportProblem.of(world, [])
    with pytest.raises(PlanningError, match="empty plan"):
        SupportProblem.of(world, [()])


def _move(world: Any, item: int, x: float) -> Any:
    """The world's move of object ``item`` to ``x``."""
    moves = world.sample_moves(world.initial_state, np.random.default_rng(0), 10_000)
    return next(m for m in moves if m.item == item and m.x == x)
