"""The top level of a partial hierarchy as a partial order of its roots (the ``general`` learner).

When no chain or clique holds the roots left by decomposition, they are kept in the orders the evidence
establishes rather than only in the orders seen: by the coin test of ``order_support``
(:func:`~supportive.learning.general.evidence.established_precedences`), or, with an ``order_penalty``, the
orders every demonstration doing both roots keeps (two at least) that are worth more than that many nats against
what the other orders already predict (:func:`~supportive.learning.general.evidence.weighed_precedences`). Any
order that respects every order kept is admitted, roots of unrelated order may come in any order, and an
optional root may be skipped (a precedence only binds roots that are both performed). The result is an
ordinary :class:`~supportive.tasks.htn.TopLevel` whose states are the sets of roots done.

When that graph would exceed ``max_states`` states (many roots of free order) or the roots are too many to
compare pairwise, the top level falls back to the orders seen, as the ``strict`` learner keeps them. In the
first case the fallback carries the precedences it stands for (:attr:`~supportive.tasks.htn.TopLevel.stands_for`):
the slip search's likelihood counts its orders by them, as it would the partial order's (issue #23: the orders
seen are fitted to the demonstrations themselves, and counted as they are they made a hierarchy loosened by
real slips look tighter than the one their removal gives back).
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Sequence

import numpy as np

from supportive.learning.general.evidence import (
    BoolMatrix,
    established_precedences,
    pair_counts,
    weighed_precedences,
)
from supportive.tasks.htn import TopLevel

__all__ = ["MAX_PAIRWISE_ROOTS", "precedence_top_level", "seen_top_level"]

MAX_PAIRWISE_ROOTS = 1500
"""More roots than this are not compared pairwise (the top level keeps the orders seen)."""
_ENUMERATIONS_KEPT = 16
"""How many enumerated top levels are kept for the same constraints asked again (a bound on memory; the
result never depends on it)."""


def precedence_top_level(
    roots: Sequence[int],
    sequences: Sequence[Sequence[int]],
    required: frozenset[int],
    *,
    order_support: int,
    order_penalty: float | None = None,
    max_states: int = 50_000,
) -> TopLevel:
    """The top level admitting every order of ``roots`` that keeps the precedences the evidence establishes.

    Args:
        roots: Root node ids, in the order of the hierarchy's ``roots``.
        sequences: Every demonstration as a sequence of root ids.
        required: Roots every demonstration performs (the others may be skipped).
        order_support: Without ``order_penalty``: see
            :func:`~supportive.learning.general.evidence.established_precedences`.
        order_penalty: None, or what an order every demonstration doing both roots keeps (two at least) must
            be worth to be kept, in nats (:func:`~supportive.learning.general.evidence.weighed_precedences`;
            0 keeps every such order); ``order_support`` is then not read.
        max_states: Fall back to :func:`seen_top_level` beyond this many states.
    """
    if len(roots) > MAX_PAIRWISE_ROOTS:
        return seen_top_level(roots, sequences)
    before, together = pair_counts(sequences, list(roots))
    # weighed: an order two demonstrations keep (one is no evidence) without exception is where weighing starts
    established = established_precedences(before, together, order_support if order_penalty is None else 2)
    for component in _cycles(established):  # orders shown by different demonstrations that contradict: dropped
        established[np.ix_(component, component)] = False
    if order_penalty is not None:
        established = weighed_precedences(established, together, order_penalty)
    kept = [(int(u), int(v)) for u, v in zip(*np.nonzero(established), strict=True)]
    # no transitive closure: through a root that may be skipped, an order is only as established as it is
    preds = [0] * len(roots)  # the required roots that must come before each root
    earlier = [0] * len(roots)  # the roots that must come before each root (none may come after it)
    unlocks = [0] * len(roots)  # the roots each required root comes before
    need = 0
    for i, root in enumerate(roots):
        if root in required:
            need |= 1 << i
    for u, v in kept:
        earlier[v] |= 1 << u
        if roots[u] in required:
            preds[v] |= 1 << u
            unlocks[u] |= 1 << v
    enumerated = _enumerated(len(roots), tuple(preds), tuple(earlier), tuple(unlocks), need, max_states)
    if enumerated is not None:
        return enumerated
    precedences = tuple(sorted(kept))
    return dataclasses.replace(seen_top_level(roots, sequences), stands_for=precedences)


def _cycles(relation: BoolMatrix) -> list[list[int]]:
    """The strongly connected components of ``relation`` (``R[i, j]``: an edge i -> j) of two steps or more."""
    import networkx as nx  # here: networkx is a fifth of every command's start-up

    graph = nx.DiGraph()
    graph.add_edges_from((int(u), int(v)) for u, v in zip(*np.nonzero(relation), strict=True))
    return [sorted(c) for c in nx.strongly_connected_components(graph) if len(c) > 1]


@functools.lru_cache(maxsize=_ENUMERATIONS_KEPT)
def _enumerated(
    n: int, preds: tuple[int, ...], earlier: tuple[int, ...], unlocks: tuple[int, ...], need: int, max_states: int
) -> TopLevel | None:
    """The top level over ``n`` roots whose required predecessors are ``preds[i]`` and predecessors
    ``earlier[i]`` (bit masks; ``unlocks[u]``: the roots required root ``u`` comes before), ``need`` the
    required roots (the others free: in no one's ``preds``, nor needed); None beyond ``max_states`` states.
    Its states are numbered in the order the enumeration finds them, so the same constraints give the same
    numbers (the slip search asks again and again for the same ones: kept, with what is worked out from
    them)."""
    if _more_states_than(max_states, preds, earlier):
        return None
    everything = (1 << n) - 1
    # a state carries the roots whose required predecessors are done and the roots that may no longer come
    # (one that must come before a done root): both follow from the roots done, so they grow with each step
    ready = sum(1 << i for i in range(n) if not preds[i])
    edges: list[tuple[int, int, int]] = []
    number = {0: 0}
    frontier = [(0, ready, 0)]
    while frontier:
        done, ready, barred = frontier.pop()
        allowed = ready & ~done & ~barred & everything
        while allowed:
            bit = allowed & -allowed
            allowed ^= bit
            i = bit.bit_length() - 1
            after = done | bit
            if after not in number:
                if len(number) >= max_states:
                    return None
                number[after] = len(number)
                now_ready = ready
                unlocked = unlocks[i]
                while unlocked:
                    low = unlocked & -unlocked
                    unlocked ^= low
                    k = low.bit_length() - 1
                    if preds[k] & ~after == 0:
                        now_ready |= low
                frontier.append((after, now_ready, barred | earlier[i]))
            edges.append((number[done], i, number[after]))
    terminal = tuple(sorted(state for done, state in number.items() if done & need == need))
    free = frozenset(i for i in range(n) if not need >> i & 1)
    precedences = tuple((u, v) for u in range(n) for v in range(n) if earlier[v] >> u & 1)
    return TopLevel(initial=(0,), terminal=terminal, edges=tuple(sorted(edges)), free=free, precedences=precedences)


def _more_states_than(limit: int, preds: Sequence[int], earlier: Sequence[int]) -> bool:
    """Whether the top level of :func:`precedence_top_level` would have more than ``limit`` states (roots
    ``i`` with required predecessors ``preds[i]`` and predecessors ``earlier[i]``, as bit masks), counted
    level by level (a state's level: how many roots are done) in arrays; False, without counting, for more
    roots than an array's 63 bits hold (the enumeration then finds out as it goes). The enumeration would
    find the same, only after building as many states as the limit, in Python."""
    n = len(preds)
    if n > 63:
        return False
    bits = np.left_shift(np.int64(1), np.arange(n, dtype=np.int64))
    preds_array = np.array(preds, dtype=np.int64)
    earlier_array = np.array(earlier, dtype=np.int64)
    level = np.zeros(1, dtype=np.int64)
    count = 1
    while len(level):
        done = (level[:, None] & bits[None, :]) != 0  # [state, root]
        barred = np.bitwise_or.reduce(np.where(done, earlier_array[None, :], 0), axis=1)
        ready = (preds_array[None, :] & ~level[:, None]) == 0
        allowed = ready & ~done & ((barred[:, None] & bits[None, :]) == 0)
        states, roots = np.nonzero(allowed)
        level = np.unique(level[states] | bits[roots])
        count += len(level)
        if count > limit:
            return True
    return False


def seen_top_level(roots: Sequence[int], sequences: Sequence[Sequence[int]]) -> TopLevel:
    """The top level admitting exactly the orders of roots seen (states: the sets of roots done)."""
    index = {root: i for i, root in enumerate(roots)}
    number: dict[frozenset[int], int] = {frozenset(): 0}
    edges: set[tuple[int, int, int]] = set()
    terminal: set[int] = set()
    for sequence in sequences:
        done: frozenset[int] = frozenset()
        for root in sequence:
            after = done | {root}
            number.setdefault(after, len(number))
            edges.add((number[done], index[root], number[after]))
            done = after
        terminal.add(number[done])
    return TopLevel(initial=(0,), terminal=tuple(sorted(terminal)), edges=tuple(sorted(edges)))
