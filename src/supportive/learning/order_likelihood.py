"""A hierarchy read as "which parts, then any valid order": the likelihood the slip search compares.

An execution is drawn in two steps: every optional node whose parent is performed is performed or skipped
with the frequencies the demonstrations show (``(performed + 1/2) / (performed + skipped + 1)``, a Jeffreys
estimate), then the performed leaves are done in an order drawn **uniformly** among the orders the hierarchy
admits for them. So an execution's probability is the product of its take-or-skip choices over the number
of valid orders of what it performs.

This reading judges structure, not habit: how much a hierarchy must loosen to admit a demonstration is the
factor by which the number of valid orders grows, paid by every demonstration. Weighting orders by how often
people chose them (:class:`~supportive.learning.distribution.ProgressModel`, the predictor's reading) would
reward a hierarchy for forbidding what few people happened to do, and a rare but valid order of free steps
would then look like a slip.

**Habits** (issue #23). People are not uniform: they share a preferred order, and a valid order few of them
take is rare, not wrong. With ``concentration`` α finite, :meth:`OrderLikelihood.log_probability_of_all`
reads a set of executions jointly: each *order choice* the hierarchy leaves open (a clique's order of the
children an execution performs; a partial top level's order of the roots it performs) has its own unknown
distribution over the orders admitted there, with a symmetric Dirichlet(α) prior, integrated out (the
Dirichlet-multinomial, i.e. the probability of the choices made in sequence, each with chance
``(times chosen so far + α) / (choices so far + K α)`` among the ``K`` orders admitted). An order many
people take then costs little however many others are admitted; one nobody else took costs about
``log(n K / α)``. As α grows the reading tends to the uniform one above (α = ∞ is it exactly). The take-or-skip
choices are read as above.

>>> from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode
>>> htn = HTN("t", (ChainNode((ActionNode("k"), CliqueNode((ActionNode("a"), ActionNode("b"))))),))
>>> reading = OrderLikelihood(htn)
>>> round(math.exp(reading.log_probability([("k", 1), ("b", 1), ("a", 1)])), 3)  # one of two orders
0.5
>>> reading.log_probability([("a", 1), ("k", 1), ("b", 1)])
-inf
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Sequence

from supportive.errors import LearningError
from supportive.learning.linear_extensions import count_linear_extensions
from supportive.tasks.htn import HTN, ActionNode, ChainNode, Leaf, Node, TopLevel, nullable, to_leaves

_Choice = tuple[object, int, tuple[int, ...]]
"""An order choice an execution made: what was chosen (a clique by its place and its performed children, or
the top level by its performed roots), how many orders were admitted there, and which was taken."""

__all__ = ["OrderLikelihood"]


class OrderLikelihood:
    """The two-step reading of ``htn`` (see the module docstring).

    ``shared``: a dict that readings of several hierarchies may share, where the orders of a partial top
    level are kept by what decides them (the top level's order automaton, each root's number of orders,
    which roots are performed and which may be skipped): hierarchies learned from nearly the same
    demonstrations often share their top level, and counting its orders is the costly part.

    ``concentration``: the Dirichlet concentration α of each order choice in
    :meth:`log_probability_of_all` (above 0; ``math.inf``, the default, is the uniform reading)."""

    def __init__(
        self, htn: HTN, *, shared: dict[object, int] | None = None, concentration: float = math.inf
    ) -> None:
        if not concentration > 0.0:
            raise LearningError(f"concentration must be above 0, got {concentration}")
        self.htn = htn
        self.concentration = concentration
        self._orders: dict[frozenset[Leaf], int] = {}
        self._shared = shared if shared is not None else {}
        top = htn.top_level
        self._successors = top.successors() if top is not None else {}

    def log_probability(self, leaves: Sequence[Leaf]) -> float:
        """Natural log of the probability of the execution ``leaves``; ``-inf`` when the hierarchy does not
        admit it."""
        if not self.htn.admits_leaves(leaves):
            return -math.inf
        done = frozenset(leaves)
        return sum(
            _choice(node, done) for root in self.htn.roots for node in _performed_parents(root, done)
        ) - math.log(self.orders(done))

    def log_probability_of_all(self, executions: Iterable[Sequence[Leaf]]) -> float:
        """Natural log of the joint probability of ``executions`` (``-inf`` when the hierarchy refuses one):
        with a finite ``concentration``, each order choice's distribution integrated out under its Dirichlet
        prior (the module docstring); with an infinite one, the sum of :meth:`log_probability`.

        >>> from supportive.tasks.htn import HTN, ActionNode, CliqueNode
        >>> htn = HTN("t", (CliqueNode((ActionNode("a"), ActionNode("b"))),))
        >>> same = [[("a", 1), ("b", 1)]] * 3
        >>> round(OrderLikelihood(htn).log_probability_of_all(same), 3)  # 3 log(1/2)
        -2.079
        >>> round(OrderLikelihood(htn, concentration=1.0).log_probability_of_all(same), 3)  # 1/2 · 2/3 · 3/4
        -1.386
        """
        if math.isinf(self.concentration):
            return sum(self.log_probability(leaves) for leaves in executions)
        alpha = self.concentration
        total = 0.0
        chosen: dict[object, tuple[int, Counter[tuple[int, ...]]]] = {}
        for leaves in executions:
            if not self.htn.admits_leaves(leaves):
                return -math.inf
            done = frozenset(leaves)
            total += sum(
                _choice(node, done) for root in self.htn.roots for node in _performed_parents(root, done)
            )
            for where, admitted, order in self._order_choices(leaves):
                chosen.setdefault(where, (admitted, Counter()))[1][order] += 1
        for admitted, orders in chosen.values():
            total += _rising_log(admitted, alpha, orders.total()) + sum(
                math.lgamma(times + alpha) - math.lgamma(alpha) for times in orders.values()
            )
        return total

    def _order_choices(self, leaves: Sequence[Leaf]) -> list[_Choice]:
        """The order choices the admitted execution ``leaves`` made (each clique's children and the top
        level's roots are done one after the other, so an order is read off where each begins)."""
        first: dict[Leaf, int] = {}
        for i, leaf in enumerate(leaves):
            first.setdefault(leaf, i)
        done = frozenset(leaves)

        def start(node: Node) -> int:
            return min(first[leaf] for leaf in node.leaves if leaf in first)

        out: list[_Choice] = []
        stack: list[tuple[tuple[int, ...], Node]] = [
            ((r,), root) for r, root in enumerate(self.htn.roots) if not done.isdisjoint(root.leaves)
        ]
        while stack:
            place, node = stack.pop()
            if isinstance(node, ActionNode):
                continue
            parts = [i for i, child in enumerate(node.children) if not done.isdisjoint(child.leaves)]
            if not isinstance(node, ChainNode) and len(parts) > 1:
                order = tuple(sorted(parts, key=lambda i: start(node.children[i])))
                out.append(((place, tuple(parts)), math.factorial(len(parts)), order))
            stack.extend(((*place, i), node.children[i]) for i in parts)
        top = self.htn.top_level
        performed = [i for i, root in enumerate(self.htn.roots) if not done.isdisjoint(root.leaves)]
        if top is not None and len(performed) > 1:
            skippable = frozenset(i for i, root in enumerate(self.htn.roots) if i not in performed and nullable(root))
            key = ("root orders", top, top.stands_for, tuple(performed), skippable)
            admitted = self._shared.get(key)
            if admitted is None:
                ones = [1] * len(self.htn.roots)
                admitted = self._shared[key] = self._top_orders(top, ones, performed, set(skippable))
            order = tuple(sorted(performed, key=lambda i: start(self.htn.roots[i])))
            out.append((("top", tuple(performed)), admitted, order))
        return out

    def log_probability_of_actions(self, actions: Sequence[str]) -> float:
        """:meth:`log_probability` of an execution given as action ids (the k-th performance of an action
        counted as its k-th leaf; whether the hierarchy admits it is decided by action ids, as
        :meth:`HTN.admits <supportive.tasks.htn.HTN.admits>` does)."""
        if not self.htn.admits(actions):
            return -math.inf
        leaves = to_leaves(actions)
        if self.htn.admits_leaves(leaves):
            return self.log_probability(leaves)
        done = frozenset(leaves)  # a repeated subtask's instances, matched by the hierarchy, not by count
        return -math.log(max(self.orders(done), 1))

    def orders(self, done: frozenset[Leaf]) -> int:
        """How many orders of exactly the leaves ``done`` the hierarchy admits."""
        orders = self._orders.get(done)
        if orders is None:
            orders = self._orders[done] = self._count(done)
        return orders

    def parameters(self) -> int:
        """The take-or-skip frequencies the demonstrations fix: optional nodes both performed and skipped."""
        return sum(
            1
            for root in self.htn.roots
            for node in _nodes(root)
            if node.optional and node.counts is not None and node.counts.performed and node.counts.skipped
        )

    def _count(self, done: frozenset[Leaf]) -> int:
        """Valid orders of exactly the leaves ``done``. On a partial hierarchy's top level, the roots that
        perform none of them and may be performed as nothing are skipped, as the executions skip them; the
        top level is walked as sets of states, so each order is counted once however many ways lead to it."""
        counts = [_orders(root, done) for root in self.htn.roots]
        top = self.htn.top_level
        if top is None:
            return math.prod(c for c in counts if c)
        performed = sorted(i for i, root in enumerate(self.htn.roots) if not done.isdisjoint(root.leaves))
        skippable = {i for i, root in enumerate(self.htn.roots) if i not in performed and nullable(root)}
        key = (top, top.stands_for, tuple(counts), tuple(performed), frozenset(skippable))
        known = self._shared.get(key)
        if known is None:
            known = self._shared[key] = self._top_orders(top, counts, performed, skippable)
        return known

    def _top_orders(
        self, top: TopLevel, counts: Sequence[int], performed: Sequence[int], skippable: set[int]
    ) -> int:
        """The orders a partial top level admits of the ``performed`` roots, each weighted by that root's
        ``counts``. A top level keeping the orders seen in place of a partial order too large to build counts
        those the partial order admits (:attr:`~supportive.tasks.htn.TopLevel.stands_for`: its precedences bind
        roots both performed); one built as a partial order counts its linear extensions
        (:attr:`~supportive.tasks.htn.TopLevel.precedences`) when every root it needs is performed, which is
        what walking its states gives; either unless that count is past
        :func:`~supportive.learning.linear_extensions.count_linear_extensions`' bound. Any other is walked
        (:meth:`_walk`)."""
        precedences = top.stands_for
        if precedences is None and top.free.union(performed) == set(range(len(counts))):
            precedences = top.precedences
        if precedences is not None:
            place = {root: k for k, root in enumerate(performed)}
            binding = [(place[u], place[v]) for u, v in precedences if u in place and v in place]
            orders = count_linear_extensions(len(performed), binding)
            if orders:
                return orders * math.prod(counts[i] for i in performed)
        return self._walk(top, counts, performed, skippable)

    def _walk(
        self, top: TopLevel, counts: Sequence[int], performed: Sequence[int], skippable: set[int]
    ) -> int:
        """The orders of a partial top level: paths of its automaton through the ``performed`` roots, each
        weighted by that root's orders, walking through the ``skippable`` roots as if absent."""
        successors = self._successors
        terminal = set(top.terminal)
        if skippable <= top.free:  # skipping only forbids: one state at a time, the roots done fix what is left
            return math.prod(counts[i] for i in performed) * self._plain(top, frozenset(performed))

        def closed(states: Iterable[int]) -> frozenset[int]:
            seen, stack = set(states), list(states)
            while skippable and stack:
                for root, nxt in successors.get(stack.pop(), {}).items():
                    if root in skippable and nxt not in seen:
                        seen.add(nxt)
                        stack.append(nxt)
            return frozenset(seen)

        memo: dict[tuple[frozenset[int], int], int] = {}

        def paths(states: frozenset[int], left: int) -> int:
            total = memo.get((states, left))
            if total is None:
                total = int(left == 0 and not terminal.isdisjoint(states))
                if left:
                    for root in performed:
                        after = {
                            nxt
                            for state in states
                            if (nxt := successors.get(state, {}).get(root)) is not None
                        }
                        if after:
                            total += counts[root] * paths(closed(after), left - 1)
                memo[(states, left)] = total
            return total

        return paths(closed(top.initial), len(performed))

    def _plain(self, top: TopLevel, performed: frozenset[int]) -> int:
        """The root orders of a top level that perform exactly ``performed`` (each path is one order: no
        root is skipped)."""
        successors = self._successors
        terminal = set(top.terminal)
        memo: dict[int, int] = {}

        def paths(state: int, left: int) -> int:
            total = memo.get(state)
            if total is None:
                total = int(left == 0 and state in terminal)
                if left:
                    for root, nxt in successors.get(state, {}).items():
                        if root in performed:
                            total += paths(nxt, left - 1)
                memo[state] = total
            return total

        return sum(paths(state, len(performed)) for state in top.initial)


_EXACT_GAMMA = 1e9
"""Below this ``K α`` the Dirichlet-multinomial's normaliser is taken from ``lgamma`` (its error is a
millionth of a nat there); above it, from a sum of logs."""


def _rising_log(admitted: int, alpha: float, chosen: int) -> float:
    """``log Γ(K α) - log Γ(K α + m)`` for ``K = admitted`` orders and ``m = chosen`` choices: minus the log of
    ``K α (K α + 1) … (K α + m - 1)``. For a large ``K`` (a clique of many children, a top level of many free
    roots) the difference of two huge ``lgamma`` values loses every digit (``K α + m`` rounds to ``K α``
    beyond 2^53, and ``K`` itself may be past a float's range), so it is summed as ``log K + log(α + i / K)``.

    >>> round(_rising_log(4, 0.5, 3), 6) == round(-math.log(2 * 3 * 4), 6)
    True
    >>> round(_rising_log(10**30, 0.25, 2) / (2 * math.log(0.25 * 10**30)), 9)  # not 0, as lgamma gives
    -1.0
    """
    if admitted * alpha < _EXACT_GAMMA:
        return math.lgamma(admitted * alpha) - math.lgamma(admitted * alpha + chosen)
    log_k = math.log(admitted)
    return -sum(log_k + math.log(alpha + i / admitted) for i in range(chosen))


def _nodes(node: Node) -> list[Node]:
    out = [node]
    if not isinstance(node, ActionNode):
        for child in node.children:
            out.extend(_nodes(child))
    return out


def _performed_parents(node: Node, done: frozenset[Leaf]) -> list[Node]:
    """Every node whose take-or-skip was decided in an execution performing ``done``: the optional nodes
    whose parent was performed (the roots count as performed by the task)."""
    out = [node] if node.optional else []
    if not isinstance(node, ActionNode) and not done.isdisjoint(node.leaves):
        for child in node.children:
            out.extend(_performed_parents(child, done))
    return out


def _choice(node: Node, done: frozenset[Leaf]) -> float:
    """Log-probability of ``node`` being performed or skipped, as ``done`` shows."""
    counts = node.counts
    performed = counts.performed if counts is not None else 0
    skipped = counts.skipped if counts is not None else 0
    take = (performed + 0.5) / (performed + skipped + 1.0)
    return math.log(take if not done.isdisjoint(node.leaves) else 1.0 - take)


def _orders(node: Node, done: frozenset[Leaf]) -> int:
    """Orders of exactly the leaves of ``done`` under ``node`` (1 when it performs none of them)."""
    if isinstance(node, ActionNode):
        return 1
    parts = [child for child in node.children if not done.isdisjoint(child.leaves)]
    product = math.prod(_orders(child, done) for child in parts)
    if isinstance(node, ChainNode):
        return product
    return math.factorial(len(parts)) * product
