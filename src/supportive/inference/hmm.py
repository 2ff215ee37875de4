"""Goal inference (§2.1.7.1): flat and hierarchical HMMs over a task's subgoals, as estimators and online
filters.

Hidden state: the subgoal the observed agent is working on. Each moment it either goes on with it (probability
``stay``, learned from how long subgoals last) or finishes it and starts another, as the task model allows (see
:mod:`supportive.inference.transitions`). Each moment's contact events are scored by an
:class:`~supportive.inference.observations.ObservationModel`.

Filtering is the forward algorithm with the belief renormalised every step and the normaliser accumulated in log
space, so it stays exact and finite over any number of steps; one update costs the same at step 10 as at step
10,000. The belief over an internal node of the HTN (a subtask such as "attach the rear left leg") is the mass of
its leaves.
"""

from __future__ import annotations

import itertools
import math
from abc import ABC, abstractmethod
from collections.abc import Iterable, Sequence
from typing import Self

import numpy as np

from supportive.errors import LearningError
from supportive.estimator import Estimator
from supportive.inference.filtering import Belief, Filter, Labels
from supportive.inference.observations import ObservationModel
from supportive.inference.transitions import FlatTransitions, HierarchicalTransitions, TaskLayout
from supportive.tasks.htn import HTN, Leaf
from supportive.tasks.naming import named

__all__ = ["FlatHMM", "GoalFilter", "HierarchicalHMM", "fitted_events"]


def fitted_events(
    observations: ObservationModel | None,
    mean_duration: float,
    sequences: Sequence[Sequence[Iterable[str]]] | None,
    labels: Sequence[Sequence[str]] | None,
) -> tuple[ObservationModel | None, float]:
    """What a goal model's ``fit`` learns about contact events: from labelled demonstrations, the observation
    model (:meth:`ObservationModel.from_labelled`) and the mean number of moments a subgoal lasts; without
    them, the ``observations`` and ``mean_duration`` it was given.

    Raises:
        LearningError: when only one of ``sequences`` and ``labels`` is given, or they do not line up.
    """
    if sequences is None and labels is None:
        return observations, mean_duration
    if sequences is None or labels is None:
        raise LearningError("give both the observation sequences and their labels, or neither")
    model = ObservationModel.from_labelled(sequences, labels)
    runs = [1 + sum(1 for a, b in itertools.pairwise(tags) if a != b) for tags in labels if tags]
    steps = sum(len(tags) for tags in labels)
    return model, max(1.0, steps / max(1, sum(runs)))


class _GoalModel(Estimator, ABC):
    """What every goal model shares: a task's hierarchy and its contact events — an observation model and how
    long subgoals last, given or learned by ``fit`` — and ``filter()``, a fresh online
    :class:`~supportive.inference.filtering.Filter`.

    Args:
        htn: The task's hierarchy; its subgoals are the hidden states.
        observations: The contact-event model to use when ``fit`` is given no labelled demonstrations.
        mean_duration: Mean moments a subgoal lasts, likewise.

    Attributes (after ``fit``):
        htn_: The hierarchy with every subtask named.
        layout_: Its subgoals and subtasks, indexed.
        observations_: The observation model in use (None: none given, none learned).
        mean_duration_: The mean moments a subgoal lasts.
    """

    def __init__(
        self,
        htn: HTN,
        observations: ObservationModel | None = None,
        *,
        mean_duration: float = 5.0,
    ) -> None:
        if not (math.isfinite(mean_duration) and mean_duration >= 1.0):  # NaN and infinity would pass a comparison
            raise LearningError(f"mean_duration is in steps and must be a finite number of at least 1, got {mean_duration}")
        self.htn = htn
        self.observations = observations
        self.mean_duration = mean_duration

    def _fit_events(
        self, sequences: Sequence[Sequence[Iterable[str]]] | None, labels: Sequence[Sequence[str]] | None
    ) -> None:
        """Forget the last fit; name the hierarchy's subtasks and lay it out; take the contact events' model
        (:func:`fitted_events`)."""
        self._forget()
        self.observations_, self.mean_duration_ = fitted_events(self.observations, self.mean_duration, sequences, labels)
        self.htn_ = HTN(self.htn.task, tuple(named(r) for r in self.htn.roots), self.htn.top_level, self.htn.alternatives)
        self.layout_ = TaskLayout.of(self.htn_)

    @abstractmethod
    def filter(self) -> Filter:
        """A fresh online filter."""


class _SubgoalHMM(_GoalModel):
    """What the flat and the hierarchical HMM share; they differ only in their transitions.

    Args: as :class:`_GoalModel`.

    Attributes (after ``fit``), besides :class:`_GoalModel`'s:
        transitions_: How mass moves between subgoals.
        stay_: The probability of going on with the current subgoal, ``1 - 1 / mean_duration_``.
    """

    @abstractmethod
    def _transitions(self, htn: HTN, layout: TaskLayout) -> FlatTransitions | HierarchicalTransitions:
        """How mass moves between subgoals in this model."""

    # ------------------------------------------------------------------ estimator API
    def fit(
        self,
        sequences: Sequence[Sequence[Iterable[str]]] | None = None,
        labels: Sequence[Sequence[str]] | None = None,
    ) -> Self:
        """Build the model over the hierarchy; learn the observation model and how long subgoals last from
        labelled demonstrations when given, else use the ones given at construction.

        Args:
            sequences: Observation sequences (each observation: the contact events that hold).
            labels: For each sequence, the action being performed at each step.

        Raises:
            LearningError: for sequences and labels that do not line up.
        """
        self._fit_events(sequences, labels)
        self.transitions_ = self._transitions(self.htn_, self.layout_)
        self.stay_ = 1.0 - 1.0 / self.mean_duration_
        return self

    def filter(self) -> GoalFilter:
        """A fresh online filter.

        Raises:
            LearningError: without an observation model.
        """
        if self.observations_ is None:
            raise LearningError("no observation model: pass one, or call fit() on labelled demonstrations")
        return GoalFilter(self.layout_, self.transitions_, self.observations_, self.stay_)

    def predict_proba(self, sequence: Iterable[Iterable[str]]) -> np.ndarray:
        """Filtered probability of each subgoal at each step (rows: steps)."""
        running = self.filter()
        return np.array([running.update(o).subgoals for o in sequence])

    def predict(self, sequence: Iterable[Iterable[str]]) -> list[Leaf]:
        """The most probable current subgoal at each step."""
        leaves = self.layout_.leaves
        return [leaves[i] for i in self.predict_proba(sequence).argmax(axis=1)]

    def score(self, sequence: Iterable[Iterable[str]]) -> float:
        """log P(sequence) under the model."""
        running = self.filter()
        for observation in sequence:
            running.update(observation)
        return running.log_likelihood


class FlatHMM(_SubgoalHMM):
    """A traditional HMM over subgoals: a dense transition matrix, uniform over each subgoal's valid successors.

    >>> from supportive.learning import HTNLearner
    >>> htn = HTNLearner(mode="strict").fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]]).htn_
    >>> model = ObservationModel({"knife": {"hand-knife": .9}, "carrots": {"knife-carrot": .9}, "celery": {"knife-celery": .9}})
    >>> [a for a, _ in FlatHMM(htn, model).fit().predict([{"hand-knife"}, {"knife-celery"}])]
    ['knife', 'celery']
    """

    def _transitions(self, htn: HTN, layout: TaskLayout) -> FlatTransitions:
        return FlatTransitions(htn, layout)


class HierarchicalHMM(_SubgoalHMM):
    """A hierarchical HMM assembled from the CC-HTN: moves decided by chains and cliques (see
    :class:`~supportive.inference.transitions.HierarchicalTransitions`)."""

    def _transitions(self, htn: HTN, layout: TaskLayout) -> HierarchicalTransitions:
        return HierarchicalTransitions(htn, layout)


class GoalFilter(Labels):
    """Online filter (a :class:`~supportive.inference.filtering.Filter`): ``update(events) -> Belief`` in
    constant time per step.

    One update scores the observation under every action, moves the belief one step (one transition product,
    whose result also gives the next-subgoal prediction) and renormalises. The belief over subtasks is computed
    when it is first asked for.
    """

    def __init__(
        self,
        layout: TaskLayout,
        transitions: FlatTransitions | HierarchicalTransitions,
        observations: ObservationModel,
        stay: float,
    ) -> None:
        missing = sorted({a for a, _ in layout.leaves} - set(observations.actions))
        if missing:
            raise LearningError(f"the observation model has no row for action(s) {', '.join(missing)}")
        super().__init__(layout)
        self.transitions = transitions
        self.observations = observations
        self.stay = stay
        self._action_of_leaf = np.array([observations.action_index[a] for a, _ in layout.leaves])
        self.reset()

    def reset(self) -> None:
        """Forget every observation."""
        self._belief = self.transitions.start.copy()
        self._arriving = self.transitions.start.copy()
        self.step = 0
        self.log_likelihood = 0.0
        self.last = Belief(0, self._belief, self._arriving, self.layout, 0.0)

    def update(self, events: Iterable[str]) -> Belief:
        """Take one moment's contact events into account."""
        prior = self._belief * self.stay + self._arriving if self.step else self._belief
        scores = self.observations.log_likelihood(events)[self._action_of_leaf]
        peak = scores.max()
        posterior = prior * np.exp(scores - peak)
        total = posterior.sum()
        if not total > 0.0:
            raise LearningError(f"step {self.step + 1}: the observation is impossible under the model")
        self._belief = posterior / total
        self._arriving = self.transitions(self._belief * (1.0 - self.stay))
        self.log_likelihood += float(np.log(total) + peak)
        self.step += 1
        self.last = Belief(self.step, self._belief, self._arriving, self.layout, self.log_likelihood)
        return self.last

    def summary(self, belief: Belief, k: int = 3) -> dict[str, object]:
        """A belief as plain data: the ``k`` most probable current subgoals, enclosing subtasks and next
        subgoals, each as ``[label, probability]``."""

        def pairs(values: np.ndarray, labels: Sequence[str]) -> list[list[object]]:
            return [[label, round(p, 6)] for label, p in self.top(values, labels, k)]

        return {
            "step": belief.step,
            "subgoals": pairs(belief.subgoals, self.subgoal_labels),
            "subtasks": pairs(belief.enclosing, self.enclosing_labels),
            "next": pairs(belief.next_subgoals, self.subgoal_labels),
            "log_likelihood": round(belief.log_likelihood, 6),
        }
