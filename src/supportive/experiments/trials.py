"""Trials: one unit of an experiment's work, each with its own seed.

Every trial's seed is spawned from the run's seed with :class:`numpy.random.SeedSequence`, so a trial's
result depends only on the run's seed and the trial's index, never on how many workers ran the trials or in
which order they finished.

>>> trials = spawn_trials(7, [{"size": 10}, {"size": 20}])
>>> [t.index for t in trials], trials[1].params["size"]
([0, 1], 20)
>>> int(trials[1].rng().integers(1000)) == int(spawn_trials(7, [{}, {}])[1].rng().integers(1000))
True
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from supportive.errors import ExperimentError

__all__ = ["Trial", "spawn_trials", "trial_seeds"]


@dataclass(frozen=True)
class Trial:
    """One trial of an experiment: its position in the run, its own seed and its parameters.

    Trials are sent to worker processes, so everything in ``params`` must be picklable.

    Attributes:
        index: Position in the run (0-based); results are reported in this order.
        seed: The trial's own seed, spawned from the run's seed (see :func:`trial_seeds`).
        params: What the experiment needs to know to run this trial (a task size, say).
    """

    index: int
    seed: np.random.SeedSequence
    params: Mapping[str, Any] = field(default_factory=dict)

    def rng(self) -> np.random.Generator:
        """A fresh generator seeded with this trial's seed (the same numbers every time)."""
        return np.random.default_rng(self.seed)

    def children(self, count: int) -> list[np.random.SeedSequence]:
        """``count`` independent seeds for parts of the trial, the same on every call (unlike
        ``self.seed.spawn``, which moves on each time): child ``i`` is what a fresh copy of the trial's seed
        spawns first at position ``i``.

        >>> trial = spawn_trials(3, [{}])[0]
        >>> [c.spawn_key for c in trial.children(2)] == [c.spawn_key for c in trial.children(2)]
        True
        """
        return [
            np.random.SeedSequence(self.seed.entropy, spawn_key=(*self.seed.spawn_key, i), pool_size=self.seed.pool_size)
            for i in range(count)
        ]


def trial_seeds(seed: int, count: int) -> list[np.random.SeedSequence]:
    """``count`` independent seeds for the trials of a run with seed ``seed``.

    Trial ``i`` gets ``SeedSequence(seed).spawn(count)[i]``, whose spawn key is ``(i,)``: the same seed for the
    same ``i`` whatever ``count`` is.

    Args:
        seed: The run's seed (an int >= 0).
        count: Number of trials (>= 0).

    Raises:
        ExperimentError: for a negative seed or count.
    """
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise ExperimentError(f"seed must be an int >= 0, got {seed!r}")
    if count < 0:
        raise ExperimentError(f"the number of trials must be >= 0, got {count}")
    return np.random.SeedSequence(int(seed)).spawn(count)


def spawn_trials(seed: int, params: Sequence[Mapping[str, Any]]) -> tuple[Trial, ...]:
    """One :class:`Trial` per entry of ``params``, each with its own seed from :func:`trial_seeds`.

    Args:
        seed: The run's seed (an int >= 0).
        params: Each trial's parameters, in trial order.

    Raises:
        ExperimentError: for a negative seed.
    """
    seeds = trial_seeds(seed, len(params))
    return tuple(Trial(i, s, dict(p)) for i, (s, p) in enumerate(zip(seeds, params, strict=True)))
