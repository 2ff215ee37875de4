from __future__ import annotations

import json
from pathlib import Path

import pytest

from supportive.experiments import get, names, run_experiment
from supportive.experiments.caregiver import FILES, THESIS
from supportive.experiments.plotting import PNG_SIGNATURE


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    a, b = tmp_path_factory.mktemp("cg-a"), tmp_path_factory.mktemp("cg-b")
    run_experiment("caregiver", trials=3, seed=5, output=a, progress=False)
    run_experiment("caregiver", trials=3, seed=5, output=b, progress=False)
    return a, b


def test_registered_with_the_thesis_sample_size() -> None:
    assert "caregiver" in names()
    assert get("caregiver").default_trials == 20 == THESIS["episodes"]


def test_runs_are_deterministic_and_write_the_three_figures(runs: tuple[Path, Path]) -> None:
    a, b = runs
    assert (a / "metrics.json").read_bytes() == (b / "metrics.json").read_bytes()
    for name in FILES.values():
        assert (a / name).read_bytes().startswith(PNG_SIGNATURE)


def test_metrics_hold_every_measure_per_type_and_condition(runs: tuple[Path, Path]) -> None:
    metrics = json.loads((runs[0] / "metrics.json").read_text())
    assert metrics["episodes"] == 3 and metrics["map"] == "house"
    damage = metrics["measures"]["damage_normalized"]
    assert set(damage) == set(THESIS["damage_normalized"])
    top = max(damage[label][c]["mean"] + 0 for label in damage for c in ("with", "without"))
    assert 0 < top <= 1.0
    for label in damage:
        steps = metrics["measures"]["steps_until_threshold"][label]
        cells = metrics["measures"]["cells_explored"][label]
        for condition in ("with", "without"):
            assert 1 <= steps[condition]["mean"] <= 200
            assert 1 <= cells[condition]["mean"] <= steps[condition]["mean"] + 1
            assert damage[label][condition]["sd"] >= 0
    # the most random novice is hurt more than the most goal-directed one
    assert damage["random motion"]["without"]["mean"] > damage["5% random"]["without"]["mean"]


def test_report_puts_the_thesis_tables_beside(runs: tuple[Path, Path]) -> None:
    text = (runs[0] / "report.md").read_text()
    for number in ("0.7346", "0.2291", "35.5", "97.05", "14.6", "24.45", "33.2"):
        assert number in text
    assert "## Verdict" in text and "Damage falls by more than half" in text
