"""Edge reduction, one trial: generate one IKEA-like task and measure three models of it.

For each task (§2.1.7.2: 10–100 subgoals, 4 random execution paths) the trial measures

* (a) ``learned``: the CC-HTN learned from the task's 4 demonstrations,
* (b) ``ground_truth``: the task's own structure, as an HTN,
* (c) ``all_orderings``: the CC-HTN learned from every valid ordering, when the structure admits at most
  ``orderings_limit`` of them (invariant 3 says this recovers the structure; ``recovered`` checks it),

and for each model: the edges of the flat task model over the same subgoals (``HTN.successor_pairs``, the
immediate-successor transitions a flat HMM needs), the CC-HTN's edges (``HTN.edge_count``, counted as
§2.1.7.3 counts them: k − 1 for a chain of k children, k for a clique of k children, plus the top-level
transitions of a partial hierarchy) and the mean depth of a primitive.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from supportive.errors import ExperimentError
from supportive.experiments.trials import Trial, spawn_trials
from supportive.generate import all_demonstrations, ikea_task_set
from supportive.learning.learner import HTNLearner
from supportive.tasks.htn import HTN, count_orderings
from supportive.tasks.spec import TaskSpec

__all__ = [
    "DEMONSTRATIONS",
    "ORDERINGS_LIMIT",
    "SIZES",
    "make_trials",
    "measure_task",
    "model_sizes",
    "run_trial",
    "task_for",
]

SIZES = (10, 100)
"""Least and most subgoals of a task (§2.1.7.2); a run's sizes are spread evenly over this range."""
DEMONSTRATIONS = 4
"""Random execution paths per task (§2.1.7.2)."""
ORDERINGS_LIMIT = 5000
"""Row (c) learns from every valid ordering of the tasks that admit at most this many."""


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    """One trial per task: sizes spread evenly over :data:`SIZES` (rounded), each trial with its own seed.

    >>> [t.params["subgoals"] for t in make_trials(3, 0)]
    [10, 55, 100]
    """
    sizes = np.linspace(SIZES[0], SIZES[1], trials).round().astype(int)
    params = [
        {"subgoals": int(size), "demonstrations": DEMONSTRATIONS, "orderings_limit": ORDERINGS_LIMIT}
        for size in sizes
    ]
    return spawn_trials(seed, params)


def task_for(trial: Trial) -> TaskSpec:
    """The trial's task: :func:`~supportive.generate.ikea_task_set` of one task of the trial's size, drawn
    with the trial's seed (redrawn, like the whole set, until its mean primitive depth is within the thesis's
    1.99–3.61). Its name, ``ikea-<trial>-n<size>-s<task seed>``, carries the int seed that
    ``generate_task(size, task_seed)`` rebuilds it from.
    """
    size = int(trial.params["subgoals"])
    (task,) = ikea_task_set(
        1, (size, size), trial.rng(), demonstrations=int(trial.params.get("demonstrations", DEMONSTRATIONS))
    )
    prefix = "ikea-001-"
    name = f"ikea-{trial.index + 1:03d}-{task.name.removeprefix(prefix)}"
    return dataclasses.replace(task, name=name)


def run_trial(trial: Trial) -> dict[str, Any]:
    """Run one trial: generate its task and measure it (see :func:`measure_task`)."""
    limit = int(trial.params.get("orderings_limit", ORDERINGS_LIMIT))
    return {"index": trial.index, **measure_task(task_for(trial), orderings_limit=limit)}


def model_sizes(htn: HTN) -> dict[str, Any]:
    """Sizes of one model of a task, as plain data.

    Keys: ``flat_edges`` (immediate-successor pairs, the flat model), ``htn_edges`` (:meth:`HTN.edge_count`,
    the CC-HTN), ``depth`` (mean primitive depth), ``roots`` and ``complete``.

    >>> from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode
    >>> clique = CliqueNode(tuple(ActionNode(a) for a in "abcd"))
    >>> sizes = model_sizes(HTN("t", (clique,)))
    >>> sizes["flat_edges"], sizes["htn_edges"], sizes["depth"]
    (12, 4, 1.0)
    >>> task = ChainNode((ActionNode("a"), CliqueNode(tuple(ActionNode(x) for x in "bcd")), ActionNode("e")))
    >>> sizes = model_sizes(HTN("t", (task,)))
    >>> sizes["flat_edges"], sizes["htn_edges"]
    (12, 5)
    """
    return {
        "flat_edges": len(htn.successor_pairs()),
        "htn_edges": htn.edge_count(),
        "depth": round(htn.mean_action_depth(), 6),
        "roots": len(htn.roots),
        "complete": htn.complete,
    }


def measure_task(spec: TaskSpec, *, orderings_limit: int = ORDERINGS_LIMIT) -> dict[str, Any]:
    """Measure the three models of one task (see the module docstring).

    Args:
        spec: A task with a ground-truth ``structure`` and demonstrations.
        orderings_limit: Learn from every valid ordering only when there are at most this many.

    Raises:
        ExperimentError: when the task has no structure or no demonstration.
    """
    if spec.structure is None:
        raise ExperimentError(f"task {spec.name}: edge reduction needs a ground-truth structure")
    if not spec.demonstrations:
        raise ExperimentError(f"task {spec.name}: edge reduction needs demonstrations to learn from")
    learned = HTNLearner().fit(spec).htn_
    truth = HTN(spec.name, (spec.structure,))
    orderings = count_orderings(spec.structure)
    every: dict[str, Any] | None = None
    if orderings <= orderings_limit:
        demos = all_demonstrations(spec.structure, orderings_limit)
        full = HTNLearner().fit(spec.with_demonstrations(demos)).htn_
        every = {
            **model_sizes(full),
            "demonstrations": orderings,
            "recovered": full.canonical() == truth.canonical(),
        }
    return {
        "task": spec.name,
        "subgoals": len(truth.leaves),
        "demonstrations": len(spec.demonstrations),
        "orderings": orderings,
        "orderings_limit": orderings_limit,
        "learned": model_sizes(learned),
        "ground_truth": model_sizes(truth),
        "all_orderings": every,
    }
