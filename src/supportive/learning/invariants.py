"""Check the invariants every learned HTN must hold (DESIGN.md), without enumerating executions.

1. It admits every demonstration it was learned from.
2. Every node's actions are performed contiguously in every known execution.
3. From all valid orderings of a nested chain/clique structure, it recovers that structure exactly.
"""

from __future__ import annotations

from supportive.learning.strict.coverage import admitted_path_count
from supportive.tasks.htn import HTN, Node, canonical, count_orderings, internal_nodes
from supportive.tasks.task_graph import TaskGraph

__all__ = ["invariant_violations"]


def invariant_violations(graph: TaskGraph, htn: HTN, structure: Node | None = None) -> list[str]:
    """What is wrong with ``htn`` as learned from ``graph``: an empty list when all invariants hold.

    Invariant 2 is decided per state: a node is interrupted in some known execution exactly when some state
    in which it is half done has a transition out of it (or ends the task). Invariant 3 is checked when a
    ``structure`` is given and the known executions are exactly its valid orderings.
    """
    problems = []
    for index, demo in enumerate(graph.demonstrations):
        if not htn.admits_leaves([graph.subgoals[s] for s in demo]):
            problems.append(f"invariant 1: demonstration {index + 1} is not admitted")
    for root in htn.roots:
        for node in internal_nodes(root):
            members = [graph.subgoal_index(leaf) for leaf in node.leaves]
            if any(m is None for m in members):
                problems.append(f"invariant 2: {node.name or node.kind} has leaves the task graph never saw")
                continue
            mask = sum(1 << m for m in members if m is not None)
            for state, done in enumerate(graph.mask):
                if not 0 < done & mask != mask:
                    continue
                leaving = [s for s in graph.out[state] if not mask >> s & 1]
                if leaving or state in graph.terminal:
                    problems.append(
                        f"invariant 2: {node.name or node.kind} is interrupted in a known execution"
                    )
                    break
    if structure is not None:
        valid = count_orderings(structure)
        all_known = graph.path_count() == valid == admitted_path_count(graph, structure)
        recovered = htn.complete and canonical(htn.roots[0]) == canonical(structure)
        if all_known and not recovered:
            problems.append("invariant 3: all valid orderings are known but the structure was not recovered")
    return problems
