"""Transfer, one trial: one (task, seed) explored under every condition, leave-one-out over the 25 tasks.

Conditions (the other 24 tasks are the known ones):

* ``none`` — (a) no transfer: the 39 primitives, Q starts at 0;
* ``q`` — (b) flat Q-function transfer: the 39 primitives, Q starts at the other tasks' aggregated
  advantages (:func:`~.sources.aggregate`, ``max``) scaled by :data:`~.sources.PRIOR_SCALE` (a prior that
  orders untried options);
* ``cchtn`` — (c) (b) plus the macro actions of the other tasks' CC-HTNs applicable to the task;
* ``q_raw`` and ``cchtn_raw`` — (b) and (c) with the advantages unscaled (a failing-elsewhere option starts
  near −1, below every known option), to show how much the result depends on the prior's weight.
"""

from __future__ import annotations

import random
from typing import Any

from supportive.examples.food import transfer_names
from supportive.experiments.transfer.explore import Option, explore
from supportive.experiments.transfer.sources import (
    PRIOR_SCALE,
    dictionary,
    task_model,
    transfer_initial,
)
from supportive.experiments.trials import Trial, spawn_trials

__all__ = ["CONDITIONS", "MAX_EPISODES", "SEEDS", "STEP_CAP", "make_trials", "run_condition", "run_trial"]

CONDITIONS: dict[str, tuple[bool, bool, float]] = {
    "none": (False, False, 0.0),
    "q": (True, False, PRIOR_SCALE),
    "cchtn": (True, True, PRIOR_SCALE),
    "q_raw": (True, False, 1.0),
    "cchtn_raw": (True, True, 1.0),
}
"""Condition -> (Q transfer, macros, prior scale)."""

SEEDS = 4
"""Seeds per task in a full run (25 × 4 = 100 trials)."""
MAX_EPISODES = 5000
"""Episodes before a run is censored."""
STEP_CAP = 400
"""Primitive attempts per episode."""


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """Trial ``i`` explores task ``i mod 25`` (sorted names), repetition ``i // 25``."""
    names = transfer_names()
    params = [
        {"task": names[i % len(names)], "repeat": i // len(names), "max_episodes": MAX_EPISODES,
         "step_cap": STEP_CAP}
        for i in range(trials)
    ]  # fmt: skip
    return spawn_trials(seed, params)


def run_condition(
    task: str, condition: str, seed: int, *, max_episodes: int = MAX_EPISODES, step_cap: int = STEP_CAP
) -> dict[str, Any]:
    """Explore ``task`` under ``condition`` with random numbers from ``seed``; plain JSON."""
    transfer, macros, scale = CONDITIONS[condition]
    model = task_model(task)
    options: tuple[Option, ...] = tuple((a,) for a in dictionary())
    initial = None
    if transfer:
        options, initial = transfer_initial(task, macros, "max", scale)
    result = explore(
        model, options, random.Random(seed), initial=initial, max_episodes=max_episodes, step_cap=step_cap
    )
    return {
        "episodes": result.episodes,
        "censored": result.episodes is None,
        "episodes_run": result.episodes_run,
        "completed": result.completed,
        "paths_found": result.paths_found,
        "paths_known": result.paths_known,
        "options": len(options),
        "macros": len(options) - len(dictionary()),
        "macro_uses": result.macro_uses,
        "steps": result.steps,
    }


def run_trial(trial: Trial) -> dict[str, Any]:
    """Explore the trial's task under every condition (each with its own seed drawn from the trial's)."""
    p = trial.params
    rng = trial.rng()
    seeds = {c: int(rng.integers(2**62)) for c in CONDITIONS}
    model = task_model(p["task"])
    return {
        "task": p["task"],
        "repeat": p["repeat"],
        "actions": len(model.actions),
        "orderings": model.orderings,
        "conditions": {
            c: run_condition(p["task"], c, seeds[c], max_episodes=p["max_episodes"], step_cap=p["step_cap"])
            for c in CONDITIONS
        },
    }
