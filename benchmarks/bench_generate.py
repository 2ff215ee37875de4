"""Speed of the task generator (``make bench``): writes benchmarks/results/generate.json.

Cases: a random structure of 5,000 actions for each profile (``ikea``, ``uniform``), the median of several runs
after a warm-up. The goal (issue #3, once a timed test): well under a second each. The peer is the other
profile in the same run: ``ikea_over_uniform`` is the ratio of their medians.
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import time
from pathlib import Path

from supportive.generate import Profile, is_normalised, random_structure
from supportive.tasks.htn import leaf_actions

GOAL_SECONDS = 1.0
SIZE = 5000
REPEATS = 7


PROFILES: tuple[Profile, ...] = ("ikea", "uniform")


def measure(profile: Profile, seed: int) -> dict[str, float | int | bool]:
    random_structure(200, seed, profile=profile)  # warm up
    times = []
    for _ in range(REPEATS):
        started = time.perf_counter()
        node = random_structure(SIZE, seed, profile=profile)
        times.append(time.perf_counter() - started)
    median = statistics.median(times)
    return {
        "actions": len(set(leaf_actions(node))),
        "normalised": is_normalised(node),
        "median_seconds": median,
        "min_seconds": min(times),
        "runs": REPEATS,
        "goal_seconds": GOAL_SECONDS,
        "meets_goal": median <= GOAL_SECONDS,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "generate.json")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    cases = {profile: measure(profile, args.seed) for profile in PROFILES}
    ratio = cases["ikea"]["median_seconds"] / cases["uniform"]["median_seconds"]
    result = {
        "benchmark": "generate",
        "machine": {"python": platform.python_version(), "processor": platform.machine(), "system": platform.system()},
        "seed": args.seed,
        "peer": "the other profile in the same run",
        "cases": cases,
        "ikea_over_uniform": ratio,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    for profile, case in cases.items():
        print(f"{profile:8s} {SIZE} actions: median {case['median_seconds'] * 1000:8.1f} ms  ok={case['meets_goal']}")
    print(f"ikea / uniform: {ratio:.2f}")


if __name__ == "__main__":
    main()
