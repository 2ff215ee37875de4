"""The learner-settings choice's spread: worst F1s from pooled counts, resampled within cells, checked against
a plain computation and, on a tiny run, against the exact bootstrap distribution by enumeration."""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import ExperimentError
from supportive.experiments.learner_settings.measure import summarize
from supportive.experiments.learner_settings.spread import spread, worst_f1s

NAMES = ["a", "b", "c"]


def _plain_worst(tasks: list[dict[str, Any]], name: str) -> float:
    """The worst F1 over cells, written out with Python numbers (the oracle)."""
    cells: dict[tuple[str, int], list[dict[str, Any]]] = {}
    for t in tasks:
        if t["case"] != "none":
            cells.setdefault((t["case"], t["demonstrations"]), []).append(t)
    worst = math.inf
    for members in cells.values():
        if not sum(t["mistakes"] for t in members):  # no mistake could be put in: not a cell of the table
            continue
        reported = sum(t["settings"][name]["reported"] for t in members)
        right = sum(t["settings"][name]["right"] for t in members)
        found = sum(t["settings"][name]["found"] for t in members)
        mistakes = sum(t["mistakes"] for t in members)
        p = right / reported if reported else 1.0
        r = found / mistakes
        worst = min(worst, 2 * p * r / (p + r) if p + r else 0.0)
    return 0.0 if worst == math.inf else worst


@st.composite
def _tasks(draw: st.DrawFn) -> list[dict[str, Any]]:
    tasks = []
    for _ in range(draw(st.integers(1, 8))):
        mistakes = draw(st.integers(0, 4))  # 0: no place a mistake could go
        row = {}
        for name in NAMES:
            reported = draw(st.integers(0, 5))
            right = draw(st.integers(0, reported))
            row[name] = {"reported": reported, "right": right, "found": min(right, mistakes)}
        tasks.append({
            "case": draw(st.sampled_from(["moved", "dropped"])), "demonstrations": draw(st.sampled_from([20, 50])),
            "mistakes": mistakes, "settings": row,
        })
    clean = {name: {"reported": 3, "right": 0, "found": 0} for name in NAMES}
    return [*tasks, {"case": "none", "demonstrations": 7, "mistakes": 0, "settings": clean}]


@settings(max_examples=60, deadline=None)
@given(_tasks(), st.integers(0, 2), st.integers(0, 10))
def test_the_spread_is_paired_and_scores_what_a_plain_count_scores(tasks: list[dict[str, Any]], at: int, seed: int) -> None:
    observed = worst_f1s(tasks, NAMES)
    assert observed == pytest.approx([_plain_worst(tasks, n) for n in NAMES], abs=1e-12)
    out = spread(tasks, NAMES, NAMES[at], resamples=50, seed=seed)
    assert out[NAMES[at]]["gap"] == 0.0 and out[NAMES[at]]["error"] == 0.0  # paired: itself minus itself
    for name in NAMES:
        assert out[name]["gap"] == round(observed[at] - observed[NAMES.index(name)], 4)
        assert out[name]["error"] >= 0
    assert sum(s["best_share"] for s in out.values()) == pytest.approx(1.0, abs=2e-4)
    assert spread(tasks, NAMES, NAMES[at], resamples=50, seed=seed) == out  # same seed, same numbers


def test_the_bootstrap_error_is_the_exact_one_of_a_tiny_run() -> None:
    # One cell of three tasks: the 27 equally likely resamples, enumerated, give the exact bootstrap standard
    # error of b's worst F1 minus a's; 20,000 random resamples estimate it.
    counts = [((2, 2, 2), (1, 1, 1)), ((2, 1, 1), (2, 2, 2)), ((3, 1, 1), (2, 1, 1))]
    tasks = [
        {"case": "moved", "demonstrations": 20, "mistakes": 2, "settings": {
            "a": dict(zip(("reported", "right", "found"), a, strict=True)),
            "b": dict(zip(("reported", "right", "found"), b, strict=True)),
        }}
        for a, b in counts
    ]
    differences = [
        _plain_worst([tasks[i] for i in draw], "b") - _plain_worst([tasks[i] for i in draw], "a")
        for draw in itertools.product(range(3), repeat=3)
    ]
    out = spread(tasks, ["a", "b"], "b", resamples=20_000, seed=3)
    assert out["a"]["error"] == pytest.approx(float(np.std(differences)), abs=0.004)
    exact_best = sum(
        _plain_worst([tasks[i] for i in draw], "a") >= _plain_worst([tasks[i] for i in draw], "b")
        for draw in itertools.product(range(3), repeat=3)
    ) / 27  # ties go to the first in grid order, "a"
    assert out["a"]["best_share"] == pytest.approx(exact_best, abs=0.015)


def test_the_summary_carries_the_spread_of_the_qualified_settings() -> None:
    row = {"reported": 1, "right": 1, "found": 1, "wrong_tasks": 0}
    noisy = {"reported": 400, "right": 0, "found": 0, "wrong_tasks": 1}  # reports every step of a clean task
    tasks = [
        {"index": 0, "case": "moved", "demonstrations": 20, "people": "uniform", "steps": 40, "mistakes": 1,
         "settings": {"quiet": row, "loud": row}},
        {"index": 1, "case": "none", "demonstrations": 50, "people": "uniform", "steps": 400, "mistakes": 0,
         "settings": {"quiet": {"reported": 0, "right": 0, "found": 0, "wrong_tasks": 0}, "loud": noisy}},
    ]
    summary = summarize(tasks)
    assert summary["chosen"] == "quiet"
    assert summary["spread"] == {"quiet": {"gap": 0.0, "error": 0.0, "best_share": 1.0}}


def test_without_tasks_with_mistakes_every_worst_f1_is_0_and_ties_go_to_the_first() -> None:
    clean = {"case": "none", "demonstrations": 7, "mistakes": 0, "settings": {n: {"reported": 0} for n in NAMES}}
    assert list(worst_f1s([clean], NAMES)) == [0.0, 0.0, 0.0]
    out = spread([clean], NAMES, "b", resamples=10)
    assert out["b"] == {"gap": 0.0, "error": 0.0, "best_share": 0.0} and out["a"]["best_share"] == 1.0


def test_a_chosen_setting_must_be_qualified() -> None:
    with pytest.raises(ExperimentError, match="not among the qualified"):
        spread([], ["a"], "b")
