"""Learn a CC-HTN from demonstrations: task graph, CTG (Algorithm 1), compaction (Algorithm 2) and ambiguity
resolution (Algorithms 3–4), as one estimator that also learns one demonstration at a time."""

from __future__ import annotations

import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Self

from supportive.errors import LearningError
from supportive.learning.ambiguity import resolve_ambiguity
from supportive.learning.compaction import Compaction
from supportive.learning.conjugate import conjugate_task_graph, update_conjugate
from supportive.learning.naming import known_names, named
from supportive.tasks.htn import HTN, Leaf
from supportive.tasks.spec import Demonstration, TaskSpec
from supportive.tasks.task_graph import TaskGraph

__all__ = ["HTNLearner", "LearningStats", "learn"]

DemonstrationLike = Demonstration | Sequence[str]


@dataclass(frozen=True)
class LearningStats:
    """Sizes of what was learned, as in the JSON export's ``stats``."""

    demonstrations: int
    actions: int
    task_graph: dict[str, int]
    ctg: dict[str, int]
    htn: dict[str, float]
    seconds: float

    def as_dict(self) -> dict[str, Any]:
        """Plain-data form."""
        return {
            "demonstrations": self.demonstrations,
            "actions": self.actions,
            "task_graph": dict(self.task_graph),
            "ctg": dict(self.ctg),
            "htn": dict(self.htn),
            "seconds": self.seconds,
        }


class HTNLearner:
    """Clique/Chain HTN learner (§2.1).

    Args:
        alternatives: Most alternative hierarchies to look for when the result is partial (0: none).
        max_alternative_roots: Look for alternatives only when at most this many roots are left.
        names: Leaf set -> name for subtasks whose name is known (a ground truth's names, say).

    Attributes (after ``fit``):
        task_graph_: The environment-space task graph.
        ctg_: Its Conjugate Task Graph (redundant edges removed).
        htn_: The learned hierarchy with its alternatives.
        stats_: Sizes and time.

    >>> learner = HTNLearner().fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]])
    >>> learner.htn_.complete, learner.htn_.roots[0].kind
    (True, 'chain')
    """

    def __init__(
        self,
        *,
        alternatives: int = 8,
        max_alternative_roots: int = 64,
        names: dict[frozenset[Leaf], str] | None = None,
    ) -> None:
        if alternatives < 0 or max_alternative_roots < 1:
            raise LearningError("alternatives must be >= 0 and max_alternative_roots >= 1")
        self.alternatives = alternatives
        self.max_alternative_roots = max_alternative_roots
        self.names = names
        self.task = ""
        self.seconds_ = 0.0

    def fit(self, demonstrations: TaskSpec | Iterable[DemonstrationLike], task: str = "") -> Self:
        """Learn from scratch.

        Args:
            demonstrations: A task spec (its demonstrations, name and structure names are used) or demonstrations
                (``Demonstration`` objects or plain action sequences).
            task: Task name, when ``demonstrations`` is not a spec.

        Raises:
            LearningError: when there is no demonstration.
            TaskGraphError: when the demonstrations cannot form a task graph.
        """
        started = time.perf_counter()
        demos = self._demonstrations(demonstrations, task)
        if not demos:
            raise LearningError(f"task {self.task or '?'}: no demonstrations to learn from")
        self.task_graph_ = TaskGraph()
        for i, demo in enumerate(demos):
            if isinstance(demo, Demonstration):
                self.task_graph_.add_demonstration(demo)
            else:
                self.task_graph_.add(demo, f"d{i + 1}")
        self.ctg_ = conjugate_task_graph(self.task_graph_)
        self._compaction = Compaction(self.task_graph_)
        self._compaction.run()
        self._finish(started)
        return self

    def partial_fit(self, demonstration: DemonstrationLike) -> Self:
        """Add one demonstration to what was learned, updating graph, CTG and HTN in place.

        Only the compaction levels the new execution changes are recomputed (see
        :meth:`Compaction.update`); the result equals ``fit`` on all demonstrations so far.
        """
        if not hasattr(self, "task_graph_"):
            return self.fit([demonstration], self.task)
        started = time.perf_counter()
        graph = self.task_graph_
        if isinstance(demonstration, Demonstration):
            update = graph.add_demonstration(demonstration)
        elif isinstance(demonstration, str):
            raise LearningError("a demonstration is a sequence of action ids, not a string")
        else:
            update = graph.add(demonstration, f"d{len(graph.demonstrations) + 1}")
        if update.changed:
            update_conjugate(self.ctg_, update)
            self._compaction.update()
        self._finish(started)
        return self

    def _demonstrations(
        self, source: TaskSpec | Iterable[DemonstrationLike], task: str
    ) -> list[Demonstration | Sequence[str]]:
        if isinstance(source, TaskSpec):
            self.task = source.name
            if self.names is None:
                self.names = known_names(source.structure)
            return list(source.demonstrations)
        self.task = task
        demos = list(source)
        for index, demo in enumerate(demos):
            if isinstance(demo, str):
                raise LearningError(
                    f"demonstration {index + 1}: expected a sequence of action ids, got a string"
                )
        return demos

    def _finish(self, started: float) -> None:
        compaction = self._compaction
        names = self.names or {}
        roots = tuple(named(root, names) for root in compaction.roots())
        alternatives: tuple[HTN, ...] = ()
        if len(roots) > 1 and self.alternatives:
            found = resolve_ambiguity(
                compaction, limit=self.alternatives, max_roots=self.max_alternative_roots
            )
            alternatives = tuple(HTN(self.task, (named(root, names),)) for root, _ in found)
        self.htn_ = HTN(self.task, roots, compaction.top_level(), alternatives)
        self.seconds_ = time.perf_counter() - started
        graph, htn = self.task_graph_, self.htn_
        self.stats_ = LearningStats(
            demonstrations=len(graph.demonstrations),
            actions=len(graph.subgoals),
            task_graph={"states": graph.n_states, "edges": graph.n_edges, "paths": graph.path_count()},
            ctg={"vertices": self.ctg_.n_vertices, "edges": self.ctg_.n_edges},
            htn={
                "nodes": htn.node_count(),
                "edges": htn.edge_count(),
                "mean_action_depth": round(htn.mean_action_depth(), 4),
            },
            seconds=round(self.seconds_, 6),
        )


def learn(spec: TaskSpec, **options: Any) -> HTNLearner:
    """Learn the CC-HTN of a task spec from its demonstrations (see :class:`HTNLearner` for ``options``)."""
    return HTNLearner(**options).fit(spec)
