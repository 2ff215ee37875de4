"""Plan weights (§3.2.6) and what each scheme makes the support agent do in the line world."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import PlanningError
from supportive.planning.problem import SupportProblem
from supportive.planning.selection import SupportPlanner
from supportive.planning.weighting import plan_weights


def test_conservative_weights_are_the_squared_ratio_to_the_best() -> None:
    assert plan_weights([16.0, 18.0, 24.0], "conservative").tolist() == pytest.approx(
        [1.0, (16 / 18) ** 2, (16 / 24) ** 2]
    )


def test_greedy_weights_keep_only_the_best() -> None:
    assert plan_weights([16.0, 18.0, 16.0], "greedy").tolist() == [1.0, 0.0, 1.0]


def test_aggressive_weights_are_negative_beyond_epsilon_and_smaller_in_sum() -> None:
    w = plan_weights([16.0, 17.0, 18.0, 24.0], "aggressive", epsilon=1.1)
    assert w[0] == 1.0 and w[1] == pytest.approx((16 / 17) ** 2)  # 17 <= 1.1 * 16
    assert w[2] < 0 and w[3] < 0
    assert -w[w < 0].sum() == pytest.approx(0.5 * w[w > 0].sum())
    assert w[2] / w[3] == pytest.approx((24 / 18) ** 2)  # the conservative shape, scaled


@given(st.lists(st.floats(1.0, 1000.0), min_size=1, max_size=12), st.floats(0.01, 0.99), st.floats(1.0, 2.0))
def test_nullifying_every_plan_never_beats_doing_nothing(
    durations: list[float], alpha: float, epsilon: float
) -> None:
    """With a penalty of twice the worst plan, making every plan impossible changes Σ w·d by Σ w·(P − d) ≥ 0."""
    w = plan_weights(durations, "aggressive", alpha=alpha, epsilon=epsilon)
    penalty = 2 * max(durations)
    assert float(np.sum(w * (penalty - np.array(durations)))) >= -1e-9


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"scheme": "bold"}, "unknown weighting scheme"),
        ({"epsilon": 0.9}, "epsilon"),
        ({"alpha": 1.0}, "alpha"),
        ({"power": 0.0}, "power"),
    ],
)
def test_bad_parameters(options: dict[str, Any], message: str) -> None:
    with pytest.raises(PlanningError, match=message):
        plan_weights([1.0, 2.0], **options)


def test_durations_must_be_positive() -> None:
    with pytest.raises(PlanningError, match="positive"):
        plan_weights([1.0, 0.0])
    with pytest.raises(PlanningError, match="at least one"):
        plan_weights([])


def choose(world: Any, scheme: str, **problem_options: Any) -> Any:
    problem = SupportProblem.of(world, world.plans(), **problem_options)
    planner = SupportPlanner[Any, Any, Any](scheme, environments=500).fit(problem)
    return planner.decide(problem, seed=1)


def three_plans(line_world_type: Any, **options: Any) -> Any:
    """Fetch a (at 8: 16 s), b (at 9: 18 s) or c (at 12: 24 s); the support hand is at 10.

    By hand: moving a to x saves 6 − x on a's plan; moving b to x saves 8 − x on b's; c to x, 10 − x on c's;
    moving b or c beyond the reach of 15 makes its plan impossible (penalty 48).
    """
    return line_world_type(["a", "b", "c"], [8.0, 9.0, 12.0], **options)


def test_greedy_helps_only_the_best_plan(line_world_type: Any) -> None:
    decision = choose(three_plans(line_world_type), "greedy")
    assert decision.chosen.move.item == 0 and decision.chosen.move.x == 1.0  # a to 1: 11 s instead of 16
    assert decision.chosen_durations[0] == 11.0 and decision.expected_saving == 5.0


def test_conservative_helps_the_plan_with_the_largest_weighted_saving(line_world_type: Any) -> None:
    """a → 1 gains 1·5 = 5; b → 1 gains (16/18)²·7 = 5.53; c → 1 gains (16/24)²·9 = 4: b goes to 1."""
    decision = choose(three_plans(line_world_type), "conservative")
    assert (decision.chosen.move.item, decision.chosen.move.x) == (1, 1.0)
    assert decision.idle_score - decision.score == pytest.approx((16 / 18) ** 2 * 7)


def test_aggressive_takes_a_bad_plan_away(line_world_type: Any) -> None:
    """b (18 s) and c (24 s) are slower than 1.1·16: negative weights −0.32 and −0.18. Putting b out of reach
    gains 0.32·(48 − 18) = 9.6, more than a → 1 (5) or c out of reach (0.18·24 = 4.3)."""
    decision = choose(three_plans(line_world_type), "aggressive")
    assert decision.chosen.move.item == 1 and decision.chosen.move.x > 15
    assert decision.chosen_durations[1] == 48.0


def test_prohibited_operators_are_never_chosen_even_when_best(line_world_type: Any) -> None:
    """Forbid the support agent to hold b: the conservative choice (b → 1) is gone, a → 1 is next best."""
    decision = choose(three_plans(line_world_type), "conservative", prohibited=["holding(support, b)"])
    assert decision.chosen.move.item == 0 and decision.chosen.move.x == 1.0
    assert decision.candidates.discarded["prohibited"] == 19  # b to any of 20 places but where it lies
    assert all(env.move.item != 1 for env in decision.candidates.environments)


def test_without_the_capability_to_place_nothing_is_attainable(line_world_type: Any) -> None:
    decision = choose(three_plans(line_world_type), "conservative", capabilities=frozenset({"pick"}))
    assert not decision.helps and decision.candidates.environments == ()
    assert decision.candidates.discarded["incapable"] > 0
