"""Slips: steps that contradict what (nearly) every other demonstration shows, set aside within a budget.

People slip: a step mislabelled as another, two steps swapped, a step forgotten. Left in, one slip can
flatten a hierarchy (a swapped pair makes a chain a clique, a stray step breaks a subtask). With ``share`` s
of the demonstrations allowed to disagree (``floor(s * m)`` of ``m``, so nothing is set aside with fewer than
``1 / s`` demonstrations), three kinds of deviation are recognised, in this order:

* **rare**: a step performed by at most that many demonstrations is taken out of them (a mislabel leaves a
  one-off step behind);
* **missing**: a step missing from at most that many demonstrations is reported, not made optional;
* **out of order**: when the demonstrations performing two steps agree on their order despite a few that
  reverse it (an agreed order, :func:`~supportive.learning.evidence.agreed_orders`: a free pair would split
  so unevenly with chance below ``evidence``), each reversing demonstration has a slip in one of the two.
  A step is taken out of a demonstration when the agreed orders it reverses there outweigh the orders it
  takes part in that vary freely among people (each counts ``VARYING_WEIGHT``): a step people place freely
  is not called a slip wherever it lands, while one step done far too early or late reverses many agreed
  orders at once. The step most worth taking out, over all demonstrations (ties: the demonstration with the
  most reversals, then the first), goes first; counts and agreements are updated, and so on until none is
  worth it or the budget is spent.

At most ``share`` of all steps are taken out; the demonstrations with a deviation are reported (the learned
hierarchy need not admit them) and learning uses the rest of their steps. On CaptainCook4D, where about a
third of the recordings have order errors, this keeps what the error-free recordings show (docs/learning.md).
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import numpy.typing as npt

from supportive.learning.evidence import BoolMatrix, IntMatrix, agreed_orders, pair_counts, slip_allowance
from supportive.tasks.htn import Leaf

__all__ = ["MAX_COMPARED_STEPS", "VARYING_WEIGHT", "Deviation", "set_aside"]

MAX_COMPARED_STEPS = 2000
"""Tasks with more distinct steps than this are not checked for out-of-order slips (pairwise counts)."""

VARYING_WEIGHT = 0.5
"""How much each freely varying order a step takes part in counts against calling its place a slip: a step
is taken out when the agreed orders it reverses outnumber half its varying ones."""

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
    labelled: Sequence[Sequence[Leaf]], share: float, evidence: float = 0.05
) -> tuple[list[tuple[Leaf, ...]], tuple[Deviation, ...]]:
    """The demonstrations with their slips taken out, and the slips (see the module docstring); ``evidence``
    decides which orders are agreed (:func:`~supportive.learning.evidence.agreed_orders`)."""
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
    _out_of_order(kept, evidence, budget, found)
    found.sort(key=lambda dev: (dev.demonstration, dev.position, dev.leaf))
    return [tuple(leaf for _, leaf in demo) for demo in kept], tuple(found)


def _out_of_order(
    kept: list[list[tuple[int, Leaf]]], evidence: float, budget: int, found: list[Deviation]
) -> None:
    """Take out, one at a time and best first, the steps that reverse agreed orders (see the module
    docstring); counts and agreements are brought up to date after each."""
    leaves = sorted({leaf for demo in kept for _, leaf in demo})
    if len(leaves) > MAX_COMPARED_STEPS or budget <= 0:
        return
    index = {leaf: i for i, leaf in enumerate(leaves)}
    sequences = [[index[leaf] for _, leaf in demo] for demo in kept]
    before, together = pair_counts(sequences, list(range(len(leaves))))
    allowance = slip_allowance(len(sequences), evidence)
    if not agreed_orders(before, before.T, together, allowance).any():
        return
    slips = _SlipSearch(sequences, before, together, allowance)
    while budget > 0:
        chosen = slips.worst()
        if chosen is None:
            break
        d, position = chosen
        original, leaf = kept[d].pop(position)
        found.append(Deviation(d, original, leaf, "out of order"))
        slips.remove(d, position)
        budget -= 1


class _SlipSearch:
    """Pair counts, agreed and freely varying orders, and per demonstration and step the agreed orders it
    reverses and the varying orders it takes part in; kept up to date as steps are taken out."""

    def __init__(
        self, sequences: list[list[int]], before: IntMatrix, together: IntMatrix, allowance: npt.NDArray[np.int64]
    ) -> None:
        size = len(before)
        self.sequences = sequences
        self.before, self.together, self.allowance = before, together, allowance
        self.agreed = agreed_orders(self.before, self.before.T, self.together, self.allowance)
        self.varying = self._varying(self.before, self.before.T, self.agreed, self.agreed.T)
        self.rank = np.full((len(sequences), size), -1, dtype=np.int64)
        self.reversals = np.zeros((len(sequences), size), dtype=np.int64)
        self.varied = np.zeros((len(sequences), size), dtype=np.int64)
        for d, sequence in enumerate(sequences):
            order = np.array(sequence, dtype=np.int64)
            self.rank[d, order] = np.arange(len(order))
            later = np.triu(np.ones((len(order), len(order)), dtype=bool), 1)  # [i, j]: i done before j
            reversed_here = self.agreed[np.ix_(order, order)].T & later
            self.reversals[d, order] = reversed_here.sum(axis=0) + reversed_here.sum(axis=1)
            self.varied[d, order] = self.varying[np.ix_(order, order)].sum(axis=1)

    @staticmethod
    def _varying(first: IntMatrix, second: IntMatrix, forward: BoolMatrix, backward: BoolMatrix) -> BoolMatrix:
        """Elementwise: the order varies freely (seen both ways, agreed neither way); the arguments as for
        :func:`~supportive.learning.evidence.agreed_orders`, with the agreements each way."""
        result: BoolMatrix = (first > 0) & (second > 0) & ~forward & ~backward
        return result

    def worst(self) -> tuple[int, int] | None:
        """``(demonstration, position)`` of the step most worth taking out, or None when none is."""
        score = self.reversals - VARYING_WEIGHT * self.varied
        best: tuple[tuple[float, int, int], int, int] | None = None
        for d in range(len(self.sequences)):
            top = float(score[d].max())
            if top <= 0:
                continue
            candidates = np.flatnonzero(score[d] == top)
            step = int(candidates[np.argmin(self.rank[d, candidates])])
            key = (top, int(self.reversals[d].sum()), -d)
            if best is None or key > best[0]:
                best = (key, d, int(self.rank[d, step]))
        return None if best is None else (best[1], best[2])

    def remove(self, d: int, position: int) -> None:
        """Take the step at ``position`` out of demonstration ``d`` and update everything it touched."""
        step = self.sequences[d].pop(position)
        others = np.array(self.sequences[d], dtype=np.int64)
        earlier = self.rank[d, others] < position
        self.before[others[earlier], step] -= 1
        self.before[step, others[~earlier]] -= 1
        self.together[step, others] -= 1
        self.together[others, step] -= 1
        old_agreed_row, old_agreed_col = self.agreed[step].copy(), self.agreed[:, step].copy()
        old_varying = self.varying[step].copy()
        self._restate(step)
        # Demonstration d: the pairs (step, t) are gone from it.
        self.reversals[d, others] -= np.where(earlier, old_agreed_row[others], old_agreed_col[others])
        self.varied[d, others] -= old_varying[others]
        self.reversals[d, step] = self.varied[d, step] = 0
        self.rank[d, step] = -1
        self.rank[d, others[~earlier]] -= 1
        # Every other demonstration with the step: its pairs with the step may have changed state.
        for e in np.flatnonzero(self.rank[:, step] >= 0):
            at = self.rank[e, step]
            mates = np.flatnonzero(self.rank[e] >= 0)
            mates = mates[mates != step]
            first = self.rank[e, mates] < at  # mate done before the step in e
            old = np.where(first, old_agreed_row[mates], old_agreed_col[mates]).astype(np.int64)
            new = np.where(first, self.agreed[step, mates], self.agreed[mates, step]).astype(np.int64)
            self.reversals[e, mates] += new - old
            self.reversals[e, step] += int((new - old).sum())
            change = self.varying[step, mates].astype(np.int64) - old_varying[mates]
            self.varied[e, mates] += change
            self.varied[e, step] += int(change.sum())

    def _restate(self, step: int) -> None:
        """Recompute which orders of ``step`` are agreed or varying after its counts changed."""
        first, second = self.before[step], self.before[:, step]  # step before / after each other step
        self.agreed[step] = agreed_orders(first, second, self.together[step], self.allowance)
        self.agreed[:, step] = agreed_orders(second, first, self.together[step], self.allowance)
        varying = self._varying(first, second, self.agreed[step], self.agreed[:, step])
        self.varying[step] = varying
        self.varying[:, step] = varying
