"""The progress-aware tracker's one transition, written once and applied to either form of its belief.

A belief is a probability over the states of a :class:`~supportive.learning.distribution.ProgressModel` (what is
done, which leaf was done last) plus **finished** (:data:`FINISHED`). :class:`ProgressStep` says how one piece of
evidence moves it:

* **One moment of contact events** (:meth:`ProgressStep.moment`). A state whose subgoal is under way stays
  with probability ``stay``; otherwise the subgoal ends and the next step starts: on-script (probability
  ``1 - slip``) as the model weighs it, off-script (probability ``slip``) by **skipping one step** — a subgoal
  that comes after next, as the model weighs the two steps (:meth:`ProgressStep.skips`; where nothing comes
  after next, the step is on-script). Finished stays finished (or, with ``restart``, starts again). The
  moment's events are then scored under the action of each state's subgoal (finished and not-yet-started
  states: the mean over the leaves, an action done twice counted twice). The off-script mass is kept apart so the belief can say how likely it
  is that the step was off-script.
* **One completed action** (:meth:`ProgressStep.act`): on-script (``1 - slip``) the belief moves to the states
  that action leads to; off-script (``slip``, spread evenly over the actions and the end) each state
  re-synchronises to the nearest state ahead of it in which the action was just done (fewest steps added;
  :meth:`ProgressStep.resync`), or keeps its progress when none is ahead (an action repeated, an unknown one).

Both moves reach only states the model itself reaches from the start, and depend only on the state they move,
so the belief can be held in two forms with the same results: :class:`VectorMasses`, a vector over the
enumerated states moved by sparse matrices (exact), and :class:`StateMasses`, a map from state to probability
that a beam may cut to its most probable states (beyond the enumeration). :meth:`ProgressStep.moment` is
written once over :class:`Masses`, the few operations both forms provide.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Mapping, Sequence
from typing import Generic, Protocol, TypeAlias, TypeVar

import numpy as np

from supportive.inference.transitions import sparse_matrix
from supportive.learning.distribution import END, ProgressModel
from supportive.tasks.executions import Progress

__all__ = ["FINISHED", "Masses", "ProgressStep", "State", "StateMasses", "VectorMasses"]

State: TypeAlias = Progress | None
"""A state of the belief: an execution's progress, or :data:`FINISHED`."""

FINISHED: State = None
"""The task is finished."""

Move = tuple[int, float, State]
"""One next step: the leaf done (or :data:`~supportive.learning.distribution.END`), its probability, the state
after it."""

M = TypeVar("M")


class Masses(Protocol, Generic[M]):
    """The operations :meth:`ProgressStep.moment` needs from a form of the belief (``M``: the form's type)."""

    def split(self, masses: M) -> tuple[M, M, M]:
        """Each state's mass times its probability of staying put, of an on-script step and of an off-script
        step (:meth:`ProgressStep.chances`)."""

    def plus(self, a: M, b: M, weight: float) -> M:
        """``a + weight * b``."""

    def advance(self, masses: M) -> M:
        """Where the mass goes in one on-script step (:meth:`ProgressStep.moves`)."""

    def skip(self, masses: M) -> M:
        """Where the mass goes in one off-script step (:meth:`ProgressStep.skips`)."""

    def emit(self, masses: M, scores: np.ndarray) -> M:
        """Each state's mass times ``scores[ProgressStep.slot(state)]``."""


class ProgressStep:
    """The tracker's transition (see the module docstring).

    Args:
        model: The progress model.
        stay: Probability that a subgoal under way goes on for another moment.
        slip: Probability that a step is off-script.
        restart: Finished starts the task again instead of staying finished.
        limit: At most this many states are visited looking for where an off-script action leads (the
            tracker gives the larger of ``max_states`` and ``beam``: never cut short when the states are
            enumerated, nor when a beam could hold them all).
        states: Every state the model reaches from the start, when they were enumerated (for the vector
            form, :meth:`vectors`).
    """

    def __init__(
        self,
        model: ProgressModel,
        *,
        stay: float,
        slip: float,
        restart: bool,
        limit: int,
        states: Sequence[Progress] | None = None,
    ) -> None:
        self.model = model
        self.states = states
        self.stay = stay
        self.slip = slip
        self.restart = restart
        self.limit = limit
        self.leaves = model.leaves
        self.n_leaves = len(self.leaves)
        self.actions = tuple(dict.fromkeys(a for a, _ in self.leaves))
        by_action: dict[str, set[int]] = defaultdict(set)
        for i, (action, _) in enumerate(self.leaves):
            by_action[action].add(i)
        self.leaves_of = {a: frozenset(leaves) for a, leaves in by_action.items()}
        self._moves: dict[State, tuple[Move, ...]] = {}
        self._skips: dict[State, tuple[tuple[Progress, float], ...]] = {}
        self._resynced: dict[tuple[State, str], State] = {}
        self._vectors: VectorMasses | None = None

    # ------------------------------------------------------------------ the model, state by state
    def moves(self, state: State) -> tuple[Move, ...]:
        """The next steps from ``state``: the model's outcomes; from finished, the end again (or, with
        ``restart``, what the start does next, shared evenly among the initial states)."""
        cached = self._moves.get(state)
        if cached is None:
            if state is not None:
                cached = tuple((leaf, p, nxt) for leaf, (p, nxt) in self.model.outcomes(state).items())
            elif self.restart:
                start = self.model.executions.initial()
                cached = tuple(
                    (leaf, p / len(start), nxt) for s in start for leaf, (p, nxt) in self.model.outcomes(s).items()
                )
            else:
                cached = ((END, 1.0, FINISHED),)
            self._moves[state] = cached
        return cached

    def skips(self, state: State) -> tuple[tuple[Progress, float], ...]:
        """Where an off-script step from ``state`` leads when read from contact events: a step skipped, so
        the states two steps ahead (through any next step, the end included; landing on a subgoal, not on
        finished), weighed as the model weighs the two steps and normalised; empty when there are none."""
        cached = self._skips.get(state)
        if cached is None:
            ahead: dict[Progress, float] = defaultdict(float)
            for _, p, nxt in self.moves(state):
                for _, q, after in self.moves(nxt):
                    if after is not None:
                        ahead[after] += p * q
            total = sum(ahead.values())
            cached = self._skips[state] = tuple((s, w / total) for s, w in ahead.items() if w > 0)
        return cached

    def chances(self, state: State) -> tuple[float, float, float]:
        """Probability that after a moment in ``state`` it stays put (``stay`` while a subgoal is under way;
        1 when finished is final; 0 before the start and for finished with ``restart``), that an on-script
        step follows, and that an off-script one does (``slip`` of the steps, 0 where no step can be skipped:
        :meth:`skips` empty)."""
        performing = state is not None and state.last >= 0
        stays = self.stay if performing else float(state is None and not self.restart)
        slip = self.slip if self.skips(state) else 0.0
        return stays, (1.0 - stays) * (1.0 - slip), (1.0 - stays) * slip

    def slot(self, state: State) -> int:
        """Which entry of a moment's scores weighs ``state``: its subgoal's leaf while one is under way, else
        :attr:`n_leaves` (the mean over the leaves, an action done twice counted twice)."""
        return state.last if state is not None and state.last >= 0 else self.n_leaves

    def vectors(self) -> VectorMasses | None:
        """The vector form over the enumerated states, built when first asked for and then shared; None
        without them."""
        if self._vectors is None and self.states is not None:
            self._vectors = VectorMasses(self, self.states)
        return self._vectors

    # ------------------------------------------------------------------ evidence
    def moment(self, form: Masses[M], belief: M, scores: np.ndarray) -> tuple[M, M]:
        """One moment of contact events: the on-script and the off-script mass after it, unnormalised.

        Args:
            form: The operations of the belief's form.
            belief: The belief before the moment.
            scores: The moment's likelihood under each leaf's action, then the mean over them (see
                :meth:`slot`).
        """
        staying, moving, skipping = form.split(belief)
        on = form.emit(form.plus(staying, form.advance(moving), 1.0), scores)
        off = form.emit(form.skip(skipping), scores)
        return on, off

    def act(self, belief: Mapping[State, float], action: str) -> tuple[dict[State, float], dict[State, float]]:
        """One completed action: the on-script and the off-script mass after it, unnormalised (an unknown
        action is off-script, never an error)."""
        on: dict[State, float] = defaultdict(float)
        off: dict[State, float] = defaultdict(float)
        leaves = self.leaves_of.get(action, frozenset())
        uniform = self.slip / (len(self.actions) + 1)
        for state, mass in belief.items():
            for leaf, p, nxt in self.moves(state):
                if leaf in leaves:
                    on[nxt] += mass * (1.0 - self.slip) * p
            off[self.resync(state, action)] += mass * uniform
        return on, off

    def resync(self, state: State, action: str) -> State:
        """Where an off-script ``action`` leads from ``state``: the nearest state ahead in which it was just
        done (the fewest steps added, searched step by step through what the model allows; ties by done set,
        last leaf, top-level state), or ``state`` itself when none is ahead (the action already done as often
        as the task has it, not part of the task, or its place passed) or ``state`` is finished."""
        key = (state, action)
        cached = self._resynced.get(key)
        if cached is not None or key in self._resynced:
            return cached
        leaves = self.leaves_of.get(action, frozenset())
        found: State = state
        if leaves and state is not None:
            seen = {state}
            layer: list[Progress] = [state]
            while layer and len(seen) <= self.limit:
                ahead: list[Progress] = []
                for s in layer:
                    for _, _, nxt in self.moves(s):
                        if nxt is not None and nxt not in seen:
                            seen.add(nxt)
                            ahead.append(nxt)
                hits = [s for s in ahead if s.last in leaves]
                if hits:
                    found = min(hits, key=lambda s: (s.done, s.last, s.top))
                    break
                layer = ahead
        self._resynced[key] = found
        return found


class StateMasses:
    """The belief as a map from state to mass (:class:`Masses` over ``dict[State, float]``); with ``beam``, a
    normalised belief keeps only its ``beam`` most probable states."""

    def __init__(self, step: ProgressStep, beam: int | None) -> None:
        self.step = step
        self.beam = beam

    def split(self, masses: Mapping[State, float]) -> tuple[dict[State, float], dict[State, float], dict[State, float]]:
        """See :class:`Masses`."""
        parts: tuple[dict[State, float], dict[State, float], dict[State, float]] = ({}, {}, {})
        for state, mass in masses.items():
            for part, chance in zip(parts, self.step.chances(state), strict=True):
                if chance > 0:
                    part[state] = mass * chance
        return parts

    def plus(self, a: Mapping[State, float], b: Mapping[State, float], weight: float) -> dict[State, float]:
        """See :class:`Masses`."""
        out = dict(a)
        for s, m in b.items():
            out[s] = out.get(s, 0.0) + weight * m
        return out

    def advance(self, masses: Mapping[State, float]) -> dict[State, float]:
        """See :class:`Masses`."""
        out: dict[State, float] = defaultdict(float)
        for state, mass in masses.items():
            if mass:
                for _, p, nxt in self.step.moves(state):
                    out[nxt] += mass * p
        return out

    def skip(self, masses: Mapping[State, float]) -> dict[State, float]:
        """See :class:`Masses`."""
        out: dict[State, float] = defaultdict(float)
        for state, mass in masses.items():
            if mass:
                for after, p in self.step.skips(state):
                    out[after] += mass * p
        return out

    def emit(self, masses: Mapping[State, float], scores: np.ndarray) -> dict[State, float]:
        """See :class:`Masses`."""
        return {s: m * float(scores[self.step.slot(s)]) for s, m in masses.items()}

    def total(self, masses: Mapping[State, float]) -> float:
        """The mass of all states."""
        return float(sum(masses.values()))

    def normalised(self, masses: Mapping[State, float], total: float) -> dict[State, float]:
        """``masses / total`` without the states of no mass; cut to the beam."""
        kept = [(s, m) for s, m in masses.items() if m > 0]
        if self.beam is not None and len(kept) > self.beam:
            kept = sorted(kept, key=lambda kv: -kv[1])[: self.beam]
            total = sum(m for _, m in kept)
        return {s: m / total for s, m in kept}

    def current(self, belief: Mapping[State, float]) -> np.ndarray:
        """Probability of each leaf being the subgoal under way."""
        out = np.zeros(self.step.n_leaves)
        for state, mass in belief.items():
            if state is not None and state.last >= 0:
                out[state.last] += mass
        return out

    def expectations(self, belief: Mapping[State, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """Probability of each leaf being done, of each leaf being the next one started, of each action (then
        the end) being done next, and of the task being finished."""
        step = self.step
        done = np.zeros(step.n_leaves)
        arriving = np.zeros(step.n_leaves)
        actions = np.zeros(len(step.actions) + 1)
        index = {a: i for i, a in enumerate(step.actions)}
        finished = 0.0
        for state, mass in belief.items():
            if state is None:
                finished += mass
            else:
                done[_bits(state.done)] += mass
            for leaf, p, _ in step.moves(state):
                if leaf == END:
                    actions[-1] += mass * p
                else:
                    arriving[leaf] += mass * p
                    actions[index[step.leaves[leaf][0]]] += mass * p
        return done, arriving, actions, finished


class VectorMasses:
    """The belief as a vector over enumerated states, then finished (:class:`Masses` over ``np.ndarray``),
    moved by sparse matrices built from the same :class:`ProgressStep`.

    Args:
        step: The transition.
        states: Every state the model reaches from the start (``ProgressModel.states``).
    """

    def __init__(self, step: ProgressStep, states: Sequence[Progress]) -> None:
        self.step = step
        self.states: list[State] = [*states, FINISHED]
        self.index = {s: i for i, s in enumerate(self.states)}
        self.size = len(self.states)
        self.finished = self.size - 1
        n_leaves, n_actions = step.n_leaves, len(step.actions)
        action_index = {a: i for i, a in enumerate(step.actions)}
        self.chances = np.array([step.chances(s) for s in self.states]).T.copy()  # rows: stay, on, off
        self.slots = np.array([step.slot(s) for s in self.states], dtype=np.intp)
        moves: list[tuple[int, int, float]] = []
        arrivals: list[tuple[int, int, float]] = []
        nexts: list[tuple[int, int, float]] = []
        done: list[tuple[int, int, float]] = []
        skips: list[tuple[int, int, float]] = []
        for i, state in enumerate(self.states):
            skips += [(self.index[after], i, p) for after, p in step.skips(state)]
            for leaf, p, nxt in step.moves(state):
                moves.append((self.index[nxt], i, p))
                nexts.append((n_actions if leaf == END else action_index[step.leaves[leaf][0]], i, p))
                if leaf != END:
                    arrivals.append((leaf, i, p))
            if state is not None:
                done += [(leaf, i, 1.0) for leaf in _bits(state.done)]
        self._advance = sparse_matrix(moves, self.size, self.size)
        self._skip = sparse_matrix(skips, self.size, self.size)
        self._arriving = sparse_matrix(arrivals, n_leaves, self.size)
        self._actions = sparse_matrix(nexts, n_actions + 1, self.size)
        self._done = sparse_matrix(done, n_leaves, self.size)

    def of(self, belief: Mapping[State, float]) -> np.ndarray:
        """The vector of a map from state to mass."""
        vector = np.zeros(self.size)
        for state, mass in belief.items():
            vector[self.index[state]] += mass
        return vector

    def to_map(self, vector: np.ndarray) -> dict[State, float]:
        """The map from state to mass of a vector (states of mass 0 left out)."""
        return {self.states[i]: float(vector[i]) for i in np.flatnonzero(vector)}

    def split(self, masses: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """See :class:`Masses`."""
        stay, on, off = masses * self.chances
        return stay, on, off

    def plus(self, a: np.ndarray, b: np.ndarray, weight: float) -> np.ndarray:
        """See :class:`Masses`."""
        out: np.ndarray = a + weight * b
        return out

    def advance(self, masses: np.ndarray) -> np.ndarray:
        """See :class:`Masses`."""
        out: np.ndarray = self._advance @ masses
        return out

    def skip(self, masses: np.ndarray) -> np.ndarray:
        """See :class:`Masses`."""
        out: np.ndarray = self._skip @ masses
        return out

    def emit(self, masses: np.ndarray, scores: np.ndarray) -> np.ndarray:
        """See :class:`Masses`."""
        out: np.ndarray = masses * scores.take(self.slots)
        return out

    def total(self, masses: np.ndarray) -> float:
        """The mass of all states."""
        return float(masses.sum())

    def normalised(self, masses: np.ndarray, total: float) -> np.ndarray:
        """``masses / total``."""
        out: np.ndarray = masses / total
        return out

    def current(self, vector: np.ndarray) -> np.ndarray:
        """Probability of each leaf being the subgoal under way."""
        return np.bincount(self.slots, weights=vector, minlength=self.step.n_leaves + 1)[:-1]

    def expectations(self, vector: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """As :meth:`StateMasses.expectations`."""
        return self._done @ vector, self._arriving @ vector, self._actions @ vector, float(vector[self.finished])


def _bits(mask: int) -> list[int]:
    return [i for i in range(mask.bit_length()) if mask >> i & 1]
