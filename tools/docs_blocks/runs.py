"""What the recorded runs are: their files' digests and how long they took (``docs/results/NAME-run.json``)."""

from __future__ import annotations

import hashlib
from typing import Any

from .common import RESULTS, Block, read_json


def digest(file: str) -> Block:
    """An inline block: the recorded file's sha256, shortened as the docs quote it (``922beaf9…9856cb71``)."""

    def make() -> str:
        full = hashlib.sha256((RESULTS / file).read_bytes()).hexdigest()
        return f"`{full[:8]}…{full[-8:]}`"

    return Block(f"docs/results/{file}", make, inline=True)


def _run(name: str) -> dict[str, Any]:
    """The ``run.json`` recorded beside ``docs/results/NAME.json``: where and how long the run took."""
    run: dict[str, Any] = read_json(RESULTS / f"{name}-run.json")
    return run


def _how_long(seconds: float) -> str:
    """``218.6 s`` or ``1,234.5 s (20.6 min)``."""
    return f"{seconds:,.1f} s" + (f" ({seconds / 60:.1f} min)" if seconds >= 600 else "")


def run_time(name: str) -> Block:
    """An inline block: how long the recorded run of ``name`` took, from its ``run.json``."""

    def make() -> str:
        run = _run(name)
        return f"{_how_long(run['seconds'])} of trials and summary ({run['backend']})"

    return Block(f"docs/results/{name}-run.json (supportive reproduce {name}: run.json)", make, inline=True)


TIMED = ("learner-settings", "selection-settings", "generalisation", "support-tamp", "active-learning")
"""The experiments whose recorded run kept its ``run.json`` (``docs/results/NAME-run.json``)."""


def recorded_run_times() -> str:
    """docs/experiments.md: the wall time of each recorded run that kept its ``run.json``."""
    runs = {name: _run(name) for name in TIMED}
    backends = sorted({run["backend"] for run in runs.values()})
    parts = [
        f"{name} {_how_long(run['seconds'])} ({run['trials']} trials)"
        for name, run in sorted(runs.items(), key=lambda item: -item[1]["seconds"])
    ]
    return (
        f"Trials and summary of the runs recorded with their `run.json` (`docs/results/NAME-run.json`; "
        f"{' and '.join(backends)}): {', '.join(parts)}.\n"
    )


BLOCKS: dict[str, Block] = {
    "recorded-run-times": Block(
        "docs/results/*-run.json (run.json of the recorded runs)", recorded_run_times
    ),
}
