"""Counting the orders that keep a set of precedences, against listing every permutation."""

from __future__ import annotations

import itertools
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.learning.linear_extensions import count_linear_extensions, count_without, covering_pairs


def _brute(n: int, precedences: list[tuple[int, int]]) -> int:
    return sum(
        all(rank[u] < rank[v] for u, v in precedences)
        for order in itertools.permutations(range(n))
        for rank in [{step: i for i, step in enumerate(order)}]
    )


@st.composite
def _posets(draw: st.DrawFn) -> tuple[int, list[tuple[int, int]]]:
    n = draw(st.integers(0, 7))
    pairs = [(u, v) for u in range(n) for v in range(n) if u != v]
    chosen = draw(st.lists(st.sampled_from(pairs), max_size=10)) if pairs else []
    if draw(st.booleans()):  # acyclic: keep the pairs that go up in a random ranking
        rank = draw(st.permutations(range(n)))
        chosen = [(u, v) for u, v in chosen if rank[u] < rank[v]]
    return n, chosen


@settings(max_examples=300, deadline=None)
@given(_posets())
def test_the_count_is_the_number_of_permutations_keeping_every_precedence(poset: tuple[int, list[tuple[int, int]]]) -> None:
    n, precedences = poset
    assert count_linear_extensions(n, precedences) == _brute(n, precedences)  # 0 for a cycle


@settings(max_examples=100, deadline=None)
@given(_posets())
def test_a_bound_on_the_work_gives_the_count_or_none(poset: tuple[int, list[tuple[int, int]]]) -> None:
    n, precedences = poset
    bounded = count_linear_extensions(n, precedences, max_down_sets=2)
    assert bounded is None or bounded == _brute(n, precedences)


@settings(max_examples=100, deadline=None)
@given(_posets(), st.randoms(use_true_random=False))
def test_the_count_is_remembered_by_the_precedences_whatever_their_order(
    poset: tuple[int, list[tuple[int, int]]], rng: random.Random
) -> None:
    # counts are remembered: the same precedences asked in another order, or some twice, are the same question
    n, precedences = poset
    first = count_linear_extensions(n, precedences)
    shuffled = precedences + precedences[: len(precedences) // 2]
    rng.shuffle(shuffled)
    assert count_linear_extensions(n, shuffled) == first == _brute(n, precedences)


def test_parts_that_split_are_counted_without_their_down_sets() -> None:
    # 40 steps in 4 chains of 10 after one first step: far too many down-sets for the plain programme
    chains = [(10 * c + k + 1, 10 * c + k + 2) for c in range(4) for k in range(9)]
    first = [(0, 10 * c + 1) for c in range(4)]
    from math import factorial

    expected = factorial(40) // factorial(10) ** 4
    assert count_linear_extensions(41, chains + first, max_down_sets=50) == expected


def test_a_prime_part_past_the_bound_is_not_counted() -> None:
    # a zigzag (0<1>2<3>4 …) splits neither way; its down-sets of one size outnumber a bound of 2
    zigzag = [(i, i + 1) if i % 2 == 0 else (i + 1, i) for i in range(7)]
    assert count_linear_extensions(8, zigzag, max_down_sets=2) is None
    assert count_linear_extensions(8, zigzag) == _brute(8, zigzag)


def test_a_precedence_outside_the_steps_is_refused() -> None:
    with pytest.raises(LearningError, match=r"precedence \(0, 3\) is outside steps 0…2"):
        count_linear_extensions(3, [(0, 3)])


@settings(max_examples=200, deadline=None)
@given(_posets())
def test_the_covering_pairs_are_the_edges_of_the_transitive_reduction(poset: tuple[int, list[tuple[int, int]]]) -> None:
    import networkx as nx

    n, precedences = poset
    graph: nx.DiGraph[int] = nx.DiGraph(precedences)
    graph.add_nodes_from(range(n))
    if not nx.is_directed_acyclic_graph(graph):
        with pytest.raises(LearningError, match="cycle"):
            covering_pairs(n, precedences)
        return
    assert covering_pairs(n, precedences) == sorted(nx.transitive_reduction(graph).edges())


@settings(max_examples=300, deadline=None)
@given(_posets(), st.data())
def test_the_count_without_a_pair_is_the_count_of_the_rest(poset: tuple[int, list[tuple[int, int]]], data: st.DataObject) -> None:
    n, precedences = poset
    pairs = sorted(set(precedences)) or [(0, 1)] if n >= 2 else []
    if not pairs:
        return
    pair = data.draw(st.sampled_from(pairs))
    rest = [p for p in precedences if p != pair]
    assert count_without(n, precedences, pair) == _brute(n, rest)
    bounded = count_without(n, precedences, pair, max_down_sets=2)
    assert bounded is None or bounded == _brute(n, rest)


def test_a_pair_inside_a_part_that_does_not_split_is_counted_from_the_part() -> None:
    # two zigzags of 6 after one another, and 0 < 1 dropped inside the first: the part stays whole
    zigzag = [(i, i + 1) if i % 2 == 0 else (i + 1, i) for i in range(5)]
    second = [(u + 6, v + 6) for u, v in zigzag]
    join = [(u, v) for u in range(6) for v in range(6, 12)]
    precedences = zigzag + second + join
    assert count_without(12, precedences, (0, 1)) == _brute(6, zigzag[1:]) * _brute(6, zigzag)
