"""Support-TAMP: Figure 3.5 (makespan) and Figure 3.6 (the lead's planning effort) as grouped bars."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from supportive.experiments.plotting import new_figure, save_png
from supportive.experiments.statistics import error_bar
from supportive.experiments.support_tamp.measure import PAIRINGS, SCENARIOS

__all__ = ["FILES", "plots"]

FILES = {"makespan": "makespan.png", "lead_nodes": "planning.png"}
"""Figure 3.5 (makespan) and Figure 3.6 (search nodes the lead expands)."""

_TITLES = {"makespan": "makespan (s)", "lead_nodes": "lead search nodes"}
_COLOURS = ("tab:grey", "tab:green", "tab:olive")


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``makespan.png`` and ``planning.png`` into ``directory``."""
    return [_bars(metrics, key, directory / name) for key, name in FILES.items()]


def _bars(metrics: Mapping[str, Any], key: str, path: Path) -> Path:
    figure = new_figure(11.0, 4.2)
    axes = figure.subplots(1, len(SCENARIOS), sharey=key == "makespan")
    labels = [p.replace(", ", "\n") for p in PAIRINGS]
    readings = list(metrics["readings"])
    series = [("alone", None), *((f"supported, {r}", r) for r in readings)]
    xs = np.arange(len(labels))
    width = 0.8 / len(series)
    for ax, scenario in zip(np.atleast_1d(axes), SCENARIOS, strict=True):
        for k, (title, reading) in enumerate(series):
            entries = [metrics["scenarios"][scenario][p] for p in PAIRINGS]
            cells = [e["alone"][key] if reading is None else e["supported"][reading][key] for e in entries]
            bars = np.array([error_bar(c) for c in cells]).T
            ax.bar(
                xs + (k - (len(series) - 1) / 2) * width, [c["mean"] for c in cells], width, yerr=bars,
                capsize=3, color=_COLOURS[k % len(_COLOURS)], label=title,
            )  # fmt: skip
        if key == "makespan":
            floors = [metrics["scenarios"][scenario][p]["floor"]["mean"] for p in PAIRINGS]
            ax.scatter(xs, floors, marker="_", s=400, color="black", zorder=3, label="ceiling: perfect staging")
        ax.set_xticks(xs, labels, fontsize=7)
        ax.set_title(f"{scenario} lead", fontsize=9)
        ax.set_ylabel(_TITLES[key])
        ax.grid(axis="y", alpha=0.3)
    np.atleast_1d(axes)[0].legend(fontsize=7)
    figure.suptitle(f"{_TITLES[key]} over {metrics['tables']} random tables, mean and 95 % CI", fontsize=10)
    return save_png(figure, path)
