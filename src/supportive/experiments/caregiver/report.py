"""Summarising the caregiver experiment beside Tables 3.1–3.3 of the thesis."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.envs.household.novice import NOVICE_TYPES
from supportive.experiments.caregiver.measure import CONDITIONS
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import format_sd, mean_sd

__all__ = ["MEASURES", "THESIS", "headline", "report", "summarize", "verdict"]

THESIS: dict[str, Any] = {
    "episodes": 20,
    "steps": 200,
    "threshold": 15,
    "damage_normalized": {  # Table 3.1
        "random motion": [0.7346, 0.2291],
        "75% random": [0.5295, 0.1438],
        "50% random": [0.2846, 0.1106],
        "25% random": [0.1887, 0.0466],
        "5% random": [0.0565, 0.0072],
    },
    "steps_until_threshold": {  # Table 3.2
        "random motion": [35.5, 97.05],
        "75% random": [41.05, 164.2],
        "50% random": [89.5, 171.5],
        "25% random": [107.7, 200.0],
        "5% random": [195.75, 200.0],
    },
    "cells_explored": {  # Table 3.3
        "random motion": [14.6, 24.45],
        "75% random": [16.85, 36.45],
        "50% random": [29.75, 38.45],
        "25% random": [34.1, 38.7],
        "5% random": [34.7, 33.2],
    },
    "claim": "the caregiver generally reduces incurred damage by over 66%",
}
"""The thesis's Tables 3.1–3.3: [without, with] the caregiver, per novice type."""

MEASURES = {
    "damage_normalized": "Mean normalised damage (Table 3.1)",
    "steps_until_threshold": "Steps until the damage threshold (Table 3.2)",
    "cells_explored": "Cells explored before the threshold (Table 3.3)",
}
"""The three measures, as the report titles them."""


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Mean and standard deviation of each measure per novice type and condition; damage normalised by the
    largest damage of any one episode (any type, either condition), as in Figure 3.14."""
    most = max(
        r["novices"][label][condition]["damage"] for r in results for label in NOVICE_TYPES for condition in CONDITIONS
    )
    scale = most or 1
    measures: dict[str, Any] = {key: {} for key in MEASURES}
    reduction: dict[str, Any] = {}
    completed: dict[str, Any] = {}
    for label in NOVICE_TYPES:
        episodes = {c: [r["novices"][label][c] for r in results] for c in CONDITIONS}
        measures["damage_normalized"][label] = {
            c: mean_sd([e["damage"] / scale for e in episodes[c]], 4) for c in CONDITIONS
        }
        measures["steps_until_threshold"][label] = {c: mean_sd([e["steps"] for e in episodes[c]], 2) for c in CONDITIONS}
        measures["cells_explored"][label] = {c: mean_sd([e["cells"] for e in episodes[c]], 2) for c in CONDITIONS}
        without = sum(e["damage"] for e in episodes["without"])
        with_ = sum(e["damage"] for e in episodes["with"])
        reduction[label] = round(100.0 * (without - with_) / without, 1) if without else None
        completed[label] = {c: sum(not e["reached_threshold"] for e in episodes[c]) for c in CONDITIONS}
    collisions: dict[str, Any] = {}
    for label in NOVICE_TYPES:
        collisions[label] = {}
        for c in CONDITIONS:
            counts: dict[str, int] = {}
            for r in results:
                for kind, n in r["novices"][label][c]["collisions"].items():
                    counts[kind] = counts.get(kind, 0) + n
            collisions[label][c] = dict(sorted(counts.items()))
    return {
        "map": results[0]["map"],
        "episodes": len(results),
        "max_damage": most,
        "novice_types": {label: epsilon for label, epsilon in NOVICE_TYPES.items()},
        "measures": measures,
        "damage_reduction_percent": reduction,
        "episodes_completed": completed,
        "collisions": collisions,
    }


def verdict(metrics: Mapping[str, Any]) -> list[str]:
    """Bullet lines on the thesis's trends, from this run's numbers."""
    labels = list(NOVICE_TYPES)
    reduction = metrics["damage_reduction_percent"]
    over_half = [label for label in labels if (reduction[label] or 0) > 50]
    steps = metrics["measures"]["steps_until_threshold"]
    cells = metrics["measures"]["cells_explored"]
    longer = [label for label in labels if steps[label]["with"]["mean"] >= steps[label]["without"]["mean"]]
    wider = [label for label in labels if cells[label]["with"]["mean"] > cells[label]["without"]["mean"]]
    return [
        f"* Damage falls by more than half with the caregiver for {len(over_half)} of {len(labels)} novice types "
        f"({', '.join(f'{label} {reduction[label]:.0f} %' for label in labels if reduction[label] is not None)}; "
        "thesis: 61–87 %, \"generally … by over 66%\").",
        f"* Steps until the threshold rise or stay at the maximum for {len(longer)} of {len(labels)} types.",
        f"* Coverage rises for {len(wider)} of {len(labels)} types"
        + (f" (not: {', '.join(x for x in labels if x not in wider)})" if len(wider) < len(labels) else "")
        + "; thesis: for all but the 5 %-random novice.",
    ]


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: each measure per novice type with and without the caregiver (mean ± sd), the thesis beside."""
    lines = [
        "# Caregiver: keeping a novice safe while it explores (§3.5, Tables 3.1–3.3)",
        "",
        f"Map `{metrics['map']}`; {metrics['episodes']} episodes of {THESIS['steps']} steps per novice type and "
        f"condition (the same seed with and without the caregiver); critical damage {THESIS['threshold']}. "
        f"Damage is normalised by the largest damage of one episode in this run ({metrics['max_damage']}). "
        "Mean ± standard deviation over episodes (the thesis's error bars), the thesis's mean beside.",
    ]
    for key, title in MEASURES.items():
        digits = 4 if key == "damage_normalized" else 2
        lines += [
            "",
            f"## {title}",
            "",
            "| novice | no caregiver | thesis | with caregiver | thesis |",
            "|---|---:|---:|---:|---:|",
        ]
        for label in NOVICE_TYPES:
            ours = metrics["measures"][key][label]
            theirs = THESIS[key][label]
            lines.append(
                f"| {label} | {format_sd(ours['without'], digits)} | {theirs[0]} | "
                f"{format_sd(ours['with'], digits)} | {theirs[1]} |"
            )
    lines += [
        "",
        "## Damage reduction and completed episodes",
        "",
        "| novice | damage reduction | thesis | episodes without reaching the threshold (no caregiver / with) |",
        "|---|---:|---:|---:|",
    ]
    for label in NOVICE_TYPES:
        theirs = THESIS["damage_normalized"][label]
        thesis_reduction = 100.0 * (theirs[0] - theirs[1]) / theirs[0]
        done = metrics["episodes_completed"][label]
        lines.append(
            f"| {label} | {metrics['damage_reduction_percent'][label]} % | {thesis_reduction:.0f} % | "
            f"{done['without']} / {done['with']} |"
        )
    lines += ["", "## Verdict", "", *verdict(metrics), ""]
    return "\n".join(lines)


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Per novice type: normalised damage without → with the caregiver, beside Table 3.1."""
    rows: list[HeadlineRow] = []
    for label in NOVICE_TYPES:
        ours = metrics["measures"]["damage_normalized"][label]
        theirs = THESIS["damage_normalized"][label]
        rows.append(
            (
                f"{label}: damage without → with",
                f"{ours['without']['mean']:.3f} → {ours['with']['mean']:.3f}",
                f"{theirs[0]:.3f} → {theirs[1]:.3f}",
            )
        )
    return rows
