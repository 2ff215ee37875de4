"""Thesis-style statistics of structures and task sets."""

from __future__ import annotations

import math

import pytest

from supportive.generate import GenerationError, generate_task, ikea_statistics, structure_statistics
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode
from supportive.tasks.spec import TaskSpec

A, B, C, D = (ActionNode(x) for x in "abcd")
CHAIR = ChainNode((A, CliqueNode((B, ChainNode((C, D))))))


def test_structure_statistics() -> None:
    stats = structure_statistics(CHAIR)
    assert stats == {
        "actions": 4,
        "mean_depth": (1 + 2 + 3 + 3) / 4,
        "max_depth": 3,
        "chains": 2,
        "cliques": 1,
        "mean_chain_children": 2.0,
        "mean_clique_children": 2.0,
        "log10_orderings": math.log10(2),
    }


def test_set_statistics_of_structures_and_specs() -> None:
    stats = ikea_statistics([CHAIR, A, TaskSpec("t", structure=CliqueNode((A, B, C)))])
    assert stats["tasks"] == 3
    assert (stats["min_actions"], stats["max_actions"]) == (1, 4)
    assert stats["min_depth"] == 0.0 and stats["max_depth"] == 2.25
    assert stats["max_leaf_depth"] == 3
    assert stats["mean_cliques"] == pytest.approx(2 / 3)
    assert stats["max_log10_orderings"] == pytest.approx(math.log10(6))
    assert stats["mean_demonstrations"] == 0.0


def test_demonstration_counts() -> None:
    tasks = [generate_task(3, seed, demonstrations=5, profile="uniform") for seed in range(4)]
    stats = ikea_statistics(tasks)
    assert stats["mean_demonstrations"] == 5
    assert 1 <= stats["mean_distinct_demonstrations"] <= 5


def test_errors() -> None:
    with pytest.raises(GenerationError, match="no tasks"):
        ikea_statistics([])
    with pytest.raises(GenerationError, match="no ground-truth structure"):
        ikea_statistics([TaskSpec("bare")])
