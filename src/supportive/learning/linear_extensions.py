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
from collections.abc import Callable, Iterable, Iterator

from supportive.errors import LearningError

__all__ = ["MAX_DOWN_SETS", "count_linear_extensions", "count_without", "covering_pairs"]

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


def count_without(
    n: int, precedences: Iterable[tuple[int, int]], pair: tuple[int, int], max_down_sets: int = MAX_DOWN_SETS
) -> int | None:
    """:func:`count_linear_extensions` of ``precedences`` without ``pair``, the question a weighing asks of
    every covering pair (:func:`covering_pairs`) in turn: answered from the count with it, where the pair lies
    in a part that does not split and stays one when the pair is dropped (the part's orders putting ``v``
    before ``u`` are counted over the down-sets that hold ``v`` and not ``u``, from the part's own programme
    run both ways once for all its pairs), and as :func:`count_linear_extensions` does otherwise.

    >>> count_without(3, [(0, 1), (1, 2)], (0, 1))  # 0 free of 1 < 2: three orders
    3

    Raises:
        LearningError: a precedence names a step outside ``0 … n-1``.
    """
    return _counted_without(n, tuple(sorted(set(precedences))), pair, max_down_sets)


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


@functools.lru_cache(maxsize=1024)  # a bound on memory: the count never depends on it
def _counted_without(n: int, precedences: tuple[tuple[int, int], ...], pair: tuple[int, int], limit: int) -> int | None:
    rest = tuple(p for p in precedences if p != pair)
    closure, after = _closure(n, precedences)  # the same for every pair a weighing tries
    looser = _closed(_predecessors(n, rest))
    if closure is None or looser is None or rest == precedences:
        return _counted(n, rest, limit)
    u, v = pair
    looser_after = _successors(looser)
    part = _prime_part((1 << n) - 1, closure, after, u, v)
    if not part or any(
        (closure[w] ^ looser[w]) & ~part or (after[w] ^ looser_after[w]) & ~part for w in range(n) if part >> w & 1
    ):  # not within one part, or the part is no longer one (a step outside relates otherwise to its steps)
        return _counted(n, rest, limit)
    total = _counted(n, precedences, limit)
    whole = _prime(part, _within(part, closure), limit)
    if total is None or whole is None:
        return None
    reversed_orders = _reversed(part, _within(part, closure), _within(part, looser), u, v, limit)
    if reversed_orders is None:
        return None
    return total + total // whole * reversed_orders  # the part's orders times those of the rest around it


@functools.lru_cache(maxsize=64)  # a weighing asks for one relation's closure once per pair it tries
def _closure(n: int, precedences: tuple[tuple[int, int], ...]) -> tuple[list[int] | None, list[int]]:
    """:func:`_closed` of ``precedences`` and its :func:`_successors` (none for a cycle); not to be changed."""
    closure = _closed(_predecessors(n, precedences))
    return closure, [] if closure is None else _successors(closure)


def _prime_part(steps: int, before: list[int], after: list[int], u: int, v: int) -> int:
    """The part that does not split holding steps ``u`` and ``v`` of ``steps``, as :func:`_count` splits them;
    0 when a split parts them."""
    while True:
        how, parts = _split(steps, before, after)
        if how == "prime":
            return steps
        steps = next(part for part in parts if part >> u & 1)
        if not steps >> v & 1:
            return 0


@functools.lru_cache(maxsize=4096)  # a bound on memory: the count never depends on it
def _reversed(steps: int, inside: tuple[int, ...], looser: tuple[int, ...], u: int, v: int, limit: int) -> int | None:
    """The orders of the part ``steps`` (predecessors within it ``inside``, as :func:`_within` gives them)
    with the covering pair ``u < v`` dropped (predecessors ``looser``) that put ``v`` before ``u``: the
    orders reaching each down-set that holds ``v`` and not ``u``, times the orders completing it from ``u``
    on. Such a down-set is reached from one of the part's own (:func:`_both_ways`) by doing ``v``, or from
    another such by doing a step other than ``u``; None past ``limit`` down-sets of one size."""
    tables = _both_ways(steps, inside, limit)
    if tables is None:
        return None
    forward, backward = tables
    needs = _spread(steps, looser)
    bit_u, bit_v = 1 << u, 1 << v
    joining = [(1 << w, needs[w]) for w in range(steps.bit_length()) if steps >> w & 1 and w != u]
    entering: dict[int, dict[int, int]] = {}  # by size: the down-sets v enters, with the orders reaching them
    for done, count in forward.items():
        if not done & (bit_u | bit_v) and not needs[v] & ~done:
            entering.setdefault(done.bit_count() + 1, {})[done | bit_v] = count
    total = 0
    counts: dict[int, int] = {}
    for size in range(1, steps.bit_count()):
        for done, count in entering.get(size, {}).items():
            counts[done] = counts.get(done, 0) + count
        if len(counts) > limit:
            return None
        following: dict[int, int] = {}
        for done, count in counts.items():
            if not needs[u] & ~done:
                total += count * backward[done | bit_u]
            for bit, need in joining:
                if not bit & done and not need & ~done:
                    following[done | bit] = following.get(done | bit, 0) + count
        counts = following
    return total


@functools.lru_cache(maxsize=64)  # each holds every down-set of a part
def _both_ways(steps: int, inside: tuple[int, ...], limit: int) -> tuple[dict[int, int], dict[int, int]] | None:
    """The orders reaching each down-set of the part ``steps`` (predecessors within it ``inside``) and the
    orders completing the part from each; None past ``limit`` down-sets of one size."""
    before = _spread(steps, inside)
    forward: dict[int, int] = {}
    levels: list[dict[int, int]] = []
    for level in _levels(steps, before, _successors(before), limit):
        if level is None:
            return None
        forward.update(level[0])
        levels.append(level[1])
    backward = {steps: 1}
    for readies in reversed(levels[:-1]):
        for done, ready in readies.items():
            total = 0
            while ready:
                bit = ready & -ready
                ready ^= bit
                total += backward[done | bit]
            backward[done] = total
    return forward, backward


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
    how, parts = _split(steps, before, after)
    if how == "prime":
        return _prime(steps, _within(steps, before), limit)
    total = math.factorial(size) if how == "parallel" else 1
    for part in parts:
        inner = _count(part, before, after, limit)
        if inner is None:
            return None
        total = total // math.factorial(part.bit_count()) * inner if how == "parallel" else total * inner
    return total


def _split(steps: int, before: list[int], after: list[int]) -> tuple[str, list[int]]:
    """How the steps in ``steps`` (two or more) split: ``parallel`` into the parts no precedence joins,
    ``series`` into layers each wholly before or after each other one, or not at all (``prime``, the steps as
    the one part)."""
    parts = _components(steps, lambda v: (before[v] | after[v]) & steps)  # joined by some precedence
    if len(parts) > 1:
        return "parallel", parts
    layers = _components(steps, lambda v: steps & ~(before[v] | after[v] | 1 << v))  # joined by being free
    if len(layers) > 1:
        return "series", layers
    return "prime", [steps]


def _within(steps: int, before: list[int]) -> tuple[int, ...]:
    """Each step of ``steps``' predecessors among ``steps`` (in the order of the steps)."""
    return tuple(before[v] & steps for v in range(steps.bit_length()) if steps >> v & 1)


@functools.lru_cache(maxsize=4096)  # a bound on memory: the count never depends on it
def _prime(steps: int, inside: tuple[int, ...], limit: int) -> int | None:
    """:func:`_down_sets` of a part that does not split, ``inside`` each of its steps' predecessors within it
    (in the order of the steps): remembered by the part alone, for the counts of relations that differ
    outside it (a weighing drops one order at a time, and the parts that order does not touch are asked
    for again)."""
    before = _spread(steps, inside)
    last = None
    for level in _levels(steps, before, _successors(before), limit):
        if level is None:
            return None
        last = level
    assert last is not None  # the empty down-set's level at least
    return last[0].get(steps, 0)


def _spread(steps: int, inside: tuple[int, ...]) -> list[int]:
    """Each step's predecessors from :func:`_within`'s ``inside`` (0 for the steps not in ``steps``)."""
    before = [0] * steps.bit_length()
    for v, mask in zip((v for v in range(len(before)) if steps >> v & 1), inside, strict=True):
        before[v] = mask
    return before


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


def _levels(
    steps: int, before: list[int], after: list[int], limit: int
) -> Iterator[tuple[dict[int, int], dict[int, int]] | None]:
    """The dynamic programme over the down-sets of ``steps`` (a step may come once every step of ``steps``
    before it is done), level by level: the down-sets of k steps with the orders reaching each and the steps
    that may come next, for k = 0, 1, …; None, and nothing after, at a level of more than ``limit`` down-sets.
    A step is tried only where it may come."""
    members = [1 << v for v in range(steps.bit_length()) if steps >> v & 1]
    needs = {bit: before[bit.bit_length() - 1] & steps for bit in members}  # by each step's bit
    unlocks = {bit: after[bit.bit_length() - 1] & steps for bit in members}
    counts = {0: 1}
    readies = {0: sum(bit for bit in members if not needs[bit])}
    yield counts, readies
    for _ in members:  # the down-sets of k steps, then of k + 1
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
            yield None
            return
        counts, readies = next_counts, next_readies
        yield counts, readies
