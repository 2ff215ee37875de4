from __future__ import annotations

import json
from pathlib import Path

import pytest

from supportive.experiments import get, names, run_experiment
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.experiments.support_tamp import FILES, PAIRINGS, SCENARIOS, THESIS, make_trials, run_trial


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    a, b = tmp_path_factory.mktemp("st-a"), tmp_path_factory.mktemp("st-b")
    run_experiment("support-tamp", trials=1, seed=3, output=a, progress=False)
    run_experiment("support-tamp", trials=1, seed=3, output=b, progress=False)
    return a, b


def test_registered() -> None:
    assert "support-tamp" in names() and get("support-tamp").default_trials == 30


def test_runs_are_deterministic_and_draw_both_figures(runs: tuple[Path, Path]) -> None:
    a, b = runs
    assert (a / "metrics.json").read_bytes() == (b / "metrics.json").read_bytes()
    for name in FILES.values():
        assert (a / name).read_bytes().startswith(PNG_SIGNATURE)
    timing = json.loads((a / "timing-summary.json").read_text())
    assert (
        set(timing) == set(SCENARIOS)
        and timing["heuristic"]["slow lead, fast support"]["support_planning_seconds"]["mean"] > 0
    )


def test_metrics_compare_every_pairing_alone_and_supported(runs: tuple[Path, Path]) -> None:
    metrics = json.loads((runs[0] / "metrics.json").read_text())
    assert metrics["tables"] == 1
    for scenario in SCENARIOS:
        for pairing in PAIRINGS:
            entry = metrics["scenarios"][scenario][pairing]
            alone, helped = entry["alone"], entry["supported"]
            assert alone["completed"] == helped["completed"] == 1
            assert alone["support_actions"]["mean"] == 0
            expected = round(100 * (1 - helped["makespan"]["mean"] / alone["makespan"]["mean"]), 1)
            assert entry["makespan_gain_percent"] == pytest.approx(expected, abs=0.11)
        slow_alone = metrics["scenarios"][scenario]["slow lead, fast support"]["alone"]["makespan"]["mean"]
        fast_alone = metrics["scenarios"][scenario]["fast lead, fast support"]["alone"]["makespan"]["mean"]
        assert slow_alone == pytest.approx(3 * fast_alone, rel=0.02)  # a third of the speed, all motion


def test_report_puts_the_thesis_beside(runs: tuple[Path, Path]) -> None:
    text = (runs[0] / "report.md").read_text()
    for number in ("44.0 %", "30.5 %", "9.8 %"):
        assert number in text
    assert "## Verdict" in text and "Scenario `heuristic`" in text and THESIS["makespan_gain_percent"]


def test_one_trial_is_the_same_whoever_runs_it() -> None:
    trial = make_trials(1, 11)[0]
    first, second = run_trial(trial), run_trial(trial)
    first.pop("timing"), second.pop("timing")
    assert first == second
