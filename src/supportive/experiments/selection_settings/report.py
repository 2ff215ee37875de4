"""The selection-settings report: what comparing the readings gains, and the policy chosen."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from supportive.evaluation.mistakes import shown
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.selection_settings.evidence import CONVENTIONAL_EVIDENCE, LEVELS
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
        **_subtasks(metrics["subtasks"]),
        **_evidence(metrics["evidence"]),
    )


def _subtasks(subtasks: Mapping[str, Any]) -> dict[str, object]:
    """The template's fields on ``subtask_demonstrations``: what making subtasks gains per number of
    demonstrations, every threshold's mean gain, and the one chosen."""
    gains, admitted, rows = subtasks["gains"], subtasks["admitted"], subtasks["thresholds"]
    present = [str(n) for n in DEMONSTRATIONS if str(n) in gains]

    def threshold(k: str) -> list[str]:
        row = rows[k]
        gain = f"{row['gain']:+.3f}" + ("" if row["qualifies"] else " ✗")
        return [f"**{k}**" if int(k) == subtasks["chosen"] else k, gain, f"{row['gap']:.3f}", f"{row['error']:.3f}"]

    return {
        "subtask_gains": markdown_table(
            ["demonstrations", "gain of making subtasks", *(f"… people {who}" for who in PEOPLE_NAMES.values()),
             "admitted, subtasks", "admitted, none"],
            [
                [
                    n, format_ci(gains[n], signed=True), *(_mean_of(gains[n], who) for who in PEOPLE_NAMES),
                    f"{admitted[n]['made']:.3f}", f"{admitted[n]['none']:.3f}",
                ]
                for n in present
            ],
        ),
        "thresholds": markdown_table(
            ["subtask_demonstrations", "mean gain", "behind the best", "standard error"],
            [threshold(str(k)) for k in DEMONSTRATIONS if str(k) in rows],
        ),
        "subtask_best": str(subtasks["best"]) if subtasks["best"] is not None else "none qualifies",
        "subtask_chosen": str(subtasks["chosen"]) if subtasks["chosen"] is not None else "none qualifies",
    }


PEOPLE_NAMES = {"uniform": "without habits", "habits": "with habits"}
"""How the report names each of :data:`~supportive.generate.habits.PEOPLE`."""


def _mean_of(row: Mapping[str, Any], people: str) -> str:
    """A row's mean gain over the tasks by ``people`` (– where the run had none)."""
    return shown(row["people"].get(people), "+.3f")


def _evidence(evidence: Mapping[str, Any]) -> dict[str, object]:
    """The template's fields on ``evidence``: each level's gain over the conventional one per number of
    demonstrations, every level's mean gain and recall, and the level chosen."""
    gains, rows = evidence["gains"], evidence["levels"]
    present = [str(n) for n in DEMONSTRATIONS if str(n) in gains[str(CONVENTIONAL_EVIDENCE)]]

    def level(value: float) -> list[str]:
        row = rows[str(value)]
        gain = f"{row['gain']:+.3f}" + ("" if row["qualifies"] else " ✗")
        recall = shown(row["recall"])
        name = f"**{value}**" if value == evidence["chosen"] else str(value)
        return [name, gain, recall, f"{row['gap']:.3f}", f"{row['error']:.3f}"]

    return {
        "evidence_gains": markdown_table(
            ["demonstrations", *(f"evidence={value}" for value in LEVELS)],
            [[n, *(format_ci(gains[str(value)][n], signed=True) for value in LEVELS)] for n in present],
        ),
        "evidence_levels": markdown_table(
            ["evidence", "mean gain", f"admitted, uniform, {RECALL_DEMONSTRATIONS} demonstrations", "behind the best", "standard error"],
            [level(value) for value in LEVELS],
        ),
        "evidence_conventional": str(CONVENTIONAL_EVIDENCE),
        "evidence_best": str(evidence["best"]) if evidence["best"] is not None else "none qualifies",
        "evidence_chosen": str(evidence["chosen"]) if evidence["chosen"] is not None else "none qualifies",
    }


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
    if metrics["best"] == policy_name(*CONVENTIONAL):
        return "It is the conventional policy."
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
    """The chosen policy, threshold and evidence level, and their mean gains."""
    chosen, subtasks = metrics["chosen"], metrics["subtasks"]
    rows: list[HeadlineRow] = [
        ("selection settings chosen", chosen, f"{metrics['policies'][chosen]['gain']:+.3f} nats per fresh execution")
        if chosen is not None
        else ("selection settings chosen", "none qualifies", "–")
    ]
    threshold = subtasks["chosen"]
    if threshold is None:
        rows.append(("subtask_demonstrations chosen", "none qualifies", "–"))
    else:
        gain = subtasks["thresholds"][str(threshold)]["gain"]
        rows.append(("subtask_demonstrations chosen", str(threshold), f"{gain:+.3f} nats per fresh execution"))
    level = metrics["evidence"]["chosen"]
    if level is None:
        rows.append(("evidence chosen", "none qualifies", "–"))
    else:
        gain = metrics["evidence"]["levels"][str(level)]["gain"]
        rows.append(("evidence chosen", str(level), f"{gain:+.3f} nats per fresh execution over {CONVENTIONAL_EVIDENCE}"))
    return rows


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """Three rows: the chosen policy and its mean gain over keeping ``general``; the chosen
    ``subtask_demonstrations`` and its mean gain over making no subtasks; the chosen ``evidence`` and its mean
    gain over the conventional level."""
    subtasks, evidence = metrics["subtasks"], metrics["evidence"]
    return [
        _choice(
            "reading selection defaults on generated tasks (issue #23)", "policy", metrics["chosen"], metrics["best"],
            lambda chosen: f"{chosen}: {metrics['policies'][chosen]['gain']:+.3f} nats per fresh execution",
        ),
        _choice(
            "subtask_demonstrations on generated tasks (issue #23)", "threshold", subtasks["chosen"], subtasks["best"],
            lambda chosen: f"subtask_demonstrations={chosen}: "
            f"{subtasks['thresholds'][str(chosen)]['gain']:+.3f} nats per fresh execution",
        ),
        _choice(
            "evidence level on generated tasks (issue #23)", "level", evidence["chosen"], evidence["best"],
            lambda chosen: f"evidence={chosen}: {evidence['levels'][str(chosen)]['gain']:+.3f} nats per fresh "
            f"execution over {CONVENTIONAL_EVIDENCE}",
        ),
    ]


def _choice(quantity: str, what: str, chosen: Any, best: Any, value: Callable[[Any], str]) -> Finding:
    """A finding on one setting the procedure chose: ``value`` of the choice, and whether it is the best on
    the generated tasks or within one standard error of it (or that no ``what`` qualified)."""
    if chosen is None:
        return Finding(quantity, "– (not in the thesis)", (("", "none"),), f"no {what} qualifies")
    verdict = "the best on generated tasks" if chosen == best else "within one standard error of the best"
    return Finding(quantity, "– (not in the thesis)", (("", value(chosen)),), verdict)
