"""Where a teammate is in a task, as a probability over the executions the hierarchy admits.

A state is an execution's progress (:class:`~supportive.tasks.executions.Progress`: what is done, which leaf
was done last) or the task **finished**. From a state the next step is decided where the hierarchy decides it,
walking up from the last leaf: a chain goes on with its next child (an optional child is taken or skipped), a
clique starts one of its children not yet started or, when nothing it still lacks is required, ends and lets
its parent decide; a partial hierarchy's top level picks the next root, or the task ends. Every choice is
weighted by how often people made it (the learned ``counts`` of each node: which clique child comes first or
next, how often an optional step is taken, how often the task ended there), smoothed toward the structure's
uniform choice by ``smoothing`` pseudo-counts per option. So an already-done subgoal has probability 0 (each
leaf is performed once), the end of the task is an outcome of its own, and doing the task again is an
explicit option of the trackers (``restart``), not part of the model.

>>> from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode
>>> htn = HTN("t", (ChainNode((ActionNode("knife"), CliqueNode((ActionNode("carrots"), ActionNode("celery"))))),))
>>> model = ProgressModel(htn)
>>> sorted((model.leaves[i][0] if i != END else "<end>", round(p, 2)) for i, (p, _) in model.outcomes(model.executions.initial()[0]).items())
[('knife', 1.0)]
>>> round(math.exp(model.log_probability(["knife", "celery", "carrots"])), 2)  # the clique's two orders
0.5
>>> model.log_probability(["celery", "knife", "carrots"])  # not an execution
-inf
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Sequence

from supportive.errors import LearningError
from supportive.tasks.executions import Executions, Progress
from supportive.tasks.htn import HTN, ActionNode, Counts, Node

__all__ = ["END", "Outcome", "ProgressModel"]

END = -1
"""The "task finished" outcome of a step, among leaf indices."""

Outcome = tuple[float, Progress | None]
"""Probability of one next step and the state after it (None: the task is finished)."""


class ProgressModel:
    """The learned probabilities of the next step, from any state of an HTN's executions.

    Args:
        htn: A complete or partial hierarchy; its nodes' ``counts`` (the general learner's) weight the
            choices, uniform where a node has none.
        smoothing: Pseudo-counts added to every allowed option of a choice.
    """

    def __init__(self, htn: HTN, *, smoothing: float = 1.0) -> None:
        if not smoothing > 0:
            raise LearningError(f"smoothing must be positive, got {smoothing}")
        self.htn = htn
        self.smoothing = smoothing
        self.executions = Executions(htn)
        self.leaves = self.executions.leaves
        self._nodes: list[Node] = []
        for root in htn.roots:
            self._collect(root)
        self._counts: list[Counts | None] = [node.counts for node in self._nodes]
        self._starts: dict[int, dict[int, float]] = {}
        self._cache: dict[Progress, dict[int, Outcome]] = {}

    def _collect(self, node: Node) -> None:
        """Every node, in the executions' depth-first numbering."""
        self._nodes.append(node)
        if not isinstance(node, ActionNode):
            for child in node.children:
                self._collect(child)

    # ------------------------------------------------------------------ next step
    def outcomes(self, state: Progress) -> dict[int, Outcome]:
        """Leaf index (or :data:`END`) -> ``(probability, state after)`` of every possible next step; the
        probabilities add up to one (empty: nothing may follow, which a valid execution never reaches)."""
        cached = self._cache.get(state)
        if cached is None:
            moves = self.executions.moves(state, symmetric=True)
            weights = self._weights(state)
            total = sum(w for leaf, w in weights.items() if leaf == END or leaf in moves)
            cached = {
                leaf: (w / total, None if leaf == END else moves[leaf])
                for leaf, w in weights.items()
                if w > 0 and (leaf == END or leaf in moves)
            }
            self._cache[state] = cached
        return cached

    def _weights(self, state: Progress) -> dict[int, float]:
        ex = self.executions
        weights: dict[int, float] = defaultdict(float)
        if state.last < 0:
            self._top(state.top, None, state.done, 1.0, weights)
            return weights
        mass = 1.0
        parent, position = ex.parents[ex.leaf_nodes[state.last]]
        while parent >= 0 and mass > 0:
            mass = self._decide(parent, position, state.done, mass, weights)
            parent, position = ex.parents[parent]
        if mass > 0:
            root = ex.root_of_leaf[state.last]
            after = ex.top_successors(state.top).get(root)
            if after is not None:
                self._top(after, root, state.done, mass, weights)
        return weights

    def _decide(self, node: int, position: int, done: int, mass: float, weights: dict[int, float]) -> float:
        """Spread ``mass`` (the child at ``position`` may end) over what ``node`` does next; return the mass
        that ends ``node`` itself."""
        ex = self.executions
        table = ex.tables[node]
        if table.chain:
            for child in table.children[position + 1 :]:
                if not ex.nullables[child]:
                    self._add_start(child, mass, weights)
                    return 0.0
                take = self._take(child)
                self._add_start(child, mass * take, weights)
                mass *= 1.0 - take
            return mass
        counts = self._counts[node]
        after = counts.after[position] if counts is not None and counts.after else None
        options: dict[int, float] = {}
        classes_open: set[int] = set()
        ends = True
        for index, (child, cls) in enumerate(zip(table.children, table.classes, strict=True)):
            if done & ex.masks[child]:
                continue
            ends &= ex.nullables[child]
            if cls in classes_open:  # an instance of a repeated subtask: its lowest free instance starts
                continue
            classes_open.add(cls)
            options[child] = (after[index] if after is not None else 0) + self.smoothing
        if ends:
            followed = sum(after) if after is not None else 0
            options[END] = max(self._performed(table.children[position]) - followed, 0) + self.smoothing
        total = sum(options.values())
        for child, weight in options.items():
            if child != END:
                self._add_start(child, mass * weight / total, weights)
        return mass * options.get(END, 0.0) / total

    def _top(self, top: int, last: int | None, done: int, mass: float, weights: dict[int, float]) -> None:
        """Spread ``mass`` over the roots that may begin from top-level state ``top`` (``last`` root just
        finished, None at the start) and the task ending there."""
        ex = self.executions
        counts = self.htn.top_level.counts if self.htn.top_level is not None else None
        options: dict[int, float] = {}
        reachable = ex.skip_closure(top)
        for state in reachable:
            for root in ex.top_successors(state):
                if root in options or done & ex.masks[ex.root_nodes[root]]:
                    continue
                seen = 0
                if counts is not None and last is None and counts.first:
                    seen = counts.first[root]
                elif counts is not None and last is not None and counts.after:
                    seen = counts.after[last][root]
                options[root] = seen + self.smoothing
        if any(ex.top_ends(state) for state in reachable):
            followed = sum(counts.after[last]) if counts is not None and last is not None and counts.after else 0
            performed = self._performed(ex.root_nodes[last]) if last is not None else 0
            options[END] = max(performed - followed, 0) + self.smoothing
        total = sum(options.values())
        for root, weight in options.items():
            if root == END:
                weights[END] += mass * weight / total
            else:
                self._add_start(ex.root_nodes[root], mass * weight / total, weights)

    def _add_start(self, node: int, mass: float, weights: dict[int, float]) -> None:
        for leaf, p in self._start(node).items():
            weights[leaf] += mass * p

    def _start(self, node: int) -> dict[int, float]:
        """How starting ``node`` (performing at least one of its leaves) spreads over the leaves it may
        begin with."""
        cached = self._starts.get(node)
        if cached is not None:
            return cached
        ex = self.executions
        table = ex.tables.get(node)
        out: dict[int, float] = defaultdict(float)
        if table is None:
            out[ex.masks[node].bit_length() - 1] = 1.0
        elif table.chain:
            mass = 1.0
            for child in table.children:
                take = 1.0 if not ex.nullables[child] else self._take(child)
                for leaf, p in self._start(child).items():
                    out[leaf] += mass * take * p
                mass *= 1.0 - take
                if mass <= 0:
                    break
            total = sum(out.values())  # performed although every part may be skipped: renormalise
            out = defaultdict(float, {leaf: p / total for leaf, p in out.items()})
        else:
            counts = self._counts[node]
            options: dict[int, float] = {}
            seen: set[int] = set()
            for index, (child, cls) in enumerate(zip(table.children, table.classes, strict=True)):
                if cls not in seen:
                    seen.add(cls)
                    first = counts.first[index] if counts is not None and counts.first else 0
                    options[child] = first + self.smoothing
            total = sum(options.values())
            for child, weight in options.items():
                for leaf, p in self._start(child).items():
                    out[leaf] += weight / total * p
        self._starts[node] = dict(out)
        return self._starts[node]

    def _take(self, node: int) -> float:
        """Probability that a node that may be skipped is performed: its counts, smoothed toward 1/2."""
        counts = self._counts[node]
        performed = counts.performed if counts is not None else 0
        skipped = counts.skipped if counts is not None else 0
        return (performed + 0.5 * self.smoothing) / (performed + skipped + self.smoothing)

    def _performed(self, node: int) -> int:
        counts = self._counts[node]
        return counts.performed if counts is not None else 0

    def log_probability(self, actions: Sequence[str]) -> float:
        """Natural log of the probability that an execution is exactly ``actions`` (action ids) and then ends,
        summed over the ways the hierarchy admits it (a repeated subtask's instances); ``-inf`` when it admits
        none."""
        belief: dict[Progress, float] = {state: 1.0 / len(self.executions.initial()) for state in self.executions.initial()}
        log_scale = 0.0
        for action in actions:
            moved: dict[Progress, float] = defaultdict(float)
            for state, mass in belief.items():
                for leaf, (p, nxt) in self.outcomes(state).items():
                    if nxt is not None and self.leaves[leaf][0] == action:
                        moved[nxt] += mass * p
            total = sum(moved.values())
            if not total > 0:
                return -math.inf
            log_scale += math.log(total)
            belief = {state: mass / total for state, mass in moved.items()}
        ending = sum(mass * self.outcomes(state).get(END, (0.0, None))[0] for state, mass in belief.items())
        return log_scale + math.log(ending) if ending > 0 else -math.inf

    def parameters(self) -> int:
        """How many choice probabilities the demonstrations had to fix: per choice (an optional node's take
        or skip, a clique's or the top level's first child, the child after each child or the end), the
        options the counts show were ever taken, less one. A choice only ever made one way costs nothing
        (the penalised likelihoods of :mod:`supportive.learning.general.noise` and :mod:`supportive.learning.selection`
        charge each parameter ``(1/2) log n``)."""
        total = 0
        ex = self.executions
        for number, node in enumerate(self._nodes):
            counts = node.counts
            if counts is None:
                continue
            if node.optional and counts.skipped and counts.performed:
                total += 1
            table = ex.tables.get(number)
            if table is not None and not table.chain and counts.first:
                performed = [self._performed(child) for child in table.children]
                total += _exercised(counts, performed)
        top = self.htn.top_level
        if top is not None and top.counts is not None and top.counts.first:
            total += _exercised(top.counts, [self._performed(root) for root in ex.root_nodes])
        return total

    # ------------------------------------------------------------------ state space
    def states(self, limit: int) -> list[Progress] | None:
        """Every state reachable from the start (initial states first), or None when there are more than
        ``limit``."""
        found: dict[Progress, None] = dict.fromkeys(self.executions.initial())
        frontier = list(found)
        while frontier:
            state = frontier.pop()
            for _, nxt in self.outcomes(state).values():
                if nxt is not None and nxt not in found:
                    if len(found) >= limit:
                        return None
                    found[nxt] = None
                    frontier.append(nxt)
        return list(found)


def _exercised(counts: Counts, performed: list[int]) -> int:
    """Free parameters of a choice of the first child and of what follows each child (or the end), counting
    only the options taken."""
    total = max(sum(1 for c in counts.first if c) - 1, 0)
    for row, done in zip(counts.after, performed, strict=True):
        options = sum(1 for c in row if c) + (done > sum(row))
        total += max(options - 1, 0)
    return total
