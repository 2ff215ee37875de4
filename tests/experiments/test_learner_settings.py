"""The learner-settings experiment: its trials, its scoring of slips against what was put in, and the
procedure that picks the defaults."""

from __future__ import annotations

import itertools
from typing import Any

from supportive.experiments import get
from supportive.experiments.learner_settings.measure import (
    CLEAN_TASKS,
    DEMONSTRATIONS,
    GRID,
    PEOPLE,
    TASKS,
    choose,
    make_trials,
    run_trial,
    settings_name,
    summarize,
)
from supportive.generate.mistakes import KINDS, PROFILES
from supportive.learning.learner import HTNLearner


def test_a_full_run_covers_every_cell_and_the_clean_tasks() -> None:
    trials = make_trials(get("learner-settings").default_trials, 0)
    mistaken = [t for t in trials if t.params["case"] != "none"]
    assert len(mistaken) == TASKS * len(PROFILES) * len(DEMONSTRATIONS) * len(KINDS)
    assert len(trials) - len(mistaken) == CLEAN_TASKS
    cells = [(t.params["profile"], t.params["demonstrations"], t.params["case"], t.params["people"]) for t in mistaken]
    assert set(cells) == set(itertools.product(PROFILES, DEMONSTRATIONS, KINDS, PEOPLE))
    assert len(set(cells)) * TASKS // len(PEOPLE) == len(cells)  # as many tasks by each people in every cell
    clean = [t.params["people"] for t in trials if t.params["case"] == "none"]
    assert clean.count("habits") == clean.count("uniform") == CLEAN_TASKS // 2


def test_a_trial_scores_every_setting_and_the_summary_picks_by_the_procedure() -> None:
    trials = make_trials(get("learner-settings").default_trials, 0)
    first_moved = next(t for t in trials if t.params["case"] == "moved" and t.params["demonstrations"] == 20)
    result = run_trial(first_moved)
    names = {settings_name(dict(zip(GRID, values, strict=True))) for values in itertools.product(*GRID.values())}
    assert set(result["settings"]) == names
    for row in result["settings"].values():
        assert row["right"] <= row["reported"] and row["found"] <= result["mistakes"]
    summary = summarize([result])
    assert summary["chosen"] in names
    assert set(summary["settings"][summary["chosen"]]["kinds"]) == {f"{k} {n}" for k in KINDS for n in DEMONSTRATIONS}


def _row(worst: float, flagged: float, tasks: int, habits: float = 0.0, habit_tasks: int = 0) -> dict[str, Any]:
    return {
        "worst_f1": worst, "clean_flagged": flagged, "clean_tasks_flagged": tasks, "clean_tasks": 100,
        "habits_flagged": habits, "habits_tasks_flagged": habit_tasks, "habits_tasks": 100,
    }


def test_choose_is_the_best_worst_f1_among_the_settings_quiet_on_clean_data() -> None:
    table = {"a": _row(0.9, 0.01, 0), "b": _row(0.8, 0.001, 0), "c": _row(0.85, 0.001, 2), "d": _row(0.8, 0.0, 1)}
    assert choose(table) == "b"  # a reports too many clean steps, c slips on too many clean tasks; b before d
    assert choose({"a": _row(0.9, 0.01, 0)}) is None


def test_choose_asks_people_with_habits_for_few_steps_flagged_not_for_few_tasks() -> None:
    table = {"a": _row(0.95, 0.0, 0, habits=0.006), "b": _row(0.9, 0.0, 0, habits=0.004, habit_tasks=20)}
    assert choose(table) == "b"  # a calls too many of the habitual people's valid steps slips


def test_the_learners_defaults_are_the_chosen_setting() -> None:
    # docs/learning.md quotes the full run that chose them; a change of grid or procedure must change both.
    defaults = HTNLearner()
    chosen = {name: getattr(defaults, name) for name in GRID}
    assert settings_name(chosen) in {
        settings_name(dict(zip(GRID, v, strict=True))) for v in itertools.product(*GRID.values())
    }


def test_the_report_lists_the_grid_of_its_run_in_the_order_of_the_values() -> None:
    # A metrics file keeps its keys sorted as text (weight 1000 before 300); the report orders by value.
    result = run_trial(make_trials(get("learner-settings").default_trials, 0)[0])
    summary = summarize([result])
    metrics = {**summary, "settings": dict(sorted(summary["settings"].items())), "experiment": "learner-settings"}
    text = get("learner-settings").report(metrics)
    grid = ", ".join(k + " ∈ {" + ", ".join(f"{v:g}".replace("inf", "∞") for v in vs) + "}" for k, vs in GRID.items())
    assert f"(grid: {grid})" in text
    grid_table = text.split("How sure")[0]  # the spread's table below it orders by distance from the chosen
    rows = [line.split(" | ")[0].strip("|* ") for line in grid_table.splitlines() if line.startswith("| ") and "=" in line]
    expected = [settings_name(dict(zip(GRID, v, strict=True))) for v in itertools.product(*GRID.values())]
    assert rows == expected
