"""What a query strategy sees: the learner's graphs, the demonstration so far, the vocabulary, the anti-edges.

The context also does the filtering every strategy shares (§2.2.6): an action is not asked for when it was
already executed in this demonstration, when a transition with it from the current state is already known in
the environment-space graph, or when ``(current state, action)`` is an anti-edge. A repeated action stays a
candidate while the task graph knows a further occurrence of it: the candidate then stands for that next
occurrence's subgoal.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from supportive.learning.active.anti_edges import AntiEdges
from supportive.tasks.conjugate import ORIGIN, ConjugateTaskGraph, Vertex
from supportive.tasks.task_graph import TaskGraph

__all__ = ["QueryContext"]


@dataclass(frozen=True)
class QueryContext:
    """Everything a strategy needs to choose a query.

    Args:
        task_graph: The learner's environment-space graph, or None before the first demonstration.
        ctg: Its Conjugate Task Graph, or None before the first demonstration.
        done: Actions done so far in the current demonstration, in order.
        actions: The action vocabulary; its order is the deterministic candidate order.
        anti_edges: Refused queries recorded so far.
        rng: Breaks ties.

    >>> from supportive.learning import HTNLearner
    >>> learner = HTNLearner().fit([["knife", "carrots", "celery"]])
    >>> ctx = QueryContext(learner.task_graph_, learner.ctg_, ("knife",), ("knife", "carrots", "celery"),
    ...                    AntiEdges(), np.random.default_rng(0))
    >>> ctx.candidates()  # knife is done, carrots is a known transition from here
    ('celery',)
    """

    task_graph: TaskGraph | None
    ctg: ConjugateTaskGraph | None
    done: tuple[str, ...]
    actions: tuple[str, ...]
    anti_edges: AntiEdges = field(default_factory=AntiEdges)
    rng: np.random.Generator = field(default_factory=np.random.default_rng)

    @cached_property
    def _counts(self) -> Counter[str]:
        return Counter(self.done)

    def next_subgoal(self, action: str) -> int | None:
        """The task-graph subgoal (CTG vertex) of ``action``'s next occurrence, or None when it is unknown."""
        if self.task_graph is None:
            return None
        return self.task_graph.subgoal_index((action, self._counts[action] + 1))

    @cached_property
    def current_states(self) -> tuple[int, ...]:
        """Task-graph states matching the done-multiset (none when the prefix left the known graph)."""
        graph = self.task_graph
        if graph is None:
            return ()
        if not self.done:
            return tuple(sorted(graph.initial))
        mask = 0
        seen: Counter[str] = Counter()
        for action in self.done:
            seen[action] += 1
            subgoal = graph.subgoal_index((action, seen[action]))
            if subgoal is None:
                return ()
            mask |= 1 << subgoal
        return tuple(state for state, known in enumerate(graph.mask) if known == mask)

    @cached_property
    def known_next(self) -> frozenset[str]:
        """Actions with a known transition from the current state."""
        graph = self.task_graph
        if graph is None:
            return frozenset()
        return frozenset(graph.subgoals[s][0] for state in self.current_states for s in graph.out[state])

    @cached_property
    def current_vertex(self) -> Vertex:
        """The CTG vertex of the last executed subgoal the graph knows; the origin when there is none."""
        graph = self.task_graph
        if graph is None:
            return ORIGIN
        counts = Counter(self.done)
        for action in reversed(self.done):
            subgoal = graph.subgoal_index((action, counts[action]))
            counts[action] -= 1
            if subgoal is not None:
                return subgoal
        return ORIGIN

    def candidates(self) -> tuple[str, ...]:
        """The actions a strategy may ask for, in vocabulary order."""
        blocked = self.anti_edges.blocked(self.done)
        known = self.known_next
        counts = self._counts
        return tuple(
            action
            for action in self.actions
            if action not in blocked
            and action not in known
            and (counts[action] == 0 or self.next_subgoal(action) is not None)
        )

    def pick(self, best: list[str]) -> str | None:
        """One of ``best`` (given in a deterministic order): the only one, or a seeded random choice."""
        if not best:
            return None
        if len(best) == 1:
            return best[0]
        return best[int(self.rng.integers(len(best)))]
