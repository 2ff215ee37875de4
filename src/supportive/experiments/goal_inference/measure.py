"""Goal inference, one trial: generate one IKEA-like task, then measure both filters on labelled streams.

Both models are built from the task's ground-truth structure. For each observation setting of
:data:`~.design.SETTINGS` the trial draws a synthetic observation model and a labelled stream
(:mod:`supportive.inference.synthetic`) and records how often each filter ranks the true subgoal and the true
enclosing subtask first, tied beliefs sharing the credit
(:func:`~supportive.inference.accuracy.filter_accuracy`). On the stream of :data:`~.design.TIMED_SETTING` it
also times every online update of both filters; those times go under the result's reserved ``timing`` key,
which the harness keeps out of the metrics because they are not deterministic.
"""

from __future__ import annotations

import dataclasses
import time
from typing import Any

import numpy as np

from supportive.errors import ExperimentError
from supportive.experiments.goal_inference.design import (
    EVENTS_PER_ACTION,
    MEAN_DURATION,
    SETTINGS,
    TIMED_SETTING,
    Setting,
    executions_for,
    steps_for,
)
from supportive.experiments.goal_inference.timing import cpu_name, describe_times, one_thread
from supportive.experiments.trials import Trial
from supportive.generate import ikea_task_set
from supportive.inference import FlatHMM, HierarchicalHMM, ObservationModel, ProgressHMM
from supportive.inference.accuracy import filter_accuracy
from supportive.inference.synthetic import SyntheticStream, synthetic_model, synthetic_stream
from supportive.inference.transitions import FlatTransitions, HierarchicalTransitions
from supportive.tasks.htn import HTN, internal_nodes
from supportive.tasks.spec import TaskSpec

__all__ = ["labelled_stream", "measure_setting", "measure_task", "operator_entries", "run_trial", "task_for"]

_SEED_BOUND = 2**31


def task_for(trial: Trial) -> TaskSpec:
    """The trial's task: one IKEA-like task of the trial's size drawn with the trial's seed by
    :func:`~supportive.generate.ikea_task_set` (like edge-reduction's tasks: redrawn until its mean primitive
    depth is within the thesis's 1.99–3.61), without demonstrations. Named ``ikea-<trial>-n<size>-s<task
    seed>``; ``generate_task(size, task_seed)`` rebuilds its structure.
    """
    return _draw(trial)[0]


def _draw(trial: Trial) -> tuple[TaskSpec, list[tuple[int, int]]]:
    """The trial's task, then for each setting the seeds of its observation model and stream."""
    rng = trial.rng()
    size = int(trial.params["subgoals"])
    (task,) = ikea_task_set(1, (size, size), rng, demonstrations=0)
    spec = dataclasses.replace(task, name=f"ikea-{trial.index + 1:03d}-{task.name.removeprefix('ikea-001-')}")
    draws = rng.integers(_SEED_BOUND, size=(len(SETTINGS), 2))
    return spec, [(int(a), int(b)) for a, b in draws]


def labelled_stream(
    spec: TaskSpec, setting: Setting, steps: int, seeds: tuple[int, int]
) -> tuple[ObservationModel, SyntheticStream]:
    """A synthetic observation model of ``spec``'s actions at ``setting`` (seeded with ``seeds[0]``) and a
    labelled stream of valid executions observed through it (``seeds[1]``), cut at ``steps``."""
    if spec.structure is None:
        raise ExperimentError(f"task {spec.name}: goal inference needs a ground-truth structure")
    model = synthetic_model(
        [action.id for action in spec.actions],
        events_per_action=EVENTS_PER_ACTION,
        overlap=setting.overlap,
        spurious=setting.spurious,
        strength=setting.strength,
        seed=seeds[0],
    )
    executions = executions_for(len(spec.actions), steps)
    stream = synthetic_stream(
        spec.structure, model, executions=executions, mean_duration=MEAN_DURATION, seed=seeds[1]
    )
    return model, SyntheticStream(stream.observations[:steps], stream.truth[:steps])


def operator_entries(transitions: FlatTransitions | HierarchicalTransitions) -> int:
    """The entries one update multiplies with to move the belief: the work of a transition step, and what
    makes the two filters' times differ (a deterministic stand-in for them).

    The flat filter keeps a dense subgoals × subgoals matrix (all its entries count); the hierarchical one a
    dense matrix up to :data:`~supportive.inference.transitions.DENSE_BELOW` subgoals, else the non-zeros of
    its sparse factors.
    """
    if isinstance(transitions, FlatTransitions):
        return int(transitions.matrix.size)
    return sum(int(f.size) if isinstance(f, np.ndarray) else int(f.nnz) for f in transitions.factors)


def measure_setting(
    htn: HTN, model: ObservationModel, stream: SyntheticStream, *, clock: bool = False
) -> tuple[dict[str, Any], dict[str, Any]]:
    """Both filters on one labelled stream.

    Returns:
        The accuracy (per model, the ``subgoal`` and ``subtask`` shares of
        :func:`~supportive.inference.accuracy.filter_accuracy`,
        rounded to 1e-6), and, with ``clock``, the timing (per model, :func:`~.timing.describe_times` of its
        updates plus ``build_ms``, the milliseconds it took to build the model); else an empty dict.
    """
    accuracy: dict[str, Any] = {}
    timing: dict[str, Any] = {}
    for name, kind in (("flat", FlatHMM), ("hierarchical", HierarchicalHMM)):
        started = time.perf_counter()
        hmm = kind(htn, model, mean_duration=MEAN_DURATION).fit()
        built = time.perf_counter() - started
        scored = filter_accuracy(hmm, stream.observations, stream.truth, timed=clock)
        accuracy[name] = {"subgoal": round(scored.subgoal, 6), "subtask": round(scored.subtask, 6)}
        if clock:
            timing[name] = {**describe_times(scored.seconds), "build_ms": round(built * 1e3, 3)}
    # the progress-aware tracker (issue 14); the streams chain several executions, so it may start again
    progress = ProgressHMM(htn, model, mean_duration=MEAN_DURATION, restart=True).fit()
    scored = filter_accuracy(progress, stream.observations, stream.truth)
    accuracy["progress"] = {"subgoal": round(scored.subgoal, 6), "subtask": round(scored.subtask, 6)}
    return accuracy, timing


def measure_task(spec: TaskSpec, steps: int, seeds: list[tuple[int, int]]) -> dict[str, Any]:
    """Measure one task: accuracy at every setting, and per-update times on the timed setting's stream.

    Args:
        spec: A task with a ground-truth ``structure``.
        steps: Most steps of each stream.
        seeds: For each setting of :data:`~.design.SETTINGS`, the seeds of its observation model and stream.

    Returns:
        Plain data: the task, its size and shape (``subgoals``, ``subtasks``, ``depth``), each model's
        ``transition_nonzeros`` (its non-zero transitions between subgoals) and ``operator_entries`` (see
        :func:`operator_entries`), ``steps`` and ``accuracy`` per setting, and, apart, ``timing``: the task,
        its ``subgoals`` and ``operator_entries`` (to plot the times against), per model the per-update times
        and build time (see :func:`measure_setting`), the steps timed, the setting and the processor.
        Everything but ``timing`` is determined by the arguments.

    Raises:
        ExperimentError: when the task has no structure.
    """
    if spec.structure is None:
        raise ExperimentError(f"task {spec.name}: goal inference needs a ground-truth structure")
    htn = HTN(spec.name, (spec.structure,))
    flat = FlatHMM(htn, mean_duration=MEAN_DURATION).fit().transitions_
    hierarchical = HierarchicalHMM(htn, mean_duration=MEAN_DURATION).fit().transitions_
    accuracy: dict[str, Any] = {}
    lengths: dict[str, int] = {}
    timing: dict[str, Any] = {}
    entries = {"flat": operator_entries(flat), "hierarchical": operator_entries(hierarchical)}
    for setting, pair in zip(SETTINGS, seeds, strict=True):
        model, stream = labelled_stream(spec, setting, steps, pair)
        timed = setting.key == TIMED_SETTING
        accuracy[setting.key], times = measure_setting(htn, model, stream, clock=timed)
        lengths[setting.key] = len(stream.truth)
        if timed:
            timing = {
                "task": spec.name,
                "subgoals": len(htn.leaves),
                "operator_entries": entries,
                **times,
                "steps": len(stream.truth),
                "setting": setting.key,
                "cpu": cpu_name(),
            }
    return {
        "task": spec.name,
        "subgoals": len(htn.leaves),
        "subtasks": sum(1 for root in htn.roots for _ in internal_nodes(root)),
        "depth": round(htn.mean_action_depth(), 6),
        "transition_nonzeros": {"flat": flat.nonzeros, "hierarchical": hierarchical.nonzeros},
        "operator_entries": entries,
        "steps": lengths,
        "accuracy": accuracy,
        "timing": timing,
    }


def run_trial(trial: Trial) -> dict[str, Any]:
    """Run one trial on one thread (see :func:`~.timing.one_thread`): draw its task (:func:`task_for`) and
    then its settings' seeds from the trial's seed, and measure the task (see :func:`measure_task`); the
    trial's ``index`` heads both the result and its ``timing``."""
    with one_thread():
        spec, seeds = _draw(trial)
        steps = int(trial.params.get("steps", steps_for(len(spec.actions))))
        result = measure_task(spec, steps, seeds)
        return {"index": trial.index, **result, "timing": {"index": trial.index, **result["timing"]}}
