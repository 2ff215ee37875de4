"""Track a teammate through a task: a progress-aware filter driven by contact events or by known actions.

The belief is over the states of :class:`~supportive.learning.distribution.ProgressModel` (what is done, what is
under way) plus **finished**. Two kinds of evidence move it, through one filter:

* :meth:`ProgressFilter.update` takes one moment's contact events (the observation model of §2.1.7.1): the
  teammate goes on with the current subgoal (probability ``stay``, from how long subgoals last) or finishes it
  and starts the next as the model says; the events are scored under the action of each state's subgoal.
* :meth:`ProgressFilter.observe` takes one completed action (a step the task board reported, a label from a
  dataset): the belief moves to the states that action leads to.

**Slips.** With probability ``slip`` a step is off-script (an order nobody showed, a mislabel, a step
skipped): the belief never becomes zero. An off-script action re-synchronises to the nearest state ahead in
which it was just done (an action with no such state — unknown, repeated, its place passed — leaves the
progress as it was); an off-script step read from contact events skips one step. Every belief says how likely
it is that the last step was off-script (``off_script``) and how surprising it was (``surprise``, in bits), so
callers can flag it. The transition is written once
(:class:`~supportive.inference.progress_step.ProgressStep`).

States are enumerated when there are at most ``max_states`` of them and the belief is moved as a vector by
sparse matrices (exact); beyond that it is a map from state to probability cut to the ``beam`` most probable
states (an approximation; docs/inference.md measures it against the exact filter). Both forms apply the same
transition, so a beam that holds every state gives the exact filter's beliefs.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Self

import numpy as np

from supportive.errors import LearningError
from supportive.inference.filtering import Belief, Labels
from supportive.inference.hmm import _GoalModel
from supportive.inference.observations import ObservationModel
from supportive.inference.progress_step import ProgressStep, State, StateMasses, VectorMasses
from supportive.inference.transitions import TaskLayout
from supportive.learning.distribution import ProgressModel
from supportive.tasks.htn import HTN

__all__ = ["END_LABEL", "ProgressBelief", "ProgressFilter", "ProgressHMM"]

END_LABEL = "<end>"
"""The key of "the task is finished" among next-step predictions."""


@dataclass(frozen=True)
class _Details:
    """What a belief works out only when asked: where the next step goes, what is done, finished."""

    arriving: np.ndarray
    finished: float
    done: np.ndarray
    next_actions: dict[str, float]


class ProgressBelief(Belief):
    """A :class:`~supportive.inference.hmm.Belief` that also knows what is done (worked out when first
    asked for, so that an update costs only the move of the probabilities).

    Attributes (besides the HMM belief's):
        finished: Probability that the task is finished.
        done: Probability that each subgoal (in :attr:`ProgressFilter.subgoal_labels` order) is done.
        next_actions: Probability of each action id being done next, plus :data:`END_LABEL`; sums to one.
        off_script: Probability that the last step was off-script (a slip).
        surprise: ``-log2`` of the probability the filter gave the last step (bits).
    """

    def __init__(
        self,
        step: int,
        subgoals: np.ndarray,
        layout: TaskLayout,
        ll: float,
        *,
        off_script: float,
        surprise: float,
        details: Callable[[], _Details],
    ) -> None:
        super().__init__(step, subgoals, subgoals, layout, ll)
        self.off_script = off_script
        self.surprise = surprise
        self._work_out = details

    @cached_property
    def _details(self) -> _Details:
        return self._work_out()

    @property
    def finished(self) -> float:
        """Probability that the task is finished."""
        return self._details.finished

    @property
    def done(self) -> np.ndarray:
        """Probability that each subgoal is done."""
        return self._details.done

    @property
    def next_actions(self) -> dict[str, float]:
        """Probability of each action id being done next, plus :data:`END_LABEL`."""
        return self._details.next_actions

    @cached_property
    def next_subgoals(self) -> np.ndarray:
        """Probability of each subgoal being the next one started (the task's end left out)."""
        arriving = self._details.arriving
        total = arriving.sum()
        return arriving / total if total > 0 else arriving


class ProgressHMM(_GoalModel):
    """The progress-aware model of a task as an estimator: ``fit()`` builds it, ``filter()`` gives online
    trackers.

    Args:
        htn: The task's hierarchy (its learned ``counts`` weight the choices).
        observations: The contact-event model (needed only for :meth:`ProgressFilter.update`) to use when
            ``fit`` is given no labelled demonstrations.
        mean_duration: Mean time steps a subgoal lasts (contact-event filtering), likewise.
        smoothing: Pseudo-counts per option of every choice (see :class:`ProgressModel`).
        slip: Probability that a step is off-script.
        restart: After the task is finished, it may start again (otherwise finished is final).
        max_states: Enumerate the states (exact) up to this many; beyond, keep a beam.
        beam: States kept by the approximate filter.

    Attributes (after ``fit``):
        htn_: The hierarchy with every subtask named.
        model_: The progress model over it.
        layout_: Its subgoals and subtasks, indexed.
        states_: The enumerated states, or None beyond ``max_states`` (beam mode).
        transition_: The one transition every filter of this model applies (its caches shared by them).
        observations_: The observation model in use (None: known actions only).
        mean_duration_: The mean moments a subgoal lasts.
    """

    def __init__(
        self,
        htn: HTN,
        observations: ObservationModel | None = None,
        *,
        mean_duration: float = 5.0,
        smoothing: float = 1.0,
        slip: float = 0.02,
        restart: bool = False,
        max_states: int = 50_000,
        beam: int = 2_000,
    ) -> None:
        super().__init__(htn, observations, mean_duration=mean_duration)
        if not 0.0 < slip < 1.0:
            raise LearningError(f"slip must be a probability in (0, 1), got {slip}")
        if beam < 1 or max_states < 1:
            raise LearningError("beam and max_states must be at least 1")
        self.smoothing = smoothing
        self.slip = slip
        self.restart = restart
        self.max_states = max_states
        self.beam = beam

    def fit(
        self,
        sequences: Sequence[Sequence[Iterable[str]]] | None = None,
        labels: Sequence[Sequence[str]] | None = None,
    ) -> Self:
        """Build the progress model over the hierarchy (and enumerate its states, up to ``max_states``); learn
        the observation model and how long subgoals last from labelled demonstrations when given (see
        :func:`~supportive.inference.hmm.fitted_events`), else use the ones given at construction.

        Raises:
            LearningError: for sequences and labels that do not line up.
        """
        self._fit_events(sequences, labels)
        self.model_ = ProgressModel(self.htn_, smoothing=self.smoothing)
        self.states_ = self.model_.states(self.max_states)
        self.transition_ = ProgressStep(
            self.model_,
            stay=1.0 - 1.0 / self.mean_duration_,
            slip=self.slip,
            restart=self.restart,
            limit=max(self.max_states, self.beam),
            states=self.states_,
        )
        return self

    @property
    def exact(self) -> bool:
        """True when the states were enumerated (no beam)."""
        return self.states_ is not None

    def filter(self) -> ProgressFilter:
        """A fresh online tracker."""
        return ProgressFilter(self)


class ProgressFilter(Labels):
    """Online tracker over a :class:`ProgressHMM` (see the module docstring), an
    :class:`~supportive.inference.filtering.ActionFilter`: ``update(events)`` or ``observe(action)``, each
    returning a :class:`ProgressBelief`.

    Attributes:
        transition: The one transition both forms of the belief apply
            (:class:`~supportive.inference.progress_step.ProgressStep`).
        belief: The belief as a map from state to probability (None: finished); the exact tracker holds it
            as a vector while contact events arrive and makes the map when asked.
    """

    def __init__(self, hmm: ProgressHMM) -> None:
        super().__init__(hmm.layout_)
        self.hmm = hmm
        self.model = hmm.model_
        self.leaves = self.model.leaves
        self.actions = tuple(dict.fromkeys(a for a, _ in self.leaves))
        self.transition = hmm.transition_
        self._states = StateMasses(self.transition, None if hmm.exact else hmm.beam)
        self._vectors: VectorMasses | None = None  # the model's, when contact events first arrive (exact only)
        if hmm.observations_ is not None:
            missing = sorted(set(self.actions) - set(hmm.observations_.actions))
            if missing:
                raise LearningError(f"the observation model has no row for action(s) {', '.join(missing)}")
            self._event_action = np.array([hmm.observations_.action_index[a] for a, _ in self.leaves])
        self.reset()

    def reset(self) -> None:
        """Forget everything observed: the task has not started."""
        start = self.model.executions.initial()
        self._map: dict[State, float] | None = {s: 1.0 / len(start) for s in start}
        self._vector: np.ndarray | None = None
        self.step = 0
        self.log_likelihood = 0.0
        self._seen: Counter[str] = Counter()
        self._last = self._summarise(0.0, 0.0)

    # ------------------------------------------------------------------ evidence
    def observe(self, action: str) -> ProgressBelief:
        """Take one completed action into account (an unknown action is a slip, never an error)."""
        self._seen[action] += 1
        on, off = self.transition.act(self._as_map(), action)
        return self._posterior(self._states, on, off, 0.0)

    def update(self, events: Iterable[str]) -> ProgressBelief:
        """Take one moment's contact events into account."""
        observations = self.hmm.observations_
        if observations is None:
            raise LearningError("no observation model: pass one to ProgressHMM, or fit it on labelled demonstrations")
        scores = observations.log_likelihood(events)[self._event_action]
        peak = float(scores.max())
        likelihood = np.exp(scores - peak)
        weights = np.append(likelihood, likelihood.mean())  # the last: finished or not started
        vectors = self._as_vector()
        if vectors is not None:
            assert self._vector is not None
            on_v, off_v = self.transition.moment(vectors, self._vector, weights)
            return self._posterior(vectors, on_v, off_v, peak)
        on, off = self.transition.moment(self._states, self._as_map(), weights)
        return self._posterior(self._states, on, off, peak)

    @property
    def belief(self) -> Mapping[State, float]:
        """The belief as a map from state to probability (None: finished)."""
        return self._as_map()

    def _as_map(self) -> dict[State, float]:
        """The belief as a map from state to probability (known actions move it so)."""
        if self._map is None:
            assert self._vectors is not None and self._vector is not None
            self._map, self._vector = self._vectors.to_map(self._vector), None
        return self._map

    def _as_vector(self) -> VectorMasses | None:
        """The belief as a vector over the enumerated states (the exact tracker; None in beam mode)."""
        if self._vectors is None:
            self._vectors = self.transition.vectors()
        if self._vectors is None:
            return None
        if self._vector is None:
            assert self._map is not None
            self._vector, self._map = self._vectors.of(self._map), None
        return self._vectors

    def _posterior(self, form: StateMasses | VectorMasses, on: Any, off: Any, peak: float) -> ProgressBelief:
        """Normalise the mass after one piece of evidence (``peak``: the log-scale taken out of the
        likelihoods) and summarise it."""
        merged: Any = form.plus(on, off, 1.0)
        total = form.total(merged)
        if not total > 0:
            raise LearningError(f"step {self.step + 1}: the evidence is impossible under the model")
        if isinstance(form, VectorMasses):
            self._vector = form.normalised(merged, total)
        else:
            self._map = form.normalised(merged, total)
        self.step += 1
        self.log_likelihood += peak + math.log(total)
        self._last = self._summarise(form.total(off) / total, -math.log2(total))
        return self._last

    # ------------------------------------------------------------------ belief
    def _summarise(self, off_script: float, surprise: float) -> ProgressBelief:
        form: StateMasses | VectorMasses
        belief: Any
        if self._vector is not None:
            assert self._vectors is not None
            form, belief = self._vectors, self._vector
        else:
            form, belief = self._states, self._map
        seen = dict(self._seen)

        def details() -> _Details:
            return self._details(*form.expectations(belief), seen)

        return ProgressBelief(
            self.step,
            form.current(belief),
            self.layout,
            self.log_likelihood,
            off_script=off_script,
            surprise=surprise,
            details=details,
        )

    def _details(
        self, done: np.ndarray, arriving: np.ndarray, actions: np.ndarray, finished: float, seen: Mapping[str, int]
    ) -> _Details:
        next_actions = dict(zip((*self.actions, END_LABEL), actions.tolist(), strict=True))
        for action, count in seen.items():  # done as often as the task has it: not again, whatever the
            if count >= len(self.transition.leaves_of.get(action, ())):  # belief says after a slip
                next_actions.pop(action, None)
        slip = self.hmm.slip
        on_script = sum(next_actions.values())
        uniform = slip / (len(self.actions) + 1)
        predicted = {
            a: (1.0 - slip) * (next_actions.get(a, 0.0) / on_script if on_script > 0 else 0.0) + uniform
            for a in (*self.actions, END_LABEL)
        }
        total = sum(predicted.values())
        return _Details(arriving, finished, done, {a: p / total for a, p in predicted.items()})

    @property
    def last(self) -> ProgressBelief:
        """The belief after the last piece of evidence (before any: the task not started)."""
        return self._last

    def summary(self, belief: Belief, k: int = 3) -> dict[str, object]:
        """A belief as plain data, as :meth:`GoalFilter.summary <supportive.inference.hmm.GoalFilter.summary>`
        gives it (``next`` by action id, ``<end>`` included), plus ``finished`` and ``off_script``
        probabilities and the step's ``surprise`` in bits."""

        def pairs(values: np.ndarray, labels: tuple[str, ...]) -> list[list[object]]:
            return [[label, round(p, 6)] for label, p in self.top(values, labels, k)]

        assert isinstance(belief, ProgressBelief)  # a ProgressFilter makes only these
        ranked = sorted(belief.next_actions.items(), key=lambda kv: (-kv[1], kv[0]))[:k]
        return {
            "step": belief.step,
            "subgoals": pairs(belief.subgoals, self.subgoal_labels),
            "subtasks": pairs(belief.enclosing, self.enclosing_labels),
            "next": [[action, round(p, 6)] for action, p in ranked],
            "finished": round(belief.finished, 6),
            "off_script": round(belief.off_script, 6),
            "log_likelihood": round(belief.log_likelihood, 6),
        }
