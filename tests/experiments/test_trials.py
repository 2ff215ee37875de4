from __future__ import annotations

import numpy as np
import pytest

from supportive.errors import ExperimentError
from supportive.experiments import get, spawn_trials, trial_seeds
from supportive.experiments.edge_reduction.measure import make_trials


def _state(seed: np.random.SeedSequence) -> list[int]:
    return [int(x) for x in seed.generate_state(4)]


def test_each_trial_gets_a_spawned_seed() -> None:
    seeds = trial_seeds(11, 5)
    expected = np.random.SeedSequence(11).spawn(5)
    assert [_state(s) for s in seeds] == [_state(s) for s in expected]
    assert [s.spawn_key for s in seeds] == [(i,) for i in range(5)]
    assert len({tuple(_state(s)) for s in seeds}) == 5


def test_a_trials_seed_does_not_depend_on_the_number_of_trials() -> None:
    few, many = trial_seeds(5, 3), trial_seeds(5, 40)
    assert [_state(s) for s in few] == [_state(s) for s in many[:3]]
    assert _state(trial_seeds(6, 1)[0]) != _state(few[0])


def test_spawn_trials_numbers_and_seeds_trials() -> None:
    trials = spawn_trials(2, [{"n": 1}, {"n": 2}, {"n": 3}])
    assert [t.index for t in trials] == [0, 1, 2] and [t.params["n"] for t in trials] == [1, 2, 3]
    draws = [int(t.rng().integers(10**9)) for t in trials]
    assert draws == [int(t.rng().integers(10**9)) for t in trials]  # a fresh generator every time
    assert len(set(draws)) == 3


def test_edge_reduction_trials() -> None:
    trials = make_trials(76, 0)
    assert len(trials) == 76 == get("edge-reduction").default_trials
    sizes = [t.params["subgoals"] for t in trials]
    assert sizes[0] == 10 and sizes[-1] == 100 and sizes == sorted(sizes)
    assert all(t.params["demonstrations"] == 4 for t in trials)
    assert [_state(t.seed) for t in trials] == [_state(s) for s in trial_seeds(0, 76)]


@pytest.mark.parametrize("seed", [-1, 1.5, "3", True])
def test_bad_seeds(seed: object) -> None:
    with pytest.raises(ExperimentError, match="seed must be an int >= 0"):
        trial_seeds(seed, 2)  # type: ignore[arg-type]
