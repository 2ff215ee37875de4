from __future__ import annotations

import json
from pathlib import Path

import pytest

from supportive.envs.circuits.scenario import thesis_scenario
from supportive.envs.tabletop.leads import PlanFollowingLead
from supportive.envs.tabletop.team import run_team
from supportive.experiments import RunResult, get, names, run_experiment
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.experiments.support_tamp.measure import (
    PAIRINGS,
    READINGS,
    SCENARIOS,
    alone_plan,
    make_trials,
    run_trial,
    staged_floor,
)
from supportive.experiments.support_tamp.plots import FILES
from supportive.experiments.support_tamp.report import THESIS


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, RunResult]:
    """A one-table run: its folder and its result."""
    output = tmp_path_factory.mktemp("st-a")
    return output, run_experiment("support-tamp", trials=1, seed=3, output=output, progress=False)


def test_registered() -> None:
    assert "support-tamp" in names() and get("support-tamp").default_trials == 30
    assert [r.name for r in get("support-tamp").readings] == ["duration", "search-aware"]


def test_a_run_draws_both_figures(runs: tuple[Path, RunResult]) -> None:
    a, _ = runs
    for name in FILES.values():
        assert (a / name).read_bytes().startswith(PNG_SIGNATURE)
    timing = json.loads((a / "timing-summary.json").read_text())
    assert set(timing) == set(SCENARIOS)
    cell = timing["heuristic"]["slow lead, fast support"]
    assert cell["duration"]["support_planning_seconds"]["mean"] > 0 and "search-aware" in cell


def test_metrics_compare_every_pairing_alone_and_supported(runs: tuple[Path, RunResult]) -> None:
    metrics = json.loads((runs[0] / "metrics.json").read_text())
    assert metrics["tables"] == 1 and metrics["readings"] == [r.name for r in READINGS]
    for scenario in SCENARIOS:
        for pairing in PAIRINGS:
            entry = metrics["scenarios"][scenario][pairing]
            alone = entry["alone"]
            assert alone["completed"] == 1 and alone["support_actions"]["mean"] == 0
            # the floor is below what the lead takes alone, and the ceiling above any gain seen
            assert 0 < entry["floor"]["mean"] < alone["makespan"]["mean"]
            for reading, helped in entry["supported"].items():
                assert helped["completed"] == 1
                r = helped["gain"]["reduction"]
                expected = round(100 * (1 - helped["makespan"]["mean"] / alone["makespan"]["mean"]), 1)
                assert r == pytest.approx(expected, abs=0.11)
                # the two readings of the gain are one number seen two ways: s = 1 / (1 − r) − 1
                assert helped["gain"]["speed-up"] == pytest.approx(100 * (1 / (1 - r / 100) - 1), abs=0.2)
                assert r <= entry["ceiling"]["reduction"], (scenario, pairing, reading)
            if scenario == "unpredictable":  # no search to model: the same run under both readings
                assert entry["supported"]["duration"] == entry["supported"]["search-aware"]
        slow_alone = metrics["scenarios"][scenario]["slow lead, fast support"]["alone"]["makespan"]["mean"]
        fast_alone = metrics["scenarios"][scenario]["fast lead, fast support"]["alone"]["makespan"]["mean"]
        assert slow_alone == pytest.approx(3 * fast_alone, rel=0.02)  # a third of the speed, all motion


def test_report_puts_the_thesis_beside(runs: tuple[Path, RunResult]) -> None:
    text = (runs[0] / "report.md").read_text()
    for number in ("44.0 %", "30.5 %", "9.8 %"):
        assert number in text
    assert "## Verdict" in text and "Scenario `heuristic`" in text and THESIS["makespan_gain_percent"]
    for words in ("`duration` (default)", "`search-aware`", "speed-up", "ceiling", "Figure 3.6"):
        assert words in text


def test_a_trial_repeats_and_measures_only_the_readings_asked_for(runs: tuple[Path, RunResult]) -> None:
    """The run's trial, made again in this process with one reading, measures only that one, and alike: the
    trial repeats, whatever the run before it kept, and the other reading changes nothing. (A run in another
    process gives the values docs/experiments.md quotes: the README's, tests/test_new_user.py.)"""
    result = run_trial(make_trials(1, 3, readings=["duration"])[0])
    every = runs[1].results[0]["scenarios"]
    for scenario, cells in result["scenarios"].items():
        for pairing, cell in cells.items():
            assert list(cell["supported"]) == ["duration"]
            assert cell["supported"]["duration"] == every[scenario][pairing]["supported"]["duration"]
            assert cell["alone"] == every[scenario][pairing]["alone"]


def test_the_staged_floor_is_the_plan_with_handling_and_hand_travel_only() -> None:
    scenario = thesis_scenario(5)
    world = scenario.world
    plans = scenario.plans()
    plan = alone_plan("unpredictable", world, plans)
    alone = run_team(world, PlanFollowingLead([plan]))
    floor = staged_floor(world, plan)
    arm = world.lead_arm
    assert len(plan) * (arm.grasp + arm.release) < floor < alone.makespan
    slow = world.with_speeds(1 / 3, 1.0)
    assert staged_floor(slow, plan) == pytest.approx(3 * floor)
