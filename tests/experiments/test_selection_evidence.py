"""selection-settings' sweep of ``evidence``: each level's gain over the conventional one, its distance from
the best, and the procedure that picks the default."""

from __future__ import annotations

from typing import Any

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from supportive.experiments.selection_settings.evidence import (
    CONVENTIONAL_EVIDENCE,
    LEVELS,
    choose_level,
    summarize_levels,
)
from supportive.experiments.selection_settings.measure import DEMONSTRATIONS, FRESH, RECALL_DEMONSTRATIONS
from supportive.generate.habits import PEOPLE
from supportive.generate.mistakes import PROFILES


def _result(
    profile: str, n: int, scores: list[float], admits: list[int] | None = None, people: str = "uniform"
) -> dict[str, Any]:
    """The part of a trial's result the sweep reads: the general reading's score and admissions per level."""
    admitted = admits or [FRESH] * len(LEVELS)
    return {
        "profile": profile,
        "demonstrations": n,
        "people": people,
        "evidence": {str(level): {"log_likelihood": s, "admitted": a} for level, s, a in zip(LEVELS, scores, admitted, strict=True)},
    }


_likelihood = st.floats(-30, -1, allow_nan=False).map(lambda x: round(x, 3))
_task = st.tuples(
    st.sampled_from(PROFILES),
    st.sampled_from(DEMONSTRATIONS),
    st.lists(_likelihood, min_size=len(LEVELS), max_size=len(LEVELS)),
    st.lists(st.integers(0, FRESH), min_size=len(LEVELS), max_size=len(LEVELS)),
    st.sampled_from(PEOPLE),
)


@given(st.lists(_task, min_size=1, max_size=12))
def test_each_levels_gain_recall_and_distance_from_the_best_are_worked_out_task_by_task(
    tasks: list[tuple[str, int, list[float], list[int], str]],
) -> None:
    # The oracle: a level's gain on a task is its score minus the conventional level's; the mean of each row,
    # then over the rows; the recall the share of the fresh executions of the uniform tasks by people without
    # habits at issue #13's row; the
    # distance from the best the same of the paired differences, its variance that of a mean of independent
    # row means.
    summary = summarize_levels([_result(*task) for task in tasks], FRESH)
    rows = sorted({n for _, n, _, _, _ in tasks})
    conventional = LEVELS.index(CONVENTIONAL_EVIDENCE)

    def per_task(i: int) -> dict[int, np.ndarray]:
        return {n: np.array([s[i] - s[conventional] for _, n2, s, _, _ in tasks if n2 == n]) for n in rows}

    means = [float(np.mean([g.mean() for g in per_task(i).values()])) for i in range(len(LEVELS))]
    uniform = [a for p, n, _, a, who in tasks if p == "uniform" and n == RECALL_DEMONSTRATIONS and who == "uniform"]
    recall = [sum(a[i] for a in uniform) / (FRESH * len(uniform)) if uniform else None for i in range(len(LEVELS))]
    qualified = [i for i in range(len(LEVELS)) if recall[i] is not None and recall[i] >= recall[conventional]]  # type: ignore[operator]
    best = summary["best"]
    if not qualified:
        assert best is None and summary["chosen"] is None
        return
    assert best in LEVELS and LEVELS.index(best) in qualified
    assert means[LEVELS.index(best)] >= max(means[i] for i in qualified) - 1e-5
    for i, level in enumerate(LEVELS):
        row = summary["levels"][str(level)]
        assert row["qualifies"] == (i in qualified)
        assert abs(row["gain"] - means[i]) < 1e-5
        share = recall[i]
        assert row["recall"] == (None if share is None else round(share, 6))
        differences = {n: per_task(LEVELS.index(best))[n] - per_task(i)[n] for n in rows}
        assert abs(row["gap"] - np.mean([d.mean() for d in differences.values()])) < 1e-5
        variance = sum(d.var(ddof=1) / len(d) if len(d) > 1 else 0.0 for d in differences.values())
        assert abs(row["error"] - np.sqrt(variance) / len(rows)) < 1e-5
    assert summary["levels"][str(CONVENTIONAL_EVIDENCE)]["gain"] == 0.0
    assert summary["chosen"] in (CONVENTIONAL_EVIDENCE, best)


def _uniform_rows(gain: list[float], spread: float) -> list[dict[str, Any]]:
    """Three tasks of every profile and row; level ``i`` scores ``gain[i]`` above the conventional level, give or
    take ``spread`` from task to task."""
    out = []
    for p in PROFILES:
        for n in DEMONSTRATIONS:
            for k in (-1, 0, 1):
                base = -10.0 + 0.1 * k
                out.append(_result(p, n, [base + g + spread * k * (g != 0) for g in gain]))
    return out


def test_a_level_that_predicts_every_task_better_is_chosen() -> None:
    gains = [0.0] * len(LEVELS)
    gains[-1] = 0.5  # the laxest level gains half a nat on every task alike: no noise
    summary = summarize_levels(_uniform_rows(gains, 0.0), FRESH)
    assert summary["best"] == summary["chosen"] == LEVELS[-1]
    assert summary["levels"][str(LEVELS[-1])]["gain"] == 0.5


def test_where_the_fresh_executions_cannot_tell_the_convention_is_kept() -> None:
    gains = [0.0] * len(LEVELS)
    gains[0] = 0.05  # a small gain with much task-to-task spread: within one standard error
    summary = summarize_levels(_uniform_rows(gains, 3.0), FRESH)
    assert summary["best"] == LEVELS[0]
    assert summary["chosen"] == CONVENTIONAL_EVIDENCE


def test_a_level_that_admits_fewer_fresh_executions_at_issue_13s_row_does_not_qualify() -> None:
    strict = [FRESH] * len(LEVELS)
    strict[-1] = FRESH - 10
    results = [_result("uniform", RECALL_DEMONSTRATIONS, [-5.0, -5.0, -5.0, -5.0, -1.0], strict)]
    summary = summarize_levels(results, FRESH)
    assert not summary["levels"][str(LEVELS[-1])]["qualifies"]
    assert summary["chosen"] == summary["best"] == CONVENTIONAL_EVIDENCE


def test_no_level_qualifies_when_the_run_learned_no_uniform_task_at_issue_13s_row() -> None:
    # neither a task of another profile nor one by people with habits measures issue #13's recall
    results = [
        _result("ikea", RECALL_DEMONSTRATIONS, [-5.0] * len(LEVELS)),
        _result("uniform", RECALL_DEMONSTRATIONS, [-5.0] * len(LEVELS), people="habits"),
    ]
    summary = summarize_levels(results, FRESH)
    assert summary["best"] is None and summary["chosen"] is None
    assert choose_level(summary["levels"], None) is None
