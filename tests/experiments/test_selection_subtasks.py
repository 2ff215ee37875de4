"""selection-settings' sweep of ``subtask_demonstrations``: each threshold's gain over the grid, its distance
from the best, and the procedure that picks the default."""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from supportive.experiments.selection_settings.measure import DEMONSTRATIONS, FRESH, RECALL_DEMONSTRATIONS
from supportive.experiments.selection_settings.subtasks import choose_threshold, summarize_thresholds
from supportive.generate.mistakes import PROFILES


def _result(profile: str, n: int, made: float, none: float, made_admits: int = FRESH) -> dict[str, Any]:
    """The part of a trial's result the sweep reads."""
    return {
        "profile": profile,
        "demonstrations": n,
        "people": "uniform",
        "subtasks": {"made": {"log_likelihood": made, "admitted": made_admits}, "none": {"log_likelihood": none, "admitted": FRESH}},
    }


_likelihood = st.floats(-30, -1, allow_nan=False).map(lambda x: round(x, 3))


@given(
    st.lists(
        st.tuples(st.sampled_from(PROFILES), st.sampled_from(DEMONSTRATIONS), _likelihood, _likelihood),
        min_size=1,
        max_size=12,
    )
)
def test_each_thresholds_gain_and_distance_from_the_best_are_worked_out_task_by_task(
    tasks: list[tuple[str, int, float, float]],
) -> None:
    # The oracle: a threshold's gain on a task is making subtasks' score minus making none's from the
    # threshold on and 0 below; the mean of each row, then over the rows; the distance from the best the same
    # of the paired differences, its variance that of a mean of independent row means.
    summary = summarize_thresholds([_result(*task) for task in tasks], DEMONSTRATIONS, FRESH)
    rows = sorted({n for _, n, _, _ in tasks})

    def per_task(k: int) -> dict[int, np.ndarray]:
        return {n: np.array([m - z if n >= k else 0.0 for _, n2, m, z in tasks if n2 == n]) for n in rows}

    qualified = [k for k in DEMONSTRATIONS if k <= RECALL_DEMONSTRATIONS]
    means = {k: float(np.mean([g.mean() for g in per_task(k).values()])) for k in DEMONSTRATIONS}
    best = summary["best"]
    assert best in qualified and means[best] >= max(means[k] for k in qualified) - 1e-5
    for k in DEMONSTRATIONS:
        row = summary["thresholds"][str(k)]
        assert row["qualifies"] == (k in qualified)
        assert abs(row["gain"] - means[k]) < 1e-5
        differences = {n: per_task(best)[n] - per_task(k)[n] for n in rows}
        assert abs(row["gap"] - np.mean([d.mean() for d in differences.values()])) < 1e-5
        variance = sum(d.var(ddof=1) / len(d) if len(d) > 1 else 0.0 for d in differences.values())
        assert abs(row["error"] - np.sqrt(variance) / len(rows)) < 1e-5
    chosen = summary["chosen"]
    assert chosen is not None and chosen >= best and summary["thresholds"][str(chosen)]["qualifies"]


def test_subtasks_that_help_from_two_demonstrations_on_are_made_from_two() -> None:
    # Making subtasks gains a nat on every task of every row, alike, so no threshold's gain is noise: the
    # best (and chosen) makes them from the first row on; thresholds beyond issue #13's row never qualify.
    results = [_result(p, n, -4.0 + 0.1 * i, -5.0 + 0.1 * i) for p in PROFILES for n in DEMONSTRATIONS for i in range(3)]
    summary = summarize_thresholds(results, DEMONSTRATIONS, FRESH)
    assert summary["best"] == summary["chosen"] == DEMONSTRATIONS[0]
    assert summary["thresholds"][str(DEMONSTRATIONS[0])]["gain"] == 1.0
    assert summary["gains"][str(DEMONSTRATIONS[0])]["mean"] == 1.0
    assert not any(row["qualifies"] for k, row in summary["thresholds"].items() if int(k) > RECALL_DEMONSTRATIONS)


def test_where_the_fresh_executions_cannot_tell_the_fewer_claims_are_kept() -> None:
    # Gains that cancel out in the first row: no threshold is ahead by more than its error, so the largest
    # qualifying one (subtasks from issue #13's row) is chosen; the shares admitted are reported per row.
    results = [_result("uniform", DEMONSTRATIONS[0], -4.0, -5.0, made_admits=FRESH // 2), _result("ikea", DEMONSTRATIONS[0], -6.0, -5.0)]
    summary = summarize_thresholds(results, DEMONSTRATIONS, FRESH)
    assert summary["chosen"] == RECALL_DEMONSTRATIONS
    assert summary["admitted"][str(DEMONSTRATIONS[0])] == {"made": 0.75, "none": 1.0}


def test_choose_threshold_by_hand() -> None:
    def row(gap: float, error: float, qualifies: bool = True) -> dict[str, Any]:
        return {"gain": 0.0, "gap": gap, "error": error, "qualifies": qualifies}

    assert choose_threshold({"2": row(0.0, 0.0), "3": row(0.2, 0.1), "4": row(0.1, 0.1), "5": row(0.0, 0.5, False)}) == 4
    assert choose_threshold({"2": row(0.0, 0.0), "3": row(0.2, 0.1)}) == 2
    assert choose_threshold({"5": row(0.0, 0.0, False)}) is None
