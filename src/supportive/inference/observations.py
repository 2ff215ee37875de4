"""Observation model: the contact events an action produces (Semantic Event Chains, §2.1.7.1).

Semantic Event Chains describe an action by which agent–object and object–object pairs touch and stop touching.
At each moment an observer sees the set of pairs that touch (``"hand-peg"``, ``"peg-frame"``); a pair not in
the set does not touch. Each action makes each event hold with its own probability, independently of the other
events (the naive Bayes assumption); events an action does not mention hold with a small ``noise`` probability.
Actions' event sets may overlap, as in real tasks (several actions touch the same part).

The log-likelihood of one observation under every action is one column sum over the events present, so scoring
is cheap however many events the vocabulary has.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import TypeAlias

import numpy as np

from supportive.errors import LearningError
from supportive.seeding import Seed, rng_from
from supportive.tasks.spec import TaskSpec

__all__ = ["Observation", "ObservationModel"]

Observation: TypeAlias = frozenset[str]
"""The contact events that hold at one moment."""


class ObservationModel:
    """Bernoulli naive Bayes over contact events, one row of probabilities per action.

    Args:
        probabilities: action -> {event: probability that the event holds while the action runs}.
        noise: probability of an event the action does not mention (0 < noise < 0.5).

    >>> model = ObservationModel({"get_peg": {"hand-peg": 0.9}, "insert_peg": {"hand-peg": 0.8, "peg-frame": 0.9}})
    >>> [round(float(x), 2) for x in model.log_likelihood({"hand-peg", "peg-frame"})]
    [-4.02, -0.33]
    """

    def __init__(self, probabilities: Mapping[str, Mapping[str, float]], noise: float = 0.02) -> None:
        if not 0.0 < noise < 0.5:
            raise LearningError(f"noise must be between 0 and 0.5, got {noise}")
        self.actions: tuple[str, ...] = tuple(probabilities)
        self.events: tuple[str, ...] = tuple(sorted({e for row in probabilities.values() for e in row}))
        self.noise = noise
        self.action_index = {a: i for i, a in enumerate(self.actions)}
        self.event_index = {e: i for i, e in enumerate(self.events)}
        table = np.full((len(self.actions), len(self.events)), noise)
        for action, row in probabilities.items():
            for event, p in row.items():
                if not 0.0 < p < 1.0:
                    raise LearningError(
                        f"action {action!r}: probability of {event!r} must be in (0, 1), got {p}"
                    )
                table[self.action_index[action], self.event_index[event]] = p
        self.table = table
        self._absent = np.log1p(-table).sum(axis=1)
        self._present = np.log(table) - np.log1p(-table)

    @classmethod
    def from_spec(cls, spec: TaskSpec, noise: float = 0.02) -> ObservationModel:
        """The model a task file declares in its actions' ``observations``.

        Raises:
            LearningError: when an action of the spec declares no observations.
        """
        missing = [a.id for a in spec.actions if not a.observations]
        if not spec.actions or missing:
            raise LearningError(
                f"task {spec.name}: actions without 'observations': {', '.join(missing) or 'no actions declared'}"
            )
        return cls({a.id: dict(a.observations) for a in spec.actions}, noise)

    @classmethod
    def from_labelled(
        cls,
        sequences: Sequence[Sequence[Iterable[str]]],
        labels: Sequence[Sequence[str]],
        *,
        smoothing: float = 1.0,
        noise: float = 0.02,
    ) -> ObservationModel:
        """The model estimated from labelled demonstrations (each step's observation and true action); the goal
        models' ``fit`` calls it (this class is a model, like an HTN, not an estimator).

        Frequencies are Laplace-smoothed; an event's probability is at least ``noise``.

        Raises:
            LearningError: when sequences and labels do not line up.
        """
        if len(sequences) != len(labels):
            raise LearningError(f"{len(sequences)} observation sequences but {len(labels)} label sequences")
        steps: dict[str, int] = {}
        counts: dict[str, dict[str, int]] = {}
        for index, (sequence, tags) in enumerate(zip(sequences, labels, strict=True)):
            if len(sequence) != len(tags):
                raise LearningError(
                    f"sequence {index + 1}: {len(sequence)} observations but {len(tags)} labels"
                )
            for observation, action in zip(sequence, tags, strict=True):
                steps[action] = steps.get(action, 0) + 1
                row = counts.setdefault(action, {})
                for event in set(observation):
                    row[event] = row.get(event, 0) + 1
        ceiling = 1.0 - noise
        probabilities = {
            action: {
                event: min(ceiling, max(noise, (n + smoothing) / (steps[action] + 2 * smoothing)))
                for event, n in row.items()
            }
            for action, row in counts.items()
        }
        return cls(probabilities, noise)

    def encode(self, observation: Iterable[str]) -> np.ndarray:
        """Indices of the known events in ``observation`` (unknown events carry no information and are dropped)."""
        index = self.event_index
        return np.fromiter((index[e] for e in observation if e in index), dtype=np.intp)

    def log_likelihood(self, observation: Iterable[str]) -> np.ndarray:
        """log P(observation | action) for every action, in :attr:`actions` order."""
        present = self.encode(observation)
        return np.asarray(self._absent + self._present[:, present].sum(axis=1))

    def sample(self, action: str, seed: Seed = None) -> Observation:
        """One observation drawn while ``action`` runs."""
        rng = rng_from(seed)
        row = self.table[self.action_index[action]]
        return frozenset(self.events[i] for i in np.flatnonzero(rng.random(len(row)) < row))
