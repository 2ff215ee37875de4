"""Speed of social force: writes benchmarks/results/social.json (``.venv/bin/python benchmarks/bench_social.py``).

* one ``SocialForce.update`` plus ``ellipse()`` with 100 samples in the window (a hand tracked at about
  133 Hz, the thesis's 0.75 s window), timed one call at a time: median and p99 against the 100 µs target;
* the peer, measured in the same run: what one writes first, a deque of samples turned into an array each
  update, ``numpy.cov`` and ``numpy.linalg.eigh``;
* the field at 10,000 points (a particle display, Figure 3.8) and three agents combined;
* a peer-role decision over the six subtasks of examples/workbench-blocks.yaml.
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path

import numpy as np

from supportive import examples
from supportive.social import Candidate, ForceField, PeerPolicy, SocialForce

TARGET_SECONDS = 100e-6
WINDOW = 0.75
SAMPLES_IN_WINDOW = 100
STEP = WINDOW / (SAMPLES_IN_WINDOW - 0.5)  # 100 samples in [t - 0.75, t]


def hand(count: int, seed: int) -> np.ndarray:
    """A wandering hand on the workbench: a smooth random walk, metres."""
    rng = np.random.default_rng(seed)
    return np.array([0.9, 0.35]) + np.cumsum(rng.normal(0.0, 0.002, size=(count, 2)), axis=0)


def timed(step: Callable[[int], object], count: int) -> dict[str, float]:
    """Median, p99 and mean of ``step(i)`` for ``i`` in ``range(count)``, one call at a time."""
    seconds = np.empty(count)
    for i in range(count):
        started = time.perf_counter_ns()
        step(i)
        seconds[i] = (time.perf_counter_ns() - started) * 1e-9
    return {
        "median_seconds": float(np.median(seconds)),
        "p99_seconds": float(np.percentile(seconds, 99)),
        "mean_seconds": float(seconds.mean()),
        "calls": count,
    }


def ours(positions: np.ndarray, warmup: int) -> tuple[dict[str, float], int]:
    force = SocialForce(window=WINDOW, min_radius=0.05)
    for i in range(warmup):
        force.update(i * STEP, positions[i])

    def step(i: int) -> object:
        force.update((warmup + i) * STEP, positions[warmup + i])
        return force.ellipse()

    return timed(step, len(positions) - warmup), len(force)


def naive(positions: np.ndarray, warmup: int) -> dict[str, float]:
    window: deque[tuple[float, float, float]] = deque()

    def add(i: int) -> None:
        t = i * STEP
        window.append((t, float(positions[i][0]), float(positions[i][1])))
        while window[0][0] < t - WINDOW:
            window.popleft()

    for i in range(warmup):
        add(i)

    def step(i: int) -> object:
        add(warmup + i)
        xy = np.array([(x, y) for _, x, y in window])
        values, vectors = np.linalg.eigh(np.cov(xy.T, bias=True))
        latest = xy[-1]
        return 2 * latest - xy.mean(axis=0), 2 * np.sqrt(np.maximum(values, 0.0)), vectors

    return timed(step, len(positions) - warmup)


def field_speed(positions: np.ndarray, seed: int) -> dict[str, object]:
    particles = np.random.default_rng(seed).uniform([0.0, 0.0], [1.83, 0.762], size=(10_000, 2))
    force = SocialForce(window=WINDOW, min_radius=0.05)
    people = ForceField(window=WINDOW, min_radius=0.05)
    for i in range(SAMPLES_IN_WINDOW):
        force.update(i * STEP, positions[i])
        for k, name in enumerate(("alice", "bob", "carol")):
            people.update(name, i * STEP, positions[i] + [0.4 * (k - 1), 0.0])
    return {
        "points": len(particles),
        "one_agent": timed(lambda _: force.field(particles), 200),
        "three_agents": timed(lambda _: people.field(particles), 200),
    }


def decision_speed(positions: np.ndarray) -> dict[str, object]:
    spec = examples.load("workbench-blocks")
    candidates = [Candidate.from_action(a, current=i == 0) for i, a in enumerate(spec.actions)]
    person = SocialForce(window=WINDOW, min_radius=0.05)
    for i in range(SAMPLES_IN_WINDOW):
        person.update(i * STEP, positions[i])
    policy = PeerPolicy(switch_margin=0.2, halt_below=-0.5, seed=0)
    return {"candidates": len(candidates), **timed(lambda _: policy.decide(candidates, person), 2000)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "social.json")
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--calls", type=int, default=20_000)
    args = parser.parse_args()
    warmup = 2 * SAMPLES_IN_WINDOW
    positions = hand(warmup + args.calls, args.seed)
    mine, in_window = ours(positions, warmup)
    theirs = naive(positions, warmup)
    result = {
        "benchmark": "social",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "seed": args.seed,
        "samples_in_window": in_window,
        "target_seconds": TARGET_SECONDS,
        "update_plus_ellipse": mine,
        "meets_target": mine["p99_seconds"] <= TARGET_SECONDS,
        "peer": "deque of samples, numpy.array + numpy.cov + numpy.linalg.eigh per update",
        "peer_update_plus_ellipse": theirs,
        "peer_over_ours_median": theirs["median_seconds"] / mine["median_seconds"],
        "field": field_speed(positions, args.seed),
        "peer_role_decision": decision_speed(positions),
    }
    print(
        f"update + ellipse, {in_window} samples: median {mine['median_seconds'] * 1e6:.1f} us, p99 "
        f"{mine['p99_seconds'] * 1e6:.1f} us (target {TARGET_SECONDS * 1e6:.0f} us: "
        f"{'met' if result['meets_target'] else 'missed'}); naive peer median "
        f"{theirs['median_seconds'] * 1e6:.1f} us"
    )
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")


if __name__ == "__main__":
    main()
