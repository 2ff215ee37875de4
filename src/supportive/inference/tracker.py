"""Track a teammate through a task: a progress-aware filter driven by contact events or by known actions.

The belief is over the states of :class:`~supportive.learning.distribution.ProgressModel` (what is done, what is
under way) plus **finished**. Two kinds of evidence move it, through one filter:

* :meth:`ProgressFilter.update` takes one moment's contact events (the observation model of §2.1.7.1): the
  teammate goes on with the current subgoal (probability ``stay``, from how long subgoals last) or finishes it
  and starts the next as the model says; the events are scored under the action of each state's subgoal.
* :meth:`ProgressFilter.observe` takes one completed action (a step the task board reported, a label from a
  dataset): the belief moves to the states that action leads to.

**Slips.** With probability ``slip`` a step is off-script (an order nobody showed, a mislabel): the belief
never becomes zero. An off-script action re-synchronises to the states in which it was just done whose done
set is closest to the believed one (an unknown action leaves the progress as it was); off-script contact
events may start any subgoal. Every belief says how likely it is that the last step was off-script
(``off_script``) and how surprising it was (``surprise``, in bits), so callers can flag it.

States are enumerated when there are at most ``max_states`` of them and moved as one sparse matrix (exact);
beyond that the filter keeps the ``beam`` most probable states (an approximation; docs/inference.md measures
it against the exact filter).
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Self

import numpy as np

from supportive.errors import LearningError
from supportive.estimator import Estimator
from supportive.inference.hmm import Belief, check_mean_duration, fitted_events
from supportive.inference.observations import ObservationModel
from supportive.inference.progress_matrices import ProgressMatrices
from supportive.inference.transitions import TaskLayout
from supportive.learning.distribution import END, ProgressModel
from supportive.tasks.executions import Progress
from supportive.tasks.htn import HTN, ActionNode
from supportive.tasks.naming import named

__all__ = ["END_LABEL", "ProgressBelief", "ProgressFilter", "ProgressHMM"]

END_LABEL = "<end>"
"""The key of "the task is finished" among next-step predictions."""

_FINISHED = None


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


class ProgressHMM(Estimator):
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
        check_mean_duration(mean_duration)
        if not 0.0 < slip < 1.0:
            raise LearningError(f"slip must be a probability in (0, 1), got {slip}")
        if beam < 1 or max_states < 1:
            raise LearningError("beam and max_states must be at least 1")
        self.htn = htn
        self.observations = observations
        self.mean_duration = mean_duration
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
        self._forget()
        self.observations_, self.mean_duration_ = fitted_events(
            self.observations, self.mean_duration, sequences, labels
        )
        self.htn_ = HTN(self.htn.task, tuple(named(r) for r in self.htn.roots), self.htn.top_level, self.htn.alternatives)
        self.model_ = ProgressModel(self.htn_, smoothing=self.smoothing)
        self.layout_ = TaskLayout.of(self.htn_)
        self.states_ = self.model_.states(self.max_states)
        return self

    @property
    def exact(self) -> bool:
        """True when the states were enumerated (no beam)."""
        return self.states_ is not None

    def filter(self) -> ProgressFilter:
        """A fresh online tracker."""
        return ProgressFilter(self)


class ProgressFilter:
    """Online tracker over a :class:`ProgressHMM` (see the module docstring): ``update(events)`` or
    ``observe(action)``, each returning a :class:`ProgressBelief`."""

    def __init__(self, hmm: ProgressHMM) -> None:
        self.hmm = hmm
        self.model = hmm.model_
        self.layout = hmm.layout_
        self.leaves = self.model.leaves
        self.subgoal_labels = tuple(ActionNode(a, k).label for a, k in self.leaves)
        self.subtask_labels = tuple(node.name or node.kind for node in self.layout.nodes)
        self.enclosing_labels = ("(top level)", *self.subtask_labels)
        self.actions = tuple(dict.fromkeys(a for a, _ in self.leaves))
        self._by_action: dict[str, list[int]] = defaultdict(list)
        for i, (action, _) in enumerate(self.leaves):
            self._by_action[action].append(i)
        self._done_at: dict[int, list[Progress]] = defaultdict(list)
        if hmm.states_ is not None:
            for state in hmm.states_:
                if state.last >= 0:
                    self._done_at[state.last].append(state)
        self.stay = 1.0 - 1.0 / hmm.mean_duration_
        self._matrices: ProgressMatrices | None = None  # built when contact events first arrive
        self._vector: np.ndarray | None = None
        if hmm.observations_ is not None:
            missing = sorted(set(self.actions) - set(hmm.observations_.actions))
            if missing:
                raise LearningError(f"the observation model has no row for action(s) {', '.join(missing)}")
            self._event_action = np.array([hmm.observations_.action_index[a] for a, _ in self.leaves])
        self.reset()

    def reset(self) -> None:
        """Forget everything observed: the task has not started."""
        start = self.model.executions.initial()
        self.belief: dict[Progress | None, float] = {s: 1.0 / len(start) for s in start}
        self._vector = None
        self.step = 0
        self.log_likelihood = 0.0
        self._seen: Counter[str] = Counter()
        self._stay_vector: np.ndarray | None = None
        self._slip_share: np.ndarray | None = None
        self._last = self._summarise(0.0, 0.0)

    # ------------------------------------------------------------------ evidence: actions
    def observe(self, action: str) -> ProgressBelief:
        """Take one completed action into account (an unknown action is a slip, never an error)."""
        self._seen[action] += 1
        slip = self.hmm.slip
        uniform = slip / (len(self.actions) + 1)
        self._as_states()
        on: dict[Progress | None, float] = defaultdict(float)
        off: dict[Progress | None, float] = defaultdict(float)
        leaves = set(self._by_action.get(action, ()))
        for state, mass in self.belief.items():
            for leaf, (p, nxt) in self._outcomes(state).items():
                if leaf in leaves:
                    on[nxt] += mass * (1.0 - slip) * p
            off[self._resync(state, action)] += mass * uniform
        return self._posterior(on, off)

    def _as_states(self) -> None:
        """Move the belief from the exact vector (contact events) to a map of states (known actions)."""
        if self._vector is not None and self._matrices is not None:
            states = (*self._matrices.states, _FINISHED)
            self.belief = {states[i]: float(p) for i in np.flatnonzero(self._vector) for p in (self._vector[i],)}
            self._vector = None

    def _as_vector(self) -> bool:
        """Move the belief to the exact vector when the states are enumerated; False in beam mode."""
        if self._vector is not None:
            return True
        if self.hmm.states_ is None:
            return False
        if self._matrices is None:
            self._matrices = ProgressMatrices(self.model, self.hmm.states_, self.actions, restart=self.hmm.restart)
        vector = np.zeros(self._matrices.size)
        for state, mass in self.belief.items():
            vector[self._matrices.finished if state is _FINISHED else self._matrices.index[state]] += mass
        self._vector = vector
        return True

    def _outcomes(self, state: Progress | None) -> Mapping[int, tuple[float, Progress | None]]:
        if state is _FINISHED:
            if self.hmm.restart:
                start = self.model.executions.initial()
                merged: dict[int, tuple[float, Progress | None]] = {}
                for s in start:
                    for leaf, (p, nxt) in self.model.outcomes(s).items():
                        merged[leaf] = (merged.get(leaf, (0.0, nxt))[0] + p / len(start), nxt)
                return merged
            return {END: (1.0, _FINISHED)}
        return self.model.outcomes(state)

    def _resync(self, state: Progress | None, action: str) -> Progress | None:
        """The state an off-script ``action`` most plausibly leads to from ``state``: one in which it was just
        done and whose done set differs least from ``state``'s (``state`` itself for an unknown action or
        when no state is known to do it)."""
        candidates = [s for leaf in self._by_action.get(action, ()) for s in self._candidates(leaf, state)]
        if not candidates or state is _FINISHED:
            return state
        done = state.done
        return min(
            candidates,
            key=lambda s: ((done & ~s.done).bit_count(), (s.done & ~done).bit_count(), s.done, s.last, s.top),
        )

    def _candidates(self, leaf: int, state: Progress | None) -> list[Progress]:
        known = self._done_at.get(leaf)
        if known is not None:
            return known
        if state is None:
            return []
        return [Progress(state.top, state.done | 1 << leaf, leaf)]  # beam mode: mark it done where we are

    # ------------------------------------------------------------------ evidence: contact events
    def update(self, events: Iterable[str]) -> ProgressBelief:
        """Take one moment's contact events into account."""
        observations = self.hmm.observations_
        if observations is None:
            raise LearningError("no observation model: pass one to ProgressHMM, or fit it on labelled demonstrations")
        scores = observations.log_likelihood(events)[self._event_action]
        peak = float(scores.max())
        likelihood = np.exp(scores - peak)
        idle = float(likelihood.mean())
        slip = self.hmm.slip
        if self._as_vector():
            self.log_likelihood += peak
            return self._update_vector(likelihood, idle, slip)
        on: dict[Progress | None, float] = defaultdict(float)
        off: dict[Progress | None, float] = defaultdict(float)
        started = self.step > 0
        for state, mass in self.belief.items():
            if state is not None and state.last >= 0 and started:
                on[state] += mass * self.stay * likelihood[state.last]
                leaving = mass * (1.0 - self.stay)
            elif state is _FINISHED:
                if not self.hmm.restart:
                    on[state] += mass * idle
                    continue
                leaving = mass
            else:
                leaving = mass
            for leaf, (p, nxt) in self._outcomes(state).items():
                weight = leaving * (1.0 - slip) * p
                if nxt is _FINISHED:
                    on[_FINISHED] += weight * idle
                else:
                    on[nxt] += weight * likelihood[leaf]
        slip_mass = slip * sum(m for s, m in self.belief.items() if s is not _FINISHED)
        if slip_mass > 0:
            candidates = self._slip_targets()
            for target in candidates:
                off[target] += slip_mass / len(candidates) * likelihood[target.last]
        self.log_likelihood += peak
        return self._posterior(on, off)

    def _update_vector(self, likelihood: np.ndarray, idle: float, slip: float) -> ProgressBelief:
        matrices, vector = self._matrices, self._vector
        assert matrices is not None and vector is not None
        if self._stay_vector is None:  # what stays put: a subgoal under way goes on; finished stays finished
            self._stay_vector = matrices.performing * self.stay
            if not self.hmm.restart:
                self._stay_vector[matrices.finished] = 1.0
            self._slip_share = matrices.performing / max(int(matrices.performing.sum()), 1)
        state_likelihood = likelihood.take(matrices.last_or_zero)
        state_likelihood[~matrices.performing] = idle
        staying = vector * self._stay_vector if self.step else np.zeros_like(vector)
        if not self.step and not self.hmm.restart:
            staying[matrices.finished] = vector[matrices.finished]
        leaving = vector - staying
        moving = float(leaving.sum() - leaving[matrices.finished])
        on = (staying + matrices.advance(leaving) * (1.0 - slip)) * state_likelihood
        assert self._slip_share is not None
        off = (slip * moving) * self._slip_share * state_likelihood
        return self._posterior_vector(on, off)

    def _posterior_vector(self, on: np.ndarray, off: np.ndarray) -> ProgressBelief:
        posterior = on + off
        total = float(posterior.sum())
        if not total > 0:
            raise LearningError(f"step {self.step + 1}: the evidence is impossible under the model")
        self._vector = posterior / total
        self.step += 1
        self.log_likelihood += math.log(total)
        self._last = self._summarise(float(off.sum()) / total, -math.log2(total))
        return self._last

    def _slip_targets(self) -> list[Progress]:
        """Where an off-script moment may land: every known state with a subgoal under way (in beam mode, the
        states in the beam)."""
        if self.hmm.states_ is not None:
            return [s for s in self.hmm.states_ if s.last >= 0]
        return [s for s in self.belief if s is not _FINISHED and s.last >= 0]

    # ------------------------------------------------------------------ belief
    def _posterior(
        self, on: Mapping[Progress | None, float], off: Mapping[Progress | None, float]
    ) -> ProgressBelief:
        merged: dict[Progress | None, float] = defaultdict(float)
        for state, mass in on.items():
            merged[state] += mass
        for state, mass in off.items():
            merged[state] += mass
        total = sum(merged.values())
        if not total > 0:
            raise LearningError(f"step {self.step + 1}: the evidence is impossible under the model")
        off_total = sum(off.values())
        if len(merged) > self.hmm.beam and self.hmm.states_ is None:
            kept = sorted(merged.items(), key=lambda kv: -kv[1])[: self.hmm.beam]
            merged = defaultdict(float, kept)
            total = sum(merged.values())
        self.belief = {s: m / total for s, m in merged.items() if m > 0}
        self.step += 1
        self.log_likelihood += math.log(total)
        self._last = self._summarise(off_total / total, -math.log2(total))
        return self._last

    def _summarise(self, off_script: float, surprise: float) -> ProgressBelief:
        n = len(self.leaves)
        matrices, vector = self._matrices, self._vector
        if vector is not None:
            assert matrices is not None
            current: np.ndarray = np.bincount(matrices.last_plus_one, weights=vector, minlength=n + 1)[1:]
        else:
            current = np.zeros(n)
            for state, mass in self.belief.items():
                if state is not _FINISHED and state.last >= 0:
                    current[state.last] += mass
        belief, seen = self.belief, dict(self._seen)

        def details() -> _Details:
            return self._details(vector, belief, seen)

        return ProgressBelief(
            self.step, current, self.layout, self.log_likelihood, off_script=off_script, surprise=surprise, details=details
        )

    def _details(
        self, vector: np.ndarray | None, belief: Mapping[Progress | None, float], seen: Mapping[str, int]
    ) -> _Details:
        n = len(self.leaves)
        done = np.zeros(n)
        arriving = np.zeros(n)
        next_actions: dict[str, float] = defaultdict(float)
        finished = 0.0
        if vector is not None:
            matrices = self._matrices
            assert matrices is not None
            done = matrices.done_t @ vector
            arriving = matrices.to_leaf_t @ vector
            next_actions = defaultdict(
                float, zip((*self.actions, END_LABEL), (matrices.to_action_t @ vector).tolist(), strict=True)
            )
            finished = float(vector[matrices.finished])
        else:
            for state, mass in belief.items():
                if state is _FINISHED:
                    finished += mass
                else:
                    done[_bits(state.done)] += mass
                for leaf, (p, _) in self._outcomes(state).items():
                    if leaf == END:
                        next_actions[END_LABEL] += mass * p
                    else:
                        arriving[leaf] += mass * p
                        next_actions[self.leaves[leaf][0]] += mass * p
        for action, count in seen.items():  # done as often as the task has it: not again, whatever the
            if count >= len(self._by_action.get(action, ())):  # belief says after a slip
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

    def top(self, values: np.ndarray, labels: tuple[str, ...], k: int = 3) -> list[tuple[str, float]]:
        """The ``k`` most probable entries of a belief vector, with their labels."""
        order = np.argsort(-values, kind="stable")[:k]
        return [(labels[i], float(values[i])) for i in order]

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


def _bits(mask: int) -> list[int]:
    return [i for i in range(mask.bit_length()) if mask >> i & 1]
