"""The next-step predictor's back-off and smoothing, fitted by cross-validation inside fit, and the calibration
figures ``evaluate`` reports (expected calibration error, reliability table)."""

from __future__ import annotations

import itertools
import math
from collections import Counter
from typing import Any, cast

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import LearningError
from supportive.evaluation.crossval import RELIABILITY_BINS, StepScores
from supportive.inference import StepPredictor
from supportive.inference.bigram import END, OpenBigram
from supportive.learning.learner import Mode
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, sample_ordering

TASK = ChainNode((ActionNode("k"), CliqueNode((ActionNode("a"), ActionNode("b"), ActionNode("c"))), ActionNode("z")))


def _demos(n: int, seed: int) -> list[list[str]]:
    rng = np.random.default_rng(seed)
    return [[a for a, _ in sample_ordering(TASK, rng)] for _ in range(n)]


def test_the_chosen_settings_have_the_best_held_out_log_likelihood_of_the_grids() -> None:
    demos = _demos(12, 0)
    predictor = StepPredictor(smoothing_grid=(0.25, 1.0, 4.0), backoff_grid=(0.0, 0.1, 0.5)).fit(demos)
    calibration = predictor.calibration_
    table = np.asarray(calibration.log2)
    assert table.shape == (3, 3, 3) and calibration.folds == 5
    i, j, k = np.unravel_index(int(np.argmax(table)), table.shape)
    chosen = (calibration.smoothing, calibration.backoff, calibration.off_script_backoff)
    assert chosen == ((0.25, 1.0, 4.0)[i], (0.0, 0.1, 0.5)[j], (0.0, 0.1, 0.5)[k])
    assert calibration.steps == sum(len(d) + 1 for d in demos)


def _slipped(seed: int) -> list[list[str]]:
    """Clean demonstrations and two with a step out of place (the tracker reads those steps as off script)."""
    return [*_demos(10, seed), ["k", "z", "a", "b", "c"], ["a", "k", "b", "c", "z"]]


def test_the_calibration_table_is_the_held_out_log_likelihood_of_each_fixed_predictor() -> None:
    """Brute force: each cell of the table, recomputed by fitting a predictor with those three settings fixed
    on each fold and scoring its sessions on the held-out demonstrations."""
    demos = _slipped(3)
    smoothings, weights = (0.5, 2.0), (0.0, 0.3, 0.8)
    fitted = StepPredictor(smoothing_grid=smoothings, backoff_grid=weights, calibration_folds=4).fit(demos)
    calibration = fitted.calibration_
    reading = cast(Mode, fitted.learner_.reading_)
    for (i, smoothing), (j, on), (k, off) in itertools.product(enumerate(smoothings), enumerate(weights), enumerate(weights)):
        total, steps = 0.0, 0
        for fold in range(4):
            train = [d for n, d in enumerate(demos) if n % 4 != fold]
            fixed = StepPredictor(mode=reading, smoothing=smoothing, backoff=on, off_script_backoff=off).fit(train)
            for held in (d for n, d in enumerate(demos) if n % 4 == fold):
                session = fixed.session()
                for truth in [*held, END]:
                    total += math.log2(max(session.next_step().get(truth, 0.0), 1e-300))
                    steps += 1
                    if truth != END:
                        session.observe(truth)
        assert calibration.log2[i][j][k] == pytest.approx(total / steps)


def test_given_settings_are_kept_and_too_few_demonstrations_take_the_grids_first() -> None:
    demos = _demos(8, 1)
    fixed = StepPredictor(smoothing=2.0, backoff=0.2, off_script_backoff=0.6).fit(demos)
    calibration = fixed.calibration_
    assert (calibration.smoothing, calibration.backoff, calibration.off_script_backoff, calibration.folds) == (2.0, 0.2, 0.6, 0)
    few = StepPredictor().fit(demos[:2]).calibration_
    assert (few.smoothing, few.backoff, few.off_script_backoff, few.folds) == (1.0, 0.1, 0.1, 0)


def test_the_back_off_is_the_open_bigram_mixed_in_by_whether_the_last_step_was_off_script() -> None:
    demos = _slipped(2)
    # the general reading (the clique of a, b, c, whichever order was seen): which reading auto keeps from
    # twelve demonstrations is not what this test is about
    alone = StepPredictor(mode="general", backoff=0.0, off_script_backoff=0.0, smoothing=1.0).fit(demos)
    mixed = StepPredictor(mode="general", backoff=0.1, off_script_backoff=0.8, smoothing=1.0).fit(demos)
    bigram = OpenBigram().fit(demos)
    for prefix, lost in ((["k", "b"], False), (["k", "z"], True)):
        session = mixed.session()
        for action in prefix:
            session.observe(action)
        off = session.tracker.last.off_script
        assert (off > 0.5) == lost, "z before the clique is off script; k then b is not"
        weight = (1 - off) * 0.1 + off * 0.8
        model = alone.next_step(prefix)
        expected = {a: (1 - weight) * model.get(a, 0.0) + weight * p for a, p in bigram.next_step(prefix).items()}
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


@pytest.mark.parametrize(
    "settings", [{"backoff": 1.0}, {"off_script_backoff": -0.1}, {"smoothing": 0.0}, {"calibration_folds": 1}]
)
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
