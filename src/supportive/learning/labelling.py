"""Which performance of a repeated action each step is, decided by what surrounds it.

Counting performances (the third ``align_leg`` is ``align_leg#3``) goes wrong as soon as someone skips one: a
person who does not align the second leg aligns the third leg third-but-second, and the count calls it
``align_leg#2``. Here the k-th label of an action is the k-th *instance* of it, as the demonstrations that
perform it most often show it: each label gets a context (the labels just before and just after it in those
demonstrations), and in a demonstration that performs the action fewer times, its performances are given the
labels (in order: instances are numbered by when they are performed) whose contexts they match best — an
order-preserving assignment found by dynamic programming. Contexts are refined over a few rounds, since a
neighbour's label may itself change.

>>> demos = [["pick", "align", "spin", "pick", "align", "spin"], ["pick", "spin", "pick", "align", "spin"]]
>>> [label for label in label_performances(demos)[1]]
[('pick', 1), ('spin', 1), ('pick', 2), ('align', 2), ('spin', 2)]
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

from supportive.tasks.htn import Leaf, to_leaves

__all__ = ["label_performances"]

_ROUNDS = 3
_START, _END = ("<start>", 0), ("<end>", 0)


def label_performances(demonstrations: Sequence[Sequence[str]]) -> list[tuple[Leaf, ...]]:
    """Each demonstration as a sequence of ``(action, instance)`` labels (see the module docstring).

    A demonstration that performs an action as often as the most frequent one keeps the counted numbering;
    so with no skipped performances the result is :func:`~supportive.tasks.htn.to_leaves` of each.
    """
    labelled = [list(to_leaves(demo)) for demo in demonstrations]
    most = Counter[str]()
    for demo in demonstrations:
        for action, count in Counter(demo).items():
            most[action] = max(most[action], count)
    short = {
        action
        for action, k in most.items()
        if k > 1 and any(0 < Counter(demo)[action] < k for demo in demonstrations)
    }
    if not short:
        return [tuple(demo) for demo in labelled]
    for _ in range(_ROUNDS):
        contexts = _contexts(labelled, demonstrations, most, short)
        changed = False
        for d, demo in enumerate(demonstrations):
            counts = Counter(demo)
            for action in short:
                if counts[action] in (0, most[action]):
                    continue
                positions = [i for i, a in enumerate(demo) if a == action]
                slots = _assign(positions, labelled[d], contexts[action], most[action])
                for position, slot in zip(positions, slots, strict=True):
                    if labelled[d][position] != (action, slot):
                        labelled[d][position] = (action, slot)
                        changed = True
        if not changed:
            break
    return [tuple(demo) for demo in labelled]


def _contexts(
    labelled: Sequence[Sequence[Leaf]],
    demonstrations: Sequence[Sequence[str]],
    most: Counter[str],
    short: set[str],
) -> dict[str, list[tuple[Counter[Leaf], Counter[Leaf]]]]:
    """For each action of ``short``: per instance, the labels seen just before and just after it in the
    demonstrations that perform the action in full."""
    out: dict[str, list[tuple[Counter[Leaf], Counter[Leaf]]]] = {
        action: [(Counter(), Counter()) for _ in range(most[action])] for action in short
    }
    for demo, labels in zip(demonstrations, labelled, strict=True):
        counts = Counter(demo)
        for i, (action, instance) in enumerate(labels):
            if action not in short or counts[action] != most[action]:
                continue
            before, after = out[action][instance - 1]
            before[labels[i - 1] if i else _START] += 1
            after[labels[i + 1] if i + 1 < len(labels) else _END] += 1
    return out


def _assign(
    positions: Sequence[int],
    labels: Sequence[Leaf],
    contexts: Sequence[tuple[Counter[Leaf], Counter[Leaf]]],
    k: int,
) -> list[int]:
    """Instances (1..k, increasing) for the performances at ``positions``, maximising context agreement."""
    n = len(positions)

    def score(p: int, slot: int) -> int:
        i = positions[p]
        before, after = contexts[slot]
        prev = labels[i - 1] if i else _START
        nxt = labels[i + 1] if i + 1 < len(labels) else _END
        return before[prev] + after[nxt]

    # best[p][s]: best score placing performances p.. into slots s.. (slots are 0-based here)
    best = [[0] * (k + 1) for _ in range(n + 1)]
    for p in range(n - 1, -1, -1):
        for s in range(k - (n - p), -1, -1):
            take = score(p, s) + best[p + 1][s + 1]
            skip = best[p][s + 1] if k - (s + 1) >= n - p else -1
            best[p][s] = max(take, skip)
    slots, s = [], 0
    for p in range(n):
        while k - (s + 1) >= n - p and best[p][s + 1] >= score(p, s) + best[p + 1][s + 1] + 1:
            s += 1
        slots.append(s + 1)
        s += 1
    return slots
