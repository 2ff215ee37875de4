"""Edge reduction: the plots (PNG, matplotlib Agg)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.edge_reduction.report import LABELS
from supportive.experiments.plotting import new_figure, save_png

__all__ = ["DEPTH_PLOT", "EDGES_PLOT", "plots"]

EDGES_PLOT = "edges.png"
"""Edges vs subgoals: flat model vs CC-HTN, learned and ground truth."""
DEPTH_PLOT = "depth.png"
"""Mean primitive depth vs subgoals, with the thesis's range."""


def _points(metrics: Mapping[str, Any], model: str, key: str) -> tuple[list[int], list[float]]:
    tasks = [t for t in metrics["tasks"] if t[model] is not None]
    return [t["subgoals"] for t in tasks], [t[model][key] for t in tasks]


def _bin_means(metrics: Mapping[str, Any], model: str, key: str) -> tuple[list[float], list[float]]:
    bins = [b for b in metrics["bins"] if b[model] is not None]
    return [(b["low"] + b["high"]) / 2 for b in bins], [b[model][key] for b in bins]


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``edges.png`` and ``depth.png`` into ``directory`` and return their paths."""
    return [_edges(metrics, directory / EDGES_PLOT), _depths(metrics, directory / DEPTH_PLOT)]


def _edges(metrics: Mapping[str, Any], path: Path) -> Path:
    figure = new_figure(11.0, 4.5)
    axes = figure.subplots(1, 2, sharey=True)
    for ax, model in zip(axes, ("learned", "ground_truth"), strict=True):
        for key, colour, label in (
            ("flat_edges", "tab:red", "flat model"),
            ("htn_edges", "tab:blue", "CC-HTN"),
        ):
            xs, ys = _points(metrics, model, key)
            ax.scatter(xs, ys, s=14, color=colour, alpha=0.45, label=f"{label} (per task)")
            bx, by = _bin_means(metrics, model, key)
            ax.plot(bx, by, color=colour, marker="o", linewidth=2, label=f"{label} (mean per 10 subgoals)")
        ax.set_title(LABELS[model])
        ax.set_xlabel("subgoals")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("edges")
    axes[0].legend(fontsize=8, loc="upper left")
    figure.suptitle(f"Edges vs subgoal count ({metrics['reference']}), seed {metrics['seed']}")
    return save_png(figure, path)


def _depths(metrics: Mapping[str, Any], path: Path) -> Path:
    figure = new_figure(7.0, 4.5)
    ax = figure.subplots()
    thesis = metrics["thesis"]["mean_action_depth"]
    ax.axhspan(thesis["min"], thesis["max"], color="tab:green", alpha=0.12, label="thesis: range 1.99–3.61")
    ax.axhline(thesis["mean"], color="tab:green", linewidth=1.5, label=f"thesis: mean {thesis['mean']:.2f}")
    for model, colour in (("learned", "tab:orange"), ("ground_truth", "tab:purple")):
        xs, ys = _points(metrics, model, "depth")
        ax.scatter(xs, ys, s=16, color=colour, alpha=0.7, label=LABELS[model])
    ax.set_xlabel("subgoals")
    ax.set_ylabel("mean depth of a primitive")
    ax.set_title("Primitive depth per task")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return save_png(figure, path)
