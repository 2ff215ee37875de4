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

import itertools
from collections import Counter
from collections.abc import Sequence

from supportive.tasks.htn import Leaf, to_leaves

__all__ = ["label_performances"]

_ROUNDS = 3
_START, _END = ("<start>", 0), ("<end>", 0)


def label_performances(demonstrations: Sequence[Sequence[str]]) -> list[tuple[Leaf, ...]]:
    """Each demonstration as a sequence of ``(action, instance)`` labels (see the module docstring).

    An action has as many instances as most of the demonstrations performing it perform it (the larger count
    on a tie). A demonstration that performs it that often keeps the counted numbering, so with no skipped or
    repeated performance the result is :func:`~supportive.tasks.htn.to_leaves` of each; one that performs it
    less often has its performances matched to the instances whose contexts fit; one that performs it more
    often has the instances matched to the performances that fit them best, and its other performances are
    labelled after the last instance (``k + 1``, ``k + 2``, … in order: a repeated step).
    """
    if all(len(set(demo)) == len(demo) for demo in demonstrations):  # no action repeats: nothing to decide
        first = {action: (action, 1) for action in set(itertools.chain.from_iterable(demonstrations))}
        return [tuple(map(first.__getitem__, demo)) for demo in demonstrations]
    counts = [Counter(demo) for demo in demonstrations]
    labelled = [list(to_leaves(demo)) for demo in demonstrations]
    tallies: dict[str, Counter[int]] = {}
    for count in counts:
        for action, times in count.items():
            tallies.setdefault(action, Counter())[times] += 1
    full = Counter({action: max(t, key=lambda k: (t[k], k)) for action, t in tallies.items()})
    missed = {action for count in counts for action, times in count.items() if times != full[action]}
    short = {action for action in full if action in missed}  # built in this order: it is iterated below
    if not short:
        return [tuple(demo) for demo in labelled]
    for _ in range(_ROUNDS):
        contexts = _contexts(labelled, counts, full, short)
        changed = False
        for d, demo in enumerate(demonstrations):
            for action in short:
                if counts[d][action] in (0, full[action]):
                    continue
                positions = [i for i, a in enumerate(demo) if a == action]
                slots = _assign(positions, labelled[d], contexts[action], full[action])
                for position, slot in zip(positions, slots, strict=True):
                    if labelled[d][position] != (action, slot):
                        labelled[d][position] = (action, slot)
                        changed = True
        if not changed:
            break
    return [tuple(demo) for demo in labelled]


def _contexts(
    labelled: Sequence[Sequence[Leaf]],
    counts: Sequence[Counter[str]],
    full: Counter[str],
    short: set[str],
) -> dict[str, list[tuple[Counter[Leaf], Counter[Leaf]]]]:
    """For each action of ``short``: per instance, the labels seen just before and just after it in the
    demonstrations that perform the action as often as it has instances (``counts``: each demonstration's
    performances per action)."""
    out: dict[str, list[tuple[Counter[Leaf], Counter[Leaf]]]] = {
        action: [(Counter(), Counter()) for _ in range(full[action])] for action in short
    }
    for count, labels in zip(counts, labelled, strict=True):
        for i, (action, instance) in enumerate(labels):
            if action not in short or count[action] != full[action]:
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
    """Labels for the performances at ``positions``: instances 1..k matched in order to as many of them as
    possible, maximising context agreement (dynamic programming over an order-preserving matching); the
    performances left over (when there are more than ``k``) get ``k + 1``, ``k + 2``, … in order."""
    n = len(positions)

    def score(p: int, slot: int) -> int:
        i = positions[p]
        before, after = contexts[slot]
        prev = labels[i - 1] if i else _START
        nxt = labels[i + 1] if i + 1 < len(labels) else _END
        return before[prev] + after[nxt]

    # best[p][s]: best score matching performances p.. with slots s.., matching min(n - p, k - s) of them
    best = [[0] * (k + 1) for _ in range(n + 1)]
    choice = [[0] * (k + 1) for _ in range(n + 1)]  # 0 match, 1 skip the slot, 2 leave the performance over
    for p in range(n - 1, -1, -1):
        for s in range(k - 1, -1, -1):
            options = [(score(p, s) + best[p + 1][s + 1], 0)]
            if k - s - 1 >= n - p:
                options.append((best[p][s + 1], 1))
            if n - p - 1 >= k - s:
                options.append((best[p + 1][s], 2))
            best[p][s], choice[p][s] = max(options, key=lambda option: (option[0], -option[1]))
    slots: list[int] = []
    extra = k
    p = s = 0
    while p < n:
        if s == k:
            extra += 1
            slots.append(extra)
            p += 1
        elif choice[p][s] == 0:
            slots.append(s + 1)
            p, s = p + 1, s + 1
        elif choice[p][s] == 1:
            s += 1
        else:
            extra += 1
            slots.append(extra)
            p += 1
    return slots
