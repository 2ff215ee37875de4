"""The online mistake detector by how many demonstrations it learned from (``make bench``): writes
benchmarks/results/detector-demos.json.

The detector flags a step the learned hierarchy refuses and that misses something it needs
(docs/inference.md); its threshold was chosen on tasks learned from 20 demonstrations. A hierarchy learned from
fewer has seen fewer of the valid orders, so it refuses more correct ones. For random tasks of each profile
(nested chains and cliques, ``ikea`` and ``uniform``, and partial orders of interleaved chains with cross
constraints), learned by :func:`~supportive.evaluation.detection_model` from the first n of the demonstrations
drawn uniformly from the valid executions, this measures on fresh executions: the share of the steps of valid
ones flagged (false alarms), the share of tasks with at least one, and the share of mistakes put in (a step done
early, one dropped, one repeated: :func:`~supportive.generate.inject`) that the detector flags at the mistaken
step or after it (a skip is named when the person moves past it). A curve, not a test.
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np

from supportive.evaluation import detection_model
from supportive.generate import inject, random_known_task
from supportive.generate.mistakes import MistakeKind
from supportive.inference import MistakeDetector

KINDS: tuple[MistakeKind, ...] = ("early", "dropped", "repeated")
"""The mistakes put in, one per execution."""


def flags(detector: MistakeDetector, execution: list[str]) -> list[int]:
    """The positions of the steps ``detector`` flags in ``execution`` (its end, where a skip is named, as
    position ``len(execution)``)."""
    detector.reset()
    flagged = [k for k, action in enumerate(execution) if detector.observe(action).mistake]
    return flagged + ([len(execution)] if detector.finish().mistake else [])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "detector-demos.json")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--sizes", type=int, nargs="+", default=[2, 3, 4, 6, 8, 12, 16, 20, 32],
        help="the numbers of demonstrations measured (20: what the threshold was chosen with)",
    )
    parser.add_argument(
        "--tasks-per-profile", type=int, default=20,
        help="random tasks per profile: a sample size (the curve's precision), not a setting of the detector",
    )
    parser.add_argument("--executions", type=int, default=6, help="fresh executions judged per task, clean and with each mistake")
    args = parser.parse_args()
    sizes: list[int] = args.sizes
    started = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    steps = dict.fromkeys(sizes, 0)
    alarms = dict.fromkeys(sizes, 0)
    tasks_alarmed = dict.fromkeys(sizes, 0)
    found = {n: dict.fromkeys(KINDS, 0) for n in sizes}
    put_in = {n: dict.fromkeys(KINDS, 0) for n in sizes}
    tasks = 0
    for profile in ("ikea", "uniform", "partial order"):
        for _ in range(args.tasks_per_profile):
            task = random_known_task(profile, int(rng.integers(6, 13)), rng)
            demos = [task.sample(rng) for _ in range(max(sizes))]
            clean = [task.sample(rng) for _ in range(args.executions)]
            slipped = {kind: inject(clean, kind, 1.0, task.admits, rng) for kind in KINDS}
            tasks += 1
            for n in sizes:
                detector = MistakeDetector(detection_model(demos[:n]))
                raised = [flags(detector, execution) for execution in clean]
                steps[n] += sum(len(execution) + 1 for execution in clean)
                alarms[n] += sum(map(len, raised))
                tasks_alarmed[n] += any(raised)
                for kind, (executions, mistakes) in slipped.items():
                    for mistake in mistakes:
                        put_in[n][kind] += 1
                        raised_here = flags(detector, executions[mistake.demonstration])
                        found[n][kind] += any(k >= mistake.position for k in raised_here)
    result = {
        "benchmark": "detector-demos",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "tasks": tasks,
        "executions_per_task": args.executions,
        "false_alarms_per_step": {str(n): round(alarms[n] / steps[n], 4) for n in sizes},
        "tasks_with_a_false_alarm": {str(n): round(tasks_alarmed[n] / tasks, 4) for n in sizes},
        "recall": {kind: {str(n): round(found[n][kind] / put_in[n][kind], 4) for n in sizes} for kind in KINDS},
        "seconds": round(time.perf_counter() - started, 1),
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print("n:            " + " ".join(f"{n:6d}" for n in sizes))
    print("false alarms: " + " ".join(f"{result['false_alarms_per_step'][str(n)]:6.3f}" for n in sizes))
    for kind in KINDS:
        print(f"{kind + ':':14s}" + " ".join(f"{result['recall'][kind][str(n)]:6.3f}" for n in sizes))


if __name__ == "__main__":
    main()
