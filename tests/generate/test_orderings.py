"""Valid orderings and demonstrations: admitted, all when few, uniform draws otherwise."""

from __future__ import annotations

import itertools
from collections import Counter

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.generate import (
    Profile,
    TooManyOrderingsError,
    all_demonstrations,
    generate_task,
    random_structure,
    sample_demonstrations,
    sample_orderings,
    valid_orderings,
)
from supportive.tasks.htn import (
    ActionNode,
    ChainNode,
    CliqueNode,
    admits,
    count_orderings,
    iter_orderings,
    to_leaves,
)

seeds = st.integers(0, 2**32 - 1)
profiles: st.SearchStrategy[Profile] = st.sampled_from(["ikea", "uniform"])


@given(n=st.integers(1, 150), seed=seeds, profile=profiles, k=st.integers(0, 6))
def test_every_sampled_demonstration_is_admitted(n: int, seed: int, profile: Profile, k: int) -> None:
    task = generate_task(n, seed, demonstrations=k, profile=profile)
    assert task.structure is not None
    assert [d.id for d in task.demonstrations] == [f"d{i}" for i in range(1, k + 1)]
    for demo in task.demonstrations:
        assert admits(task.structure, to_leaves(demo.actions))


@given(n=st.integers(1, 7), seed=seeds, profile=profiles)
def test_all_orderings_when_few(n: int, seed: int, profile: Profile) -> None:
    node = random_structure(n, seed, profile=profile)
    orderings = valid_orderings(node, limit=5040)
    assert len(orderings) == count_orderings(node)
    assert set(orderings) == set(iter_orderings(node))
    assert all(admits(node, o) for o in orderings)


def test_samples_when_many_and_raises_without_sample() -> None:
    node = CliqueNode(tuple(ActionNode(f"a{i}") for i in range(8)))  # 40320 orderings
    drawn = valid_orderings(node, limit=1000, sample=5, seed=1)
    assert len(drawn) == 5
    assert all(admits(node, o) for o in drawn)
    with pytest.raises(TooManyOrderingsError, match="40320 orderings, more than the limit of 1000") as info:
        valid_orderings(node, limit=1000)
    assert isinstance(info.value, LearningError)
    assert isinstance(info.value, ValueError)
    assert (info.value.count, info.value.limit) == (40320, 1000)


def test_all_demonstrations() -> None:
    node = ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("c"), ActionNode("d")))))
    demos = all_demonstrations(node, limit=6)
    assert [d.id for d in demos] == ["d1", "d2", "d3", "d4", "d5", "d6"]
    assert {d.actions for d in demos} == {("a", *p) for p in itertools.permutations("bcd")}
    with pytest.raises(TooManyOrderingsError, match="6 orderings"):
        all_demonstrations(node, limit=5)


def test_huge_counts_are_reported_briefly() -> None:
    node = CliqueNode(tuple(ActionNode(f"a{i}") for i in range(40)))
    with pytest.raises(TooManyOrderingsError, match=r"about 10\^47 orderings"):
        all_demonstrations(node)


def test_draws_are_uniform() -> None:
    node = ChainNode((ActionNode("x"), CliqueNode((ActionNode("a"), ActionNode("b"), ActionNode("c")))))
    counts = Counter(sample_orderings(node, 6000, seed=3))
    assert len(counts) == 6
    assert all(850 <= c <= 1150 for c in counts.values())  # 1000 expected each, sd about 29


def test_distinct_draws() -> None:
    node = CliqueNode((ActionNode("a"), ActionNode("b"), ActionNode("c")))
    drawn = sample_orderings(node, 5, seed=0, distinct=True)
    assert len(set(drawn)) == 5
    everything = sample_orderings(node, 10, seed=0, distinct=True)
    assert sorted(everything) == sorted(iter_orderings(node))
    assert len(sample_demonstrations(ActionNode("a"), 4, seed=0, distinct=True)) == 1
    assert len(sample_demonstrations(ActionNode("a"), 4, seed=0)) == 4


def test_same_seed_same_draws() -> None:
    node = random_structure(50, 9)
    assert sample_orderings(node, 4, seed=2) == sample_orderings(node, 4, seed=2)
    assert sample_orderings(node, 4, seed=2) != sample_orderings(node, 4, seed=3)
