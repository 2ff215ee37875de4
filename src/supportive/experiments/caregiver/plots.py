"""Caregiver: Figures 3.14–3.16 as grouped bars (mean ± one standard deviation), with the thesis's means."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from supportive.envs.household.novice import NOVICE_TYPES
from supportive.experiments.caregiver.measure import CONDITIONS
from supportive.experiments.caregiver.report import MEASURES, THESIS
from supportive.experiments.plotting import new_figure, save_png

__all__ = ["FILES", "plots"]

FILES = {
    "damage_normalized": "damage.png",
    "steps_until_threshold": "steps.png",
    "cells_explored": "coverage.png",
}
"""One PNG per measure: Figure 3.14 (damage), 3.15 (steps), 3.16 (coverage)."""

_COLOURS = {"without": "tab:red", "with": "tab:blue"}
_LABELS = {"without": "no caregiver", "with": "with caregiver"}


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """Write ``damage.png``, ``steps.png`` and ``coverage.png`` into ``directory``."""
    return [_bars(metrics, key, directory / name) for key, name in FILES.items()]


def _bars(metrics: Mapping[str, Any], key: str, path: Path) -> Path:
    figure = new_figure(8.0, 4.5)
    ax = figure.subplots()
    labels = list(NOVICE_TYPES)
    xs = np.arange(len(labels))
    width = 0.38
    for k, condition in enumerate(CONDITIONS):
        values = [metrics["measures"][key][label][condition] for label in labels]
        offset = (k - 0.5) * width
        ax.bar(xs + offset, [v["mean"] for v in values], width, yerr=[v["sd"] for v in values], capsize=3,
               color=_COLOURS[condition], alpha=0.8, label=_LABELS[condition])
        ax.scatter(xs + offset, [THESIS[key][label][k] for label in labels], marker="_", s=300, color="black",
                   zorder=3, label="thesis" if k == 0 else None)
    ax.set_xticks(xs, labels, fontsize=8)
    ax.set_ylabel(MEASURES[key].split(" (")[0].lower())
    ax.set_title(f"{MEASURES[key]}: {metrics['episodes']} episodes per type, mean ± sd; black: the thesis")
    ax.legend(fontsize=8)
    ax.grid(axis="y", alpha=0.3)
    return save_png(figure, path)
