"""The "which parts, then any valid order" reading (learning/order_likelihood.py) against counting executions."""

from __future__ import annotations

from collections import Counter

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.learning.test_pair_orders import _executions, sampled_demonstrations

from supportive.learning import HTNLearner
from supportive.learning.order_likelihood import OrderLikelihood


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
