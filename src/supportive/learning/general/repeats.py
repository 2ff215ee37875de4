"""Repeated subtasks: k performances of one subtask (the four legs of a table) as k instances of it.

Instances are numbered by when they are performed (:mod:`~supportive.learning.general.labelling`), so in every
demonstration instance 1 comes before instance 2: decomposition finds them as a run of a chain. A run of a
chain's children that splits into k ≥ 2 consecutive segments of the same shape (the same actions in the same
structure, whatever their occurrence numbers and whichever steps were skipped) is made a clique of k
segments, each segment one node: "the legs, in any order", which admits the same action sequences (the
instances are interchangeable) and says what the subtask is.
"""

from __future__ import annotations

import bisect
import dataclasses
from collections import defaultdict

from supportive.learning.general.decomposition import Decomposition, Group, Shapes

__all__ = ["fold_repeats"]

_CANDIDATE_PERIODS = 8
"""Segment lengths tried at a position: up to the next eight children of the same shape."""


def fold_repeats(decomposition: Decomposition) -> Decomposition:
    """``decomposition`` with every run of repeated segments in a chain made a clique of instances."""
    actions = [action for action, _ in decomposition.leaves]
    if len(set(actions)) == len(actions):  # no action in two leaves: no two nodes share a shape
        return decomposition
    shape = Shapes(decomposition.leaves, decomposition.groups)  # the shapes before any folding
    groups = dict(decomposition.groups)
    presence = dict(decomposition.presence)
    next_id = max([*groups, len(decomposition.leaves) - 1]) + 1
    for node in sorted(decomposition.groups):
        group = groups[node]
        if not group.chain:
            continue
        children = list(group.children)
        keys = [shape(c) for c in children]
        where: dict[int, list[int]] = defaultdict(list)
        for i, key in enumerate(keys):
            where[key].append(i)
        out: list[int] = []
        i = 0
        while i < len(children):
            period, count = _repeat_at(keys, i, where[keys[i]])
            if count < 2:
                out.append(children[i])
                i += 1
                continue
            instances = []
            for k in range(count):
                segment = children[i + k * period : i + (k + 1) * period]
                if period == 1:
                    instances.append(segment[0])
                    continue
                groups[next_id] = Group(tuple(segment), True)
                presence[next_id] = frozenset().union(*(presence[c] for c in segment))
                instances.append(next_id)
                next_id += 1
            groups[next_id] = Group(tuple(instances), False)
            presence[next_id] = frozenset().union(*(presence[c] for c in instances))
            out.append(next_id)
            next_id += 1
            i += period * count
        if len(out) == 1 and out[0] in groups and not groups[out[0]].chain:
            groups[node] = groups.pop(out[0])
            presence.pop(out[0])
        else:
            groups[node] = Group(tuple(out), True)
    return dataclasses.replace(decomposition, groups=groups, presence=presence)


def _repeat_at(keys: list[int], start: int, same: list[int]) -> tuple[int, int]:
    """``(period, count)`` of the longest run of equal segments starting at ``start`` (count 1: none);
    ``same`` lists the positions holding the key at ``start``."""
    best = (1, 1)
    after = bisect.bisect_right(same, start)
    for nxt in same[after : after + _CANDIDATE_PERIODS]:
        period = nxt - start
        count = 1
        while start + (count + 1) * period <= len(keys) and (
            keys[start + count * period : start + (count + 1) * period] == keys[start : start + period]
        ):
            count += 1
        if count >= 2 and count * period > best[0] * best[1]:
            best = (period, count)
    return best
