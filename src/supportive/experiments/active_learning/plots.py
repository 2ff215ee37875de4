"""Active learning: the plots (PNG, matplotlib Agg), after Figures 2.10 and 2.11."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.active_learning.blocks import CONDITIONS as BLOCK_CONDITIONS
from supportive.experiments.active_learning.blocks import GROUPS
from supportive.experiments.active_learning.common import STRATEGIES
from supportive.experiments.active_learning.food import CONDITIONS, LABELS
from supportive.experiments.plotting import new_figure, save_png
from supportive.experiments.statistics import error_bar

__all__ = ["BLOCKS_PLOT", "COMPREHENSION_PLOT", "blocks_plots", "food_plots"]

BLOCKS_PLOT = "paths.png"
"""Figure 2.10: mean known paths per task, data set and condition (95% CI)."""
COMPREHENSION_PLOT = "comprehension.png"
"""Figure 2.11: mean % comprehension vs iteration, solo and multi-instructor, with the thesis's."""

COLOURS = {"passive": "tab:gray", "random": "tab:red", "distance": "tab:blue", "connectivity": "tab:green"}


def blocks_plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``paths.png``: one panel per task, grouped bars (solo, pairs, triads) per condition."""
    tasks = list(metrics["tasks"])
    figure = new_figure(4.2 * len(tasks), 4.2)
    axes = figure.subplots(1, len(tasks))
    width = 0.8 / len(BLOCK_CONDITIONS)
    for ax, task in zip(axes, tasks, strict=True):
        for c, condition in enumerate(BLOCK_CONDITIONS):
            xs, ys, low, high = [], [], [], []
            for g, group in enumerate(GROUPS):
                paths = task["groups"][group]["conditions"][condition]["paths"]
                xs.append(g - 0.4 + width * (c + 0.5))
                ys.append(paths["mean"])
                below, above = error_bar(paths)
                low.append(below)
                high.append(above)
            ax.bar(xs, ys, width, yerr=[low, high], capsize=2, color=COLOURS[condition], label=condition)
        ax.set_xticks(range(len(GROUPS)), list(GROUPS))
        ax.set_title(f"Task {task['number']} ({task['orderings']} valid orderings)")
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("known unique paths (mean, 95% CI)")
    axes[0].legend(fontsize=8, loc="upper left")
    figure.suptitle(
        f"Active learning strategies by task and data set (Fig. 2.10), {metrics['panels']} panels"
    )
    return [save_png(figure, directory / BLOCKS_PLOT)]


def food_plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``comprehension.png``: % comprehension vs iteration per strategy (and the instructors' ceiling),
    solo and multi-instructor, one row of panels per reading, the thesis's curves dashed."""
    iterations = metrics["iterations"]
    thesis = metrics["thesis"]["comprehension_percent"]
    readings = list(metrics["by_reading"])
    figure = new_figure(11.0, 4.0 * len(readings))
    axes = figure.subplots(len(readings), len(CONDITIONS), sharey=True, squeeze=False)
    for row, name in zip(axes, readings, strict=True):
        comprehension = metrics["by_reading"][name]["comprehension"]
        for ax, condition in zip(row, CONDITIONS, strict=True):
            for s, strategy in enumerate(STRATEGIES):
                ours = comprehension[condition][strategy]
                xs = [n + (s - 1) * 0.12 for n in iterations]
                bars = [error_bar(v) for v in ours]
                err = [[b[0] for b in bars], [b[1] for b in bars]]
                ax.errorbar(
                    xs, [v["mean"] for v in ours], yerr=err, marker="o", capsize=3, color=COLOURS[strategy],
                    label=strategy,
                )  # fmt: skip
                ax.plot(
                    iterations, thesis[condition][strategy], linestyle="--", marker="x",
                    color=COLOURS[strategy], alpha=0.6, label=f"{strategy} (thesis)",
                )  # fmt: skip
            ax.plot(
                iterations, [v["mean"] for v in comprehension[condition]["ceiling"]], color="black",
                linestyle=":", label="instructors' ceiling",
            )  # fmt: skip
            ax.set_title(f"{LABELS[condition]}, queries: {name}", fontsize=9)
            ax.set_xticks(iterations)
            ax.set_ylim(0, 100)
            ax.grid(alpha=0.3)
        row[0].set_ylabel("% of valid orderings known")
    for ax in axes[-1]:
        ax.set_xlabel("demonstrations (iteration)")
    axes[0][0].legend(fontsize=7, loc="lower right")
    figure.suptitle(f"Task comprehension over 12 food tasks (Fig. 2.11), {metrics['trials']} trials")
    return [save_png(figure, directory / COMPREHENSION_PLOT)]
