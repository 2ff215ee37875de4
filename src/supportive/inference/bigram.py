"""Counted transitions of demonstrations, and the add-one smoothed bigram they give.

The bigram is the next-step predictor's back-off (:class:`~supportive.inference.predictor.StepPredictor`
mixes it in, with a weight fitted by cross-validation, so that a step the hierarchy did not expect is never
given probability 0) and the simplest baseline ``supportive evaluate`` reports
(:mod:`supportive.evaluation.baselines`).

>>> bigram = Bigram().fit([["a", "b"], ["a", "c"]])
>>> {k: round(v, 2) for k, v in bigram.next_step(["a"]).items()}
{'a': 0.17, 'b': 0.33, 'c': 0.33, '<end>': 0.17}
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Iterable, Sequence
from typing import Self

from supportive.estimator import Estimator
from supportive.tasks.spec import Demonstration, TaskSpec

__all__ = ["END", "START", "Bigram", "OpenBigram", "TransitionCounts", "sequences_of"]

END = "<end>"
START = "<start>"


def sequences_of(demonstrations: TaskSpec | Iterable[Demonstration | Sequence[str]]) -> list[tuple[str, ...]]:
    """The demonstrations (of a task spec, or given) as tuples of action ids."""
    source = demonstrations.demonstrations if isinstance(demonstrations, TaskSpec) else demonstrations
    return [d.actions if isinstance(d, Demonstration) else tuple(d) for d in source]


class TransitionCounts(Estimator):
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
        sequences = sequences_of(demonstrations)
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

    def _open_evidence(self, prefix: Sequence[str]) -> dict[str, float]:
        """Counts of the transitions from the last action of ``prefix`` into open actions; when there are none,
        how often each open action is performed (``<end>``: how many demonstrations ended)."""
        allowed = self._open(prefix)
        counts = self.transitions_.get(prefix[-1] if prefix else START, Counter())
        evidence = {a: float(counts[a]) for a in allowed if counts[a] > 0}
        return evidence or {a: float(self.actions_[a] if a != END else self.ends_) for a in allowed}

    @staticmethod
    def _normalised(weights: dict[str, float]) -> dict[str, float]:
        total = sum(weights.values())
        return {a: w / total for a, w in weights.items()} if total > 0 else weights


class Bigram(TransitionCounts):
    """First-order Markov model, add-one smoothed over the actions seen and ``<end>``."""

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """P(next | last action of ``prefix``)."""
        counts = self.transitions_.get(prefix[-1] if prefix else START, Counter())
        vocabulary = [*self.actions_, END]
        return self._normalised({a: counts[a] + 1.0 for a in vocabulary})


class OpenBigram(TransitionCounts):
    """The add-one smoothed bigram whose evidence goes only to actions still open: an action already done as
    often as any demonstration does it keeps its pseudo-count (so it is never given probability 0) but not the
    counts of the transitions into it; when no transition from the last action leads to an open action, the
    evidence is how often each open action is performed (``<end>``: how many demonstrations ended). The
    next-step predictor's back-off.

    >>> bigram = OpenBigram().fit([["a", "b"], ["a", "c"]])
    >>> {k: round(v, 2) for k, v in bigram.next_step(["a", "b"]).items()}
    {'a': 0.2, 'b': 0.2, 'c': 0.2, '<end>': 0.4}
    """

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """P(next | last action of ``prefix``), the evidence counted only for open actions."""
        evidence = self._open_evidence(prefix)
        return self._normalised({a: evidence.get(a, 0.0) + 1.0 for a in [*self.actions_, END]})
