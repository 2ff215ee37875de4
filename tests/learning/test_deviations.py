"""Slips set aside: the incremental search against a from-scratch oracle, and what it does on order errors."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import binomtest

from supportive.learning import HTNLearner
from supportive.learning.deviations import VARYING_WEIGHT, Deviation, set_aside
from supportive.learning.evidence import slip_allowance
from supportive.learning.precedence import implied_precedences
from supportive.tasks.htn import Leaf


def _oracle_out_of_order(
    demos: list[list[Leaf]], evidence: float, budget: int
) -> list[tuple[int, Leaf]]:
    """Out-of-order slips by the definition, everything recounted from scratch before each choice."""
    kept = [list(enumerate(d)) for d in demos]
    chosen: list[tuple[int, Leaf]] = []
    leaves = sorted({leaf for d in demos for leaf in d})
    while budget > 0:
        order = [[leaf for _, leaf in d] for d in kept]

        def count(a: Leaf, b: Leaf, order: list[list[Leaf]] = order) -> int:
            return sum(1 for d in order if a in d and b in d and d.index(a) < d.index(b))

        def agreed(a: Leaf, b: Leaf) -> bool:
            first, second = count(a, b), count(b, a)
            return 0 < second < first and binomtest(second, first + second, 0.5).pvalue < evidence

        def varying(a: Leaf, b: Leaf) -> bool:
            return count(a, b) > 0 and count(b, a) > 0 and not agreed(a, b) and not agreed(b, a)

        best: tuple[tuple[float, int, int], int, int] | None = None
        for d, demo in enumerate(order):
            reversing = {x: sum(agreed(y, x) for y in demo[i + 1 :]) + sum(agreed(x, y) for y in demo[:i])
                         for i, x in enumerate(demo)}
            score = {x: reversing[x] - VARYING_WEIGHT * sum(varying(x, y) for y in demo if y != x) for x in demo}
            if not score or max(score.values()) <= 0:
                continue
            top = max(score.values())
            position = min(i for i, x in enumerate(demo) if score[x] == top)
            key = (top, sum(reversing.values()), -d)
            if best is None or key > best[0]:
                best = (key, d, position)
        if best is None:
            break
        _, d, position = best
        chosen.append((d, kept[d].pop(position)[1]))
        budget -= 1
    assert leaves  # the oracle saw the task
    return chosen


@st.composite
def _noisy_demonstrations(draw: st.DrawFn) -> list[list[Leaf]]:
    size = draw(st.integers(3, 6))
    base = [(chr(ord("a") + i), 1) for i in range(size)]
    demos = []
    for _ in range(draw(st.integers(10, 14))):
        demo = list(base)
        for _ in range(draw(st.integers(0, 2))):
            i = draw(st.integers(0, size - 1))
            step = demo.pop(i)
            demo.insert(draw(st.integers(0, size - 1)), step)
        demos.append(demo)
    return demos


@settings(max_examples=60, deadline=None)
@given(_noisy_demonstrations())
def test_out_of_order_slips_match_the_from_scratch_oracle(demos: list[list[Leaf]]) -> None:
    share = 0.3
    _, found = set_aside(demos, share)
    budget = math.floor(share * sum(len(d) for d in demos) + 1e-9)
    slips = [(d.demonstration, d.leaf) for d in found if d.kind == "out of order"]
    oracle = _oracle_out_of_order(demos, 0.05, budget)
    assert sorted(slips) == sorted(oracle)


@pytest.mark.parametrize("evidence", [0.01, 0.05, 0.2, 1.0])
def test_slip_allowance_is_the_binomial_test(evidence: float) -> None:
    allowance = slip_allowance(30, evidence)
    for n in range(31):
        passing = [r for r in range(n // 2 + 1) if 2 * r < n and binomtest(r, n, 0.5).pvalue < evidence]
        assert allowance[n] == (max(passing) if passing else -1), n


def test_a_step_done_far_too_late_is_the_slip_not_the_steps_it_passed() -> None:
    # Twelve people do a first, then b, c and d in either order, e, f; three recordings do "a" last, an
    # order error reversing five agreed orders in each: a fifth of the recordings, yet slips.
    clean = [list("abcdef")] * 6 + [list("abdcef")] * 6
    late = [list("bcdefa")] * 3
    learner = HTNLearner().fit([*clean, *late])
    slips = {(d.demonstration, d.leaf[0]) for d in learner.deviations_}
    assert slips == {(i, "a") for i in range(12, 15)}
    pairs = {(a[0], b[0]) for a, b in implied_precedences(learner.htn_)}
    assert {("a", x) for x in "bcdef"} <= pairs
    assert ("c", "d") not in pairs and ("d", "c") not in pairs, "the freely ordered pair stays free"


def test_freely_placed_steps_are_not_slips() -> None:
    # c is placed anywhere after a: its place varies, so no recording's c is a slip.
    demos = [list("acbde"), list("abcde"), list("abdce"), list("abdec")] * 3
    learner = HTNLearner().fit(demos)
    assert not [d for d in learner.deviations_ if d.kind == "out of order"]
    assert all(learner.htn_.admits(d) for d in demos)


def test_deviations_name_their_demonstrations() -> None:
    dev = Deviation(3, 4, ("stir", 2), "out of order")
    assert dev.as_dict(["r1", "r2", "r3", "r4"]) == {
        "demonstration": "r4", "kind": "out of order", "action": "stir", "occurrence": 2, "step": 5,
    }
