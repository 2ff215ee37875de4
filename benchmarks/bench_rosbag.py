"""Reading contact events from a ROS bag (``make bench``): writes benchmarks/results/rosbag.json.

One hour of contact frames at 100 Hz (360,000 ``supportive_msgs/msg/ContactFrame`` messages in a rosbag2 MCAP
bag, each frame drawn from the IKEA chair's observation model) is read two ways, each in a fresh process so
its peak memory is its own:

* ours: ``read_contact_frames`` (what ``supportive infer --bag`` consumes), one frame at a time;
* the peer: the naive way, every message read and deserialized into a list first, then turned into frames.

Each way runs twice: once timed (and its peak resident set size taken from the kernel), once under
tracemalloc for the peak of Python allocations. A child that only imports the modules gives the baseline RSS.
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

HZ = 100
SECONDS = 3600
TARGET_SECONDS = 5.0  # "a few seconds" for the hour


def make_bag(path: Path, seed: int = 0) -> int:
    """The hour of frames; how many."""
    from supportive.examples import load
    from supportive.inference import ObservationModel
    from supportive.io.rosbag import BagWriter, write_contact_frames

    spec = load("ikea-chair")
    model = ObservationModel.from_spec(spec)
    rng = np.random.default_rng(seed)
    actions = [step.action for step in spec.demonstrations[0].steps]
    start = 1_704_067_200 * 1_000_000_000
    period = 1_000_000_000 // HZ

    def frames():  # type: ignore[no-untyped-def]
        for k in range(HZ * SECONDS):
            yield model.sample(actions[(k // 500) % len(actions)], rng), start + k * period

    with BagWriter(path, "mcap") as writer:
        return write_contact_frames(writer, frames())


def read_streaming(path: Path) -> tuple[int, int]:
    from supportive.io.rosbag import read_contact_frames

    frames = events = 0
    for moment, _ in read_contact_frames(path):
        frames += 1
        events += len(moment)
    return frames, events


def read_naive(path: Path) -> tuple[int, int]:
    from rosbags.highlevel import AnyReader

    with AnyReader([path]) as reader:
        connections = [c for c in reader.connections if c.topic == "/contacts"]
        messages = [(t, reader.deserialize(raw, c.msgtype)) for c, t, raw in reader.messages(connections)]
    frames = [(frozenset(m.events), t) for t, m in messages]  # type: ignore[attr-defined]
    return len(frames), sum(len(f) for f, _ in frames)


def child(mode: str, path: Path, trace: bool) -> dict[str, float]:
    import rosbags.highlevel  # noqa: F401  (the baseline imports what both ways import)

    import supportive.io.rosbag  # noqa: F401

    if trace:
        tracemalloc.start()
    started = time.perf_counter()
    frames, events = (
        (0, 0) if mode == "baseline" else (read_streaming if mode == "stream" else read_naive)(path)
    )
    seconds = time.perf_counter() - started
    result = {"frames": frames, "events": events, "seconds": seconds}
    if trace:
        result["tracemalloc_peak_mb"] = tracemalloc.get_traced_memory()[1] / 2**20
    result["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return result


def run_child(mode: str, path: Path, trace: bool) -> dict[str, float]:
    command = [sys.executable, __file__, "--child", mode, str(path), *(["--trace"] if trace else [])]
    done = subprocess.run(command, check=True, capture_output=True, text=True)
    data: dict[str, float] = json.loads(done.stdout)
    return data


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--child", nargs=2, metavar=("MODE", "BAG"))
    parser.add_argument("--trace", action="store_true")
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "rosbag.json")
    args = parser.parse_args()
    if args.child:
        print(json.dumps(child(args.child[0], Path(args.child[1]), args.trace)))
        return
    with tempfile.TemporaryDirectory() as tmp:
        bag = Path(tmp) / "hour"
        started = time.perf_counter()
        count = make_bag(bag)
        written = time.perf_counter() - started
        size = sum(p.stat().st_size for p in bag.iterdir()) / 2**20
        baseline = run_child("baseline", bag, False)
        ours, peer = run_child("stream", bag, False), run_child("naive", bag, False)
        ours_traced, peer_traced = run_child("stream", bag, True), run_child("naive", bag, True)
    assert ours["frames"] == peer["frames"] == count and ours["events"] == peer["events"]
    result = {
        "machine": platform.platform(),
        "python": platform.python_version(),
        "bag": {"frames": count, "hz": HZ, "seconds": SECONDS, "storage": "mcap", "size_mb": round(size, 1)},
        "write_seconds": round(written, 2),
        "baseline_rss_mb": round(baseline["peak_rss_mb"], 1),
        "ours": {
            "seconds": round(ours["seconds"], 2),
            "frames_per_second": round(count / ours["seconds"]),
            "peak_rss_mb": round(ours["peak_rss_mb"], 1),
            "tracemalloc_peak_mb": round(ours_traced["tracemalloc_peak_mb"], 2),
        },
        "naive_peer": {
            "seconds": round(peer["seconds"], 2),
            "peak_rss_mb": round(peer["peak_rss_mb"], 1),
            "tracemalloc_peak_mb": round(peer_traced["tracemalloc_peak_mb"], 2),
        },
        "rss_above_baseline_mb": {
            "ours": round(ours["peak_rss_mb"] - baseline["peak_rss_mb"], 1),
            "naive_peer": round(peer["peak_rss_mb"] - baseline["peak_rss_mb"], 1),
        },
        "tracemalloc_ratio_peer_to_ours": round(
            peer_traced["tracemalloc_peak_mb"] / ours_traced["tracemalloc_peak_mb"], 1
        ),
        "target_seconds": TARGET_SECONDS,
        "meets_target": ours["seconds"] < TARGET_SECONDS,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
