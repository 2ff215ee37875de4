"""Active learning on 12 food-preparation tasks, solo vs pooled instructors (§2.2.10.1, Figure 2.11).

One trial = one simulated panel of 3 instructors (each with its own seed) on all 12 tasks of
:mod:`supportive.examples.food`, for each query strategy (random, distance, connectivity) and each reading of
*when* the learner asks (:data:`READINGS`; at most 3 queries per demonstration, none in the first).

* **solo**: instructor 1 teaches 12 demonstrations; comprehension after 4, 8 and 12 of them.
* **multi-instructor**: instructors 1, 2 and 3 teach 4 demonstrations each to their own learners; iteration 4
  is instructor 1's learner (so it equals solo's iteration 4, as in the thesis), 8 is instructors 1 + 2
  pooled, 12 is 1 + 2 + 3 pooled (the union of the learned graphs).
* **ceiling**: the known paths of every demonstration the same instructors could have given under the
  schedule, whatever the learner asked (:mod:`.ceiling`) — a bound no strategy can pass.

Comprehension = known origin→terminal paths of the task graph as a percentage of the task's valid orderings
(:func:`~supportive.tasks.htn.count_orderings`), averaged over the 12 tasks; 95% confidence intervals are over
trials.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import cache
from typing import Any

from supportive.examples import food
from supportive.experiments.active_learning.ceiling import ceiling_paths, reachable_demonstrations
from supportive.experiments.active_learning.common import STRATEGIES, known_paths, make_instructor, teach
from supportive.experiments.readings import Finding, Reading, reading_names, readings_table
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
    "ITERATIONS",
    "READINGS",
    "SCHEDULES",
    "THESIS",
    "findings",
    "headline",
    "make_trials",
    "report",
    "run_trial",
    "summarize",
]

READINGS = (
    Reading(
        "pilot",
        "queries after steps 1, 3 and 5",
        '§2.2.10.1 runs the food tasks under "conditions identical to the pilot study", modelling the pilot '
        'participants "for each task type"; the pilot asked after steps 1, 3 and 5 in its chain-with-a-clique '
        "and chain-of-cliques tasks (§2.2.7.1, tasks 1 and 2) and at the start only in its clique of chains "
        "(task 3). Every food task is a chain of cliques and actions, the type of tasks 1 and 2, so the "
        "pilot's schedule for that type is the closest reading: the default.",
    ),
    Reading(
        "start-2-4",
        "queries at the start and after steps 2 and 4",
        "The pilot's other schedule (§2.2.7.1, task 3: \"at the beginning of this task, as well as after the "
        'second and fourth steps"), for every food task.',
    ),
    Reading(
        "start-4-8",
        "queries at the start and after steps 4 and 8",
        "A query at the start, the other two spread over a 10–14-step recipe: the thesis gives no schedule "
        "for the food tasks, and the pilot's steps 1–5 cover only the first half of them.",
    ),
)
"""When the learner asks, as named readings; the first (``pilot``) is the default."""

SCHEDULES: dict[str, QuerySchedule] = {
    "pilot": QuerySchedule(after_steps=(1, 3, 5), max_per_demonstration=3, skip_first_demonstrations=1),
    "start-2-4": QuerySchedule(after_steps=(0, 2, 4), max_per_demonstration=3, skip_first_demonstrations=1),
    "start-4-8": QuerySchedule(after_steps=(0, 4, 8), max_per_demonstration=3, skip_first_demonstrations=1),
}
"""Each reading's schedule: §2.2.10.1's "3 queries allowed per demonstration, no queries during the initial
demonstration", asked at the reading's steps."""
ITERATIONS = (4, 8, 12)
"""Demonstrations seen, in all, at the three measurements."""
CONDITIONS = ("solo", "multi")
"""One instructor for 12 demonstrations, or three instructors of 4 demonstrations each, pooled."""
INSTRUCTORS = 3
BASE = "own"
"""The instructors' base path. ``"own"`` (default): a valid ordering drawn uniformly per instructor, then
perturbed — people differ in their habits. ``"canonical"`` (a trial parameter): the structure's order for
everyone, the thesis's literal "a fixed arbitrarily chosen canonical base path" (§2.2.10.1), perturbed per
instructor. Only ``"own"`` reproduces the thesis's *random* baseline when pooled (61.2 % at iteration 12; the
canonical base path leaves three instructors nearly alike and pooling gains ~1 point), see docs/experiments.md."""
DEFAULT_TRIALS = 50
"""§2.2.10.1: 50 simulated trials."""

THESIS: dict[str, Any] = {
    "trials": 50,
    "tasks": 12,
    "skills": {"min": 10, "max": 14},
    "valid_orderings": {"min": 12, "max": 24},
    "iterations": list(ITERATIONS),
    "comprehension_percent": {
        "solo": {
            "random": [25.9, 35.4, 42.9],
            "connectivity": [36.5, 54.1, 65.0],
            "distance": [54.6, 61.5, 65.4],
        },
        "multi": {
            "random": [25.9, 46.6, 61.2],
            "connectivity": [36.6, 52.0, 63.1],
            "distance": [54.6, 76.6, 85.8],
        },
    },
    "claim": (
        "this diversity gained from pooling instructors can be more beneficial for learning task constraints "
        "than using a single instructor with the same amount of demonstrations"
    ),
}
"""What §2.2.10.1 reports for Figure 2.11 (mean % of task comprehension at iterations 4, 8, 12)."""

LABELS = {"solo": "solo instructor", "multi": "multi-instructor (pooled)"}
CLOSE = 5.0
"""A curve "matches" the thesis when it is within this many percentage points at all three iterations."""


@cache
def _tasks() -> tuple[tuple[TaskSpec, int], ...]:
    out = []
    for name in food.names():
        spec = food.load(name)
        assert spec.structure is not None
        out.append((spec, count_orderings(spec.structure)))
    return tuple(out)


def make_trials(trials: int, seed: int, readings: Sequence[str] | None = None) -> tuple[Trial, ...]:
    """One trial per simulated panel of 3 instructors, each trial with its own seed, for ``readings``
    (default: all of :data:`READINGS`). A reading's numbers do not depend on which other readings run."""
    chosen = list(readings if readings is not None else reading_names(READINGS))
    return spawn_trials(
        seed, [{"instructors": INSTRUCTORS, "base": BASE, "readings": chosen} for _ in range(trials)]
    )


def run_trial(trial: Trial) -> dict[str, Any]:
    """Run one panel on every task with every strategy under every reading; path counts at iterations 4, 8,
    12, solo and pooled, and the instructors' ceilings."""
    own_base = trial.params.get("base", BASE) == "own"
    seeds = [int(s) for s in trial.rng().integers(0, 2**32, size=INSTRUCTORS)]
    chosen = trial.params.get("readings", reading_names(READINGS))
    return {
        "index": trial.index,
        "base": "own" if own_base else "canonical",
        "readings": {name: {"tasks": _panel(SCHEDULES[name], seeds, own_base)} for name in chosen},
    }


def _panel(schedule: QuerySchedule, seeds: Sequence[int], own_base: bool) -> dict[str, Any]:
    step = ITERATIONS[0]
    tasks: dict[str, Any] = {}
    for number, (spec, orderings) in enumerate(_tasks(), start=1):
        assert spec.structure is not None
        out: dict[str, Any] = {"orderings": orderings}
        for s, strategy in enumerate(STRATEGIES):
            taught = [
                teach(
                    spec.structure,
                    spec.action_ids(),
                    instructor_seed=seed,
                    task=number,
                    strategy=strategy,
                    strategy_index=s,
                    schedule=schedule,
                    demonstrations=ITERATIONS[-1] if i == 0 else step,
                    own_base=own_base,
                )
                for i, seed in enumerate(seeds)
            ]
            solo = [taught[0].paths[n - 1] for n in ITERATIONS]
            first = taught[0].demonstrations[:step]
            multi = [
                known_paths(first, *(t.demonstrations for t in taught[1:k]))
                for k in range(1, INSTRUCTORS + 1)
            ]
            out[strategy] = {"solo": solo, "multi": multi}
        reachable = [
            _reachable(spec, number, seed, schedule, ITERATIONS[-1] if i == 0 else step, own_base)
            for i, seed in enumerate(seeds)
        ]
        out["ceiling"] = {
            "solo": [ceiling_paths(reachable[0][:n]) for n in ITERATIONS],
            "multi": [
                ceiling_paths([*reachable[0][:step], *(d for r in reachable[1:k] for d in r)])
                for k in range(1, INSTRUCTORS + 1)
            ],
        }
        tasks[spec.name] = out
    return tasks


def _reachable(
    spec: TaskSpec, number: int, seed: int, schedule: QuerySchedule, demonstrations: int, own_base: bool
) -> list[set[tuple[str, ...]]]:
    """For each of an instructor's demonstrations, every one she could have given under ``schedule``."""
    assert spec.structure is not None
    person = make_instructor(spec.structure, instructor_seed=seed, task=number, own_base=own_base)
    actions = spec.action_ids()
    return [reachable_demonstrations(person, schedule, d, actions) for d in range(demonstrations)]


def _percent(paths: int, orderings: int) -> float:
    return 100.0 * paths / orderings


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Per reading: mean comprehension over tasks per trial, then mean and 95% CI over trials, for every
    strategy and the ceiling; per-task means; pooled minus solo at the same number of demonstrations."""
    readings = list(results[0]["readings"])
    return {
        "iterations": list(ITERATIONS),
        "instructors": INSTRUCTORS,
        "base": results[0].get("base", BASE),
        "task_count": len(results[0]["readings"][readings[0]]["tasks"]),
        "schedules": {
            name: {
                "after_steps": list(SCHEDULES[name].after_steps),
                "max_per_demonstration": SCHEDULES[name].max_per_demonstration,
                "skip_first_demonstrations": SCHEDULES[name].skip_first_demonstrations,
            }
            for name in readings
        },
        "by_reading": {name: _summarize_reading([r["readings"][name] for r in results]) for name in readings},
    }


def _summarize_reading(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    names = list(results[0]["tasks"])
    rows = (*STRATEGIES, "ceiling")

    def per_trial(r: Mapping[str, Any], row: str, condition: str, i: int) -> float:
        tasks = r["tasks"]
        values = [_percent(tasks[n][row][condition][i], tasks[n]["orderings"]) for n in names]
        return sum(values) / len(values)

    comprehension = {
        condition: {
            row: [
                mean_ci([per_trial(r, row, condition, i) for r in results], 2) for i in range(len(ITERATIONS))
            ]
            for row in rows
        }
        for condition in CONDITIONS
    }
    pooled_gain = {
        strategy: {
            str(n): {
                "percent": mean_ci(
                    [per_trial(r, strategy, "multi", i) - per_trial(r, strategy, "solo", i) for r in results],
                    2,
                ),
                "trials_better": sum(
                    per_trial(r, strategy, "multi", i) > per_trial(r, strategy, "solo", i) for r in results
                ),
                "trials_worse": sum(
                    per_trial(r, strategy, "multi", i) < per_trial(r, strategy, "solo", i) for r in results
                ),
            }
            for i, n in enumerate(ITERATIONS)
            if i > 0
        }
        for strategy in STRATEGIES
    }
    tasks = {
        n: {
            "orderings": results[0]["tasks"][n]["orderings"],
            **{
                condition: {
                    row: [
                        round(
                            sum(
                                _percent(r["tasks"][n][row][condition][i], r["tasks"][n]["orderings"])
                                for r in results
                            )
                            / len(results),
                            2,
                        )
                        for i in range(len(ITERATIONS))
                    ]
                    for row in rows
                }
                for condition in CONDITIONS
            },
        }
        for n in names
    }
    return {"comprehension": comprehension, "pooled_minus_solo": pooled_gain, "tasks": tasks}


def _readings(metrics: Mapping[str, Any]) -> list[str]:
    return list(metrics["by_reading"])


def report(metrics: Mapping[str, Any]) -> str:
    """The markdown report: comprehension per reading, strategy and iteration beside the thesis's, the
    instructors' ceiling, pooled vs solo, and per task (its prose: ``templates/food.md``)."""
    readings = _readings(metrics)
    return render(
        __package__,
        "food.md",
        metrics,
        base="a valid ordering drawn for each instructor" if metrics["base"] == "own" else "the structure's order",
        readings_table=readings_table(READINGS, readings, "schedule"),
        curves="\n\n".join(_section(LABELS[condition], _curve_table(metrics, condition)) for condition in CONDITIONS),
        pooled_table=_pooled_table(metrics),
        per_task="\n\n".join(
            _section(
                f"Per task, `{name}` (mean % over trials at iterations " + ", ".join(map(str, metrics["iterations"])) + ")",
                _task_table(metrics, name),
            )
            for name in readings
        ),
        verdict=verdict(metrics),
    )


def _section(title: str, table: list[str]) -> str:
    return "\n".join([f"## {title}", "", *table])


def _curve_table(metrics: Mapping[str, Any], condition: str) -> list[str]:
    """Comprehension per strategy (and the ceiling) and reading at each iteration, beside the thesis's."""
    thesis = metrics["thesis"]["comprehension_percent"][condition]
    its = metrics["iterations"]
    rows = []
    for row in (*STRATEGIES, "ceiling"):
        for name in _readings(metrics):
            ours = metrics["by_reading"][name]["comprehension"][condition][row]
            theirs = " / ".join(f"{v:.1f}" for v in thesis[row]) if row in thesis else "–"
            rows.append([row, f"`{name}`", *(format_ci(ours[i], 1) for i in range(len(its))), theirs])
    header = ["strategy", "reading", *(f"iteration {n}" for n in its), "thesis"]
    return markdown_table(header, rows, align="ll" + "r" * (len(its) + 1))


def _pooled_table(metrics: Mapping[str, Any]) -> list[str]:
    """Pooled minus solo comprehension per strategy, reading and iteration (after the first)."""
    thesis = metrics["thesis"]["comprehension_percent"]
    rows = []
    for strategy in STRATEGIES:
        for name in _readings(metrics):
            for i, n in enumerate(metrics["iterations"]):
                if i == 0:
                    continue
                gain = metrics["by_reading"][name]["pooled_minus_solo"][strategy][str(n)]
                theirs = thesis["multi"][strategy][i] - thesis["solo"][strategy][i]
                rows.append(
                    [
                        strategy,
                        f"`{name}`",
                        str(n),
                        format_ci(gain["percent"], 1),
                        f"{gain['trials_better']} / {gain['trials_worse']}",
                        f"{theirs:+.1f}",
                    ]
                )
    header = [
        "strategy", "reading", "iteration", "multi − solo (percentage points)", "trials multi better / worse",
        "thesis multi − solo",
    ]
    return markdown_table(header, rows, align="llrrrr")


def _task_table(metrics: Mapping[str, Any], name: str) -> list[str]:
    """Per task, the mean % known at each iteration under reading ``name``, per condition and strategy."""
    rows = [
        [
            task_name,
            str(task["orderings"]),
            *(
                "/".join(f"{v:.0f}" for v in task[condition][row])
                for condition in CONDITIONS
                for row in (*STRATEGIES, "ceiling")
            ),
        ]
        for task_name, task in metrics["by_reading"][name]["tasks"].items()
    ]
    header = [
        "task", "orderings", "solo random", "solo distance", "solo connectivity", "solo ceiling",
        "multi random", "multi distance", "multi connectivity", "multi ceiling",
    ]
    return markdown_table(header, rows, align="lr" + "l" * 8)


def _gap(metrics: Mapping[str, Any], name: str, condition: str, strategy: str) -> float:
    """The largest distance from the thesis's curve over the three iterations, percentage points."""
    ours = metrics["by_reading"][name]["comprehension"][condition][strategy]
    theirs = metrics["thesis"]["comprehension_percent"][condition][strategy]
    return max(abs(float(o["mean"]) - float(t)) for o, t in zip(ours, theirs, strict=True))


def _curve_verdict(metrics: Mapping[str, Any], condition: str, strategy: str) -> str:
    readings = _readings(metrics)
    gaps = {name: _gap(metrics, name, condition, strategy) for name in readings}
    close = [name for name in readings if gaps[name] <= CLOSE]
    best = min(readings, key=gaps.__getitem__)
    if readings[0] in close:
        return f"reproduced (within {CLOSE:g} points at 4/8/12)"
    if close:
        return (
            f"reproduced only under {', '.join(close)}; default off by up to {gaps[readings[0]]:.1f} points"
        )
    return f"not reproduced: off by up to {gaps[best]:.1f} points even under {best}"


def verdict(metrics: Mapping[str, Any]) -> list[str]:
    """Bullet lines on the thesis's claims, from this run's numbers, for each reading."""
    last = len(metrics["iterations"]) - 1
    n = metrics["iterations"][last]
    out = []
    for name in _readings(metrics):
        comp = metrics["by_reading"][name]["comprehension"]
        for condition in CONDITIONS:
            order = sorted(STRATEGIES, key=lambda s: -comp[condition][s][last]["mean"])
            thesis = metrics["thesis"]["comprehension_percent"][condition]
            theirs = sorted(STRATEGIES, key=lambda s: -thesis[s][last])
            out.append(
                f"* `{name}`, {LABELS[condition]}, iteration {n}: "
                + " > ".join(f"{s} {comp[condition][s][last]['mean']:.1f} %" for s in order)
                + f" (ceiling {comp[condition]['ceiling'][last]['mean']:.1f} %; thesis: "
                + " > ".join(f"{s} {thesis[s][last]:.1f} %" for s in theirs)
                + ")."
            )
        for strategy in STRATEGIES:
            gain = metrics["by_reading"][name]["pooled_minus_solo"][strategy][str(n)]["percent"]
            if above_zero(gain):
                word = "beat"
            elif below_zero(gain):
                word = "fall behind"
            else:
                word = "are level with"
            out.append(
                f"* `{name}`, {strategy}: 3 pooled instructors {word} one instructor with the same 12 "
                f"demonstrations ({format_ci(gain, 1, signed=True)} points, mean and 95% CI)."
            )
    for condition in CONDITIONS:
        for strategy in STRATEGIES:
            out.append(
                f"* {LABELS[condition]} {strategy} curve: {_curve_verdict(metrics, condition, strategy)}."
            )
    return out


def findings(metrics: Mapping[str, Any]) -> list[Finding]:
    """One row per condition and strategy: % known at 4/8/12 under each reading, beside the thesis."""
    thesis = metrics["thesis"]["comprehension_percent"]
    rows = []
    for condition in CONDITIONS:
        for strategy in STRATEGIES:
            values = tuple(
                (
                    name,
                    "/".join(
                        f"{v['mean']:.1f}"
                        for v in metrics["by_reading"][name]["comprehension"][condition][strategy]
                    ),
                )
                for name in _readings(metrics)
            )
            rows.append(
                Finding(
                    f"{condition} {strategy}: % known at 4/8/12",
                    "/".join(f"{v:.1f}" for v in thesis[condition][strategy]),
                    values,
                    _curve_verdict(metrics, condition, strategy),
                )
            )
    return rows


def headline(metrics: Mapping[str, Any]) -> list[HeadlineRow]:
    """Comprehension at iteration 12 per condition and strategy under each reading, beside the thesis's."""
    thesis = metrics["thesis"]["comprehension_percent"]
    rows: list[HeadlineRow] = []
    for condition in CONDITIONS:
        for strategy in (*STRATEGIES, "ceiling"):
            ours = " · ".join(
                f"{name} {metrics['by_reading'][name]['comprehension'][condition][strategy][-1]['mean']:.1f}"
                for name in _readings(metrics)
            )
            theirs = f"{thesis[condition][strategy][-1]:.1f}" if strategy in thesis[condition] else "–"
            rows.append((f"{condition} {strategy}: % known at 12", ours, theirs))
    return rows
