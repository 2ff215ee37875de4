"""Summarising the support-TAMP experiment beside Figures 3.5 and 3.6 of the thesis."""

from __future__ import annotations

import statistics
from collections.abc import Mapping, Sequence
from typing import Any

from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import format_ci, mean_ci
from supportive.experiments.support_tamp.measure import PAIRINGS, SCENARIOS

__all__ = ["CONDITIONS", "THESIS", "headline", "report", "summarize", "timing_summary"]

CONDITIONS = ("alone", "supported")
"""The lead alone, and with the support agent."""

THESIS: dict[str, Any] = {
    "makespan_gain_percent": {  # §3.2.9.3, read off Figure 3.5
        "slow lead, fast support": 44.0,
        "fast lead, fast support": 30.5,
        "slow lead, slow support": 30.5,
        "fast lead, slow support": 9.8,
    },
    "claims": [
        "supportive agents drove average task completion times down universally",
        "a slow lead with a fast support agent performed competitively with a single fast lead",
        "a support agent aware of the lead's heuristic dramatically reduces its planning burden",
    ],
}
"""What the thesis reports: makespan improvements by pairing (equal speed: 30.5 %), and its claims."""


def _gain(alone: Sequence[float], supported: Sequence[float]) -> float:
    return round(100.0 * (1.0 - sum(supported) / sum(alone)), 1) if sum(alone) else 0.0


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Per scenario and pairing: makespan and lead search nodes alone and supported (mean and 95 % CI), the
    makespan gain (of the means, and per table with its CI), support actions, conflicts, completions."""
    out: dict[str, Any] = {"tables": len(results), "scenarios": {}}
    for scenario in SCENARIOS:
        out["scenarios"][scenario] = {}
        for pairing in PAIRINGS:
            runs = [r["scenarios"][scenario][pairing] for r in results]
            entry: dict[str, Any] = {}
            for condition in CONDITIONS:
                outcomes = [run[condition] for run in runs]
                conflicts: dict[str, int] = {}
                for outcome in outcomes:
                    for kind, n in outcome["conflicts"].items():
                        conflicts[kind] = conflicts.get(kind, 0) + n
                entry[condition] = {
                    "makespan": mean_ci([o["makespan"] for o in outcomes], 3),
                    "lead_nodes": mean_ci([o["lead_nodes"] for o in outcomes], 1),
                    "lead_nodes_median": statistics.median(o["lead_nodes"] for o in outcomes),
                    "lead_plans": mean_ci([o["lead_plans"] for o in outcomes], 2),
                    "lead_steps": mean_ci([o["lead_steps"] for o in outcomes], 2),
                    "support_actions": mean_ci([o["support_actions"] for o in outcomes], 2),
                    "completed": sum(o["completed"] for o in outcomes),
                    "conflicts": dict(sorted(conflicts.items())),
                }
            alone = [run["alone"]["makespan"] for run in runs]
            helped = [run["supported"]["makespan"] for run in runs]
            entry["makespan_gain_percent"] = _gain(alone, helped)
            entry["per_table_gain_percent"] = mean_ci(
                [100.0 * (1 - h / a) for a, h in zip(alone, helped, strict=True)], 2
            )
            entry["tables_faster"] = sum(h < a for a, h in zip(alone, helped, strict=True))
            entry["tables_slower"] = sum(h > a for a, h in zip(alone, helped, strict=True))
            nodes_alone = [run["alone"]["lead_nodes"] for run in runs]
            nodes_helped = [run["supported"]["lead_nodes"] for run in runs]
            entry["lead_nodes_change_percent"] = (
                round(100.0 * (sum(nodes_helped) / sum(nodes_alone) - 1.0), 1) if sum(nodes_alone) else 0.0
            )
            out["scenarios"][scenario][pairing] = entry
    for scenario in SCENARIOS:
        fast_alone = out["scenarios"][scenario]["fast lead, fast support"]["alone"]["makespan"]["mean"]
        slow_helped = out["scenarios"][scenario]["slow lead, fast support"]["supported"]["makespan"]["mean"]
        slow_alone = out["scenarios"][scenario]["slow lead, fast support"]["alone"]["makespan"]["mean"]
        out["scenarios"][scenario]["slow lead helped vs fast lead alone"] = {
            "fast_alone": fast_alone,
            "slow_supported": slow_helped,
            "slow_alone": slow_alone,
            "gap_closed_percent": round(100.0 * (slow_alone - slow_helped) / (slow_alone - fast_alone), 1)
            if slow_alone != fast_alone
            else None,
        }
    return out


def timing_summary(timings: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Mean lead planning seconds per run (Figure 3.6's "planning duration") and support planning seconds."""
    out: dict[str, Any] = {}
    for scenario in SCENARIOS:
        out[scenario] = {}
        for pairing in PAIRINGS:
            cells = [t[scenario][pairing] for t in timings]
            out[scenario][pairing] = {
                "lead_planning_seconds_alone": mean_ci(
                    [c["alone"]["lead_planning_seconds"] for c in cells], 5
                ),
                "lead_planning_seconds_supported": mean_ci(
                    [c["supported"]["lead_planning_seconds"] for c in cells], 5
                ),
                "support_planning_seconds": mean_ci(
                    [c["supported"]["support_planning_seconds"] for c in cells], 4
                ),
            }
    return out


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: makespan (Figure 3.5) and the lead's planning effort (Figure 3.6) per scenario and pairing,
    the thesis's gains beside."""
    lines = [
        "# Supportive-behavior TAMP: circuit building with a support robot (§3.2.9, Figures 3.5, 3.6)",
        "",
        f"{metrics['tables']} random tables of the thesis-size task (two cells in series drive an LED on a "
        "switched circuit; 14 pieces, excess wires, a lamp and a resistor). Each table is run with the lead "
        "alone and with the support agent, for each scenario and pairing of speeds (fast 100 %, slow 33 %). "
        "Means with 95 % confidence intervals; the gain is 1 − (mean supported makespan / mean alone).",
    ]
    for scenario in SCENARIOS:
        title = (
            "unpredictable lead, conservative weights"
            if scenario == "unpredictable"
            else ("greedy heuristic lead, aggressive weights")
        )
        lines += [
            "",
            f"## Scenario `{scenario}`: {title}",
            "",
            "| pairing | makespan alone (s) | supported (s) | gain | thesis | faster / slower tables | lead search nodes alone → supported, mean (median) |",
            "|---|---:|---:|---:|---:|---:|---:|",
        ]
        for pairing in PAIRINGS:
            entry = metrics["scenarios"][scenario][pairing]
            lines.append(
                f"| {pairing} | {format_ci(entry['alone']['makespan'], 1)} | "
                f"{format_ci(entry['supported']['makespan'], 1)} | {entry['makespan_gain_percent']:.1f} % | "
                f"{THESIS['makespan_gain_percent'][pairing]:.1f} % | {entry['tables_faster']} / {entry['tables_slower']} | "
                f"{entry['alone']['lead_nodes']['mean']:.0f} ({entry['alone']['lead_nodes_median']:.0f}) → "
                f"{entry['supported']['lead_nodes']['mean']:.0f} ({entry['supported']['lead_nodes_median']:.0f}) |"
            )
        gap = metrics["scenarios"][scenario]["slow lead helped vs fast lead alone"]
        lines += [
            "",
            f"A slow lead with a fast support agent: {gap['slow_supported']:.1f} s, against {gap['slow_alone']:.1f} s "
            f"alone and {gap['fast_alone']:.1f} s for a fast lead alone — "
            f'{gap["gap_closed_percent"]}% of the gap closed (thesis: "competitively with a single fast lead").',
        ]
    lines += ["", "## Verdict", "", *verdict(metrics), ""]
    return "\n".join(lines)


def verdict(metrics: Mapping[str, Any]) -> list[str]:
    """Bullet lines on the thesis's claims, from this run's numbers."""
    lines = []
    for scenario in SCENARIOS:
        entries = metrics["scenarios"][scenario]
        gains = {pairing: entries[pairing]["makespan_gain_percent"] for pairing in PAIRINGS}
        lowered = [p for p, g in gains.items() if g > 0]
        lines.append(
            f"* `{scenario}`: support lowered the mean makespan in {len(lowered)} of {len(gains)} pairings "
            f"({', '.join(f'{p}: {g:+.1f} %' for p, g in gains.items())}); thesis: in every pairing, 44 / 30.5 / 9.8 %."
        )
    heuristic = metrics["scenarios"]["heuristic"]
    lines.append(
        "* The greedy lead's search nodes, alone → supported: "
        + ", ".join(
            f"{p}: {heuristic[p]['alone']['lead_nodes']['mean']:.0f} → "
            f"{heuristic[p]['supported']['lead_nodes']['mean']:.0f} ({heuristic[p]['lead_nodes_change_percent']:+.1f} %)"
            for p in PAIRINGS
        )
        + " (thesis: a support agent aware of the lead's heuristic dramatically reduces its planning burden)."
    )
    return lines


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Makespan gains per scenario and pairing, beside the thesis's."""
    rows: list[HeadlineRow] = []
    for scenario in SCENARIOS:
        for pairing in PAIRINGS:
            entry = metrics["scenarios"][scenario][pairing]
            rows.append(
                (
                    f"{scenario}: {pairing}",
                    f"{entry['makespan_gain_percent']:.1f} % faster",
                    f"{THESIS['makespan_gain_percent'][pairing]:.1f} %",
                )
            )
    return rows
