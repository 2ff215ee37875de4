"""Synthetic contact-event streams with known ground truth, for measuring goal-inference accuracy.

Each action gets a few contact events. ``overlap`` is the share of an action's events drawn from a pool that
other actions use too (0: every action has its own events; near 1: actions are told apart only by
combinations); ``spurious`` is how many events an action does not produce show up anyway at a moment, on
average (sensor noise: a stray contact), whatever the size of the vocabulary. An agent performs
valid orderings of the task back to back, spending a geometric number of steps (mean ``mean_duration``) on each
subgoal.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from supportive.errors import LearningError
from supportive.inference.observations import Observation, ObservationModel
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import Leaf, Node, sample_ordering

__all__ = ["SyntheticStream", "synthetic_model", "synthetic_stream"]


def synthetic_model(
    actions: Sequence[str],
    *,
    events_per_action: int = 3,
    overlap: float = 0.3,
    spurious: float = 0.3,
    strength: float = 0.85,
    seed: Seed = None,
) -> ObservationModel:
    """A random observation model over ``actions``.

    Args:
        events_per_action: Contact events each action produces.
        overlap: Share of those events taken from a pool shared with other actions (0 ≤ overlap ≤ 1).
        spurious: Expected number of events an action does not produce that are observed anyway at a moment.
        strength: Probability that an event the action produces is observed at a given moment.
    """
    if not 0.0 <= overlap <= 1.0 or events_per_action < 1 or spurious <= 0.0:
        raise LearningError("overlap must be in [0, 1], events_per_action at least 1 and spurious above 0")
    rng = rng_from(seed)
    shared = events_per_action + 2  # a small pool: shared events really confuse actions
    probabilities: dict[str, dict[str, float]] = {}
    for action in actions:
        n_shared = int(rng.binomial(events_per_action, overlap))
        row = {f"{action}~part{j}": strength for j in range(events_per_action - n_shared)}
        for j in rng.choice(shared, size=min(n_shared, shared), replace=False):
            row[f"shared~{j}"] = strength
        probabilities[action] = row
    vocabulary = len({e for row in probabilities.values() for e in row})
    return ObservationModel(probabilities, noise=min(0.2, spurious / vocabulary))


@dataclass(frozen=True)
class SyntheticStream:
    """Observations and, for each, the subgoal truly being performed."""

    observations: tuple[Observation, ...]
    truth: tuple[Leaf, ...]


def synthetic_stream(
    structure: Node,
    model: ObservationModel,
    *,
    executions: int = 1,
    mean_duration: float = 5.0,
    seed: Seed = None,
) -> SyntheticStream:
    """Perform ``executions`` uniformly drawn valid orderings of ``structure`` back to back and observe them."""
    rng = rng_from(seed)
    observations: list[Observation] = []
    truth: list[Leaf] = []
    for _ in range(executions):
        for leaf in sample_ordering(structure, rng):
            for _ in range(int(rng.geometric(1.0 / mean_duration))):
                observations.append(model.sample(leaf[0], rng))
                truth.append(leaf)
    return SyntheticStream(tuple(observations), tuple(truth))
