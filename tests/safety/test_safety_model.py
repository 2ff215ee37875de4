"""Action priors, P(safe | τ) and the danger model, checked by hand and against a direct computation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.safety import ActionPriors, DangerModel, SafetyEstimate
from supportive.worlds.household import MOVES, HouseholdWorld, MapDistances, load_map, parse_map

# Two bins at the ends of a corridor:  B . . . B  — row 1, columns 1..5.
CORRIDOR = "#######\n#B...B#\n#######\n"


def test_action_priors_by_hand() -> None:
    distances = MapDistances(parse_map(CORRIDOR))
    priors = ActionPriors.from_experts(distances, hyperprior=1.0, seed=0)
    # (1, 3), the middle: west is optimal for the west bin, east for the east bin.
    assert priors.probability((1, 3), "west") == pytest.approx(2 / 6)
    assert priors.probability((1, 3), "east") == pytest.approx(2 / 6)
    assert priors.probability((1, 3), "north") == pytest.approx(1 / 6)
    # (1, 2) is beside the west bin: only the east bin's expert moves there (east).
    assert priors.probability((1, 2), "east") == pytest.approx(2 / 5)
    assert priors.probability((1, 2), "west") == pytest.approx(1 / 5)
    row = priors.cells.index((1, 3))
    assert list(priors.counts[row]) == [0, 1, 0, 1]  # north, east, south, west
    assert np.allclose(priors.theta.sum(axis=1), 1.0)
    assert priors.probability((0, 0), "north") == 0.25  # outside the play area: uniform


def test_action_priors_options() -> None:
    distances = MapDistances(load_map("playroom"))
    sampled = ActionPriors.from_experts(distances, sample=True, seed=3)
    assert np.allclose(sampled.theta.sum(axis=1), 1.0)
    again = ActionPriors.from_experts(distances, sample=True, seed=3)
    assert np.array_equal(sampled.theta, again.theta)
    few = ActionPriors.from_experts(distances, starts=2, seed=3)
    assert few.counts.sum() <= ActionPriors.from_experts(distances, seed=3).counts.sum()
    for bad in ({"hyperprior": 0.0}, {"delta": 1.0}, {"starts": 0}):
        with pytest.raises(ValueError):
            ActionPriors.from_experts(distances, **bad)


def _direct(priors: ActionPriors, trajectory: list[tuple[tuple[int, int], str]], prior: float) -> float:
    safe = math.prod(priors.probability(c, m) for c, m in trajectory) * prior
    unsafe = math.prod(0.25 for _ in trajectory) * (1 - prior)
    return safe / (safe + unsafe)


@given(st.lists(st.tuples(st.sampled_from([(1, 2), (1, 3), (1, 4)]), st.sampled_from(list(MOVES))), max_size=30),
       st.floats(0.05, 0.95))
def test_p_safe_matches_equation_3_2(trajectory: list[tuple[tuple[int, int], str]], prior: float) -> None:
    priors = ActionPriors.from_experts(MapDistances(parse_map(CORRIDOR)), hyperprior=0.5, seed=0)
    estimate = SafetyEstimate(priors, prior_safe=prior)
    for cell, move in trajectory:
        estimate.observe(cell, move)
    assert estimate.probability == pytest.approx(_direct(priors, trajectory, prior), rel=1e-9, abs=1e-12)
    assert estimate.steps == len(trajectory)


def test_p_safe_does_not_underflow_on_long_trajectories() -> None:
    priors = ActionPriors.from_experts(MapDistances(parse_map(CORRIDOR)), hyperprior=0.5, seed=0)
    estimate = SafetyEstimate(priors)
    for _ in range(5000):
        estimate.observe((1, 3), "north")  # bumping into the wall: never what an expert does
    assert 0.0 <= estimate.probability < 1e-300 or estimate.probability == 0.0
    assert math.isfinite(estimate.log_odds) and estimate.log_odds < -1000
    for _ in range(10_000):
        estimate.observe((1, 2), "east")
    assert estimate.probability > 0.999


def test_memory_forgets_old_steps() -> None:
    priors = ActionPriors.from_experts(MapDistances(parse_map(CORRIDOR)), hyperprior=0.5, seed=0)
    forgetful = SafetyEstimate(priors, memory=0.9)
    for _ in range(100):
        forgetful.observe((1, 3), "north")
    low = forgetful.probability
    for _ in range(20):
        forgetful.observe((1, 2), "east")
    assert low < 0.01 and forgetful.probability > 0.9
    with pytest.raises(ValueError):
        SafetyEstimate(priors, memory=0.0)
    with pytest.raises(ValueError):
        SafetyEstimate(priors, prior_safe=1.0)


def test_danger_model() -> None:
    grid = parse_map("########\n#B....S#\n#..C...#\n########\n")
    model = DangerModel(MapDistances(grid), horizon=4)
    world = HouseholdWorld.start(grid, novice=(1, 5))
    assert model.steps((1, 6), (1, 5)) == 1 and model.reach((1, 6), (1, 5)) == 1.0
    expected = model.expected_damage(world, p_safe=0.5)
    assert expected[(1, 6)] == pytest.approx(0.5 * 1.0 * 5)
    # the candle at (2, 3): from (1, 5) the novice needs 2 steps to (2, 4) or (1, 3)... then bumps: 3 steps
    assert model.steps((2, 3), (1, 5)) == 3
    assert expected[(2, 3)] == pytest.approx(0.5 * (1 - 2 / 4) * 4)
    assert model.expected_damage(world, p_safe=1.0)[(1, 6)] == 0.0
    world.caregiver = (1, 6)  # standing in the stairwell blocks it
    assert (1, 6) not in model.expected_damage(world, p_safe=0.5)
    world.candles.clear()
    assert model.expected_damage(world, 0.5)[(2, 3)] == pytest.approx(0.5 * 0.5 * 1)  # an empty table
