"""Simple next-step predictors to measure the progress-aware one against, with its API:
``fit(demonstrations)`` then ``next_step(prefix) -> {action: probability, "<end>": probability}``.

* :class:`~supportive.inference.bigram.Bigram`: a first-order Markov model over the training demonstrations
  (``<start>`` and ``<end>`` included), add-one smoothed over the actions seen and ``<end>``.
* :class:`MaskedBigram`: the strongest simple baseline: a bigram (unsmoothed) that never predicts an action
  already done as often as any training demonstration does it, backing off to the counts of the actions not
  yet done when the bigram has nothing allowed to say.
* :class:`MostFrequentNotDone`: the actions not yet done (as above), by how often they are performed.
"""

from __future__ import annotations

from collections.abc import Sequence

from supportive.inference.bigram import END, Bigram, TransitionCounts

__all__ = ["BASELINES", "END", "Bigram", "MaskedBigram", "MostFrequentNotDone"]


class MaskedBigram(TransitionCounts):
    """A bigram that never predicts what is already done (see the module docstring); unsmoothed, so it may
    give a step probability 0."""

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """P(next | last action), over the actions not yet done; the counts of those when none follows."""
        weights = self._open_evidence(prefix)
        return self._normalised({a: weights.get(a, 0.0) for a in [*self.actions_, END]})


class MostFrequentNotDone(TransitionCounts):
    """The actions not yet done, weighted by how often they are performed (``<end>`` by how often tasks end)."""

    def next_step(self, prefix: Sequence[str]) -> dict[str, float]:
        """Counts of the actions still open, normalised."""
        allowed = self._open(prefix)
        weights = {a: float(self.actions_[a]) if a in allowed else 0.0 for a in self.actions_}
        weights[END] = float(self.ends_) if not (allowed - {END}) else 0.0
        if not any(weights.values()):
            weights[END] = 1.0
        return self._normalised(weights)


BASELINES: dict[str, type[TransitionCounts]] = {
    "bigram": Bigram,
    "masked bigram": MaskedBigram,
    "most frequent not done": MostFrequentNotDone,
}
"""The baselines ``supportive evaluate`` reports, by name."""
