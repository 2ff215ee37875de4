"""Clique/Chain HTN nodes (§2.1.4) and what they mean.

A ``ChainNode`` runs its children in order; a ``CliqueNode`` runs its children in any order, each child
finished before the next starts (no interleaving). Leaves are ``ActionNode``: an action id and, when the same
action is performed more than once in a task, which performance it is (``occurrence``, counted from 1 in the
order performed, §2.1.2's multiset of completed actions).

The same classes describe a ground-truth ``structure`` from a task file and a learned hierarchy.
"""

from __future__ import annotations

import itertools
import math
from collections import Counter
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal, TypeAlias

import numpy as np

from supportive.seeding import Seed, rng_from

__all__ = [
    "HTN",
    "ActionNode",
    "ChainNode",
    "CliqueNode",
    "Leaf",
    "Node",
    "TopLevel",
    "allowed_next",
    "canonical",
    "count_orderings",
    "first_leaves",
    "internal_nodes",
    "iter_orderings",
    "last_leaves",
    "leaf_actions",
    "mean_action_depth",
    "node_count",
    "node_edges",
    "sample_ordering",
    "successor_pairs",
    "to_leaves",
]

Leaf: TypeAlias = tuple[str, int]
"""A performed subgoal: (action id, occurrence)."""


@dataclass(frozen=True)
class ActionNode:
    """A primitive subgoal."""

    action: str
    occurrence: int = 1
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


def canonical(node: Node) -> tuple[object, ...]:
    """A hashable form that is equal for equivalent hierarchies.

    Names are ignored, clique children are unordered, and a chain nested directly in a chain is merged into
    it (both mean the same order), per invariant 3 of the design.
    """
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


def count_orderings(node: Node) -> int:
    """How many leaf sequences ``node`` admits (exact, without enumerating)."""
    if isinstance(node, ActionNode):
        return 1
    inner = math.prod(count_orderings(child) for child in node.children)
    if isinstance(node, CliqueNode):
        return math.factorial(len(node.children)) * inner
    return inner


def iter_orderings(node: Node) -> Iterator[tuple[Leaf, ...]]:
    """Every leaf sequence ``node`` admits. Mind ``count_orderings`` first: the number can be huge."""
    if isinstance(node, ActionNode):
        yield node.leaves
        return
    orders: Iterable[Sequence[Node]] = (
        [node.children] if isinstance(node, ChainNode) else itertools.permutations(node.children)
    )
    for order in orders:
        for parts in itertools.product(*(list(iter_orderings(child)) for child in order)):
            yield tuple(leaf for part in parts for leaf in part)


def sample_ordering(node: Node, seed: Seed = None) -> tuple[Leaf, ...]:
    """One leaf sequence drawn uniformly from those ``node`` admits."""
    rng = rng_from(seed)
    return tuple(_sample(node, rng))


def _sample(node: Node, rng: np.random.Generator) -> Iterator[Leaf]:
    if isinstance(node, ActionNode):
        yield node.leaf
        return
    children = list(node.children)
    if isinstance(node, CliqueNode):
        children = [children[i] for i in rng.permutation(len(children))]
    for child in children:
        yield from _sample(child, rng)


def admits(node: Node, leaves: Sequence[Leaf]) -> bool:
    """True when ``leaves`` is one of the sequences ``node`` admits."""
    return len(leaves) == len(node.leaves) and _admits_at(node, leaves, 0)


def _admits_at(node: Node, leaves: Sequence[Leaf], start: int) -> bool:
    if isinstance(node, ActionNode):
        return leaves[start] == node.leaf
    if isinstance(node, ChainNode):
        pos = start
        for child in node.children:
            if not _block_matches(child, leaves, pos):
                return False
            pos += len(child.leaves)
        return True
    owner = {leaf: child for child in node.children for leaf in child.leaves}
    pos, used = start, set()
    for _ in node.children:
        member = owner.get(leaves[pos])
        if member is None or id(member) in used or not _block_matches(member, leaves, pos):
            return False
        used.add(id(member))
        pos += len(member.leaves)
    return True


def _block_matches(node: Node, leaves: Sequence[Leaf], start: int) -> bool:
    block = leaves[start : start + len(node.leaves)]
    return sorted(block) == sorted(node.leaves) and _admits_at(node, leaves, start)


def internal_nodes(node: Node) -> Iterator[ChainNode | CliqueNode]:
    """Every chain and clique under ``node`` (itself included), outermost first."""
    if not isinstance(node, ActionNode):
        yield node
        for child in node.children:
            yield from internal_nodes(child)


def first_leaves(node: Node) -> frozenset[Leaf]:
    """Leaves that can be performed first in ``node``."""
    if isinstance(node, ActionNode):
        return frozenset((node.leaf,))
    if isinstance(node, ChainNode):
        return first_leaves(node.children[0])
    return frozenset().union(*(first_leaves(c) for c in node.children))


def last_leaves(node: Node) -> frozenset[Leaf]:
    """Leaves that can be performed last in ``node``."""
    if isinstance(node, ActionNode):
        return frozenset((node.leaf,))
    if isinstance(node, ChainNode):
        return last_leaves(node.children[-1])
    return frozenset().union(*(last_leaves(c) for c in node.children))


def successor_pairs(node: Node) -> set[tuple[Leaf, Leaf]]:
    """Pairs ``(u, v)`` such that ``v`` immediately follows ``u`` in some sequence ``node`` admits: the
    transitions a flat (non-hierarchical) model of the task needs."""
    pairs: set[tuple[Leaf, Leaf]] = set()
    for inner in internal_nodes(node):
        children = inner.children
        if isinstance(inner, ChainNode):
            links = itertools.pairwise(children)
        else:
            links = ((a, b) for a in children for b in children if a is not b)  # type: ignore[assignment]
        for a, b in links:
            pairs.update((u, v) for u in last_leaves(a) for v in first_leaves(b))
    return pairs


def allowed_next(node: Node, done: Iterable[Leaf]) -> frozenset[Leaf]:
    """Leaves that may be performed next, after the leaves in ``done`` (a valid prefix of one of ``node``'s
    sequences): nothing when ``node`` is finished.

    >>> task = ChainNode((ActionNode("knife"), CliqueNode((ActionNode("carrots"), ActionNode("celery")))))
    >>> sorted(a for a, _ in allowed_next(task, [("knife", 1)]))
    ['carrots', 'celery']

    Raises:
        ValueError: when ``done`` is not a valid prefix (a chain child started before the one ahead of it is
            finished, or two clique children both half done).
    """
    return _allowed(node, frozenset(done))


def _progress(node: Node, done: frozenset[Leaf]) -> int:
    """0: not started, 1: under way, 2: finished."""
    count = sum(leaf in done for leaf in node.leaves)
    return 0 if count == 0 else 2 if count == len(node.leaves) else 1


def _allowed(node: Node, done: frozenset[Leaf]) -> frozenset[Leaf]:
    if isinstance(node, ActionNode):
        return frozenset() if node.leaf in done else frozenset((node.leaf,))
    states = [_progress(child, done) for child in node.children]
    if isinstance(node, ChainNode):
        for i, state in enumerate(states):
            if state != 2:
                if any(later for later in states[i + 1 :]):
                    raise ValueError(
                        f"{node.name or 'chain'}: a later part is started before an earlier one ends"
                    )
                return _allowed(node.children[i], done)
        return frozenset()
    under_way = [child for child, state in zip(node.children, states, strict=True) if state == 1]
    if len(under_way) > 1:
        raise ValueError(f"{node.name or 'clique'}: two parts are under way at once")
    if under_way:
        return _allowed(under_way[0], done)
    fresh = [child for child, state in zip(node.children, states, strict=True) if state == 0]
    return frozenset().union(*(_allowed(child, done) for child in fresh))


def node_count(node: Node) -> int:
    """Nodes in the tree under ``node``, leaves included."""
    if isinstance(node, ActionNode):
        return 1
    return 1 + sum(node_count(child) for child in node.children)


def node_edges(node: Node) -> int:
    """Transitions the tree under ``node`` needs to state its ordering, counted as §2.1.7.3 counts them.

    A chain of k children needs k − 1 (one between consecutive children; entering and leaving the chain is
    its parent's single edge, whatever the chain holds); a clique of k children needs k (one between each
    member and the clique node: any member may start or end it); a primitive needs none. Summed over every
    chain and clique. So a clique of k primitives costs k against the flat model's k² − k
    (``len(successor_pairs(node))``), a chain of k primitives k − 1 against k − 1, and a transition into or
    out of a clique one edge instead of one per member.

    >>> a, b, c, d, e = (ActionNode(x) for x in "abcde")
    >>> node = ChainNode((a, CliqueNode((b, c, d)), e))
    >>> node_edges(node), len(successor_pairs(node))
    (5, 12)
    """
    if isinstance(node, ActionNode):
        return 0
    own = len(node.children) - 1 if isinstance(node, ChainNode) else len(node.children)
    return own + sum(node_edges(child) for child in node.children)


def _depths(node: Node, depth: int) -> Iterator[int]:
    if isinstance(node, ActionNode):
        yield depth
        return
    for child in node.children:
        yield from _depths(child, depth + 1)


def mean_action_depth(roots: Sequence[Node]) -> float:
    """Mean number of chain/clique ancestors of a primitive (§2.1.7.2 reports 1.99–3.61 on IKEA-like tasks)."""
    depths = [d for root in roots for d in _depths(root, 0)]
    return float(np.mean(depths)) if depths else 0.0


@dataclass(frozen=True)
class TopLevel:
    """How the roots of a partial hierarchy may follow one another: the learned task graph at the level where
    compaction stopped (§2.1.5.2). States are numbered; an edge ``(src, r, dst)`` performs ``roots[r]``."""

    initial: tuple[int, ...]
    terminal: tuple[int, ...]
    edges: tuple[tuple[int, int, int], ...]

    def successors(self) -> dict[int, dict[int, int]]:
        """``state -> {root index -> next state}``."""
        out: dict[int, dict[int, int]] = {}
        for src, root, dst in self.edges:
            out.setdefault(src, {})[root] = dst
        return out

    def count_orderings(self) -> int:
        """How many root orders this top level allows (exact, by dynamic programming)."""
        out = self.successors()
        terminal = set(self.terminal)
        memo: dict[int, int] = {}

        def paths(state: int) -> int:
            if state not in memo:
                memo[state] = int(state in terminal) + sum(paths(dst) for dst in out.get(state, {}).values())
            return memo[state]

        return sum(paths(s) for s in self.initial)


@dataclass(frozen=True)
class HTN:
    """A learned (or given) Clique/Chain HTN.

    ``roots`` holds one node when the hierarchy is complete; otherwise the top-level nodes left when
    compaction stopped, in the order their members first occur, and ``top_level`` says in which orders they
    were seen. ``alternatives`` holds other complete hierarchies found by ambiguity resolution (§2.1.5.3),
    best first: each admits only executions known to be valid.
    """

    task: str
    roots: tuple[Node, ...]
    top_level: TopLevel | None = None
    alternatives: tuple[HTN, ...] = ()

    @property
    def complete(self) -> bool:
        """True when the hierarchy has a single root."""
        return len(self.roots) == 1

    @cached_property
    def leaves(self) -> tuple[Leaf, ...]:
        """Every leaf, root by root."""
        return tuple(leaf for root in self.roots for leaf in root.leaves)

    def admits(self, actions: Sequence[str]) -> bool:
        """True when the HTN allows performing ``actions`` (action ids) in this order."""
        return self.admits_leaves(to_leaves(actions))

    def admits_leaves(self, leaves: Sequence[Leaf]) -> bool:
        """True when the HTN allows this sequence of (action, occurrence) leaves."""
        if self.top_level is None:
            return len(self.roots) == 1 and admits(self.roots[0], leaves)
        owner = {leaf: i for i, root in enumerate(self.roots) for leaf in root.leaves}
        out = self.top_level.successors()
        terminal = set(self.top_level.terminal)
        return any(self._walk(state, leaves, owner, out, terminal) for state in self.top_level.initial)

    def _walk(
        self,
        state: int,
        leaves: Sequence[Leaf],
        owner: dict[Leaf, int],
        out: dict[int, dict[int, int]],
        terminal: set[int],
    ) -> bool:
        pos = 0
        while pos < len(leaves):
            index = owner.get(leaves[pos])
            if index is None or index not in out.get(state, {}):
                return False
            root = self.roots[index]
            if pos + len(root.leaves) > len(leaves) or not _block_matches(root, leaves, pos):
                return False
            pos += len(root.leaves)
            state = out[state][index]
        return state in terminal

    def count_orderings(self) -> int:
        """How many leaf sequences this HTN admits (exact)."""
        inner = math.prod(count_orderings(root) for root in self.roots)
        if self.top_level is None:
            return inner
        return self.top_level.count_orderings() * inner

    def canonical(self) -> tuple[object, ...]:
        """Hashable form, equal for equivalent hierarchies (see :func:`canonical`)."""
        return tuple(canonical(root) for root in self.roots)

    def successor_pairs(self) -> set[tuple[Leaf, Leaf]]:
        """Pairs ``(u, v)`` such that ``v`` immediately follows ``u`` in some sequence the HTN admits."""
        pairs = set().union(*(successor_pairs(root) for root in self.roots))
        if self.top_level is not None:
            following: dict[int, set[int]] = {}
            for _, root, dst in self.top_level.edges:
                following.setdefault(root, set()).update(
                    r for src, r, _ in self.top_level.edges if src == dst
                )
            for root, nexts in following.items():
                for nxt in nexts:
                    pairs.update(
                        (u, v) for u in last_leaves(self.roots[root]) for v in first_leaves(self.roots[nxt])
                    )
        return pairs

    def node_count(self) -> int:
        """Nodes in all trees, leaves included."""
        return sum(node_count(root) for root in self.roots)

    def edge_count(self) -> int:
        """Transitions the CC-HTN needs: :func:`node_edges` summed over the roots, plus, for a partial
        hierarchy, the transitions of its top level (``len(top_level.edges)``)."""
        extra = len(self.top_level.edges) if self.top_level is not None else 0
        return sum(node_edges(root) for root in self.roots) + extra

    def mean_action_depth(self) -> float:
        """Mean depth of a primitive (see :func:`mean_action_depth`)."""
        return mean_action_depth(self.roots)
