"""Clique/Chain HTN nodes and the top level of a partial hierarchy: the data, and what can be read off one
node without running it.

A ``ChainNode`` runs its children in order; a ``CliqueNode`` runs its children in any order, each child
finished before the next starts (no interleaving). Leaves are ``ActionNode``: an action id and, when the same
action is performed more than once in a task, which performance it is (``occurrence``, counted from 1). Any
node may be optional and may carry ``counts`` and ``support`` (see :mod:`supportive.tasks.htn`, which also
re-exports every name here). A partial hierarchy's roots follow one another as its :class:`TopLevel` says.

This module imports nothing of the model, so :mod:`supportive.tasks.executions` (the state machine over a
hierarchy's executions) and :mod:`supportive.tasks.htn` (the ``HTN``, which runs that machine) both build on
it without importing each other.
"""

from __future__ import annotations

import dataclasses
from collections import Counter
from collections.abc import Callable, Collection, Iterable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any, Literal, TypeAlias

from supportive.errors import TaskModelError

__all__ = [
    "ActionNode",
    "ChainNode",
    "CliqueNode",
    "Counts",
    "Leaf",
    "Node",
    "Support",
    "TopLevel",
    "canonical",
    "leaf_actions",
    "nullable",
    "shape",
    "to_leaves",
    "with_children",
]

Leaf: TypeAlias = tuple[str, int]
"""A performed subgoal: (action id, occurrence)."""


@dataclass(frozen=True)
class Counts:
    """How often each choice at a node was made in the demonstrations it was learned from.

    Attributes:
        performed: Demonstrations in which the node was performed (at least one of its leaves done).
        skipped: Demonstrations in which an optional node was skipped (0 for a required node).
        first: For a clique (and a partial hierarchy's top level): times each child came first.
        after: For a clique: ``after[i][j]`` is how often child ``j`` directly followed child ``i``.
    """

    performed: int = 0
    skipped: int = 0
    first: tuple[int, ...] = ()
    after: tuple[tuple[int, ...], ...] = ()

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (the ``"counts"`` of the HTN JSON); empty parts are left out."""
        data: dict[str, object] = {"performed": self.performed}
        if self.skipped:
            data["skipped"] = self.skipped
        if self.first:
            data["first"] = list(self.first)
        if self.after:
            data["after"] = [list(row) for row in self.after]
        return data


@dataclass(frozen=True)
class Support:
    """The evidence a learned node rests on.

    Attributes:
        demonstrations: Demonstrations that show the node (perform at least one of its leaves).
        orders_seen: Distinct orders of its children seen in them (1 for a leaf).
        orders: Orders of its children the node admits (``k!`` for a clique of ``k``, 1 for a chain).
        observed: True when every order it admits was seen ("observed in full"); False when it was inferred
            (a clique accepted from commuting pairs, say).
    """

    demonstrations: int
    orders_seen: int
    orders: int
    observed: bool

    def as_dict(self) -> dict[str, object]:
        """Plain-data form (the ``"support"`` of the HTN JSON)."""
        return {
            "demonstrations": self.demonstrations,
            "orders_seen": self.orders_seen,
            "orders": self.orders,
            "observed": "full" if self.observed else "inferred",
        }


@dataclass(frozen=True)
class ActionNode:
    """A primitive subgoal."""

    action: str
    occurrence: int = 1
    optional: bool = False
    counts: Counts | None = field(default=None, compare=False, repr=False)
    support: Support | None = field(default=None, compare=False, repr=False)
    kind: Literal["action"] = field(default="action", init=False, repr=False)

    @property
    def leaf(self) -> Leaf:
        """The (action, occurrence) pair this leaf stands for."""
        return (self.action, self.occurrence)

    @cached_property
    def leaves(self) -> tuple[Leaf, ...]:
        """The leaves under this node, depth first."""
        return ((self.action, self.occurrence),)

    @property
    def label(self) -> str:
        """The action id, with ``#k`` for a repeated action's k-th performance."""
        return self.action if self.occurrence == 1 else f"{self.action}#{self.occurrence}"


@dataclass(frozen=True)
class ChainNode:
    """Children performed in this order (an order-invariant subtask)."""

    children: tuple[Node, ...]
    name: str | None = field(default=None, compare=False)
    optional: bool = False
    counts: Counts | None = field(default=None, compare=False, repr=False)
    support: Support | None = field(default=None, compare=False, repr=False)
    kind: Literal["chain"] = field(default="chain", init=False, repr=False)

    @cached_property
    def leaves(self) -> tuple[Leaf, ...]:
        """The leaves under this node, depth first."""
        return tuple(leaf for child in self.children for leaf in child.leaves)


@dataclass(frozen=True)
class CliqueNode:
    """Children performed in any order, none interleaved with another (an order-agnostic subtask)."""

    children: tuple[Node, ...]
    name: str | None = field(default=None, compare=False)
    optional: bool = False
    counts: Counts | None = field(default=None, compare=False, repr=False)
    support: Support | None = field(default=None, compare=False, repr=False)
    kind: Literal["clique"] = field(default="clique", init=False, repr=False)

    @cached_property
    def leaves(self) -> tuple[Leaf, ...]:
        """The leaves under this node, depth first."""
        return tuple(leaf for child in self.children for leaf in child.leaves)


Node: TypeAlias = ActionNode | ChainNode | CliqueNode


def to_leaves(actions: Iterable[str]) -> tuple[Leaf, ...]:
    """Number the performances of each action: ``["a", "b", "a"] -> (("a", 1), ("b", 1), ("a", 2))``."""
    seen: Counter[str] = Counter()
    out = []
    for action in actions:
        seen[action] += 1
        out.append((action, seen[action]))
    return tuple(out)


def leaf_actions(node: Node) -> tuple[str, ...]:
    """The action ids under ``node``, depth first (repeats included)."""
    return tuple(action for action, _ in node.leaves)


def with_children(
    node: ChainNode | CliqueNode, children: Iterable[Node], **changes: Any
) -> ChainNode | CliqueNode:
    """A copy of ``node`` with other children, keeping its name, optional flag, counts and support unless
    ``changes`` sets them."""
    return dataclasses.replace(node, children=tuple(children), **changes)


def nullable(node: Node) -> bool:
    """True when ``node`` may be performed as nothing: it is optional, or every child of it may be."""
    if node.optional:
        return True
    return not isinstance(node, ActionNode) and all(nullable(child) for child in node.children)


def canonical(node: Node) -> tuple[object, ...]:
    """A hashable form that is equal for equivalent hierarchies.

    Names, counts and support are ignored, clique children are unordered, and a chain nested directly in a
    chain is merged into it (both mean the same order), per invariant 3 of the design. An optional node is
    wrapped as ``("optional", form)`` (so an optional chain is not merged into its parent).
    """
    form = _canonical(node)
    return ("optional", form) if node.optional else form


def _canonical(node: Node) -> tuple[object, ...]:
    if isinstance(node, ActionNode):
        return ("action", node.action, node.occurrence)
    if isinstance(node, ChainNode):
        items: list[object] = []
        for child in node.children:
            form = canonical(child)
            if form[0] == "chain":
                items.extend(form[1])  # type: ignore[arg-type]
            else:
                items.append(form)
        return ("chain", tuple(items))
    return ("clique", frozenset(canonical(child) for child in node.children))


def shape(node: Node, *, optional: bool = True) -> object:
    """The structure of ``node`` with occurrence numbers left out (and optional flags, unless ``optional``):
    equal for the instances of one repeated subtask (the k legs of a table)."""
    if isinstance(node, ActionNode):
        form: object = ("action", node.action)
    elif isinstance(node, ChainNode):
        form = ("chain", tuple(shape(c, optional=optional) for c in node.children))
    else:
        form = ("clique", tuple(sorted((shape(c, optional=optional) for c in node.children), key=repr)))
    return ("optional", form) if optional and node.optional else form


@dataclass(frozen=True)
class TopLevel:
    """How the roots of a partial hierarchy may follow one another: the learned task graph at the level where
    compaction stopped (§2.1.5.2). States are numbered; an edge ``(src, r, dst)`` performs ``roots[r]``."""

    initial: tuple[int, ...]
    terminal: tuple[int, ...]
    edges: tuple[tuple[int, int, int], ...]
    counts: Counts | None = field(default=None, compare=False, repr=False)
    free: frozenset[int] = field(default=frozenset(), compare=False, repr=False)
    """Roots (indices) whose being done never lets another root be done or the task end: leaving one out
    of an execution admits the same orders of the rest as passing through it would (the optional roots of
    a partial order of roots; a hint for counting orders, not part of the language)."""
    stands_for: tuple[tuple[int, int], ...] | None = field(default=None, compare=False, repr=False)
    """When this top level keeps the orders of roots seen only because the partial order of roots the
    evidence establishes had too many states to build, that partial order's precedences (pairs of root
    indices, binding roots both performed): what the top level stands for when a likelihood counts its
    orders. In memory only, while learning (a hint, not part of the language; not saved)."""
    precedences: tuple[tuple[int, int], ...] | None = field(default=None, compare=False, repr=False)
    """When this top level was built as a partial order of roots, its precedences (pairs of root indices,
    binding roots both performed): the orders it admits of roots that include every root not ``free`` are
    that partial order's linear extensions, counted without walking its states. In memory only (a hint, not
    part of the language; not saved)."""

    def __hash__(self) -> int:
        return self._hash

    def with_counts(self, counts: Counts | None) -> TopLevel:
        """This top level with other ``counts`` (the same language): what is worked out from its edges (its
        successors and hash; their order, when it was) is worked out here once and shared."""
        other = replace(self, counts=counts)
        other.__dict__["_successors"] = self._successors
        other.__dict__["_hash"] = self._hash
        if "_successors_first" in self.__dict__:
            other.__dict__["_successors_first"] = self.__dict__["_successors_first"]
        return other

    @cached_property
    def _hash(self) -> int:
        """The hash of the fields compared (initial, terminal and edge states), worked out once: a top level
        keys the caches of order counts, and its edges may number hundreds of thousands."""
        return hash((self.initial, self.terminal, self.edges))

    def successors(self) -> dict[int, dict[int, int]]:
        """``state -> {root index -> next state}``: built once per top level and shared by every caller (the
        executions, the likelihood readings and the counts all walk it), so callers must not change it."""
        return self._successors

    @cached_property
    def _successors(self) -> dict[int, dict[int, int]]:
        out: dict[int, dict[int, int]] = {}
        for src, root, dst in self.edges:
            out.setdefault(src, {})[root] = dst
        return out

    def successors_first(self) -> list[int]:
        """Every state, each after all the states it leads to: built once per top level and shared, so callers
        must not change it."""
        return self._successors_first

    @cached_property
    def _successors_first(self) -> list[int]:
        out = self.successors()
        states = out.keys() | set(self.terminal) | set(self.initial) | {d for e in out.values() for d in e.values()}
        return _reverse_topological(sorted(states), out)

    def required_roots(self, n_roots: int) -> frozenset[int]:
        """The roots (of ``n_roots``) every execution performs: on every path from an initial state to a
        terminal one (an initial state with no move and no end requires nothing).

        >>> TopLevel((0,), (3,), ((0, 0, 1), (1, 1, 3), (0, 2, 2), (2, 1, 3))).required_roots(3)  # 0 1, or 2 1
        frozenset({1})
        """
        out = self.successors()
        terminal = set(self.terminal)
        every = -1  # all roots, as bits
        on_all: dict[int, int] = {}  # state -> roots (bits) on every path from it to a terminal state
        for state in self.successors_first():
            bits = 0 if state in terminal else every
            for root, dst in out.get(state, {}).items():
                bits &= 1 << root | on_all[dst]
            on_all[state] = bits
        found = every
        for state in self.initial:
            found &= on_all[state] if state in out or state in terminal else 0
        return frozenset(r for r in range(n_roots) if found >> r & 1)

    def count_orderings(self, weights: Sequence[int] | None = None, silent: Collection[int] = ()) -> int:
        """How many root orders this top level allows (exact, by dynamic programming); with ``weights``, each
        root performed on a path counts ``weights[root]`` times (its own orderings, say).

        ``silent`` roots may also be performed as nothing where a path passes them: what is counted is then
        the distinct orders of the roots performed (each weighted), however many paths give one (a path
        through a root performed as nothing gives the order of the path without it). That count keeps a set
        of states per prefix: it grows with the silent roots of free order, about threefold for each.

        Raises:
            TaskModelError: with ``silent`` roots, when the top level has a cycle (it is a DAG by design).
        """
        out = self.successors()
        terminal = set(self.terminal)
        weight = (lambda root: 1) if weights is None else weights.__getitem__
        if not silent:
            memo: dict[int, int] = {}
            for state in self.successors_first():
                memo[state] = int(state in terminal) + sum(
                    weight(root) * memo[dst] for root, dst in out.get(state, {}).items()
                )
            return sum(memo.get(s, int(s in terminal)) for s in self.initial)
        return _count_distinct(out, terminal, self.initial, weight, frozenset(silent))


def _count_distinct(
    out: dict[int, dict[int, int]],
    terminal: set[int],
    initial: Sequence[int],
    weight: Callable[[int], int],
    silent: frozenset[int],
) -> int:
    """:meth:`TopLevel.count_orderings` with roots that may be performed as nothing: the weighted orders of the
    roots performed, counted once each, over the sets of states a prefix of them may lead to (the subset
    construction of the graph whose ``silent`` edges may also be passed without a root performed)."""

    def closure(states: Iterable[int]) -> frozenset[int]:
        reached = set(states)
        frontier = list(reached)
        while frontier:
            for root, dst in out.get(frontier.pop(), {}).items():
                if root in silent and dst not in reached:
                    reached.add(dst)
                    frontier.append(dst)
        return frozenset(reached)

    def moves(states: frozenset[int]) -> dict[int, frozenset[int]]:
        targets: dict[int, set[int]] = {}
        for state in states:
            for root, dst in out.get(state, {}).items():
                targets.setdefault(root, set()).add(dst)
        return {root: closure(dsts) for root, dsts in targets.items()}

    start = closure(initial)
    memo: dict[frozenset[int], int] = {}
    successors: dict[frozenset[int], dict[int, frozenset[int]]] = {}  # the sets entered and not yet counted
    stack = [start]
    while stack:  # depth first, without recursion: a set is counted once every set it leads to is
        states = stack[-1]
        if states in memo:
            stack.pop()
            continue
        if states not in successors:
            successors[states] = moves(states)
        following = successors[states]
        waiting = [nxt for nxt in following.values() if nxt not in memo]
        if any(nxt in successors for nxt in waiting):  # entered, not counted: it leads back here
            raise TaskModelError("the top level has a cycle: its roots cannot be counted")
        if waiting:
            stack.extend(waiting)
            continue
        stack.pop()
        memo[states] = int(bool(states & terminal)) + sum(weight(root) * memo[nxt] for root, nxt in following.items())
        del successors[states]
    return memo[start]


def _reverse_topological(states: Sequence[int], out: dict[int, dict[int, int]]) -> list[int]:
    """``states`` ordered so that every state comes after all states it leads to (the graph is a DAG)."""
    order: list[int] = []
    seen: set[int] = set()
    for root in states:
        if root in seen:
            continue
        seen.add(root)
        stack = [(root, iter(out.get(root, {}).values()))]
        while stack:
            state, children = stack[-1]
            child = next(children, None)
            if child is None:
                order.append(state)
                stack.pop()
            elif child not in seen:
                seen.add(child)
                stack.append((child, iter(out.get(child, {}).values())))
    return order
