"""The task-graph protocol of Differentiable Task Graph Learning (learning/graph_edges.py)."""

from __future__ import annotations

import networkx as nx
import pytest

from supportive.errors import LearningError
from supportive.io.captaincook import load_captaincook
from supportive.learning.graph_edges import END_NODE, START_NODE, GraphEdge, edge_scores, reduced_edges

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
