"""How many orders of some steps keep a set of precedences: the linear extensions of a partial order, counted
exactly without listing its down-sets where the order splits.

Counting linear extensions is #P-complete in general, and the plain dynamic programme over down-sets (the
sets of steps that may be done first) is exponential in the steps of free order. The partial orders a
learner meets split, though: steps in **parallel** parts (no precedence joins them) interleave freely, so
the count is the multinomial of the parts' sizes times each part's count; steps in **series** parts (every
step of one before every step of the next) multiply. Only a part that splits neither way (prime) is counted
by the dynamic programme, with a bound on its down-sets; past it the count is not known (None).

>>> count_linear_extensions(3, [])  # three free steps
6
>>> count_linear_extensions(4, [(0, 1), (2, 3)])  # two chains of two, interleaved: 4! / (2! 2!)
6
>>> count_linear_extensions(4, [(0, 2), (1, 2), (2, 3)])  # {0, 1} then 2 then 3
2
>>> count_linear_extensions(30, [])  # too many down-sets for a plain programme, not for the split
265252859812191058636308480000000
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Iterable

from supportive.errors import LearningError

__all__ = ["MAX_DOWN_SETS", "count_linear_extensions", "covering_pairs"]

MAX_DOWN_SETS = 200_000
"""Most down-sets of one size the dynamic programme keeps for a part that does not split (a bound on the
work, not a model setting)."""


def count_linear_extensions(n: int, precedences: Iterable[tuple[int, int]], max_down_sets: int = MAX_DOWN_SETS) -> int | None:
    """The orders of steps ``0 … n-1`` in which ``u`` comes before ``v`` for every ``(u, v)`` of
    ``precedences``: 0 when they form a cycle, None when a part that does not split has more than
    ``max_down_sets`` down-sets of one size.

    Counts are remembered by the precedences asked (the slip search asks for the same ones from many
    hierarchies whose top levels differ only where these steps are not concerned).

    Raises:
        LearningError: a precedence names a step outside ``0 … n-1``.
    """
    return _counted(n, tuple(sorted(set(precedences))), max_down_sets)


def covering_pairs(n: int, precedences: Iterable[tuple[int, int]]) -> list[tuple[int, int]]:
    """The pairs of the acyclic relation ``precedences`` over steps ``0 … n-1`` that no path of two or more of
    its pairs joins (the edges of its transitive reduction), sorted.

    >>> covering_pairs(3, [(0, 1), (1, 2), (0, 2)])  # 0 before 2 follows from the other two
    [(0, 1), (1, 2)]

    Raises:
        LearningError: a precedence names a step outside ``0 … n-1``, or the pairs form a cycle.
    """
    pairs = set(precedences)
    closure = _closed(_predecessors(n, pairs))
    if closure is None:
        raise LearningError("the precedences form a cycle: no order keeps them")
    after = _successors(closure)
    return sorted((u, v) for u, v in pairs if not after[u] & closure[v])  # no step between u and v


@functools.lru_cache(maxsize=1024)  # a bound on memory: the count never depends on it
def _counted(n: int, precedences: tuple[tuple[int, int], ...], max_down_sets: int) -> int | None:
    closure = _closed(_predecessors(n, precedences))
    if closure is None:
        return 0
    return _count((1 << n) - 1, closure, _successors(closure), max_down_sets)


def _predecessors(n: int, precedences: Iterable[tuple[int, int]]) -> list[int]:
    """Each step's direct predecessors in ``precedences`` (bit masks).

    Raises:
        LearningError: a precedence names a step outside ``0 … n-1``.
    """
    before = [0] * n
    for u, v in precedences:
        if not (0 <= u < n and 0 <= v < n):
            raise LearningError(f"precedence ({u}, {v}) is outside steps 0…{n - 1}")
        before[v] |= 1 << u
    return before


def _successors(before: list[int]) -> list[int]:
    """Each step's successors (bit masks), from each step's predecessors ``before``."""
    after = [0] * len(before)
    for v, rest in enumerate(before):
        while rest:
            low = rest & -rest
            after[low.bit_length() - 1] |= 1 << v
            rest ^= low
    return after


def _closed(before: list[int]) -> list[int] | None:
    """The transitive closure of ``before`` (bit masks); None when a step must come before itself."""
    n = len(before)
    closure = list(before)
    for k in range(n):  # Warshall, one row of bits at a time
        bit = 1 << k
        row = closure[k]
        for v in range(n):
            if closure[v] & bit:
                closure[v] |= row
    if any(closure[v] >> v & 1 for v in range(n)):
        return None
    return closure


def _count(steps: int, before: list[int], after: list[int], limit: int) -> int | None:
    """The linear extensions of the steps in the mask ``steps`` (``before``/``after``: each step's
    predecessors/successors, transitively closed, over all steps)."""
    size = steps.bit_count()
    if size <= 1:
        return 1
    parts = _components(steps, lambda v: (before[v] | after[v]) & steps)  # joined by some precedence
    if len(parts) > 1:
        total = math.factorial(size)
        for part in parts:
            inner = _count(part, before, after, limit)
            if inner is None:
                return None
            total = total // math.factorial(part.bit_count()) * inner
        return total
    layers = _components(steps, lambda v: steps & ~(before[v] | after[v] | 1 << v))  # joined by being free
    if len(layers) > 1:  # each layer wholly before or after each other one
        total = 1
        for layer in layers:
            inner = _count(layer, before, after, limit)
            if inner is None:
                return None
            total *= inner
        return total
    return _prime(steps, tuple(before[v] & steps for v in range(steps.bit_length()) if steps >> v & 1), limit)


@functools.lru_cache(maxsize=4096)  # a bound on memory: the count never depends on it
def _prime(steps: int, inside: tuple[int, ...], limit: int) -> int | None:
    """:func:`_down_sets` of a part that does not split, ``inside`` each of its steps' predecessors within it
    (in the order of the steps): remembered by the part alone, for the counts of relations that differ
    outside it (a weighing drops one order at a time, and the parts that order does not touch are asked
    for again)."""
    before = [0] * steps.bit_length()
    for v, mask in zip((v for v in range(len(before)) if steps >> v & 1), inside, strict=True):
        before[v] = mask
    return _down_sets(steps, before, _successors(before), limit)


def _components(steps: int, neighbours: Callable[[int], int]) -> list[int]:
    """The connected parts of the steps in ``steps`` under ``neighbours`` (a step -> bit mask of its
    neighbours), as bit masks."""
    parts: list[int] = []
    left = steps
    while left:
        seed = left & -left
        part, frontier = seed, seed
        while frontier:
            low = frontier & -frontier
            frontier ^= low
            new = neighbours(low.bit_length() - 1) & ~part
            part |= new
            frontier |= new
        parts.append(part)
        left &= ~part
    return parts


def _down_sets(steps: int, before: list[int], after: list[int], limit: int) -> int | None:
    """The linear extensions of ``steps`` by the dynamic programme over its down-sets (a step may come once
    every step of ``steps`` before it is done); None past ``limit`` down-sets of one size. Each down-set
    carries the steps that may come next, so a step is tried only where it may come."""
    members = [1 << v for v in range(steps.bit_length()) if steps >> v & 1]
    needs = {bit: before[bit.bit_length() - 1] & steps for bit in members}  # by each step's bit
    unlocks = {bit: after[bit.bit_length() - 1] & steps for bit in members}
    counts = {0: 1}
    readies = {0: sum(bit for bit in members if not needs[bit])}
    for _ in members:  # level by level: the down-sets of k steps, then of k + 1
        next_counts: dict[int, int] = {}
        next_readies: dict[int, int] = {}
        for done, count in counts.items():
            ready = readies[done]
            left = ready
            while left:
                bit = left & -left
                left ^= bit
                nxt = done | bit
                if nxt in next_counts:
                    next_counts[nxt] += count
                    continue
                next_counts[nxt] = count
                now = ready ^ bit
                unlocked = unlocks[bit] & ~nxt
                while unlocked:
                    low = unlocked & -unlocked
                    unlocked ^= low
                    if needs[low] & ~nxt == 0:
                        now |= low
                next_readies[nxt] = now
        if len(next_counts) > limit:
            return None
        counts, readies = next_counts, next_readies
    return counts.get(steps, 0)
