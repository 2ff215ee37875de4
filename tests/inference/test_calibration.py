"""The next-step predictor's back-off and smoothing, fitted by cross-validation inside fit, and the calibration
figures ``evaluate`` reports (expected calibration error, reliability table)."""

from __future__ import annotations

import math
from collections import Counter
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.evaluation.crossval import RELIABILITY_BINS, StepScores
from supportive.inference import StepPredictor
from supportive.inference.bigram import END, OpenBigram
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, sample_ordering

TASK = ChainNode((ActionNode("k"), CliqueNode((ActionNode("a"), ActionNode("b"), ActionNode("c"))), ActionNode("z")))


def _demos(n: int, seed: int) -> list[list[str]]:
    rng = np.random.default_rng(seed)
    return [[a for a, _ in sample_ordering(TASK, rng)] for _ in range(n)]


def test_the_chosen_pair_has_the_best_held_out_log_likelihood_of_the_grid() -> None:
    demos = _demos(12, 0)
    predictor = StepPredictor(smoothing_grid=(0.25, 1.0, 4.0), backoff_grid=(0.0, 0.1, 0.5)).fit(demos)
    calibration = predictor.calibration_
    table = np.asarray(calibration.log2)
    assert table.shape == (3, 3) and calibration.folds == 5
    row, column = np.unravel_index(int(np.argmax(table)), table.shape)
    assert (calibration.smoothing, calibration.backoff) == ((0.25, 1.0, 4.0)[row], (0.0, 0.1, 0.5)[column])
    assert calibration.steps == sum(len(d) + 1 for d in demos)


def test_given_settings_are_kept_and_too_few_demonstrations_take_the_grids_first() -> None:
    demos = _demos(8, 1)
    fixed = StepPredictor(smoothing=2.0, backoff=0.2).fit(demos)
    assert (fixed.calibration_.smoothing, fixed.calibration_.backoff, fixed.calibration_.folds) == (2.0, 0.2, 0)
    few = StepPredictor().fit(demos[:2])
    assert (few.calibration_.smoothing, few.calibration_.backoff, few.calibration_.folds) == (1.0, 0.1, 0)


def test_the_back_off_is_the_open_bigram_mixed_in() -> None:
    demos = _demos(10, 2)
    alone = StepPredictor(backoff=0.0, smoothing=1.0).fit(demos)
    mixed = StepPredictor(backoff=0.3, smoothing=1.0).fit(demos)
    bigram = OpenBigram().fit(demos)
    prefix = ["k", "b"]
    expected = {a: 0.7 * alone.next_step(prefix).get(a, 0.0) + 0.3 * p for a, p in bigram.next_step(prefix).items()}
    assert mixed.next_step(prefix) == pytest.approx(expected)
    assert math.isclose(sum(mixed.next_step(prefix).values()), 1.0)
    assert min(mixed.next_step(["k", "b", "z"]).values()) > 0, "with a back-off no step has probability 0"


_WORDS = st.lists(st.lists(st.sampled_from("abcd"), min_size=1, max_size=6), min_size=1, max_size=6)


@settings(max_examples=60, deadline=None)
@given(demos=_WORDS, prefix=st.lists(st.sampled_from("abcd"), max_size=6))
def test_the_open_bigram_never_ranks_a_finished_action_above_an_open_one(demos: list[list[str]], prefix: list[str]) -> None:
    """By its definition, counted by hand: open actions get their evidence plus one, finished ones only one."""
    bigram = OpenBigram().fit(demos)
    known = [a for a in prefix if a in bigram.actions_]
    most = {a: max(d.count(a) for d in demos) for a in bigram.actions_}
    done = Counter(known)
    finished = {a for a in most if done[a] >= most[a]}
    after = [d[i + 1] if i + 1 < len(d) else END for d in demos for i in range(len(d)) if known and d[i] == known[-1]]
    if not known:
        after = [d[0] for d in demos]
    into_open = Counter(a for a in after if a not in finished)
    if not into_open:
        into_open = Counter({a: sum(d.count(a) for d in demos) for a in most if a not in finished} | {END: len(demos)})
    expected = {a: into_open.get(a, 0) + 1.0 for a in [*most, END]}
    total = sum(expected.values())
    got = bigram.next_step(known)
    assert got == pytest.approx({a: w / total for a, w in expected.items()})
    assert min(got.values()) > 0
    assert all(got[f] <= got[o] for f in finished for o in set(got) - finished)


@pytest.mark.parametrize("settings", [{"backoff": 1.0}, {"smoothing": 0.0}, {"calibration_folds": 1}])
def test_bad_settings_are_refused(settings: dict[str, Any]) -> None:
    with pytest.raises(LearningError):
        StepPredictor(**settings)


def test_calibration_error_and_reliability_table_by_hand() -> None:
    scores = StepScores()
    scores.add({"a": 0.95, "b": 0.05}, "a", set())  # right at 0.95
    scores.add({"a": 0.95, "b": 0.05}, "b", set())  # wrong at 0.95
    scores.add({"a": 0.35, "b": 0.65}, "b", set())  # right at 0.65
    assert len(scores.bins) == RELIABILITY_BINS
    table = scores.reliability()
    assert [(r["from"], r["predictions"], r["confidence"], r["accuracy"]) for r in table] == [
        (0.6, 1, 0.65, 1.0),
        (0.9, 2, 0.95, 0.5),
    ]
    assert scores.calibration_error() == pytest.approx((abs(1 - 0.65) + 2 * abs(0.5 - 0.95)) / 3)
    merged = StepScores()
    merged.merge(scores)
    merged.merge(scores)
    assert merged.reliability()[1]["predictions"] == 4 and merged.calibration_error() == pytest.approx(scores.calibration_error())
