"""The evidence level of the ``general`` reading: the sweep and the procedure that picks
:class:`~supportive.learning.learner.HTNLearner`'s ``evidence``.

``evidence`` is the level below which a chance is taken as evidence: a run of steps never interleaved is a
subtask when its contiguity would be that unlikely were it none, an order is established when the
demonstrations keeping it would be that unlikely were it free (``order_support`` follows from it), and the slip
search's candidates and its by-chance test read it too. A larger level makes more claims from the same
demonstrations (a tighter hierarchy); a smaller one fewer.

Each selection-settings trial also learns its demonstrations with the ``general`` reading at every level of
:data:`LEVELS` and scores each on the same fresh executions as the readings are scored. A level's gain on a
task is its score minus the :data:`CONVENTIONAL_EVIDENCE` level's.

The procedure (:func:`choose_level`): among the levels that keep issue #13's recall (admit no fewer fresh
executions of the trials :func:`~supportive.experiments.selection_settings.gains.recall_trials` picks than the
conventional level), the best mean gain over the rows — unless the conventional level is within one standard
error of it: these tasks cannot then tell the two apart, and the convention is kept.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.experiments.selection_settings.gains import (
    best_qualified,
    mean_gain,
    recall_trials,
    row_summary,
    set_distances,
    thresholded_gains,
    within_one_error,
)
from supportive.learning import HTNLearner

__all__ = ["CONVENTIONAL_EVIDENCE", "LEVELS", "choose_level", "level_gains", "summarize_levels"]

CONVENTIONAL_EVIDENCE: float = HTNLearner().evidence
"""The learner's default level (the conventional 5 %), the reference every level is scored against: kept
unless a level predicts fresh executions better by more than one standard error (:func:`choose_level`)."""

LEVELS = (0.01, 0.025, CONVENTIONAL_EVIDENCE, 0.1, 0.2)
"""The levels swept: the usual ones, from a strict 1 % to a lax 20 %."""


def level_gains(results: Sequence[Mapping[str, Any]], level: float) -> dict[int, list[float]]:
    """Per number of demonstrations, each task's gain at ``level`` over the conventional level, in the order of
    ``results``."""
    return thresholded_gains(results, 0, lambda trial: _gain(trial, level))


def _gain(trial: Mapping[str, Any], level: float) -> float:
    """What the trial's ``general`` reading at ``level`` scored on its fresh executions minus what it scored
    at the conventional level."""
    scores = trial["evidence"]
    return float(scores[str(level)]["log_likelihood"] - scores[str(CONVENTIONAL_EVIDENCE)]["log_likelihood"])


def summarize_levels(results: Sequence[Mapping[str, Any]], fresh: int) -> dict[str, Any]:
    """Per number of demonstrations, each level's gain over the conventional one (mean and 95 % interval over
    the tasks, per profile and per kind of people) and the share of fresh executions it admits; every level's
    mean gain over the rows, its recall (on :func:`~.gains.recall_trials`; None when the run learned none),
    whether it qualifies, and its distance from the best (``gap``, with the standard error ``error`` of that
    difference); the best and the chosen level (:func:`choose_level`). ``fresh``: the fresh executions each
    trial scores."""
    present = sorted({int(r["demonstrations"]) for r in results})
    gains: dict[str, dict[str, Any]] = {}
    admitted: dict[str, dict[str, float]] = {}
    for level in LEVELS:
        gains[str(level)], admitted[str(level)] = {}, {}
        for n in present:
            cell = [r for r in results if r["demonstrations"] == n]
            gains[str(level)][str(n)] = row_summary([_gain(r, level) for r in cell], cell)
            admitted[str(level)][str(n)] = _share(cell, level, fresh)
    uniform = recall_trials(results)
    recall = {level: _share(uniform, level, fresh) if uniform else None for level in LEVELS}
    per_level = {level: level_gains(results, level) for level in LEVELS}
    rows: dict[str, dict[str, Any]] = {}
    for level in LEVELS:
        kept, conventional = recall[level], recall[CONVENTIONAL_EVIDENCE]
        rows[str(level)] = {
            "gain": round(mean_gain(per_level[level]), 6),
            "recall": kept,
            "qualifies": kept is not None and conventional is not None and kept >= conventional,
        }
    best_name = best_qualified(rows, lambda name: float(name) == CONVENTIONAL_EVIDENCE)
    set_distances(rows, {str(level): gains for level, gains in per_level.items()}, best_name)
    best = None if best_name is None else float(best_name)
    return {
        "gains": gains,
        "admitted": admitted,
        "levels": rows,
        "best": best,
        "chosen": choose_level(rows, best),
    }


def _share(cell: Sequence[Mapping[str, Any]], level: float, fresh: int) -> float:
    """The share of the cell's fresh executions the ``general`` reading at ``level`` admitted (0 for none)."""
    if not cell:
        return 0.0
    admitted: int = sum(r["evidence"][str(level)]["admitted"] for r in cell)
    return round(admitted / (fresh * len(cell)), 6)


def choose_level(rows: Mapping[str, Mapping[str, Any]], best: float | None) -> float | None:
    """The procedure that picks ``evidence``: the conventional level when it qualifies and is within one
    standard error of the ``best``, else the best; None when no level qualifies."""
    conventional = rows.get(str(CONVENTIONAL_EVIDENCE))
    if best is None or conventional is None or not conventional["qualifies"]:
        return best
    return CONVENTIONAL_EVIDENCE if within_one_error(conventional) else best
