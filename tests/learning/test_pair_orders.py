"""Order probabilities of a hierarchy (learning/pair_orders.py) against counting its executions one by one."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.generate import random_partial_order, random_structure
from supportive.learning import HTNLearner
from supportive.learning.pair_orders import order_probabilities, required_orders
from supportive.tasks.executions import Executions, Progress
from supportive.tasks.htn import HTN, ActionNode, Leaf, TopLevel, sample_ordering


def _executions(htn: HTN) -> list[tuple[Leaf, ...]]:
    machine = Executions(htn)
    out: list[tuple[Leaf, ...]] = []
    stack: list[tuple[Progress, tuple[Leaf, ...]]] = [(state, ()) for state in machine.initial()]
    seen: set[tuple[Leaf, ...]] = set()
    while stack:
        state, prefix = stack.pop()
        if machine.can_finish(state) and prefix not in seen:
            seen.add(prefix)
            out.append(prefix)
        stack.extend((nxt, (*prefix, machine.leaves[leaf])) for leaf, nxt in machine.moves(state).items())
    return out


def _brute_force(htn: HTN) -> np.ndarray:
    index = {leaf: i for i, leaf in enumerate(htn.leaves)}
    first = np.zeros((len(index), len(index)))
    both = np.zeros_like(first)
    for execution in _executions(htn):
        position = {leaf: p for p, leaf in enumerate(execution)}
        for x, y in itertools.permutations(position, 2):
            both[index[x], index[y]] += 1
            first[index[x], index[y]] += position[x] < position[y]
    return np.divide(first, both, out=np.zeros_like(first), where=both > 0)


def sampled_demonstrations(rng: np.random.Generator, kind: str, skips: bool) -> list[list[str]]:
    """Eight demonstrations of a random 6-step task of ``kind`` (a partial order, or an ``ikea``/``uniform``
    chain/clique structure), drawn uniformly; with ``skips``, every third loses a step (optional steps and
    roots)."""
    if kind == "partial order":
        task = random_partial_order(6, rng, chains=int(rng.integers(2, 4)), cross=int(rng.integers(0, 3)))
        demos = [list(task.sample(rng)) for _ in range(8)]
    else:
        structure = random_structure(6, rng, profile=kind)  # type: ignore[arg-type]
        demos = [[a for a, _ in sample_ordering(structure, rng)] for _ in range(8)]
    if skips:
        for demo in demos[::3]:
            demo.pop(int(rng.integers(len(demo))))
    return demos


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 10_000),
    kind=st.sampled_from(["ikea", "uniform", "partial order"]),
    mode=st.sampled_from(["general", "strict", "partial order"]),
    skips=st.booleans(),
)
def test_order_probabilities_and_required_orders_equal_counting_every_execution(
    seed: int, kind: str, mode: str, skips: bool
) -> None:
    demos = sampled_demonstrations(np.random.default_rng(seed), kind, skips)
    htn = HTNLearner(mode=mode, alternatives=0).fit(demos).htn_  # type: ignore[arg-type]
    leaves, before = order_probabilities(htn)
    counted = _brute_force(htn)
    assert leaves == htn.leaves
    assert np.allclose(before, counted)
    required_leaves, always = required_orders(htn)  # the pairs every execution performing both orders alike
    assert required_leaves == htn.leaves
    assert (always == (counted == 1.0)).all() and (always == (before == 1.0)).all()


def test_a_free_pair_of_a_partial_order_is_not_a_coin() -> None:
    # a1 < a2 < a3 and b1 < b2 < b3, interleaved freely: 20 executions, b3 before a1 in one of them.
    chains = (("a1", "a2", "a3"), ("b1", "b2", "b3"))
    valid = [list(p) for p in itertools.permutations([s for c in chains for s in c])
             if all(p.index(c[i]) < p.index(c[i + 1]) for c in chains for i in range(2))]
    htn = HTNLearner(mode="partial order").fit(valid).htn_
    leaves, before = order_probabilities(htn)
    index = {leaf[0]: i for i, leaf in enumerate(leaves)}
    assert before[index["b3"], index["a1"]] == pytest.approx(1 / 20)
    assert before[index["a1"], index["b1"]] == pytest.approx(1 / 2)


def test_required_orders_between_roots_come_from_the_paths_that_perform_both() -> None:
    # Two paths through the top level: a, b, c and c, a. Only the first performs b: a and b come before c
    # there, but c also comes before a.
    roots = (ActionNode("a"), ActionNode("b"), ActionNode("c"))
    top = TopLevel(initial=(0,), terminal=(3, 5), edges=((0, 0, 1), (1, 1, 2), (2, 2, 3), (0, 2, 4), (4, 0, 5)))
    leaves, always = required_orders(HTN("t", roots, top))
    assert [leaf[0] for leaf in leaves] == ["a", "b", "c"]
    assert {(leaves[i][0], leaves[j][0]) for i, j in zip(*np.nonzero(always), strict=True)} == {("a", "b"), ("b", "c")}
