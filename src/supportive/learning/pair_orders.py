"""How often a hierarchy predicts one step before another: the order probabilities of its executions.

Read as a distribution that draws every execution it admits with equal chance, a hierarchy predicts for two
steps ``a`` and ``b`` the probability that ``a`` comes first among the executions that perform both. It
follows from the structure alone:

* within one root, the two steps part at their lowest common node: a chain orders them (1 or 0), a clique
  puts either of its children first with equal chance (1/2);
* in two roots of a partial hierarchy, it is the probability that the one root comes before the other on a
  path through the top level drawn with the number of executions it carries (each root weighs the number of
  its own orderings): forward and backward sums over the top level's states, in log space.

This is what a free pair of a partial order is expected to do: of two interleaved chains ``a1 a2 a3`` and
``b1 b2 b3``, ``b3`` precedes ``a1`` in one execution of twenty, not one of two; a slip is an order the
demonstrations reverse far less often than the structure without it predicts
(:mod:`~supportive.learning.general.noise`).

>>> from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, HTN
>>> htn = HTN("t", (ChainNode((ActionNode("k"), CliqueNode((ActionNode("a"), ActionNode("b"))))),))
>>> leaves, before = order_probabilities(htn)
>>> [(leaves[i][0], leaves[j][0], float(before[i, j])) for i in range(3) for j in range(3) if i != j]
[('k', 'a', 1.0), ('k', 'b', 1.0), ('a', 'k', 0.0), ('a', 'b', 0.5), ('b', 'k', 0.0), ('b', 'a', 0.5)]
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from supportive.tasks.htn import HTN, ActionNode, ChainNode, Leaf, Node, TopLevel, count_performed

__all__ = ["order_probabilities", "required_orders"]

FloatMatrix = npt.NDArray[np.float64]
BoolMatrix = npt.NDArray[np.bool_]
RootOrders = Callable[[TopLevel, list[int]], FloatMatrix]
"""What relates the roots of a top level (root ``r`` weighing ``weights[r]`` executions): ``[x, y]`` for
root ``x`` before root ``y``."""


def order_probabilities(htn: HTN) -> tuple[tuple[Leaf, ...], FloatMatrix]:
    """``(leaves, before)``: ``before[i, j]`` is the probability that ``leaves[i]`` comes before
    ``leaves[j]`` in an execution drawn uniformly among those ``htn`` admits that perform both (0 where no
    execution performs both). ``before + before.T`` is 1 wherever both may be performed."""
    return _by_leaves(htn, _root_orders)


def required_orders(htn: HTN) -> tuple[tuple[Leaf, ...], BoolMatrix]:
    """``(leaves, always)``: ``always[i, j]`` when some execution ``htn`` admits performs both ``leaves[i]``
    and ``leaves[j]`` and every one that does performs ``leaves[i]`` first — where :func:`order_probabilities`
    is 1, found from which orders of the roots the top level admits at all, with no probability summed."""
    leaves, before = _by_leaves(htn, _root_precedences)
    return leaves, before == 1.0


def _by_leaves(htn: HTN, root_orders: RootOrders) -> tuple[tuple[Leaf, ...], FloatMatrix]:
    """``htn``'s leaves and, for each two, the chance that the one comes first as the structure below the
    roots gives it, and between two roots as ``root_orders`` gives it."""
    leaves = htn.leaves
    index = {leaf: i for i, leaf in enumerate(leaves)}
    before = np.zeros((len(leaves), len(leaves)))
    spans = [np.array([index[leaf] for leaf in root.leaves], dtype=np.int64) for root in htn.roots]
    for root in htn.roots:
        _within(root, index, before)
    if htn.top_level is not None and len(htn.roots) > 1:
        roots = root_orders(htn.top_level, [count_performed(root) for root in htn.roots])
        for x, y in zip(*np.nonzero(roots), strict=True):
            before[np.ix_(spans[x], spans[y])] = roots[x, y]
    return leaves, before


def _within(node: Node, index: dict[Leaf, int], before: FloatMatrix) -> None:
    """Fill ``before`` for every pair of leaves that part at ``node`` or below it."""
    if isinstance(node, ActionNode):
        return
    spans = [np.array([index[leaf] for leaf in child.leaves], dtype=np.int64) for child in node.children]
    for i, first in enumerate(spans):
        for j, second in enumerate(spans):
            if i != j:
                chance = (1.0 if i < j else 0.0) if isinstance(node, ChainNode) else 0.5
                before[np.ix_(first, second)] = chance
    for child in node.children:
        _within(child, index, before)


def _root_precedences(top: TopLevel, weights: list[int]) -> FloatMatrix:
    """``[x, y]``: 1 when some path through ``top`` performs root ``x`` before root ``y`` and none performs
    ``y`` before ``x`` (a path through a root of weight 0 carries no execution), else 0. Any path to a state,
    the move from it and any path on to the end make a path: ``x`` can come before ``y`` when ``x`` is on a
    path to a state a move by ``y`` leaves from."""
    out, order = top.successors(), top.successors_first()
    terminal = set(top.terminal)
    ends: set[int] = set()  # the states some path leads from to the end
    for state in order:  # successors first
        if state in terminal or any(weights[root] > 0 and dst in ends for root, dst in out.get(state, {}).items()):
            ends.add(state)
    done = {s: 0 for s in top.initial if s in ends}  # reached: the roots on some path to it, as bits
    earlier = [0] * len(weights)  # the roots that can come before each root, as bits
    for state in reversed(order):  # predecessors first
        if state not in done:
            continue
        for root, dst in out.get(state, {}).items():
            if weights[root] > 0 and dst in ends:
                earlier[root] |= done[state]
                done[dst] = done.get(dst, 0) | done[state] | 1 << root
    can = np.zeros((len(weights), len(weights)), dtype=bool)  # [x, y]: x can come before y
    for y, bits in enumerate(earlier):
        lowest_first = np.frombuffer(bin(bits)[:1:-1].encode(), dtype=np.uint8) == ord("1")
        can[: len(lowest_first), y] = lowest_first
    result: FloatMatrix = (can & ~can.T).astype(np.float64)
    return result


def _root_orders(top: TopLevel, weights: list[int]) -> FloatMatrix:
    """``P[x, y]``: the probability that root ``x`` comes before root ``y`` on a path through ``top`` drawn
    with the executions it carries (root ``r`` weighing ``weights[r]``), among the paths performing both."""
    out, order = top.successors(), top.successors_first()
    terminal = set(top.terminal)
    log_weight = [math.log(w) if w > 0 else -math.inf for w in weights]
    log_paths: dict[int, float] = {}  # executions from a state to the end, in log space
    for state in order:  # successors first
        terms = [0.0] if state in terminal else []
        terms += [log_weight[root] + log_paths[dst] for root, dst in out.get(state, {}).items()]
        log_paths[state] = _log_sum(terms)
    size = len(weights)
    later: dict[int, npt.NDArray[np.float64]] = {}  # chance each root is performed after the state
    for state in order:
        chance = np.zeros(size)
        for root, dst in out.get(state, {}).items():
            step = math.exp(log_weight[root] + log_paths[dst] - log_paths[state])
            after = later[dst].copy()
            after[root] = 1.0
            chance += step * after
        later[state] = chance
    starts = [s for s in top.initial if log_paths.get(s, -math.inf) > -math.inf]
    total = _log_sum([log_paths[s] for s in starts])
    reach = dict.fromkeys(order, 0.0)
    for s in starts:
        reach[s] += math.exp(log_paths[s] - total)
    first_before = np.zeros((size, size))
    for state in reversed(order):  # predecessors first
        if reach[state] == 0.0:
            continue
        for root, dst in out.get(state, {}).items():
            step = reach[state] * math.exp(log_weight[root] + log_paths[dst] - log_paths[state])
            reach[dst] += step
            first_before[root] += step * later[dst]
    both = first_before + first_before.T
    result: FloatMatrix = np.divide(first_before, both, out=np.zeros_like(first_before), where=both > 0)
    return result


def _log_sum(terms: list[float]) -> float:
    """``log(sum(exp(t)))``, ``-inf`` for no terms."""
    if not terms:
        return -math.inf
    top = max(terms)
    if top == -math.inf:
        return top
    return top + math.log(sum(math.exp(t - top) for t in terms))
