"""Transfer: trial results -> metrics, the markdown report beside the thesis, the terminal headline."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from supportive.experiments.readings import Finding, readings_table
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import below_zero, format_ci, mean_ci
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render
from supportive.experiments.transfer.explore import (
    ALPHA,
    COMPLETION,
    EPSILON,
    FAIL,
    GAMMA,
    NOVELTY,
    STEP,
)
from supportive.experiments.transfer.measure import CONDITIONS, MACRO_CONDITIONS, READINGS, SEEDS
from supportive.experiments.transfer.sources import PRIOR_SCALE

__all__ = [
    "CLAIM",
    "DEFAULT_TRIALS",
    "LABELS",
    "THESIS",
    "column",
    "columns",
    "findings",
    "headline",
    "label",
    "pair",
    "report",
    "summarize",
]

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
DEFAULT_TRIALS = THESIS["tasks"] * SEEDS
"""Trials of a full run: every task, :data:`~.measure.SEEDS` times."""

LABELS = {
    "none": "(a) no transfer",
    "q": "(b) Q-function transfer",
    "cchtn": "(c) Q-function + CC-HTN macros",
    "q_raw": "(b′) Q-function transfer, unscaled",
    "cchtn_raw": "(c′) Q + CC-HTN macros, unscaled",
}
"""Report labels of the conditions."""

PAIRS = (("cchtn", "q"), ("cchtn", "none"), ("q", "none"), ("cchtn_raw", "q_raw"), ("cchtn_raw", "none"))
"""Paired comparisons reported: (first, second): in how many trials first needed fewer episodes (a win),
as many (a tie) or more (a loss)."""


def column(condition: str, reading: str | None) -> str:
    """The key of a condition under a reading in per-task and per-trial tables (``cchtn:any-order``);
    conditions without macros have no reading."""
    return condition if reading is None or condition not in MACRO_CONDITIONS else f"{condition}:{reading}"


def columns(readings: Sequence[str]) -> list[str]:
    """Every (condition, reading) column, in report order."""
    return [column(c, r) for c in CONDITIONS for r in (readings if c in MACRO_CONDITIONS else [None])]


def label(key: str) -> str:
    """``(c) Q-function + CC-HTN macros, any-order`` for ``cchtn:any-order``."""
    condition, _, reading = key.partition(":")
    return f"{LABELS[condition]}, {reading}" if reading else LABELS[condition]


def _episodes(run: Mapping[str, Any]) -> int:
    """Episodes to comprehension; a censored run counts as its episode budget (a lower bound)."""
    return int(run["episodes"] if run["episodes"] is not None else run["episodes_run"])


def _runs(result: Mapping[str, Any]) -> dict[str, Mapping[str, Any]]:
    """One trial's runs by column."""
    out = dict(result["conditions"])
    for reading, runs in result["readings"].items():
        for condition, run in runs.items():
            out[column(condition, reading)] = run
    return out


def _condition(runs: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    return {
        "episodes": mean_ci([_episodes(run) for run in runs], digits=2, bounds=(0.0, 1e12)),
        "censored": sum(run["censored"] for run in runs),
        "macros": round(sum(run["macros"] for run in runs) / len(runs), 2),
        "macro_uses": round(sum(run["macro_uses"] for run in runs) / len(runs), 2),
        "steps": round(sum(run["steps"] for run in runs) / len(runs), 1),
    }


def _pair(first: str, second: str, trials: Sequence[Mapping[str, Mapping[str, Any]]]) -> dict[str, Any]:
    a = [_episodes(t[first]) for t in trials]
    b = [_episodes(t[second]) for t in trials]
    return {
        "first": first,
        "second": second,
        "difference": mean_ci([x - y for x, y in zip(a, b, strict=True)], 2),
        "wins": sum(x < y for x, y in zip(a, b, strict=True)),
        "ties": sum(x == y for x, y in zip(a, b, strict=True)),
        "losses": sum(x > y for x, y in zip(a, b, strict=True)),
        "trials": len(trials),
    }


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Means with 95% CIs per condition (and reading), per-trial wins/ties/losses, per-task means and
    per-trial episodes."""
    readings = list(results[0]["readings"])
    trials = [_runs(r) for r in results]
    keys = columns(readings)
    pairs = []
    for first, second in PAIRS:
        for reading in readings if first in MACRO_CONDITIONS else [None]:
            pairs.append(_pair(column(first, reading), column(second, reading), trials))
    for condition in MACRO_CONDITIONS:
        for i, reading in enumerate(readings):
            for other in readings[i + 1 :]:
                pairs.append(_pair(column(condition, reading), column(condition, other), trials))
    tasks: dict[str, dict[str, Any]] = {}
    for r, runs in zip(results, trials, strict=True):
        t = tasks.setdefault(
            r["task"], {"task": r["task"], "actions": r["actions"], "orderings": r["orderings"], "runs": []}
        )
        t["runs"].append({key: _episodes(runs[key]) for key in keys})
    per_task = [
        {
            "task": t["task"],
            "actions": t["actions"],
            "orderings": t["orderings"],
            "trials": len(t["runs"]),
            "episodes": {key: round(sum(run[key] for run in t["runs"]) / len(t["runs"]), 2) for key in keys},
        }
        for _, t in sorted(tasks.items())
    ]
    return {
        "columns": keys,
        "conditions": {key: _condition([runs[key] for runs in trials]) for key in keys},
        "pairs": pairs,
        "tasks": per_task,
        "runs": [
            {"task": r["task"], "repeat": r["repeat"], **{key: runs[key]["episodes"] for key in keys}}
            for r, runs in zip(results, trials, strict=True)
        ],
    }


def pair(metrics: Mapping[str, Any], first: str, second: str) -> Mapping[str, Any]:
    """The paired comparison of columns ``first`` and ``second``."""
    return next(p for p in metrics["pairs"] if p["first"] == first and p["second"] == second)


def _readings(metrics: Mapping[str, Any]) -> list[str]:
    return list(metrics["readings"])


def verdict(metrics: Mapping[str, Any], reading: str) -> str:
    """Does (c) beat (a) and (b) in every trial, under ``reading``?"""
    vs_q = pair(metrics, column("cchtn", reading), "q")
    vs_none = pair(metrics, column("cchtn", reading), "none")
    n = metrics["trials"]
    if vs_q["wins"] == n and vs_none["wins"] == n:
        return f"**Holds** (`{reading}`): (c) needed fewer episodes than both (a) and (b) in all {n} trials."
    return (
        f"**Not reproduced** (`{reading}`): (c) needed fewer episodes than (b) in {vs_q['wins']} of {n} trials "
        f"({vs_q['ties']} ties, {vs_q['losses']} losses) and than (a) in {vs_none['wins']} of {n} "
        f"({vs_none['ties']} ties, {vs_none['losses']} losses)."
    )


def report(metrics: Mapping[str, Any]) -> str:
    """The markdown report: this run beside the thesis's claim, every reading side by side (its prose:
    ``templates/report.md``)."""
    thesis = metrics["thesis"]
    columns = metrics["columns"]
    return render(
        __package__,
        "report.md",
        metrics,
        thesis_tasks=thesis["tasks"],
        thesis_steps=thesis["steps"],
        primitive_actions=thesis["primitive_actions"],
        claim=CLAIM,
        alpha=ALPHA,
        gamma=GAMMA,
        epsilon=EPSILON,
        fail=f"{FAIL:+g}",
        step=f"{STEP:+g}",
        novelty=f"{NOVELTY:+g}",
        completion=f"{COMPLETION:+g}",
        prior_scale=f"{PRIOR_SCALE:g}",
        readings_table=readings_table(READINGS, _readings(metrics), "a macro performs"),
        episodes_table=_episodes_table(metrics),
        pairs_table=_pairs_table(metrics),
        claim_table=markdown_table(
            ["the thesis", "this run"], [[f'"{CLAIM}"', verdict(metrics, r)] for r in _readings(metrics)], align="ll"
        ),
        task_table=markdown_table(
            ["task", "actions", "orderings", *(label(k) for k in columns)],
            [
                [t["task"], str(t["actions"]), str(t["orderings"]), *(f"{t['episodes'][k]:g}" for k in columns)]
                for t in metrics["tasks"]
            ],
        ),
    )


def _episodes_table(metrics: Mapping[str, Any]) -> list[str]:
    """Episodes to full comprehension per condition, with censored runs and macro use."""
    header = [
        "condition", "episodes to comprehension, mean [95% CI]", "censored", "macros in dictionary", "macro uses",
        "primitive attempts",
    ]
    rows = []
    for key in metrics["columns"]:
        s = metrics["conditions"][key]
        rows.append(
            [
                label(key),
                format_ci(s["episodes"], 1),
                str(s["censored"]),
                f"{s['macros']:g}",
                f"{s['macro_uses']:g}",
                f"{s['steps']:g}",
            ]
        )
    return markdown_table(header, rows)


def _pairs_table(metrics: Mapping[str, Any]) -> list[str]:
    """Trial by trial: wins, ties and losses of one condition against another."""
    rows = [
        [
            f"{label(p['first'])} vs {label(p['second'])}",
            f"{p['wins']} of {p['trials']}",
            str(p["ties"]),
            str(p["losses"]),
            format_ci(p["difference"], 1, signed=True),
        ]
        for p in metrics["pairs"]
    ]
    header = ["comparison", "wins (fewer episodes)", "ties", "losses (more)", "mean difference in episodes [95% CI]"]
    return markdown_table(header, rows)


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """The summary rows: mean episodes (a)/(b)/(c), and (c)'s wins over (b) and (a), per reading."""
    n = metrics["trials"]
    readings = _readings(metrics)

    def mean(key: str) -> str:
        return f"{metrics['conditions'][key]['episodes']['mean']:.1f}"

    episodes = tuple((r, f"{mean('none')} / {mean('q')} / {mean(column('cchtn', r))}") for r in readings)
    wins = tuple(
        (
            r,
            f"{pair(metrics, column('cchtn', r), 'q')['wins']}/{n} vs (b), "
            f"{pair(metrics, column('cchtn', r), 'none')['wins']}/{n} vs (a)",
        )
        for r in readings
    )
    every = {
        r: pair(metrics, column("cchtn", r), "q")["wins"]
        == n
        == pair(metrics, column("cchtn", r), "none")["wins"]
        for r in readings
    }
    faster = {
        r: all(below_zero(pair(metrics, column("cchtn", r), c)["difference"]) for c in ("q", "none"))
        for r in readings
    }
    if every[readings[0]]:
        claim = "reproduced"
    else:
        best = max(readings, key=lambda r: pair(metrics, column("cchtn", r), "q")["wins"])
        claim = (
            f"not reproduced: (c) wins {pair(metrics, column('cchtn', best), 'q')['wins']} of {n} against (b) at "
            f"best ({best}), not every trial"
        )
    means = (
        "(c) faster than (a) and (b) on average (paired differences' 95% CIs below 0)" if faster[readings[0]]
        else "(c) not faster than both on average (a paired difference's CI reaches 0)" + (
            f"; under {', '.join(r for r in readings if faster[r])} it is" if any(faster.values()) else ""
        )
    )  # fmt: skip
    return [
        Finding("episodes to comprehension, (a) / (b) / (c)", "plotted, no values", episodes, means),
        Finding("trials in which (c) needs fewer episodes", "every trial", wins, claim),
    ]


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Mean episodes per condition and the (c) win counts, beside the thesis."""
    n = metrics["trials"]
    rows: list[HeadlineRow] = [
        (f"episodes, {label(k)}", format_ci(metrics["conditions"][k]["episodes"], 1), "plotted, no values")
        for k in metrics["columns"]
        if k.partition(":")[0] in ("none", "q", "cchtn")
    ]
    for reading in _readings(metrics):
        rows.append(
            (
                f"trials (c) < (b), {reading}",
                f"{pair(metrics, column('cchtn', reading), 'q')['wins']} of {n}",
                "every trial",
            )
        )
        rows.append(
            (
                f"trials (c) < (a), {reading}",
                f"{pair(metrics, column('cchtn', reading), 'none')['wins']} of {n}",
                "every trial",
            )
        )
    return rows
