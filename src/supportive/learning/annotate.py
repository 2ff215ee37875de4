"""Turn what the ``general`` learner decomposed into HTN nodes: optional flags, counts and support.

A node is **optional** when some demonstration performs its parent (or, for a root, any part of the task) but
none of its leaves. Every node counts in how many demonstrations it was performed and, when optional, skipped;
a clique (and the top level) also counts which child came first and which child followed which, the
frequencies a next-step predictor needs (:class:`~supportive.tasks.htn.Counts`). Every node says what its
structure rests on (:class:`~supportive.tasks.htn.Support`): how many demonstrations show it, how many of the
orders of its children it admits were seen, and so whether it was observed in full or inferred.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections import Counter, defaultdict
from collections.abc import Mapping, Sequence

import numpy as np

from supportive.learning.decomposition import Decomposition, Group, Shapes
from supportive.learning.evidence import IntMatrix, as_matrix
from supportive.tasks.htn import (
    ActionNode,
    ChainNode,
    CliqueNode,
    Counts,
    Node,
    Support,
    count_orderings,
    shape,
    with_children,
)

__all__ = ["Annotated", "annotate"]

_ABSENT = np.iinfo(np.int64).max
"""The first position of a node a demonstration does not perform (after any other)."""


class Annotated:
    """HTN nodes for every id of a :class:`Decomposition`, and the counts of its top level.

    Args:
        decomposition: What :func:`~supportive.learning.decomposition.decompose` found.
        excused: Node id -> demonstrations in which it was set aside as a deviation; they count as performing
            it, so a step someone slipped on does not become optional.
        demonstrations: How many demonstrations there were.
    """

    def __init__(
        self, decomposition: Decomposition, excused: Mapping[int, frozenset[int]], demonstrations: int
    ) -> None:
        self.decomposition = decomposition
        self.demonstrations = demonstrations
        self._performed = self._performances(excused)
        self._orders = _ChildOrders(decomposition)
        self._shape = Shapes(decomposition.leaves, decomposition.groups)
        self._admitted: dict[tuple[bool, tuple[bool, ...]], int] = {}
        self.nodes: dict[int, Node] = {}
        for root in decomposition.roots:
            self._node(root, frozenset(range(demonstrations)))

    def root_nodes(self) -> tuple[Node, ...]:
        """The roots as HTN nodes, in order."""
        return tuple(self.nodes[r] for r in self.decomposition.roots)

    def top_counts(self) -> Counts:
        """Which root came first and which followed which, over the demonstrations."""
        roots = self.decomposition.roots
        index = {root: i for i, root in enumerate(roots)}
        sequences = [[index[r] for r in s] for s in self.decomposition.sequences]
        return _choice_counts(sequences, len(roots), self.demonstrations, 0)

    # ------------------------------------------------------------------ building
    def _performances(self, excused: Mapping[int, frozenset[int]]) -> dict[int, frozenset[int]]:
        presence = dict(self.decomposition.presence)
        for node, demos in excused.items():
            presence[node] = presence.get(node, frozenset()) | demos
        performed: dict[int, frozenset[int]] = {}

        def visit(node: int) -> frozenset[int]:
            group = self.decomposition.groups.get(node)
            if group is None:
                out = presence.get(node, frozenset())
            else:
                out = frozenset().union(*(visit(child) for child in group.children))
            performed[node] = out
            return out

        for root in self.decomposition.roots:
            visit(root)
        return performed

    def _classes(self, children: Sequence[int]) -> list[int]:
        """For each child, the index of the first child of its shape (instances of one subtask share it)."""
        first: dict[int, int] = {}
        return [first.setdefault(self._shape(child), i) for i, child in enumerate(children)]

    def _orders_seen(self, node: int, group: Group, kinds: list[int]) -> int:
        """How many orders of its children (instances of one subtask alike) the demonstrations show; a chain
        whose every child is performed wherever it is shows its one order."""
        presence = self.decomposition.presence
        if (
            group.chain
            and self._orders.whole(node)
            and all(presence[child] == presence[node] for child in group.children)
        ):
            return 1
        classes = [*kinds, -1]  # -1 (not performed) stays -1
        return len({tuple(classes[i] for i in order) for order in self._orders(node).tolist()})

    def _admitted_orders(self, chain: bool, optional: tuple[bool, ...]) -> int:
        """Orders of children with these optional flags a chain (or clique) admits, performing any."""
        key = (chain, optional)
        if key not in self._admitted:
            children = tuple(ActionNode(str(i), optional=flag) for i, flag in enumerate(optional))
            level: Node = ChainNode(children) if chain else CliqueNode(children)
            self._admitted[key] = count_orderings(level) - int(all(optional))
        return self._admitted[key]

    def _node(self, node: int, parent_performed: frozenset[int]) -> Node:
        performed = self._performed[node]
        optional = not parent_performed <= performed
        group = self.decomposition.groups.get(node)
        skipped = len(parent_performed - performed)
        if group is None:
            action, instance = self.decomposition.leaves[node]
            out: Node = ActionNode(
                action,
                instance,
                optional=optional,
                counts=Counts(performed=len(performed), skipped=skipped),
                support=Support(len(performed), 1, 1, True),
            )
        else:
            kinds = self._classes(group.children)  # interchangeable instances make one order
            children = tuple(self._node(child, performed) for child in group.children)
            if len(set(kinds)) < len(kinds):
                children = _instances_alike(children)
            seen = self._orders_seen(node, group, kinds)
            if group.chain:
                counts = Counts(performed=len(performed), skipped=skipped)
            else:
                counts = _choice_counts(self._orders(node), len(children), len(performed), skipped)
            admitted = self._admitted_orders(group.chain, tuple(c.optional for c in children))
            if not group.chain:
                admitted //= math.prod(math.factorial(n) for n in Counter(kinds).values())
            support = Support(len(performed), seen, admitted, seen >= admitted)
            kind = ChainNode if group.chain else CliqueNode
            out = kind(children, optional=optional, counts=counts, support=support)
        self.nodes[node] = out
        return out


def annotate(
    decomposition: Decomposition, excused: Mapping[int, frozenset[int]], demonstrations: int
) -> Annotated:
    """Build the HTN nodes of ``decomposition`` (see :class:`Annotated`)."""
    return Annotated(decomposition, excused, demonstrations)


def _instances_alike(children: tuple[Node, ...]) -> tuple[Node, ...]:
    """Siblings that are instances of one subtask (the same shape but for occurrences and optional flags)
    made alike: a step one instance may skip, every instance may (whoever skipped it, the subtask is one)."""
    classes: dict[object, list[int]] = defaultdict(list)
    for i, child in enumerate(children):
        classes[shape(child, optional=False)].append(i)
    out = list(children)
    for members in classes.values():
        if len(members) > 1:
            for i, node in zip(members, _merged_flags([children[i] for i in members]), strict=True):
                out[i] = node
    return tuple(out)


def _merged_flags(nodes: list[Node]) -> list[Node]:
    """Copies of same-shaped ``nodes`` in which each part is optional when it is in any of them."""
    optional = any(node.optional for node in nodes)
    if isinstance(nodes[0], ActionNode):
        return [dataclasses.replace(node, optional=optional) for node in nodes]
    orders = [_aligned(node) for node in nodes]
    merged_at = [_merged_flags([node.children[order[k]] for node, order in zip(nodes, orders, strict=True)])  # type: ignore[union-attr]
                 for k in range(len(orders[0]))]
    out: list[Node] = []
    for n, (node, order) in enumerate(zip(nodes, orders, strict=True)):
        children = list(node.children)  # type: ignore[union-attr]
        for k, position in enumerate(order):
            children[position] = merged_at[k][n]
        out.append(with_children(node, children, optional=optional))  # type: ignore[arg-type]
    return out


def _aligned(node: Node) -> list[int]:
    """Positions of ``node``'s children in an order that pairs the parts of same-shaped nodes."""
    if isinstance(node, ChainNode):
        return list(range(len(node.children)))
    assert not isinstance(node, ActionNode)
    return sorted(range(len(node.children)), key=lambda i: repr(shape(node.children[i], optional=False)))


def _choice_counts(orders: Sequence[Sequence[int]] | IntMatrix, size: int, performed: int, skipped: int) -> Counts:
    """Which child came first and which followed which: ``orders`` holds, per demonstration, the children
    in the order performed (a matrix row may end in -1s)."""
    matrix = orders if isinstance(orders, np.ndarray) else as_matrix(orders)
    starts = matrix[:, :1]
    first = np.bincount(starts[starts >= 0], minlength=size)
    later = matrix[:, 1:] >= 0
    after = np.bincount(matrix[:, :-1][later] * size + matrix[:, 1:][later], minlength=size * size)
    return Counts(
        performed=performed,
        skipped=skipped,
        first=tuple(first.tolist()),
        after=tuple(tuple(row) for row in after.reshape(size, size).tolist()),
    )


class _ChildOrders:
    """The orders in which the demonstrations perform each node's children, read as a walk from every leaf
    up through its parents reads them (every node's leaves are performed contiguously, so a child is met once
    per demonstration). A node's parent on that walk is the last group in ``groups`` that lists it: a group
    left behind by splicing or folding may list it too, and then the node counts for that group only.

    Args:
        decomposition: What :func:`~supportive.learning.decomposition.decompose` found.
    """

    def __init__(self, decomposition: Decomposition) -> None:
        owner: dict[int, tuple[int, int]] = {}
        for node, group in decomposition.groups.items():
            for i, child in enumerate(group.children):
                owner[child] = (node, i)
        self._owned = {
            node: [i for i, child in enumerate(group.children) if owner[child] == (node, i)]
            for node, group in decomposition.groups.items()
        }
        self._groups = decomposition.groups
        self._whole: dict[int, bool] = {}
        self._first = self._first_positions(decomposition)

    def __call__(self, node: int) -> IntMatrix:
        """Per demonstration performing any child of ``node`` (in order), the indices of the children it
        performs in the order performed, -1 after them."""
        owned = self._owned[node]
        children = self._groups[node].children
        first = self._first[:, [children[i] for i in owned]]
        absent = first == _ABSENT
        performing = ~absent.all(axis=1)
        first, absent = first[performing], absent[performing]
        order = np.argsort(first, axis=1, kind="stable")
        index = np.append(np.asarray(owned, dtype=np.int64), -1)  # -1 (not performed) stays -1
        out: IntMatrix = index[np.where(np.take_along_axis(absent, order, axis=1), -1, order)]
        return out

    def whole(self, node: int) -> bool:
        """True when every node under ``node`` has it as its parent on the walk (its orders are read from all
        its leaves)."""
        found = self._whole.get(node)
        if found is None:
            group = self._groups.get(node)
            found = group is None or (
                len(self._owned[node]) == len(group.children) and all(self.whole(c) for c in group.children)
            )
            self._whole[node] = found
        return found

    def _first_positions(self, decomposition: Decomposition) -> IntMatrix:
        """``first[d, n]``: where demonstration ``d`` first meets node ``n`` on the walks (:data:`_ABSENT`
        when it never does), lowest nodes first."""
        size = max([*decomposition.groups, len(decomposition.leaves) - 1]) + 1
        first = np.full((len(decomposition.leaf_sequences), size), _ABSENT, dtype=np.int64)
        nodes = as_matrix(decomposition.leaf_sequences)
        rows, columns = np.nonzero(nodes >= 0)
        first[rows, nodes[rows, columns]] = columns
        for parents in self._by_height():
            children = [[self._groups[p].children[i] for i in self._owned[p]] for p in parents]
            starts = np.cumsum([0, *(len(c) for c in children[:-1])])
            below = first[:, list(itertools.chain.from_iterable(children))]
            first[:, parents] = np.minimum.reduceat(below, starts, axis=1)
        return first

    def _by_height(self) -> list[list[int]]:
        """The groups that are parents on the walks, by height (those over leaves only first)."""
        height: dict[int, int] = {}

        def visit(node: int) -> int:
            if node not in self._groups:
                return 0
            if node not in height:
                height[node] = 1 + max((visit(self._groups[node].children[i]) for i in self._owned[node]), default=-1)
            return height[node]

        for node in self._groups:
            visit(node)
        levels: list[list[int]] = [[] for _ in range(max(height.values(), default=0))]
        for node, h in height.items():
            if h > 0:
                levels[h - 1].append(node)
        return levels
