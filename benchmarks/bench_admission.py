"""Generalisation with more clean data (``make bench``): writes benchmarks/results/admission.json.

Issue #23: learned by the default learner from n demonstrations drawn uniformly from the valid executions of
random tasks (nested chain/clique structures of the ``ikea`` and ``uniform`` profiles, and partial orders of
interleaved chains with cross constraints), the share of the valid executions the hierarchy admits should not
fall as n grows (on average over the tasks): more clean data must never make the model reject more correct
orders. A curve, not a test: each point is the mean over the tasks at that n, with the number of steps the
learner set aside as slips (0 on clean data) and the share of the demonstrations it admits (1).

Beside the default learner, the same learner making subtasks from :data:`COMPARED_SUBTASKS` demonstrations
on (``subtask_demonstrations``; the default is 2, chosen by ``supportive reproduce selection-settings``): the
former default, whose curve stepped down where it started making subtasks (docs/learning.md).
"""

from __future__ import annotations

import argparse
import itertools
import json
import platform
import time
from pathlib import Path
from typing import TypedDict

import numpy as np

from supportive.generate.mistakes import KnownTask, random_known_task
from supportive.learning import HTNLearner
from supportive.tasks.htn import HTN

SIZES = (1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 16, 24, 32, 64, 128, 200)
"""The numbers of demonstrations measured: every one up to 8, so that a step where the learner changes how it
reads few demonstrations shows (a doubling grid steps over 3), then doubling up to issue #23's 200."""
TASKS_PER_PROFILE = 8
"""Random tasks per profile: a sample size (the curve's precision), not a setting of the learner."""
STEPS = 7
"""Steps per task: few enough that every valid execution can be listed by brute force."""
COMPARED_SUBTASKS = 4
"""``subtask_demonstrations`` of the comparison curve: issue #13's value, the default before
``selection-settings`` chose one."""


class Drop(TypedDict):
    """A fall of the mean share from one measured n (``start``) to the next (``end``), ``by`` < 0, with the
    standard error of that mean change paired by task (how much of it the sample of tasks may explain)."""

    start: int
    end: int
    by: float
    standard_error: float


def valid_executions(task: KnownTask) -> list[list[str]]:
    """Every valid execution of a small task (by brute force over orders of its steps)."""
    steps = sorted({a for a in task.sample(0)})
    return [list(order) for order in itertools.permutations(steps) if task.admits(order)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "admission.json")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    started = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    curve: dict[str, dict[int, list[float]]] = {}
    slips: dict[int, int] = dict.fromkeys(SIZES, 0)
    own: dict[int, list[float]] = {n: [] for n in SIZES}
    compared: dict[int, list[float]] = {n: [] for n in SIZES}
    for profile in ("ikea", "uniform", "partial order"):
        curve[profile] = {n: [] for n in SIZES}
        for _ in range(TASKS_PER_PROFILE):
            task = random_known_task(profile, STEPS, rng)
            valid = valid_executions(task)
            demos = [task.sample(rng) for _ in range(max(SIZES))]
            for n in SIZES:
                learner = HTNLearner().fit(demos[:n])
                curve[profile][n].append(share_admitted(learner.htn_, valid))
                slips[n] += len(learner.deviations_)
                own[n].append(share_admitted(learner.htn_, demos[:n]))
                compared_htn = HTNLearner(subtask_demonstrations=COMPARED_SUBTASKS).fit(demos[:n]).htn_
                compared[n].append(share_admitted(compared_htn, valid))
    shares = {n: [x for p in curve for x in curve[p][n]] for n in SIZES}  # every task's, in one order
    means = {n: float(np.mean(shares[n])) for n in SIZES}
    drops = _drops(shares)
    compared_means = {n: float(np.mean(compared[n])) for n in SIZES}
    result = {
        "benchmark": "admission",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "tasks": {p: TASKS_PER_PROFILE for p in curve},
        "steps_per_task": STEPS,
        "mean_share_of_valid_executions_admitted": {str(n): round(v, 4) for n, v in means.items()},
        "by_profile": {p: {str(n): round(float(np.mean(v)), 4) for n, v in by_n.items()} for p, by_n in curve.items()},
        "steps_set_aside": {str(n): k for n, k in slips.items()},
        "own_demonstrations_admitted": {str(n): round(float(np.mean(v)), 4) for n, v in own.items()},
        "drops": drops,
        "compared_threshold": {
            "subtask_demonstrations": COMPARED_SUBTASKS,
            "mean_share_of_valid_executions_admitted": {str(n): round(v, 4) for n, v in compared_means.items()},
            "drops": _drops(compared),
        },
        "seconds": round(time.perf_counter() - started, 1),
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print("n:        " + " ".join(f"{n:6d}" for n in SIZES))
    print("admitted: " + " ".join(f"{means[n]:6.3f}" for n in SIZES))
    print("set aside:" + " ".join(f"{slips[n]:6d}" for n in SIZES))
    print(f"from {COMPARED_SUBTASKS}:   " + " ".join(f"{compared_means[n]:6.3f}" for n in SIZES))
    falls = "".join(f"; {d['start']}→{d['end']}: {d['by']:+.3f} ± {d['standard_error']:.3f}" for d in drops)
    print(f"non-decreasing on average: {not drops}{falls}")


def share_admitted(htn: HTN, executions: list[list[str]]) -> float:
    """The share of ``executions`` that ``htn`` admits."""
    return sum(htn.admits(e) for e in executions) / len(executions)


def _drops(shares: dict[int, list[float]]) -> list[Drop]:
    """Where the mean share (``shares``: every task's by n, in increasing n, the tasks in one order) falls from
    one measured n to the next, with the paired standard error of the change."""
    drops = []
    for a, b in itertools.pairwise(shares):
        change = np.subtract(shares[b], shares[a])
        if change.mean() < -1e-12:
            error = float(change.std(ddof=1) / np.sqrt(len(change)))
            drops.append(Drop(start=a, end=b, by=round(float(change.mean()), 4), standard_error=round(error, 4)))
    return drops


if __name__ == "__main__":
    main()
