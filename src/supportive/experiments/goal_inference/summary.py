"""Goal inference: trial results -> metrics (accuracy per setting and per size, work per update, tasks).

Everything here is deterministic: the harness removes the trials' wall-clock ``timing`` before
:func:`summarize` sees them (and hands them to :func:`~.plots.timing_report` instead).
"""

from __future__ import annotations

import statistics
from collections.abc import Mapping, Sequence
from typing import Any

from supportive.errors import ExperimentError
from supportive.experiments.goal_inference.design import (
    EVENTS_PER_ACTION,
    MEAN_DURATION,
    SETTINGS,
    TIMED_SETTING,
)
from supportive.experiments.goal_inference.timing import MODELS
from supportive.experiments.statistics import mean_ci

__all__ = ["ACCURACY_MODELS", "LEVELS", "summarize", "summarize_setting", "summarize_sizes"]

LEVELS = ("subgoal", "subtask")
"""What is ranked: the current subgoal, and the subtask enclosing it (the subgoal's parent)."""
ACCURACY_MODELS = (*MODELS, "progress")
"""Models whose accuracy is measured: the thesis's two HMMs and the progress-aware tracker."""


def summarize_setting(results: Sequence[Mapping[str, Any]], key: str) -> dict[str, Any]:
    """Accuracy at one setting over trials: per model and level the mean and its 95% CI; ``difference``:
    hierarchical − flat, paired by trial; ``hierarchical_ahead`` / ``flat_ahead``: trials in which one model
    was strictly more accurate."""
    scores = [r["accuracy"][key] for r in results]
    summary: dict[str, Any] = {
        model: {level: mean_ci([s[model][level] for s in scores], bounds=(0.0, 1.0)) for level in LEVELS}
        for model in ACCURACY_MODELS
    }
    summary["progress_difference"] = {
        level: mean_ci([s["progress"][level] - s["hierarchical"][level] for s in scores]) for level in LEVELS
    }
    summary["difference"] = {
        level: mean_ci([s["hierarchical"][level] - s["flat"][level] for s in scores]) for level in LEVELS
    }
    summary["hierarchical_ahead"] = {
        level: sum(s["hierarchical"][level] > s["flat"][level] for s in scores) for level in LEVELS
    }
    summary["flat_ahead"] = {
        level: sum(s["flat"][level] > s["hierarchical"][level] for s in scores) for level in LEVELS
    }
    return summary


def _mean(values: Sequence[float]) -> float:
    return round(statistics.fmean(values), 6)


def summarize_sizes(results: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """Per task size: trials, the tasks' mean shape (``subtasks``, ``depth``), the mean steps of a stream,
    each model's mean ``transition_nonzeros`` and ``operator_entries``, and the mean accuracy per setting,
    model and level."""
    rows = []
    for size in sorted({int(r["subgoals"]) for r in results}):
        members = [r for r in results if int(r["subgoals"]) == size]
        rows.append(
            {
                "subgoals": size,
                "trials": len(members),
                "subtasks": _mean([m["subtasks"] for m in members]),
                "depth": _mean([m["depth"] for m in members]),
                "steps": _mean([s for m in members for s in m["steps"].values()]),
                **{
                    measure: {model: _mean([m[measure][model] for m in members]) for model in MODELS}
                    for measure in ("transition_nonzeros", "operator_entries")
                },
                "accuracy": {
                    s.key: {
                        model: {
                            level: _mean([m["accuracy"][s.key][model][level] for m in members])
                            for level in LEVELS
                        }
                        for model in ACCURACY_MODELS
                    }
                    for s in SETTINGS
                },
                "progress_difference": {
                    s.key: mean_ci(
                        [
                            m["accuracy"][s.key]["progress"]["subgoal"]
                            - m["accuracy"][s.key]["hierarchical"]["subgoal"]
                            for m in members
                        ]
                    )
                    for s in SETTINGS
                },
            }
        )
    return rows


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Metrics of a goal-inference run from its trial results (in trial order, without their ``timing``).

    Returns:
        ``design``: the run's sizes and stream parameters; ``settings``: the observation settings;
        ``accuracy``: per setting, :func:`summarize_setting`; ``sizes``: :func:`summarize_sizes`; ``tasks``:
        the trial results.

    Raises:
        ExperimentError: for no results.
    """
    if not results:
        raise ExperimentError("goal inference: no trial results to summarise")
    records = [dict(r) for r in results]
    return {
        "design": {
            "sizes": sorted({int(r["subgoals"]) for r in records}),
            "events_per_action": EVENTS_PER_ACTION,
            "mean_duration": MEAN_DURATION,
            "timed_setting": TIMED_SETTING,
        },
        "settings": [
            {
                "key": s.key,
                "overlap": s.overlap,
                "noise": s.noise,
                "spurious": s.spurious,
                "strength": s.strength,
            }
            for s in SETTINGS
        ],
        "accuracy": {s.key: summarize_setting(records, s.key) for s in SETTINGS},
        "sizes": summarize_sizes(records),
        "tasks": records,
    }
