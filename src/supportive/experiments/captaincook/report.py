"""Report, plots and terminal summary of the CaptainCook4D experiment."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from supportive.experiments.captaincook.measure import CONDITIONS, METRICS
from supportive.experiments.plotting import new_figure, save_png
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import above_zero, below_zero, error_bar, format_ci
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render

__all__ = ["CURVES_PLOT", "THESIS", "findings", "headline", "plots", "report"]

CURVES_PLOT = "curves.png"

THESIS: dict[str, Any] = {
    "numbers": None,
    "note": "The thesis has no CaptainCook4D experiment and prints no numbers for it",
    "claims": [
        "§2.2: a learner that asks for actions during demonstrations (active learning) comprehends the task's "
        "structure better than one that only watches, from the same few demonstrations",
        "§2.2.10: the feature-based strategies (distance, connectivity) do better than random queries",
    ],
}

_LABELS = {"passive": "passive", "random": "random", "distance": "distance", "connectivity": "connectivity"}
_COLOURS = {"passive": "black", "random": "tab:grey", "distance": "tab:blue", "connectivity": "tab:orange"}


def _signed(cell: Mapping[str, Any]) -> str:
    text = format_ci(cell, 3, signed=True)
    return f"**{text}**" if above_zero(cell) or below_zero(cell) else text


def _verdict(metrics: Mapping[str, Any]) -> list[str]:
    curves, deltas = metrics["curves"], metrics["delta_f1"]
    few = [k for k in ("2", "3", "4") if k in curves]
    lines = []
    for strategy in CONDITIONS[1:]:
        better = [k for k in few if above_zero(deltas[k][strategy])]
        worse = [k for k in few if below_zero(deltas[k][strategy])]
        if better and not worse:
            word = f"better than passive at k = {', '.join(better)} (95% CI of the paired difference above 0)"
        elif worse and not better:
            word = f"worse than passive at k = {', '.join(worse)} (95% CI of the paired difference below 0)"
        elif better or worse:
            word = f"better at k = {', '.join(better) or '–'}, worse at k = {', '.join(worse) or '–'}"
        else:
            word = "not distinguishable from passive at k = 2–4"
        lines.append(f"* **{strategy}**: F1 {word}.")
    return lines


def report(metrics: Mapping[str, Any]) -> str:
    """The markdown report: curves per k, passive vs each strategy, beside the thesis's qualitative claims (its
    prose: ``templates/report.md``)."""
    demos = metrics["demonstrations"]
    return render(
        __package__,
        "report.md",
        metrics,
        title=metrics.get("title", "CaptainCook4D learning curves"),
        seed=metrics.get("seed"),
        trials=metrics.get("trials"),
        recipes=metrics["recipes_run"],
        recordings=f"{demos['min']}–{demos['max']}",
        after_steps=", ".join(map(str, metrics["schedule"]["after_steps"])),
        note=THESIS["note"],
        claims=[f"* {claim}" for claim in THESIS["claims"]],
        f1_table=_f1_table(metrics["curves"]),
        delta_table=_delta_table(metrics),
        metric_tables="\n\n".join(
            "\n".join([f"## {metric.capitalize()} per demonstration (means)", "", *_metric_table(metrics["curves"], metric)])
            for metric in ("precision", "recall")
        ),
        at_own_k_table=markdown_table(
            ["condition", "precision", "recall", "F1"],
            [[c, *(format_ci(metrics["at_own_k"][c][m]) for m in METRICS)] for c in CONDITIONS],
        ),
        queries_table=_queries_table(metrics),
        valid="yes." if metrics["active_demonstrations_valid"] else "**no**.",
        verdict=_verdict(metrics),
    )


def _by_k(table: Mapping[str, Any]) -> list[tuple[str, Any]]:
    return sorted(table.items(), key=lambda item: int(item[0]))


def _f1_table(curves: Mapping[str, Any]) -> list[str]:
    """F1 per demonstration k, per condition, with its CI."""
    rows = [[key, str(row["recipes"]), *(format_ci(row[c]["f1"]) for c in CONDITIONS)] for key, row in _by_k(curves)]
    return markdown_table(["k", "recipes", *CONDITIONS], rows, align="r" * (2 + len(CONDITIONS)))


def _delta_table(metrics: Mapping[str, Any]) -> list[str]:
    """Strategy − passive F1 per k and at each recipe's own K."""
    rows = [[key, *(_signed(row[s]) for s in CONDITIONS[1:])] for key, row in _by_k(metrics["delta_f1"])]
    rows.append(["own K", *(_signed(metrics["delta_f1_at_own_k"][s]) for s in CONDITIONS[1:])])
    return markdown_table(["k", *CONDITIONS[1:]], rows, align="r" * len(CONDITIONS))


def _metric_table(curves: Mapping[str, Any], metric: str) -> list[str]:
    """Mean ``metric`` (precision or recall) per demonstration k, per condition."""
    rows = [[key, *(f"{row[c][metric]['mean']:.3f}" for c in CONDITIONS)] for key, row in _by_k(curves)]
    return markdown_table(["k", *CONDITIONS], rows, align="r" * (1 + len(CONDITIONS)))


def _queries_table(metrics: Mapping[str, Any]) -> list[str]:
    """Queries asked and heeded per strategy, and how many distinct demonstrations they gave."""
    total = metrics["demonstrations"]["total"] * (metrics.get("trials") or 1)
    rows = [
        [s, str(q["asked"]), str(q["honoured"]), f"{q['distinct_demonstrations']} of {total}"]
        for s, q in metrics["queries"].items()
    ]
    return markdown_table(["strategy", "asked", "heeded", "distinct demonstrations"], rows)


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    """``curves.png``: precision, recall and F1 vs demonstrations, one line per condition, 95% CIs."""
    figure = new_figure(14.0, 4.5)
    axes = figure.subplots(1, 3, sharex=True)
    ks = sorted(int(k) for k in metrics["curves"])
    for ax, metric in zip(axes, ("f1", "precision", "recall"), strict=True):
        for cond in CONDITIONS:
            cells = [metrics["curves"][str(k)][cond][metric] for k in ks]
            means = [c["mean"] for c in cells]
            ax.plot(ks, means, marker="o", color=_COLOURS[cond], label=_LABELS[cond])
            bars = [error_bar(c) for c in cells]
            low = [c["mean"] - b[0] for c, b in zip(cells, bars, strict=True)]
            high = [c["mean"] + b[1] for c, b in zip(cells, bars, strict=True)]
            ax.fill_between(ks, low, high, color=_COLOURS[cond], alpha=0.12)
        ax.set_title(metric if metric != "f1" else "F1")
        ax.set_xlabel("demonstrations k (recipes with ≥ k recordings)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("score vs published graph")
    axes[0].legend(fontsize=8, loc="lower right")
    figure.suptitle(f'CaptainCook4D: "must come before" pairs vs demonstrations, seed {metrics.get("seed")}')
    return [save_png(figure, directory / CURVES_PLOT)]


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """F1 at k = 2 and at each recipe's K, per condition."""
    rows: list[HeadlineRow] = []
    for cond in CONDITIONS:
        at2 = metrics["curves"].get("2", metrics["curves"]["1"])[cond]["f1"]
        rows.append((f"F1 at k = 2, {cond}", f"{at2['mean']:.3f}", "no numbers (qualitative)"))
    for cond in CONDITIONS:
        rows.append((f"F1 at own K, {cond}", f"{metrics['at_own_k'][cond]['f1']['mean']:.3f}", "–"))
    return rows


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """The summary row: F1 at each recipe's own number of recordings, passive and each query strategy."""
    own = metrics["at_own_k"]
    values = (("", " · ".join(f"{c} {own[c]['f1']['mean']:.3f}" for c in CONDITIONS)),)
    passive = own["passive"]["f1"]["mean"]
    below = [c for c in CONDITIONS[1:] if own[c]["f1"]["mean"] < passive]
    verdict = (
        "not reproduced: every strategy below passive learning from real recordings"
        if len(below) == len(CONDITIONS) - 1
        else "reproduced for " + ", ".join(c for c in CONDITIONS[1:] if c not in below)
    )
    return [
        Finding(
            "F1 of implied precedences at each recipe's K recordings",
            "no CaptainCook4D experiment; claim: asking beats watching",
            values,
            verdict,
        )
    ]
