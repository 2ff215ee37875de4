"""The "which parts, then any valid order" reading (learning/order_likelihood.py) against counting executions."""

from __future__ import annotations

import dataclasses
import itertools
import math
import random
from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.learning.test_pair_orders import _executions, sampled_demonstrations

from supportive.errors import LearningError
from supportive.learning import HTNLearner
from supportive.learning.order_likelihood import OrderLikelihood
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    kind=st.sampled_from(["ikea", "uniform", "partial order"]),
    mode=st.sampled_from(["general", "strict", "partial order"]),
)
def test_the_orders_of_each_set_of_steps_are_counted_once(seed: int, kind: str, mode: str) -> None:
    # optional steps and roots, skipped on the seen orders' top level too
    demos = sampled_demonstrations(np.random.default_rng(seed), kind, skips=True)
    htn = HTNLearner(mode=mode, alternatives=0, slips=False).fit(demos).htn_  # type: ignore[arg-type]
    executions = _executions(htn)
    orders = Counter(frozenset(e) for e in executions)
    reading = OrderLikelihood(htn)
    for done, count in orders.items():
        assert reading.orders(done) == count
    assert all(reading.log_probability(e) > -np.inf for e in executions)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    kind=st.sampled_from(["ikea", "uniform", "partial order"]),
    mode=st.sampled_from(["general", "strict", "partial order"]),
)
def test_the_habit_reading_names_every_admitted_order_apart_and_tends_to_the_uniform_one(
    seed: int, kind: str, mode: str
) -> None:
    # with a huge concentration every admitted order is as likely: the order choices multiply to the number of
    # orders; with a tiny one a repeated order costs nothing more, and two different orders of the same steps
    # cost much more (so no two orders are read as the same choices)
    rng = np.random.default_rng(seed)
    demos = sampled_demonstrations(rng, kind, skips=True)
    htn = HTNLearner(mode=mode, alternatives=0, slips=False).fit(demos).htn_  # type: ignore[arg-type]
    executions = _executions(htn)
    uniform, flat = OrderLikelihood(htn), OrderLikelihood(htn, concentration=1e6)
    sample = [executions[int(i)] for i in rng.integers(len(executions), size=6)]
    assert flat.log_probability_of_all(sample) == pytest.approx(uniform.log_probability_of_all(sample), abs=1e-3)
    assert uniform.log_probability_of_all(sample) == pytest.approx(sum(uniform.log_probability(e) for e in sample))
    habitual = OrderLikelihood(htn, concentration=1e-6)
    by_steps: dict[frozenset[tuple[str, int]], list[tuple[tuple[str, int], ...]]] = {}
    for execution in executions:
        by_steps.setdefault(frozenset(execution), []).append(execution)
    for same in by_steps.values():
        first = same[0]
        twice = habitual.log_probability_of_all([first, first])  # the order once, what is done twice
        once = uniform.log_probability(first) + math.log(uniform.orders(frozenset(first)))
        assert twice == pytest.approx(2 * once - math.log(uniform.orders(frozenset(first))), abs=1e-3)
        for other in same[1:3]:
            assert habitual.log_probability_of_all([first, other]) < twice - 5.0


@settings(max_examples=60, deadline=None)
@given(
    orders=st.lists(st.permutations("abc"), min_size=1, max_size=12),
    alpha=st.sampled_from([0.25, 1.0, 3.0]),
    shuffle=st.randoms(use_true_random=False),
)
def test_a_cliques_orders_are_read_as_a_polya_urn_in_any_sequence(
    orders: list[list[str]], alpha: float, shuffle: random.Random
) -> None:
    # the Dirichlet-multinomial of one clique of three steps against drawing the orders one by one from an urn
    # holding alpha of each of the 6 orders plus one more of each order already drawn
    htn = HTN("t", (ChainNode((ActionNode("k"), CliqueNode(tuple(ActionNode(a) for a in "abc")))),))
    executions = [(("k", 1), *((a, 1) for a in order)) for order in orders]
    expected, seen = 0.0, Counter[tuple[str, ...]]()
    for i, order in enumerate(orders):
        expected += math.log((seen[tuple(order)] + alpha) / (i + 6 * alpha))
        seen[tuple(order)] += 1
    reading = OrderLikelihood(htn, concentration=alpha)
    assert reading.log_probability_of_all(executions) == pytest.approx(expected)
    shuffle.shuffle(executions)
    assert reading.log_probability_of_all(executions) == pytest.approx(expected)
    assert reading.log_probability_of_all([*executions, (("a", 1), ("k", 1), ("b", 1), ("c", 1))]) == -math.inf


def test_a_concentration_must_be_above_zero() -> None:
    htn = HTN("t", (ActionNode("a"),))
    with pytest.raises(LearningError, match="concentration"):
        OrderLikelihood(htn, concentration=0.0)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.permutations(list("abcdef")), min_size=1, max_size=6), st.sets(st.sampled_from("abcdef")))
def test_the_orders_seen_in_place_of_a_partial_order_count_as_the_partial_order(
    orders: list[list[str]], optional: set[str]
) -> None:
    # Built without a state limit, the partial order of the roots is the oracle: the top level of the orders
    # seen that stands in for it (one state allowed) counts the same orders of every set of roots performed.
    from supportive.learning.general.top_order import precedence_top_level

    sequences = [[ord(x) - 97 for x in o if not (x in optional and i % 2)] for i, o in enumerate(orders)]
    roots = sorted({x for s in sequences for x in s})
    required = frozenset(r for r in roots if all(r in s for s in sequences))
    nodes = tuple(ActionNode(chr(97 + r), optional=r not in required) for r in roots)
    walked = dataclasses.replace(precedence_top_level(roots, sequences, required, order_support=2), precedences=None)
    built = OrderLikelihood(HTN("t", nodes, walked))
    fallback = precedence_top_level(roots, sequences, required, order_support=2, max_states=1)
    assert fallback.stands_for is not None
    standing = OrderLikelihood(HTN("t", nodes, fallback))
    optional_roots = [r for r in roots if r not in required]
    for k in range(len(optional_roots) + 1):
        for extra in itertools.combinations(optional_roots, k):
            done = frozenset((chr(97 + r), 1) for r in (*required, *extra))
            assert standing.orders(done) == built.orders(done), sorted(done)
    demos = [[(chr(97 + r), 1) for r in s] for s in sequences]  # and so reads the demonstrations the same
    for alpha in (0.25, math.inf):
        assert OrderLikelihood(HTN("t", nodes, fallback), concentration=alpha).log_probability_of_all(demos) == (
            pytest.approx(OrderLikelihood(HTN("t", nodes, built.htn.top_level), concentration=alpha).log_probability_of_all(demos))
        )


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.permutations(list("abcdef")), min_size=1, max_size=6),
    st.sets(st.sampled_from("abcdef")),
    st.sets(st.sampled_from("abcdef")),
)
def test_a_partial_order_of_roots_counted_by_its_precedences_counts_what_walking_its_states_does(
    orders: list[list[str]], optional: set[str], nullable: set[str]
) -> None:
    # The oracle: the same top level with its precedences forgotten, walked state by state. Every set of
    # roots performed, with roots every demonstration does but that may be done as nothing (``nullable``:
    # the walk passes through them; the count is not used there).
    from supportive.learning.general.top_order import precedence_top_level

    sequences = [[ord(x) - 97 for x in o if not (x in optional and i % 2)] for i, o in enumerate(orders)]
    roots = sorted({x for s in sequences for x in s})
    required = frozenset(r for r in roots if all(r in s for s in sequences))
    nodes = tuple(ActionNode(chr(97 + r), optional=r not in required or chr(97 + r) in nullable) for r in roots)
    top = precedence_top_level(roots, sequences, required, order_support=2)
    assert top.precedences is not None
    counted = OrderLikelihood(HTN("t", nodes, top))
    walked = OrderLikelihood(HTN("t", nodes, dataclasses.replace(top, precedences=None)))
    for k in range(len(roots) + 1):
        for performed in itertools.combinations(roots, k):
            done = frozenset((chr(97 + r), 1) for r in performed)
            assert counted.orders(done) == walked.orders(done), sorted(done)
    demos = [[(chr(97 + r), 1) for r in s] for s in sequences]
    for alpha in (0.25, math.inf):
        assert OrderLikelihood(counted.htn, concentration=alpha).log_probability_of_all(demos) == pytest.approx(
            OrderLikelihood(walked.htn, concentration=alpha).log_probability_of_all(demos)
        )


def test_a_clique_of_many_children_read_jointly_pays_for_each_new_order() -> None:
    # 22 children: K = 22! orders, past where lgamma(K a) - lgamma(K a + m) keeps a digit. Five executions in
    # five different orders: each new order has chance a / (K a + i), i = 0 … 4, exactly (a = 1/4:
    # K a + i = (K + 4 i) / 4, a ratio of integers).
    children = [f"c{i}" for i in range(22)]
    htn = HTN("t", (CliqueNode(tuple(ActionNode(c) for c in children)),))
    rng = random.Random(5)
    executions = []
    for _ in range(5):
        order = list(children)
        rng.shuffle(order)
        executions.append([(c, 1) for c in order])
    k = math.factorial(22)
    exact = sum(math.log(0.25) - (math.log(k + 4 * i) - math.log(4)) for i in range(5))
    reading = OrderLikelihood(htn, concentration=0.25)
    assert reading.log_probability_of_all(executions) == pytest.approx(exact, rel=1e-12)
    assert exact < -5 * math.log(k) + 1  # about five times the uniform reading's cost, not a fifth of it
