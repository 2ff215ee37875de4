from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from supportive.errors import ExperimentError
from supportive.experiments import (
    ALL,
    Experiment,
    Finding,
    Reading,
    findings_table,
    get,
    names,
    register,
    run_experiment,
    unregister,
)

Toy = Callable[..., Experiment]


@pytest.fixture
def registered(toy: Toy) -> Iterator[str]:
    experiment = register(toy())
    yield experiment.name
    unregister(experiment.name)


def test_builtin_edge_reduction_is_registered() -> None:
    assert "edge-reduction" in names()
    assert names() == tuple(sorted(names()))
    experiment = get("edge-reduction")
    assert experiment.default_trials == 76
    assert experiment.thesis["mean_action_depth"] == {"min": 1.99, "max": 3.61, "mean": 2.84}
    assert "Figure 2.5" in experiment.reference


def test_unknown_name_lists_the_known_ones() -> None:
    with pytest.raises(ExperimentError, match=r"unknown experiment 'nope'.*all, .*edge-reduction"):
        get("nope")
    with pytest.raises(ExperimentError, match="unknown experiment"):
        unregister("nope")


def test_register_get_unregister(registered: str, toy: Toy) -> None:
    assert registered in names()
    assert get(registered).title == "A toy"
    with pytest.raises(ExperimentError, match="already registered"):
        register(toy())
    replacement = register(toy(title="Another toy"), replace=True)
    assert get(registered) is replacement
    unregister(registered)
    assert registered not in names()
    register(toy())  # the fixture unregisters it again


@pytest.mark.parametrize("name", [ALL, "Toy", "two words", "-toy", "toy-", ""])
def test_bad_names_are_refused(name: str, toy: Toy) -> None:
    with pytest.raises(ExperimentError, match="expected lowercase words"):
        toy(name)


def test_default_trials_must_be_positive(toy: Toy) -> None:
    with pytest.raises(ExperimentError, match="default_trials"):
        toy(default_trials=0)


@pytest.mark.parametrize(("kinds", "default"), [(("a", "a"), 5), (("a", "b", "c"), 2)])
def test_trial_kinds_are_distinct_and_fit_in_the_default(toy: Toy, kinds: tuple[str, ...], default: int) -> None:
    with pytest.raises(ExperimentError, match="trial_kinds must be distinct and no more than default_trials"):
        toy(trial_kinds=kinds, default_trials=default)
    assert toy(default_trials=default).fewest_trials == 1


def test_a_run_of_fewer_trials_than_the_experiment_takes_is_refused_before_it_starts(toy: Toy) -> None:
    calls: list[int] = []
    made = toy().make_trials

    def counted(trials: int, seed: int) -> Any:
        calls.append(trials)
        return made(trials, seed)

    experiment = register(toy("toy-fewest", trial_kinds=("a", "b", "c"), make_trials=counted))
    try:
        with pytest.raises(ExperimentError, match=r"^toy-fewest: at least 3 trials \(one of each kind it compares: a, b, c\), got 2$"):
            run_experiment(experiment.name, trials=2, progress=False)
        assert calls == []
        assert run_experiment(experiment.name, trials=3, progress=False).trials == 3
    finally:
        unregister(experiment.name)


def test_the_experiments_needing_more_than_one_kind_of_trial_say_so() -> None:
    assert {name: get(name).fewest_trials for name in names() if get(name).fewest_trials > 1} == {
        "generalisation": 3,
        "learner-settings": 2,
        "mistake-detection": 2,
    }


def test_run_in_process_orders_results_and_writes_files(registered: str, tmp_path: Path) -> None:
    result = run_experiment(registered, seed=3, output=tmp_path, progress=False)
    assert result.trials == 5 and result.backend == "in process"
    assert [r["index"] for r in result.results] == list(range(5))
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics == result.metrics
    assert metrics["experiment"] == registered and metrics["seed"] == 3 and metrics["trials"] == 5
    assert metrics["thesis"] == {"answer": 42} and metrics["indices"] == list(range(5))
    assert (tmp_path / "report.md").read_text() == result.report and "thesis: 42" in result.report
    run = json.loads((tmp_path / "run.json").read_text())
    assert "seconds" in run and "seconds" not in (tmp_path / "metrics.json").read_text()
    assert {p.name for p in result.files} == {"metrics.json", "report.md", "run.json"}
    assert result.headline == (("draws", "5", "–"),)
    again = run_experiment(registered, seed=3, progress=False)
    assert again.metrics == result.metrics and again.files == () and again.output is None
    other = run_experiment(registered, seed=4, progress=False)
    assert other.metrics["draws"] != result.metrics["draws"]


def test_summary_may_not_overwrite_the_run_keys(toy: Toy) -> None:
    experiment = register(toy("toy-clash", summarize=lambda results: {"seed": 1}))
    try:
        with pytest.raises(ExperimentError, match="may not set seed"):
            run_experiment(experiment.name, trials=1, progress=False)
    finally:
        unregister(experiment.name)


def test_trials_must_return_json_objects(toy: Toy) -> None:
    experiment = register(toy("toy-list", run_trial=lambda trial: [trial.index]))
    try:
        with pytest.raises(ExperimentError, match="returned list, not a dict"):
            run_experiment(experiment.name, trials=2, progress=False)
    finally:
        unregister(experiment.name)


def test_metrics_must_be_plain_json(toy: Toy) -> None:
    experiment = register(toy("toy-set", summarize=lambda results: {"odd": {1, 2}}))
    try:
        with pytest.raises(ExperimentError, match="not plain JSON"):
            run_experiment(experiment.name, trials=1, progress=False)
    finally:
        unregister(experiment.name)


@pytest.mark.parametrize("trials", [0, -1])
def test_bad_trial_counts(trials: int) -> None:
    with pytest.raises(ExperimentError, match="trials must be an int >= 1"):
        run_experiment("edge-reduction", trials=trials, progress=False)


def test_timings_stay_out_of_the_metrics(timed_toy: Toy, tmp_path: Path) -> None:
    experiment = register(timed_toy())
    try:
        first = run_experiment(experiment.name, trials=4, seed=2, output=tmp_path / "a", progress=False)
        second = run_experiment(experiment.name, trials=4, seed=2, output=tmp_path / "b", progress=False)
        quiet = run_experiment(experiment.name, trials=4, seed=2, progress=False)
    finally:
        unregister(experiment.name)
    metrics = (tmp_path / "a" / "metrics.json").read_bytes()
    assert metrics == (tmp_path / "b" / "metrics.json").read_bytes()
    assert b"seconds" not in metrics and b"timing" not in metrics
    assert {p.name for p in first.files} == {
        "metrics.json",
        "report.md",
        "run.json",
        "timing.json",
        "timing.md",
    }
    timing = json.loads((tmp_path / "a" / "timing.json").read_text())
    assert timing["experiment"] == "toy-timed" and timing["seed"] == 2 and "run to run" in timing["note"]
    assert [t["index"] for t in timing["trials"]] == [0, 1, 2, 3]
    assert all(t["seconds"] >= 0 for t in timing["trials"])
    assert list(first.timings) == timing["trials"] and len(second.timings) == 4
    assert all("timing" not in r for r in first.results)
    assert (tmp_path / "a" / "timing.md").read_text().endswith("4 trials\n")
    assert quiet.files == () and len(quiet.timings) == 4 and quiet.metrics == first.metrics


def test_no_timing_file_without_timings(registered: str, tmp_path: Path) -> None:
    result = run_experiment(registered, trials=2, output=tmp_path, progress=False)
    assert result.timings == () and not (tmp_path / "timing.json").exists()


def test_timings_must_be_plain_json(toy: Toy, tmp_path: Path) -> None:
    experiment = register(
        toy("toy-bad-timing", run_trial=lambda trial: {"index": 0, "draw": 1, "timing": {1}})
    )
    try:
        with pytest.raises(ExperimentError, match="timings are not plain JSON"):
            run_experiment(experiment.name, trials=1, output=tmp_path, progress=False)
    finally:
        unregister(experiment.name)
    assert not (tmp_path / "metrics.json").exists()  # refused before anything is written


def _reading_trials(trials: int, seed: int, readings: tuple[str, ...] = ("plain", "doubled")) -> tuple[Any, ...]:
    from supportive.experiments import spawn_trials

    return spawn_trials(seed, [{"scale": 10, "readings": list(readings)} for _ in range(trials)])


def _reading_trial(trial: Any) -> dict[str, Any]:
    draw = int(trial.rng().integers(1000))
    return {"index": trial.index, "by": {r: draw * (2 if r == "doubled" else 1) for r in trial.params["readings"]}}


def _reading_summary(results: Any) -> dict[str, Any]:
    return {"by": {r: [x["by"][r] for x in results] for r in results[0]["by"]}}


def _reading_findings(metrics: Any) -> list[Finding]:
    return [Finding("first draw", "42", tuple((r, str(metrics["by"][r][0])) for r in metrics["readings"]), "ok")]


@pytest.fixture
def with_readings(toy: Toy) -> Iterator[str]:
    experiment = register(
        toy(
            "toy-readings",
            make_trials=_reading_trials,
            run_trial=_reading_trial,
            summarize=_reading_summary,
            report=lambda metrics: f"# toy\n\n{metrics['by']}\n",
            headline=lambda metrics: [("readings", ", ".join(metrics["readings"]), "–")],
            readings=(Reading("plain", "as drawn", "the default"), Reading("doubled", "twice", "another")),
            findings=_reading_findings,
        )
    )
    yield experiment.name
    unregister(experiment.name)


def test_every_reading_runs_side_by_side_unless_some_are_chosen(with_readings: str) -> None:
    every = run_experiment(with_readings, trials=3, seed=1, progress=False)
    assert every.readings == ("plain", "doubled") and every.metrics["readings"] == ["plain", "doubled"]
    assert get(with_readings).default_reading == "plain"
    assert every.metrics["by"]["doubled"] == [2 * x for x in every.metrics["by"]["plain"]]
    one = run_experiment(with_readings, trials=3, seed=1, progress=False, readings=["doubled"])
    assert one.readings == ("doubled",) and one.metrics["by"] == {"doubled": every.metrics["by"]["doubled"]}
    assert [f.values for f in one.findings] == [(("doubled", str(every.metrics["by"]["doubled"][0])),)]
    assert every.findings[0].value("plain") == str(every.metrics["by"]["plain"][0])
    with pytest.raises(ExperimentError, match="no value under reading 'nope'"):
        every.findings[0].value("nope")


def test_bad_readings_are_refused(with_readings: str, registered: str, toy: Toy) -> None:
    with pytest.raises(ExperimentError, match="unknown reading 'x'; its readings are plain, doubled"):
        run_experiment(with_readings, trials=1, readings=["x"], progress=False)
    with pytest.raises(ExperimentError, match="at least one reading"):
        run_experiment(with_readings, trials=1, readings=[], progress=False)
    with pytest.raises(ExperimentError, match="has no readings"):
        run_experiment(registered, trials=1, readings=["plain"], progress=False)
    with pytest.raises(ExperimentError, match="must be unique"):
        toy("toy-twice", readings=(Reading("a", "", ""), Reading("a", "", "")))
    with pytest.raises(ExperimentError, match="reading name 'A b'"):
        Reading("A b", "", "")


def test_findings_table_bolds_the_default_and_reads_json() -> None:
    finding = Finding("q", "1", (("a", "2"), ("b", "3")), "v")
    table = findings_table([("x", "Fig. 1", [finding, Finding("p", "4", (("", "5"),), "w").as_json()])])
    lines = table.splitlines()
    assert lines[2] == "| x | Fig. 1 | q | 1 | **a 2** · b 3 | v |"
    assert lines[3] == "| x | Fig. 1 | p | 4 | 5 | w |"
