"""Learn a CC-HTN from demonstrations, as one estimator that also learns one demonstration at a time.

Two learners share it. ``strict`` is the thesis's pipeline as first implemented here: task graph, CTG
(Algorithm 1), compaction (Algorithm 2) with every subtask observed in full, ambiguity resolution (Algorithms
3–4); it admits exactly the executions it can piece together from what was seen. ``general`` (the default)
accepts what the evidence supports — optional steps, repeated subtasks, cliques from contiguous runs seen in
several orders, chains from consistently ordered runs, a partial order where no tree fits, slips set aside —
see :mod:`supportive.learning.general` and docs/learning.md for the measurements behind the choice.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Literal, Self

from supportive.errors import LearningError
from supportive.estimator import Estimator
from supportive.learning.ambiguity import resolve_ambiguity
from supportive.learning.compaction import Compaction
from supportive.learning.conjugate import conjugate_task_graph, update_conjugate
from supportive.learning.general import GeneralResult, learn_general
from supportive.learning.noise import Deviation, NoiseEstimate, NoiseSettings
from supportive.learning.selection import CONSISTENT, READINGS, Selection, select_reading
from supportive.learning.structure import FittedStructure, StructureSettings, fit_structure
from supportive.tasks.htn import HTN, Leaf
from supportive.tasks.naming import known_names, named
from supportive.tasks.spec import Demonstration, TaskSpec
from supportive.tasks.task_graph import TaskGraph

__all__ = ["HTNLearner", "LearningStats", "learn"]

DemonstrationLike = Demonstration | Sequence[str]
Mode = Literal["auto", "general", "strict", "partial order"]


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
        mode: ``"auto"`` (default): learn the ``general``, ``strict`` and ``partial order`` readings (the
            first and last also with every consistent order established) and keep the one that best predicts
            held-out demonstrations (:mod:`~supportive.learning.selection`); or one of the three by name.
            Demonstrations with explicit states are always learned strictly.
        slips: ``general``: look for slips (steps out of order, repeated, missing or unknown) and learn
            without them (:mod:`~supportive.learning.noise`); False learns from every step as it is.
        slip_margin: ``general``: each slip is kept only when it makes the demonstrations more probable by
            more than this many nats (natural log-likelihood ratio against the explanation without it, after
            the noise it claims has been paid for); 0 or more. Default 2, with ``slip_rate`` 0.2: the setting
            ``supportive reproduce learner-settings`` picks on generated tasks (docs/learning.md).
        slip_rate: ``general`` and ``auto``: the prior mean of how often a step slips, per step and kind, in
            (0, 0.5); ``auto`` also charges it for each step a held-out demonstration has out of place.
        slip_rate_weight: ``general``: how many observed steps that prior is worth (each kind's rate is
            integrated out under a beta prior with this mean and weight, so demonstrations with many more
            steps outweigh it); above 0. Not swept: 1,000 steps is the size of the generated tasks' data
            (50–100 demonstrations of 6–12 steps), so the data and the prior weigh alike there.
        max_slip_candidates: ``general``: most single out-of-order steps a round of the slip search scores
            (the most telling first); at least 1. A bound on the work, not a model setting.
        evidence: ``general``: accept a subtask when the chance of its contiguity were it not one is below
            this (:func:`~supportive.learning.evidence.contiguity_chance`, a likelihood-ratio test), and take
            an order the demonstrations reverse far less often than the hierarchy predicts as agreed (the
            slip search's candidates, :mod:`~supportive.learning.noise`). The conventional 5 % level.
        order_support: ``general``: demonstrations showing two steps in one order that establish the order
            even when no step is between them (:func:`~supportive.learning.evidence.established_precedences`);
            by default the fewest with which that order would be chance below ``evidence`` (6 for 0.05).
        subtask_demonstrations: ``general``: from how many demonstrations on contiguous runs are made
            subtasks (chains and cliques); with fewer, the steps are kept in the orders the evidence
            establishes (a partial order, as a partial hierarchy's top level).
        selection_folds: ``auto``: folds of the cross-validation that chooses the reading (leave one out with
            fewer demonstrations); at least 2.
        selection_demonstrations: ``auto``: the fewest demonstrations the readings are compared on (with
            fewer, ``general`` is kept); at least 2.
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
        noise_: The noise model fitted with them: slips and rate per kind (``general``; None otherwise).
        reading_: The reading learned (one of :data:`~supportive.learning.selection.CANDIDATES`).
        selection_: Why it was chosen (``auto``; None otherwise).
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
        mode: Mode = "auto",
        slips: bool = True,
        slip_margin: float = 2.0,
        slip_rate: float = 0.2,
        slip_rate_weight: float = 1000.0,
        max_slip_candidates: int = 48,
        evidence: float = 0.05,
        order_support: int | None = None,
        subtask_demonstrations: int = 4,
        selection_folds: int = 5,
        selection_demonstrations: int = 5,
        alternatives: int = 8,
        max_alternative_roots: int = 64,
        names: dict[frozenset[Leaf], str] | None = None,
    ) -> None:
        if mode not in ("auto", *READINGS):
            raise LearningError(f"mode must be 'auto', 'general', 'strict' or 'partial order', got {mode!r}")
        if selection_folds < 2 or selection_demonstrations < 2:
            raise LearningError("selection_folds and selection_demonstrations must be at least 2")
        if alternatives < 0 or max_alternative_roots < 1:
            raise LearningError("alternatives must be >= 0 and max_alternative_roots >= 1")
        if not slip_margin >= 0.0:
            raise LearningError(f"slip_margin must be 0 or more, got {slip_margin}")
        if not 0.0 < slip_rate < 0.5:
            raise LearningError(f"slip_rate must be in (0, 0.5), got {slip_rate}")
        if not slip_rate_weight > 0.0:
            raise LearningError(f"slip_rate_weight must be above 0, got {slip_rate_weight}")
        if max_slip_candidates < 1:
            raise LearningError(f"max_slip_candidates must be at least 1, got {max_slip_candidates}")
        if not 0.0 < evidence <= 1.0:
            raise LearningError(f"evidence must be in (0, 1], got {evidence}")
        if order_support is not None and order_support < 1:
            raise LearningError(f"order_support must be >= 1, got {order_support}")
        if subtask_demonstrations < 1:
            raise LearningError(f"subtask_demonstrations must be >= 1, got {subtask_demonstrations}")
        self.mode = mode
        self.slips = slips
        self.slip_margin = slip_margin
        self.slip_rate = slip_rate
        self.slip_rate_weight = slip_rate_weight
        self.max_slip_candidates = max_slip_candidates
        self.evidence = evidence
        self.order_support = order_support
        self.subtask_demonstrations = subtask_demonstrations
        self.selection_folds = selection_folds
        self.selection_demonstrations = selection_demonstrations
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
        """Add one demonstration to what was learned, updating graph, CTG and HTN in place; the result equals
        ``fit`` on all demonstrations so far.

        The task graph and CTG are updated incrementally. The strict learner (``mode="strict"``, or
        demonstrations with explicit states) also recomputes only the compaction levels the new execution
        changes (see :meth:`Compaction.update`); the general and ``auto`` readings learn the hierarchy again
        from all demonstrations (slips searched and, for ``auto``, the reading chosen anew).
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

    def _structure_settings(self, reading: str) -> StructureSettings:
        """The evidence settings of a reading (``consistent orders``: two demonstrations establish an order)."""
        support = 2 if reading.endswith(CONSISTENT) else self.order_support
        return StructureSettings(self.evidence, support, self.subtask_demonstrations)

    def _general(self, sequences: Sequence[Sequence[str]], reading: str) -> GeneralResult:
        """The general learner in one of its readings, slips searched (:mod:`~supportive.learning.noise`)."""
        noise = NoiseSettings(
            math.inf if not self.slips else self.slip_margin,
            self.slip_rate,
            self.slip_rate_weight,
            self.max_slip_candidates,
        )
        return learn_general(
            sequences, self._structure_settings(reading), noise, modules=not reading.startswith("partial order")
        )

    def _reading(self, name: str, found: GeneralResult, indices: Sequence[int]) -> FittedStructure:
        """One reading learned from the demonstrations ``indices`` with the slips ``found`` taken out (for
        the selection, :mod:`~supportive.learning.selection`)."""
        cleaned = [found.cleaned[i] for i in indices]
        if name == "strict":
            graph = TaskGraph()
            for i, demo in enumerate(cleaned):
                graph.add([action for action, _ in demo], f"d{i + 1}")
            compaction = Compaction(graph)
            compaction.run()
            return FittedStructure(tuple(compaction.roots()), compaction.top_level())
        position = {d: i for i, d in enumerate(indices)}
        excused = [
            (position[d.demonstration], d.leaf)
            for d in found.deviations
            if d.kind in ("out of order", "missing") and d.demonstration in position
        ]
        return fit_structure(
            cleaned, excused, self._structure_settings(name), modules=not name.startswith("partial order")
        )

    def _selected(self, found: GeneralResult, general: FittedStructure) -> tuple[FittedStructure, Selection]:
        """The reading the held-out likelihood prefers, learned from the demonstrations with the slips
        ``found`` taken out, and why it was chosen."""
        fits: dict[tuple[str, tuple[int, ...]], FittedStructure] = {}

        def fit(name: str, indices: Sequence[int]) -> HTN:
            key = (name, tuple(indices))
            if key not in fits:
                fits[key] = self._reading(name, found, indices)
            return fits[key].htn()

        everything = tuple(range(len(found.cleaned)))
        fits[("general", everything)] = general
        selection = select_reading(
            [[action for action, _ in demo] for demo in found.cleaned],
            fit,
            general.htn(),
            folds=self.selection_folds,
            min_demonstrations=self.selection_demonstrations,
            slip_rate=self.slip_rate,
        )
        chosen = selection.chosen
        return fits.get((chosen, everything)) or self._reading(chosen, found, everything), selection

    def _compacted(self) -> Compaction:
        """Algorithm 2 over the task graph (run once, then kept up to date by ``partial_fit``)."""
        if self._compaction is None:
            self._compaction = Compaction(self.task_graph_)
            self._compaction.run()
        return self._compaction

    def _finish(self, started: float) -> None:
        names = self.names_
        self.selection_: Selection | None = None
        self.deviations_: tuple[Deviation, ...] = ()
        self.noise_: NoiseEstimate | None = None
        reading: str = "strict" if self.learns_strictly else self.mode
        if reading == "strict":
            compaction = self._compacted()
            roots = tuple(named(root, names) for root in compaction.roots())
            top = compaction.top_level()
            self.labelled_ = tuple(tuple(self.task_graph_.subgoals[s] for s in d) for d in self.task_graph_.demonstrations)
        else:
            sequences = [d.actions if isinstance(d, Demonstration) else tuple(d) for d in self._demos]
            result = self._general(sequences, "general" if reading == "auto" else reading)
            fitted = FittedStructure(result.roots, result.top_level)
            if reading == "auto":
                fitted, self.selection_ = self._selected(result, fitted)
                reading = self.selection_.chosen
            roots = tuple(named(root, names) for root in fitted.roots)
            top = fitted.top_level
            self.deviations_ = result.deviations
            self.noise_ = result.noise
            self.labelled_ = result.labelled
        self.reading_ = reading
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
