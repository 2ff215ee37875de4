"""``supportive reproduce all``: docs/results/summary.json."""

from __future__ import annotations

from typing import Any

from .common import RESULTS, Block, read_json

_SUMMARY = "docs/results/summary.json (supportive reproduce all)"


def _summary() -> dict[str, Any]:
    summary: dict[str, Any] = read_json(RESULTS / "summary.json")
    return summary


def reproduce_all_trials() -> str:
    """docs/experiments.md: the seed and each experiment's trials in the recorded run."""
    from supportive.experiments import get

    summary = _summary()
    counts = ", ".join(
        f"{name} {count}" + ("" if count == get(name).default_trials else f" (of a full run's {get(name).default_trials})")
        for name, count in sorted(summary["trials"].items())
    )
    return f"(seed {summary['seed']}, each experiment's trials: {counts})\n"


def reproduce_all_summary() -> str:
    """docs/experiments.md: the summary table, as ``summary.md`` renders it."""
    from supportive.experiments import findings_table

    rows = [
        (e["experiment"], e["reference"], e["findings"]) for e in _summary()["experiments"] if e["findings"]
    ]
    return findings_table(rows) + "\n"


BLOCKS: dict[str, Block] = {
    "reproduce-all-trials": Block(_SUMMARY, reproduce_all_trials),
    "reproduce-all-summary": Block(_SUMMARY, reproduce_all_summary),
}
