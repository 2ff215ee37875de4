"""The generalisation experiment's CaptainCook4D summary: each learner's mean task-graph F1 over the recipes
with its 95 % interval and the paired difference from the strict learner, and its held-out admission with an
interval over the recipes (a ratio of means), worked out here from Student's t directly."""

from __future__ import annotations

import math
import statistics
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

from supportive.experiments.generalisation.measure import LEARNERS, summarize

SCORE = st.floats(0.0, 1.0, allow_nan=False)


def recipe(
    index: int, f1: dict[str, tuple[float, float]], admitted: int = 1, held_out: int = 2, likelihood: float = -5.0
) -> dict[str, Any]:
    """A recipe trial's result with the given (full, 5-shot) edge F1 per learner, held-out recordings
    admitted of those held out and their mean log-likelihood (every learner alike); the rest are fillers."""
    record: dict[str, Any] = {"index": index, "kind": "recipe", "recipe": f"r{index}", "held_out": held_out}
    for mode in LEARNERS:
        scores = {"precision": 0.5, "recall": 0.5, "all_precision": 0.5}
        edges = {s: {"precision": 0.5, "recall": 0.5, "f1": f} for s, f in zip(("full", "5-shot"), f1[mode], strict=True)}
        record[mode] = {
            "admitted": admitted,
            "held_out_log_likelihood": likelihood,
            "error_free": scores,
            "with_errors": scores,
            "edges": edges,
        }
    return record


def t_interval(values: list[float]) -> tuple[float, float]:
    mean = statistics.fmean(values)
    half = stats.t.ppf(0.975, len(values) - 1) * statistics.stdev(values) / math.sqrt(len(values))
    return mean - half, mean + half


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(SCORE, SCORE, SCORE), min_size=2, max_size=24))
def test_the_f1_interval_and_the_paired_difference_from_strict(rows: list[tuple[float, float, float]]) -> None:
    results = [recipe(i, {"auto": (a, a), "general": (g, g), "strict": (s, s)}) for i, (a, g, s) in enumerate(rows)]
    edges = summarize(results)["captaincook"]
    for mode, column in (("auto", 0), ("general", 1), ("strict", 2)):
        values = [row[column] for row in rows]
        summary = edges[mode]["edges"]["full"]
        assert summary["f1"] == pytest.approx(statistics.fmean(values), abs=1e-4)
        low, high = t_interval(values)
        assert summary["f1_interval"]["low"] == pytest.approx(max(0.0, low), abs=1e-4)
        assert summary["f1_interval"]["high"] == pytest.approx(min(1.0, high), abs=1e-4)
        assert summary["f1_interval"]["low"] <= summary["f1"] <= summary["f1_interval"]["high"]
        if mode == "strict":
            assert "f1_minus_strict" not in summary
            continue
        paired = [row[column] - row[2] for row in rows]
        difference = summary["f1_minus_strict"]
        assert difference["n"] == len(rows) and difference["mean"] == pytest.approx(statistics.fmean(paired), abs=1e-4)
        if statistics.stdev(paired) > 0:
            assert (difference["low"], difference["high"]) == pytest.approx(t_interval(paired), abs=1e-4)


def test_one_recipe_gives_no_interval() -> None:
    edges = summarize([recipe(0, {m: (0.8, 0.7) for m in LEARNERS})])["captaincook"]["auto"]["edges"]
    assert edges["5-shot"]["f1"] == 0.7 and edges["5-shot"]["f1_interval"] == {"low": None, "high": None}
    assert edges["5-shot"]["f1_minus_strict"] == {"mean": 0.0, "low": None, "high": None, "n": 1}


@settings(max_examples=40, deadline=None)
@given(st.lists(st.integers(1, 9).flatmap(lambda n: st.tuples(st.integers(0, n), st.just(n))), min_size=2, max_size=24))
def test_the_admission_interval_is_over_the_recipes(counts: list[tuple[int, int]]) -> None:
    results = [recipe(i, {m: (0.5, 0.5) for m in LEARNERS}, *pair, likelihood=-pair[0] - i) for i, pair in enumerate(counts)]
    auto = summarize(results)["captaincook"]["auto"]
    # the held-out log-likelihood: the mean over the recipes, with Student's t interval over them
    likelihoods = [-float(a) - i for i, (a, _) in enumerate(counts)]
    assert auto["held_out_log_likelihood"]["mean"] == pytest.approx(statistics.fmean(likelihoods), abs=1e-4)
    assert auto["held_out_log_likelihood"]["low"] == pytest.approx(t_interval(likelihoods)[0], abs=1e-4)
    admitted, held = [float(a) for a, _ in counts], [float(n) for _, n in counts]
    share = sum(admitted) / sum(held)
    assert auto["admission"] == pytest.approx(share, abs=1e-4)
    residuals = [a - share * n for a, n in zip(admitted, held, strict=True)]
    half = stats.t.ppf(0.975, len(counts) - 1) * statistics.stdev(residuals) / math.sqrt(len(counts)) / statistics.fmean(held)
    assert auto["admission_interval"]["low"] == pytest.approx(max(0.0, share - half), abs=1e-4)
    assert auto["admission_interval"]["high"] == pytest.approx(min(1.0, share + half), abs=1e-4)
