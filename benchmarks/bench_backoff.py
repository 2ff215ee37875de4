"""The next-step predictor's back-off after an off-script step (``make bench``): writes
benchmarks/results/backoff.json.

The check that chose the design of :class:`~supportive.inference.predictor.StepPredictor`'s back-off, on
generated tasks only: random tasks of the three profiles (6–12 steps), demonstrations drawn uniformly from
their valid executions, and in a share of them one mistake put in (a step moved, moved early, repeated or
dropped, as :func:`~supportive.generate.mistakes.inject` does), 15 to learn from and 10 held out. Two
predictors learned from the same demonstrations are scored on the held-out steps (top-1 and mean log2
probability of the step that came next, the end included):

* **off-script back-off** (the default): the bigram weighs ``backoff`` after a step the tracker followed and
  ``off_script_backoff`` after one it read as off script, both fitted by cross-validation;
* **one weight**: the same weight in both cases, the best of the same cross-validation table's diagonal (the
  predictor before the change).

A comparison, not a test: each figure is the mean over every held-out step of every task.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import time
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from supportive.generate.mistakes import PROFILES, KnownTask, MistakeKind, inject, random_known_task
from supportive.inference import StepPredictor
from supportive.inference.tracker import END_LABEL

SHARES = (0.0, 0.4, 0.8)
"""Shares of the demonstrations with a mistake put in."""
MISTAKES: tuple[MistakeKind, ...] = ("moved", "early", "repeated", "dropped")
TASKS_PER_PROFILE = 20
TRAIN, HELD_OUT = 15, 10
SIZES = (6, 12)


def _demonstrations(task: KnownTask, n: int, share: float, rng: np.random.Generator) -> list[list[str]]:
    demos = [task.sample(rng) for _ in range(n)]
    if share > 0:
        for kind in MISTAKES:
            demos, _ = inject(demos, kind, share / len(MISTAKES), task.admits, rng)
    return demos


def _one_weight(fitted: StepPredictor, train: Sequence[Sequence[str]]) -> StepPredictor:
    """The predictor with one back-off weight, chosen on the diagonal of ``fitted``'s cross-validation table."""
    calibration = fitted.calibration_
    table = np.asarray(calibration.log2)
    diagonal = np.einsum("ijj->ij", table)
    row, column = np.unravel_index(int(np.argmax(diagonal)), diagonal.shape)
    smoothing, weight = fitted.smoothing_grid[row], fitted.backoff_grid[column]
    return StepPredictor(mode=fitted.learner_.reading_, smoothing=smoothing, backoff=weight, off_script_backoff=weight).fit(train)


def _score(predictor: StepPredictor, held: Sequence[Sequence[str]], totals: dict[str, float]) -> None:
    for demo in held:
        session = predictor.session()
        for truth in [*demo, END_LABEL]:
            guess = session.next_step()
            totals["top1"] += max(guess, key=guess.__getitem__) == truth
            totals["log2"] += math.log2(max(guess.get(truth, 0.0), 1e-300))
            totals["steps"] += 1
            if truth != END_LABEL:
                session.observe(truth)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "backoff.json")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    started = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    rows = []
    for share in SHARES:
        totals = {name: {"top1": 0.0, "log2": 0.0, "steps": 0.0} for name in ("off-script back-off", "one weight")}
        weights: list[tuple[float, float]] = []
        for profile in PROFILES:
            for _ in range(TASKS_PER_PROFILE):
                task = random_known_task(profile, int(rng.integers(SIZES[0], SIZES[1] + 1)), rng)
                train = _demonstrations(task, TRAIN, share, rng)
                held = _demonstrations(task, HELD_OUT, share, rng)
                fitted = StepPredictor().fit(train)
                weights.append((fitted.calibration_.backoff, fitted.calibration_.off_script_backoff))
                _score(fitted, held, totals["off-script back-off"])
                _score(_one_weight(fitted, train), held, totals["one weight"])
        rows.append(
            {
                "share_mistaken": share,
                "tasks": TASKS_PER_PROFILE * len(PROFILES),
                "held_out_steps": int(totals["one weight"]["steps"]),
                **{
                    name: {"top1": round(t["top1"] / t["steps"], 4), "log2": round(t["log2"] / t["steps"], 4)}
                    for name, t in totals.items()
                },
                "mean_backoff": round(float(np.mean([w[0] for w in weights])), 3),
                "mean_off_script_backoff": round(float(np.mean([w[1] for w in weights])), 3),
            }
        )
        last = rows[-1]
        print(
            f"share {share:.1f}: top-1 {last['one weight']['top1']:.3f} -> {last['off-script back-off']['top1']:.3f}, "
            f"log2 {last['one weight']['log2']:.3f} -> {last['off-script back-off']['log2']:.3f}"
        )
    result = {
        "benchmark": "backoff",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "steps_per_task": list(SIZES),
        "demonstrations": {"train": TRAIN, "held_out": HELD_OUT},
        "rows": rows,
        "seconds": round(time.perf_counter() - started, 1),
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
