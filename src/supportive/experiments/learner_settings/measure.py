"""Learner-settings trials: one generated task, demonstrations by people with or without habits, one kind of
mistake put into a tenth of them (or none), learned under every setting of the grid.

Half the trials draw their demonstrations uniformly from the task's valid executions (``people`` "uniform"),
half from people with habits (``people`` "habits": :class:`~supportive.generate.habits.HabitualPeople` of a
strength drawn from :data:`~supportive.generate.habits.HABIT_STRENGTHS`), whose rare valid orders must not be
read as slips.

A slip the learner reports is **right** when it is in a demonstration that had a mistake put in, of the
matching kind (``moved`` ↔ ``out of order``, ``repeated``, ``dropped`` ↔ ``missing``) and putting it right
(the step moved back to a valid place, the repeat taken out, the missing step done where it may be) makes the
demonstration a valid execution; a mistake is **found** when a right slip explains its demonstration. (A step
moved past one neighbour is the neighbour moved past it; either explanation is right.) On clean data every
reported slip is wrong.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any

from supportive.experiments.learner_settings.spread import f1_scores, spread
from supportive.experiments.trials import Trial, spawn_trials
from supportive.generate.habits import PEOPLE, executions_by
from supportive.generate.mistakes import KINDS, PROFILES, inject, random_known_task
from supportive.learning import HTNLearner
from supportive.learning.general.noise import Deviation, SlipSearchCache

__all__ = [
    "CLEAN_DEMONSTRATIONS",
    "CLEAN_TASKS",
    "DEFAULT_TRIALS",
    "DEMONSTRATIONS",
    "GRID",
    "KIND_OF_SLIP",
    "PEOPLE",
    "SHARE",
    "SIZES",
    "TASKS",
    "grid_settings",
    "learn_grid",
    "make_trials",
    "qualified",
    "run_trial",
    "settings_name",
    "slip_cells",
    "slip_counts",
    "summarize",
    "trial_demonstrations",
]

DEMONSTRATIONS = (20, 50, 100)
"""Demonstrations per task."""
SHARE = 0.1
"""Share of the demonstrations given a mistake."""
SIZES = (6, 12)
"""Steps per task (inclusive range)."""
TASKS = 18
"""Generated tasks per profile, number of demonstrations and kind of mistake (a full run): a sample size, not
a setting of any learner. A cell of the report (a kind of mistake and a number of demonstrations) pools the
profiles: 54 tasks, half by each kind of people. (It was 6, 18 tasks a cell; two full samples of that size,
seeds 0 and 1, ranked the weights 300 and 1,000 in opposite orders, decided by a few tasks of people with
habits, docs/learning.md. At 18 the tasks with mistakes are about a quarter of a run's work, the clean ones
the rest.)"""
CLEAN_TASKS = 3000
"""Generated tasks without mistakes (a full run), each with 1–200 demonstrations: how often a setting reports
a slip where there is none."""
CLEAN_DEMONSTRATIONS = (1, 200)
DEFAULT_TRIALS = TASKS * len(PROFILES) * len(DEMONSTRATIONS) * len(KINDS) + CLEAN_TASKS
"""Trials of a full run: the tasks with mistakes, then the clean ones."""
TRIAL_KINDS = ("task with mistakes", "clean task")
"""What a run needs a trial of each of (its summary compares them)."""
KIND_OF_SLIP = {"moved": "out of order", "repeated": "repeated", "dropped": "missing"}
"""Which kind of slip the learner should report for each kind of mistake put in."""
GRID: dict[str, tuple[float, ...]] = {
    "slip_margin": (0.0, 1.0),
    "slip_rate": (0.1,),
    "slip_rate_weight": (100.0, 300.0, 1000.0),
    "order_concentration": (0.25, 1.0, math.inf),
}
"""The settings swept: every combination. ``slip_rate`` is held at 0.1, the value the earlier sweep of margin ×
rate chose on uniform demonstrations (0.03, 0.1, 0.2; docs/learning.md): a rate's log is a cost per slip as
the margin is, so the margin's sweep spans what the rate's would. ``slip_rate_weight`` (how many steps the
rate's prior is worth) decides how far the data move the rates from it: 1,000 steps is about the data of a
task with 100 demonstrations, 100 lets the rates of clean data fall toward 0. The margin's sweep stops at 1:
margin 2 had the worst F1 of every concentration in the run before the weight was swept (0.50–0.63,
docs/learning.md), and each value of the grid adds to a run that the clean tasks by people with habits make
slow."""


def settings_name(settings: Mapping[str, float]) -> str:
    """``slip_margin=1 slip_rate=0.1``: a combination of the grid as text (a key of the metrics)."""
    return " ".join(f"{k}={v:g}" for k, v in settings.items())


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """Trials with mistakes cycle through profile × demonstrations × kind (a full run has :data:`TASKS` of
    each), then clean ones cycle through the profiles (:data:`CLEAN_TASKS`); fewer trials keep the proportion.
    Within each, the people alternate (:data:`PEOPLE`)."""
    cells = list(itertools.product(PROFILES, DEMONSTRATIONS, KINDS))
    mistaken = max(1, round(trials * len(cells) * TASKS / (len(cells) * TASKS + CLEAN_TASKS)))
    params: list[dict[str, Any]] = []
    for i in range(mistaken):
        profile, n, kind = cells[i % len(cells)]
        people = PEOPLE[(i // len(cells)) % len(PEOPLE)]
        params.append({"profile": profile, "demonstrations": n, "case": kind, "people": people})
    for i in range(trials - mistaken):
        people = PEOPLE[(i // len(PROFILES)) % len(PEOPLE)]
        params.append({"profile": PROFILES[i % len(PROFILES)], "case": "none", "people": people})
    return spawn_trials(seed, params)


def trial_demonstrations(trial: Trial) -> tuple[list[list[str]], set[int], Callable[[Sequence[str]], bool]]:
    """A trial's generated demonstrations, the indices of those given a mistake, and its task's validity check.

    Its ``params``: ``profile``, ``case`` (a kind of mistake or ``"none"``), ``people``, ``demonstrations``
    (for a clean task, drawn from :data:`CLEAN_DEMONSTRATIONS` when not given) and ``sizes`` (steps per task,
    an inclusive range; :data:`SIZES` when not given)."""
    rng = trial.rng()
    profile, case = trial.params["profile"], trial.params["case"]
    if case == "none" and "demonstrations" not in trial.params:
        n = int(rng.integers(CLEAN_DEMONSTRATIONS[0], CLEAN_DEMONSTRATIONS[1] + 1))
    else:
        n = int(trial.params["demonstrations"])
    low, high = trial.params.get("sizes", SIZES)
    task = random_known_task(profile, int(rng.integers(low, high + 1)), rng)
    draw = executions_by(task, trial.params["people"], rng)
    demos = [draw(rng) for _ in range(n)]
    truth: set[int] = set()
    if case != "none":
        demos, injected = inject(demos, case, SHARE, task.admits, rng)
        truth = {i.demonstration for i in injected}
    return demos, truth, task.admits


def grid_settings() -> list[dict[str, float]]:
    """Every combination of :data:`GRID`, in the order the trials learn them."""
    return [dict(zip(GRID, values, strict=True)) for values in itertools.product(*GRID.values())]


def learn_grid(
    demos: Sequence[Sequence[str]], cache: SlipSearchCache | None
) -> Iterator[tuple[dict[str, float], HTNLearner, float]]:
    """Learn ``demos`` with the ``general`` reading under each setting of the grid in turn (sharing ``cache``'s
    work; None: nothing shared): each setting, its fitted learner and the fit's seconds."""
    for settings in grid_settings():
        started = time.perf_counter()
        learner = HTNLearner(mode="general", alternatives=0, slip_cache=cache, **settings).fit(demos)  # type: ignore[arg-type]
        yield settings, learner, time.perf_counter() - started


def run_trial(trial: Trial) -> dict[str, Any]:
    """Generate the task and its demonstrations, then learn them under every setting of the grid (sharing the
    slip search's work between the settings: :class:`~supportive.learning.general.SlipSearchCache`; each
    setting's time under ``"timing"`` is its fit's given what the settings before it shared)."""
    profile, case, people = trial.params["profile"], trial.params["case"], trial.params["people"]
    demos, truth, valid = trial_demonstrations(trial)
    n = len(demos)
    out: dict[str, Any] = {
        "index": trial.index, "profile": profile, "demonstrations": n, "case": case, "people": people,
        "steps": sum(len(d) for d in demos), "mistakes": len(truth), "settings": {},
    }
    timing: dict[str, float] = {}
    for settings, learner, seconds in learn_grid(demos, SlipSearchCache()):
        name = settings_name(settings)
        timing[name] = seconds
        out["settings"][name] = slip_counts(learner.deviations_, case, demos, truth, valid)
    out["timing"] = timing
    return out


def slip_counts(
    slips: Sequence[Deviation],
    case: str,
    demos: Sequence[Sequence[str]],
    truth: set[int],
    valid: Callable[[Sequence[str]], bool],
) -> dict[str, int]:
    """How a learner's reported ``slips`` on ``demos`` (``case`` put into the demonstrations ``truth``) score:
    ``reported``, ``right`` (the module docstring), ``found`` (mistakes a right slip explains) and
    ``wrong_tasks`` (1 when any reported slip is wrong)."""
    right = [d for d in slips if _right(d, case, demos, valid) and d.demonstration in truth]
    return {
        "reported": len(slips),
        "right": len(right),
        "found": len({d.demonstration for d in right}),
        "wrong_tasks": int(len(slips) > len(right)),
    }


def _right(slip: Deviation, case: str, demos: Sequence[Sequence[str]], valid: Callable[[Sequence[str]], bool]) -> bool:
    """The slip is of the kind put in and putting it right makes its demonstration valid."""
    if case == "none" or slip.kind != KIND_OF_SLIP[case]:
        return False
    demo = list(demos[slip.demonstration])
    action = slip.leaf[0]
    if slip.kind == "missing":
        return any(valid([*demo[:j], action, *demo[j:]]) for j in range(len(demo) + 1))
    rest = demo[: slip.position] + demo[slip.position + 1 :]
    if slip.kind == "repeated":
        return valid(rest)
    return any(valid([*rest[:j], action, *rest[j:]]) for j in range(len(rest) + 1))


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Per setting: precision and recall per kind and number of demonstrations (over all the tasks with
    mistakes, and apart for each :data:`PEOPLE`), the share of steps reported on clean data and of clean tasks
    with any report, by people without habits (``clean_*``) and with them (``habits_*``); the chosen setting
    (see :func:`choose`) and how sure that choice is (``spread``: for each qualified setting, how far behind
    the chosen one it is, the bootstrap standard error of that, and how often it is best when the tasks with
    mistakes are resampled; :func:`~supportive.experiments.learner_settings.spread.spread`)."""
    names = list(results[0]["settings"]) if results else []
    table: dict[str, Any] = {}
    for name in names:
        row: dict[str, Any] = {
            "kinds": slip_cells(results, name),
            "kinds_by_people": {people: slip_cells([r for r in results if r["people"] == people], name) for people in PEOPLE},
        }
        for people, prefix in (("uniform", "clean"), ("habits", "habits")):
            clean = [r for r in results if r["case"] == "none" and r["people"] == people]
            steps = sum(r["steps"] for r in clean)
            reported = sum(r["settings"][name]["reported"] for r in clean)
            row[f"{prefix}_flagged"] = round(reported / steps, 6) if steps else 0.0
            row[f"{prefix}_tasks_flagged"] = sum(r["settings"][name]["wrong_tasks"] for r in clean)
            row[f"{prefix}_tasks"] = len(clean)
        row["worst_f1"] = min((k["f1"] for k in row["kinds"].values() if k["mistakes"]), default=0.0)
        table[name] = row
    chosen = choose(table)
    return {
        "settings": table,
        "chosen": chosen,
        "spread": spread(results, qualified(table), chosen) if chosen else {},
        "tasks": [dict(r) for r in results],
    }


def slip_cells(results: Sequence[Mapping[str, Any]], name: str) -> dict[str, dict[str, Any]]:
    """Precision, recall, F1 and mistakes put in of setting ``name`` (the key of each result's ``settings``),
    per kind and number of demonstrations (``"moved 20"``), pooling the counts of ``results``' tasks."""
    cells: dict[str, dict[str, Any]] = {}
    for kind, n in itertools.product(KINDS, DEMONSTRATIONS):
        cell = [r for r in results if r["case"] == kind and r["demonstrations"] == n]
        reported = sum(r["settings"][name]["reported"] for r in cell)
        right = sum(r["settings"][name]["right"] for r in cell)
        found = sum(r["settings"][name]["found"] for r in cell)
        mistakes = sum(r["mistakes"] for r in cell)
        precision, recall, f1 = f1_scores(reported, right, found, mistakes)
        cells[f"{kind} {n}"] = {
            "precision": round(precision, 4), "recall": round(recall, 4), "f1": round(f1, 4), "mistakes": mistakes,
        }
    return cells


def qualified(table: Mapping[str, Mapping[str, Any]]) -> list[str]:
    """The settings quiet enough on clean data to be chosen, in ``table``'s order: those that report at most
    0.5 % of the steps of clean demonstrations, by people with habits or without, and a slip in at most 1 % of
    the clean tasks without habits. (A slip in a few clean tasks by people with habits is allowed: one
    person's rare valid order among many who keep the habit cannot always be told from a slip.)"""
    return [
        name
        for name, row in table.items()
        if row["clean_flagged"] <= 0.005
        and row["habits_flagged"] <= 0.005
        and row["clean_tasks_flagged"] <= 0.01 * row["clean_tasks"]
    ]


def choose(table: Mapping[str, Mapping[str, Any]]) -> str | None:
    """The procedure that picks the defaults: among the :func:`qualified` settings, the one with the best
    worst F1 over kinds of mistake and numbers of demonstrations (ties: the first in grid order, i.e. the
    smaller margin, rate and concentration). None when no setting qualifies. How sure the choice is, the
    summary's ``spread`` says (:mod:`~supportive.experiments.learner_settings.spread`)."""
    names = qualified(table)
    if not names:
        return None
    best = max(table[name]["worst_f1"] for name in names)
    return next(name for name in names if table[name]["worst_f1"] == best)

