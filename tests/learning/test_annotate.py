"""The general learner's annotation: what its nodes say about the orders they admit."""

from __future__ import annotations

from typing import Literal

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from supportive.generate import generate_task
from supportive.learning.general.annotate import (
    Annotated,
    _ListOrders,
    _MatrixOrders,
    _owned_children,
    admitted_orders,
)
from supportive.learning.general.decomposition import decompose
from supportive.learning.general.labelling import label_performances
from supportive.learning.general.repeats import fold_repeats
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, iter_orderings


@pytest.mark.parametrize("chain", [True, False])
@pytest.mark.parametrize(("children", "optional"), [(n, k) for n in range(1, 6) for k in range(n + 1)])
def test_admitted_orders_are_the_non_empty_orders_counted_one_by_one(chain: bool, children: int, optional: int) -> None:
    leaves = tuple(ActionNode(str(i), optional=i < optional) for i in range(children))
    level = ChainNode(leaves) if chain else CliqueNode(leaves)
    orders = [order for order in iter_orderings(level) if order]
    assert len(set(orders)) == len(orders) == admitted_orders(chain, optional, children)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    size=st.integers(4, 40),
    seed=st.integers(0, 10_000),
    demonstrations=st.integers(1, 12),
    profile=st.sampled_from(["ikea", "uniform"]),
    slipped=st.booleans(),
    dropped=st.lists(st.integers(0, 10_000), max_size=6),
)
def test_both_forms_of_the_child_orders_agree(
    size: int, seed: int, demonstrations: int, profile: Literal["ikea", "uniform"], slipped: bool, dropped: list[int]
) -> None:
    """The child orders read one demonstration at a time and as matrices are the same (the learner picks one
    by size only), on generated tasks with repeated subtasks and, some, a step moved and steps left out (so
    that nodes are optional and chains performed in part)."""
    spec = generate_task(size, seed, demonstrations=demonstrations, profile=profile)
    demos = [list(d.actions) for d in spec.demonstrations]
    if slipped and len(demos[0]) > 2:
        demos[0].insert(0, demos[0].pop())
    for k, where in enumerate(dropped):  # a step left out of demonstration k (of those with two or more)
        demo = demos[k % len(demos)]
        if len(demo) > 1:
            demo.pop(where % len(demo))
    decomposition = fold_repeats(decompose(label_performances(demos), evidence=0.05, order_support=2))
    kinds = Annotated(decomposition, {}, len(demos))._kinds
    owned = _owned_children(decomposition.groups, kinds)
    by_lists = _ListOrders(decomposition, kinds, owned)
    by_matrix = _MatrixOrders(decomposition, kinds, owned)
    assert by_lists.seen == by_matrix.seen
    assert set(by_lists._choices) == set(by_matrix._place)  # the nodes whose children come in several orders
    for node in by_lists._choices:
        assert by_lists.counts(node, 3, 1) == by_matrix.counts(node, 3, 1)
