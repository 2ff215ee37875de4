"""Goal inference: describing how long online updates took, and summarising those times by task size.

Wall-clock times differ from run to run, so they never enter ``metrics.json``: each trial returns them under
its ``"timing"`` key, which the harness writes to ``timing.json`` and hands to the experiment's
``timing_report`` (:func:`~.plots.timing_report`: ``timing.md`` and ``timing.png``).
"""

from __future__ import annotations

import importlib
import platform
import statistics
from collections.abc import Mapping, Sequence
from contextlib import AbstractContextManager, nullcontext
from typing import Any, cast

__all__ = [
    "MODELS",
    "TIMING_PLOT",
    "TIMING_REPORT",
    "cpu_name",
    "describe_times",
    "one_thread",
    "summarize_timing",
    "timing_summary",
]

MODELS = ("flat", "hierarchical")
"""The two filters compared, in report order."""
TIMING_REPORT = "timing.md"
"""The per-size times in a table, beside the thesis's Figure 2.4."""
TIMING_PLOT = "timing.png"
"""Per-update time vs subgoals (log-log), flat vs hierarchical."""


def cpu_name() -> str:
    """This machine's processor, as the operating system names it (``model name`` in ``/proc/cpuinfo`` on
    Linux), else :func:`platform.processor` or :func:`platform.machine`."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as info:
            for line in info:
                if line.startswith("model name"):
                    return " ".join(line.split(":", 1)[1].split())
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def one_thread() -> AbstractContextManager[object]:
    """Limit numpy's BLAS (and OpenMP) to one thread while in the block, as the thesis timed on one thread of
    its CPU; dask's workers already run with one. Needs ``threadpoolctl`` (installed with scikit-learn);
    without it, a block that changes nothing."""
    try:
        threadpoolctl = importlib.import_module("threadpoolctl")
    except ImportError:  # pragma: no cover - threadpoolctl comes with the dev and bench extras
        return nullcontext()
    return cast(AbstractContextManager[object], threadpoolctl.threadpool_limits(limits=1))


def describe_times(seconds: Sequence[float]) -> dict[str, float]:
    """Per-update times (seconds) as ``median_us``, ``mean_us``, ``p90_us`` and ``max_us``: microseconds,
    rounded to 0.001 µs.

    >>> describe_times([1e-5, 2e-5, 4e-5])
    {'median_us': 20.0, 'mean_us': 23.333, 'p90_us': 40.0, 'max_us': 40.0}
    """
    ordered = sorted(seconds)
    return {
        "median_us": round(statistics.median(ordered) * 1e6, 3),
        "mean_us": round(statistics.fmean(ordered) * 1e6, 3),
        "p90_us": round(ordered[min(len(ordered) - 1, int(0.9 * len(ordered)))] * 1e6, 3),
        "max_us": round(ordered[-1] * 1e6, 3),
    }


def summarize_timing(timings: Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """Per task size, the trials' per-update times (their ``"timing"`` entries): for each model the median over trials of the per-trial
    medians (``median_us``), the mean of the per-trial means (``mean_us``) and the least and greatest
    per-trial median (``least_median_us``, ``greatest_median_us``); ``ratio`` is flat ÷ hierarchical
    (medians).

    >>> trial = {"subgoals": 10, "flat": {"median_us": 4.0, "mean_us": 5.0},
    ...          "hierarchical": {"median_us": 2.0, "mean_us": 3.0}}
    >>> summarize_timing([trial])[0]["ratio"]
    2.0
    """
    sizes = sorted({int(t["subgoals"]) for t in timings})
    rows = []
    for size in sizes:
        members = [t for t in timings if int(t["subgoals"]) == size]
        row: dict[str, Any] = {"subgoals": size, "trials": len(members)}
        for model in MODELS:
            medians = [m[model]["median_us"] for m in members]
            row[model] = {
                "median_us": round(statistics.median(medians), 3),
                "mean_us": round(statistics.fmean(m[model]["mean_us"] for m in members), 3),
                "least_median_us": min(medians),
                "greatest_median_us": max(medians),
            }
        flat, hierarchical = row["flat"]["median_us"], row["hierarchical"]["median_us"]
        row["ratio"] = round(flat / hierarchical, 3) if hierarchical > 0 else None
        rows.append(row)
    return rows


def timing_summary(timings: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """What ``timing.md`` and ``timing.png`` are drawn from: the processors that measured (``cpus``), this
    Python's version, the per-size summary (:func:`summarize_timing`) and every trial's times (``trials``)."""
    return {
        "cpus": sorted({str(t.get("cpu", "unknown")) for t in timings}),
        "python": platform.python_version(),
        "sizes": summarize_timing(timings),
        "trials": [dict(t) for t in timings],
    }
