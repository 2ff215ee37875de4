"""Algorithm 1: the Conjugate Task Graph transform (§2.1.3), in one go or one demonstration at a time."""

from __future__ import annotations

from supportive.tasks.conjugate import EMPTY, ORIGIN, TERMINAL, ConjugateTaskGraph
from supportive.tasks.task_graph import GraphUpdate, TaskGraph

__all__ = ["conjugate_task_graph", "update_conjugate"]


def conjugate_task_graph(task_graph: TaskGraph) -> ConjugateTaskGraph:
    """Build the CTG of ``task_graph``.

    An edge out of an initial state gives ``origin -> action`` with no prerequisites; an edge into a terminal
    state gives ``action -> terminal`` with that state as prerequisites; two consecutive edges ``e, f`` through a
    state give ``action(e) -> action(f)`` with that state as prerequisites. Redundant edges (same ends, a superset
    of another's prerequisites) are dropped as they arrive. Unlike line 12 of the thesis's listing, a terminal state
    that other demonstrations continue from contributes both kinds of edge.

    >>> g = TaskGraph(); _ = g.add(["knife", "carrots", "celery"]); _ = g.add(["knife", "celery", "carrots"])
    >>> ctg = conjugate_task_graph(g)
    >>> sorted(ctg.label(v) for v in ctg.successors(g.subgoal_index(("knife", 1))))
    ['carrots', 'celery']
    """
    ctg = ConjugateTaskGraph(task_graph)
    for src, subgoal, dst in task_graph.edges():
        _add_edge(ctg, task_graph, src, subgoal, dst, both_sides=False)
    return ctg


def update_conjugate(ctg: ConjugateTaskGraph, update: GraphUpdate) -> bool:
    """Bring ``ctg`` up to date with what one demonstration added to its task graph.

    Returns:
        True when the CTG changed.
    """
    graph = ctg.task_graph
    changed = False
    for src, subgoal, dst in update.edges:
        changed |= _add_edge(ctg, graph, src, subgoal, dst, both_sides=True)
    for state in update.new_terminal:
        for subgoal, _ in graph.into[state]:
            changed |= ctg.add(subgoal, TERMINAL, state)
    return changed


def _add_edge(
    ctg: ConjugateTaskGraph, graph: TaskGraph, src: int, subgoal: int, dst: int, *, both_sides: bool
) -> bool:
    """The CTG edges that the task-graph edge ``src -subgoal-> dst`` takes part in.

    In a full build every pair of consecutive edges is met from its first edge, so only the outgoing side is
    needed; an incremental update must also pair a new edge with the edges already entering ``src``.
    """
    changed = False
    if src in graph.initial:
        changed |= ctg.add(ORIGIN, subgoal, EMPTY)
    if dst in graph.terminal:
        changed |= ctg.add(subgoal, TERMINAL, dst)
    for following in graph.out[dst]:
        changed |= ctg.add(subgoal, following, dst)
    if both_sides:
        for preceding, _ in graph.into[src]:
            changed |= ctg.add(preceding, subgoal, src)
    return changed
