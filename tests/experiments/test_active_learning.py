from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path

import pytest

from supportive.examples import food as food_examples
from supportive.experiments import RunResult, get, names, run_experiment
from supportive.experiments.active_learning import blocks, food
from supportive.experiments.active_learning.ceiling import ceiling_paths, reachable_demonstrations
from supportive.experiments.active_learning.common import (
    STRATEGIES,
    anova,
    known_paths,
    make_instructor,
    teach,
)
from supportive.experiments.plotting import PNG_SIGNATURE
from supportive.experiments.statistics import mean_ci
from supportive.learning.active import QuerySchedule
from supportive.learning.instructors import SimulatedInstructor
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode


def test_both_registered() -> None:
    assert {"active-learning", "active-learning-blocks"} <= set(names())
    assert get("active-learning").default_trials == 50
    assert get("active-learning").reference == "§2.2.10.1, Figure 2.11"
    assert get("active-learning-blocks").reference == "§2.2.7–2.2.10, Figure 2.10"


@pytest.fixture(scope="module")
def food_runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, RunResult]:
    """A small run of the food experiment: its folder and its result."""
    output = tmp_path_factory.mktemp("al-a")
    return output, run_experiment("active-learning", trials=2, seed=3, output=output, progress=False)


@pytest.fixture(scope="module")
def block_runs(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    a, b = tmp_path_factory.mktemp("alb-a"), tmp_path_factory.mktemp("alb-b")
    run_experiment("active-learning-blocks", trials=2, seed=3, output=a, progress=False)
    run_experiment("active-learning-blocks", trials=2, seed=3, output=b, progress=False)
    return a, b


def test_food_run_writes_files(food_runs: tuple[Path, RunResult]) -> None:
    a, result = food_runs
    assert {p.name for p in result.files} >= {"metrics.json", "report.md", "comprehension.png"}
    assert (a / "comprehension.png").read_bytes().startswith(PNG_SIGNATURE)


def test_food_comprehension_percentages(food_runs: tuple[Path, RunResult]) -> None:
    metrics = json.loads((food_runs[0] / "metrics.json").read_text())
    assert metrics["trials"] == 2 and metrics["task_count"] == 12 and metrics["iterations"] == [4, 8, 12]
    assert metrics["readings"] == list(metrics["by_reading"]) == ["pilot", "start-2-4", "start-4-8"]
    assert metrics["schedules"]["start-4-8"]["after_steps"] == [0, 4, 8]
    for name, reading in metrics["by_reading"].items():
        comprehension = reading["comprehension"]
        for condition in ("solo", "multi"):
            for row in ("random", "distance", "connectivity", "ceiling"):
                means = [v["mean"] for v in comprehension[condition][row]]
                assert all(0.0 <= m <= 100.0 for m in means)
                if condition == "multi" or row == "ceiling":
                    assert means == sorted(means)
        for row in ("random", "distance", "connectivity", "ceiling"):
            # iteration 4 is instructor 1's learner in both conditions
            assert comprehension["solo"][row][0] == comprehension["multi"][row][0], name
        for task in reading["tasks"].values():
            for condition in ("solo", "multi"):
                for values in task[condition].values():
                    assert all(0.0 <= v <= 100.0 for v in values)
                # no strategy passes the instructors' ceiling, task by task
                for strategy in ("random", "distance", "connectivity"):
                    assert all(
                        v <= c for v, c in zip(task[condition][strategy], task[condition]["ceiling"], strict=True)
                    )


def test_food_instructors_differ_so_pooling_beats_one_instructor(food_runs: tuple[Path, RunResult]) -> None:
    metrics = json.loads((food_runs[0] / "metrics.json").read_text())
    assert metrics["base"] == "own"
    for strategy in ("random", "distance", "connectivity"):
        assert metrics["by_reading"]["pilot"]["pooled_minus_solo"][strategy]["12"]["trials_better"] == 2


def test_food_trial_counts_never_exceed_orderings_or_the_ceiling() -> None:
    (trial,) = food.make_trials(1, 5, readings=["start-4-8"])
    result = food.run_trial(trial)
    assert list(result["readings"]) == ["start-4-8"]
    for task in result["readings"]["start-4-8"]["tasks"].values():
        for strategy in ("random", "distance", "connectivity"):
            multi, solo = task[strategy]["multi"], task[strategy]["solo"]
            assert multi == sorted(multi) and solo == sorted(solo) and multi[0] == solo[0]
            assert 1 <= max(multi + solo) <= task["orderings"]
            for condition in ("solo", "multi"):
                assert all(v <= c for v, c in zip(task[strategy][condition], task["ceiling"][condition], strict=True))


def test_food_trials_repeat_and_readings_do_not_interact(food_runs: tuple[Path, RunResult]) -> None:
    """The run's first trial, made again in this process with one reading, measures that reading alike: the
    trial repeats, whatever the run before it kept, and the other readings change nothing. (Whole runs are
    compared byte for byte with their records, made in other processes, by ``make docs-verify``.)"""
    one = food.make_trials(2, 3, readings=["start-2-4"])[0]
    assert food.run_trial(one)["readings"]["start-2-4"] == food_runs[1].results[0]["readings"]["start-2-4"]


def test_food_report_has_thesis_numbers_and_every_reading(food_runs: tuple[Path, RunResult]) -> None:
    text = (food_runs[0] / "report.md").read_text()
    for number in ("25.9", "35.4", "42.9", "36.5", "54.1", "65.0", "54.6", "61.5", "65.4"):
        assert number in text
    for number in ("46.6", "61.2", "36.6", "52.0", "63.1", "76.6", "85.8"):
        assert number in text
    assert "Pooled instructors vs a solo instructor" in text
    for name in ("`pilot` (default)", "`start-2-4`", "`start-4-8`", "Ceiling"):
        assert name in text


def test_blocks_run_is_deterministic_and_reports(block_runs: tuple[Path, Path]) -> None:
    a, b = block_runs
    assert (a / "metrics.json").read_bytes() == (b / "metrics.json").read_bytes()
    assert (a / "paths.png").read_bytes().startswith(PNG_SIGNATURE)
    metrics = json.loads((a / "metrics.json").read_text())
    assert [t["orderings"] for t in metrics["tasks"]] == [720, 24, 6]
    for task in metrics["tasks"]:
        for group in ("solo", "pairs", "triads"):
            conditions = task["groups"][group]["conditions"]
            assert conditions["passive"]["paths"]["mean"] <= conditions["random"]["paths"]["mean"]
            for condition in conditions.values():
                assert 1 <= condition["paths"]["mean"] <= condition["max"] <= task["orderings"]
        # pooling never loses paths
        solo, triads = (
            task["groups"][g]["conditions"]["distance"]["paths"]["mean"] for g in ("solo", "triads")
        )
        assert solo <= triads
    text = (a / "report.md").read_text()
    for number in ("720", "11.508", "17.381", "85.597", "11.65", "5.667"):
        assert number in text


def test_blocks_trial_groups() -> None:
    (trial,) = blocks.make_trials(1, 0)
    result = blocks.run_trial(trial)
    task = result["tasks"]["blocks-v"]
    assert [len(task["random"][g]) for g in ("solo", "pairs", "triads")] == [6, 15, 20]
    passive = task["passive"]["solo"]
    assert (
        min(passive) >= 1 and max(passive) > 1
    )  # no queries, yet unprompted deviations vary the demonstrations


def test_helpers() -> None:
    structure = ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("c"), ActionNode("d")))))
    taught = teach(
        structure,
        ["a", "b", "c", "d"],
        instructor_seed=1,
        task=1,
        strategy="distance",
        strategy_index=1,
        schedule=QuerySchedule((1,), max_per_demonstration=1, skip_first_demonstrations=1),
        demonstrations=3,
    )
    assert len(taught.demonstrations) == 3 and list(taught.paths) == sorted(taught.paths)
    assert known_paths(taught.demonstrations) == taught.paths[-1]
    assert known_paths([("a", "b", "c", "d")], [("a", "c", "b", "d")]) == 2
    assert mean_ci([2.0, 2.0]) == {"mean": 2.0, "low": 2.0, "high": 2.0, "n": 2}
    assert anova([[1, 1], [1, 1]])["F"] is None
    assert anova([[1, 2], [5, 6], [9, 9]])["p"] < 0.05


def _every_query_sequence(
    instructor: SimulatedInstructor, schedule: QuerySchedule, demonstration: int, actions: Sequence[str]
) -> set[tuple[str, ...]]:
    """The oracle for the ceiling: replay the demonstration for every sequence of answers the learner could
    give at the scheduled steps (nothing, or any action), each from a fresh copy of the instructor."""
    import copy
    import itertools

    instructor.begin_demonstration()
    start = copy.deepcopy(instructor)
    found = set()
    slots = len(schedule.after_steps)
    for answers in itertools.product([None, *actions], repeat=slots):
        person = copy.deepcopy(start)
        done: tuple[str, ...] = ()
        asked = 0
        pending = list(answers)
        while True:
            query = None
            if schedule.should_query(demonstration=demonstration, step=len(done), asked=asked):
                query = pending.pop(0) if pending else None
                asked += query is not None
            action = person.next_action(done, query)
            if action is None:
                break
            done = (*done, action)
        found.add(done)
    instructor.next_action((), None)
    return found


@pytest.mark.parametrize(("after_steps", "most"), [((1, 3), 2), ((0, 2), 2), ((0, 1, 2), 3), ((0, 1, 3), 1)])
def test_reachable_demonstrations_match_every_query_sequence(after_steps: tuple[int, ...], most: int) -> None:
    structure = ChainNode(
        (
            ActionNode("a"),
            CliqueNode((ActionNode("b"), ChainNode((ActionNode("c"), ActionNode("d"))), ActionNode("e"))),
            CliqueNode((ActionNode("f"), ActionNode("g"))),
        )
    )
    actions = ["a", "b", "c", "d", "e", "f", "g"]
    schedule = QuerySchedule(after_steps, max_per_demonstration=most, skip_first_demonstrations=1)
    for seed in range(3):
        fast = make_instructor(structure, instructor_seed=seed, task=1, own_base=True)
        slow = make_instructor(structure, instructor_seed=seed, task=1, own_base=True)
        for d in range(3):
            assert reachable_demonstrations(fast, schedule, d, actions) == _every_query_sequence(
                slow, schedule, d, actions
            )


def test_the_ceiling_bounds_every_strategy_and_holds_what_they_showed() -> None:
    spec = food_examples.load("tea")
    assert spec.structure is not None
    schedule = food.SCHEDULES["start-4-8"]
    person = make_instructor(spec.structure, instructor_seed=11, task=3, own_base=True)
    sets = [reachable_demonstrations(person, schedule, d, spec.action_ids()) for d in range(6)]
    for index, strategy in enumerate(STRATEGIES):
        taught = teach(
            spec.structure, spec.action_ids(), instructor_seed=11, task=3, strategy=strategy,
            strategy_index=index, schedule=schedule, demonstrations=6, own_base=True,
        )  # fmt: skip
        assert all(demo in sets[d] for d, demo in enumerate(taught.demonstrations))
        assert taught.paths[-1] <= ceiling_paths(sets)
