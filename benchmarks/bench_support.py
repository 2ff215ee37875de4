"""Speed of the support planner (``make bench``): writes benchmarks/results/support.json.

One support decision (§3.2.7) on the thesis-size circuit task — 14 pieces on the table, Π_T of 31 known
plans — is timed over 200 hypothetical environments (target: under 1 s on one core) and over 400 and 800,
in this process and with 2 local worker processes (the pool already started, as it is during a run). The
peer of the 2-worker figure is the in-process decision on the same tables and seeds: the speed-up is their
ratio. Scores are checked equal in both, so the choice never depends on the number of workers.

Run: ``.venv/bin/python benchmarks/bench_support.py``
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from pathlib import Path
from typing import Any

from supportive.envs.circuits.scenario import thesis_scenario
from supportive.planning import SupportPlanner, SupportProblem

TARGET_SECONDS = 1.0
SIZES = (200, 400, 800)


def time_decisions(tables: int, environments: int, workers: int) -> tuple[list[float], list[tuple[float, ...]]]:
    """Seconds per decision, and the scores, for ``tables`` random tables (3 seeds each)."""
    seconds: list[float] = []
    scores: list[tuple[float, ...]] = []
    for table in range(tables):
        scenario = thesis_scenario(table)
        plans = scenario.plans()
        problem = SupportProblem.of(scenario.world, plans)
        with SupportPlanner("conservative", environments=environments, workers=workers).fit(problem) as planner:
            planner.decide(problem, seed=999)  # start the pool, warm the world's memories
            for seed in range(3):
                began = time.perf_counter()
                decision = planner.decide(problem, seed)
                seconds.append(time.perf_counter() - began)
                scores.append(decision.scores)
    return seconds, scores


def summary(seconds: list[float]) -> dict[str, Any]:
    return {
        "decisions": len(seconds),
        "median_seconds": round(statistics.median(seconds), 4),
        "max_seconds": round(max(seconds), 4),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "support.json")
    parser.add_argument("--tables", type=int, default=4)
    args = parser.parse_args()
    runs: dict[str, Any] = {}
    for size in SIZES:
        one, scores_one = time_decisions(args.tables, size, 1)
        two, scores_two = time_decisions(args.tables, size, 2)
        runs[str(size)] = {
            "one_process": summary(one),
            "two_workers": summary(two),
            "speedup_two_workers": round(statistics.median(one) / statistics.median(two), 2),
            "same_scores": scores_one == scores_two,
        }
    result = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count()},
        "task": "thesis-size circuit task (two cells, switch, LED; 14 pieces), conservative weights",
        "plans": len(thesis_scenario(0).plans()),
        "environments": runs,
        "target_seconds_200": TARGET_SECONDS,
        "meets_target": runs["200"]["one_process"]["max_seconds"] < TARGET_SECONDS,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
