"""The ``strict`` learner: the thesis's pipeline, kept up to date one demonstration at a time.

The demonstrations' environment-space task graph, its Conjugate Task Graph (Algorithm 1), compaction with
every subtask observed in full (Algorithm 2) and, when compaction stops with several roots, alternative
hierarchies by ambiguity resolution (Algorithms 3–4). It admits exactly the executions it can piece together
from what was seen; its alternatives are *restrictions*: complete hierarchies that each admit only known
executions (§2.1.5.3), not every one the main hierarchy admits. docs/learning.md §1–5.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from supportive.learning.strict.ambiguity import resolve_ambiguity
from supportive.learning.strict.compaction import Compaction
from supportive.learning.strict.conjugate import conjugate_task_graph, update_conjugate
from supportive.tasks.conjugate import ConjugateTaskGraph
from supportive.tasks.htn import Leaf, Node, TopLevel
from supportive.tasks.spec import Demonstration
from supportive.tasks.task_graph import GraphUpdate, TaskGraph

__all__ = ["StrictLearner", "StrictResult"]


@dataclass(frozen=True)
class StrictResult:
    """Roots and top level (None when one root is left) of the strict hierarchy, its complete alternatives
    (best first, :func:`~supportive.learning.strict.ambiguity.resolve_ambiguity`) and every demonstration as
    the leaves it performs."""

    roots: tuple[Node, ...]
    top_level: TopLevel | None
    alternatives: tuple[Node, ...]
    labelled: tuple[tuple[Leaf, ...], ...]


class StrictLearner:
    """The task graph and CTG of the demonstrations added so far, and their compaction (run when first
    asked for, then updated level by level as demonstrations are added, :meth:`Compaction.update`).

    >>> strict = StrictLearner.of([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]])
    >>> result = strict.result(alternatives=8, max_roots=64)
    >>> [root.kind for root in result.roots], result.alternatives
    (['chain'], ())
    """

    def __init__(self, graph: TaskGraph) -> None:
        self.graph = graph
        self.ctg: ConjugateTaskGraph = conjugate_task_graph(graph)
        self._compaction: Compaction | None = None

    @classmethod
    def of(cls, demonstrations: Iterable[Demonstration | Sequence[str]]) -> StrictLearner:
        """The task graph and CTG of ``demonstrations`` (``Demonstration`` objects or action sequences).

        Raises:
            TaskGraphError: when the demonstrations cannot form a task graph.
        """
        graph = TaskGraph()
        for demo in demonstrations:
            _add(graph, demo)
        return cls(graph)

    def add(self, demonstration: Demonstration | Sequence[str]) -> None:
        """Add one demonstration: the task graph and CTG in place, then only the compaction levels the new
        execution changes (the result equals :meth:`of` all demonstrations so far)."""
        update = _add(self.graph, demonstration)
        if update.changed:
            update_conjugate(self.ctg, update)
            if self._compaction is not None:
                self._compaction.update()

    def result(self, *, alternatives: int, max_roots: int) -> StrictResult:
        """The hierarchy compaction learns, with at most ``alternatives`` alternative hierarchies, looked for
        only when between 2 and ``max_roots`` roots are left."""
        compaction = self._compacted()
        roots = tuple(compaction.roots())
        found: tuple[Node, ...] = ()
        if len(roots) > 1 and alternatives:
            found = tuple(
                root for root, _ in resolve_ambiguity(compaction, limit=alternatives, max_roots=max_roots)
            )
        labelled = tuple(tuple(self.graph.subgoals[s] for s in demo) for demo in self.graph.demonstrations)
        return StrictResult(roots, compaction.top_level(), found, labelled)

    def _compacted(self) -> Compaction:
        """Algorithm 2 over the task graph (run once, then kept up to date by :meth:`add`)."""
        if self._compaction is None:
            self._compaction = Compaction(self.graph)
            self._compaction.run()
        return self._compaction


def _add(graph: TaskGraph, demo: Demonstration | Sequence[str]) -> GraphUpdate:
    """Add ``demo`` to ``graph`` (a plain sequence named by its place, ``d1``, ``d2``, …)."""
    if isinstance(demo, Demonstration):
        return graph.add_demonstration(demo)
    return graph.add(demo, f"d{len(graph.demonstrations) + 1}")
