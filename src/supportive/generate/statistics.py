"""Thesis-style statistics (§2.1.7.2) of generated structures and task sets."""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from supportive.errors import GenerationError
from supportive.tasks.htn import ActionNode, ChainNode, Node, count_orderings, mean_action_depth
from supportive.tasks.spec import TaskSpec

__all__ = ["ikea_statistics", "structure_statistics"]


def structure_statistics(node: Node) -> dict[str, float]:
    """Shape of one structure.

    Returns:
        Counts as ints, the rest as floats: ``actions`` (leaves), ``mean_depth`` (mean primitive depth, as in §2.1.7.2), ``max_depth`` (deepest
        primitive), ``chains`` and ``cliques`` (node counts), ``mean_chain_children`` and
        ``mean_clique_children`` (0 when there is none), ``log10_orderings`` (log10 of the orderings admitted).
    """
    chains: list[int] = []
    cliques: list[int] = []
    deepest = 0
    stack: list[tuple[Node, int]] = [(node, 0)]
    while stack:
        current, depth = stack.pop()
        if isinstance(current, ActionNode):
            deepest = max(deepest, depth)
            continue
        (chains if isinstance(current, ChainNode) else cliques).append(len(current.children))
        stack.extend((child, depth + 1) for child in current.children)
    return {
        "actions": len(node.leaves),
        "mean_depth": mean_action_depth([node]),
        "max_depth": deepest,
        "chains": len(chains),
        "cliques": len(cliques),
        "mean_chain_children": float(np.mean(chains)) if chains else 0.0,
        "mean_clique_children": float(np.mean(cliques)) if cliques else 0.0,
        "log10_orderings": math.log10(count_orderings(node)),
    }


def ikea_statistics(tasks: Iterable[TaskSpec | Node]) -> dict[str, float]:
    """Statistics of a set of tasks (or bare structures), in the terms §2.1.7.2 reports.

    Returns:
        Counts as ints, the rest as floats: ``tasks``; ``min_actions``, ``max_actions``, ``mean_actions``; ``mean_depth`` (mean over tasks of the
        mean primitive depth; the thesis reports 2.84), ``min_depth``, ``max_depth`` (the thesis: 1.99 and
        3.61), ``std_depth``; ``max_leaf_depth`` (deepest primitive of any task); ``mean_chains``,
        ``mean_cliques`` (per task), ``mean_chain_children``, ``mean_clique_children`` (per task, then
        averaged); ``mean_log10_orderings``, ``min_log10_orderings``, ``max_log10_orderings``; and for task
        specs ``mean_demonstrations`` and ``mean_distinct_demonstrations``.

    Raises:
        GenerationError: when there is no task, or a task spec has no structure.
    """
    rows: list[dict[str, float]] = []
    demos: list[tuple[int, int]] = []
    for index, task in enumerate(tasks):
        if isinstance(task, TaskSpec):
            if task.structure is None:
                raise GenerationError(f"task {index + 1} ({task.name}) has no ground-truth structure")
            rows.append(structure_statistics(task.structure))
            sequences = list(task.action_sequences())
            demos.append((len(sequences), len(set(sequences))))
        else:
            rows.append(structure_statistics(task))
    if not rows:
        raise GenerationError("no tasks to describe")

    def column(key: str) -> np.ndarray:
        return np.array([row[key] for row in rows])

    depth, actions, orderings = column("mean_depth"), column("actions"), column("log10_orderings")
    out = {
        "tasks": len(rows),
        "min_actions": int(actions.min()),
        "max_actions": int(actions.max()),
        "mean_actions": float(actions.mean()),
        "mean_depth": float(depth.mean()),
        "min_depth": float(depth.min()),
        "max_depth": float(depth.max()),
        "std_depth": float(depth.std()),
        "max_leaf_depth": int(column("max_depth").max()),
        "mean_chains": float(column("chains").mean()),
        "mean_cliques": float(column("cliques").mean()),
        "mean_chain_children": float(column("mean_chain_children").mean()),
        "mean_clique_children": float(column("mean_clique_children").mean()),
        "mean_log10_orderings": float(orderings.mean()),
        "min_log10_orderings": float(orderings.min()),
        "max_log10_orderings": float(orderings.max()),
    }
    if demos:
        out["mean_demonstrations"] = float(np.mean([n for n, _ in demos]))
        out["mean_distinct_demonstrations"] = float(np.mean([d for _, d in demos]))
    return out
