"""Slips set aside in clean demonstrations by people with habits (``make bench``): writes
benchmarks/results/habits.json.

Issue #23's property tests draw demonstrations uniformly from a task's valid executions. People do not: they
share a preferred order and each keeps close to it (:class:`~supportive.generate.habits.HabitualPeople`).
Here every demonstration is still valid — nothing is a slip. Random tasks of 7 steps of each profile, learned
from the first n of :data:`MOST` demonstrations by the default learner and by the same learner reading every
admitted order as equally likely in its slip search (``order_concentration=inf``, the reading before the
habit model): how many fits set a step aside, and the share of steps set aside (0 is right). A measurement,
not a test (docs/learning.md).
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import time
from pathlib import Path

import numpy as np

from bench_admission import STEPS
from supportive.generate.habits import HABIT_STRENGTHS, HabitualPeople
from supportive.generate.mistakes import PROFILES, random_known_task
from supportive.learning import HTNLearner

SIZES = (2, 5, 10, 20, 40)
"""Numbers of demonstrations learned from."""
MOST = max(SIZES)
"""Demonstrations drawn per task."""
TASKS_PER_PROFILE = 8
"""Random tasks per profile and strength: a sample size, not a setting of the learner."""
LEARNERS = {"default": HTNLearner, "uniform reading": lambda: HTNLearner(order_concentration=math.inf)}
"""The learners compared: the default, and the slip search reading every admitted order as equally likely."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "habits.json")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    started = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    rows: dict[str, dict[str, dict[str, dict[str, float]]]] = {name: {} for name in LEARNERS}
    for strength in HABIT_STRENGTHS:
        fits_with_slips = {name: dict.fromkeys(SIZES, 0) for name in LEARNERS}
        set_aside = {name: dict.fromkeys(SIZES, 0) for name in LEARNERS}
        steps = dict.fromkeys(SIZES, 0)
        for profile in PROFILES:
            for _ in range(TASKS_PER_PROFILE):
                people = HabitualPeople.of(random_known_task(profile, STEPS, rng), strength, rng)
                demos = [people.demonstration(rng) for _ in range(MOST)]
                for n in SIZES:
                    steps[n] += sum(map(len, demos[:n]))
                    for name, learner in LEARNERS.items():
                        found = len(learner().fit(demos[:n]).deviations_)
                        fits_with_slips[name][n] += found > 0
                        set_aside[name][n] += found
        for name in LEARNERS:
            rows[name][str(strength)] = {
                str(n): {
                    "fits_with_a_step_set_aside": fits_with_slips[name][n],
                    "share_of_steps_set_aside": round(set_aside[name][n] / steps[n], 5),
                }
                for n in SIZES
            }
            tasks = len(PROFILES) * TASKS_PER_PROFILE
            print(f"{name}, strength {strength}: " + " ".join(f"{n}:{fits_with_slips[name][n]}/{tasks}" for n in SIZES))
    result = {
        "benchmark": "habits",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "tasks_per_strength": len(PROFILES) * TASKS_PER_PROFILE,
        "steps_per_task": STEPS,
        "by_learner": rows,
        "seconds": round(time.perf_counter() - started, 1),
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
