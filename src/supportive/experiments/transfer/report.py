"""Transfer: trial results -> metrics, the markdown report beside the thesis, the terminal headline."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import format_ci, mean_ci
from supportive.experiments.transfer.explore import (
    ALPHA,
    COMPLETION,
    EPSILON,
    FAIL,
    GAMMA,
    NOVELTY,
    STEP,
)
from supportive.experiments.transfer.measure import CONDITIONS
from supportive.experiments.transfer.sources import PRIOR_SCALE

__all__ = ["CLAIM", "LABELS", "THESIS", "headline", "report", "summarize"]

CLAIM = (
    "the macro actions produced by the CC-HTNs allowed the agent to achieve full task comprehension faster "
    "than either random exploration or flat Q-function transfer strategies in every trial"
)
"""The thesis's claim (§2.1.7.4), verbatim."""

THESIS: dict[str, Any] = {
    "tasks": 25,
    "steps": "6-14",
    "primitive_actions": 39,
    "claim": CLAIM,
    "values": "Figure 2.6 plots iterations per condition; the text prints no numbers",
}
"""What the thesis reports about the experiment."""

LABELS = {
    "none": "(a) no transfer",
    "q": "(b) Q-function transfer",
    "cchtn": "(c) Q-function + CC-HTN macros",
    "q_raw": "(b′) Q-function transfer, unscaled",
    "cchtn_raw": "(c′) Q + CC-HTN macros, unscaled",
}
"""Report labels of the conditions."""

PAIRS = (("cchtn", "q"), ("cchtn", "none"), ("q", "none"), ("cchtn_raw", "q_raw"), ("cchtn_raw", "none"))
"""Paired comparisons reported: (first, second): in how many trials first needed fewer episodes."""


def _episodes(run: Mapping[str, Any]) -> int:
    """Episodes to comprehension; a censored run counts as its episode budget (a lower bound)."""
    return int(run["episodes"] if run["episodes"] is not None else run["episodes_run"])


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Means with 95% CIs per condition, paired win counts, per-task means and per-trial episodes."""
    conditions = {}
    for c in CONDITIONS:
        runs = [r["conditions"][c] for r in results]
        conditions[c] = {
            "episodes": mean_ci([_episodes(run) for run in runs], digits=2, bounds=(0.0, 1e12)),
            "censored": sum(run["censored"] for run in runs),
            "macros": round(sum(run["macros"] for run in runs) / len(runs), 2),
            "macro_uses": round(sum(run["macro_uses"] for run in runs) / len(runs), 2),
            "steps": round(sum(run["steps"] for run in runs) / len(runs), 1),
        }
    pairs = []
    for first, second in PAIRS:
        a = [_episodes(r["conditions"][first]) for r in results]
        b = [_episodes(r["conditions"][second]) for r in results]
        pairs.append(
            {
                "first": first,
                "second": second,
                "fewer": sum(x < y for x, y in zip(a, b, strict=True)),
                "equal": sum(x == y for x, y in zip(a, b, strict=True)),
                "more": sum(x > y for x, y in zip(a, b, strict=True)),
                "trials": len(results),
            }
        )
    tasks: dict[str, dict[str, Any]] = {}
    for r in results:
        t = tasks.setdefault(
            r["task"], {"task": r["task"], "actions": r["actions"], "orderings": r["orderings"], "runs": []}
        )
        t["runs"].append({c: _episodes(r["conditions"][c]) for c in CONDITIONS})
    per_task = [
        {
            "task": t["task"],
            "actions": t["actions"],
            "orderings": t["orderings"],
            "trials": len(t["runs"]),
            "episodes": {c: round(sum(run[c] for run in t["runs"]) / len(t["runs"]), 2) for c in CONDITIONS},
        }
        for _, t in sorted(tasks.items())
    ]
    return {
        "conditions": conditions,
        "pairs": pairs,
        "tasks": per_task,
        "runs": [
            {
                "task": r["task"],
                "repeat": r["repeat"],
                **{c: r["conditions"][c]["episodes"] for c in CONDITIONS},
            }
            for r in results
        ],
    }


def _pair(metrics: Mapping[str, Any], first: str, second: str) -> Mapping[str, Any]:
    return next(p for p in metrics["pairs"] if p["first"] == first and p["second"] == second)


def verdict(metrics: Mapping[str, Any]) -> str:
    """Does (c) beat (a) and (b) in every trial?"""
    vs_q, vs_none = _pair(metrics, "cchtn", "q"), _pair(metrics, "cchtn", "none")
    n = metrics["trials"]
    if vs_q["fewer"] == n and vs_none["fewer"] == n:
        return f"**Holds**: (c) needed fewer episodes than both (a) and (b) in all {n} trials."
    return (
        f"**Not reproduced**: (c) needed fewer episodes than (b) in {vs_q['fewer']} of {n} trials "
        f"({vs_q['equal']} equal, {vs_q['more']} more) and fewer than (a) in {vs_none['fewer']} of {n} "
        f"({vs_none['equal']} equal, {vs_none['more']} more)."
    )


def report(metrics: Mapping[str, Any]) -> str:
    """The markdown report: this run beside the thesis's claim."""
    m = metrics
    lines = [
        "# Transfer: task exploration with Q-function and CC-HTN transfer (§2.1.7.4, Figure 2.6)",
        "",
        f"**Thesis.** {m['thesis']['tasks']} food-preparation tasks of {m['thesis']['steps']} steps encoded as "
        f"SMDPs (|A| = {m['thesis']['primitive_actions']}); iterations an ε-greedy explorer needs to capture "
        "every valid subgoal ordering, without transfer, with flat Q-function transfer and with CC-HTN macro "
        f'actions added. Claim: "{CLAIM}". Figure 2.6 prints no numbers.',
        "",
        "**This run.** Leave-one-out over the 25 transfer tasks (`supportive.examples.food.load_transfer`); "
        f"{m['trials']} trials, one (task, seed) each, every condition explored with its own seed. A state is "
        "the set of completed actions; a primitive the task does not allow next fails (the step is spent, the "
        "state kept); a macro runs its actions in order and stops at the first disallowed one. Q-learning "
        f"(α {ALPHA}, γ {GAMMA}, ε {EPSILON}); rewards {FAIL:+g} for a failure, {STEP:+g} for a valid step, "
        f"{NOVELTY:+g} more for a transition never performed before and {COMPLETION:+g} more for completing "
        "along a new ordering. Comprehension: the completed episodes' task graph has as many paths as the "
        "task has valid orderings. Iterations = episodes until then (a censored run counts as its budget, "
        "a lower bound: see the censored column).",
        "",
        "Q-function transfer: the other tasks' converged Q-functions (exact, by value iteration), as "
        "advantages Q − V, aggregated by the last action performed (max over the other tasks' states with that "
        f"last action) and scaled by {PRIOR_SCALE:g} to initialise each new state's Q row: a prior that orders "
        "untried options. The unscaled variants (′) start failing-elsewhere options near −1. CC-HTN macros: "
        "the chains and cliques (≥ 2 actions) of the CC-HTNs learned from all valid orderings of the other "
        "tasks, when every action of the macro belongs to the task.",
        "",
        "| condition | episodes to comprehension, mean [95% CI] | censored | macros in dictionary | macro uses | "
        "primitive attempts |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for c in CONDITIONS:
        s = m["conditions"][c]
        lines.append(
            f"| {LABELS[c]} | {format_ci(s['episodes'], 1)} | {s['censored']} | {s['macros']:g} | "
            f"{s['macro_uses']:g} | {s['steps']:g} |"
        )
    lines += [
        "",
        "| comparison | fewer episodes | equal | more |",
        "|---|---:|---:|---:|",
    ]
    for p in m["pairs"]:
        lines.append(
            f"| {LABELS[p['first']]} vs {LABELS[p['second']]} | {p['fewer']} of {p['trials']} | "
            f"{p['equal']} | {p['more']} |"
        )
    lines += [
        "",
        "| the thesis | this run |",
        "|---|---|",
        f'| "{CLAIM}" | {verdict(m)} |',
        "",
        "Per task (mean episodes over its trials):",
        "",
        "| task | actions | orderings | " + " | ".join(LABELS[c] for c in CONDITIONS) + " |",
        "|---|---:|---:|" + "---:|" * len(CONDITIONS),
    ]
    for t in m["tasks"]:
        lines.append(
            f"| {t['task']} | {t['actions']} | {t['orderings']} | "
            + " | ".join(f"{t['episodes'][c]:g}" for c in CONDITIONS)
            + " |"
        )
    lines.append("")
    return "\n".join(lines)


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Mean episodes per condition and the (c) win counts, beside the thesis."""
    n = metrics["trials"]
    rows: list[HeadlineRow] = [
        (f"episodes, {LABELS[c]}", format_ci(metrics["conditions"][c]["episodes"], 1), "plotted, no values")
        for c in ("none", "q", "cchtn")
    ]
    rows.append(("trials (c) < (b)", f"{_pair(metrics, 'cchtn', 'q')['fewer']} of {n}", "every trial"))
    rows.append(("trials (c) < (a)", f"{_pair(metrics, 'cchtn', 'none')['fewer']} of {n}", "every trial"))
    return rows
