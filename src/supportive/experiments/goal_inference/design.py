"""Goal inference: the design of a run (task sizes, observation settings, stream lengths) and its trials.

A trial is one generated IKEA-like task of one size. Sizes are dealt out in turn (10, 20, 50, …, 1,000,
10, 20, …), so a full run has :data:`TRIALS_PER_SIZE` tasks of every size and a short run (``--trials 3``)
only the smallest sizes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from supportive.experiments.trials import Trial, spawn_trials

__all__ = [
    "DEFAULT_TRIALS",
    "EVENTS_PER_ACTION",
    "MEAN_DURATION",
    "SETTINGS",
    "SIZES",
    "TIMED_SETTING",
    "TRIALS_PER_SIZE",
    "Setting",
    "executions_for",
    "make_trials",
    "steps_for",
]

SIZES = (10, 20, 50, 100, 200, 500, 1000)
"""Subgoals per task, from the thesis's smallest task (10) to ten times its largest (100)."""
TRIALS_PER_SIZE = 5
"""Tasks per size in a full run."""
DEFAULT_TRIALS = TRIALS_PER_SIZE * len(SIZES)
"""Trials of a full run: one per task."""
MEAN_DURATION = 5.0
"""Mean number of steps spent on a subgoal, in the streams and in both filters."""
EVENTS_PER_ACTION = 3
"""Contact events each action produces (:func:`~supportive.inference.synthetic.synthetic_model`)."""


@dataclass(frozen=True)
class Setting:
    """One observation setting: how much actions share their contact events, and how noisy the sensing is.

    Attributes:
        overlap: Share of an action's events taken from a pool shared with other actions.
        noise: ``"clean"`` or ``"noisy"``.
        spurious: Expected number of stray events per moment.
        strength: Probability that an event the action produces is observed at a moment.
    """

    overlap: float
    noise: str
    spurious: float
    strength: float

    @property
    def key(self) -> str:
        """Its name in the metrics, e.g. ``overlap-0.5-noisy``.

        >>> Setting(0.5, "noisy", 1.0, 0.6).key
        'overlap-0.5-noisy'
        """
        return f"overlap-{self.overlap:.1f}-{self.noise}"


_NOISE = {"clean": (0.3, 0.85), "noisy": (1.0, 0.6)}
SETTINGS = tuple(
    Setting(overlap, noise, *_NOISE[noise]) for overlap in (0.0, 0.5, 0.8) for noise in ("clean", "noisy")
)
"""The grid: overlap 0.0 / 0.5 / 0.8, each clean (0.3 stray events per moment, events seen with probability
0.85) and noisy (1.0 stray events, probability 0.6)."""
TIMED_SETTING = "overlap-0.5-noisy"
"""The setting whose stream the per-update times are measured on."""


def steps_for(subgoals: int) -> int:
    """Most steps of a trial's streams: 3,000 up to 200 subgoals, fewer for the biggest tasks.

    >>> [steps_for(n) for n in (10, 200, 500, 1000)]
    [3000, 3000, 2000, 1500]
    """
    if subgoals <= 200:
        return 3000
    return 2000 if subgoals <= 500 else 1500


def executions_for(subgoals: int, steps: int, mean_duration: float = MEAN_DURATION) -> int:
    """Executions of the task to perform back to back so that the stream very likely reaches ``steps`` (it is
    then cut there): 20% more than expected to be needed, at least one.

    >>> executions_for(10, 3000), executions_for(200, 3000), executions_for(1000, 1500)
    (72, 4, 1)
    """
    return max(1, math.ceil(1.2 * steps / (mean_duration * subgoals)))


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """``trials`` tasks, sizes dealt out in turn from :data:`SIZES`, each trial with its own seed.

    >>> [t.params["subgoals"] for t in make_trials(9, 0)]
    [10, 20, 50, 100, 200, 500, 1000, 10, 20]
    """
    sizes = [SIZES[i % len(SIZES)] for i in range(trials)]
    return spawn_trials(seed, [{"subgoals": size, "steps": steps_for(size)} for size in sizes])
