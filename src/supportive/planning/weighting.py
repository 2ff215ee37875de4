"""Plan weights (§3.2.6): how much each known lead plan counts in the support agent's objective.

Each scheme starts from the plans' durations without support in s_0 (Algorithm 5 with no support and no
decay), whose minimum is m:

* ``conservative`` (case 1): w = (m / d)^p, p = 2 — better plans count more, every plan counts.
* ``greedy`` (case 2): w = 1 for the best plans (d = m), 0 for the rest.
* ``aggressive`` (case 3): the conservative weight for plans no slower than ε = ``epsilon`` · m, and
  −α times it for the slower ones, so that making bad plans worse (or impossible) is rewarded too.
  α is set so that the negative weights' magnitudes sum to ``alpha`` times the positive weights' sum
  (default ½). The thesis asks only that negative magnitudes stay below the positive ones, lest the
  support agent block progress where good and bad plans overlap; with this α and a nullification
  penalty of at least twice the worst plan's duration, making every plan impossible never scores better
  than doing nothing (tested).

>>> plan_weights([10.0, 20.0], "conservative").round(3).tolist()
[1.0, 0.25]
>>> plan_weights([10.0, 20.0], "aggressive").round(3).tolist()
[1.0, -0.5]
"""

from __future__ import annotations

from collections.abc import Sequence
from enum import StrEnum

import numpy as np

from supportive.errors import PlanningError

__all__ = ["WeightingScheme", "parse_scheme", "plan_weights"]


class WeightingScheme(StrEnum):
    """The three weighting schemes of §3.2.6."""

    CONSERVATIVE = "conservative"
    GREEDY = "greedy"
    AGGRESSIVE = "aggressive"


def parse_scheme(scheme: WeightingScheme | str) -> WeightingScheme:
    """The weighting scheme named ``scheme``.

    Raises:
        PlanningError: for an unknown name.
    """
    try:
        return WeightingScheme(scheme)
    except ValueError:
        names = ", ".join(s.value for s in WeightingScheme)
        raise PlanningError(f"unknown weighting scheme {scheme!r}: expected one of {names}") from None


def plan_weights(
    durations: Sequence[float],
    scheme: WeightingScheme | str = WeightingScheme.CONSERVATIVE,
    *,
    power: float = 2.0,
    epsilon: float = 1.1,
    alpha: float = 0.5,
) -> np.ndarray:
    """The weight of every known plan, given its duration without support in s_0.

    Args:
        durations: Each plan's duration (seconds, > 0) in s_0 without support.
        scheme: ``conservative``, ``greedy`` or ``aggressive``.
        power: p of the conservative weight (m / d)^p.
        epsilon: ε as a multiple of m (≥ 1): aggressive weights are negative for plans slower than ε · m.
        alpha: Aggressive only: the negative weights' magnitudes sum to ``alpha`` times the positive ones'
            (in (0, 1)).

    Raises:
        PlanningError: for no durations, a duration that is not positive and finite, an unknown scheme, or a
            parameter out of range.
    """
    kind = parse_scheme(scheme)
    d = np.asarray(durations, dtype=float)
    if d.size == 0:
        raise PlanningError("plan weights need at least one plan duration")
    if not np.all(np.isfinite(d)) or np.any(d <= 0):
        raise PlanningError(f"plan durations must be positive and finite, got {d.tolist()}")
    if power <= 0:
        raise PlanningError(f"power must be > 0, got {power}")
    if epsilon < 1:
        raise PlanningError(f"epsilon must be >= 1 (a multiple of the best duration m), got {epsilon}")
    if not 0 < alpha < 1:
        raise PlanningError(f"alpha must be in (0, 1), got {alpha}")
    best = float(d.min())
    relative = best / d
    if kind is WeightingScheme.GREEDY:
        greedy: np.ndarray = np.isclose(d, best, rtol=1e-9, atol=0.0).astype(float)
        return greedy
    weights = relative**power
    if kind is WeightingScheme.CONSERVATIVE:
        return weights
    slow = d > epsilon * best
    if slow.any():
        weights[slow] *= -alpha * weights[~slow].sum() / weights[slow].sum()
    return weights
