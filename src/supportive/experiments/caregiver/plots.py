"""Caregiver: Figures 3.14–3.16 as grouped bars (mean ± one standard deviation), with the thesis's means."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from supportive.experiments.caregiver.report import MEASURES, THESIS
from supportive.experiments.plotting import new_figure, save_png
from supportive.worlds.household.novice import NOVICE_TYPES

__all__ = ["FILES", "plots"]

FILES = {
    "damage_normalized": "damage.png",
    "steps_until_threshold": "steps.png",
    "cells_explored": "coverage.png",
}
"""One PNG per measure: Figure 3.14 (damage), 3.15 (steps), 3.16 (coverage)."""

_COLOURS = ("tab:red", "tab:blue", "tab:cyan", "tab:purple")


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``damage.png``, ``steps.png`` and ``coverage.png`` into ``directory``."""
    return [_bars(metrics, key, directory / name) for key, name in FILES.items()]


def _bars(metrics: Mapping[str, Any], key: str, path: Path) -> Path:
    figure = new_figure(9.0, 4.5)
    ax = figure.subplots()
    labels = list(NOVICE_TYPES)
    readings = list(metrics["readings"])
    series = [("no caregiver", None), *((f"with, {name}", name) for name in readings)]
    xs = np.arange(len(labels))
    width = 0.8 / len(series)
    for k, (title, name) in enumerate(series):
        cells = metrics["measures"][key]
        values = [cells[label]["without"] if name is None else cells[label]["with"][name] for label in labels]
        offset = (k - (len(series) - 1) / 2) * width
        ax.bar(
            xs + offset, [v["mean"] for v in values], width, yerr=[v["sd"] for v in values], capsize=2,
            color=_COLOURS[k % len(_COLOURS)], alpha=0.8, label=title,
        )  # fmt: skip
    for k, offset in enumerate((-0.4 + width / 2, 0.4 - width / 2)):  # beside "no caregiver", the last "with"
        ax.scatter(
            xs + offset, [THESIS[key][label][k] for label in labels],
            marker="_", s=300, color="black", zorder=3, label="thesis (without, with)" if k == 0 else None,
        )  # fmt: skip
    ax.set_xticks(xs, labels, fontsize=8)
    ax.set_ylabel(MEASURES[key].split(" (")[0].lower())
    ax.set_title(f"{MEASURES[key]}: {metrics['episodes']} episodes per type, mean ± sd; black: the thesis", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(axis="y", alpha=0.3)
    return save_png(figure, path)
