"""Clique/Chain HTN nodes (§2.1.4) and what they mean.

A ``ChainNode`` runs its children in order; a ``CliqueNode`` runs its children in any order, each child
finished before the next starts (no interleaving). Leaves are ``ActionNode``: an action id and, when the same
action is performed more than once in a task, which performance it is (``occurrence``, counted from 1 in the
order performed, §2.1.2's multiset of completed actions).

Any node may be **optional** (``optional=True``): it is performed whole or skipped whole. A learned node also
carries how often each choice was made in the demonstrations (``counts``, :class:`Counts`) and what evidence
it rests on (``support``, :class:`Support`); neither takes part in equality.

The same classes describe a ground-truth ``structure`` from a task file and a learned hierarchy.

The node classes and :class:`TopLevel` are defined in :mod:`supportive.tasks.nodes` (re-exported here); this module
holds what they mean (counting, sampling, admitting) and the :class:`HTN`, whose executions
:mod:`supportive.tasks.executions` runs.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Collection, Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from supportive.errors import TaskModelError
from supportive.seeding import Seed, rng_from
from supportive.tasks.executions import Executions
from supportive.tasks.nodes import (
    ActionNode,
    ChainNode,
    CliqueNode,
    Counts,
    Leaf,
    Node,
    Support,
    TopLevel,
    canonical,
    leaf_actions,
    nullable,
    shape,
    to_leaves,
    with_children,
)

__all__ = [
    "HTN",
    "ActionNode",
    "ChainNode",
    "CliqueNode",
    "Counts",
    "Leaf",
    "Node",
    "Support",
    "TopLevel",
    "allowed_next",
    "canonical",
    "count_orderings",
    "count_performed",
    "first_leaves",
    "internal_nodes",
    "iter_orderings",
    "last_leaves",
    "leaf_actions",
    "mean_action_depth",
    "node_count",
    "node_edges",
    "nullable",
    "sample_ordering",
    "shape",
    "successor_pairs",
    "to_leaves",
    "with_children",
]

def _counts(node: Node) -> tuple[int, bool]:
    """``(non-empty sequences node admits, whether it may also be performed as nothing)``."""
    if isinstance(node, ActionNode):
        return 1, node.optional
    parts = [_counts(child) for child in node.children]
    if isinstance(node, ChainNode):
        total = math.prod(n + int(e) for n, e in parts)
        everything_skippable = all(e for _, e in parts)
        return total - int(everything_skippable), node.optional or everything_skippable
    # clique: choose which children are performed (the others must be skippable), then their order.
    poly = [1]
    for n, e in parts:
        step = [0] * (len(poly) + 1)
        for k, coef in enumerate(poly):
            if e:
                step[k] += coef
            step[k + 1] += coef * n
        poly = step
    total = sum(math.factorial(k) * coef for k, coef in enumerate(poly))
    return total - poly[0], node.optional or poly[0] > 0


def count_orderings(node: Node) -> int:
    """How many leaf sequences ``node`` admits (exact, without enumerating); a node that may be skipped also
    admits the empty sequence.

    >>> count_orderings(ChainNode((ActionNode("a"), ActionNode("b", optional=True))))
    2
    """
    performed, skippable = _counts(node)
    return performed + int(skippable)


def count_performed(node: Node) -> int:
    """How many non-empty leaf sequences ``node`` admits."""
    return _counts(node)[0]


def iter_orderings(node: Node) -> Iterator[tuple[Leaf, ...]]:
    """Every leaf sequence ``node`` admits (the empty one too when it may be skipped). Mind
    ``count_orderings`` first: the number can be huge."""
    seen_empty = False
    for sequence in _iter_performed(node):
        seen_empty |= not sequence
        yield sequence
    if node.optional and not seen_empty:
        yield ()


def _iter_performed(node: Node) -> Iterator[tuple[Leaf, ...]]:
    """Sequences of ``node`` when it is not skipped as an optional node (empty ones possible when every
    child may be skipped)."""
    if isinstance(node, ActionNode):
        yield node.leaves
        return
    if isinstance(node, ChainNode):
        options = [list(iter_orderings(child)) for child in node.children]
        for parts in itertools.product(*options):
            yield tuple(leaf for part in parts for leaf in part)
        return
    required = [i for i, child in enumerate(node.children) if not nullable(child)]
    others = [i for i in range(len(node.children)) if i not in required]
    for size in range(len(others), -1, -1):
        for extra in itertools.combinations(others, size):
            present = sorted((*required, *extra))
            for order in itertools.permutations(node.children[i] for i in present):
                options = [[s for s in iter_orderings(child) if s] for child in order]
                for parts in itertools.product(*options):
                    yield tuple(leaf for part in parts for leaf in part)


def sample_ordering(node: Node, seed: Seed = None) -> tuple[Leaf, ...]:
    """One leaf sequence drawn uniformly from those ``node`` admits."""
    rng = rng_from(seed)
    return tuple(_sample(node, rng, allow_empty=True))


def _sample(node: Node, rng: np.random.Generator, *, allow_empty: bool) -> list[Leaf]:
    """A uniform draw among the node's sequences (the non-empty ones when ``allow_empty`` is False). A node
    that cannot be skipped draws exactly what it drew before optional nodes existed."""
    performed, skippable = _counts(node)
    if allow_empty and skippable and rng.random() * (performed + 1) < 1:
        return []
    if isinstance(node, ActionNode):
        return [node.leaf]
    if isinstance(node, CliqueNode):
        present = [node.children[i] for i in _sample_present(node.children, rng)]
        order = [present[i] for i in rng.permutation(len(present))]
        return [leaf for child in order for leaf in _sample(child, rng, allow_empty=False)]
    while True:  # a chain whose every part may be skipped: draw again until something is performed
        drawn = [leaf for child in node.children for leaf in _sample(child, rng, allow_empty=True)]
        if drawn:
            return drawn


def _sample_present(children: Sequence[Node], rng: np.random.Generator) -> list[int]:
    """Which children of a performed clique are performed (at least one), drawn with the weight of the
    sequences each choice allows; every child, without drawing, when none may be skipped."""
    parts = [_counts(child) for child in children]
    optional = [i for i, (_, e) in enumerate(parts) if e]
    if not optional:
        return list(range(len(children)))
    choices = []
    weights = []
    for size in range(len(optional) + 1):
        for extra in itertools.combinations(optional, size):
            present = sorted({i for i, (_, e) in enumerate(parts) if not e} | set(extra))
            if not present:
                continue
            choices.append(present)
            weights.append(math.factorial(len(present)) * math.prod(parts[i][0] for i in present))
    total = sum(weights)
    pick = int(rng.integers(total)) if total < 2**63 else int(rng.random() * total)
    for present, weight in zip(choices, weights, strict=True):
        if pick < weight:
            return present
        pick -= weight
    return choices[-1]


def admits(node: Node, leaves: Sequence[Leaf]) -> bool:
    """True when ``leaves`` is one of the sequences ``node`` admits.

    >>> admits(ChainNode((ActionNode("a"), ActionNode("b", optional=True), ActionNode("c"))), [("a", 1), ("c", 1)])
    True
    """
    return Executions(HTN("", (node,))).accepts_leaves(leaves)


def internal_nodes(node: Node) -> Iterator[ChainNode | CliqueNode]:
    """Every chain and clique under ``node`` (itself included), outermost first."""
    if not isinstance(node, ActionNode):
        yield node
        for child in node.children:
            yield from internal_nodes(child)


def first_leaves(node: Node) -> frozenset[Leaf]:
    """Leaves that can be performed first in ``node`` (when it is performed)."""
    if isinstance(node, ActionNode):
        return frozenset((node.leaf,))
    if isinstance(node, ChainNode):
        out: frozenset[Leaf] = frozenset()
        for child in node.children:
            out |= first_leaves(child)
            if not nullable(child):
                break
        return out
    return frozenset().union(*(first_leaves(c) for c in node.children))


def last_leaves(node: Node) -> frozenset[Leaf]:
    """Leaves that can be performed last in ``node`` (when it is performed)."""
    if isinstance(node, ActionNode):
        return frozenset((node.leaf,))
    if isinstance(node, ChainNode):
        out: frozenset[Leaf] = frozenset()
        for child in reversed(node.children):
            out |= last_leaves(child)
            if not nullable(child):
                break
        return out
    return frozenset().union(*(last_leaves(c) for c in node.children))


def successor_pairs(node: Node) -> set[tuple[Leaf, Leaf]]:
    """Pairs ``(u, v)`` such that ``v`` immediately follows ``u`` in some sequence ``node`` admits: the
    transitions a flat (non-hierarchical) model of the task needs."""
    pairs: set[tuple[Leaf, Leaf]] = set()
    for inner in internal_nodes(node):
        children = inner.children
        links: list[tuple[Node, Node]] = []
        if isinstance(inner, ChainNode):
            for i, a in enumerate(children):
                for b in children[i + 1 :]:
                    links.append((a, b))
                    if not nullable(b):
                        break
        else:
            links = [(a, b) for a in children for b in children if a is not b]
        for a, b in links:
            pairs.update((u, v) for u in last_leaves(a) for v in first_leaves(b))
    return pairs


def allowed_next(node: Node, done: Iterable[Leaf]) -> frozenset[Leaf]:
    """Leaves that may be performed next, after the leaves in ``done`` (a valid prefix of one of ``node``'s
    sequences): nothing when ``node`` is finished. Optional nodes are treated as required here; for the
    executions of a structure with optional parts, use :class:`supportive.tasks.executions.Executions`.

    >>> task = ChainNode((ActionNode("knife"), CliqueNode((ActionNode("carrots"), ActionNode("celery")))))
    >>> sorted(a for a, _ in allowed_next(task, [("knife", 1)]))
    ['carrots', 'celery']

    Raises:
        TaskModelError: when ``done`` is not a valid prefix (a chain child started before the one ahead of it is
            finished, or two clique children both half done).
    """
    return _allowed(node, frozenset(done))


def _progress(node: Node, done: frozenset[Leaf]) -> int:
    """0: not started, 1: under way, 2: finished."""
    if isinstance(node, ActionNode):
        return 2 if node.leaf in done else 0
    if done.isdisjoint(node.leaves):
        return 0
    return 2 if done.issuperset(node.leaves) else 1


def _allowed(node: Node, done: frozenset[Leaf]) -> frozenset[Leaf]:
    if isinstance(node, ActionNode):
        return frozenset() if node.leaf in done else frozenset((node.leaf,))
    states = [_progress(child, done) for child in node.children]
    if isinstance(node, ChainNode):
        for i, state in enumerate(states):
            if state != 2:
                if any(later for later in states[i + 1 :]):
                    raise TaskModelError(
                        f"{node.name or 'chain'}: a later part is started before an earlier one ends"
                    )
                return _allowed(node.children[i], done)
        return frozenset()
    under_way = [child for child, state in zip(node.children, states, strict=True) if state == 1]
    if len(under_way) > 1:
        raise TaskModelError(f"{node.name or 'clique'}: two parts are under way at once")
    if under_way:
        return _allowed(under_way[0], done)
    fresh = [child for child, state in zip(node.children, states, strict=True) if state == 0]
    return frozenset().union(*(_allowed(child, done) for child in fresh))


def _required_under(node: Node) -> Iterator[Leaf]:
    """The leaves under ``node`` whose every node from ``node`` down is not optional."""
    if node.optional:
        return
    if isinstance(node, ActionNode):
        yield node.leaf
        return
    for child in node.children:
        yield from _required_under(child)


def node_count(node: Node) -> int:
    """Nodes in the tree under ``node``, leaves included."""
    if isinstance(node, ActionNode):
        return 1
    return 1 + sum(node_count(child) for child in node.children)


def node_edges(node: Node) -> int:
    """Transitions the tree under ``node`` needs to state its ordering, counted as §2.1.7.3 counts them.

    A chain of k children needs k − 1 (one between consecutive children; entering and leaving the chain is
    its parent's single edge, whatever the chain holds); a clique of k children needs k (one between each
    member and the clique node: any member may start or end it); a primitive needs none; an optional child
    adds the one edge that skips it. Summed over every chain and clique. So a clique of k primitives costs k
    against the flat model's k² − k (``len(successor_pairs(node))``), a chain of k primitives k − 1 against
    k − 1, and a transition into or out of a clique one edge instead of one per member.

    >>> a, b, c, d, e = (ActionNode(x) for x in "abcde")
    >>> node = ChainNode((a, CliqueNode((b, c, d)), e))
    >>> node_edges(node), len(successor_pairs(node))
    (5, 12)
    """
    if isinstance(node, ActionNode):
        return 0
    own = len(node.children) - 1 if isinstance(node, ChainNode) else len(node.children)
    skips = sum(child.optional for child in node.children)
    return own + skips + sum(node_edges(child) for child in node.children)


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
class HTN:
    """A learned (or given) Clique/Chain HTN.

    ``roots`` holds one node when the hierarchy is complete; otherwise the top-level nodes left when
    compaction stopped, in the order their members first occur, and ``top_level`` says in which orders they
    were seen. ``alternatives`` holds other complete hierarchies its learner offers, best first: the strict
    learner's (ambiguity resolution, §2.1.5.3) each admit only executions known to be valid; the general
    learner's admits every execution this one admits.
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

    @cached_property
    def required_leaves(self) -> tuple[Leaf, ...]:
        """The leaves every execution performs, root by root: none of their nodes optional, in a root every
        path of the top level performs (every root of a complete hierarchy or one without a top level)."""
        if self.top_level is None or len(self.roots) == 1:
            roots: Collection[int] = range(len(self.roots))
        else:
            roots = self.top_level.required_roots(len(self.roots))
        return tuple(leaf for i, root in enumerate(self.roots) if i in roots for leaf in _required_under(root))

    @cached_property
    def executions(self) -> Executions:
        """The executions this HTN admits, as a state machine (see :class:`~supportive.tasks.executions.Executions`)."""
        return Executions(self)

    def admits(self, actions: Sequence[str]) -> bool:
        """True when the HTN allows performing ``actions`` (action ids) in this order.

        Which performance of a repeated action a step is (which leg a ``pick_leg`` picks) is decided by
        the hierarchy, not by counting: the step may be any leaf of that action the hierarchy allows there.
        """
        return self.executions.accepts(actions)

    def admits_leaves(self, leaves: Sequence[Leaf]) -> bool:
        """True when the HTN allows this sequence of (action, occurrence) leaves."""
        return self.executions.accepts_leaves(leaves)

    def count_orderings(self) -> int:
        """How many leaf sequences this HTN's structure allows: its roots' orderings along every path of the
        top level (exact: a root that may be performed as nothing where a path passes it gives an order counted
        once, not once per path): the sequences :meth:`admits_leaves` accepts."""
        if self.top_level is None:
            return math.prod(count_orderings(root) for root in self.roots)
        free = self.top_level.free  # passing one silently gives an order a path without it gives already
        silent = [i for i, root in enumerate(self.roots) if nullable(root) and i not in free]
        return self.top_level.count_orderings([count_performed(root) for root in self.roots], silent)

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
