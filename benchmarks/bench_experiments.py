"""Speed of the full ``active-learning`` experiment (``make bench``): writes benchmarks/results/experiments.json.

The peer is the same run in one process: the issue's target is the full experiment (50 trials) in under 60 s
with ``--workers 2`` on a 2-core machine, and the Dask speed-up is the in-process time over the 2-worker time
(cluster start-up included). Both runs must give the same metrics, which the benchmark checks.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path

from supportive.experiments import run_experiment

TARGET_SECONDS = 60.0


def timed(name: str, workers: int) -> tuple[float, dict[str, object]]:
    """Wall-clock seconds of one full run (trials, summary and report; no files) and its metrics."""
    started = time.perf_counter()
    result = run_experiment(name, workers=workers, progress=False)
    return time.perf_counter() - started, result.metrics


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "experiments.json")
    args = parser.parse_args()
    parallel, parallel_metrics = timed("active-learning", 2)
    serial, serial_metrics = timed("active-learning", 1)
    if parallel_metrics != serial_metrics:
        raise SystemExit("active-learning: the 2-worker and in-process runs gave different metrics")
    result = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count()},
        "active_learning": {
            "trials": serial_metrics["trials"],
            "workers_2_seconds": round(parallel, 2),
            "in_process_seconds": round(serial, 2),
            "dask_speedup": round(serial / parallel, 2),
            "target_seconds": TARGET_SECONDS,
            "meets_target": parallel < TARGET_SECONDS,
        },
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
