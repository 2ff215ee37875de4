"""Partial-order tasks: counting their executions and drawing them uniformly, against listing every order."""

from __future__ import annotations

import itertools
from collections import Counter

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import chisquare

from supportive.errors import GenerationError
from supportive.generate.partial_orders import PartialOrderTask, random_partial_order


def listed(task: PartialOrderTask) -> list[tuple[str, ...]]:
    """Every valid execution, by trying every permutation (the oracle)."""
    return [order for order in itertools.permutations(task.steps) if task.admits(order)]


@st.composite
def small_tasks(draw: st.DrawFn) -> PartialOrderTask:
    steps = draw(st.integers(2, 6))
    chains = draw(st.integers(1, steps))
    return random_partial_order(steps, draw(st.integers(0, 2**32 - 1)), chains=chains, cross=draw(st.integers(0, 4)))


@settings(max_examples=40, deadline=None)
@given(small_tasks(), st.integers(0, 2**32 - 1))
def test_counting_draws_are_valid_and_counting_matches_the_listing(task: PartialOrderTask, seed: int) -> None:
    valid = listed(task)
    assert task.count_executions() == len(valid)
    draw = task.counting_sampler()
    assert all(draw(seed + k) in valid for k in range(5))


def test_counting_draws_are_uniform_where_tight_constraints_defeat_redrawing() -> None:
    # Five one-step chains under a chain of cross constraints with one free step: 5 valid orders of 120.
    task = PartialOrderTask((("a",), ("b",), ("c",), ("d",), ("e",)), (("a", "b"), ("b", "c"), ("c", "d")))
    valid = listed(task)
    assert len(valid) == 5
    draw = task.counting_sampler()
    seen = Counter(draw(seed) for seed in range(2_000))
    assert set(seen) == set(valid)
    assert chisquare([seen[order] for order in valid]).pvalue > 0.001  # seeded: the same counts every run


def test_a_task_with_no_execution_refuses_to_draw() -> None:
    cyclic = PartialOrderTask((("a",), ("b",)), (("a", "b"), ("b", "a")))
    assert cyclic.count_executions() == 0
    with pytest.raises(GenerationError, match="no execution"):
        cyclic.counting_sampler()
