"""Learn a CC-HTN from demonstrations, as one estimator that also learns one demonstration at a time.

Two learners share it. ``strict`` is the thesis's pipeline as first implemented here: task graph, CTG
(Algorithm 1), compaction (Algorithm 2) with every subtask observed in full, ambiguity resolution (Algorithms
3–4); it admits exactly the executions it can piece together from what was seen. ``general`` (the default)
accepts what the evidence supports — optional steps, repeated subtasks, cliques from contiguous runs seen in
several orders, chains from consistently ordered runs, a partial order where no tree fits, slips set aside —
see :mod:`supportive.learning.general` and docs/learning.md for the measurements behind the choice.
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Literal, Self

from supportive.errors import LearningError
from supportive.estimator import Estimator
from supportive.learning.ambiguity import resolve_ambiguity
from supportive.learning.compaction import Compaction
from supportive.learning.conjugate import conjugate_task_graph, update_conjugate
from supportive.learning.deviations import Deviation
from supportive.learning.general import GeneralSettings, learn_general
from supportive.tasks.htn import HTN, Leaf
from supportive.tasks.naming import known_names, named
from supportive.tasks.spec import Demonstration, TaskSpec
from supportive.tasks.task_graph import TaskGraph

__all__ = ["HTNLearner", "LearningStats", "learn"]

DemonstrationLike = Demonstration | Sequence[str]
Mode = Literal["general", "strict"]


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


class HTNLearner(Estimator):
    """Clique/Chain HTN learner (§2.1).

    Args:
        mode: ``"general"`` (default) or ``"strict"`` (see the module docstring). Demonstrations with
            explicit states are always learned strictly.
        deviations: ``general``: the share of demonstrations that may perform or skip a step the others do
            not before it counts, and the most of all steps set aside as slips
            (:mod:`~supportive.learning.deviations`); 0 sets nothing aside.
        evidence: ``general``: accept a subtask when the chance of its contiguity were it not one is below
            this (:func:`~supportive.learning.evidence.contiguity_chance`), and an order despite a few
            demonstrations reversing it when a free pair would split so unevenly with chance below this
            (:func:`~supportive.learning.evidence.agreed_orders`).
        order_support: ``general``: demonstrations showing two steps in one order that establish the order
            even when no step is between them (:func:`~supportive.learning.evidence.established_precedences`);
            by default the fewest with which that order would be chance below ``evidence`` (6 for 0.05).
        subtask_demonstrations: ``general``: from how many demonstrations on contiguous runs are made
            subtasks (chains and cliques); with fewer, the steps are kept in the orders the evidence
            establishes (a partial order, as a partial hierarchy's top level).
        alternatives: Most alternative hierarchies to look for when the result is partial (0: none).
        max_alternative_roots: Look for alternatives only when at most this many roots are left.
        names: Leaf set -> name for subtasks whose name is known (a ground truth's names, say); by default
            the names of a task spec's ``structure``.

    Attributes (after ``fit``):
        task_: The task's name (the spec's, or ``fit``'s ``task``).
        names_: The subtask names used: ``names``, or the spec's structure's.
        task_graph_: The environment-space task graph.
        ctg_: Its Conjugate Task Graph (redundant edges removed).
        htn_: The learned hierarchy with its alternatives.
        deviations_: The slips set aside (``general``), in demonstration order.
        labelled_: Every demonstration as the leaves the hierarchy gave its steps.
        stats_: Sizes and time.

    >>> two = [["knife", "carrots", "celery"], ["knife", "celery", "carrots"]]
    >>> learner = HTNLearner(mode="strict").fit(two)
    >>> learner.htn_.complete, learner.htn_.roots[0].kind
    (True, 'chain')
    >>> HTNLearner().fit(two).htn_.complete  # two demonstrations: only orders, no subtasks yet
    False
    >>> HTNLearner().fit(two * 2).htn_.roots[0].kind  # four: knife, then carrots and celery in any order
    'chain'
    """

    def __init__(
        self,
        *,
        mode: Mode = "general",
        deviations: float = 0.1,
        evidence: float = 0.05,
        order_support: int | None = None,
        subtask_demonstrations: int = 4,
        alternatives: int = 8,
        max_alternative_roots: int = 64,
        names: dict[frozenset[Leaf], str] | None = None,
    ) -> None:
        if mode not in ("general", "strict"):
            raise LearningError(f"mode must be 'general' or 'strict', got {mode!r}")
        if alternatives < 0 or max_alternative_roots < 1:
            raise LearningError("alternatives must be >= 0 and max_alternative_roots >= 1")
        if not 0.0 <= deviations < 0.5:
            raise LearningError(f"deviations must be a share in [0, 0.5), got {deviations}")
        if not 0.0 < evidence <= 1.0:
            raise LearningError(f"evidence must be in (0, 1], got {evidence}")
        if order_support is not None and order_support < 1:
            raise LearningError(f"order_support must be >= 1, got {order_support}")
        if subtask_demonstrations < 1:
            raise LearningError(f"subtask_demonstrations must be >= 1, got {subtask_demonstrations}")
        self.mode = mode
        self.deviations = deviations
        self.evidence = evidence
        self.order_support = order_support
        self.subtask_demonstrations = subtask_demonstrations
        self.alternatives = alternatives
        self.max_alternative_roots = max_alternative_roots
        self.names = names

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
        self._forget()
        demos = self._demonstrations(demonstrations, task)
        if not demos:
            raise LearningError(f"task {self.task_ or '?'}: no demonstrations to learn from")
        self._demos = list(demos)
        self.task_graph_ = TaskGraph()
        for i, demo in enumerate(demos):
            if isinstance(demo, Demonstration):
                self.task_graph_.add_demonstration(demo)
            else:
                self.task_graph_.add(demo, f"d{i + 1}")
        self.ctg_ = conjugate_task_graph(self.task_graph_)
        self._compaction: Compaction | None = None
        self._finish(started)
        return self

    def partial_fit(self, demonstration: DemonstrationLike) -> Self:
        """Add one demonstration to what was learned, updating graph, CTG and HTN in place.

        Only the compaction levels the new execution changes are recomputed (see
        :meth:`Compaction.update`); the result equals ``fit`` on all demonstrations so far.
        """
        if not self.fitted:
            return self.fit([demonstration])
        started = time.perf_counter()
        graph = self.task_graph_
        if not isinstance(demonstration, str):
            self._demos.append(demonstration)
        if isinstance(demonstration, Demonstration):
            update = graph.add_demonstration(demonstration)
        elif isinstance(demonstration, str):
            raise LearningError("a demonstration is a sequence of action ids, not a string")
        else:
            update = graph.add(demonstration, f"d{len(graph.demonstrations) + 1}")
        if update.changed:
            update_conjugate(self.ctg_, update)
            if self._compaction is not None:
                self._compaction.update()
        self._finish(started)
        return self

    def _demonstrations(
        self, source: TaskSpec | Iterable[DemonstrationLike], task: str
    ) -> list[Demonstration | Sequence[str]]:
        if isinstance(source, TaskSpec):
            self.task_ = source.name
            self.names_ = self.names if self.names is not None else known_names(source.structure)
            return list(source.demonstrations)
        self.names_ = self.names or {}
        self.task_ = task
        demos = list(source)
        for index, demo in enumerate(demos):
            if isinstance(demo, str):
                raise LearningError(
                    f"demonstration {index + 1}: expected a sequence of action ids, got a string"
                )
        return demos

    @property
    def learns_strictly(self) -> bool:
        """True when this fit uses the ``strict`` learner (asked for, or explicit states given)."""
        return self.mode == "strict" or bool(self.task_graph_.explicit_states)

    def _compacted(self) -> Compaction:
        """Algorithm 2 over the task graph (run once, then kept up to date by ``partial_fit``)."""
        if self._compaction is None:
            self._compaction = Compaction(self.task_graph_)
            self._compaction.run()
        return self._compaction

    def _finish(self, started: float) -> None:
        names = self.names_
        if self.learns_strictly:
            compaction = self._compacted()
            roots = tuple(named(root, names) for root in compaction.roots())
            top = compaction.top_level()
            self.deviations_: tuple[Deviation, ...] = ()
            self.labelled_ = tuple(tuple(self.task_graph_.subgoals[s] for s in d) for d in self.task_graph_.demonstrations)
        else:
            sequences = [d.actions if isinstance(d, Demonstration) else tuple(d) for d in self._demos]
            settings = GeneralSettings(
                self.deviations, self.evidence, self.order_support, self.subtask_demonstrations
            )
            result = learn_general(sequences, settings)
            roots = tuple(named(root, names) for root in result.roots)
            top = result.top_level
            self.deviations_ = result.deviations
            self.labelled_ = result.labelled
        alternatives: tuple[HTN, ...] = ()
        if len(roots) > 1 and self.alternatives:
            found = resolve_ambiguity(
                self._compacted(), limit=self.alternatives, max_roots=self.max_alternative_roots
            )
            alternatives = tuple(HTN(self.task_, (named(root, names),)) for root, _ in found)
        self.htn_ = HTN(self.task_, roots, top, alternatives)
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
