"""Transfer, one trial: one (task, seed) explored under every condition, leave-one-out over the 25 tasks.

Conditions (the other 24 tasks are the known ones):

* ``none`` — (a) no transfer: the 39 primitives, Q starts at 0;
* ``q`` — (b) flat Q-function transfer: the 39 primitives, Q starts at the other tasks' aggregated
  advantages (:func:`~.sources.aggregate`, ``max``) scaled by :data:`~.sources.PRIOR_SCALE` (a prior that
  orders untried options);
* ``cchtn`` — (c) (b) plus the macro actions of the other tasks' CC-HTNs applicable to the task;
* ``q_raw`` and ``cchtn_raw`` — (b) and (c) with the advantages unscaled (a failing-elsewhere option starts
  near −1, below every known option), to show how much the result depends on the prior's weight.

The macro conditions run under each reading of what a CC-HTN macro performs (:data:`READINGS`): any
admissible order of its subtask (default) or always one fixed order. Every condition draws its own seed
from the trial's, the same under every reading (common random numbers), so a reading's numbers do not
depend on which other readings run.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from supportive.examples.food import transfer_names
from supportive.experiments.readings import Reading, reading_names
from supportive.experiments.transfer.explore import Option, explore
from supportive.experiments.transfer.sources import (
    PRIOR_SCALE,
    dictionary,
    task_model,
    transfer_initial,
)
from supportive.experiments.trials import Trial, spawn_trials

__all__ = [
    "CONDITIONS",
    "MACRO_CONDITIONS",
    "MAX_EPISODES",
    "READINGS",
    "SEEDS",
    "STEP_CAP",
    "make_trials",
    "run_condition",
    "run_trial",
]

CONDITIONS: dict[str, tuple[bool, bool, float]] = {
    "none": (False, False, 0.0),
    "q": (True, False, PRIOR_SCALE),
    "cchtn": (True, True, PRIOR_SCALE),
    "q_raw": (True, False, 1.0),
    "cchtn_raw": (True, True, 1.0),
}
"""Condition -> (Q transfer, macros, prior scale)."""
MACRO_CONDITIONS = tuple(c for c, (_, macros, _) in CONDITIONS.items() if macros)
"""The conditions whose numbers depend on the reading (they use macros)."""

READINGS = (
    Reading(
        "any-order",
        "a clique's macro performs any admissible order of its subtask, drawn uniformly each time",
        "§2.1.7.4's macros are \"produced by the CC-HTNs\" of the other tasks, and a CC-HTN's clique stands for "
        "every order of its children (§2.1.4): a macro that always ran one order would be a chain, which the "
        "CC-HTN did not learn. The closest reading, so the default.",
    ),
    Reading(
        "fixed-order",
        "every macro performs one fixed order (its subtask's learned order, `MacroAction.actions`)",
        "A macro action as one stored action sequence; the thesis does not say how a clique's macro orders "
        "its children.",
    ),
)
"""What a CC-HTN macro performs, as named readings; the first (``any-order``) is the default."""
ORDERS = {"any-order": "any", "fixed-order": "fixed"}

SEEDS = 4
"""Seeds per task in a full run (25 × 4 = 100 trials)."""
MAX_EPISODES = 5000
"""Episodes before a run is censored."""
STEP_CAP = 400
"""Primitive attempts per episode."""


def make_trials(trials: int, seed: int, readings: Sequence[str] | None = None) -> tuple[Trial, ...]:
    """Trial ``i`` explores task ``i mod 25`` (sorted names), repetition ``i // 25``, under ``readings``
    (default: all of :data:`READINGS`)."""
    names = transfer_names()
    chosen = list(readings if readings is not None else reading_names(READINGS))
    params = [
        {"task": names[i % len(names)], "repeat": i // len(names), "max_episodes": MAX_EPISODES,
         "step_cap": STEP_CAP, "readings": chosen}
        for i in range(trials)
    ]  # fmt: skip
    return spawn_trials(seed, params)


def run_condition(
    task: str,
    condition: str,
    seed: int,
    *,
    max_episodes: int = MAX_EPISODES,
    step_cap: int = STEP_CAP,
    reading: str = READINGS[0].name,
) -> dict[str, Any]:
    """Explore ``task`` under ``condition`` (macros as ``reading`` says) with random numbers from ``seed``;
    plain JSON."""
    transfer, macros, scale = CONDITIONS[condition]
    model = task_model(task)
    options: tuple[Option, ...] = tuple(((a,),) for a in dictionary())
    initial = None
    if transfer:
        options, initial = transfer_initial(task, macros, "max", scale, ORDERS[reading])
    result = explore(
        model, options, seed, initial=initial, max_episodes=max_episodes, step_cap=step_cap
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
    """Explore the trial's task under every condition: those without macros once, those with macros under
    each of the trial's readings (each condition with its own seed drawn from the trial's)."""
    p = trial.params
    rng = trial.rng()
    seeds = {c: int(rng.integers(2**62)) for c in CONDITIONS}
    model = task_model(p["task"])
    budget = {"max_episodes": p["max_episodes"], "step_cap": p["step_cap"]}
    return {
        "task": p["task"],
        "repeat": p["repeat"],
        "actions": len(model.actions),
        "orderings": model.orderings,
        "conditions": {
            c: run_condition(p["task"], c, seeds[c], **budget)
            for c in CONDITIONS
            if c not in MACRO_CONDITIONS
        },
        "readings": {
            reading: {
                c: run_condition(p["task"], c, seeds[c], **budget, reading=reading) for c in MACRO_CONDITIONS
            }
            for reading in p.get("readings", reading_names(READINGS))
        },
    }
