"""Turn what the ``general`` learner decomposed into HTN nodes: optional flags, counts and support.

A node is **optional** when some demonstration performs its parent (or, for a root, any part of the task) but
none of its leaves. Every node counts in how many demonstrations it was performed and, when optional, skipped;
a clique (and the top level) also counts which child came first and which child followed which, the
frequencies a next-step predictor needs (:class:`~supportive.tasks.htn.Counts`). Every node says what its
structure rests on (:class:`~supportive.tasks.htn.Support`): how many demonstrations show it, how many of the
orders of its children it admits were seen, and so whether it was observed in full or inferred.
"""

from __future__ import annotations

import abc
import dataclasses
import itertools
import math
from collections import Counter, defaultdict
from collections.abc import Iterable, Mapping, Sequence

import numpy as np
import numpy.typing as npt

from supportive.learning.general.decomposition import Decomposition, Group, Shapes
from supportive.learning.general.evidence import IntMatrix, positions_of
from supportive.tasks.htn import (
    ActionNode,
    ChainNode,
    CliqueNode,
    Counts,
    Node,
    Support,
    shape,
    with_children,
)

__all__ = ["Annotated", "admitted_orders", "annotate"]

_ABSENT = np.iinfo(np.int64).max
"""The first position of a node a demonstration does not perform (after any other)."""


class Annotated:
    """HTN nodes for every id of a :class:`Decomposition`, and the counts of its top level.

    Args:
        decomposition: What :func:`~supportive.learning.general.decomposition.decompose` found.
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
        shape = Shapes(decomposition.leaves, decomposition.groups)
        self._kinds = {  # for each child, the index of the first child of its shape (instances share it)
            node: _first_alike([shape(child) for child in decomposition.groups[node].children])
            for node in self._performed
            if node in decomposition.groups
        }
        self._orders = _child_orders(decomposition, self._kinds)
        self.nodes: dict[int, Node] = {}
        self._leaves: dict[tuple[int, int], tuple[Counts, Support]] = {}
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

    def _leaf_evidence(self, performed: int, skipped: int) -> tuple[Counts, Support]:
        """A leaf's counts and support (made once for each pair of numbers and shared: they are frozen)."""
        key = (performed, skipped)
        found = self._leaves.get(key)
        if found is None:
            found = self._leaves[key] = (Counts(performed=performed, skipped=skipped), Support(performed, 1, 1, True))
        return found

    def _node(self, node: int, parent_performed: frozenset[int]) -> Node:
        performed = self._performed[node]
        optional = not parent_performed <= performed
        group = self.decomposition.groups.get(node)
        skipped = len(parent_performed - performed)
        if group is None:
            action, instance = self.decomposition.leaves[node]
            counts, support = self._leaf_evidence(len(performed), skipped)
            out: Node = ActionNode(action, instance, optional=optional, counts=counts, support=support)
        else:
            kinds = self._kinds[node]  # interchangeable instances make one order
            children = tuple(self._node(child, performed) for child in group.children)
            if len(set(kinds)) < len(kinds):
                children = _instances_alike(children)
            seen = self._orders.seen[node]
            if group.chain:
                counts = Counts(performed=len(performed), skipped=skipped)
            else:
                counts = self._orders.counts(node, len(performed), skipped)
            admitted = admitted_orders(group.chain, sum(c.optional for c in children), len(children))
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


def admitted_orders(chain: bool, optional: int, children: int) -> int:
    """The non-empty orders a chain (or clique) of ``children`` children, ``optional`` of them optional and
    each performed as one step, admits: each subset of the optional children performed, in the one order (a
    chain) or in any order (a clique).

    >>> admitted_orders(False, 1, 3)  # a, b and maybe c, in any order: 2 + 6
    8
    """
    required = children - optional
    if chain:
        total = 1 << optional
    else:
        total = sum(math.comb(optional, k) * math.factorial(required + k) for k in range(optional + 1))
    return total - int(required == 0)


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


def _first_alike(keys: Sequence[int]) -> list[int]:
    """For each key, the index of its first occurrence."""
    first: dict[int, int] = {}
    return [first.setdefault(key, i) for i, key in enumerate(keys)]


class _ChildOrders(abc.ABC):
    """How the demonstrations order each node's children: how many distinct orders (instances of one subtask
    alike) and, as :class:`~supportive.tasks.htn.Counts` hold them, which child came first and which followed
    which. Computed for all nodes at once.

    The orders are those a walk from every leaf up through its parents reads (every node's leaves are
    performed contiguously, so a child is met once per demonstration). A node's parent on that walk is the
    last group in ``groups`` that lists it: a group left behind by splicing or folding may list it too, and
    then the node counts for that group only.

    Two forms answer alike: :class:`_MatrixOrders` (all demonstrations at once) and :class:`_ListOrders` (one
    demonstration at a time, for few short ones); :func:`_child_orders` picks one.

    Attributes:
        seen: Node -> how many distinct orders of its children the demonstrations show.
    """

    seen: dict[int, int]

    @abc.abstractmethod
    def counts(self, node: int, performed: int, skipped: int) -> Counts:
        """A clique's counts: performed and skipped as given, and which child came first and which followed
        which."""


_SMALL_ORDERS = 256
"""Up to this many leaf performances (demonstrations times the steps of the longest), the child orders are
read one demonstration at a time (:class:`_ListOrders`), from there on as matrices (:class:`_MatrixOrders`):
only the speed depends on it. Numpy's cost per call outweighs its speed per entry on a few dozen entries: on
generated tasks with 4 demonstrations, 40 entries take 32 µs one demonstration at a time and 142 µs as
matrices, 240 take about 150 µs either way, 400 take 294 µs and 257 µs."""


def _child_orders(decomposition: Decomposition, kinds: Mapping[int, Sequence[int]]) -> _ChildOrders:
    """The child orders of the nodes of ``kinds`` (for each, per child, the index of the first child of its
    shape), in the form that suits the demonstrations' size (:data:`_SMALL_ORDERS`)."""
    owned = _owned_children(decomposition.groups, kinds)
    sequences = decomposition.leaf_sequences
    if len(sequences) * max(map(len, sequences), default=0) <= _SMALL_ORDERS:
        return _ListOrders(decomposition, kinds, owned)
    return _MatrixOrders(decomposition, kinds, owned)


def _owned_children(groups: Mapping[int, Group], nodes: Iterable[int]) -> dict[int, list[int]]:
    """For each of ``nodes``, the indices of the children it is the parent of on the walks (see
    :class:`_ChildOrders`)."""
    owner: dict[int, tuple[int, int]] = {}
    for node, group in groups.items():
        for i, child in enumerate(group.children):
            owner[child] = (node, i)
    return {node: [i for i, c in enumerate(groups[node].children) if owner[c] == (node, i)] for node in nodes}


class _ListOrders(_ChildOrders):
    """:class:`_ChildOrders` read one demonstration at a time."""

    def __init__(
        self, decomposition: Decomposition, kinds: Mapping[int, Sequence[int]], owned: Mapping[int, list[int]]
    ) -> None:
        groups = decomposition.groups
        below = {node: [groups[node].children[i] for i in owned[node]] for node in kinds}
        upward = [node for level in _heights(below) for node in level]
        firsts: list[dict[int, int]] = []  # per demonstration, node -> where it starts
        for sequence in decomposition.leaf_sequences:
            first = {leaf: k for k, leaf in enumerate(sequence)}
            for node in upward:
                starts = [first[c] for c in below[node] if c in first]
                if starts:
                    first[node] = min(starts)
            firsts.append(first)
        self.seen = {}
        self._choices: dict[int, tuple[tuple[int, ...], tuple[tuple[int, ...], ...]]] = {}
        for node in kinds:
            children = list(zip(owned[node], below[node], strict=True))
            if groups[node].chain:
                done = [sum(map(first.__contains__, below[node])) for first in firsts]
                if all(k in (0, len(children)) for k in done):  # a simple chain: its order or nothing
                    self.seen[node] = int(any(done))
                    continue
            size = len(groups[node].children)
            came_first = [0] * size
            after = [[0] * size for _ in range(size)]
            orders: set[tuple[int, ...]] = set()
            for first in firsts:
                order = [i for _, i in sorted((first[c], i) for i, c in children if c in first)]
                if order:
                    came_first[order[0]] += 1
                    for a, b in itertools.pairwise(order):
                        after[a][b] += 1
                    orders.add(tuple(kinds[node][i] for i in order))
            self.seen[node] = len(orders)
            self._choices[node] = (tuple(came_first), tuple(map(tuple, after)))

    def counts(self, node: int, performed: int, skipped: int) -> Counts:
        """See :meth:`_ChildOrders.counts`."""
        first, after = self._choices[node]
        return Counts(performed=performed, skipped=skipped, first=first, after=after)


class _MatrixOrders(_ChildOrders):
    """:class:`_ChildOrders` read from all demonstrations at once, as matrices."""

    def __init__(
        self, decomposition: Decomposition, kinds: Mapping[int, Sequence[int]], owned: Mapping[int, list[int]]
    ) -> None:
        groups = decomposition.groups
        below = {node: [groups[node].children[i] for i in owned[node]] for node in kinds}
        first = _first_positions(decomposition, below)
        self.seen = _simple_chains(first, {node: below[node] for node in kinds if groups[node].chain})
        nodes = [node for node in kinds if node not in self.seen]
        self._sizes = np.array([len(groups[node].children) for node in nodes], dtype=np.int64)
        self._offsets = np.cumsum(self._sizes) - self._sizes
        self._squares = np.cumsum(self._sizes**2) - self._sizes**2
        self._place = {node: i for i, node in enumerate(nodes)}
        node_of = np.repeat(np.arange(len(nodes)), [len(owned[node]) for node in nodes])
        index = np.array([i for node in nodes for i in owned[node]], dtype=np.int64)
        kind = np.array([kinds[node][i] for node in nodes for i in owned[node]], dtype=np.int64)
        where = first[:, [c for node in nodes for c in below[node]]]
        demo, entry = np.nonzero(where != _ABSENT)
        ranked = np.lexsort((where[demo, entry], demo, node_of[entry]))  # by node, demonstration, position
        demo, entry = demo[ranked], entry[ranked]
        parent = node_of[entry]
        starts = np.ones(len(entry), dtype=bool)  # where one node's order in one demonstration starts
        starts[1:] = (parent[1:] != parent[:-1]) | (demo[1:] != demo[:-1])
        self._first = np.bincount(self._offsets[parent[starts]] + index[entry[starts]], minlength=int(self._sizes.sum()))
        within = ~starts[1:]
        following = parent[1:][within]
        pairs = self._squares[following] + index[entry[:-1][within]] * self._sizes[following] + index[entry[1:][within]]
        self._after = np.bincount(pairs, minlength=int((self._sizes**2).sum()))
        self.seen.update(zip(nodes, _distinct_runs(parent, starts, kind[entry], len(nodes)).tolist(), strict=True))

    def counts(self, node: int, performed: int, skipped: int) -> Counts:
        """See :meth:`_ChildOrders.counts`."""
        place = self._place[node]
        size = int(self._sizes[place])
        first = self._first[self._offsets[place] : self._offsets[place] + size]
        after = self._after[self._squares[place] : self._squares[place] + size * size].reshape(size, size)
        return Counts(
            performed=performed,
            skipped=skipped,
            first=tuple(first.tolist()),
            after=tuple(tuple(row) for row in after.tolist()),
        )


def _simple_chains(first: IntMatrix, chains: Mapping[int, Sequence[int]]) -> dict[int, int]:
    """Chain -> the orders of its children shown (0 or 1), for the chains whose children (``chains``: those
    it is the parent of) every demonstration performs all or none of: they come in the chain's order."""
    nonempty = [node for node, children in chains.items() if children]
    out = {node: 0 for node, children in chains.items() if not children}
    if nonempty:
        sizes = np.array([len(chains[node]) for node in nonempty], dtype=np.int64)
        present = first[:, [c for node in nonempty for c in chains[node]]] != _ABSENT
        performed = np.add.reduceat(present, np.cumsum(sizes) - sizes, axis=1)
        simple: list[bool] = np.all((performed == 0) | (performed == sizes), axis=0).tolist()
        shown: list[bool] = np.any(performed > 0, axis=0).tolist()
        out.update((node, int(one)) for node, one, alike in zip(nonempty, shown, simple, strict=True) if alike)
    return out


def _distinct_runs(node: IntMatrix, starts: npt.NDArray[np.bool_], kind: IntMatrix, nodes: int) -> IntMatrix:
    """Per node (``0 … nodes-1``), how many distinct sequences of ``kind`` its runs hold; a run is the
    entries from one start to the next, all of one node."""
    begin = np.flatnonzero(starts)
    length = np.diff(np.append(begin, len(starts)))
    distinct = np.zeros(nodes, dtype=np.int64)
    for size in np.unique(length).tolist():  # runs of different lengths differ
        chosen = begin[length == size]
        rows = kind[chosen[:, None] + np.arange(size)]
        owner = node[chosen]
        order = np.lexsort((*rows.T[::-1], owner))
        rows, owner = rows[order], owner[order]
        new = np.ones(len(owner), dtype=bool)
        new[1:] = (owner[1:] != owner[:-1]) | (rows[1:] != rows[:-1]).any(axis=1)
        distinct += np.bincount(owner[new], minlength=nodes)
    return distinct


def _first_positions(decomposition: Decomposition, below: Mapping[int, Sequence[int]]) -> IntMatrix:
    """``first[d, n]``: where demonstration ``d`` starts node ``n`` on the walks (:data:`_ABSENT` when it never
    does), for the leaves and the nodes of ``below`` (node -> the children it is the parent of)."""
    size = max([*decomposition.groups, len(decomposition.leaves) - 1]) + 1
    first = positions_of(decomposition.leaf_nodes, size, _ABSENT)
    for parents in _heights(below):
        starts = np.cumsum([0, *(len(below[p]) for p in parents[:-1])])
        first[:, parents] = np.minimum.reduceat(first[:, [c for p in parents for c in below[p]]], starts, axis=1)
    return first


def _heights(below: Mapping[int, Sequence[int]]) -> list[list[int]]:
    """The nodes of ``below`` (node -> the children it is the parent of) that have children there, by height:
    the k-th list holds those whose longest path down to a node without children has k + 1 steps."""
    height: dict[int, int] = {}

    def visit(node: int) -> int:
        if node not in below:
            return 0
        if node not in height:
            height[node] = 1 + max(map(visit, below[node]), default=-1)
        return height[node]

    levels: list[list[int]] = [[] for _ in range(max(map(visit, below), default=0))]
    for node, h in height.items():
        if h > 0:
            levels[h - 1].append(node)
    return levels
