"""CTG features the informed strategies rank by (§2.2.6.2–2.2.6.3): shortest-path distance and connectivity."""

from __future__ import annotations

from collections import deque

from supportive.tasks.conjugate import TERMINAL, ConjugateTaskGraph, Vertex

__all__ = ["connectivity_base", "connectivity_scores", "ctg_distances"]


def ctg_distances(ctg: ConjugateTaskGraph, source: Vertex) -> dict[Vertex, int]:
    """Shortest-path distance (edges) from ``source`` to every vertex it reaches; unreachable ones are absent.

    >>> from supportive.learning import HTNLearner
    >>> learner = HTNLearner().fit([["knife", "carrots", "celery"]])
    >>> {learner.ctg_.label(v): d for v, d in ctg_distances(learner.ctg_, "origin").items()}
    {'origin': 0, 'knife': 1, 'carrots': 2, 'celery': 3, 'terminal': 4}
    """
    distance: dict[Vertex, int] = {source: 0}
    queue: deque[Vertex] = deque([source])
    while queue:
        vertex = queue.popleft()
        for following in sorted(ctg.successors(vertex), key=str):
            if following not in distance:
                distance[following] = distance[vertex] + 1
                queue.append(following)
    return distance


def connectivity_base(ctg: ConjugateTaskGraph) -> int:
    """The number of possible prerequisites: the largest prerequisite set on an edge into the terminal vertex
    (at least 1)."""
    sizes = [
        len(ctg.prerequisites(state))
        for source in ctg.predecessors(TERMINAL)
        for state in ctg.prerequisite_states(source, TERMINAL)
    ]
    return max([1, *sizes])


def connectivity_scores(ctg: ConjugateTaskGraph) -> dict[Vertex, float]:
    """The connectivity score of every vertex with an edge.

    Each inbound edge scores ``base - prerequisite_count`` and each outbound edge ``base / 2``, where ``base`` is
    :func:`connectivity_base`; a vertex's score is the sum over its edges (every edge of the multigraph counts).

    >>> from supportive.learning import HTNLearner
    >>> learner = HTNLearner().fit([["knife", "carrots", "celery"]])
    >>> scores = connectivity_scores(learner.ctg_)
    >>> [scores[learner.task_graph_.subgoal_index((a, 1))] for a in ("knife", "carrots", "celery")]
    [4.5, 3.5, 2.5]
    """
    base = connectivity_base(ctg)
    doubled: dict[Vertex, int] = {}
    for edge in ctg.edges():
        doubled[edge.target] = doubled.get(edge.target, 0) + 2 * (base - len(edge.prerequisites))
        doubled[edge.source] = doubled.get(edge.source, 0) + base
    return {vertex: score / 2 for vertex, score in doubled.items()}
