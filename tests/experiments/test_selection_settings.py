"""The selection-settings experiment: its trials, the gain of each policy, and the procedure that picks the
defaults."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.experiments import get
from supportive.experiments.selection_settings.evidence import LEVELS
from supportive.experiments.selection_settings.measure import (
    CONVENTIONAL,
    DEMONSTRATIONS,
    FOLDS,
    FRESH,
    RECALL_DEMONSTRATIONS,
    TASKS,
    choose,
    make_trials,
    policy_name,
    run_trial,
    summarize,
)
from supportive.experiments.selection_settings.report import findings
from supportive.generate.habits import PEOPLE
from supportive.generate.mistakes import PROFILES
from supportive.learning import HTNLearner


def test_a_full_run_has_the_same_number_of_tasks_in_every_cell() -> None:
    trials = make_trials(get("selection-settings").default_trials, 0)
    cells = [(t.params["profile"], t.params["demonstrations"], t.params["people"]) for t in trials]
    assert {cell: cells.count(cell) for cell in set(cells)} == {
        (p, n, who): TASKS for p in PROFILES for n in DEMONSTRATIONS for who in PEOPLE
    }


@pytest.mark.parametrize("people", PEOPLE)
def test_a_trial_scores_general_and_every_number_of_folds_on_fresh_executions(people: str) -> None:
    trial = next(
        t for t in make_trials(120, 0) if t.params == {"profile": "uniform", "demonstrations": 5, "people": people}
    )
    result = run_trial(trial)
    assert result == run_trial(trial) and result["people"] == people
    assert set(result["folds"]) == {str(k) for k in FOLDS}
    assert set(result["evidence"]) == {str(level) for level in LEVELS}
    for score in (result["general"], *result["folds"].values(), *result["subtasks"].values(), *result["evidence"].values()):
        assert 0 <= score["admitted"] <= FRESH and score["log_likelihood"] < 0
    # general, from this many demonstrations, is one of the two ways subtasks.py compares, and the level of
    # evidence.py at the learner's default
    default = "made" if HTNLearner().subtask_demonstrations <= 5 else "none"
    assert result["subtasks"][default] == result["general"] == result["evidence"][str(HTNLearner().evidence)]


def _result(
    profile: str, n: int, general: float, auto: dict[int, float], *, general_admits: int = FRESH, auto_admits: int = FRESH
) -> dict[str, Any]:
    """A trial's result as :func:`run_trial` gives it, with these held-out log-likelihoods and admissions (the
    general reading's with and without subtasks both ``general``'s)."""
    score = {"log_likelihood": general, "admitted": general_admits}
    return {
        "profile": profile,
        "demonstrations": n,
        "people": "uniform",
        "general": score,
        "folds": {str(k): {"log_likelihood": auto[k], "admitted": auto_admits, "chosen": "x"} for k in FOLDS},
        "subtasks": {"made": score, "none": score},
        "evidence": {str(level): score for level in LEVELS},
    }


_likelihood = st.floats(-30, -1, allow_nan=False).map(lambda x: round(x, 3))


@given(
    st.lists(
        st.tuples(st.sampled_from(PROFILES), st.sampled_from(DEMONSTRATIONS), _likelihood, st.lists(_likelihood, min_size=len(FOLDS), max_size=len(FOLDS))),
        min_size=1,
        max_size=12,
    )
)
def test_a_policys_gain_and_its_distance_from_the_best_are_worked_out_task_by_task(
    tasks: list[tuple[str, int, float, list[float]]],
) -> None:
    # The oracle: a policy's gain on each task (what its learner scores minus general's, 0 where it keeps
    # general), the mean of each row, then the mean over the rows; the distance from the best policy is the
    # same for the task-by-task differences, its variance that of a mean of independent row means.
    tasks = [("uniform", RECALL_DEMONSTRATIONS, -5.0, [-5.0] * len(FOLDS)), *tasks]  # the recall is measured
    results = [_result(p, n, g, dict(zip(FOLDS, auto, strict=True))) for p, n, g, auto in tasks]
    summary = summarize(results)
    policies = summary["policies"]
    rows = sorted({n for _, n, _, _ in tasks})
    assert all(row["gain"] <= policies[summary["best"]]["gain"] for row in policies.values() if row["qualifies"])

    def per_task(k: int | None, m: int | None) -> dict[int, np.ndarray]:
        return {
            n: np.array([(a[FOLDS.index(k)] - g) if m is not None and k is not None and n >= m else 0.0 for _, n2, g, a in tasks if n2 == n])
            for n in rows
        }

    best = policies[summary["best"]]
    best_gains = per_task(best["folds"], best["demonstrations"])
    for k in FOLDS:
        for m in (*DEMONSTRATIONS, None):
            row = policies[policy_name(k, m)]
            gains = per_task(k, m)
            assert abs(row["gain"] - np.mean([g.mean() for g in gains.values()])) < 1e-5
            differences = {n: best_gains[n] - gains[n] for n in rows}
            assert abs(row["gap"] - np.mean([d.mean() for d in differences.values()])) < 1e-5
            variance = sum(d.var(ddof=1) / len(d) if len(d) > 1 else 0.0 for d in differences.values())
            assert abs(row["error"] - np.sqrt(variance) / len(rows)) < 1e-5
    assert policies[policy_name(FOLDS[0], None)]["gain"] == 0


def test_a_policy_comparing_where_it_costs_recall_does_not_qualify() -> None:
    folds = dict.fromkeys(FOLDS, -2.0)  # comparing gains a nat on every task...
    results = [_result(p, n, -3.0, folds, auto_admits=FRESH - 10) for p in PROFILES for n in DEMONSTRATIONS]  # ...but admits fewer
    summary = summarize(results)
    assert summary["recall"]["general"] == 1.0 and summary["recall"][str(FOLDS[0])] == (FRESH - 10) / FRESH
    for k in FOLDS:
        assert not summary["policies"][policy_name(k, RECALL_DEMONSTRATIONS)]["qualifies"]
        assert summary["policies"][policy_name(k, RECALL_DEMONSTRATIONS + 1)]["qualifies"]
    # The best of the rest compares from the first threshold above the recall's, with the fewest folds; the
    # conventional policy gains as much, so it is kept.
    assert summary["best"] == policy_name(FOLDS[0], RECALL_DEMONSTRATIONS + 1)
    assert summary["chosen"] == policy_name(*CONVENTIONAL)


def test_the_distance_from_the_best_and_its_error_by_hand() -> None:
    # With 2 folds comparing gains 1 and 3 nats on the tasks of 2 demonstrations, 0 and 2 on those of 3, 0 on
    # the one of 4. Compared from 2 on: (2 + 1 + 0) / 3 = 1. From 3 on: (0 + 1 + 0) / 3, behind by 2/3; the
    # paired differences are the first row's gains (1, 3: variance 2) and 0 elsewhere: error sqrt(2 / 2) / 3.
    gains = {2: (1.0, 3.0), 3: (0.0, 2.0)}
    other = dict.fromkeys(FOLDS[1:], -10.0)  # the other folds lose: never best
    results = [
        _result("uniform" if n == 3 else "ikea", n, -5.0, {FOLDS[0]: -5.0 + gain, **other})
        for n, pair in gains.items()
        for gain in pair
    ]
    results.append(_result("uniform", RECALL_DEMONSTRATIONS, -5.0, dict.fromkeys(FOLDS, -5.0)))
    summary = summarize(results)
    policies = summary["policies"]
    assert summary["best"] == policy_name(FOLDS[0], 2)
    assert policies[policy_name(FOLDS[0], 2)]["gain"] == 1.0
    row = policies[policy_name(FOLDS[0], 3)]
    assert (row["gain"], row["gap"], row["error"]) == (round(1 / 3, 6), round(2 / 3, 6), round((2 / 2) ** 0.5 / 3, 6))


def _policy(
    gain: float, folds: int | None, demonstrations: int | None, qualifies: bool = True, gap: float = 0.0, error: float = 0.0
) -> dict[str, Any]:
    return {"gain": gain, "folds": folds, "demonstrations": demonstrations, "qualifies": qualifies, "gap": gap, "error": error}


CONVENTIONAL_NAME = policy_name(*CONVENTIONAL)


def test_choose_is_the_best_gain_among_the_qualified_unless_the_convention_is_within_one_error() -> None:
    table = {
        "a": _policy(0.5, 5, 3, qualifies=False),
        "b": _policy(0.2, 10, 5),
        "c": _policy(0.2, 3, 6),
        "d": _policy(0.2, 3, 8),
        CONVENTIONAL_NAME: _policy(0.1, *CONVENTIONAL, gap=0.1, error=0.05),
        "never": _policy(0.0, None, None),
    }
    assert choose(table) == "d"  # a costs recall; b, c, d tie: fewer folds, then comparing later
    table[CONVENTIONAL_NAME]["error"] = 0.1  # exactly one error behind: within
    assert choose(table) == CONVENTIONAL_NAME
    table[CONVENTIONAL_NAME]["qualifies"] = False
    assert choose(table) == "d"
    assert choose({"never": _policy(0.0, None, None), "x": _policy(0.0, 2, 20)}) == "never"
    assert choose({"a": table["a"]}) is None


def test_the_findings_name_each_choice_or_say_that_nothing_qualified() -> None:
    metrics = json.loads((Path(__file__).parent / "reports" / "selection-settings" / "metrics.json").read_text())
    verdicts = [f.as_json()["verdict"] for f in findings(metrics)]
    assert all(v in ("the best on generated tasks", "within one standard error of the best") for v in verdicts)
    nothing = {
        **metrics, "chosen": None,
        "subtasks": {**metrics["subtasks"], "chosen": None}, "evidence": {**metrics["evidence"], "chosen": None},
    }
    found = [f.as_json() for f in findings(nothing)]
    assert [f["verdict"] for f in found] == ["no policy qualifies", "no threshold qualifies", "no level qualifies"]
