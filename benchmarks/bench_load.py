"""Speed of reading and writing task files (``make bench``): writes benchmarks/results/load.json.

Case: the largest benchmark task (``generate_task(5000, 0, demonstrations=4)``, about 830 KB of YAML), the
median of several runs after a warm-up. Peers in the same run: PyYAML's own loaders on the same text, which
check nothing — its Python ``SafeLoader`` (what ``supportive.io.safe_load`` was built on until it parsed with
libyaml) and its ``CSafeLoader``; ``read_over_python`` and ``read_over_libyaml`` are the ratios of
``parse_task_string`` (the limits, every field validated, the task built) to their medians. Writing:
``dump_task`` against ``yaml.dump`` with PyYAML's Python ``SafeDumper`` on the same data.
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import time
from collections.abc import Callable
from pathlib import Path

import yaml

from supportive.generate import generate_task
from supportive.io.taskfile import dump_task, parse_task_string, task_to_dict

SIZE = 5000
DEMONSTRATIONS = 4
REPEATS = 5


def median_seconds(run: Callable[[], object]) -> float:
    """The median of :data:`REPEATS` timed runs after one untimed."""
    run()
    times = []
    for _ in range(REPEATS):
        started = time.perf_counter()
        run()
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "load.json")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    spec = generate_task(SIZE, args.seed, demonstrations=DEMONSTRATIONS)
    text = dump_task(spec, "yaml")
    data = task_to_dict(spec)
    assert parse_task_string(text, "yaml") == spec
    cases = {
        "read": median_seconds(lambda: parse_task_string(text, "yaml")),
        "python_safe_load": median_seconds(lambda: yaml.load(text, Loader=yaml.SafeLoader)),
        "libyaml_safe_load": median_seconds(lambda: yaml.load(text, Loader=yaml.CSafeLoader)),
        "write": median_seconds(lambda: dump_task(spec, "yaml")),
        "python_safe_dump": median_seconds(
            lambda: yaml.dump(data, Dumper=yaml.SafeDumper, sort_keys=False, allow_unicode=True, width=110)
        ),
    }
    result = {
        "benchmark": "load",
        "machine": {"python": platform.python_version(), "processor": platform.machine(), "system": platform.system()},
        "seed": args.seed,
        "task": {"actions": SIZE, "demonstrations": DEMONSTRATIONS, "yaml_bytes": len(text.encode())},
        "peer": "PyYAML's loaders and dumper on the same text and data, in the same run",
        "median_seconds": cases,
        "runs": REPEATS,
        "read_over_python": cases["read"] / cases["python_safe_load"],
        "read_over_libyaml": cases["read"] / cases["libyaml_safe_load"],
        "write_over_python": cases["write"] / cases["python_safe_dump"],
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n")
    for name, seconds in cases.items():
        print(f"{name:18s} {seconds * 1000:8.1f} ms")
    print(f"read / Python safe_load {result['read_over_python']:.2f}, read / libyaml safe_load "
          f"{result['read_over_libyaml']:.2f}, write / Python safe_dump {result['write_over_python']:.2f}")


if __name__ == "__main__":
    main()
