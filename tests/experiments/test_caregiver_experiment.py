from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.experiments.test_docs_numbers import check_quoted

from supportive.experiments import RunResult, get, names, run_experiment
from supportive.experiments.caregiver.measure import (
    DEFAULT_TRIALS,
    MEMORIES,
    READINGS,
    make_trials,
    run_trial,
)
from supportive.experiments.caregiver.plots import FILES
from supportive.experiments.caregiver.report import THESIS
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.experiments.statistics import ratio_ci


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, RunResult]:
    """A three-episode run: its folder and its result."""
    output = tmp_path_factory.mktemp("cg-a")
    return output, run_experiment("caregiver", trials=3, seed=5, output=output, progress=False)


def test_the_docs_quote_this_run(runs: tuple[Path, RunResult]) -> None:
    assert check_quoted("supportive reproduce caregiver -n 3 --seed 5", runs[0]) >= 1


def test_registered_with_100_episodes_and_three_readings() -> None:
    assert "caregiver" in names()
    experiment = get("caregiver")
    assert experiment.default_trials == DEFAULT_TRIALS == 100 and THESIS["episodes"] == 20
    assert [r.name for r in experiment.readings] == ["trajectory", "memory", "per-step"]
    assert experiment.default_reading == "trajectory" and MEMORIES["trajectory"] == 1.0  # Eq. 3.2 as printed
    assert MEMORIES["per-step"] < MEMORIES["memory"] < 1


def test_a_run_writes_the_three_figures(runs: tuple[Path, RunResult]) -> None:
    a, _ = runs
    for name in FILES.values():
        assert (a / name).read_bytes().startswith(PNG_SIGNATURE)


def test_a_trial_repeats_and_readings_do_not_interact(runs: tuple[Path, RunResult]) -> None:
    """The run's last episode, made again in this process with one reading, is what it was: the trial
    repeats, whatever the run before it kept, and the other readings change nothing."""
    last = make_trials(3, 5, readings=["memory"])[2]
    again, before = run_trial(last)["novices"], runs[1].results[2]["novices"]
    for novice, episodes in again.items():
        assert list(episodes["with"]) == ["memory"]
        assert episodes == {"without": before[novice]["without"], "with": {"memory": before[novice]["with"]["memory"]}}


def test_metrics_hold_every_measure_per_type_condition_and_reading(runs: tuple[Path, RunResult]) -> None:
    metrics = json.loads((runs[0] / "metrics.json").read_text())
    assert metrics["episodes"] == 3 and metrics["map"] == "house"
    assert metrics["readings"] == [r.name for r in READINGS] and metrics["memory"] == MEMORIES
    damage = metrics["measures"]["damage_normalized"]
    assert set(damage) == set(THESIS["damage_normalized"])
    top = max(
        [damage[label]["without"]["mean"] for label in damage]
        + [v["mean"] for label in damage for v in damage[label]["with"].values()]
    )
    assert 0 < top <= 1.0
    for label in damage:
        steps = metrics["measures"]["steps_until_threshold"][label]
        cells = metrics["measures"]["cells_explored"][label]
        for cell_steps, cell_cells in [
            (steps["without"], cells["without"]),
            *((steps["with"][r], cells["with"][r]) for r in metrics["readings"]),
        ]:
            assert 1 <= cell_steps["mean"] <= 200
            assert 1 <= cell_cells["mean"] <= cell_steps["mean"] + 1
        for reading, reduction in metrics["damage_reduction_percent"][label].items():
            if reduction["percent"] is not None and reduction["low"] is not None:
                assert reduction["low"] <= reduction["percent"] <= reduction["high"], (label, reading)
    # the most random novice is hurt more than the most goal-directed one
    assert damage["random motion"]["without"]["mean"] > damage["5% random"]["without"]["mean"]


def test_one_episode_without_the_caregiver_and_one_per_reading_from_the_same_seed() -> None:
    (trial,) = make_trials(1, 3, readings=["per-step"])
    (every,) = make_trials(1, 3)
    one, all_ = run_trial(trial), run_trial(every)
    for label, novice in one["novices"].items():
        assert list(novice["with"]) == ["per-step"]
        assert novice["without"] == all_["novices"][label]["without"]  # reading-independent
        assert novice["with"]["per-step"] == all_["novices"][label]["with"]["per-step"]


def test_report_puts_the_thesis_tables_beside(runs: tuple[Path, RunResult]) -> None:
    text = (runs[0] / "report.md").read_text()
    for number in ("0.7346", "0.2291", "35.5", "97.05", "14.6", "24.45", "33.2"):
        assert number in text
    assert "## Verdict" in text and "damage falls by more than 66 %" in text
    for name in ("`trajectory` (default)", "`memory`", "`per-step`"):
        assert name in text


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.floats(0.5, 20.0), st.floats(0.0, 20.0)), min_size=2, max_size=40
    )
)
def test_ratio_ci_is_the_delta_method(pairs: list[tuple[float, float]]) -> None:
    x = np.array([a for a, _ in pairs])
    y = np.array([b for _, b in pairs])
    result = ratio_ci(list(y), list(x), digits=9)
    ratio = y.mean() / x.mean()
    assert result["mean"] == pytest.approx(ratio, abs=1e-8)
    from scipy import stats

    se = np.std(y - ratio * x, ddof=1) / np.sqrt(len(x)) / x.mean()
    half = stats.t.ppf(0.975, len(x) - 1) * se
    assert result["low"] == pytest.approx(ratio - half, abs=1e-7)
    assert result["high"] == pytest.approx(ratio + half, abs=1e-7)


def test_ratio_ci_edge_cases() -> None:
    assert ratio_ci([1.0], [0.0])["mean"] is None
    assert ratio_ci([1.0], [2.0]) == {"mean": 0.5, "low": None, "high": None, "n": 1}
    with pytest.raises(ValueError, match="pair up"):
        ratio_ci([1.0], [1.0, 2.0])
