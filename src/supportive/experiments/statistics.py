"""Means over trials with 95% confidence intervals, and how reports and plots show them: one place for every
experiment."""

from __future__ import annotations

import math
import statistics
from collections.abc import Mapping, Sequence
from typing import Any

from scipy import stats

from supportive.errors import ExperimentError

__all__ = [
    "above_zero",
    "below_zero",
    "error_bar",
    "format_ci",
    "format_sd",
    "mean_ci",
    "mean_sd",
    "ratio_ci",
]


def mean_ci(
    values: Sequence[float], digits: int = 6, bounds: tuple[float, float] | None = None
) -> dict[str, Any]:
    """The mean of ``values`` and a 95% confidence interval for it (Student's t), as plain JSON.

    Bounds are ``None`` for fewer than two values (no interval can be given), everything is ``None`` for none;
    values are rounded to ``digits`` and the bounds clipped to ``bounds`` when given (a share lies in 0–1).

    >>> mean_ci([0.8, 0.9, 1.0])
    {'mean': 0.9, 'low': 0.651586, 'high': 1.148414, 'n': 3}
    >>> mean_ci([0.8, 0.9, 1.0], bounds=(0.0, 1.0))["high"]
    1.0
    >>> mean_ci([0.5]), mean_ci([])["mean"]
    ({'mean': 0.5, 'low': None, 'high': None, 'n': 1}, None)
    """
    if not values:
        return {"mean": None, "low": None, "high": None, "n": 0}
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


def ratio_ci(
    numerators: Sequence[float],
    denominators: Sequence[float],
    digits: int = 6,
    bounds: tuple[float, float] | None = None,
) -> dict[str, Any]:
    """The ratio of the means of paired samples, mean(numerators) / mean(denominators), with a 95% confidence
    interval by the delta method (the standard error of the ratio estimator: the sample standard deviation
    of ``y − R x`` over √n, divided by mean(x); Student's t), as plain JSON like :func:`mean_ci`.

    Everything is ``None`` when the denominators' mean is 0; the bounds are ``None`` for fewer than two pairs,
    and clipped to ``bounds`` when given (a share lies in 0–1).

    >>> ratio_ci([1.0, 2.0, 3.0], [2.0, 4.0, 6.0])
    {'mean': 0.5, 'low': 0.5, 'high': 0.5, 'n': 3}
    >>> r = ratio_ci([1.0, 3.0, 2.0, 2.0], [4.0, 4.0, 5.0, 3.0]); r["low"] < r["mean"] == 0.5 < r["high"]
    True
    >>> ratio_ci([1.0, 0.0, 2.0], [1.0, 2.0, 2.0], bounds=(0.0, 1.0))["low"]
    0.0
    """
    if len(numerators) != len(denominators):
        raise ExperimentError("ratio_ci: numerators and denominators must pair up")
    n = len(numerators)
    if not n or statistics.fmean(denominators) == 0:
        return {"mean": None, "low": None, "high": None, "n": n}
    x, y = statistics.fmean(denominators), statistics.fmean(numerators)
    ratio = y / x
    low: float | None = None
    high: float | None = None
    if n > 1:
        residuals = [b - ratio * a for a, b in zip(denominators, numerators, strict=True)]
        half = float(stats.t.ppf(0.975, n - 1)) * statistics.stdev(residuals) / math.sqrt(n) / abs(x)
        low, high = ratio - half, ratio + half
        if bounds is not None:
            low, high = max(bounds[0], low), min(bounds[1], high)
        low, high = round(low, digits), round(high, digits)
    return {"mean": round(ratio, digits), "low": low, "high": high, "n": n}


def mean_sd(values: Sequence[float], digits: int = 6) -> dict[str, Any]:
    """The mean of ``values`` and their sample standard deviation (the thesis's error bars in §3.5), as JSON.

    >>> mean_sd([1.0, 2.0, 3.0]), mean_sd([4.0])["sd"]
    ({'mean': 2.0, 'sd': 1.0, 'n': 3}, 0.0)
    """
    if not values:
        return {"mean": None, "sd": None, "n": 0}
    sd = statistics.stdev(values) if len(values) > 1 else 0.0
    return {"mean": round(statistics.fmean(values), digits), "sd": round(sd, digits), "n": len(values)}


def format_sd(summary: Mapping[str, Any], digits: int = 2) -> str:
    """``"mean ± sd"``; ``–`` for none.

    >>> format_sd({"mean": 2.0, "sd": 0.5}, 1)
    '2.0 ± 0.5'
    """
    if summary.get("mean") is None:
        return "–"
    return f"{summary['mean']:.{digits}f} ± {summary['sd']:.{digits}f}"


def format_ci(summary: Mapping[str, Any], digits: int = 3, *, signed: bool = False) -> str:
    """``"mean [low, high]"``; the mean alone when there is no interval (or it has no width); ``–`` for none.

    >>> format_ci({"mean": 2.0, "low": 1.5, "high": 2.5}, 1), format_ci({"mean": 0.1, "low": None}, 2, signed=True)
    ('2.0 [1.5, 2.5]', '+0.10')
    """

    def number(value: float) -> str:
        return format(round(value, digits) + 0.0, f"+.{digits}f" if signed else f".{digits}f")  # no "-0.0"

    if summary.get("mean") is None:
        return "–"
    low, high = summary.get("low"), summary.get("high")
    if low is None or high is None or low == high:
        return number(summary["mean"])
    return f"{number(summary['mean'])} [{number(low)}, {number(high)}]"


def above_zero(summary: Mapping[str, Any]) -> bool:
    """True when the whole interval lies above zero (a difference that is significantly positive)."""
    return summary.get("low") is not None and summary["low"] > 0


def below_zero(summary: Mapping[str, Any]) -> bool:
    """True when the whole interval lies below zero."""
    return summary.get("high") is not None and summary["high"] < 0


def error_bar(summary: Mapping[str, Any]) -> tuple[float, float]:
    """Distances from the mean down to the low bound and up to the high bound (0 without an interval)."""
    mean = summary["mean"]
    low, high = summary.get("low"), summary.get("high")
    return (0.0 if low is None else mean - low, 0.0 if high is None else high - mean)
