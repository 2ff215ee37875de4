"""Speed of the caregiver (``make bench``): writes benchmarks/results/caregiver.json.

* The thesis-size ``caregiver`` run (5 novice types × 2 conditions × 20 episodes of 200 steps, the default
  reading only) in one process (target: under 30 s on one core), and the full default run (100 episodes per
  type, without the caregiver and with it under each of the 3 readings) on 2 dask workers (issue 18's target:
  "a few minutes", here 180 s).
* One caregiver decision on the ``house`` map (target: under 1 ms): the median and 99th percentile over every
  decision of random-novice episodes, timed around ``Caregiver.decide``. The peer is the novice's own step
  (drawing an ε-greedy move and applying it) in the same episodes, to put the decision's cost in proportion.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import time
from pathlib import Path

from supportive.experiments import run_experiment
from supportive.safety import Caregiver, map_model
from supportive.worlds.household import EpsilonGreedyNovice, HouseholdWorld, load_map

EXPERIMENT_TARGET_SECONDS = 30.0
FULL_TARGET_SECONDS = 180.0
DECISION_TARGET_SECONDS = 1e-3


def decisions(episodes: int = 10, steps: int = 200) -> tuple[list[float], list[float]]:
    """Seconds per caregiver decision and per novice step, over ``episodes`` random-novice episodes."""
    grid = load_map("house")
    distances, priors = map_model(grid)
    decide: list[float] = []
    novice_steps: list[float] = []
    for seed in range(episodes):
        carer = Caregiver(distances, priors, seed=seed)
        novice = EpsilonGreedyNovice(distances, 1.0, seed)
        start = novice.start_cell()
        world = HouseholdWorld.start(grid, start, grid.caregiver_start if grid.caregiver_start != start else None)
        for _ in range(steps):
            if world.caregiver is not None:
                began = time.perf_counter()
                decision = carer.decide(world)
                decide.append(time.perf_counter() - began)
                for action in decision.actions:
                    world.act_caregiver(action)
            before = world.novice
            began = time.perf_counter()
            move = novice.act(before)
            world.move_novice(move)
            novice_steps.append(time.perf_counter() - began)
            carer.observe(before, move)
    return decide, novice_steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "caregiver.json")
    args = parser.parse_args()
    began = time.perf_counter()
    run_experiment("caregiver", trials=20, readings=["trajectory"], progress=False)
    experiment = time.perf_counter() - began
    began = time.perf_counter()
    full = run_experiment("caregiver", workers=2, progress=False)
    full_seconds = time.perf_counter() - began
    decide, novice = decisions()
    decide.sort()
    median = statistics.median(decide)
    result = {
        "machine": {"python": platform.python_version()},
        "experiment": {
            "episodes": 5 * 2 * 20,
            "seconds_one_process": round(experiment, 2),
            "target_seconds": EXPERIMENT_TARGET_SECONDS,
            "meets_target": experiment < EXPERIMENT_TARGET_SECONDS,
        },
        "full_run": {
            "episodes": full.trials * 5 * (1 + len(full.readings)),
            "readings": list(full.readings),
            "seconds_two_workers": round(full_seconds, 2),
            "load_average": [round(x, 2) for x in os.getloadavg()],
            "target_seconds": FULL_TARGET_SECONDS,
            "meets_target": full_seconds < FULL_TARGET_SECONDS,
        },
        "decision": {
            "map": "house",
            "decisions": len(decide),
            "median_seconds": round(median, 7),
            "p99_seconds": round(decide[int(0.99 * (len(decide) - 1))], 7),
            "max_seconds": round(decide[-1], 7),
            "target_seconds": DECISION_TARGET_SECONDS,
            "meets_target": median < DECISION_TARGET_SECONDS,
            "peer_novice_step_median_seconds": round(statistics.median(novice), 7),
            "decision_over_novice_step": round(median / statistics.median(novice), 1),
        },
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
