"""Algorithms 3 and 4: alternative hierarchies when compaction stops short of one root (§2.1.5.3).

When the known executions are not the language of any one chain/clique tree (two glasses, each placed before it
is filled: the six valid orders fit neither "place both, then fill both" nor "glass by glass"), each reading is
a *restriction*: it commits to a subset of the known executions that some tree generates exactly.

* Chain resolution (Algorithm 3) ignores the CTG edges between commutative subgoals, finds the chains that this
  reveals, keeps only executions in which those chains run contiguously and in order, and compacts on.
* Clique resolution (Algorithm 4) takes the maximal cliques of commutative subgoals, keeps only executions in
  which each is contiguous, and compacts on. Overlapping cliques are tried with each one first.

A result is kept only when it is complete (one root) and valid: every execution it admits is known. Results are
ranked by how many known executions they admit (the least committed first).
"""

from __future__ import annotations

from collections.abc import Iterator

from supportive.learning.strict.compaction import Compaction, Registry
from supportive.learning.strict.coverage import admitted_path_count
from supportive.learning.strict.levels import Group, LevelGraph
from supportive.tasks.htn import Node, canonical, count_orderings
from supportive.tasks.task_graph import TaskGraph

__all__ = ["resolve_ambiguity"]


def resolve_ambiguity(
    compaction: Compaction, *, limit: int = 8, max_roots: int = 64, depth: int = 2
) -> list[tuple[Node, int]]:
    """Complete, valid alternative hierarchies for a compaction that stopped with several roots.

    Args:
        compaction: A finished :class:`Compaction`.
        limit: Most alternatives to return.
        max_roots: Skip resolution when more roots than this are left (the search grows with them).
        depth: How many rounds of resolution to chain when one round still leaves several roots.

    Returns:
        ``(root, admitted known executions)`` pairs, best first.
    """
    top = compaction.top
    if len(top.by_node) <= 1 or len(top.by_node) > max_roots:
        return []
    found: dict[tuple[object, ...], tuple[Node, int]] = {}
    for root in _resolve(compaction.graph, top, compaction.registry, depth, limit * 4):
        key = canonical(root)
        if key in found:
            continue
        admitted = admitted_path_count(compaction.graph, root)
        if admitted and admitted == count_orderings(root):
            found[key] = (root, admitted)
    ranked = sorted(found.values(), key=lambda pair: (-pair[1], _size(pair[0])))
    return ranked[:limit]


def _size(node: Node) -> int:
    return len(getattr(node, "children", ())) + sum(_size(c) for c in getattr(node, "children", ()))


def _resolve(
    graph: TaskGraph, level: LevelGraph, registry: Registry, depth: int, budget: int
) -> Iterator[Node]:
    if depth == 0 or budget <= 0:
        return
    for groups in _readings(level, registry):
        budget -= 1
        if budget < 0:
            return
        restricted = level.restrict(groups)
        if restricted is None:
            continue
        scratch = registry.copy()
        restricted.node_mask = scratch.mask
        top = Compaction.resumed(graph, restricted, scratch).top
        if len(top.by_node) == 1:
            yield scratch.nodes[next(iter(top.by_node))]
        elif top.n_edges < level.n_edges or len(top.by_node) < len(level.by_node):
            yield from _resolve(graph, top, scratch, depth - 1, budget)


def _readings(level: LevelGraph, registry: Registry) -> Iterator[list[Group]]:
    ordering = registry.ordering
    mutual = level.mutual_pairs()
    ignore: dict[int, set[int]] = {}
    for u, v in mutual:
        ignore.setdefault(u, set()).add(v)
        ignore.setdefault(v, set()).add(u)
    chains = level.chains(ordering, ignore)
    if chains:
        yield chains
    cliques = level.clique_candidates(mutual, ordering)
    for first in cliques:
        chosen, used = [first], set(first)
        for other in cliques:
            if used.isdisjoint(other):
                chosen.append(other)
                used |= other
        yield [
            Group(tuple(sorted(c, key=lambda n: ordering.rank[n])), False, level.mask_of(c)) for c in chosen
        ]
