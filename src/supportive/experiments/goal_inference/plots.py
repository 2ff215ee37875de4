"""Goal inference: the plots (PNG, matplotlib Agg), and the timing files the harness asks for
(:func:`timing_report`)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.goal_inference.report import LABELS, timing_markdown
from supportive.experiments.goal_inference.summary import LEVELS
from supportive.experiments.goal_inference.thesis import THESIS
from supportive.experiments.goal_inference.timing import MODELS, TIMING_PLOT, TIMING_REPORT, timing_summary
from supportive.experiments.output import write_text
from supportive.experiments.plotting import new_figure, save_png
from supportive.experiments.statistics import error_bar

__all__ = ["ACCURACY_PLOT", "plots", "timing_report"]

ACCURACY_PLOT = "accuracy.png"
"""Accuracy vs overlap, flat vs hierarchical, clean and noisy, subgoal and subtask."""

_COLOURS = {"flat": "tab:red", "hierarchical": "tab:blue"}
_LINES = {"clean": "-", "noisy": "--"}


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``accuracy.png`` into ``directory``; return the paths written."""
    return [_accuracy(metrics, directory / ACCURACY_PLOT)]


def timing_report(timings: list[dict[str, Any]], directory: Path) -> list[Path]:
    """The experiment's ``timing_report``: from the trials' ``timing`` entries (as in ``timing.json``, in trial
    order), write ``timing.md`` (:func:`~.report.timing_markdown`) and ``timing.png`` into ``directory``;
    return the paths written. Not deterministic."""
    document = timing_summary(timings)
    return [
        write_text(directory / TIMING_REPORT, timing_markdown(document)),
        _timing(document, directory / TIMING_PLOT),
    ]


def _accuracy(metrics: Mapping[str, Any], path: Path) -> Path:
    figure = new_figure(11.0, 4.5)
    axes = figure.subplots(1, 2, sharey=True)
    for ax, level in zip(axes, LEVELS, strict=True):
        for noise in sorted({s["noise"] for s in metrics["settings"]}):
            settings = sorted(
                (s for s in metrics["settings"] if s["noise"] == noise), key=lambda s: s["overlap"]
            )
            xs = [s["overlap"] for s in settings]
            for model in MODELS:
                cells = [metrics["accuracy"][s["key"]][model][level] for s in settings]
                ys = [c["mean"] for c in cells]
                bars = [error_bar(c) for c in cells]
                below, above = [b[0] for b in bars], [b[1] for b in bars]
                shift = -0.008 if model == "flat" else 0.008
                ax.errorbar(
                    [x + shift for x in xs],
                    ys,
                    yerr=[below, above],
                    color=_COLOURS[model],
                    linestyle=_LINES[noise],
                    marker="o",
                    capsize=3,
                    label=f"{LABELS[model]}, {noise}",
                )
        ax.set_title(f"true {level} ranked first")
        ax.set_xlabel("observation overlap")
        ax.set_xticks(sorted({s["overlap"] for s in metrics["settings"]}))
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("share of steps (mean over trials, 95% CI)")
    axes[0].legend(fontsize=8, loc="lower left")
    figure.suptitle(
        f"Goal-inference accuracy vs observation overlap, {metrics['trials']} trials, seed {metrics['seed']}"
    )
    return save_png(figure, path)


def _plain_ticks(ax: Any) -> None:
    """Log axes labelled 10, 20, 50, 100, … rather than 10^1, 2×10^1 (minor ticks labelled when few)."""
    from matplotlib.ticker import FuncFormatter, LogFormatter

    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
        axis.set_minor_formatter(LogFormatter(labelOnlyBase=False, minor_thresholds=(1.5, 0.5)))


def _timing(document: Mapping[str, Any], path: Path) -> Path:
    figure = new_figure(11.0, 4.5)
    left, right = figure.subplots(1, 2)
    bound_us = THESIS["update_seconds_bound"] * 1e6
    sizes = [row["subgoals"] for row in document["sizes"]]
    for model in MODELS:
        colour = _COLOURS[model]
        left.scatter(
            [t["subgoals"] for t in document["trials"]],
            [t[model]["median_us"] for t in document["trials"]],
            s=14,
            color=colour,
            alpha=0.4,
        )
        left.plot(
            sizes,
            [row[model]["median_us"] for row in document["sizes"]],
            color=colour,
            marker="o",
            label=f"{LABELS[model]} (median over trials)",
        )
        right.plot(
            sizes,
            [_mean_entries(document["trials"], size, model) for size in sizes],
            color=colour,
            marker="o",
            label=LABELS[model],
        )
    left.set_ylabel("time per update (µs), median over the steps")
    left.set_title(
        f"Per-update time ({', '.join(document['cpus'])}, 1 thread)\nthesis: CC-HTN faster than 1 Hz "
        f"(under {bound_us:,.0f} µs) in most cases, i7-3930K",
        fontsize=9,
    )
    right.set_ylabel("entries one update multiplies with")
    right.set_title("Work per update (deterministic)")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_yscale("log")
        _plain_ticks(ax)
        ax.set_xlabel("subgoals")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="upper left")
    figure.suptitle(
        f"Goal inference: flat vs hierarchical HMM (thesis Figure 2.4), {len(document['trials'])} trials"
    )
    return save_png(figure, path)


def _mean_entries(trials: list[Mapping[str, Any]], size: int, model: str) -> float:
    entries = [float(t["operator_entries"][model]) for t in trials if int(t["subgoals"]) == size]
    return sum(entries) / len(entries)
