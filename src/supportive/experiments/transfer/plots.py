"""Transfer: the plots (PNG, matplotlib Agg)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.plotting import new_figure, save_png
from supportive.experiments.statistics import error_bar
from supportive.experiments.transfer.report import label

__all__ = ["CONDITIONS_PLOT", "TASKS_PLOT", "plots"]

CONDITIONS_PLOT = "iterations.png"
"""Mean episodes to full comprehension per condition, with 95% CIs (Figure 2.6)."""
TASKS_PLOT = "tasks.png"
"""Mean episodes per task and condition."""

_SHORT = {
    "none": "(a) no transfer",
    "q": "(b) Q transfer",
    "cchtn": "(c) Q + macros",
    "q_raw": "(b′) Q,\nunscaled",
    "cchtn_raw": "(c′) Q + macros,\nunscaled",
}
_COLOURS = {
    "none": "tab:gray",
    "q": "tab:orange",
    "cchtn": "tab:blue",
    "q_raw": "navajowhite",
    "cchtn_raw": "lightsteelblue",
}


def _short(key: str) -> str:
    condition, _, reading = key.partition(":")
    return f"{_SHORT[condition]}\n{reading}" if reading else _SHORT[condition]


def _colour(key: str) -> str:
    return _COLOURS[key.partition(":")[0]]


def _hatch(key: str) -> str:
    return "//" if key.endswith(":fixed-order") else ""


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``iterations.png`` and ``tasks.png`` into ``directory`` and return their paths."""
    return [_bars(metrics, directory / CONDITIONS_PLOT), _tasks(metrics, directory / TASKS_PLOT)]


def _bars(metrics: Mapping[str, Any], path: Path) -> Path:
    figure = new_figure(8.0, 4.5)
    ax = figure.subplots()
    conditions = list(metrics["columns"])
    means: list[float] = []
    errors: list[list[float]] = [[], []]
    for c in conditions:
        s = metrics["conditions"][c]["episodes"]
        means.append(s["mean"])
        below, above = error_bar(s)
        errors[0].append(below)
        errors[1].append(above)
    xs = range(len(conditions))
    ax.bar(
        xs, means, yerr=errors, capsize=4, color=[_colour(c) for c in conditions],
        hatch=[_hatch(c) for c in conditions],
    )  # fmt: skip
    ax.set_xticks(list(xs), [_short(c) for c in conditions], fontsize=7)
    ax.set_ylabel("episodes to full task comprehension")
    ax.set_title(f"Task exploration, {metrics['trials']} trials (mean, 95% CI; censored runs at the cap)")
    ax.grid(axis="y", alpha=0.3)
    return save_png(figure, path)


def _tasks(metrics: Mapping[str, Any], path: Path) -> Path:
    figure = new_figure(12.0, 5.0)
    ax = figure.subplots()
    tasks = metrics["tasks"]
    conditions = list(metrics["columns"])
    width = 0.8 / len(conditions)
    for k, c in enumerate(conditions):
        xs = [i + (k - (len(conditions) - 1) / 2) * width for i in range(len(tasks))]
        ax.bar(
            xs, [t["episodes"][c] for t in tasks], width, color=_colour(c), hatch=_hatch(c), label=label(c)
        )
    ax.set_xticks(range(len(tasks)), [t["task"] for t in tasks], rotation=60, ha="right", fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel("episodes (mean over seeds, log)")
    ax.legend(fontsize=8)
    ax.grid(axis="y", alpha=0.3)
    return save_png(figure, path)
