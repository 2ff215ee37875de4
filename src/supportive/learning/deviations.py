"""Slips: steps that contradict what (nearly) every other demonstration shows, set aside within a budget.

People slip: a step mislabelled as another, two steps swapped, a step forgotten. Left in, one slip can
flatten a hierarchy (a swapped pair makes a chain a clique, a stray step breaks a subtask). With ``share`` s
of the demonstrations allowed to disagree (``floor(s * m)`` of ``m``, so nothing is set aside with fewer than
``1 / s`` demonstrations), three kinds of deviation are recognised, in this order:

* **rare**: a step performed by at most that many demonstrations is taken out of them (a mislabel leaves a
  one-off step behind);
* **missing**: a step missing from at most that many demonstrations is reported, not made optional;
* **out of order**: when all but at most that share of the demonstrations performing two steps agree on
  their order, a demonstration that has them the other way round has a slip; the step involved in the most
  such disagreements in it is taken out, until none is left.

At most ``share`` of all steps are taken out; the demonstrations with a deviation are reported (the learned
hierarchy need not admit them) and learning uses the rest of their steps.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from supportive.learning.evidence import pair_counts
from supportive.tasks.htn import Leaf

__all__ = ["MAX_COMPARED_STEPS", "Deviation", "set_aside"]

MAX_COMPARED_STEPS = 2000
"""Tasks with more distinct steps than this are not checked for out-of-order slips (pairwise counts)."""

Kind = Literal["rare", "missing", "out of order"]


@dataclass(frozen=True)
class Deviation:
    """One slip: in demonstration ``demonstration`` (an index), the step at ``position`` (-1 for a missing
    step) labelled ``leaf``, of kind ``kind``."""

    demonstration: int
    position: int
    leaf: Leaf
    kind: Kind

    def as_dict(self, demo_ids: Sequence[str] = ()) -> dict[str, object]:
        """Plain-data form; ``demo_ids`` names the demonstrations by their ids."""
        action, instance = self.leaf
        name = demo_ids[self.demonstration] if self.demonstration < len(demo_ids) else str(self.demonstration + 1)
        data: dict[str, object] = {"demonstration": name, "kind": self.kind, "action": action}
        if instance != 1:
            data["occurrence"] = instance
        if self.position >= 0:
            data["step"] = self.position + 1
        return data


def set_aside(
    labelled: Sequence[Sequence[Leaf]], share: float
) -> tuple[list[tuple[Leaf, ...]], tuple[Deviation, ...]]:
    """The demonstrations with their slips taken out, and the slips (see the module docstring)."""
    m = len(labelled)
    tolerated = math.floor(share * m + 1e-9)
    kept: list[list[tuple[int, Leaf]]] = [list(enumerate(demo)) for demo in labelled]
    if tolerated == 0:
        return [tuple(demo) for demo in labelled], ()
    budget = math.floor(share * sum(len(d) for d in labelled) + 1e-9)
    found: list[Deviation] = []
    performers = Counter(leaf for demo in labelled for leaf in set(demo))
    rare = {leaf for leaf, n in performers.items() if n <= tolerated and n < m}
    for d, demo in enumerate(kept):
        remaining = []
        for position, leaf in demo:
            if leaf in rare and budget > 0:
                found.append(Deviation(d, position, leaf, "rare"))
                budget -= 1
            else:
                remaining.append((position, leaf))
        kept[d] = remaining
    for leaf, n in sorted(performers.items()):
        if leaf not in rare and m - n <= tolerated and n < m:
            for d, performed in enumerate(labelled):
                if leaf not in performed:
                    found.append(Deviation(d, -1, leaf, "missing"))
    budget = _out_of_order(kept, tolerated, share, budget, found)
    found.sort(key=lambda dev: (dev.demonstration, dev.position, dev.leaf))
    return [tuple(leaf for _, leaf in demo) for demo in kept], tuple(found)


def _out_of_order(
    kept: list[list[tuple[int, Leaf]]], tolerated: int, share: float, budget: int, found: list[Deviation]
) -> int:
    """Take out, demonstration by demonstration, the steps that reverse orders (nearly) all others agree on."""
    leaves = sorted({leaf for demo in kept for _, leaf in demo})
    if len(leaves) > MAX_COMPARED_STEPS or budget <= 0:
        return budget
    index = {leaf: i for i, leaf in enumerate(leaves)}
    sequences = [[index[leaf] for _, leaf in demo] for demo in kept]
    before, together = pair_counts(sequences, list(range(len(leaves))))
    allowed = np.floor(share * together + 1e-9)
    agreed = (allowed >= before.T) & (before > before.T) & (before.T > 0)
    if not agreed.any():
        return budget
    for d, sequence in enumerate(sequences):
        while budget > 0:
            rank = np.full(len(leaves), -1, dtype=np.int64)
            rank[np.array(sequence, dtype=np.int64)] = np.arange(len(sequence))
            present = rank >= 0
            reversed_here = agreed & present[:, None] & present[None, :] & (rank[None, :] < rank[:, None])
            conflicts = reversed_here.sum(axis=0) + reversed_here.sum(axis=1)
            if not conflicts.any():
                break
            worst = int(max(sequence, key=lambda s: (int(conflicts[s]), -int(rank[s]))))
            position = int(rank[worst])
            original, leaf = kept[d][position]
            found.append(Deviation(d, original, leaf, "out of order"))
            budget -= 1
            del kept[d][position]
            del sequence[position]
    return budget
