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

from supportive.learning.decomposition import Decomposition
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
        self._orders = self._child_orders()
        self.nodes: dict[int, Node] = {}
        self._shapes: dict[int, object] = {}
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

    def _child_orders(self) -> dict[int, list[list[int]]]:
        """Internal node id -> per demonstration, the indices of its children in the order performed."""
        groups = self.decomposition.groups
        parent: dict[int, tuple[int, int]] = {}
        for node, group in groups.items():
            for i, child in enumerate(group.children):
                parent[child] = (node, i)
        orders: dict[int, list[list[int]]] = {node: [] for node in groups}
        for sequence in self.decomposition.leaf_sequences:
            current: dict[int, list[int]] = {}
            for leaf in sequence:
                node = leaf
                while node in parent:
                    up, position = parent[node]
                    seen = current.setdefault(up, [])
                    if not seen or seen[-1] != position:
                        seen.append(position)
                    node = up
            for node, seen in current.items():
                orders[node].append(seen)
        return orders

    def _shape(self, node: int) -> object:
        """A node's shape by its actions, occurrences and optional flags left out (cached by id)."""
        cached = self._shapes.get(node)
        if cached is None:
            group = self.decomposition.groups.get(node)
            if group is None:
                cached = ("action", self.decomposition.leaves[node][0])
            else:
                parts = [self._shape(c) for c in group.children]
                cached = ("chain", tuple(parts)) if group.chain else ("clique", tuple(sorted(parts, key=repr)))
            self._shapes[node] = cached
        return cached

    def _classes(self, children: Sequence[int]) -> list[int]:
        """For each child, the index of the first child of its shape (instances of one subtask share it)."""
        first: dict[object, int] = {}
        return [first.setdefault(self._shape(child), i) for i, child in enumerate(children)]

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
            orders = self._orders.get(node, [])
            seen = len({tuple(kinds[i] for i in o) for o in orders})
            if group.chain:
                counts = Counts(performed=len(performed), skipped=skipped)
                level: Node = ChainNode(tuple(ActionNode(str(i), optional=c.optional) for i, c in enumerate(children)))
            else:
                counts = _choice_counts(orders, len(children), len(performed), skipped)
                level = CliqueNode(tuple(ActionNode(str(i), optional=c.optional) for i, c in enumerate(children)))
            admitted = count_orderings(level) - int(all(c.optional for c in children))
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


def _choice_counts(orders: Sequence[Sequence[int]], size: int, performed: int, skipped: int) -> Counts:
    first = [0] * size
    after = [[0] * size for _ in range(size)]
    for order in orders:
        if order:
            first[order[0]] += 1
        for a, b in itertools.pairwise(order):
            after[a][b] += 1
    return Counts(
        performed=performed, skipped=skipped, first=tuple(first), after=tuple(tuple(row) for row in after)
    )
