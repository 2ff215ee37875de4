"""The orderings a hierarchy imposes, and how well they match a published "must come before" relation.

An HTN implies ``a`` before ``b`` when every execution it admits performs ``a`` before ``b``. Inside one
tree that happens exactly when the lowest common ancestor of the two leaves is a chain and ``a``'s branch
comes first (a clique lets its children go in any order). Between the roots of a partial hierarchy it happens
when every path of the top-level graph that performs ``b``'s root has performed ``a``'s root before.

Used to score learned hierarchies against a published "must come before" relation (the CaptainCook4D
experiments in :mod:`supportive.experiments.captaincook`).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Hashable, Iterable, Iterator
from dataclasses import dataclass

from supportive.learning.reachability import reachable
from supportive.tasks.htn import HTN, ActionNode, ChainNode, Leaf, Node, TopLevel

__all__ = ["PrecedenceScore", "implied_precedences", "precedence_scores"]

Pair = tuple[Leaf, Leaf]


@dataclass(frozen=True)
class PrecedenceScore:
    """Learned precedence pairs scored against published ones.

    By convention the precision of an empty learned set is 1.0 (it claims nothing wrong) and the recall of an
    empty published set is 1.0 (there is nothing to find); F1 is 0.0 when precision and recall are both 0.
    """

    precision: float
    recall: float
    f1: float
    true_positives: int
    learned: int
    published: int


def implied_precedences(htn: HTN) -> frozenset[Pair]:
    """Pairs ``(a, b)`` of leaves such that ``a`` comes before ``b`` in every execution ``htn`` admits.

    Within a tree, ``a`` precedes ``b`` when their lowest common ancestor is a chain with ``a``'s branch
    first. For a partial hierarchy, leaves of different roots are ordered as their roots are on every
    top-level path (see :func:`_root_precedences`); a hierarchy with several roots and no top level leaves its
    roots unordered.
    """
    pairs: set[Pair] = set()
    for root in htn.roots:
        pairs.update(_tree_pairs(root))
    if htn.top_level is not None and len(htn.roots) > 1:
        for first, second in _root_precedences(htn.top_level, len(htn.roots)):
            pairs.update((a, b) for a in htn.roots[first].leaves for b in htn.roots[second].leaves)
    return frozenset(pairs)


def _tree_pairs(node: Node) -> Iterator[Pair]:
    if isinstance(node, ActionNode):
        return
    if isinstance(node, ChainNode):
        for i, earlier in enumerate(node.children):
            for later in node.children[i + 1 :]:
                yield from ((a, b) for a in earlier.leaves for b in later.leaves)
    for child in node.children:
        yield from _tree_pairs(child)


def _root_precedences(top: TopLevel, n_roots: int) -> Iterator[tuple[int, int]]:
    """Root pairs ``(a, b)`` such that no initial-to-terminal path performs ``b`` and later ``a`` (a root a
    path skips binds nothing: an optional root keeps its orders).

    ``a`` fails to precede ``b`` exactly when some ``b`` edge leaves a state reachable from an initial state
    and enters one from which an ``a`` edge can still be taken on the way to a terminal state. So one forward
    pass, one backward pass and, per root, one backward pass from its edges decide every pair, in
    O(roots x edges), without listing paths.
    """
    into: dict[int, list[int]] = defaultdict(list)
    out: dict[int, list[int]] = defaultdict(list)
    for src, _, dst in top.edges:
        into[dst].append(src)
        out[src].append(dst)
    alive = reachable(top.terminal, into)
    started = reachable(top.initial, out)
    for first in range(n_roots):
        sources = {src for src, root, dst in top.edges if root == first and dst in alive}
        still_possible = reachable(sources, into)
        unordered = {
            root for src, root, dst in top.edges if src in started and dst in still_possible and root != first
        }
        yield from ((first, second) for second in range(n_roots) if second not in unordered | {first})


def precedence_scores(learned: Iterable[Hashable], published: Iterable[Hashable]) -> PrecedenceScore:
    """Precision, recall and F1 of ``learned`` pairs against ``published`` pairs (see :class:`PrecedenceScore`
    for the empty-set conventions).

    >>> s = precedence_scores({(("a", 1), ("b", 1))}, {(("a", 1), ("b", 1)), (("b", 1), ("c", 1))})
    >>> s.precision, s.recall
    (1.0, 0.5)
    """
    mine, truth = set(learned), set(published)
    hits = len(mine & truth)
    precision = hits / len(mine) if mine else 1.0
    recall = hits / len(truth) if truth else 1.0
    total = precision + recall
    f1 = 2 * precision * recall / total if total else 0.0
    return PrecedenceScore(precision, recall, f1, hits, len(mine), len(truth))
