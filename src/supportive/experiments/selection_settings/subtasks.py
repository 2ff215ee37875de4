"""From how many demonstrations the ``general`` reading makes subtasks: the sweep and the procedure that
picks :class:`~supportive.learning.learner.HTNLearner`'s ``subtask_demonstrations``.

Each selection-settings trial also learns its demonstrations with the ``general`` reading twice — making
subtasks (chains and cliques) and making none (every step a root, in the orders the evidence establishes) —
and scores both on the same fresh executions, as the readings are scored. A **threshold** ``k`` (a value of
``subtask_demonstrations``) scores the first from ``k`` demonstrations on and the second below; its gain at
``n`` demonstrations is the first's score minus the second's when ``n >= k``, else 0.

The procedure (:func:`choose_threshold`): among the thresholds that keep the learner issue #13 measured
(subtasks made from :data:`RECALL_DEMONSTRATIONS` demonstrations, where its precision and recall were fixed),
the best mean gain over the grid — then the largest threshold within one standard error of it: subtasks are
claims (these steps are never interleaved) that a partial order does not make, so where the fresh
executions cannot tell the two apart, fewer claims are kept.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.experiments.generalisation.measure import DEMONSTRATIONS as RECALL_DEMONSTRATIONS
from supportive.experiments.selection_settings.gains import (
    best_qualified,
    mean_gain,
    row_summary,
    set_distances,
    thresholded_gains,
    within_one_error,
)

__all__ = ["choose_threshold", "summarize_thresholds", "threshold_gains"]


def threshold_gains(results: Sequence[Mapping[str, Any]], threshold: int) -> dict[int, list[float]]:
    """Per number of demonstrations, each task's gain under ``threshold`` (see the module docstring), in the
    order of ``results``."""
    return thresholded_gains(results, threshold, _made_minus_none)


def _made_minus_none(trial: Mapping[str, Any]) -> float:
    """What making subtasks scored on the trial's fresh executions minus what making none scored."""
    return float(trial["subtasks"]["made"]["log_likelihood"] - trial["subtasks"]["none"]["log_likelihood"])


def summarize_thresholds(
    results: Sequence[Mapping[str, Any]], thresholds: Sequence[int], fresh: int
) -> dict[str, Any]:
    """Per number of demonstrations, what making subtasks gains (mean and 95 % interval over the tasks, and per
    profile) and the share of fresh executions each way admits; every threshold's mean gain over the grid,
    whether it qualifies, and its distance from the best (``gap``, with the standard error ``error`` of that
    difference); the best and the chosen threshold (:func:`choose_threshold`). ``fresh``: the fresh executions
    each trial scores."""
    present = sorted({int(r["demonstrations"]) for r in results})
    gains: dict[str, Any] = {}
    admitted: dict[str, dict[str, float]] = {}
    for n in present:
        cell = [r for r in results if r["demonstrations"] == n]
        differences = [_made_minus_none(r) for r in cell]
        gains[str(n)] = row_summary(differences, cell)
        admitted[str(n)] = {
            way: round(sum(r["subtasks"][way]["admitted"] for r in cell) / (fresh * len(cell)), 6)
            for way in ("made", "none")
        }
    per_threshold = {k: threshold_gains(results, k) for k in thresholds}
    rows: dict[str, dict[str, Any]] = {
        str(k): {"gain": round(mean_gain(per_threshold[k]), 6), "qualifies": k <= RECALL_DEMONSTRATIONS}
        for k in thresholds
    }
    best_name = best_qualified(rows, int)
    set_distances(rows, {str(k): gains for k, gains in per_threshold.items()}, best_name)
    best = None if best_name is None else int(best_name)
    return {
        "gains": gains,
        "admitted": admitted,
        "thresholds": rows,
        "best": best,
        "chosen": choose_threshold(rows),
    }


def choose_threshold(rows: Mapping[str, Mapping[str, Any]]) -> int | None:
    """The procedure that picks ``subtask_demonstrations``: the largest qualifying threshold within one
    standard error of the best (ties of gain go to the larger); None when none qualifies."""
    within = [int(k) for k, row in rows.items() if row["qualifies"] and within_one_error(row)]
    return max(within, default=None)
