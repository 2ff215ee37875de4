"""A toy experiment for the registry and runner tests (in process only: test modules are not importable by
dask workers)."""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import pytest

from supportive.experiments import Experiment, Trial, spawn_trials


def make_trials(trials: int, seed: int) -> tuple[Trial, ...]:
    return spawn_trials(seed, [{"scale": 10} for _ in range(trials)])


def run_trial(trial: Trial) -> dict[str, Any]:
    return {"index": trial.index, "draw": int(trial.rng().integers(trial.params["scale"] * 1000))}


def run_timed_trial(trial: Trial) -> dict[str, Any]:
    """Like :func:`run_trial`, plus a wall-clock measurement under the reserved ``timing`` key."""
    started = time.perf_counter()
    result = run_trial(trial)
    return {**result, "timing": {"index": trial.index, "seconds": time.perf_counter() - started}}


def summarize(results: Sequence[Mapping[str, Any]]) -> dict[str, Any]:
    assert all("timing" not in r for r in results), "the runner must keep timings from summarize"
    return {"draws": [r["draw"] for r in results], "indices": [r["index"] for r in results]}


def report(metrics: Mapping[str, Any]) -> str:
    return f"# toy\n\ndraws: {metrics['draws']} (thesis: {metrics['thesis']['answer']})\n"


def plots(metrics: Mapping[str, Any], directory: Path) -> list[Path]:
    return []


def timing_report(timings: list[dict[str, Any]], directory: Path) -> list[Path]:
    path = directory / "timing.md"
    path.write_text(f"# toy timings\n\n{len(timings)} trials\n", encoding="utf-8")
    return [path]


def headline(metrics: Mapping[str, Any]) -> list[tuple[str, str, str]]:
    return [("draws", str(len(metrics["draws"])), "–")]


def _toy(name: str = "toy-experiment", **changes: Any) -> Experiment:
    fields: dict[str, Any] = {
        "name": name,
        "title": "A toy",
        "reference": "nowhere",
        "thesis": {"answer": 42},
        "default_trials": 5,
        "make_trials": make_trials,
        "run_trial": run_trial,
        "summarize": summarize,
        "report": report,
        "plots": plots,
        "headline": headline,
    }
    fields.update(changes)
    return Experiment(**fields)


@pytest.fixture
def toy() -> Callable[..., Experiment]:
    """``toy(name="toy-experiment", **field_changes)``: a toy experiment (not registered)."""
    return _toy


@pytest.fixture
def timed_toy() -> Callable[..., Experiment]:
    """Like :func:`toy`, but its trials also return a wall-clock ``timing`` and it has a ``timing_report``."""
    return lambda name="toy-timed", **changes: _toy(
        name, **{"run_trial": run_timed_trial, "timing_report": timing_report, **changes}
    )
