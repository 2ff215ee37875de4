"""Summarising the caregiver experiment beside Tables 3.1–3.3 of the thesis, every reading side by side."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.experiments.caregiver.measure import MEMORIES, READINGS
from supportive.experiments.readings import Finding, readings_table
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import format_ci, format_sd, mean_sd, ratio_ci
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render
from supportive.worlds.household.novice import NOVICE_TYPES

__all__ = ["MEASURES", "THESIS", "findings", "headline", "report", "summarize", "thesis_reduction", "verdict"]

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

_KEYS = {"damage_normalized": "damage", "steps_until_threshold": "steps", "cells_explored": "cells"}
_DIGITS = {"damage_normalized": 4, "steps_until_threshold": 2, "cells_explored": 2}


def thesis_reduction(label: str) -> float:
    """The damage reduction Table 3.1 implies for a novice type, %."""
    without, with_ = THESIS["damage_normalized"][label]
    return float(100.0 * (without - with_) / without)


def _readings(metrics: Mapping[str, Any]) -> list[str]:
    return list(metrics["readings"])


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Mean and standard deviation of each measure per novice type, without the caregiver and with it under
    each reading; damage normalised by the largest damage of any one episode of the run (any type,
    condition or reading), as in Figure 3.14; the damage reduction with its 95% CI (ratio of paired means,
    delta method)."""
    readings = list(results[0]["novices"][next(iter(NOVICE_TYPES))]["with"])
    episodes_of: dict[str, dict[str, Any]] = {
        label: {
            "without": [r["novices"][label]["without"] for r in results],
            "with": {name: [r["novices"][label]["with"][name] for r in results] for name in readings},
        }
        for label in NOVICE_TYPES
    }
    every = [
        e
        for label in NOVICE_TYPES
        for e in (*episodes_of[label]["without"], *(x for n in readings for x in episodes_of[label]["with"][n]))
    ]
    most = max(e["damage"] for e in every)
    scale = most or 1
    measures: dict[str, Any] = {key: {} for key in MEASURES}
    reduction: dict[str, Any] = {}
    completed: dict[str, Any] = {}
    collisions: dict[str, Any] = {}
    for label in NOVICE_TYPES:
        without, with_ = episodes_of[label]["without"], episodes_of[label]["with"]
        for key, field in _KEYS.items():
            factor = scale if key == "damage_normalized" else 1
            measures[key][label] = {
                "without": mean_sd([e[field] / factor for e in without], _DIGITS[key]),
                "with": {
                    name: mean_sd([e[field] / factor for e in with_[name]], _DIGITS[key]) for name in readings
                },
            }
        reduction[label] = {}
        for name in readings:
            ratio = ratio_ci([e["damage"] for e in with_[name]], [e["damage"] for e in without], 6)
            reduction[label][name] = (
                {"percent": None, "low": None, "high": None}
                if ratio["mean"] is None
                else {
                    "percent": round(100.0 * (1.0 - ratio["mean"]), 1),
                    "low": None if ratio["high"] is None else round(100.0 * (1.0 - ratio["high"]), 1),
                    "high": None if ratio["low"] is None else round(100.0 * (1.0 - ratio["low"]), 1),
                }
            )
        completed[label] = {
            "without": sum(not e["reached_threshold"] for e in without),
            "with": {name: sum(not e["reached_threshold"] for e in with_[name]) for name in readings},
        }
        collisions[label] = {
            "without": _collisions(without),
            "with": {name: _collisions(with_[name]) for name in readings},
        }
    return {
        "map": results[0]["map"],
        "episodes": len(results),
        "max_damage": most,
        "memory": {name: MEMORIES[name] for name in readings},
        "novice_types": {label: epsilon for label, epsilon in NOVICE_TYPES.items()},
        "measures": measures,
        "damage_reduction_percent": reduction,
        "episodes_completed": completed,
        "collisions": collisions,
    }


def _collisions(episodes: Sequence[Mapping[str, Any]]) -> dict[str, int]:
    counts: dict[str, int] = {}
    for e in episodes:
        for kind, n in e["collisions"].items():
            counts[kind] = counts.get(kind, 0) + n
    return dict(sorted(counts.items()))


def _reduction_text(entry: Mapping[str, Any]) -> str:
    return format_ci({"mean": entry["percent"], "low": entry["low"], "high": entry["high"]}, 0) + " %"


def _reduction_verdict(metrics: Mapping[str, Any], label: str) -> str:
    readings = _readings(metrics)
    theirs = thesis_reduction(label)

    def holds(name: str) -> bool:
        entry = metrics["damage_reduction_percent"][label][name]
        return entry["low"] is not None and entry["low"] <= theirs <= entry["high"]

    default = metrics["damage_reduction_percent"][label][readings[0]]
    if holds(readings[0]):
        return "reproduced (the thesis's value within the 95% CI)"
    others = [name for name in readings[1:] if holds(name)]
    side = "below" if (default["percent"] or 0) < theirs else "above"
    tail = f"; within the CI under {', '.join(others)}" if others else ""
    return f"not reproduced: default {side} the thesis{tail}"


def verdict(metrics: Mapping[str, Any]) -> list[str]:
    """Bullet lines on the thesis's trends, from this run's numbers, per reading."""
    labels = list(NOVICE_TYPES)
    steps = metrics["measures"]["steps_until_threshold"]
    cells = metrics["measures"]["cells_explored"]
    out = []
    for name in _readings(metrics):
        reduction = {label: metrics["damage_reduction_percent"][label][name] for label in labels}
        over = [label for label in labels if (reduction[label]["percent"] or 0) > 66]
        longer = [label for label in labels if steps[label]["with"][name]["mean"] >= steps[label]["without"]["mean"]]
        wider = [label for label in labels if cells[label]["with"][name]["mean"] > cells[label]["without"]["mean"]]
        out += [
            f"* `{name}`: damage falls by more than 66 % for {len(over)} of {len(labels)} novice types "
            f"({', '.join(f'{label} {_reduction_text(reduction[label])}' for label in labels)}; thesis: "
            f"{', '.join(f'{thesis_reduction(label):.0f} %' for label in labels)}, \"generally … by over 66%\"); "
            f"steps until the threshold rise or stay at the maximum for {len(longer)} of {len(labels)} types; "
            f"coverage rises for {len(wider)} of {len(labels)}"
            + (f" (not: {', '.join(x for x in labels if x not in wider)})" if len(wider) < len(labels) else "")
            + " (thesis: for all but the 5 %-random novice).",
        ]
    return out


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: each measure per novice type without the caregiver and with it under every reading (mean ±
    sd), the thesis beside; damage reductions with 95% CIs (the prose: ``templates/report.md``)."""
    readings = _readings(metrics)
    return render(
        __package__,
        "report.md",
        metrics,
        steps=THESIS["steps"],
        thesis_episodes=THESIS["episodes"],
        threshold=THESIS["threshold"],
        readings_table=readings_table(
            READINGS, readings, "P(safe | τ)", ("memory γ", {n: f"{metrics['memory'][n]:g}" for n in readings})
        ),
        measures="\n\n".join(
            "\n".join([f"## {title}", "", *_measure_table(metrics, key)]) for key, title in MEASURES.items()
        ),
        reduction_table=_reduction_table(metrics),
        verdict=verdict(metrics),
    )


def _measure_table(metrics: Mapping[str, Any], key: str) -> list[str]:
    """One measure per novice type: without the caregiver and with it under each reading, the thesis beside."""
    readings = _readings(metrics)
    digits = _DIGITS[key]
    rows = []
    for label in NOVICE_TYPES:
        ours = metrics["measures"][key][label]
        theirs = THESIS[key][label]
        with_cells = [format_sd(ours["with"][name], digits) for name in readings]
        rows.append([label, format_sd(ours["without"], digits), f"{theirs[0]}", *with_cells, f"{theirs[1]}"])
    header = ["novice", "no caregiver", "thesis", *(f"with, `{name}`" for name in readings), "thesis, with"]
    return markdown_table(header, rows)


def _reduction_table(metrics: Mapping[str, Any]) -> list[str]:
    """Damage reduction per novice type and reading, and the episodes that never reached the threshold."""
    readings = _readings(metrics)
    rows = []
    for label in NOVICE_TYPES:
        done = metrics["episodes_completed"][label]
        rows.append(
            [
                label,
                *(_reduction_text(metrics["damage_reduction_percent"][label][name]) for name in readings),
                f"{thesis_reduction(label):.0f} %",
                f"{done['without']} / " + " / ".join(str(done["with"][name]) for name in readings),
            ]
        )
    header = [
        "novice",
        *(f"reduction, `{name}`" for name in readings),
        "thesis",
        "episodes not reaching the threshold: none / " + " / ".join(readings),
    ]
    return markdown_table(header, rows)


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """One row per novice type: the damage reduction under each reading, beside Table 3.1's."""
    return [
        Finding(
            f"damage reduction, {label} novice",
            f"{thesis_reduction(label):.0f} %",
            tuple(
                (name, _reduction_text(metrics["damage_reduction_percent"][label][name]))
                for name in _readings(metrics)
            ),
            _reduction_verdict(metrics, label),
        )
        for label in NOVICE_TYPES
    ]


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Per novice type: the damage reduction under each reading, beside Table 3.1's."""
    return [
        (
            f"{label}: damage reduction",
            " · ".join(
                f"{name} {metrics['damage_reduction_percent'][label][name]['percent']:.0f} %"
                for name in _readings(metrics)
                if metrics["damage_reduction_percent"][label][name]["percent"] is not None
            ),
            f"{thesis_reduction(label):.0f} %",
        )
        for label in NOVICE_TYPES
    ]
