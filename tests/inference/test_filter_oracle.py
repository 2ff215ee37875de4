"""The HMM filter's posterior against brute force (issue 17): on tiny tasks, enumerate every hidden path of
subgoals, weigh it by the model's start, stay/switch moves and the observation probabilities (worked out here
from the model's table, event by event), and compare the marginal of the last subgoal, the log-likelihood
and the next-subgoal prediction with GoalFilter's belief after the same observations."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.generate import random_structure
from supportive.inference import FlatHMM, HierarchicalHMM, ObservationModel
from supportive.tasks.htn import HTN


def _observation_probability(model: ObservationModel, action: str, observation: frozenset[str]) -> float:
    """P(observation | action): each known event holds independently with the action's probability."""
    row = [float(p) for p in model.table[model.action_index[action]]]
    return math.prod(p if event in observation else 1.0 - p for event, p in zip(model.events, row, strict=True))


def _brute_force(
    hmm: FlatHMM | HierarchicalHMM, observations: list[frozenset[str]]
) -> tuple[np.ndarray, float, np.ndarray]:
    """Posterior of the last subgoal, log P(observations) and the next-subgoal distribution, by enumerating
    every path of subgoals."""
    leaves = hmm.layout_.leaves
    n = len(leaves)
    switch = np.column_stack([hmm.transitions_(np.eye(n)[s]) for s in range(n)])  # switch[to, from]
    stay = hmm.stay_
    start = hmm.transitions_.start
    events = hmm.observations_
    assert events is not None
    emit = np.array([[_observation_probability(events, a, o) for a, _ in leaves] for o in observations])
    last = np.zeros(n)
    for path in itertools.product(range(n), repeat=len(observations)):
        weight = start[path[0]] * emit[0, path[0]]
        for t in range(1, len(path)):
            move = stay * (path[t] == path[t - 1]) + (1.0 - stay) * switch[path[t], path[t - 1]]
            weight *= move * emit[t, path[t]]
        last[path[-1]] += weight
    total = last.sum()
    posterior = last / total
    arriving = switch @ (posterior * (1.0 - stay))
    return posterior, math.log(total), arriving / arriving.sum()


def _events(actions: list[str], seed: int) -> ObservationModel:
    rng = np.random.default_rng(seed)
    events = ["e0", "e1", "e2"]
    return ObservationModel(
        {a: {e: float(rng.uniform(0.05, 0.95)) for e in events if rng.random() < 0.8} for a in actions}, noise=0.1
    )


@settings(max_examples=25)
@given(
    size=st.integers(2, 4),
    structure_seed=st.integers(0, 10_000),
    steps=st.integers(1, 5),
    data=st.data(),
)
@pytest.mark.parametrize("kind", [FlatHMM, HierarchicalHMM])
def test_the_filter_posterior_equals_the_sum_over_every_hidden_path(
    kind: type[FlatHMM] | type[HierarchicalHMM], size: int, structure_seed: int, steps: int, data: st.DataObject
) -> None:
    htn = HTN("t", (random_structure(size, structure_seed, profile="uniform"),))
    actions = [a for a, _ in htn.leaves]
    model = _events(actions, structure_seed)
    subsets = st.frozensets(st.sampled_from(["e0", "e1", "e2", "unknown"]))
    observations = data.draw(st.lists(subsets, min_size=steps, max_size=steps))
    duration = data.draw(st.floats(1.0, 6.0))
    hmm = kind(htn, model, mean_duration=duration).fit()
    running = hmm.filter()
    for observation in observations:
        belief = running.update(observation)
    posterior, log_likelihood, upcoming = _brute_force(hmm, [frozenset(o) for o in observations])
    assert belief.subgoals == pytest.approx(posterior, abs=1e-9)
    assert running.log_likelihood == pytest.approx(log_likelihood, rel=1e-9, abs=1e-9)
    assert belief.next_subgoals == pytest.approx(upcoming, abs=1e-9)
