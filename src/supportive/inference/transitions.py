"""How probability mass moves between subgoals from one moment to the next, flat or through the hierarchy.

Both models share the same picture of a teammate: they keep working on the current subgoal for a while, then
finish it and start another; when the task ends they start it again. They differ in which subgoal comes next.

* **Flat** (a traditional HMM over subgoals): the next subgoal is drawn uniformly from the subgoals that may
  immediately follow the current one in some valid execution (the task model's valid transitions), or, where the
  task may end, from a fresh start. Its transition matrix is dense, as in any textbook HMM.
* **Hierarchical** (assembled from the CC-HTN, §2.1.7.1): finishing a subgoal finishes its place in its parent.
  In a chain the next child starts; in a clique of k children another child starts (each with probability 1/k)
  or, with probability 1/k, the clique itself is done and its own parent decides; a partial hierarchy's roots
  follow one another as the learned top level allows. Starting a node starts its first child (chain) or any
  child (clique). Mass therefore flows up the tree to where the next step is decided and back down to leaves:
  three sparse products whose size grows with leaves × depth, not with the square of a clique's size.

Both operators map the mass leaving each subgoal (a vector over leaves) to the mass arriving at each subgoal.
"""

from __future__ import annotations

import itertools
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    Node,
    first_leaves,
    internal_nodes,
    last_leaves,
)

if TYPE_CHECKING:
    from scipy import sparse

__all__ = ["DENSE_BELOW", "FlatTransitions", "HierarchicalTransitions", "TaskLayout", "sparse_matrix"]

DENSE_BELOW = 128
"""Up to this many subgoals the hierarchical operator is compiled into one dense matrix."""


@dataclass(frozen=True)
class TaskLayout:
    """Leaves and internal nodes of an HTN, numbered, with where the task may start and end."""

    leaves: tuple[Leaf, ...]
    nodes: tuple[ChainNode | CliqueNode, ...]
    parent_of_leaf: np.ndarray
    membership: sparse.csr_matrix
    start_roots: tuple[int, ...]
    end_roots: tuple[int, ...]
    root_successors: tuple[tuple[int, ...], ...]

    @classmethod
    def of(cls, htn: HTN) -> TaskLayout:
        """Number ``htn``'s leaves (in :attr:`HTN.leaves` order) and internal nodes (outermost first)."""
        leaves = htn.leaves
        leaf_index = {leaf: i for i, leaf in enumerate(leaves)}
        nodes = tuple(n for root in htn.roots for n in internal_nodes(root))
        rows, cols = [], []
        parent = np.full(len(leaves), -1, dtype=np.intp)
        for j, node in enumerate(nodes):
            for leaf in node.leaves:
                rows.append(j)
                cols.append(leaf_index[leaf])
            for child in node.children:
                if isinstance(child, ActionNode):
                    parent[leaf_index[child.leaf]] = j
        membership = sparse_matrix([(r, c, 1.0) for r, c in zip(rows, cols, strict=True)], len(nodes), len(leaves))
        n_roots = len(htn.roots)
        starts: tuple[int, ...]
        ends: tuple[int, ...]
        successors: tuple[tuple[int, ...], ...]
        if htn.top_level is None:
            starts, ends, successors = (0,), (0,), ((),)
        else:
            top = htn.top_level
            leaving: dict[int, set[int]] = defaultdict(set)
            for src, root, _ in top.edges:
                leaving[src].add(root)
            follow: list[set[int]] = [set() for _ in range(n_roots)]
            for _, root, dst in top.edges:
                follow[root] |= leaving.get(dst, set())
            starts = tuple(sorted({r for src, r, _ in top.edges if src in top.initial}))
            ends = tuple(sorted({r for _, r, dst in top.edges if dst in top.terminal}))
            successors = tuple(tuple(sorted(f)) for f in follow)
        return cls(leaves, nodes, parent, membership, starts, ends, successors)

    @property
    def n_leaves(self) -> int:
        """Number of subgoals."""
        return len(self.leaves)


class FlatTransitions:
    """Dense subgoal-to-subgoal transition matrix: uniform over each subgoal's valid successors."""

    def __init__(self, htn: HTN, layout: TaskLayout) -> None:
        index = {leaf: i for i, leaf in enumerate(layout.leaves)}
        n = layout.n_leaves
        successors: list[set[int]] = [set() for _ in range(n)]
        for before, after in htn.successor_pairs():
            successors[index[before]].add(index[after])
        starts = sorted({index[leaf] for r in layout.start_roots for leaf in first_leaves(htn.roots[r])})
        can_end = {index[leaf] for r in layout.end_roots for leaf in last_leaves(htn.roots[r])}
        matrix = np.zeros((n, n))
        for u in range(n):
            choices = len(successors[u]) + (u in can_end)
            for v in successors[u]:
                matrix[u, v] += 1.0 / choices
            if u in can_end:
                matrix[u, starts] += 1.0 / choices / len(starts)
        self.matrix = matrix
        self.start = np.zeros(n)
        self.start[starts] = 1.0 / len(starts)
        self.nonzeros = int(np.count_nonzero(matrix))

    def __call__(self, leaving: np.ndarray) -> np.ndarray:
        """Mass arriving at each subgoal, given the mass leaving each."""
        arriving: np.ndarray = leaving @ self.matrix
        return arriving


class HierarchicalTransitions:
    """The same moves routed through the HTN: finish masses up, sibling moves, start masses down."""

    def __init__(self, htn: HTN, layout: TaskLayout) -> None:
        n, m = layout.n_leaves, len(layout.nodes)
        top = n + m  # the task itself: a virtual node above the roots
        leaf_index = {leaf: i for i, leaf in enumerate(layout.leaves)}
        node_index = {id(node): n + j for j, node in enumerate(layout.nodes)}

        def index_of(node: Node) -> int:
            return leaf_index[node.leaf] if isinstance(node, ActionNode) else node_index[id(node)]

        parent = np.full(top + 1, -1, dtype=np.intp)
        end = np.zeros(top + 1)  # P(finishing this node also finishes its parent)
        enter = np.zeros(top + 1)  # P(starting the parent starts this child)
        moves: list[tuple[int, int, float]] = []  # (to child, from node's finish, weight)
        for node in layout.nodes:
            me = node_index[id(node)]
            kids = [index_of(c) for c in node.children]
            k = len(kids)
            parent[kids] = me
            if isinstance(node, ChainNode):
                end[kids[-1]] = 1.0
                enter[kids[0]] = 1.0
                moves += [(b, a, 1.0) for a, b in itertools.pairwise(kids)]
            else:
                end[kids] = 1.0 / k
                enter[kids] = 1.0 / k
                # another child starts: (sum of siblings' finishes) / k = parent's finish - own finish / k
                moves += [(c, me, 1.0) for c in kids] + [(c, c, -1.0 / k) for c in kids]
        roots = [index_of(r) for r in htn.roots]
        parent[roots] = top
        for r, root in enumerate(roots):
            choices = len(layout.root_successors[r]) + (r in layout.end_roots)
            end[root] = (1.0 / choices) if r in layout.end_roots else 0.0
            moves += [(roots[s], root, 1.0 / choices) for s in layout.root_successors[r]]
        for r in layout.start_roots:  # the task ends and starts again
            moves.append((roots[r], top, 1.0 / len(layout.start_roots)))
        up = _paths(n, top + 1, parent, end, upward=True)
        across = sparse_matrix(moves, top + 1, top + 1)
        down = _paths(n, top + 1, parent, enter, upward=False)
        self.start = np.asarray(down @ across[:, top].toarray()).ravel()
        # The same numbers three ways; use the cheapest. Three sparse products (big cliques), their product
        # compiled into one sparse matrix (small cliques), or, for small tasks, one dense matrix (a dense
        # product of that size costs less than a sparse product's overhead).
        compiled = (down @ across @ up).tocsr()
        compiled.data[np.abs(compiled.data) < 1e-15] = 0.0
        compiled.eliminate_zeros()
        factored = (down, across, up)
        self.nonzeros = min(compiled.nnz, sum(f.nnz for f in factored))
        self.factors: tuple[Any, ...]
        if n <= DENSE_BELOW:
            self.factors = (compiled.toarray(),)
        elif sum(f.nnz for f in factored) < compiled.nnz:
            self.factors = factored
        else:
            self.factors = (compiled,)

    def __call__(self, leaving: np.ndarray) -> np.ndarray:
        """Mass arriving at each subgoal, given the mass leaving each."""
        for factor in reversed(self.factors):
            leaving = factor @ leaving
        if len(self.factors) == 1:
            return np.asarray(leaving)
        arriving: np.ndarray = np.maximum(leaving, 0.0)  # the clique shortcut subtracts; clip rounding
        return arriving  # the clique shortcut subtracts; clip rounding below zero


def _paths(n: int, size: int, parent: np.ndarray, weight: np.ndarray, *, upward: bool) -> sparse.csr_matrix:
    """Products of ``weight`` along each leaf's path to its ancestors.

    ``upward``: (size × n) matrix taking leaf finishes to every node's finish. Otherwise (n × size): every
    node's start mass to the leaves it starts.
    """
    rows, cols, values = [], [], []
    for leaf in range(n):
        node, product = leaf, 1.0
        while node >= 0 and product > 0.0:
            rows.append(node)
            cols.append(leaf)
            values.append(product)
            product *= weight[node]
            node = parent[node]
    if upward:
        return sparse_matrix(list(zip(rows, cols, values, strict=True)), size, n)
    return sparse_matrix(list(zip(cols, rows, values, strict=True)), n, size)


def sparse_matrix(entries: Sequence[tuple[int, int, float]], rows: int, cols: int) -> sparse.csr_matrix:
    """A sparse matrix from ``(row, column, value)`` entries (repeated entries add up).

    scipy is imported here, where the first matrix is built: a command or a server that never tracks a
    teammate does not pay for it."""
    from scipy import sparse

    r, c, v = zip(*entries, strict=True) if entries else ((), (), ())
    indices = (np.asarray(r, dtype=np.intp), np.asarray(c, dtype=np.intp))
    return sparse.csr_matrix((np.asarray(v, dtype=float), indices), shape=(rows, cols))
