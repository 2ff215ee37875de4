"""The general learner's annotation: what its nodes say about the orders they admit."""

from __future__ import annotations

import pytest

from supportive.learning.general.annotate import admitted_orders
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, iter_orderings


@pytest.mark.parametrize("chain", [True, False])
@pytest.mark.parametrize(("children", "optional"), [(n, k) for n in range(1, 6) for k in range(n + 1)])
def test_admitted_orders_are_the_non_empty_orders_counted_one_by_one(chain: bool, children: int, optional: int) -> None:
    leaves = tuple(ActionNode(str(i), optional=i < optional) for i in range(children))
    level = ChainNode(leaves) if chain else CliqueNode(leaves)
    orders = [order for order in iter_orderings(level) if order]
    assert len(set(orders)) == len(orders) == admitted_orders(chain, optional, children)
