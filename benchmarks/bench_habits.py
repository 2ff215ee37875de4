"""Slips set aside in clean demonstrations by people with habits (``make bench``): writes
benchmarks/results/habits.json.

Issue #23's property tests draw demonstrations uniformly from a task's valid executions. People do not: they
share a preferred order and each keeps close to it. Here every demonstration is still valid — nothing is a
slip — but drawn from a model of people with habits: the population's preferred order is one valid execution
(drawn uniformly); each person shifts every step's rank in it by their own normal noise (standard deviation
:data:`PERSON_NOISE`), then at each point picks among the steps the task allows next with weight
``exp(-strength * rank)``; ``strength`` 0 would be uniform over the allowed steps. Random tasks of 7 steps of
each profile, learned by the default learner from the first n of :data:`MOST` demonstrations: how many fits
set a step aside, and the share of steps set aside (0 is right). A measurement of a known limitation, not a
test (docs/learning.md).
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np

from bench_admission import STEPS, valid_executions
from supportive.generate.mistakes import PROFILES, random_known_task
from supportive.learning import HTNLearner

SIZES = (2, 5, 10, 20, 40)
"""Numbers of demonstrations learned from."""
MOST = max(SIZES)
"""Demonstrations drawn per task."""
STRENGTHS = (1.0, 2.0, 4.0)
"""How strongly people keep the preferred order (per rank of it, in the log weight of a step)."""
PERSON_NOISE = 0.5
"""Standard deviation of each person's own shift of each step's rank: people share the habit, not exactly."""
TASKS_PER_PROFILE = 8
"""Random tasks per profile and strength: a sample size, not a setting of the learner."""


def habitual_person(valid: list[list[str]], preferred: list[str], strength: float, rng: np.random.Generator) -> list[str]:
    """One valid execution by a person with the population's habit (see the module docstring)."""
    rank = {step: i + rng.normal(0.0, PERSON_NOISE) for i, step in enumerate(preferred)}
    done: list[str] = []
    left = valid
    while len(done) < len(preferred):
        allowed = sorted({execution[len(done)] for execution in left})
        weights = np.exp(-strength * np.array([rank[step] for step in allowed]))
        step = allowed[int(rng.choice(len(allowed), p=weights / weights.sum()))]
        done.append(step)
        left = [execution for execution in left if execution[len(done) - 1] == step]
    return done


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "habits.json")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    started = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    rows: dict[str, dict[str, dict[str, float]]] = {}
    for strength in STRENGTHS:
        fits_with_slips = dict.fromkeys(SIZES, 0)
        set_aside = dict.fromkeys(SIZES, 0)
        steps = dict.fromkeys(SIZES, 0)
        for profile in PROFILES:
            for _ in range(TASKS_PER_PROFILE):
                task = random_known_task(profile, STEPS, rng)
                valid = valid_executions(task)
                preferred = valid[int(rng.integers(len(valid)))]
                demos = [habitual_person(valid, preferred, strength, rng) for _ in range(MOST)]
                for n in SIZES:
                    found = len(HTNLearner().fit(demos[:n]).deviations_)
                    fits_with_slips[n] += found > 0
                    set_aside[n] += found
                    steps[n] += sum(map(len, demos[:n]))
        rows[str(strength)] = {
            str(n): {
                "fits_with_a_step_set_aside": fits_with_slips[n],
                "share_of_steps_set_aside": round(set_aside[n] / steps[n], 5),
            }
            for n in SIZES
        }
        print(f"strength {strength}: " + " ".join(f"{n}:{fits_with_slips[n]}/{len(PROFILES) * TASKS_PER_PROFILE}" for n in SIZES))
    result = {
        "benchmark": "habits",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "tasks_per_strength": len(PROFILES) * TASKS_PER_PROFILE,
        "steps_per_task": STEPS,
        "person_noise": PERSON_NOISE,
        "by_strength": rows,
        "seconds": round(time.perf_counter() - started, 1),
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
