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
    assert {(t.params["profile"], t.params["demonstrations"], t.params["case"]) for t in mistaken} == {
        (p, n, k) for p in PROFILES for n in DEMONSTRATIONS for k in KINDS
    }


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


def _row(worst: float, flagged: float, tasks: int) -> dict[str, Any]:
    return {"worst_f1": worst, "clean_flagged": flagged, "clean_tasks_flagged": tasks, "clean_tasks": 100}


def test_choose_is_the_best_worst_f1_among_the_settings_quiet_on_clean_data() -> None:
    table = {"a": _row(0.9, 0.01, 0), "b": _row(0.8, 0.001, 0), "c": _row(0.85, 0.001, 2), "d": _row(0.8, 0.0, 1)}
    assert choose(table) == "b"  # a reports too many clean steps, c slips on too many clean tasks; b before d
    assert choose({"a": _row(0.9, 0.01, 0)}) is None


def test_the_learners_defaults_are_the_chosen_setting() -> None:
    # docs/learning.md quotes the full run that chose them; a change of grid or procedure must change both.
    defaults = HTNLearner()
    assert settings_name({"slip_margin": defaults.slip_margin, "slip_rate": defaults.slip_rate}) in {
        settings_name(dict(zip(GRID, v, strict=True))) for v in itertools.product(*GRID.values())
    }
