"""Gains over a grid of numbers of demonstrations, and the one-standard-error rule the procedures use.

A setting's **gains** are, per number of demonstrations (a row), one value per generated task: what the
learner with that setting scores on fresh executions minus a baseline's score on the same task. The rows
are weighted alike; within a row the tasks of two settings are paired (the same task and fresh executions),
and the rows are independent (different tasks).
"""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from supportive.experiments.generalisation.measure import DEMONSTRATIONS as RECALL_DEMONSTRATIONS
from supportive.experiments.statistics import mean_ci
from supportive.generate.habits import PEOPLE
from supportive.generate.mistakes import PROFILES

__all__ = [
    "best_qualified",
    "mean_gain",
    "paired_difference",
    "recall_trials",
    "row_summary",
    "set_distances",
    "thresholded_gains",
    "within_one_error",
]


def thresholded_gains(
    results: Sequence[Mapping[str, Any]], threshold: int | None, gain: Callable[[Mapping[str, Any]], float]
) -> dict[int, list[float]]:
    """Per number of demonstrations (a row), each trial's gain under a setting that acts from ``threshold``
    demonstrations on: ``gain(trial)`` where the trial has that many or more, else 0 (always 0 for a
    ``threshold`` of None: a setting that never acts), in the order of ``results``.

    >>> trials = [{"demonstrations": 2, "g": 1.0}, {"demonstrations": 5, "g": 2.0}]
    >>> thresholded_gains(trials, 3, lambda t: t["g"])
    {2: [0.0], 5: [2.0]}
    """
    rows: dict[int, list[float]] = {}
    for r in results:
        n = int(r["demonstrations"])
        rows.setdefault(n, []).append(gain(r) if threshold is not None and n >= threshold else 0.0)
    return rows


def row_summary(differences: Sequence[float], cell: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """One row's gains: their mean with its 95 % interval, and the mean per task profile (``profiles``) and per
    kind of people (``people``) over the trials of ``cell`` (the trial results the ``differences`` come from,
    in the same order)."""
    return {
        **mean_ci(differences),
        "profiles": _means_by(differences, cell, "profile", PROFILES),
        "people": _means_by(differences, cell, "people", PEOPLE),
    }


def _means_by(
    differences: Sequence[float], cell: Sequence[Mapping[str, Any]], key: str, values: Sequence[str]
) -> dict[str, float]:
    """The mean of ``differences`` over the trials of ``cell`` with each of ``values`` under ``key`` (values no
    trial has left out)."""
    return {
        value: round(statistics.fmean(d for d, r in zip(differences, cell, strict=True) if r[key] == value), 6)
        for value in values
        if any(r[key] == value for r in cell)
    }


def recall_trials(results: Sequence[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
    """The trials issue #13's recall is measured on: ``uniform`` tasks learned from
    :data:`RECALL_DEMONSTRATIONS` demonstrations drawn uniformly (people without habits), in order.

    >>> recall_trials([{"demonstrations": 4, "profile": "uniform", "people": "habits"}])
    []
    """
    return [
        r for r in results
        if r["demonstrations"] == RECALL_DEMONSTRATIONS and r["profile"] == "uniform" and r["people"] == "uniform"
    ]


def mean_gain(rows: Mapping[int, Sequence[float]]) -> float:
    """The mean over the rows of the mean gain of each (0 for no rows).

    >>> mean_gain({2: [1.0, 3.0], 4: [0.0]})
    1.0
    """
    return statistics.fmean(statistics.fmean(row) for row in rows.values()) if rows else 0.0


def paired_difference(
    first: Mapping[int, Sequence[float]], second: Mapping[int, Sequence[float]]
) -> tuple[float, float]:
    """``first``'s mean gain minus ``second``'s and the standard error of that difference: the tasks of a row
    paired, the rows independent (the variance of a mean of row means).

    >>> paired_difference({2: [1.0, 3.0]}, {2: [0.0, 0.0]})
    (2.0, 1.0)
    """
    if not first:
        return 0.0, 0.0
    variance = 0.0
    for n, row in first.items():
        differences = [a - b for a, b in zip(row, second[n], strict=True)]
        variance += statistics.variance(differences) / len(differences) if len(differences) > 1 else 0.0
    return mean_gain(first) - mean_gain(second), math.sqrt(variance) / len(first)


def set_distances(
    rows: Mapping[str, dict[str, Any]], gains: Mapping[str, Mapping[int, Sequence[float]]], best: str | None
) -> None:
    """Give each of ``rows`` (settings, by name) its ``gap`` behind the ``best`` one and the standard ``error`` of
    that difference (:func:`paired_difference` of their per-task ``gains``, by the same names; both 0 when
    there is no best), rounded to 6 places.

    >>> rows = {"a": {}, "b": {}}
    >>> set_distances(rows, {"a": {2: [1.0, 3.0]}, "b": {2: [0.0, 0.0]}}, "a")
    >>> rows
    {'a': {'gap': 0.0, 'error': 0.0}, 'b': {'gap': 2.0, 'error': 1.0}}
    """
    for name, row in rows.items():
        gap, error = paired_difference(gains[best], gains[name]) if best is not None else (0.0, 0.0)
        row["gap"], row["error"] = round(gap, 6), round(error, 6)


def best_qualified(rows: Mapping[str, Mapping[str, Any]], prefer: Callable[[str], Any]) -> str | None:
    """The name of the row with the best ``gain`` among those that ``qualify``; of rows tied on gain, the one
    ``prefer`` ranks highest (then the first). None when no row qualifies.

    >>> rows = {"a": {"gain": 1.0, "qualifies": True}, "b": {"gain": 1.0, "qualifies": True}, "c": {"gain": 2.0, "qualifies": False}}
    >>> best_qualified(rows, lambda name: name == "b")
    'b'
    """
    qualified = [name for name, row in rows.items() if row["qualifies"]]
    return max(qualified, key=lambda name: (rows[name]["gain"], prefer(name)), default=None)


def within_one_error(row: Mapping[str, Any]) -> bool:
    """Whether a setting is within one standard error of the best (its ``gap`` ≤ its ``error``; exactly one
    error away counts as within, rounding apart)."""
    return bool(row["gap"] <= row["error"] or math.isclose(row["gap"], row["error"]))
