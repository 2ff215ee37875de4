"""Simple next-step predictors to measure the progress-aware one against, with its API:
``fit(demonstrations)`` then ``next_step(prefix) -> {action: probability, "<end>": probability}``.

* :class:`Bigram`: a first-order Markov model over the training demonstrations (``<start>`` and ``<end>``
  included), add-one smoothed over the actions seen and ``<end>``.
* :class:`MaskedBigram`: the strongest simple baseline: a bigram (unsmoothed) that never predicts an action
  already done as often as any training demonstration does it, backing off to the counts of the actions not
  yet done when the bigram has nothing allowed to say.
* :class:`MostFrequentNotDone`: the actions not yet done (as above), by how often they are performed.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Iterable, Sequence
from typing import Self

from supportive.estimator import Estimator
from supportive.tasks.spec import Demonstration, TaskSpec

__all__ = ["BASELINES", "Bigram", "MaskedBigram", "MostFrequentNotDone"]

END = "<end>"
START = "<start>"


def _sequences(demonstrations: TaskSpec | Iterable[Demonstration | Sequence[str]]) -> list[tuple[str, ...]]:
    source = demonstrations.demonstrations if isinstance(demonstrations, TaskSpec) else demonstrations
    return [d.actions if isinstance(d, Demonstration) else tuple(d) for d in source]


class _Counted(Estimator):
    """Transition and action counts of the training demonstrations.

    Attributes (after ``fit``):
        transitions_: Counts of each action (or ``<start>``) followed by each action (or ``<end>``).
        actions_: How often each action is performed.
        most_: The most times one demonstration performs each action.
        ends_: How many demonstrations there were.
    """

    def fit(self, demonstrations: TaskSpec | Iterable[Demonstration | Sequence[str]]) -> Self:
        """Count the demonstrations' transitions, actions and how often each is done at most."""
        self._forget()
        self.transitions_: dict[str, Counter[str]] = defaultdict(Counter)
        self.actions_: Counter[str] = Counter()
        self.most_: Counter[str] = Counter()
        sequences = _sequences(demonstrations)
        for sequence in sequences:
            for before, after in zip((START, *sequence), (*sequence, END), strict=True):
                self.transitions_[before][after] += 1
            self.actions_.update(sequence)
            for action, n in Counter(sequence).items():
                self.most_[action] = max(self.most_[action], n)
        self.ends_ = len(sequences)
        return self

    def _open(self, prefix: Sequence[str]) -> set[str]:
        """Actions not yet done as often as any demonstration does them, and ``<end>``."""
        done = Counter(prefix)
        return {a for a in self.actions_ if done[a] < self.most_[a]} | {END}

    @staticmethod
    def _normalised(weights: dict[str, float]) -> dict[str, float]:
        total = sum(weights.values())
        return {a: w / total for a, w in weights.items()} if total > 0 else weights


class Bigram(_Counted):
    """First-order Markov model, add-one smoothed over the actions seen and ``<end>``."""

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """P(next | last action of ``prefix``)."""
        counts = self.transitions_.get(prefix[-1] if prefix else START, Counter())
        vocabulary = [*self.actions_, END]
        return self._normalised({a: counts[a] + 1.0 for a in vocabulary})


class MaskedBigram(_Counted):
    """A bigram that never predicts what is already done (see the module docstring); unsmoothed, so it may
    give a step probability 0."""

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """P(next | last action), over the actions not yet done; the counts of those when none follows."""
        allowed = self._open(prefix)
        counts = self.transitions_.get(prefix[-1] if prefix else START, Counter())
        weights = {a: float(counts[a]) for a in allowed if counts[a] > 0}
        if not weights:
            weights = {a: float(self.actions_[a] if a != END else self.ends_) for a in allowed}
        return self._normalised({a: weights.get(a, 0.0) for a in [*self.actions_, END]})


class MostFrequentNotDone(_Counted):
    """The actions not yet done, weighted by how often they are performed (``<end>`` by how often tasks end)."""

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """Counts of the actions still open, normalised."""
        allowed = self._open(prefix)
        weights = {a: float(self.actions_[a]) if a in allowed else 0.0 for a in self.actions_}
        weights[END] = float(self.ends_) if not (allowed - {END}) else 0.0
        if not any(weights.values()):
            weights[END] = 1.0
        return self._normalised(weights)


BASELINES: dict[str, type[_Counted]] = {
    "bigram": Bigram,
    "masked bigram": MaskedBigram,
    "most frequent not done": MostFrequentNotDone,
}
"""The baselines ``supportive evaluate`` reports, by name."""
