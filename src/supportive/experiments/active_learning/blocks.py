"""Active learning on the pilot study's three block tasks (§2.2.7–2.2.10, Figure 2.10).

One trial = one simulated panel of 6 instructors (like the pilot study's 6 participants), each with its own
seed and her own base path (a valid ordering drawn for her, perturbed; see :data:`BASE`). Every instructor teaches each block task with each condition — passive (no queries), random,
distance-based, connectivity-based — for 4 demonstrations, on the thesis's schedule
(:meth:`~supportive.learning.active.QuerySchedule.thesis`). The measure is the known unique origin→terminal
paths of the learner's task graph: *solo* for each of the 6 instructors, *pairs* for the 15 pairs and
*triads* for the 20 triads of the panel (their learned graphs pooled). Each trial also runs the thesis's
one-way ANOVA (path count by strategy, the three active strategies) on its panel.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import cache
from itertools import combinations
from typing import Any

from supportive.evaluation.mistakes import shown
from supportive.examples import load
from supportive.experiments.active_learning.common import (
    NO_QUERIES,
    STRATEGIES,
    anova,
    known_paths,
    teach,
)
from supportive.experiments.readings import Finding
from supportive.experiments.registry import HeadlineRow
from supportive.experiments.statistics import above_zero, below_zero, format_ci, mean_ci
from supportive.experiments.tables import markdown_table
from supportive.experiments.templates import render
from supportive.experiments.trials import Trial, spawn_trials
from supportive.learning.active import QuerySchedule
from supportive.tasks.htn import count_orderings
from supportive.tasks.spec import TaskSpec

__all__ = [
    "CONDITIONS",
    "DEFAULT_TRIALS",
    "DEMONSTRATIONS",
    "GROUPS",
    "PANEL",
    "TASKS",
    "THESIS",
    "findings",
    "headline",
    "make_trials",
    "report",
    "run_trial",
    "summarize",
]

TASKS = ("blocks-tower", "blocks-v", "blocks-towers")
"""The bundled examples of the thesis's block tasks 1, 2 and 3 (Figure 2.9)."""
CONDITIONS = ("passive", *STRATEGIES)
"""Passive (no queries, the baseline) and the three query strategies."""
GROUPS = {"solo": 1, "pairs": 2, "triads": 3}
"""The data sets of §2.2.8: single instructors, and every pair and triad of the panel pooled."""
PANEL = 6
"""Instructors per panel (the pilot study's six participants)."""
DEMONSTRATIONS = 4
"""Demonstrations per task and condition (§2.2.7)."""
BASE = "own"
"""Each simulated participant's base path: ``"own"`` (a valid ordering drawn for her) or ``"canonical"`` (the
structure's order for everyone, as the thesis's food simulation does); perturbed either way."""
DEFAULT_TRIALS = 20
"""Panels of a full run (the thesis had one panel of 6 people; 20 simulated panels steady the means)."""

THESIS: dict[str, Any] = {
    "participants": 6,
    "demonstrations_per_task": 4,
    "groups": {"solo": 6, "pairs": 15, "triads": 20},
    "valid_orderings": {"1": 720, "2": 24, "3": 6},
    "schedules": {
        "1": "after steps 1, 3, 5",
        "2": "after steps 1, 3, 5",
        "3": "at the start, after steps 2, 4",
    },
    "anova": {
        "solo": {"1": {"F": 11.508, "df": [2, 10], "p": "< 0.01"}, "2": None, "3": None},
        "pairs": {
            "1": {"F": 17.381, "df": [2, 28], "p": "< 0.001"},
            "2": {"F": 9.591, "df": [2, 28], "p": "0.001"},
        },
        "triads": {
            "1": {"F": 25.107, "df": [2, 38], "p": "< 0.001"},
            "2": {"F": 85.597, "df": [2, 38], "p": "< 0.001"},
        },
    },
    "post_hoc_differences": {
        "solo": {"1": {"connectivity": 6.5, "distance": 5.667}},
        "pairs": {"1": {"connectivity": 9.1, "distance": 9.7}, "2": {"connectivity": 4.8, "distance": 4.0}},
        "triads": {
            "1": {"connectivity": 9.5, "distance": 11.65},
            "2": {"connectivity": 7.6, "distance": 6.1},
        },
    },
    "claims": [
        "single instructors: only task 1 shows a significant effect of query strategy (F(2,10) = 11.508, "
        "p < 0.01); connectivity beats random by 6.5 paths (p < 0.05), distance by 5.667 (p = 0.055)",
        "pairs and triads: feature-based strategies perform substantially better than random on tasks 1 and 2",
        "pooled, the distance-based learner learned task 2 completely and the connectivity-based learner "
        "tasks 2 and 3",
        "task 3: pooling improves the counts, but not clearly because of the queries (only 6 paths)",
    ],
}
"""What §2.2.8–2.2.10 report for Figure 2.10 (mean differences are the Bonferroni post-hoc ones, feature
strategy minus random; the text gives no means or standard deviations)."""


@cache
def _task(name: str) -> tuple[TaskSpec, int]:
    spec = load(name)
    assert spec.structure is not None
    return spec, count_orderings(spec.structure)


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """One trial per simulated panel of :data:`PANEL` instructors, each trial with its own seed."""
    return spawn_trials(
        seed, [{"panel": PANEL, "demonstrations": DEMONSTRATIONS, "base": BASE} for _ in range(trials)]
    )


def run_trial(trial: Trial) -> dict[str, Any]:
    """Run one panel: every instructor teaches every task under every condition; pool pairs and triads."""
    panel = int(trial.params.get("panel", PANEL))
    demonstrations = int(trial.params.get("demonstrations", DEMONSTRATIONS))
    own_base = trial.params.get("base", BASE) == "own"
    seeds = [int(s) for s in trial.rng().integers(0, 2**32, size=panel)]
    tasks: dict[str, Any] = {}
    for number, name in enumerate(TASKS, start=1):
        spec, orderings = _task(name)
        assert spec.structure is not None
        out: dict[str, Any] = {"number": number, "orderings": orderings}
        for c, condition in enumerate(CONDITIONS):
            schedule = NO_QUERIES if condition == "passive" else QuerySchedule.thesis(number)
            taught = [
                teach(
                    spec.structure,
                    spec.action_ids(),
                    instructor_seed=seed,
                    task=number,
                    strategy="random" if condition == "passive" else condition,
                    strategy_index=c,
                    schedule=schedule,
                    demonstrations=demonstrations,
                    own_base=own_base,
                ).demonstrations
                for seed in seeds
            ]
            out[condition] = {
                group: [
                    known_paths(*(taught[i] for i in members)) for members in combinations(range(panel), size)
                ]
                for group, size in GROUPS.items()
            }
        tasks[name] = out
    return {"index": trial.index, "base": "own" if own_base else "canonical", "tasks": tasks}


def _mean(values: Sequence[float]) -> float:
    return sum(values) / len(values)


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Per task, group and condition: the mean path count (95% CI over panels), the share of learners that
    know every valid ordering, each feature strategy's gain over random, and the panels' ANOVAs."""
    tasks: list[dict[str, Any]] = []
    for name in TASKS:
        per = [r["tasks"][name] for r in results]
        orderings = per[0]["orderings"]
        groups: dict[str, Any] = {}
        for group in GROUPS:
            conditions = {}
            for condition in CONDITIONS:
                units = [p[condition][group] for p in per]
                everything = [v for u in units for v in u]
                conditions[condition] = {
                    "paths": mean_ci([_mean(u) for u in units], 3),
                    "max": max(everything),
                    "complete": round(sum(v == orderings for v in everything) / len(everything), 4),
                    "percent": round(100 * _mean(everything) / orderings, 2),
                }
            gains = {
                strategy: {
                    "paths": mean_ci([_mean(p[strategy][group]) - _mean(p["random"][group]) for p in per], 3),
                    "panels_better": sum(_mean(p[strategy][group]) > _mean(p["random"][group]) for p in per),
                }
                for strategy in ("distance", "connectivity")
            }
            tests = [anova([p[s][group] for s in STRATEGIES]) for p in per]
            significant = sum(t["p"] is not None and t["p"] < 0.05 for t in tests)
            fs = sorted(t["F"] for t in tests if t["F"] is not None)
            groups[group] = {
                "conditions": conditions,
                "gain_over_random": gains,
                "anova": {
                    "df": tests[0]["df"],
                    "panels_significant": significant,
                    "median_F": fs[len(fs) // 2] if fs else None,
                    "first_panel": tests[0],
                },
            }
        tasks.append({"name": name, "number": per[0]["number"], "orderings": orderings, "groups": groups})
    return {
        "panels": len(results),
        "panel": PANEL,
        "demonstrations": DEMONSTRATIONS,
        "base": results[0].get("base", BASE),
        "tasks": tasks,
    }


def _thesis_anova(thesis: Mapping[str, Any], group: str, number: int) -> str:
    entry = thesis["anova"].get(group, {}).get(str(number))
    if entry is None:
        return "n.s." if group == "solo" else "–"
    return f"F({entry['df'][0]},{entry['df'][1]}) = {entry['F']}, p {entry['p']}"


def _thesis_gain(thesis: Mapping[str, Any], group: str, number: int, strategy: str) -> str:
    entry = thesis["post_hoc_differences"].get(group, {}).get(str(number))
    return "–" if entry is None else f"{entry[strategy]:g}"


def report(metrics: Mapping[str, Any]) -> str:
    """The markdown report: path counts per task, group and condition, and the gains beside the thesis's (its
    prose: ``templates/blocks.md``)."""
    return render(
        __package__,
        "blocks.md",
        metrics,
        claims=[f"* {claim}" for claim in metrics["thesis"]["claims"]],
        tasks="\n\n".join(_task_section(metrics, task) for task in metrics["tasks"]),
        verdict=verdict(metrics),
    )


def _task_section(metrics: Mapping[str, Any], task: Mapping[str, Any]) -> str:
    """One task's section: known paths per group and condition, then the gains over random and the ANOVAs."""
    thesis = metrics["thesis"]
    number = task["number"]
    paths = []
    for group, g in ((k, task["groups"][k]) for k in GROUPS):
        c = g["conditions"]
        complete = " / ".join(f"{100 * c[k]['complete']:.0f} %" for k in CONDITIONS)
        paths.append([group, *(format_ci(c[k]["paths"], 1) for k in CONDITIONS), complete])
    header = ["data set", "passive", "random", "distance", "connectivity", "complete (passive/random/distance/connectivity)"]
    gains_rows = []
    for group, g in ((k, task["groups"][k]) for k in GROUPS):
        gains, test = g["gain_over_random"], g["anova"]
        median = shown(test["median_F"], ".1f")
        gains_rows.append(
            [
                group,
                format_ci(gains["distance"]["paths"], 1),
                _thesis_gain(thesis, group, number, "distance"),
                format_ci(gains["connectivity"]["paths"], 1),
                _thesis_gain(thesis, group, number, "connectivity"),
                f"{test['panels_significant']} of {metrics['panels']}, F({test['df'][0]},{test['df'][1]}) = {median}",
                _thesis_anova(thesis, group, number),
            ]
        )
    gains_header = [
        "data set", "distance − random", "thesis", "connectivity − random", "thesis",
        "ANOVA: panels p < 0.05, median F", "thesis",
    ]
    return "\n".join(
        [
            f"## Task {number}: {task['name']} ({task['orderings']} valid orderings)",
            "",
            *markdown_table(header, paths, align="lrrrrl"),
            "",
            *markdown_table(gains_header, gains_rows, align="lrrrrll"),
        ]
    )


def verdict(metrics: Mapping[str, Any]) -> list[str]:
    """Bullet lines: do the feature strategies beat random, and where, in this run?"""
    out = []
    for task in metrics["tasks"]:
        parts = []
        for group, g in ((k, task["groups"][k]) for k in GROUPS):
            gains = {s: g["gain_over_random"][s]["paths"] for s in ("distance", "connectivity")}
            better = [s for s, gain in gains.items() if above_zero(gain)]
            worse = [s for s, gain in gains.items() if below_zero(gain)]
            text = f"{group}: " + (
                f"{' and '.join(better)} beat random" if better else "no strategy beats random"
            )
            if worse:
                text += f" ({' and '.join(worse)} worse)"
            parts.append(text)
        out.append(
            f"* task {task['number']} ({task['name']}): "
            + "; ".join(parts)
            + " (95% CI of the gain above 0)."
        )
    return out


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Mean path counts of pooled triads per task and strategy, beside the thesis's post-hoc gains."""
    rows: list[HeadlineRow] = []
    thesis = metrics["thesis"]
    for task in metrics["tasks"]:
        number = task["number"]
        c = task["groups"]["triads"]["conditions"]
        ours = " / ".join(f"{c[k]['paths']['mean']:.1f}" for k in STRATEGIES)
        gains = thesis["post_hoc_differences"]["triads"].get(str(number))
        theirs = (
            "–"
            if gains is None
            else f"dist +{gains['distance']:g}, conn +{gains['connectivity']:g} vs random"
        )
        rows.append((f"task {number} triads: paths rand/dist/conn (of {task['orderings']})", ours, theirs))
    return rows


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """The summary rows: the distance and connectivity gains over random of pooled triads on tasks 1 and 2
    (the thesis's post-hoc differences), and task 3."""
    rows = []
    thesis = metrics["thesis"]["post_hoc_differences"]["triads"]
    for task in metrics["tasks"]:
        number = str(task["number"])
        gains = task["groups"]["triads"]["gain_over_random"]
        ours = " / ".join(format_ci(gains[s]["paths"], 1) for s in ("distance", "connectivity"))
        theirs = thesis.get(number)
        above = [s for s in ("distance", "connectivity") if above_zero(gains[s]["paths"])]
        below = [s for s in ("distance", "connectivity") if below_zero(gains[s]["paths"])]
        if theirs is None:
            claim = "no significant difference"
            if above or below:
                parts = [f"{' and '.join(x)} {word} random" for x, word in ((above, "beat"), (below, "below")) if x]
                verdict = "not reproduced: " + "; ".join(parts) + " (95% CIs)"
            else:
                verdict = "reproduced (no difference from random)"
        else:
            claim = f"+{theirs['distance']:g} / +{theirs['connectivity']:g}"
            inside = [
                s
                for s in ("distance", "connectivity")
                if gains[s]["paths"]["low"] is not None
                and gains[s]["paths"]["low"] <= theirs[s] <= gains[s]["paths"]["high"]
            ]
            verdict = (
                "reproduced (the thesis's gains within the 95% CIs)"
                if len(inside) == 2
                else "direction reproduced, size not (" + (", ".join(inside) or "neither") + " within the CI)"
                if len(above) == 2
                else "not reproduced"
            )
        rows.append(
            Finding(
                f"task {number} ({task['orderings']} orderings), triads: paths gained over random, distance / "
                "connectivity",
                claim,
                (("", ours),),
                verdict,
            )
        )
    return rows
