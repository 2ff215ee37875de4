"""Slips as noise (learning/noise.py): nothing set aside on clean data; injected slips found."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from supportive.generate import random_partial_order, random_structure
from supportive.learning import HTNLearner
from supportive.tasks.htn import sample_ordering

CLEAN = settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _assert_clean(demos: list[list[str]]) -> None:
    learner = HTNLearner().fit(demos)
    assert learner.deviations_ == ()
    assert learner.noise_ is not None and all(rate == 0.0 for rate in learner.noise_.rates.values())
    assert all(learner.htn_.admits(demo) for demo in demos)


@CLEAN
@given(
    seed=st.integers(0, 10_000),
    size=st.integers(3, 10),
    profile=st.sampled_from(["ikea", "uniform"]),
    n=st.integers(1, 200),
)
def test_nested_structures_sampled_uniformly_have_no_slips(seed: int, size: int, profile: str, n: int) -> None:
    rng = np.random.default_rng(seed)
    structure = random_structure(size, rng, profile=profile)  # type: ignore[arg-type]
    _assert_clean([[a for a, _ in sample_ordering(structure, rng)] for _ in range(n)])


@CLEAN
@given(
    seed=st.integers(0, 10_000),
    size=st.integers(4, 9),
    chains=st.integers(2, 3),
    cross=st.integers(0, 3),
    n=st.integers(1, 200),
)
def test_partial_orders_sampled_uniformly_have_no_slips(seed: int, size: int, chains: int, cross: int, n: int) -> None:
    rng = np.random.default_rng(seed)
    task = random_partial_order(size, rng, chains=chains, cross=cross)
    _assert_clean([list(task.sample(rng)) for _ in range(n)])


@pytest.mark.parametrize("n", [10, 20, 40, 80])
def test_two_interleaved_chains_the_issue_case(n: int) -> None:
    task = random_partial_order(6, 0, chains=2)
    rng = np.random.default_rng(n)
    _assert_clean([list(task.sample(rng)) for _ in range(n)])
