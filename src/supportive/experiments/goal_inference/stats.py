"""Goal inference: a mean and its 95% confidence interval over trials."""

from __future__ import annotations

import math
import statistics
from collections.abc import Sequence
from typing import Any

from scipy import stats

__all__ = ["mean_ci"]


def mean_ci(
    values: Sequence[float], digits: int = 6, bounds: tuple[float, float] | None = None
) -> dict[str, Any]:
    """The mean of ``values`` and a 95% confidence interval for it (Student's t over the trials; ``None``
    bounds for fewer than two values), rounded to ``digits`` and clipped to ``bounds`` when given (a share
    lies in 0–1).

    >>> mean_ci([0.8, 0.9, 1.0])
    {'mean': 0.9, 'low': 0.651586, 'high': 1.148414, 'n': 3}
    >>> mean_ci([0.8, 0.9, 1.0], bounds=(0.0, 1.0))["high"]
    1.0
    >>> mean_ci([0.5])
    {'mean': 0.5, 'low': None, 'high': None, 'n': 1}
    """
    if not values:
        raise ValueError("mean_ci needs at least one value")
    mean = statistics.fmean(values)
    low: float | None = None
    high: float | None = None
    if len(values) > 1:
        half = float(stats.t.ppf(0.975, len(values) - 1)) * statistics.stdev(values) / math.sqrt(len(values))
        low, high = mean - half, mean + half
        if bounds is not None:
            low, high = max(bounds[0], low), min(bounds[1], high)
        low, high = round(low, digits), round(high, digits)
    return {"mean": round(mean, digits), "low": low, "high": high, "n": len(values)}
