"""A sweep of the slip settings with the slip search's work shared (``make bench``): writes
benchmarks/results/sweep.json.

``supportive reproduce learner-settings`` learns each generated task's demonstrations under every setting of its
grid (18). What no slip setting changes — the hierarchies learned with each set of slips taken out, the
candidates, the hierarchies' scores for each ``order_concentration`` — is the same in every fit, and a
:class:`~supportive.learning.general.SlipSearchCache` shared by the fits learns it once. Here a sample of the
experiment's own trials (every :data:`STRIDE`-th of a full run, seed 0: tasks with mistakes and clean ones, by
people with and without habits) is learned under the whole grid twice, with one cache per task and with none
(the peer: the experiment before the cache), alternating which goes first after a warm-up; the results must be the same fit for fit, which the
benchmark checks. The ratio is the time without over the time with.
"""

from __future__ import annotations

import argparse
import json
import platform
from pathlib import Path

from supportive.experiments.learner_settings.measure import (
    DEFAULT_TRIALS,
    grid_settings,
    learn_grid,
    make_trials,
    trial_demonstrations,
)
from supportive.learning.general import SlipSearchCache

STRIDE = 150
"""Every how many trials of a full run one is timed: a sample size, not a setting."""


def sweep(demos: list[list[str]], cache: SlipSearchCache | None) -> tuple[float, list[object]]:
    """Seconds to learn ``demos`` under every setting of the grid (sharing ``cache``), and what each fit found."""
    seconds, found = 0.0, []
    for _, learner, fit_seconds in learn_grid(demos, cache):
        assert learner.noise_ is not None
        seconds += fit_seconds
        found.append((learner.deviations_, learner.noise_.as_dict(), learner.noise_.evaluations))
    return seconds, found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=Path, default=Path(__file__).parent / "results" / "sweep.json")
    args = parser.parse_args()
    trials = make_trials(DEFAULT_TRIALS, 0)[::STRIDE]
    sweep(trial_demonstrations(trials[0])[0], None)  # warm up: imports and first-use work are no one's cost
    rows = []
    for k, trial in enumerate(trials):
        demos, _, _ = trial_demonstrations(trial)
        if k % 2:  # alternate which goes first
            shared, together = sweep(demos, SlipSearchCache())
            alone, separate = sweep(demos, None)
        else:
            alone, separate = sweep(demos, None)
            shared, together = sweep(demos, SlipSearchCache())
        if together != separate:
            raise SystemExit(f"trial {trial.index}: the sweep with a shared cache found something else")
        rows.append({"trial": trial.index, **trial.params, "demonstrations": len(demos),
                     "seconds_without": round(alone, 3), "seconds_with": round(shared, 3)})
        print(f"trial {trial.index} ({trial.params['case']}, {trial.params['people']}, {len(demos)} demonstrations): "
              f"{alone:.2f} s without, {shared:.2f} s with")
    without = sum(r["seconds_without"] for r in rows)
    with_cache = sum(r["seconds_with"] for r in rows)
    result = {
        "benchmark": "sweep",
        "machine": {"python": platform.python_version(), "processor": platform.machine()},
        "settings": len(grid_settings()),
        "trials": rows,
        "seconds_without_cache": round(without, 2),
        "seconds_with_cache": round(with_cache, 2),
        "ratio": round(without / with_cache, 2),
        "same_results": True,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(result, indent=2) + "\n", encoding="utf-8")
    print(f"the whole sample: {without:.1f} s without a cache, {with_cache:.1f} s with: {without / with_cache:.1f}x")


if __name__ == "__main__":
    main()
