"""The orderings a hierarchy imposes, and how well they match a published "must come before" relation.

An HTN implies ``a`` before ``b`` when every execution it admits performs ``a`` before ``b``. Inside one
tree that happens exactly when the lowest common ancestor of the two leaves is a chain and ``a``'s branch
comes first (a clique lets its children go in any order). Between the roots of a partial hierarchy it happens
when every path of the top-level graph that performs ``b``'s root has performed ``a``'s root before.

Executions name a step by its action and how many times the action was done so far (``("stir", 2)``: the
second stir), whichever leaf of the tree performed it. Where the leaves of one action may come in either
order (a clique of repeats, ``3 × stir``), the tree's own labels are not the executions': the first stir
always comes before the second, and a leaf's orders with other steps hold for the *k*-th performance only
as far as *k* of the action's leaves are sure to be done by then. A clique of repeats is done block after
block, the first block done holding the first performances (``2 × (heat → stir)``: heat, stir, heat, stir),
so it orders its children as a chain would (:func:`_in_turn`); the pairs read off the tree are then turned
into the executions' (:func:`_as_performed`): the performances of one action in their order, and
``(x, k)`` before ``(z, m)`` when ``k`` leaves of ``x`` that every execution performs (or every leaf of
``x``) all come before leaves of ``z`` that leave out at most ``m − 1`` of them — then at least ``k``
performances of ``x`` precede the ``m``-th of ``z`` in every execution doing both. For
an action done once, or whose leaves the tree keeps in their order, these are the tree's pairs; for a clique of
repeats they are every pair that holds. Every pair named holds in every execution; where cliques keep blocks of
an action's leaves together, counting can hold a few more than these find (both tested against listing every
execution).

Used to score learned hierarchies against a published "must come before" relation (the CaptainCook4D
experiments in :mod:`supportive.experiments.captaincook`).
"""

from __future__ import annotations

import itertools
from collections import defaultdict
from collections.abc import Collection, Hashable, Iterable, Iterator, Sequence
from dataclasses import dataclass

from supportive.learning.reachability import reachable
from supportive.tasks.htn import HTN, ActionNode, ChainNode, Leaf, Node, TopLevel, nullable
from supportive.tasks.nodes import shape

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
    by_action: dict[str, list[Leaf]] = defaultdict(list)
    for leaf in htn.leaves:
        by_action[leaf[0]].append(leaf)
    if all(len(group) == 1 for group in by_action.values()):
        return frozenset(pairs)
    return frozenset(_as_performed(pairs, by_action, frozenset(htn.required_leaves)))


def _as_performed(pairs: set[Pair], by_action: dict[str, list[Leaf]], always: Collection[Leaf]) -> set[Pair]:
    """The tree's ``pairs`` as executions name the steps (see the module docstring and
    :func:`_performed_orders`); the performances of one action always in their order. ``always``: the
    leaves every execution performs."""
    out = {(a, b) for a, b in pairs if len(by_action[a[0]]) == 1 and len(by_action[b[0]]) == 1}
    for x, xs in by_action.items():
        for z, zs in by_action.items():
            if x == z:
                out.update(((x, k), (x, m)) for k in range(1, len(xs) + 1) for m in range(k + 1, len(xs) + 1))
            elif len(xs) > 1 or len(zs) > 1:
                out.update(((x, k), (z, m)) for k, m in _performed_orders(xs, zs, pairs, always))
    return out


def _performed_orders(xs: list[Leaf], zs: list[Leaf], pairs: set[Pair], always: Collection[Leaf]) -> Iterator[tuple[int, int]]:
    """``(k, m)`` such that the ``k``-th performance of ``x`` comes before the ``m``-th of ``z`` in every
    execution doing both, ``xs`` and ``zs`` their leaves: some leaves ``A`` of ``x`` all come before some
    leaves ``B`` of ``z`` (in ``pairs``, which bind executions doing both), at most ``m - 1`` leaves of ``z``
    are not in ``B`` (so one of the first ``m`` performances of ``z`` is in ``B``), and either ``A`` is every
    leaf of ``x`` or ``k`` of its leaves that every execution performs (then ``k`` performances of ``x`` are
    done before it). For each ``k``, ``A`` is tried as every leaf and as the ``k`` performed-always leaves
    with the most leaves of ``z`` after them: every pair found holds; where those sets are nested (repeats in
    turn) none is missed."""

    def after(chosen: Sequence[Leaf]) -> int:
        return sum(all((a, b) in pairs for a in chosen) for b in zs)

    everyone = after(xs)
    required = sorted((a for a in xs if a in always), key=lambda a: -after([a]))
    for k in range(1, len(xs) + 1):
        best = max(everyone, after(required[:k]) if k <= len(required) else 0)
        yield from ((k, m) for m in range(len(zs) - best + 1, len(zs) + 1))


def _tree_pairs(node: Node) -> Iterator[Pair]:
    if isinstance(node, ActionNode):
        return
    turns = node.children if isinstance(node, ChainNode) else _in_turn(node.children)
    for i, earlier in enumerate(turns):
        for later in turns[i + 1 :]:
            yield from ((a, b) for a in earlier.leaves for b in later.leaves)
    for child in node.children:
        yield from _tree_pairs(child)


def _in_turn(children: Sequence[Node]) -> Sequence[Node]:
    """A clique's children in the order executions name them, when that order is fixed: a clique of repeats
    (``2 × (microwave → stir)``: children of one shape, none skipped) is done block after block, and the
    block done first holds the first performance of each of its actions, whichever child it is — so it is a
    chain of its children by their performances (each position's increasing from child to child). Empty for
    any other clique (its children in any order)."""
    if len(children) < 2 or any(nullable(child) for child in children):
        return ()
    first = shape(children[0])
    if any(shape(child) != first for child in children[1:]):
        return ()
    ordered = sorted(children, key=lambda child: [occurrence for _, occurrence in child.leaves])
    places = zip(*([occurrence for _, occurrence in child.leaves] for child in ordered), strict=True)
    return ordered if all(a < b for place in places for a, b in itertools.pairwise(place)) else ()


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
