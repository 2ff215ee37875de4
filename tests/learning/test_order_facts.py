"""The general learner's order evidence for a candidate subtask, read from lists and from matrices (the counts
and the test of `learning.general.evidence` in both forms, and the facts `_classify` reads from them)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.learning.general.decomposition import _ListFacts, _MatrixFacts, _topological
from supportive.learning.general.evidence import (
    established_precedences,
    establishes_any,
    position_pair_counts,
    position_pair_counts_listed,
)


@st.composite
def position_rows(draw: st.DrawFn) -> list[list[int]]:
    """Sequences over ``k`` members, each a permutation of places with some members left out (-1), every
    member done somewhere."""
    k = draw(st.integers(2, 6))
    rows = []
    for _ in range(draw(st.integers(1, 8))):
        places = draw(st.permutations(range(k + 2)))[:k]  # gaps between places, as at a level
        rows.append([p if draw(st.booleans()) or draw(st.booleans()) else -1 for p in places])
    rows.append(list(draw(st.permutations(range(k)))))  # every member done somewhere
    return rows


@settings(max_examples=300, deadline=None)
@given(rows=position_rows(), order_support=st.integers(1, 8))
def test_both_forms_of_the_pair_counts_and_the_order_test_agree(rows: list[list[int]], order_support: int) -> None:
    before, together = position_pair_counts(np.array(rows, dtype=np.int64))
    listed = position_pair_counts_listed(rows, len(rows[0]))
    assert listed == (before.tolist(), together.tolist())
    assert establishes_any(*listed, order_support) == bool(established_precedences(before, together, order_support).any())


@settings(max_examples=300, deadline=None)
@given(rows=position_rows(), order_support=st.integers(1, 8))
def test_both_forms_of_the_order_facts_agree(rows: list[list[int]], order_support: int) -> None:
    """The form is picked by size only: whatever the positions, both read the same successors, mean positions
    (to the bit), established orders and complete orders."""
    lists, matrix = _ListFacts(rows), _MatrixFacts(np.array(rows, dtype=np.int64))
    assert lists.successors == matrix.successors
    assert lists.mean_positions() == matrix.mean_positions()
    assert lists.established(order_support) == matrix.established(order_support)
    assert sorted(lists.complete_orders()) == sorted(matrix.complete_orders())


def test_a_member_done_first_everywhere_is_established_with_enough_support_or_a_witness() -> None:
    rows = [[0, 1], [0, 2], [1, 2]]  # member 0 always before 1
    for facts in (_ListFacts(rows), _MatrixFacts(np.array(rows))):
        assert facts.successors == [[1], []]
        assert _topological(facts.successors, lambda i: i) == [0, 1]
        assert facts.established(3) and not facts.established(4)
    witnessed = [[0, 1, 2], [0, 1, 2]]  # 0 before 1 before 2: "0 before 2" has a witness between them
    assert _ListFacts(witnessed).established(10) and _MatrixFacts(np.array(witnessed)).established(10)
