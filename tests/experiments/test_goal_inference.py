"""The goal-inference experiment (thesis Fig. 2.4): registry, determinism, summary, report, timing files."""

from __future__ import annotations

import json
import statistics
from pathlib import Path
from typing import Any

import pytest
from tests.experiments.test_docs_numbers import check_quoted

from supportive.errors import ExperimentError
from supportive.experiments import get, names, run_experiment
from supportive.experiments.goal_inference.design import SETTINGS, SIZES, make_trials
from supportive.experiments.goal_inference.measure import measure_task, task_for
from supportive.experiments.goal_inference.plots import plots, timing_report
from supportive.experiments.goal_inference.report import headline, report
from supportive.experiments.goal_inference.summary import summarize
from supportive.experiments.goal_inference.thesis import THESIS
from supportive.experiments.goal_inference.timing import timing_summary
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.tasks.spec import TaskSpec

TRIALS = 3  # sizes 10, 20, 50: about six seconds in process
SEED = 4
TIMING_FILES = {"timing.json", "timing.md", "timing.png"}


@pytest.fixture(scope="module")
def first_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Any]:
    output = tmp_path_factory.mktemp("gi-a")
    result = run_experiment("goal-inference", trials=TRIALS, seed=SEED, output=output, progress=False)
    return output, result


def test_registered() -> None:
    assert "goal-inference" in names() and "edge-reduction" in names()
    experiment = get("goal-inference")
    assert experiment.reference == "§2.1.7.1–2.1.7.3, Figure 2.4"
    assert experiment.default_trials == 5 * len(SIZES) and SIZES[0] == 10 and SIZES[-1] == 1000
    assert experiment.thesis["accuracy"] is None and experiment.thesis["figure_2_4_numbers"] is None
    assert experiment.thesis["update_seconds_bound"] == 1.0


def test_trials_deal_out_sizes_with_their_own_seeds() -> None:
    trials = make_trials(9, 0)
    assert [t.params["subgoals"] for t in trials] == [*SIZES, 10, 20]
    assert [t.params["steps"] for t in trials][:7] == [3000, 3000, 3000, 3000, 3000, 2000, 1500]
    assert len({t.seed.spawn_key for t in trials}) == 9
    task = task_for(trials[1])
    assert task.name.startswith("ikea-002-n20-s") and len(task.actions) == 20
    assert task_for(trials[1]) == task


def test_small_run_writes_everything(first_run: tuple[Path, Any]) -> None:
    output, result = first_run
    assert {p.name for p in result.files} == {
        "metrics.json",
        "report.md",
        "run.json",
        "accuracy.png",
        *TIMING_FILES,
    }
    for png in ("accuracy.png", "timing.png"):
        data = (output / png).read_bytes()
        assert data[:8] == PNG_SIGNATURE and len(data) > 1000
    metrics = json.loads((output / "metrics.json").read_text())
    assert metrics["trials"] == TRIALS and metrics["design"]["sizes"] == [10, 20, 50]
    assert [t["subgoals"] for t in metrics["tasks"]] == [10, 20, 50]
    assert set(metrics["accuracy"]) == {s.key for s in SETTINGS}
    # no wall-clock time in metrics.json: the harness writes the trials' timings to timing.json
    assert "timing" not in metrics and all("timing" not in t for t in metrics["tasks"])
    assert "median_us" not in json.dumps(metrics)
    timing = json.loads((output / "timing.json").read_text())
    assert timing["experiment"] == "goal-inference" and timing["seed"] == SEED
    assert [row["index"] for row in timing["trials"]] == [0, 1, 2]
    assert [row["subgoals"] for row in timing["trials"]] == [10, 20, 50]
    for row in timing["trials"]:
        assert 0 < row["hierarchical"]["median_us"] < 1e6 and 0 < row["flat"]["median_us"] < 1e6
    # library users get them from the RunResult, not from the results summarize saw
    assert list(result.timings) == timing["trials"]
    assert all(t["steps"] == 3000 for t in result.timings)
    assert all("timing" not in r for r in result.results)
    for row in metrics["sizes"]:  # dense up to 128 subgoals: both multiply with n² entries
        assert row["operator_entries"] == {"flat": row["subgoals"] ** 2, "hierarchical": row["subgoals"] ** 2}


def test_the_docs_quote_this_run(first_run: tuple[Path, Any]) -> None:
    assert check_quoted(f"supportive reproduce goal-inference -n {TRIALS} --seed {SEED}", first_run[0]) >= 1


def test_same_seed_gives_the_same_trials_again_in_this_process(first_run: tuple[Path, Any], tmp_path: Path) -> None:
    """A second run in the process that made the first (whatever it kept) measures its first trial alike: each
    trial has its own seed, so a shorter run is the longer one's first trials. (Trials are compared across
    processes by the local-cluster test.)"""
    output, _ = first_run
    run_experiment("goal-inference", trials=1, seed=SEED, output=tmp_path, progress=False)
    again = json.loads((tmp_path / "metrics.json").read_text())
    assert again["tasks"] == json.loads((output / "metrics.json").read_text())["tasks"][:1]


def test_local_cluster_gives_identical_trials(first_run: tuple[Path, Any], tmp_path: Path) -> None:
    """The first two trials (the smallest tasks) on two worker processes measure what they measured in this
    process (whole runs' files are compared across processes by tests/experiments/test_execution.py)."""
    output, _ = first_run
    result = run_experiment("goal-inference", trials=2, seed=SEED, workers=2, output=tmp_path, progress=False)
    assert result.backend == "dask LocalCluster, 2 worker processes"
    tasks = json.loads((tmp_path / "metrics.json").read_text())["tasks"]
    assert tasks == json.loads((output / "metrics.json").read_text())["tasks"][:2]
    assert {p.name for p in result.files} >= TIMING_FILES


def test_hierarchical_at_least_as_accurate_on_average(first_run: tuple[Path, Any]) -> None:
    metrics = first_run[1].metrics
    for level in ("subgoal", "subtask"):
        flat = statistics.fmean(a["flat"][level]["mean"] for a in metrics["accuracy"].values())
        hierarchical = statistics.fmean(
            a["hierarchical"][level]["mean"] for a in metrics["accuracy"].values()
        )
        assert hierarchical >= flat
    # overlap and noise cost accuracy
    easiest, hardest = metrics["accuracy"]["overlap-0.0-clean"], metrics["accuracy"]["overlap-0.8-noisy"]
    assert easiest["flat"]["subgoal"]["mean"] > hardest["flat"]["subgoal"]["mean"]


def test_report_states_the_thesis(first_run: tuple[Path, Any]) -> None:
    output, result = first_run
    text = (output / "report.md").read_text()
    for phrase in (
        "Figure 2.4",
        "In most cases, the CC-HTN model completed its computation faster than 1Hz.",
        "i7-3930K",
        "no accuracy numbers",
        "dependent on observation set overlap",
        "76 tasks of 10–100 subgoals",
        "timing.md",
    ):
        assert phrase in text
    timing = (output / "timing.md").read_text()
    assert "faster than 1Hz" in timing and "Not deterministic" in timing
    rows = {row[0]: row for row in result.headline}
    assert rows["trials, subgoals"][1:] == ("3, 10–50", "76, 10–100")
    assert rows["time per update flat / hierarchical (median), by size"][1] == "see timing.md"


def _timing(index: int, subgoals: int, micros: float) -> dict[str, Any]:
    times = {"median_us": micros, "mean_us": micros + 1, "p90_us": micros + 2, "max_us": micros + 3}
    return {
        "index": index,
        "task": f"t{index}",
        "subgoals": subgoals,
        "operator_entries": {"flat": subgoals**2, "hierarchical": 50},
        "flat": {**times, "build_ms": 1.0},
        "hierarchical": {**times, "median_us": micros / 2, "build_ms": 1.0},
        "steps": 100,
        "setting": "overlap-0.5-noisy",
        "cpu": "test cpu",
    }


def _result(index: int, subgoals: int, flat: float, hierarchical: float) -> dict[str, Any]:
    accuracy = {
        s.key: {
            "flat": {"subgoal": flat - s.overlap / 10, "subtask": flat},
            "hierarchical": {"subgoal": hierarchical - s.overlap / 10, "subtask": hierarchical},
            "progress": {"subgoal": hierarchical - s.overlap / 20, "subtask": hierarchical},
        }
        for s in SETTINGS
    }
    return {
        "index": index,
        "task": f"t{index}",
        "subgoals": subgoals,
        "subtasks": 3,
        "depth": 2.0,
        "transition_nonzeros": {"flat": 20, "hierarchical": 20},
        "operator_entries": {"flat": subgoals**2, "hierarchical": 50},
        "steps": {s.key: 100 for s in SETTINGS},
        "accuracy": accuracy,
    }


def test_summarize_hand_made_results() -> None:
    results = [
        _result(0, 10, 0.8, 0.9),
        _result(1, 10, 0.9, 0.9),
        _result(2, 200, 0.7, 0.8),
    ]
    metrics = summarize(results)
    cell = metrics["accuracy"]["overlap-0.0-clean"]
    assert cell["flat"]["subgoal"]["mean"] == 0.8 and cell["hierarchical"]["subgoal"][
        "mean"
    ] == pytest.approx(0.866667)
    assert cell["flat"]["subgoal"]["n"] == 3
    assert cell["flat"]["subgoal"]["low"] < 0.8 < cell["flat"]["subgoal"]["high"] <= 1.0
    assert cell["difference"]["subtask"]["mean"] == pytest.approx(0.066667)
    assert cell["hierarchical_ahead"] == {"subgoal": 2, "subtask": 2} and cell["flat_ahead"]["subgoal"] == 0
    assert metrics["accuracy"]["overlap-0.8-noisy"]["flat"]["subgoal"]["mean"] == pytest.approx(0.72)
    assert [(row["subgoals"], row["trials"]) for row in metrics["sizes"]] == [(10, 2), (200, 1)]
    assert metrics["sizes"][1]["operator_entries"] == {"flat": 40000, "hierarchical": 50}
    assert "timing" not in metrics and metrics["tasks"][0]["task"] == "t0"
    assert summarize(results) == metrics  # deterministic


def test_timing_summary_and_files_from_hand_made_timings(tmp_path: Path) -> None:
    timings = [_timing(0, 10, 10.0), _timing(1, 10, 20.0), _timing(2, 200, 40.0)]
    document = timing_summary(timings)
    small = document["sizes"][0]
    assert small["subgoals"] == 10 and small["flat"]["median_us"] == 15.0 and small["ratio"] == 2.0
    assert small["flat"]["least_median_us"] == 10.0 and small["flat"]["greatest_median_us"] == 20.0
    assert document["cpus"] == ["test cpu"] and document["trials"] == timings
    written = timing_report(timings, tmp_path)
    assert [p.name for p in written] == ["timing.md", "timing.png"]
    text = (tmp_path / "timing.md").read_text()
    assert "Not deterministic" in text and "faster than 1Hz" in text and "overlap-0.5-noisy" in text
    assert (tmp_path / "timing.png").read_bytes()[:8] == PNG_SIGNATURE


def test_plots_report_and_headline_need_the_metrics_only(tmp_path: Path) -> None:
    metrics = summarize([_result(0, 10, 0.8, 0.9), _result(1, 20, 0.8, 0.85)])
    document = {**metrics, "experiment": "goal-inference", "title": "t", "reference": "r", "thesis": THESIS}
    document.update(seed=0, trials=2)
    written = plots(document, tmp_path)
    assert [p.name for p in written] == ["accuracy.png"]
    quantity, measured, _ = headline(document)[-1]
    assert (quantity, measured) == ("time per update flat / hierarchical (median), by size", "see timing.md")
    text = report(document)
    assert "faster than 1Hz" in text and "timing.md" in text and "RunResult.timings" in text


def test_summarize_and_measure_refuse_bad_input() -> None:
    with pytest.raises(ExperimentError, match="no trial results"):
        summarize([])
    with pytest.raises(ExperimentError, match="ground-truth structure"):
        measure_task(TaskSpec("x", (), None, ()), 10, [(0, 0)] * len(SETTINGS))
