"""Which reading of the demonstrations to keep: chosen by how well each predicts demonstrations it did not see.

Readings of the same demonstrations (:class:`~supportive.learning.learner.HTNLearner`):

* ``general``: chains and cliques the evidence supports, a partial order where no tree fits, slips set aside;
* ``strict``: the thesis's reading, only what was seen in full;
* ``partial order``: no subtasks, the steps in the orders the evidence establishes (slips set aside);
* ``general`` and ``partial order`` with **consistent orders**: every order two or more demonstrations keep
  without exception counts as established (``order_support=2``), not only those unlikely by chance; people
  with habits keep orders that are free, but a task also has orders too few demonstrations show to rule out
  chance, and which of the two explains the demonstrations better is for them to say.

When they differ, each is scored by K-fold cross-validation: learned from the other folds, the held-out
demonstrations' log-likelihood in the reading of :class:`~supportive.learning.order_likelihood.OrderLikelihood`
(which parts, then any valid order), and for a demonstration the reading does not admit, its probability as
noise, as the slip model of :mod:`~supportive.learning.noise` reads it: one step out of order (``slip_rate``
times the landing place, times the most probable admitted execution it came from), or when no single move
explains it, ``slip_rate`` times a uniformly random order of its steps. So a reading too tight to generalise
pays for every demonstration it refuses. The reading with the highest mean held-out log-likelihood per
demonstration is kept (``general`` on a tie). With fewer than ``min_demonstrations`` demonstrations there is
nothing to hold out and ``general`` is kept.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from supportive.learning.order_likelihood import OrderLikelihood
from supportive.tasks.htn import HTN

__all__ = ["CANDIDATES", "CONSISTENT", "READINGS", "Selection", "held_out_log_likelihood", "select_reading"]

READINGS = ("general", "strict", "partial order")
"""The readings one can ask for by name (``mode``), the default first."""

CONSISTENT = " (consistent orders)"
"""Suffix of a reading that takes every order two or more demonstrations keep without exception as
established (``order_support=2``), however likely by chance."""

CANDIDATES = ("general", f"general{CONSISTENT}", "strict", "partial order", f"partial order{CONSISTENT}")
"""The readings ``auto`` chooses between, the default first."""

Fitter = Callable[[str, Sequence[Sequence[str]]], HTN]
"""Learns one reading (by name) from action sequences."""


@dataclass(frozen=True)
class Selection:
    """Which reading was kept and why.

    Attributes:
        chosen: The reading kept.
        reason: ``"held-out likelihood"``, ``"the readings agree"`` or ``"too few demonstrations"``.
        scores: Mean held-out log-likelihood per demonstration (nats) of each reading, when compared.
        admitted: Held-out demonstrations each reading admitted, when compared.
        folds: Folds of the cross-validation (0 when none was run).
    """

    chosen: str
    reason: str
    scores: dict[str, float] = field(default_factory=dict)
    admitted: dict[str, int] = field(default_factory=dict)
    folds: int = 0

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (``"selection"`` in ``learn --format json``)."""
        return {
            "chosen": self.chosen,
            "reason": self.reason,
            "held_out_log_likelihood": {k: round(v, 4) for k, v in self.scores.items()},
            "held_out_admitted": dict(self.admitted),
            "folds": self.folds,
        }

    def describe(self) -> str:
        """One line for a terminal."""
        if not self.scores:
            return f"reading: {self.chosen} ({self.reason})"
        scores = ", ".join(f"{name} {value:.2f}" for name, value in self.scores.items())
        return (
            f"reading: {self.chosen} (held-out log-likelihood per demonstration, {self.folds} folds: {scores})"
        )


def held_out_log_likelihood(htn: HTN, actions: Sequence[str], slip_rate: float) -> tuple[float, bool]:
    """The log-likelihood of a held-out demonstration under ``htn`` and whether it admits it (see the module
    docstring for how a refused one is explained)."""
    reading = OrderLikelihood(htn)
    value = reading.log_probability_of_actions(actions)
    if value > -math.inf:
        return value, True
    steps = list(actions)
    best = -math.inf
    for i, step in enumerate(steps):
        rest = steps[:i] + steps[i + 1 :]
        for j in range(len(rest) + 1):
            if j != i:
                best = max(best, reading.log_probability_of_actions([*rest[:j], step, *rest[j:]]))
    landing = math.log(slip_rate) - math.log(max(len(steps), 1))
    if best > -math.inf:
        return best + landing, False
    return math.log(slip_rate) - math.lgamma(len(steps) + 1), False


def select_reading(
    sequences: Sequence[Sequence[str]],
    fit: Fitter,
    full: dict[str, HTN],
    *,
    folds: int,
    min_demonstrations: int,
    slip_rate: float,
) -> Selection:
    """Choose a reading among those of ``full`` (see the module docstring).

    Args:
        sequences: The demonstrations, as action ids.
        fit: Learns a reading from some of them.
        full: Each reading learned from all of them (to tell whether they differ).
        folds: At most this many folds (leave one out when there are fewer demonstrations).
        min_demonstrations: Compare only from this many demonstrations on.
        slip_rate: The probability of a refused demonstration as noise (see the module docstring).
    """
    if len({htn.canonical() + (htn.count_orderings(),) for htn in full.values()}) == 1:
        return Selection(READINGS[0], "the readings agree")
    if len(sequences) < min_demonstrations:
        return Selection(READINGS[0], "too few demonstrations")
    k = min(folds, len(sequences))
    totals = dict.fromkeys(full, 0.0)
    admitted = dict.fromkeys(full, 0)
    for fold in range(k):
        train = [s for i, s in enumerate(sequences) if i % k != fold]
        held = [s for i, s in enumerate(sequences) if i % k == fold]
        for name in full:
            htn = fit(name, train)
            for actions in held:
                value, ok = held_out_log_likelihood(htn, actions, slip_rate)
                totals[name] += value
                admitted[name] += ok
    scores = {name: total / len(sequences) for name, total in totals.items()}
    best = max(scores.values())
    chosen = next(name for name in full if scores[name] == best)
    return Selection(chosen, "held-out likelihood", scores, admitted, k)
