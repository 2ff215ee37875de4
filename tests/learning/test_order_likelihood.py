"""The "which parts, then any valid order" reading (learning/order_likelihood.py) against counting executions."""

from __future__ import annotations

from collections import Counter

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.learning.test_pair_orders import _executions

from supportive.generate import random_partial_order, random_structure
from supportive.learning import HTNLearner
from supportive.learning.order_likelihood import OrderLikelihood
from supportive.tasks.htn import sample_ordering


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    kind=st.sampled_from(["ikea", "uniform", "partial order"]),
    mode=st.sampled_from(["general", "strict", "partial order"]),
)
def test_the_orders_of_each_set_of_steps_are_counted_once(seed: int, kind: str, mode: str) -> None:
    rng = np.random.default_rng(seed)
    if kind == "partial order":
        task = random_partial_order(6, rng, chains=int(rng.integers(2, 4)), cross=int(rng.integers(0, 3)))
        demos = [list(task.sample(rng)) for _ in range(8)]
    else:
        structure = random_structure(6, rng, profile=kind)  # type: ignore[arg-type]
        demos = [[a for a, _ in sample_ordering(structure, rng)] for _ in range(8)]
    for demo in demos[::3]:  # optional steps and roots, skipped on the seen orders' top level too
        demo.pop(int(rng.integers(len(demo))))
    htn = HTNLearner(mode=mode, alternatives=0, slips=False).fit(demos).htn_  # type: ignore[arg-type]
    executions = _executions(htn)
    orders = Counter(frozenset(e) for e in executions)
    reading = OrderLikelihood(htn)
    for done, count in orders.items():
        assert reading._count(done) == count
    assert all(reading.log_probability(e) > -np.inf for e in executions)
