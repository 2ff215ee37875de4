"""How often the default learner sets a step of clean demonstrations aside (``make bench``): writes
benchmarks/results/clean-slips.json.

Issue #23's property: for random nested chain/clique structures (3–10 actions, the ``ikea`` and ``uniform``
profiles) and random partial orders (4–9 actions in 2–3 interleaved chains with 0–3 cross constraints), n = 1 …
200 demonstrations drawn uniformly from the valid executions, every demonstration is admitted and no step is set
aside. The tests (tests/learning/test_noise.py) pin a fixed sample of that distribution; no test of a statistical
learner can promise the property for every sample (a clean sample can avoid an arrangement by chance, and the
slip test works at the ``evidence`` level), so this measures how often it fails over fresh draws of the same
distribution: the share of tasks with a step set aside or a demonstration refused, with its 95 % upper bound
(Clopper–Pearson), by kind of task and by number of demonstrations, and the draws that failed (to replay them).
A rate, not a test.
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np
from scipy.stats import beta

from supportive.generate import random_partial_order, random_structure
from supportive.learning import HTNLearner
from supportive.tasks.htn import sample_ordering


def draw(rng: np.random.Generator, kind: str) -> tuple[dict[str, object], list[list[str]]]:
    """One task of the property's distribution and its clean demonstrations: what was drawn, and the draws."""
    n = int(rng.integers(1, 201))
    if kind == "nested":
        size, profile = int(rng.integers(3, 11)), str(rng.choice(["ikea", "uniform"]))
        structure = random_structure(size, rng, profile=profile)  # type: ignore[arg-type]
        demos = [[a for a, _ in sample_ordering(structure, rng)] for _ in range(n)]
        return {"kind": kind, "size": size, "profile": profile, "n": n}, demos
    size, chains, cross = int(rng.integers(4, 10)), int(rng.integers(2, 4)), int(rng.integers(0, 4))
    task = random_partial_order(size, rng, chains=chains, cross=cross)
    return {"kind": kind, "size": size, "chains": chains, "cross": cross, "n": n}, [list(task.sample(rng)) for _ in range(n)]


def upper_bound(failed: int, tasks: int) -> float:
    """The one-sided 95 % Clopper–Pearson upper bound of a rate seen ``failed`` times in ``tasks``."""
    return 1.0 if failed >= tasks else float(beta.ppf(0.95, failed + 1, tasks - failed))


def rate(failed: int, tasks: int) -> dict[str, float | int]:
    """A failure count as plain data: tasks, failed, their share and its 95 % upper bound."""
    return {
        "tasks": tasks,
        "failed": failed,
        "share": round(failed / tasks, 6) if tasks else 0.0,
        "upper_95": round(upper_bound(failed, tasks), 6) if tasks else 1.0,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "clean-slips.json")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--tasks-per-kind", type=int, default=2000,
        help="random tasks of each kind (nested, partial order): a sample size (the rate's precision), not a setting",
    )
    args = parser.parse_args()
    started = time.perf_counter()
    bands = ((1, 10), (11, 50), (51, 200))  # the numbers of demonstrations reported apart (inclusive)
    failures: list[dict[str, object]] = []
    counts: dict[str, list[int]] = {}  # key -> [failed, tasks]
    for number, kind in enumerate(("nested", "partial order")):
        for k in range(args.tasks_per_kind):
            rng = np.random.default_rng([args.seed, number, k])  # each task its own stream: a failure replays alone
            drawn, demos = draw(rng, kind)
            learner = HTNLearner().fit(demos)
            refused = sum(not learner.htn_.admits(demo) for demo in demos)
            failed = bool(learner.deviations_ or refused)
            n = len(demos)
            band = next(f"{low}-{high}" for low, high in bands if low <= n <= high)
            for key in ("all", kind, f"n {band}"):
                counts.setdefault(key, [0, 0])
                counts[key][0] += failed
                counts[key][1] += 1
            if failed:
                failures.append({**drawn, "task": k, "set_aside": len(learner.deviations_), "refused": refused})
    result = {
        "benchmark": "clean-slips",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "rates": {key: rate(*counts[key]) for key in ("all", "nested", "partial order", *(f"n {a}-{b}" for a, b in bands))},
        "failures": failures,
        "seconds": round(time.perf_counter() - started, 1),
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    for key, row in result["rates"].items():
        print(f"{key:14s} {row['failed']:4d} of {row['tasks']:5d}  share {row['share']:.4%}  95 % upper {row['upper_95']:.4%}")


if __name__ == "__main__":
    main()
