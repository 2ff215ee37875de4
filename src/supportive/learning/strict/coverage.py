"""How many known executions a hierarchy admits, counted over the task graph without enumerating paths."""

from __future__ import annotations

from dataclasses import dataclass

from supportive.tasks.htn import ActionNode, ChainNode, Node
from supportive.tasks.task_graph import TaskGraph

__all__ = ["admitted_path_count"]


@dataclass(frozen=True)
class _Ancestor:
    mask: int
    before: int  # for a chain: leaves of the children before the one on the path; else 0
    after: int  # for a chain: leaves of the children after it; else 0


def admitted_path_count(graph: TaskGraph, root: Node) -> int:
    """Known executions (paths of ``graph``) that ``root`` admits.

    A path is admitted when every node's leaves are contiguous and every chain's children come in order. Both
    are decided edge by edge from the done-mask of the state an edge leaves, so one dynamic-programming pass over
    the graph counts them. Leaves of ``root`` the graph never saw admit nothing.
    """
    ancestors: dict[int, list[_Ancestor]] = {}
    if not _collect(graph, root, [], ancestors) or len(ancestors) != len(root.leaves):
        return 0
    counts: dict[int, int] = {}
    for state in reversed(graph.topological_order()):
        total = int(state in graph.terminal)
        done = graph.mask[state]
        came_by = [s for s, _ in graph.into[state][:1]]
        for subgoal, dst in graph.out[state].items():
            if _allowed(done, subgoal, came_by, ancestors):
                total += counts[dst]
        counts[state] = total
    return sum(counts[s] for s in graph.initial)


def _allowed(done: int, subgoal: int, came_by: list[int], ancestors: dict[int, list[_Ancestor]]) -> bool:
    mine = ancestors.get(subgoal)
    if mine is None:
        return False
    bit = 1 << subgoal
    for node in mine:
        if done & node.before != node.before or done & node.after:
            return False
    for previous in came_by:
        for node in ancestors.get(previous, ()):
            if not node.mask & bit and 0 < done & node.mask != node.mask:
                return False
    return True


def _collect(graph: TaskGraph, node: Node, path: list[_Ancestor], out: dict[int, list[_Ancestor]]) -> bool:
    if isinstance(node, ActionNode):
        index = graph.subgoal_index(node.leaf)
        if index is None:
            return False
        out[index] = list(path)
        return True
    masks = [_mask(graph, child) for child in node.children]
    whole = sum(masks)
    for i, child in enumerate(node.children):
        if isinstance(node, ChainNode):
            entry = _Ancestor(whole, sum(masks[:i]), sum(masks[i + 1 :]))
        else:
            entry = _Ancestor(whole, 0, 0)
        if not _collect(graph, child, [*path, entry], out):
            return False
    return True


def _mask(graph: TaskGraph, node: Node) -> int:
    mask = 0
    for leaf in node.leaves:
        index = graph.subgoal_index(leaf)
        if index is not None:
            mask |= 1 << index
    return mask
