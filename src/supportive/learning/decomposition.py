"""Learn chains and cliques from the demonstrations themselves, accepting what the evidence supports
(the ``general`` learner; the ``strict`` one is :class:`~supportive.learning.compaction.Compaction`).

Bottom up, level after level, like Algorithm 2, but over the demonstrations as sequences rather than over the
states they share, so that a subtask need not have been seen in every order once:

1. Candidates are the smallest sets of current nodes that contain two nodes performed one right after the
   other somewhere and are contiguous in every demonstration that performs any of them (a step a
   demonstration skips does not break contiguity): the *closure* of that pair.
2. A candidate performed in one order everywhere is a **chain** (§2.1.4's maximal chains, found as runs
   that are consistently ordered); one performed in several orders is a **clique** unless an order between
   two of its members is established (:func:`~supportive.learning.evidence.established_precedences`) —
   then no chain/clique node fits it and it is left to the level above. §2.1.4 accepts a clique whose
   members commute pairwise and are contiguous; this accepts one whose members are contiguous and show no
   established order, which is what a few demonstrations of an order-free subtask show.
3. The accepted candidates are disjoint (smallest first); each becomes one node and every demonstration is
   rewritten with it. The loop stops at one root or when a level accepts nothing.
4. A clique nested directly in a clique claims that its members are never interleaved with its siblings;
   it is kept only when the demonstrations are evidence of that (steps outside it were seen on both sides
   of it and never inside, :func:`~supportive.learning.evidence.contiguity_chance`), and otherwise merged
   into its parent. A contiguous run seen in varying orders among other steps that move around it is more
   often chance than a subtask of its own, and the merged clique admits what people go on to do.

Nodes are plain ids here; :mod:`supportive.learning.annotate` turns them into HTN nodes with optional flags,
counts and support.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import networkx as nx
import numpy as np

from supportive.learning.evidence import contiguity_chance, established_precedences, pair_counts, supported
from supportive.tasks.htn import Leaf

__all__ = ["Decomposition", "Group", "decompose"]


@dataclass(frozen=True)
class Group:
    """One learned internal node: its children (node ids) in order, whether it is a chain, and (a clique)
    whether every order of its children was seen."""

    children: tuple[int, ...]
    chain: bool
    seen_in_full: bool = False


@dataclass
class Decomposition:
    """What :func:`decompose` found.

    Attributes:
        leaves: The leaf labels; leaf ``i`` is node ``i``.
        groups: Internal nodes by id (ids after the leaves).
        roots: The top-level node ids, in the order they first occur.
        sequences: Every demonstration as a sequence of root ids.
        presence: Node id -> the demonstrations (indices) performing any of its leaves.
        leaf_sequences: Every demonstration as a sequence of leaf ids.
    """

    leaves: tuple[Leaf, ...]
    groups: dict[int, Group] = field(default_factory=dict)
    roots: list[int] = field(default_factory=list)
    sequences: list[list[int]] = field(default_factory=list)
    presence: dict[int, frozenset[int]] = field(default_factory=dict)
    leaf_sequences: list[list[int]] = field(default_factory=list)


def decompose(
    labelled: Sequence[Sequence[Leaf]],
    *,
    evidence: float,
    order_support: int,
    modules: bool = True,
    max_module: int = 1000,
) -> Decomposition:
    """Chains and cliques of the labelled demonstrations (see the module docstring).

    Args:
        labelled: Demonstrations as ``(action, instance)`` labels, each label at most once per demonstration.
        evidence: A clique nested in a clique stays a node of its own only when the chance of its contiguity
            under random placement of the free steps is below this
            (:func:`~supportive.learning.evidence.contiguity_chance`).
        order_support: Demonstrations showing a pair in one order that establish the order without a
            witness (see :func:`~supportive.learning.evidence.established_precedences`).
        modules: False keeps every leaf a root (no chain or clique is made).
        max_module: Candidates larger than this (nodes of one level) are not grown further (they are found
            only as the whole level); bounds the work on long demonstrations without structure.
    """
    order: dict[Leaf, int] = {}
    for demo in labelled:
        for leaf in demo:
            order.setdefault(leaf, len(order))
    result = Decomposition(tuple(order))
    sequences = [[order[leaf] for leaf in demo] for demo in labelled]
    result.leaf_sequences = [list(s) for s in sequences]
    rank = {i: i for i in range(len(order))}
    presence: dict[int, set[int]] = {i: set() for i in range(len(order))}
    for d, sequence in enumerate(sequences):
        for node in sequence:
            presence[node].add(d)
    next_id = len(order)
    chance: dict[int, float] = {}
    closures: dict[frozenset[int], frozenset[int] | None] = {}  # pair -> closure, kept while no member merges
    while modules:
        level = {node for sequence in sequences for node in sequence}
        if len(level) <= 1:
            break
        chosen = _choose(sequences, level, rank, order_support, max_module, closures)
        if not chosen:
            break
        replace: dict[int, int] = {}
        arrays = [np.asarray(sequence, dtype=np.int64) for sequence in sequences]
        for group in chosen:
            node = next_id
            next_id += 1
            whole = len(group.children) == len(level)
            if not group.chain:
                chance[node] = 1.0 if whole else contiguity_chance(arrays, frozenset(group.children), next_id)
            weak = set()
            if not group.chain and not group.seen_in_full:
                weak = {m for m in group.children if not supported(chance.get(m, 1.0), evidence)}
            result.groups[node] = _spliced(group, result.groups, presence, weak)
            rank[node] = min(rank[m] for m in group.children)
            presence[node] = set().union(*(presence[m] for m in group.children))
            for member in group.children:
                replace[member] = node
        sequences = [_rewrite(sequence, replace) for sequence in sequences]
        closures = {  # one that outgrew the limit may fit once nodes in its span merge: try it again
            pair: found
            for pair, found in closures.items()
            if found is not None and not (found & replace.keys())
        }
    result.sequences = sequences
    result.roots = sorted({n for s in sequences for n in s}, key=lambda n: rank[n])
    result.presence = {node: frozenset(ds) for node, ds in presence.items()}
    return result


def _choose(
    sequences: Sequence[Sequence[int]],
    level: set[int],
    rank: dict[int, int],
    order_support: int,
    max_module: int,
    closures: dict[frozenset[int], frozenset[int] | None],
) -> list[Group]:
    """This level's accepted candidates (see the module docstring); ``closures`` caches the closures of
    pairs from level to level (a closure none of whose members merged is the same at the next level: no node
    outside it was inside its span)."""
    where = [{x: i for i, x in enumerate(sequence)} for sequence in sequences]
    pairs = _candidate_pairs(sequences)
    followers: dict[int, set[int | None]] = {}
    leaders: dict[int, set[int | None]] = {}
    for s in sequences:
        for i, x in enumerate(s):
            followers.setdefault(x, set()).add(s[i + 1] if i + 1 < len(s) else None)
            leaders.setdefault(x, set()).add(s[i - 1] if i else None)
    candidates: dict[frozenset[int], None] = {}
    tried: set[frozenset[int]] = set()
    for pair in sorted(pairs, key=lambda p: (rank[p[0]], rank[p[1]])):
        x, y = pair
        if followers[x] == {y} and leaders[y] == {x}:  # always one right after the other: a link
            candidates[frozenset(pair)] = None
            continue
        key = frozenset(pair)
        if key in tried:  # the same pair in the other order: the same closure
            continue
        tried.add(key)
        if key in closures:
            found = closures[key]
        else:
            found = closures[key] = _closure(pair, where, sequences, max_module)
        if found is not None:
            candidates[found] = None
    whole = frozenset(level)
    ordered = sorted(candidates, key=lambda c: (len(c), min(rank[m] for m in c)))
    chosen: list[Group] = []
    used: set[int] = set()
    for candidate in ordered:
        if candidate & used or candidate == whole:
            continue
        group = _classify(_member_orders(candidate, where), rank, order_support)
        if group is None:
            continue
        chosen.append(group)
        used |= candidate
    if not chosen:
        group = _classify([list(s) for s in sequences], rank, order_support)
        if group is not None:
            chosen.append(group)
    return chosen


def _member_orders(members: frozenset[int], where: Sequence[dict[int, int]]) -> list[list[int]]:
    """The members each sequence performs, in its order."""
    out = []
    for positions in where:
        present = [(positions[m], m) for m in members if m in positions]
        present.sort()
        out.append([m for _, m in present])
    return out


def _candidate_pairs(sequences: Sequence[Sequence[int]]) -> set[tuple[int, int]]:
    """Pairs whose closures hold every minimal candidate: those adjacent in the first sequence, and those
    adjacent elsewhere that involve a node the first sequence lacks (a set contiguous everywhere with two
    members in the first sequence holds a pair adjacent there; otherwise it holds such a node next to
    another member)."""
    first = sequences[0]
    pairs = {(first[i], first[i + 1]) for i in range(len(first) - 1)}
    seen = set(first)
    for sequence in sequences[1:]:
        for i in range(len(sequence) - 1):
            x, y = sequence[i], sequence[i + 1]
            if x not in seen or y not in seen:
                pairs.add((x, y))
    return pairs


def _closure(
    pair: tuple[int, int], where: Sequence[dict[int, int]], sequences: Sequence[Sequence[int]], limit: int
) -> frozenset[int] | None:
    """The smallest set holding ``pair`` whose present members are contiguous in every sequence, or None
    when it outgrows ``limit``."""
    members = set(pair)
    frontier = list(pair)
    lo = [-1] * len(sequences)
    hi = [-1] * len(sequences)
    while frontier:
        node = frontier.pop()
        for d, positions in enumerate(where):
            p = positions.get(node)
            if p is None:
                continue
            if lo[d] < 0:
                lo[d] = hi[d] = p
                continue
            sequence = sequences[d]
            if p < lo[d]:
                span = range(p, lo[d])
                lo[d] = p
            elif p > hi[d]:
                span = range(hi[d] + 1, p + 1)
                hi[d] = p
            else:
                continue
            for i in span:
                x = sequence[i]
                if x not in members:
                    members.add(x)
                    frontier.append(x)
                    if len(members) > limit:
                        return None
    return frozenset(members)


def _classify(orders: Sequence[Sequence[int]], rank: dict[int, int], order_support: int) -> Group | None:
    """Members performed in ``orders`` (each sequence's members, in its order): a chain when one order fits
    every sequence, a clique when no order between two of them is established, else None."""
    listed = sorted({m for order in orders for m in order}, key=lambda n: rank[n])
    performed = [order for order in orders if order]
    if all(len(order) == len(listed) and order == performed[0] for order in performed):
        return Group(tuple(performed[0]), True)
    before, together = pair_counts(orders, listed)
    graph = nx.DiGraph()
    graph.add_nodes_from(range(len(listed)))
    graph.add_edges_from((int(u), int(v)) for u, v in zip(*np.nonzero(before), strict=True))
    if nx.is_directed_acyclic_graph(graph):
        mean = _mean_positions(orders, listed)
        order = list(nx.lexicographical_topological_sort(graph, key=lambda i: (mean[i], i)))
        return Group(tuple(listed[i] for i in order), True)
    if established_precedences(before, together, order_support).any():
        return None
    complete = {tuple(order) for order in orders if len(order) == len(listed)}
    return Group(tuple(listed), False, len(complete) == math.factorial(len(listed)))


def _mean_positions(orders: Sequence[Sequence[int]], members: Sequence[int]) -> list[float]:
    """Mean relative position (0 to 1) of each member within the orders it is performed in."""
    index = {m: i for i, m in enumerate(members)}
    total = [0.0] * len(members)
    count = [0] * len(members)
    for order in orders:
        inside = [index[x] for x in order]
        for p, i in enumerate(inside):
            total[i] += p / max(len(inside) - 1, 1)
            count[i] += 1
    return [t / c if c else 0.0 for t, c in zip(total, count, strict=True)]


def _spliced(group: Group, groups: dict[int, Group], presence: dict[int, set[int]], weak: set[int]) -> Group:
    """Members that mean nothing of their own are replaced by their children: a chain in a chain performed
    whenever its siblings are (both mean the same order; an optional sub-chain stays a node of its own), and
    a clique in a clique whose contiguity is not evidenced (``weak``: a clique of its own would claim it is
    never interleaved with its siblings)."""
    whole = set().union(*(presence[m] for m in group.children))
    children: list[int] = []
    for member in group.children:
        inner = groups.get(member)
        if inner is not None and inner.chain == group.chain and (
            (group.chain and presence[member] == whole) or (not group.chain and member in weak)
        ):
            children.extend(inner.children)
        else:
            children.append(member)
    return Group(tuple(children), group.chain, group.seen_in_full and not weak)


def _rewrite(sequence: Sequence[int], replace: dict[int, int]) -> list[int]:
    out: list[int] = []
    for node in sequence:
        new = replace.get(node, node)
        if new != node and out and out[-1] == new:
            continue
        out.append(new)
    return out


