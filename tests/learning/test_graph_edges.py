"""The task-graph protocol of Differentiable Task Graph Learning (learning/graph_edges.py)."""

from __future__ import annotations

import itertools

import networkx as nx
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.io.captaincook import load_captaincook
from supportive.learning.graph_edges import (
    EDGE_ERRORS,
    END_NODE,
    START_NODE,
    GraphEdge,
    compare_edges,
    edge_errors,
    edge_scores,
    reduced_edges,
)

A, B, C, D = ("a", 1), ("b", 1), ("c", 1), ("d", 1)


def test_the_published_graphs_scored_against_themselves_are_perfect_when_already_reduced() -> None:
    recipes = load_captaincook()
    assert len(recipes) == 24
    for recipe in recipes:
        graph = nx.DiGraph(list(recipe.graph_edges))
        redundant = len(graph.edges) - len(nx.transitive_reduction(graph).edges)
        score = edge_scores(recipe.published, recipe.steps, recipe.graph_edges)
        assert score.precision == 1.0, recipe.name
        assert score.recall == pytest.approx((len(graph.edges) - redundant) / len(graph.edges)), recipe.name


def test_a_redundant_published_edge_costs_recall_only() -> None:
    truth: set[GraphEdge] = {(START_NODE, A), (A, B), (B, C), (A, C), (C, END_NODE)}  # a -> c: implied by a -> b -> c
    score = edge_scores({(A, B), (B, C), (A, C)}, [A, B, C], truth)
    assert (score.precision, score.recall) == (1.0, 0.8)


def test_terminals_join_steps_nothing_precedes_or_follows() -> None:
    edges = reduced_edges({(A, B), (C, B)}, [A, B, C, D])
    assert edges == {(START_NODE, A), (START_NODE, C), (A, B), (C, B), (B, END_NODE), (START_NODE, D), (D, END_NODE)}


def test_pairs_outside_the_published_steps_are_left_out_and_cycles_refused() -> None:
    assert reduced_edges({(A, ("x", 1))}, [A]) == {(START_NODE, A), (A, END_NODE)}
    with pytest.raises(LearningError, match="cycle"):
        reduced_edges({(A, B), (B, A)}, [A, B])


def _closure(pairs: set[tuple[int, int]], n: int) -> set[tuple[int, int]]:
    """Warshall's closure of a relation over ``range(n)``."""
    reach = {(a, b) for a, b in pairs}
    for k, a, b in itertools.product(range(n), repeat=3):
        if (a, k) in reach and (k, b) in reach:
            reach.add((a, b))
    return reach


def _dag(n: int) -> st.SearchStrategy[set[tuple[int, int]]]:
    """Relations over ``range(n)`` with every pair from a lower to a higher number: acyclic."""
    return st.sets(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] < p[1]))


@given(_dag(5), _dag(5))
def test_every_wrong_edge_is_counted_once_under_the_kind_its_orders_give(
    learned: set[tuple[int, int]], published: set[tuple[int, int]]
) -> None:
    """Against brute force (Warshall's closures, reductions as the pairs no third step joins): each edge in
    one reduced graph and not the other is counted once, under the kind the two relations' orders give."""
    steps = [(str(i), 1) for i in range(5)]
    leaf = dict(enumerate(steps))
    reach, truth_reach = _closure(learned, 5), _closure(published, 5)

    def graph(reach: set[tuple[int, int]]) -> set[GraphEdge]:
        direct = {(a, b) for a, b in reach if not any((a, k) in reach and (k, b) in reach for k in range(5))}
        edges: set[GraphEdge] = {(leaf[a], leaf[b]) for a, b in direct}
        edges |= {(START_NODE, leaf[i]) for i in range(5) if not any((k, i) in reach for k in range(5))}
        edges |= {(leaf[i], END_NODE) for i in range(5) if not any((i, k) in reach for k in range(5))}
        return edges

    mine, truth = graph(reach), graph(truth_reach)
    number = {v: k for k, v in leaf.items()}
    expected = dict.fromkeys(EDGE_ERRORS, 0)
    for a, b in mine - truth:
        if isinstance(a, str) or isinstance(b, str):
            kind = 3
        else:
            pair = (number[a], number[b])
            kind = 1 if pair in truth_reach else 2 if pair[::-1] in truth_reach else 0
        expected[EDGE_ERRORS[kind]] += 1
    for a, b in truth - mine:
        kind = 6 if isinstance(a, str) or isinstance(b, str) else 4 if (number[a], number[b]) in reach else 5
        expected[EDGE_ERRORS[kind]] += 1
    pairs = {(leaf[a], leaf[b]) for a, b in learned}
    assert edge_errors(pairs, steps, truth) == expected
    score = edge_scores(pairs, steps, truth)
    assert sum(expected[k] for k in EDGE_ERRORS[:4]) == score.learned - score.true_positives
    assert sum(expected[k] for k in EDGE_ERRORS[4:]) == score.published - score.true_positives
    both = compare_edges(pairs, steps, truth)
    assert (both.score, both.errors) == (score, expected)
