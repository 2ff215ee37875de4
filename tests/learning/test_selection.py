"""The reading ``auto`` keeps: held-out likelihood with the one-standard-error rule."""

from __future__ import annotations

import itertools
import math
import statistics

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.generate.mistakes import random_known_task
from supportive.learning import HTNLearner
from supportive.learning.selection import _within_one_error

values = st.lists(st.floats(-20, 0, allow_nan=False), min_size=1, max_size=12)


@given(data=st.data(), best=values)
def test_within_one_error_is_the_paired_standard_error_rule(data: st.DataObject, best: list[float]) -> None:
    candidate = data.draw(st.lists(st.floats(-20, 0, allow_nan=False), min_size=len(best), max_size=len(best)))
    differences = [b - c for b, c in zip(best, candidate, strict=True)]
    mean = statistics.fmean(differences)
    error = statistics.stdev(differences) / math.sqrt(len(differences)) if len(differences) > 1 else 0.0
    if mean <= 0:
        assert _within_one_error(candidate, best)
    elif len(differences) == 1:
        assert not _within_one_error(candidate, best)
    elif not math.isclose(mean, error, rel_tol=1e-9):
        assert _within_one_error(candidate, best) == (mean < error)
    else:  # exactly one error away: within, whatever the rounding
        assert _within_one_error(candidate, best)


def test_a_reading_better_on_every_held_out_demonstration_is_kept_however_little() -> None:
    assert not _within_one_error([-3.0, -3.0, -3.0], [-2.99, -2.99, -2.99])
    assert _within_one_error([-3.0, -2.0, -3.0, -2.0], [-2.0, -3.0, -2.0, -2.9])  # a mean gain below its error


def test_one_held_out_demonstration_alone_telling_them_apart_is_within_one_error() -> None:
    """Its gain ``d`` among ``n`` gives mean and standard error both ``d / n``: a tie the rounding of the sums
    must not break (CaptainCook4D's tomatochutney, 5 recordings, flipped between two ways of summing)."""
    for n, gain in itertools.product((2, 3, 5, 7, 12), (0.1, 0.992 * 5, 4.96, 37.3)):
        best = [-3.0] * n
        candidate = [-3.0 - gain, *best[1:]]
        assert _within_one_error(candidate, best), (n, gain)


def test_more_clean_demonstrations_do_not_make_a_tighter_reading_win_by_chance() -> None:
    """benchmarks/bench_admission.py's first ``uniform`` task (four steps in any order, then a clique of a
    chain and a step): from 32 of its demonstrations, which happen to show 20 distinct orders, the strict
    reading scored a higher held-out likelihood than the general one (−3.77 against −3.87 nats) by less than
    its standard error and was kept, refusing 29 % of the valid executions that 16 demonstrations had
    admitted. Within one standard error the default reading is kept."""
    rng = np.random.default_rng(0)
    for _ in range(8):  # the benchmark's ikea tasks come first, from the same generator
        task = random_known_task("ikea", 7, rng)
        for _ in range(200):
            task.sample(rng)
    task = random_known_task("uniform", 7, rng)
    valid = [order for order in itertools.permutations(sorted(set(task.sample(0)))) if task.admits(order)]
    demos = [task.sample(rng) for _ in range(200)]
    for n in (16, 32, 64):
        learner = HTNLearner().fit(demos[:n])
        assert learner.reading_ == "general", n
        assert all(learner.htn_.admits(list(order)) for order in valid)
    selection = HTNLearner().fit(demos[:32]).selection_
    assert selection is not None
    assert selection.reason == "held-out likelihood (strict best by 0.104 nats, within one standard error, 0.183)"


def test_a_tighter_reading_kept_says_by_how_much_it_beat_general() -> None:
    """Three blocks in any order (6 executions), 20 demonstrations that never show one of them (a sample
    ``selection-settings`` drew: a chance of 2.6 %). Every held-out demonstration is one the strict reading saw,
    so it predicts each with probability 1/5 where ``general`` gives 1/6: better by ``log(6/5)`` nats on every
    one, with no spread — and the reason says so."""
    blocks = {"H": ["h1", "h2"], "P": ["p1", "p2", "p3", "p4"], "S": ["s1", "s2", "s3", "s4"]}
    shown = [
        "HPS", "PHS", "SHP", "HSP", "SPH", "HPS", "PHS", "SHP", "HPS", "HSP",
        "PHS", "SPH", "HPS", "PHS", "SHP", "HPS", "PHS", "SHP", "HPS", "PHS",
    ]  # fmt: skip
    learner = HTNLearner().fit([[step for block in order for step in blocks[block]] for order in shown])
    selection = learner.selection_
    assert selection is not None and learner.reading_ == "strict"
    assert math.isclose(selection.scores["strict"] - selection.scores["general"], math.log(6 / 5))
    assert selection.reason == f"held-out likelihood (strict against general: +{math.log(6 / 5):.3f} nats, standard error 0.000)"


@pytest.mark.parametrize(
    "demos",
    [
        "abcdfeg abdcefg bacdefg abcdfeg abcdefg abcdefg abcdegf abcdefg abcdefg abcdefg abcefdg",
        "abcdfeg abcdefg abcdefg abcdefg abcdefg acbdefg abcdefg abcdfeg bacdefg abcdefg abcedfg abcdefg abcdefg "
        "abdecfg",
    ],
)
def test_a_step_slipped_on_stays_required_whichever_reading_is_kept(demos: str) -> None:
    # every demonstration does every step, one of them out of place in a few: the readings are learned and
    # held out with those steps put back, not deleted (deleted, the strict reading learned them as optional
    # and, kept, admitted the task without them)
    sequences = [list(demo) for demo in demos.split()]
    learner = HTNLearner().fit(sequences)
    assert learner.deviations_
    for step in "abcdefg":
        assert not any(learner.htn_.admits([s for s in demo if s != step]) for demo in sequences)
