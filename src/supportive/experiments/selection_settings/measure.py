"""Selection-settings trials: one generated task, ``n`` demonstrations of it by people with or without habits,
learned by the ``general`` reading and by ``auto`` comparing the readings with every number of folds of
:data:`FOLDS`; each learned hierarchy scored on fresh executions of the same task by the same people.

Half the trials draw the executions uniformly from the task's valid executions (``people`` "uniform"), half
from people with habits (``people`` "habits", :func:`~supportive.generate.habits.executions_by`), as
``learner-settings`` does: people favour some valid orders, and a setting chosen on uniform draws alone would
be chosen for people nobody is. Issue #13's recall is measured on the uniform half (:func:`.gains.recall_trials`).

The score is the one the comparison itself estimates (:func:`~supportive.learning.selection.held_out_log_likelihoods`):
the log-likelihood of an execution when every execution a hierarchy admits is equally likely, a refused one
explained as noise. A trial gives, per hierarchy, the mean over the fresh executions and how many it admitted.

A **policy** is a pair of settings: ``selection_folds`` and ``selection_demonstrations`` (compare from this
many demonstrations on; below, the ``general`` reading is kept). Its gain at ``n`` demonstrations is
``auto``'s score minus ``general``'s when ``n`` reaches its threshold, else 0. The procedure
(:func:`choose`): among the policies that cost no recall at :data:`RECALL_DEMONSTRATIONS` demonstrations of
``uniform`` tasks, where issue #13 fixed the default learner's recall, the best mean gain over the numbers of
demonstrations of the grid — or the :data:`CONVENTIONAL` policy when it is within one standard error of that.

Each trial also scores the ``general`` reading making subtasks and making none, from which
:mod:`.subtasks` picks ``subtask_demonstrations``, and at every evidence level, from which :mod:`.evidence`
picks ``evidence`` — the same tasks, fresh executions and score.
"""

from __future__ import annotations

import itertools
import statistics
from collections.abc import Mapping, Sequence
from typing import Any

# issue #13 fixed the default learner's recall on `uniform` tasks learned from this many demonstrations; the
# generalisation experiment's row holds it there
from supportive.experiments.generalisation.measure import DEMONSTRATIONS as RECALL_DEMONSTRATIONS
from supportive.experiments.selection_settings.evidence import LEVELS, summarize_levels
from supportive.experiments.selection_settings.gains import (
    best_qualified,
    mean_gain,
    recall_trials,
    row_summary,
    set_distances,
    thresholded_gains,
    within_one_error,
)
from supportive.experiments.selection_settings.subtasks import summarize_thresholds
from supportive.experiments.trials import Trial, spawn_trials
from supportive.generate.habits import PEOPLE, executions_by
from supportive.generate.mistakes import PROFILES, random_known_task
from supportive.learning import HTNLearner
from supportive.learning.selection import held_out_log_likelihoods

__all__ = [
    "CONVENTIONAL",
    "DEFAULT_TRIALS",
    "DEMONSTRATIONS",
    "FOLDS",
    "FRESH",
    "RECALL_DEMONSTRATIONS",
    "SIZES",
    "TASKS",
    "best_policy",
    "choose",
    "make_trials",
    "policy_name",
    "run_trial",
    "summarize",
    "within_one_error",
]

DEMONSTRATIONS = (2, 3, 4, 5, 6, 8, 10, 12, 16, 20)
"""Numbers of demonstrations a task is learned from; also the thresholds a policy may compare from."""
FOLDS = (2, 3, 5, 10)
"""Folds of the comparison swept (leave one out where there are fewer demonstrations)."""
SIZES = (6, 12)
"""Steps per task (inclusive range), as in ``learner-settings``."""
TASKS = 100
"""Generated tasks per profile, number of demonstrations and kind of people (a full run): a sample size, which
sets how precisely the gains are measured, not a setting of any learner (a run of fewer trials keeps the
proportions)."""
FRESH = 50
"""Fresh executions of each task the learned hierarchies are scored on: a sample size, like :data:`TASKS`."""
DEFAULT_TRIALS = TASKS * len(PROFILES) * len(DEMONSTRATIONS) * len(PEOPLE)
"""Trials of a full run."""
CONVENTIONAL = (5, 5)
"""``selection_folds`` and ``selection_demonstrations`` by convention: 5-fold cross-validation (the usual
choice; Hastie, Tibshirani and Friedman, *The Elements of Statistical Learning*, §7.10), compared from as many
demonstrations as folds. Kept unless a policy predicts fresh executions better by more than one standard
error (:func:`choose`)."""


def policy_name(folds: int | None, demonstrations: int | None) -> str:
    """``selection_folds=5 selection_demonstrations=5``, or ``never compare`` (either None)."""
    if folds is None or demonstrations is None:
        return "never compare"
    return f"selection_folds={folds} selection_demonstrations={demonstrations}"


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """Trials cycle through profile × number of demonstrations, the people alternating with each cycle (a
    full run has :data:`TASKS` of each profile, number and kind of people)."""
    cells = list(itertools.product(PROFILES, DEMONSTRATIONS))
    params: list[dict[str, Any]] = []
    for i in range(trials):
        profile, n = cells[i % len(cells)]
        params.append({"profile": profile, "demonstrations": n, "people": PEOPLE[(i // len(cells)) % len(PEOPLE)]})
    return spawn_trials(seed, params)


def run_trial(trial: Trial) -> dict[str, Any]:
    """Generate the task, its demonstrations and fresh executions (by the trial's people); learn and score
    ``general`` and ``auto`` under every number of folds, ``general`` making subtasks and making none, and
    ``general`` at every evidence level."""
    rng = trial.rng()
    profile, n = trial.params["profile"], int(trial.params["demonstrations"])
    task = random_known_task(profile, int(rng.integers(SIZES[0], SIZES[1] + 1)), rng)
    draw = executions_by(task, trial.params["people"], rng)
    demos = [draw(rng) for _ in range(n)]
    fresh = [draw(rng) for _ in range(FRESH)]
    general = HTNLearner(mode="general", alternatives=0).fit(demos)
    out: dict[str, Any] = {
        "index": trial.index, "profile": profile, "demonstrations": n, "people": trial.params["people"],
        "general": _score(general, fresh), "folds": {},
    }
    for folds in FOLDS:
        auto = HTNLearner(mode="auto", alternatives=0, selection_folds=folds, selection_demonstrations=2).fit(demos)
        assert auto.selection_ is not None
        out["folds"][str(folds)] = {**_score(auto, fresh), "chosen": auto.selection_.chosen}
    # the general reading making subtasks from the first demonstration on, and making none (subtasks.py)
    made = HTNLearner(mode="general", alternatives=0, subtask_demonstrations=1).fit(demos)
    none = HTNLearner(mode="general", alternatives=0, subtask_demonstrations=n + 1).fit(demos)
    out["subtasks"] = {"made": _score(made, fresh), "none": _score(none, fresh)}
    # the general reading at every evidence level (evidence.py)
    out["evidence"] = {
        str(level): _score(
            general if level == general.evidence else HTNLearner(mode="general", alternatives=0, evidence=level).fit(demos),
            fresh,
        )
        for level in LEVELS
    }
    return out


def _score(learner: HTNLearner, fresh: Sequence[Sequence[str]]) -> dict[str, Any]:
    """Mean held-out log-likelihood (nats) of the fresh executions under the learned hierarchy, and how many
    it admits."""
    scored = held_out_log_likelihoods(learner.htn_, fresh, learner.slip_rate)
    return {"log_likelihood": round(statistics.fmean(v for v, _ in scored), 6), "admitted": sum(ok for _, ok in scored)}


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    """Per number of folds and of demonstrations: the gain of comparing over ``general`` (mean and 95 %
    interval over the tasks, and per profile); the share of fresh executions each admits; every policy's mean
    gain over the grid and recall at :data:`RECALL_DEMONSTRATIONS`; the chosen policy (:func:`choose`); the
    sweeps of ``subtask_demonstrations`` (:mod:`.subtasks`) and ``evidence`` (:mod:`.evidence`)."""
    present = sorted({int(r["demonstrations"]) for r in results})
    gains: dict[str, dict[str, Any]] = {}
    admitted: dict[str, dict[str, float | None]] = {"general": {}}
    for folds in FOLDS:
        key = str(folds)
        gains[key] = {}
        admitted[key] = {}
        for n in present:
            cell = [r for r in results if r["demonstrations"] == n]
            differences = [r["folds"][key]["log_likelihood"] - r["general"]["log_likelihood"] for r in cell]
            gains[key][str(n)] = row_summary(differences, cell)
            admitted[key][str(n)] = _share(cell, key)
    for n in present:
        admitted["general"][str(n)] = _share([r for r in results if r["demonstrations"] == n], "general")
    uniform = recall_trials(results)
    recall = {name: _share(uniform, name) for name in admitted}
    policies, best = _policies(results, recall)
    return {
        "gains": gains,
        "admitted": admitted,
        "recall": recall,
        "policies": policies,
        "best": best,
        "chosen": choose(policies),
        "subtasks": summarize_thresholds(results, DEMONSTRATIONS, FRESH),
        "evidence": summarize_levels(results, FRESH),
        "tasks": [dict(r) for r in results],
    }


def _share(cell: Sequence[Mapping[str, Any]], reading: str) -> float | None:
    """The share of the cell's fresh executions that ``reading`` (``general`` or a number of folds) admitted
    (None for an empty cell)."""
    if not cell:
        return None
    admitted: int = sum(r["general"]["admitted"] if reading == "general" else r["folds"][reading]["admitted"] for r in cell)
    return round(admitted / (FRESH * len(cell)), 6)


def _policies(
    results: Sequence[Mapping[str, Any]], recall: Mapping[str, float | None]
) -> tuple[dict[str, dict[str, Any]], str | None]:
    """Every policy: its mean gain over the numbers of demonstrations run, its recall at
    :data:`RECALL_DEMONSTRATIONS` (``uniform`` tasks), whether that is no less than ``general``'s (never, when the
    run learned no such task: the recall is then not measured), and how far it is behind the best policy that
    keeps the recall (``gap``) with the standard error of that difference (``error``; the tasks of a row are
    paired, the rows independent). Also the best (:func:`best_policy`)."""
    settings = [*itertools.product(FOLDS, DEMONSTRATIONS), (None, None)]
    per_task: dict[str, dict[int, list[float]]] = {}
    out: dict[str, dict[str, Any]] = {}
    for folds, threshold in settings:
        name = policy_name(folds, threshold)
        per_task[name] = _policy_gains(results, folds, threshold)
        at_recall = folds is not None and threshold is not None and threshold <= RECALL_DEMONSTRATIONS
        kept = recall[str(folds)] if at_recall else recall["general"]
        out[name] = {
            "folds": folds,
            "demonstrations": threshold,
            "gain": round(mean_gain(per_task[name]), 6),
            "recall": kept,
            "qualifies": kept is not None and recall["general"] is not None and kept >= recall["general"],
        }
    best = best_policy(out)
    set_distances(out, per_task, best)
    return out, best


def _policy_gains(
    results: Sequence[Mapping[str, Any]], folds: int | None, threshold: int | None
) -> dict[int, list[float]]:
    """Per number of demonstrations, each task's gain under the policy (0 where it keeps ``general``; always
    for never comparing, ``folds`` None), in the order of ``results``."""
    return thresholded_gains(
        results,
        threshold if folds is not None else None,
        lambda r: float(r["folds"][str(folds)]["log_likelihood"] - r["general"]["log_likelihood"]),
    )


def _cost(row: Mapping[str, Any]) -> tuple[int, int, int]:
    """How much work a policy asks (smaller is cheaper): never comparing, then fewer folds, then comparing from
    more demonstrations."""
    if row["demonstrations"] is None:
        return (0, 0, 0)
    return (1, row["folds"], -row["demonstrations"])


def best_policy(policies: Mapping[str, Mapping[str, Any]]) -> str | None:
    """The best mean gain among the policies that keep the recall (ties: the cheaper); None when none does."""
    return best_qualified(policies, lambda name: tuple(-part for part in _cost(policies[name])))


def choose(policies: Mapping[str, Mapping[str, Any]]) -> str | None:
    """The procedure that picks the defaults: among the policies that admit no fewer fresh executions of
    ``uniform`` tasks from :data:`RECALL_DEMONSTRATIONS` demonstrations than the ``general`` reading (issue #13's
    recall is kept), the one with the best mean gain over the grid (ties: the cheaper) — unless the
    :data:`CONVENTIONAL` policy is within one standard error of it (``gap`` ≤ ``error``): then the convention
    is kept, for these tasks cannot tell the two apart. None when no policy keeps the recall."""
    best = best_policy(policies)
    conventional = policies.get(policy_name(*CONVENTIONAL))
    if best is None or conventional is None or not conventional["qualifies"]:
        return best
    return policy_name(*CONVENTIONAL) if within_one_error(conventional) else best
