"""Speed of the experiments (``make bench``): writes benchmarks/results/experiments.json.

* ``active-learning`` under its default reading (``pilot``), 50 trials: in one process (the peer) and with 2
  dask workers, cluster start-up included; the earlier issue's target is under 60 s with 2 workers on a
  2-core machine. Both runs must give the same metrics, which the benchmark checks.
* ``supportive reproduce all --workers 2`` (every experiment, every reading, full runs; issue 18's target:
  under 15 minutes on 2 cores). The machine may be shared, so the load average is recorded before and after
  (``os.getloadavg``: runnable processes, 1, 5 and 15 minutes); a load above the core count means other work
  competed for the cores. ``--skip-all`` leaves this part out, as ``make bench`` does (``make bench-reproduce-all``
  runs it).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import tempfile
import time
from pathlib import Path

from supportive.experiments import run_all, run_experiment

TARGET_SECONDS = 60.0
ALL_TARGET_SECONDS = 900.0


def timed(name: str, workers: int) -> tuple[float, dict[str, object]]:
    """Wall-clock seconds of one full run of the default reading (trials, summary and report; no files)."""
    started = time.perf_counter()
    result = run_experiment(name, workers=workers, progress=False, readings=["pilot"])
    return time.perf_counter() - started, result.metrics


def load() -> list[float]:
    """The load average over 1, 5 and 15 minutes."""
    return [round(x, 2) for x in os.getloadavg()]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "experiments.json")
    parser.add_argument("--skip-all", action="store_true", help="do not time reproduce all")
    args = parser.parse_args()
    before = load()
    parallel, parallel_metrics = timed("active-learning", 2)
    serial, serial_metrics = timed("active-learning", 1)
    if parallel_metrics != serial_metrics:
        raise SystemExit("active-learning: the 2-worker and in-process runs gave different metrics")
    result: dict[str, object] = {
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count()},
        "active_learning": {
            "trials": serial_metrics["trials"],
            "reading": "pilot",
            "workers_2_seconds": round(parallel, 2),
            "in_process_seconds": round(serial, 2),
            "dask_speedup": round(serial / parallel, 2),
            "load_before": before,
            "load_after": load(),
            "target_seconds": TARGET_SECONDS,
            "meets_target": parallel < TARGET_SECONDS,
        },
    }
    if not args.skip_all:
        before = load()
        started = time.perf_counter()
        with tempfile.TemporaryDirectory() as directory:
            results = run_all(workers=2, output=directory, progress=False)
        seconds = time.perf_counter() - started
        result["reproduce_all"] = {
            "workers": 2,
            "seconds": round(seconds, 1),
            "per_experiment_seconds": {r.experiment: round(r.seconds, 1) for r in results},
            "load_before": before,
            "load_after": load(),
            "target_seconds": ALL_TARGET_SECONDS,
            "meets_target": seconds < ALL_TARGET_SECONDS,
        }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
