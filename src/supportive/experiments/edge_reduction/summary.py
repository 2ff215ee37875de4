"""Edge reduction: trial results -> metrics (per model, per size bin, per task)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.errors import ExperimentError

__all__ = ["BIN_WIDTH", "MODELS", "bin_of", "summarize", "summarize_model"]

MODELS = ("learned", "ground_truth", "all_orderings")
"""The three models of each task: (a) learned from the demonstrations, (b) the ground truth, (c) learned from
every valid ordering (only tasks with few enough orderings)."""

BIN_WIDTH = 10
"""Task sizes are binned by tens of subgoals."""


def bin_of(subgoals: int, largest: int) -> tuple[int, int]:
    """The size bin ``(low, high)`` of a task: tens of subgoals (``10–19``, ``20–29``, …), except that the
    largest size of a run, when it is a multiple of ten, closes the bin below (``90–100``) rather than
    opening one of its own.

    >>> bin_of(17, 100), bin_of(90, 100), bin_of(100, 100), bin_of(100, 120)
    ((10, 19), (90, 100), (90, 100), (100, 109))
    """
    key = subgoals // BIN_WIDTH
    if largest % BIN_WIDTH == 0 and largest > BIN_WIDTH and subgoals > largest - BIN_WIDTH:
        key = largest // BIN_WIDTH - 1
    low = key * BIN_WIDTH
    high = low + BIN_WIDTH - 1
    if largest % BIN_WIDTH == 0 and low == largest - BIN_WIDTH:
        high = largest
    return low, high


def _mean(values: Sequence[float]) -> float:
    return round(sum(values) / len(values), 4)


def summarize_model(records: Sequence[Mapping[str, Any]]) -> dict[str, Any] | None:
    """Means over tasks of one model's sizes (see :func:`~.measure.model_sizes`); ``None`` for no task.

    ``flat_per_htn`` is total flat edges over total CC-HTN edges (above 1: the CC-HTN needs fewer; ``None``
    when the CC-HTNs have no edge); ``fewer_edges`` and ``more_edges`` count the tasks whose CC-HTN needs
    fewer, and more, edges than their flat model.

    >>> summarize_model([{"flat_edges": 12, "htn_edges": 4, "depth": 1.0, "complete": True},
    ...                  {"flat_edges": 12, "htn_edges": 5, "depth": 1.5, "complete": True}])["flat_per_htn"]
    2.6667
    """
    if not records:
        return None
    flat = [r["flat_edges"] for r in records]
    htn = [r["htn_edges"] for r in records]
    depth = [r["depth"] for r in records]
    return {
        "tasks": len(records),
        "flat_edges": _mean(flat),
        "htn_edges": _mean(htn),
        "flat_per_htn": round(sum(flat) / sum(htn), 4) if sum(htn) else None,
        "fewer_edges": sum(h < f for f, h in zip(flat, htn, strict=True)),
        "more_edges": sum(h > f for f, h in zip(flat, htn, strict=True)),
        "depth": {"mean": _mean(depth), "min": round(min(depth), 4), "max": round(max(depth), 4)},
        "complete": sum(bool(r["complete"]) for r in records),
    }


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Metrics of an edge-reduction run from its trial results (in trial order).

    Returns:
        ``tasks``: the trial results; ``models``: per model (``learned``, ``ground_truth``,
        ``all_orderings``) the means of :func:`summarize_model`; ``bins``: the same per size bin;
        ``all_orderings``: the ordering limit, how many tasks qualified and how many of those the learner
        recovered exactly; ``subgoals``: least and most subgoals.

    Raises:
        ExperimentError: for no results.
    """
    if not results:
        raise ExperimentError("edge reduction: no trial results to summarise")
    largest = max(int(r["subgoals"]) for r in results)
    groups: dict[tuple[int, int], list[Mapping[str, Any]]] = {}
    for result in results:
        groups.setdefault(bin_of(int(result["subgoals"]), largest), []).append(result)
    bins = []
    for (low, high), members in sorted(groups.items()):
        entry: dict[str, Any] = {"low": low, "high": high, "label": f"{low}–{high}"}
        for model in MODELS:
            entry[model] = summarize_model([m[model] for m in members if m[model] is not None])
        bins.append(entry)
    qualified = [r["all_orderings"] for r in results if r["all_orderings"] is not None]
    return {
        "tasks": [dict(r) for r in results],
        "subgoals": {"min": min(int(r["subgoals"]) for r in results), "max": largest},
        "models": {
            model: summarize_model([r[model] for r in results if r[model] is not None]) for model in MODELS
        },
        "bins": bins,
        "all_orderings": {
            "limit": max(int(r["orderings_limit"]) for r in results),
            "qualified": len(qualified),
            "recovered": sum(bool(q["recovered"]) for q in qualified),
        },
    }
