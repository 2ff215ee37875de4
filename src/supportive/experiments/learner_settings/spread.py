"""How sure the learner-settings choice is: the tasks with mistakes resampled.

A setting's worst F1 is a minimum over cells of F1s of pooled counts, so it has no textbook standard error.
The tasks with mistakes are resampled with replacement within each cell (a kind of mistake and a number of
demonstrations: the cell is what a worst F1 is taken over), :data:`RESAMPLES` times, with a fixed seed, and
every setting is scored on the same resampled tasks (paired). For each setting the procedure qualifies
(:func:`~supportive.experiments.learner_settings.measure.choose`'s clean-data limits, which are not
resampled) this gives how far its worst F1 is behind the chosen one's (``gap``), the standard deviation of that
difference over the resamples (``error``, its bootstrap standard error), and the share of resamples in which
it has the best worst F1 of the qualified settings (``best_share``; ties go to the first in grid order, as in
``choose``). A setting whose ``gap`` is within its ``error`` is one the run does not tell from the chosen one.

>>> tasks = [
...     {"case": "moved", "demonstrations": 20, "mistakes": 2,
...      "settings": {"a": {"reported": 2, "right": 2, "found": 2}, "b": {"reported": 1, "right": 1, "found": 1}}},
...     {"case": "moved", "demonstrations": 20, "mistakes": 2,
...      "settings": {"a": {"reported": 2, "right": 1, "found": 1}, "b": {"reported": 2, "right": 2, "found": 2}}},
... ]
>>> round(float(worst_f1s(tasks, ["a", "b"])[0]), 4), round(float(worst_f1s(tasks, ["a", "b"])[1]), 4)
(0.75, 0.8571)
>>> out = spread(tasks, ["a", "b"], "b", resamples=200, seed=0)
>>> out["b"]["gap"], out["b"]["error"], out["a"]["gap"] > 0, 0 < out["a"]["best_share"] < out["b"]["best_share"]
(0.0, 0.0, True, True)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from supportive.errors import ExperimentError

__all__ = ["RESAMPLES", "SEED", "f1_scores", "spread", "worst_f1s"]

RESAMPLES = 1000
"""Bootstrap resamples of the tasks with mistakes: a sample size of the spread's estimate, not a setting."""
SEED = 0
"""The resampling's seed: the spread of a run's metrics is a function of its trials alone."""

_COUNTS = ("reported", "right", "found")

FloatArray = npt.NDArray[np.float64]


def f1_scores(reported: Any, right: Any, found: Any, mistakes: Any) -> tuple[Any, Any, Any]:
    """Precision, recall and F1 from pooled counts (numbers or arrays, elementwise): precision is 1 where
    nothing was reported, recall 1 where no mistake was put in, F1 0 where both are 0.

    >>> f1_scores(4, 3, 3, 6)
    (0.75, 0.5, 0.6)
    >>> f1_scores(0, 0, 0, 0)
    (1.0, 1.0, 1.0)
    """
    reported, right, found, mistakes = (np.asarray(x, dtype=float) for x in (reported, right, found, mistakes))
    precision = np.where(reported > 0, right / np.maximum(reported, 1.0), 1.0)
    recall = np.where(mistakes > 0, found / np.maximum(mistakes, 1.0), 1.0)
    total = precision + recall
    f1 = np.where(total > 0, 2 * precision * recall / np.where(total > 0, total, 1.0), 0.0)
    return _plain(precision), _plain(recall), _plain(f1)


def _plain(x: FloatArray) -> Any:
    """A 0-d array as a Python float, any other array as it is."""
    return float(x) if x.ndim == 0 else x


def _cells(tasks: Sequence[Mapping[str, Any]]) -> dict[tuple[str, int], list[Mapping[str, Any]]]:
    """The tasks with mistakes put in, by cell (kind of mistake, number of demonstrations), as the summary's
    table groups them; a cell where no mistake could be put in is left out, as its worst F1 leaves it out."""
    cells: dict[tuple[str, int], list[Mapping[str, Any]]] = {}
    for task in tasks:
        if task["case"] != "none":
            cells.setdefault((task["case"], int(task["demonstrations"])), []).append(task)
    return {cell: members for cell, members in cells.items() if sum(t["mistakes"] for t in members)}


def worst_f1s(
    tasks: Sequence[Mapping[str, Any]], names: Sequence[str], draws: Mapping[tuple[str, int], Any] | None = None
) -> FloatArray:
    """Each setting's worst F1 over the cells of ``tasks`` (those with mistakes put in), pooling each cell's
    counts; with ``draws`` (a cell's tasks' indices into that cell, shape ``(resamples, tasks)``), one row per
    resample, the cells' tasks taken as drawn."""
    scores = []
    for cell, members in _cells(tasks).items():
        counts = {k: np.array([[t["settings"][n][k] for n in names] for t in members], dtype=float) for k in _COUNTS}
        mistakes = np.array([t["mistakes"] for t in members], dtype=float)
        if draws is None:
            sums = {k: v.sum(axis=0) for k, v in counts.items()}
            total: Any = mistakes.sum()
        else:
            chosen = np.asarray(draws[cell])
            sums = {k: v[chosen].sum(axis=1) for k, v in counts.items()}
            total = mistakes[chosen].sum(axis=1)[:, None]
        scores.append(f1_scores(sums["reported"], sums["right"], sums["found"], total)[2])
    if not scores:  # no task with mistakes: every worst F1 is 0, as in the summary's table
        return np.zeros(len(names))
    return np.asarray(np.min(scores, axis=0), dtype=float)


def spread(
    tasks: Sequence[Mapping[str, Any]], qualified: Sequence[str], chosen: str, resamples: int = RESAMPLES, seed: int = SEED
) -> dict[str, dict[str, float]]:
    """For each setting in ``qualified`` (in grid order; ``chosen`` among them): ``gap`` (the chosen setting's
    worst F1 minus this one's, on the run's tasks), ``error`` (the bootstrap standard error of that difference)
    and ``best_share`` (the share of resamples in which it has the best worst F1 of ``qualified``).

    Raises:
        ExperimentError: ``chosen`` is not among ``qualified``.
    """
    if chosen not in qualified:
        raise ExperimentError(f"the chosen setting {chosen!r} is not among the qualified ones")
    rng = np.random.default_rng(seed)
    cells = _cells(tasks)
    draws = {cell: rng.integers(0, len(cells[cell]), size=(resamples, len(cells[cell]))) for cell in sorted(cells)}
    observed = worst_f1s(tasks, qualified)
    resampled = worst_f1s(tasks, qualified, draws) if draws else np.zeros((resamples, len(qualified)))
    at = list(qualified).index(chosen)
    best = np.bincount(np.argmax(resampled, axis=1), minlength=len(qualified)) / resamples
    return {
        name: {
            "gap": round(float(observed[at] - observed[j]), 4),
            "error": round(float(np.std(resampled[:, at] - resampled[:, j])), 4),
            "best_share": round(float(best[j]), 4),
        }
        for j, name in enumerate(qualified)
    }
