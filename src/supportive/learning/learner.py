"""Learn a CC-HTN from demonstrations, as one estimator that also learns one demonstration at a time.

A thin front over two learners that share no code (docs/learning.md, "Module layout"):

* ``strict`` (:mod:`supportive.learning.strict`) is the thesis's pipeline as first implemented here: task
  graph, CTG (Algorithm 1), compaction (Algorithm 2) with every subtask observed in full, ambiguity resolution
  (Algorithms 3–4); it admits exactly the executions it can piece together from what was seen.
* ``general`` (:mod:`supportive.learning.general`; the ``general`` and ``partial order`` readings) accepts
  what the evidence supports — optional steps, repeated subtasks, cliques from contiguous runs seen in several
  orders, chains from consistently ordered runs, a partial order where no tree fits, slips set aside.

``auto`` (the default) learns both wings' readings and keeps the one that best predicts held-out
demonstrations (:mod:`supportive.learning.selection`). Each wing builds only its own structures: a general
fit builds no task graph, CTG or compaction (``task_graph_`` and ``ctg_`` are built when first asked for), and
the alternatives a hierarchy reports are its own learner's.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Literal, Self

from supportive.errors import LearningError, NotFittedError, TaskGraphError
from supportive.estimator import Estimator
from supportive.learning.general import (
    Deviation,
    FittedStructure,
    GeneralResult,
    NoiseEstimate,
    NoiseSettings,
    SlipSearchCache,
    StructureSettings,
    alternatives_of,
    learn_general,
    refit,
)
from supportive.learning.selection import CANDIDATES, CONSISTENT, Selection, select_reading
from supportive.learning.strict import StrictLearner
from supportive.tasks.conjugate import ConjugateTaskGraph
from supportive.tasks.htn import HTN, Leaf, Node, TopLevel
from supportive.tasks.naming import known_names, named
from supportive.tasks.spec import Demonstration, TaskSpec
from supportive.tasks.task_graph import TaskGraph

__all__ = ["HTNLearner", "LearningStats", "learn"]

DemonstrationLike = Demonstration | Sequence[str]
Mode = Literal[
    "auto", "general", "strict", "partial order", "general (consistent orders)", "partial order (consistent orders)"
]


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
            held-out demonstrations (:mod:`~supportive.learning.selection`); or one of the three by name, or
            any reading ``auto`` may keep (``"general (consistent orders)"``, ``"partial order (consistent
            orders)"``: ``reading_`` of a learner fitted with ``auto`` pins its choice for another fit).
            Demonstrations with explicit states are always learned strictly.
        slips: ``general``: look for slips (steps out of order, repeated, missing or unknown) and learn
            without them (:mod:`~supportive.learning.general.noise`); False learns from every step as it is.
        slip_margin: ``general``: each slip is kept only when it makes the demonstrations more probable by
            more than this many nats (natural log-likelihood ratio against the explanation without it, after
            the noise it claims has been paid for); 0 or more. Default 0, with ``slip_rate`` 0.1,
            ``slip_rate_weight`` 300 and ``order_concentration`` 0.25: the setting ``supportive reproduce
            learner-settings`` picks on generated tasks (docs/learning.md).
        slip_rate: ``general`` and ``auto``: the prior mean of how often a step slips, per step and kind, in
            (0, 0.5); ``auto`` also charges it for each step a held-out demonstration has out of place.
        slip_rate_weight: ``general``: how many observed steps that prior is worth (each kind's rate is
            integrated out under a beta prior with this mean and weight, so demonstrations with many more
            steps outweigh it, and the rates of clean data fall toward 0 as they grow); above 0. Default
            300, with ``slip_margin``: swept over 100, 300 and 1,000 by ``supportive reproduce
            learner-settings`` on tasks done by people with and without habits.
        order_concentration: ``general``: how the slip search reads the orders a hierarchy admits. Each
            order choice it leaves open (a clique's order of its children, a partial top level's of its
            roots) has its own distribution over the orders admitted there, unknown, with a symmetric
            Dirichlet prior of this concentration, integrated out
            (:meth:`~supportive.learning.order_likelihood.OrderLikelihood.log_probability_of_all`): small
            values expect people's habits (an order several people take costs little, so a rare valid order
            is not read as a slip), large ones every admitted order equally likely (``math.inf``: exactly
            that, the reading before issue #23's habits work); above 0. Default 0.25, with ``slip_margin``: the
            setting ``supportive reproduce learner-settings`` picks on generated tasks done by people with
            and without habits (docs/learning.md).
        max_slip_candidates: ``general``: most single out-of-order steps a round of the slip search scores
            (the most telling first); at least 1. A bound on the work, not a model setting.
        slip_cache: ``general``: a :class:`~supportive.learning.general.noise.SlipSearchCache` shared by the
            fits of a sweep over the slip settings (``slip_margin``, ``slip_rate``, ``slip_rate_weight``,
            ``order_concentration``) on the same demonstrations, so that what no slip setting changes (the
            hierarchies learned with each set of slips taken out, the candidates) is learned once; None
            (default): nothing shared. Not a model setting: a fit gives the same result with it or without.
        evidence: ``general``: accept a subtask when the chance of its contiguity were it not one is below
            this (:func:`~supportive.learning.general.evidence.contiguity_chance`, a likelihood-ratio test), and take
            an order the demonstrations reverse far less often than the hierarchy predicts as agreed (the
            slip search's candidates, :mod:`~supportive.learning.general.noise`); a step out of order stands
            only when a sample of valid executions shows what the demonstrations show with a chance below
            this over the number of pairs of steps. Default 0.05, the conventional level, which ``supportive
            reproduce selection-settings`` keeps on generated tasks: the levels above it predict fresh
            executions a little better but admit fewer of them from issue #13's 4 demonstrations, and those
            below predict them worse by more than one standard error (docs/learning.md).
        order_support: ``general``: demonstrations showing two steps in one order that establish the order
            even when no step is between them (:func:`~supportive.learning.general.evidence.established_precedences`);
            by default the fewest with which that order would be chance below ``evidence`` (6 for 0.05).
        order_penalty: ``general``: a number of nats (0 or more): a partial top level keeps each order that
            every demonstration doing both roots keeps (two at least) and that is worth more than this against
            what the other orders already predict
            (:func:`~supportive.learning.general.evidence.weighed_precedences`: a pair free in a partial order
            is no coin); 0 keeps every such order. None: the coin test instead, the orders ``order_support``
            establishes. Default 1, the procedure's pick on generated tasks (``make bench``,
            benchmarks/results/order-penalty.json: the best task-graph F1 among the penalties learning in at
            most 1.5× the coin test's time; docs/learning.md).
        subtask_demonstrations: ``general``: from how many demonstrations on contiguous runs are made
            subtasks (chains and cliques); with fewer, the steps are kept in the orders the evidence
            establishes (a partial order, as a partial hierarchy's top level); at least 1 (1 and 2 alike: one
            demonstration is one chain). Default 3: the threshold ``supportive reproduce selection-settings``
            picks on generated tasks by held-out likelihood (docs/learning.md; 2 before 2026-12-07, when the
            run with the weighed top level and ``slip_rate_weight`` 300 chose 3).
        selection_folds: ``auto``: folds of the cross-validation that chooses the reading (leave one out with
            fewer demonstrations); at least 2.
        selection_demonstrations: ``auto``: the fewest demonstrations the readings are compared on (with
            fewer, ``general`` is kept); at least 2. Both defaults are the policy ``supportive reproduce
            selection-settings`` keeps on generated tasks: the conventional 5-fold cross-validation from 5
            demonstrations, which no policy keeping issue #13's recall beats there by more than one
            standard error (docs/learning.md).
        alternatives: Most alternative hierarchies to look for when the result is partial (0: none); the
            strict learner finds up to this many restrictions, the others one hierarchy admitting all the
            result admits (docs/learning.md, "Module layout").
        max_alternative_roots: Look for alternatives only when at most this many roots are left.
        names: Leaf set -> name for subtasks whose name is known (a ground truth's names, say); by default
            the names of a task spec's ``structure``.

    Attributes (after ``fit``):
        task_: The task's name (the spec's, or ``fit``'s ``task``).
        names_: The subtask names used: ``names``, or the spec's structure's.
        task_graph_: The environment-space task graph.
        ctg_: Its Conjugate Task Graph (redundant edges removed).
            Both belong to the strict learner: after a general fit they are built when first asked for.
        htn_: The learned hierarchy with its alternatives: ``mode="strict"``'s are restrictions (complete
            hierarchies each admitting only known executions, §2.1.5.3); the other modes' (whichever reading
            ``auto`` keeps) are one complete hierarchy admitting every execution the partial one admits
            (:mod:`~supportive.learning.general.alternatives`).
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
    >>> learner = HTNLearner(subtask_demonstrations=2).fit(two)  # subtasks from two demonstrations on
    >>> learner.htn_.roots[0].kind  # knife, then carrots and celery in any order (Figure 2.8)
    'chain'
    >>> HTNLearner().fit(two).htn_.complete  # the default makes subtasks from 3: two give only orders
    False
    """

    htn_: HTN
    reading_: str
    selection_: Selection | None
    deviations_: tuple[Deviation, ...]
    noise_: NoiseEstimate | None
    labelled_: tuple[tuple[Leaf, ...], ...]
    seconds_: float
    _stats: LearningStats | None

    def __init__(
        self,
        *,
        mode: Mode = "auto",
        slips: bool = True,
        slip_margin: float = 0.0,
        slip_rate: float = 0.1,
        slip_rate_weight: float = 300.0,
        order_concentration: float = 0.25,
        max_slip_candidates: int = 48,
        slip_cache: SlipSearchCache | None = None,
        evidence: float = 0.05,
        order_support: int | None = None,
        order_penalty: float | None = 1.0,
        subtask_demonstrations: int = 3,
        selection_folds: int = 5,
        selection_demonstrations: int = 5,
        alternatives: int = 8,
        max_alternative_roots: int = 64,
        names: dict[frozenset[Leaf], str] | None = None,
    ) -> None:
        if mode not in ("auto", *CANDIDATES):
            raise LearningError(f"mode must be 'auto' or a reading ({', '.join(map(repr, CANDIDATES))}), got {mode!r}")
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
        if not order_concentration > 0.0:
            raise LearningError(f"order_concentration must be above 0, got {order_concentration}")
        if max_slip_candidates < 1:
            raise LearningError(f"max_slip_candidates must be at least 1, got {max_slip_candidates}")
        if slip_cache is not None and not isinstance(slip_cache, SlipSearchCache):
            raise LearningError(f"slip_cache must be a SlipSearchCache or None, got {type(slip_cache).__name__}")
        if not 0.0 < evidence <= 1.0:
            raise LearningError(f"evidence must be in (0, 1], got {evidence}")
        if order_support is not None and order_support < 1:
            raise LearningError(f"order_support must be >= 1, got {order_support}")
        if order_penalty is not None and not order_penalty >= 0.0:
            raise LearningError(f"order_penalty must be 0 or more, got {order_penalty}")
        if subtask_demonstrations < 1:
            raise LearningError(f"subtask_demonstrations must be >= 1, got {subtask_demonstrations}")
        self.mode = mode
        self.slips = slips
        self.slip_margin = slip_margin
        self.slip_rate = slip_rate
        self.slip_rate_weight = slip_rate_weight
        self.order_concentration = order_concentration
        self.max_slip_candidates = max_slip_candidates
        self.slip_cache = slip_cache
        self.evidence = evidence
        self.order_support = order_support
        self.order_penalty = order_penalty
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
        self._strictly = self.mode == "strict" or any(
            isinstance(d, Demonstration) and d.has_states for d in demos
        )
        self._strict: StrictLearner | None = StrictLearner.of(demos) if self._strictly else None
        if not self._strictly:
            for i, demo in enumerate(demos):
                _check_steps(demo, i)
        self._finish(started)
        return self

    def partial_fit(self, demonstration: DemonstrationLike) -> Self:
        """Add one demonstration to what was learned; the result equals ``fit`` on all demonstrations so far.

        The strict learner updates its task graph, CTG and only the compaction levels the new execution
        changes (see :meth:`Compaction.update`); the general learner refits from all demonstrations.
        """
        if not self.fitted:
            return self.fit([demonstration])
        _check_action_ids([demonstration], len(self._demos))
        started = time.perf_counter()
        if self._strict is not None:
            self._strict.add(demonstration)
        else:
            _check_steps(demonstration, len(self._demos))
        self._demos.append(demonstration)
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
        _check_action_ids(demos)
        return demos

    @property
    def learns_strictly(self) -> bool:
        """True when this fit uses the ``strict`` learner (asked for, or explicit states given)."""
        self._check_fitted("learns_strictly")
        return self._strictly

    @property
    def task_graph_(self) -> TaskGraph:
        """The environment-space task graph (the strict learner's; after a general fit, built when first
        asked for)."""
        return self._strict_learner("task_graph_").graph

    @property
    def ctg_(self) -> ConjugateTaskGraph:
        """The task graph's Conjugate Task Graph (as ``task_graph_``)."""
        return self._strict_learner("ctg_").ctg

    @property
    def stats_(self) -> LearningStats:
        """Sizes of what was learned and the time ``fit`` (or the last ``partial_fit``) took; the task graph's
        and CTG's sizes build them when a general fit has not."""
        self._check_fitted("stats_")
        if self._stats is None:
            graph, ctg, htn = self.task_graph_, self.ctg_, self.htn_
            self._stats = LearningStats(
                demonstrations=len(graph.demonstrations),
                actions=len(graph.subgoals),
                task_graph={"states": graph.n_states, "edges": graph.n_edges, "paths": graph.path_count()},
                ctg={"vertices": ctg.n_vertices, "edges": ctg.n_edges},
                htn={
                    "nodes": htn.node_count(),
                    "edges": htn.edge_count(),
                    "mean_action_depth": round(htn.mean_action_depth(), 4),
                },
                seconds=round(self.seconds_, 6),
            )
        return self._stats

    def _check_fitted(self, name: str) -> None:
        if "htn_" not in vars(self):
            raise NotFittedError(
                f"{type(self).__name__} is not fitted: call fit(...) before asking for {name}"
            )

    def _strict_learner(self, name: str) -> StrictLearner:
        """The strict learner's structures of the demonstrations (built now after a general fit)."""
        self._check_fitted(name)
        if self._strict is None:
            self._strict = StrictLearner.of(self._demos)
        return self._strict

    def _structure_settings(self, reading: str) -> StructureSettings:
        """The evidence settings of a reading (``consistent orders``: two demonstrations establish an order)."""
        if reading.endswith(CONSISTENT):
            return StructureSettings(self.evidence, 2, self.subtask_demonstrations)
        return StructureSettings(self.evidence, self.order_support, self.subtask_demonstrations, self.order_penalty)

    def _general(self, sequences: Sequence[Sequence[str]], reading: str) -> GeneralResult:
        """The general learner in one of its readings, slips searched (:mod:`~supportive.learning.general.noise`)."""
        noise = NoiseSettings(
            math.inf if not self.slips else self.slip_margin,
            self.slip_rate,
            self.slip_rate_weight,
            self.max_slip_candidates,
            self.order_concentration,
        )
        return learn_general(
            sequences,
            self._structure_settings(reading),
            noise,
            modules=not reading.startswith("partial order"),
            cache=self.slip_cache,
        )

    def _reading(self, name: str, found: GeneralResult, indices: Sequence[int]) -> HTN:
        """One reading learned from the demonstrations ``indices`` with the slips ``found`` undone (for
        the selection, :mod:`~supportive.learning.selection`)."""
        if name == "strict":
            result = StrictLearner.of(_actions(found, indices)).result(alternatives=0, max_roots=1)
            return HTN("", result.roots, result.top_level)
        structure = self._structure_settings(name)
        return refit(found, indices, structure, modules=not name.startswith("partial order")).htn()

    def _selected(self, found: GeneralResult, general: FittedStructure) -> tuple[Selection, HTN]:
        """Why a reading was chosen by the held-out likelihood, and that reading learned from the
        demonstrations with the slips ``found`` undone (as they are, when there are none)."""
        fits: dict[tuple[str, tuple[int, ...]], HTN] = {}

        def fit(name: str, indices: Sequence[int]) -> HTN:
            key = (name, tuple(indices))
            if key not in fits:
                fits[key] = self._reading(name, found, indices)
            return fits[key]

        everything = tuple(range(len(found.restored)))
        fits[("general", everything)] = general.htn()
        selection = select_reading(
            _actions(found, everything),
            fit,
            general.htn(),
            folds=self.selection_folds,
            min_demonstrations=self.selection_demonstrations,
            slip_rate=self.slip_rate,
        )
        return selection, fit(selection.chosen, everything)

    def _learned(self) -> tuple[str, tuple[Node, ...], TopLevel | None, tuple[Node, ...]]:
        """The reading learned, its roots, top level and alternatives: the strict learner's when it learns
        alone (``mode="strict"`` or explicit states), else the general learner's, whichever reading ``auto``
        keeps (its alternative admits every execution the hierarchy admits); the labels, and the slips and
        noise the general learner found, are set on the way."""
        limit, most = self.alternatives, self.max_alternative_roots
        if self._strictly:
            assert self._strict is not None
            result = self._strict.result(alternatives=limit, max_roots=most)
            self.labelled_ = result.labelled
            return "strict", result.roots, result.top_level, result.alternatives
        sequences = [d.actions if isinstance(d, Demonstration) else tuple(d) for d in self._demos]
        found = self._general(sequences, "general" if self.mode == "auto" else self.mode)
        self.deviations_, self.noise_, self.labelled_ = found.deviations, found.noise, found.labelled
        fitted = FittedStructure(found.roots, found.top_level)
        reading: str = self.mode
        if self.mode == "auto":
            self.selection_, chosen = self._selected(found, fitted)
            reading = self.selection_.chosen
            fitted = FittedStructure(chosen.roots, chosen.top_level)  # its alternative too: one admitting all
        return reading, fitted.roots, fitted.top_level, alternatives_of(fitted, limit=limit, max_roots=most)

    def _finish(self, started: float) -> None:
        self.selection_ = None
        self.deviations_ = ()
        self.noise_ = None
        self._stats = None
        reading, roots, top, alternatives = self._learned()
        self.reading_ = reading
        names = self.names_
        self.htn_ = HTN(
            self.task_,
            tuple(named(root, names) for root in roots),
            top,
            tuple(HTN(self.task_, (named(root, names),)) for root in alternatives),
        )
        self.seconds_ = time.perf_counter() - started


def _actions(found: GeneralResult, indices: Iterable[int]) -> list[list[str]]:
    """The demonstrations ``indices`` of ``found`` with their slips undone (a step out of order or missing
    put back where the hierarchy admits it; repeated and unknown ones taken out), as action ids: what the
    strict reading learns from and the selection holds out (a step deleted, not put back, would make it
    optional to the strict learner and a refused demonstration to the others)."""
    return [[action for action, _ in found.restored[i]] for i in indices]


def _check_action_ids(demos: Sequence[DemonstrationLike], first: int = 0) -> None:
    """Plain demonstrations (not :class:`Demonstration` objects, which check themselves), numbered from
    ``first``, are sequences of action ids: none is a string, and every step is a string.

    Raises:
        LearningError: naming the first demonstration (1-based) and step that is not an action id.
    """
    plain = [demo for demo in demos if not isinstance(demo, Demonstration)]
    if not any(map(str.__instancecheck__, plain)) and set(map(type, itertools.chain.from_iterable(plain))) <= {str}:
        return  # the usual case, checked at C speed
    for index, demo in enumerate(demos, start=first):
        if isinstance(demo, str):
            raise LearningError(f"demonstration {index + 1}: expected a sequence of action ids, got a string")
        if isinstance(demo, Demonstration):
            continue
        for k, step in enumerate(demo):
            if not isinstance(step, str):
                raise LearningError(
                    f"demonstration {index + 1}, step {k + 1}: expected an action id (a string), got {type(step).__name__}"
                )


def _check_steps(demo: DemonstrationLike, index: int) -> None:
    """The task graph's checks of a demonstration, for a fit without explicit states that builds none: it
    has a step and gives no explicit state."""
    if isinstance(demo, Demonstration):
        if demo.has_states:
            raise TaskGraphError(f"demonstration {demo.id or '?'}: all demonstrations must give explicit states, or none")
        if not demo.actions:
            raise TaskGraphError(f"demonstration {demo.id or '?'} has no steps")
    elif not demo:
        raise TaskGraphError(f"demonstration d{index + 1} has no steps")


def learn(spec: TaskSpec, **options: Any) -> HTNLearner:
    """Learn the CC-HTN of a task spec from its demonstrations (see :class:`HTNLearner` for ``options``)."""
    return HTNLearner(**options).fit(spec)
