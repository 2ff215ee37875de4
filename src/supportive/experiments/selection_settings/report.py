"""The selection-settings report: what comparing the readings gains, and the policy chosen."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.selection_settings.measure import (
    CONVENTIONAL,
    DEMONSTRATIONS,
    FOLDS,
    FRESH,
    RECALL_DEMONSTRATIONS,
    SIZES,
    policy_name,
)
from supportive.experiments.statistics import format_ci
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render

__all__ = ["findings", "headline", "plots", "report"]


def report(metrics: Mapping[str, Any]) -> str:
    """Markdown: the gain per number of demonstrations and folds, the shares admitted, every policy's mean
    gain and the chosen one (its prose: ``templates/report.md``)."""
    gains, admitted = metrics["gains"], metrics["admitted"]
    rows = [str(n) for n in DEMONSTRATIONS if str(n) in gains[str(FOLDS[0])]]
    return render(
        __package__,
        "report.md",
        sizes=f"{SIZES[0]}–{SIZES[1]}",
        fresh=str(FRESH),
        tasks=str(gains[str(FOLDS[0])][rows[0]]["n"]) if rows else "0",
        recall_demonstrations=str(RECALL_DEMONSTRATIONS),
        gains=markdown_table(
            ["demonstrations", *(f"{k} folds" for k in FOLDS)],
            [[n, *(format_ci(gains[str(k)][n], signed=True) for k in FOLDS)] for n in rows],
        ),
        admitted=markdown_table(
            ["demonstrations", "general", *(f"auto, {k} folds" for k in FOLDS)],
            [[n, *(f"{admitted[name][n]:.3f}" for name in ("general", *map(str, FOLDS)))] for n in rows],
        ),
        policies=_policies(metrics),
        conventional=f"`{policy_name(*CONVENTIONAL)}`",
        best=f"`{metrics['best']}`" if metrics["best"] else "none qualifies",
        conventional_gap=_conventional_gap(metrics),
        chosen=metrics["chosen"] or "none qualifies",
    )


def _conventional_gap(metrics: Mapping[str, Any]) -> str:
    """How far the conventional policy is behind the best, against one standard error of that difference."""
    row = metrics["policies"][policy_name(*CONVENTIONAL)]
    if metrics["recall"]["general"] is None:
        return (
            f"The recall at {RECALL_DEMONSTRATIONS} demonstrations was not measured (this run learned no `uniform` "
            f"task from {RECALL_DEMONSTRATIONS}), so no policy qualifies."
        )
    if metrics["best"] is None or not row["qualifies"]:
        return "The conventional policy costs recall."
    return f"The conventional policy is {row['gap']:.4f} nats behind it, one standard error {row['error']:.4f}."


def _policies(metrics: Mapping[str, Any]) -> list[str]:
    """One row per threshold, one column per number of folds, and never comparing."""
    policies, chosen = metrics["policies"], metrics["chosen"]

    def cell(name: str) -> str:
        row = policies[name]
        text = f"{row['gain']:+.3f}" + ("" if row["qualifies"] else " ✗")
        return f"**{text}**" if name == chosen else text

    table = [[str(m), *(cell(policy_name(k, m)) for k in FOLDS)] for m in DEMONSTRATIONS]
    table.append(["never", *[cell(policy_name(FOLDS[0], None))] * len(FOLDS)])
    return markdown_table(["compare from", *(f"{k} folds" for k in FOLDS)], table)


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """No plots: the tables say it."""
    return []


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """The chosen policy and its mean gain."""
    chosen = metrics["chosen"]
    if chosen is None:
        return [("selection settings chosen", "none qualifies", "–")]
    return [("selection settings chosen", chosen, f"{metrics['policies'][chosen]['gain']:+.3f} nats per fresh execution")]


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """One row: the chosen policy and its mean gain over keeping ``general``."""
    chosen = metrics["chosen"]
    quantity = "reading selection defaults on generated tasks (issue #23)"
    if chosen is None:
        return [Finding(quantity, "– (not in the thesis)", (("", "none"),), "no policy qualifies")]
    value = f"{chosen}: {metrics['policies'][chosen]['gain']:+.3f} nats per fresh execution"
    verdict = "the best on generated tasks" if chosen == metrics["best"] else "within one standard error of the best"
    return [Finding(quantity, "– (not in the thesis)", (("", value),), verdict)]
