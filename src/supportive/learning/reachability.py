"""Reachability in a small adjacency map (the level graphs of compaction, the top level of an HTN)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

__all__ = ["reachable"]


def reachable(starts: Iterable[int], step: Mapping[int, Sequence[int]]) -> set[int]:
    """Every node reachable from ``starts`` (included) following ``step``.

    >>> sorted(reachable([0], {0: [1], 1: [2], 3: [0]}))
    [0, 1, 2]
    """
    seen = set(starts)
    stack = list(seen)
    while stack:
        for nxt in step.get(stack.pop(), ()):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen
