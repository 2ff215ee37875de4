"""The top level's orders weighed against what the orders around them predict (issue #23), checked against
listing every order of a few steps."""

from __future__ import annotations

import itertools
import math

import numpy as np
import numpy.typing as npt
from hypothesis import given
from hypothesis import strategies as st

from supportive.learning.general.evidence import weighed_precedences

Pairs = frozenset[tuple[int, int]]


def _orders_keeping(size: int, pairs: Pairs) -> int:
    """How many of the ``size!`` orders keep every pair (listed one by one)."""
    return sum(
        all(rank[u] < rank[v] for u, v in pairs)
        for rank in ({step: i for i, step in enumerate(order)} for order in itertools.permutations(range(size)))
    )


def _implied(pairs: Pairs, u: int, v: int) -> bool:
    """Whether a path of two or more pairs leads from u to v."""
    frontier, seen = [w for a, w in pairs if a == u and w != v], set()
    while frontier:
        w = frontier.pop()
        if w == v:
            return True
        if w not in seen:
            seen.add(w)
            frontier.extend(x for a, x in pairs if a == w)
    return False


def _oracle(size: int, pairs: Pairs, shown: dict[tuple[int, int], int], penalty: float) -> Pairs:
    """Drop the cheapest pair no other pairs imply while it is worth less than ``penalty``, by listing orders;
    a pair once worth the penalty is not weighed again."""
    kept, worth = set(pairs), set()
    while True:
        total = _orders_keeping(size, frozenset(kept))
        weights = [
            (shown[p] * math.log(_orders_keeping(size, frozenset(kept - {p})) / total), p)
            for p in sorted(kept)
            if p not in worth and not _implied(frozenset(kept), *p)
        ]
        worth |= {p for w, p in weights if w >= penalty}
        below = sorted((w, p) for w, p in weights if w < penalty)
        if not below:
            return frozenset(kept)
        kept.discard(below[0][1])


def _acyclic(size: int, drawn: list[tuple[int, int]]) -> Pairs:
    """The drawn pairs pointing forward in the steps' numbering (an acyclic relation)."""
    return frozenset((u, v) for u, v in drawn if u < v < size)


def _matrix(size: int, pairs: Pairs) -> npt.NDArray[np.bool_]:
    matrix = np.zeros((size, size), dtype=bool)
    for u, v in pairs:
        matrix[u, v] = True
    return matrix


@given(
    st.integers(2, 6),
    st.lists(st.tuples(st.integers(0, 5), st.integers(0, 5)), max_size=10),
    st.lists(st.integers(1, 12), min_size=36, max_size=36),
    st.sampled_from([0.0, 0.3, 1.0, 2.0, 4.0, math.inf]),
)
def test_the_orders_kept_are_what_listing_every_order_keeps(
    size: int, drawn: list[tuple[int, int]], counts: list[int], penalty: float
) -> None:
    pairs = _acyclic(size, drawn)
    together = np.array(counts, dtype=np.int64).reshape(6, 6)[:size, :size]
    shown = {(u, v): int(together[u, v]) for u, v in pairs}
    kept = weighed_precedences(_matrix(size, pairs), together, penalty)
    assert {(int(u), int(v)) for u, v in zip(*np.nonzero(kept), strict=True)} == _oracle(size, pairs, shown, penalty)


def test_a_pair_the_others_nearly_imply_is_worth_little() -> None:
    # two interleaved chains a1 < a2 < a3 (0, 1, 2) and b1 < b2 < b3 (3, 4, 5), and a1 < b3 besides: 19 of
    # the 20 orders of the chains keep it, so six demonstrations weigh 6 ln(20/19) = 0.31 nats for it
    chains = frozenset({(0, 1), (1, 2), (3, 4), (4, 5)})
    together = np.full((6, 6), 6, dtype=np.int64)
    kept = weighed_precedences(_matrix(6, chains | {(0, 5)}), together, penalty=1.0)
    assert {(int(u), int(v)) for u, v in zip(*np.nonzero(kept), strict=True)} == chains
    # a1 < a2 is worth 6 ln 3 = 6.6 nats: without it, a1 could come anywhere among a2, a3 and the b's
    assert weighed_precedences(_matrix(6, chains), together, penalty=6.5)[0, 1]
    assert not weighed_precedences(_matrix(6, chains), together, penalty=6.7)[0, 1]
    # two steps alone: the order is worth 6 ln 2 = 4.2 nats, what a coin's six tosses landing alike are
    pair = _matrix(2, frozenset({(0, 1)}))
    assert weighed_precedences(pair, together[:2, :2], 4.1)[0, 1] and not weighed_precedences(pair, together[:2, :2], 4.2)[0, 1]
