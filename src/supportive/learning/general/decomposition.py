"""Learn chains and cliques from the demonstrations themselves, accepting what the evidence supports
(the ``general`` learner; the ``strict`` one is :class:`~supportive.learning.strict.compaction.Compaction`).

Bottom up, level after level, like Algorithm 2, but over the demonstrations as sequences rather than over the
states they share, so that a subtask need not have been seen in every order once:

1. Candidates are the smallest sets of current nodes that contain two nodes performed one right after the
   other somewhere and are contiguous in every demonstration that performs any of them (a step a
   demonstration skips does not break contiguity): the *closure* of that pair.
2. A candidate performed in one order everywhere is a **chain** (§2.1.4's maximal chains, found as runs
   that are consistently ordered); one performed in several orders is a **clique** unless an order between
   two of its members is established (:func:`~supportive.learning.general.evidence.established_precedences`) —
   then no chain/clique node fits it and it is left to the level above. §2.1.4 accepts a clique whose
   members commute pairwise and are contiguous; this accepts one whose members are contiguous and show no
   established order, which is what a few demonstrations of an order-free subtask show.
3. The accepted candidates are disjoint (smallest first); each becomes one node and every demonstration is
   rewritten with it. The loop stops at one root or when a level accepts nothing.
4. A clique nested directly in a clique claims that its members are never interleaved with its siblings;
   it is kept only when the demonstrations are evidence of that (steps outside it were seen on both sides
   of it and never inside, :func:`~supportive.learning.general.evidence.contiguity_chance`), and otherwise merged
   into its parent. A contiguous run seen in varying orders among other steps that move around it is more
   often chance than a subtask of its own, and the merged clique admits what people go on to do.

Nodes are plain ids here; :mod:`supportive.learning.general.annotate` turns them into HTN nodes with optional flags,
counts and support.
"""

from __future__ import annotations

import abc
import heapq
import itertools
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from supportive.learning.general.evidence import (
    IntMatrix,
    as_matrix,
    established_precedences,
    establishes_any,
    matrix_contiguity_chance,
    position_pair_counts,
    position_pair_counts_listed,
    positions_of,
    supported,
)
from supportive.tasks.htn import Leaf

__all__ = ["Decomposition", "Group", "Shapes", "decompose"]


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
        leaf_sequences: Every demonstration as a list of leaf ids.
    """

    leaves: tuple[Leaf, ...]
    groups: dict[int, Group] = field(default_factory=dict)
    roots: list[int] = field(default_factory=list)
    sequences: list[list[int]] = field(default_factory=list)
    presence: dict[int, frozenset[int]] = field(default_factory=dict)
    leaf_sequences: list[list[int]] = field(default_factory=list)

    @cached_property
    def leaf_nodes(self) -> IntMatrix:
        """Every demonstration as a row of leaf ids, -1 after its end (:func:`~supportive.learning.general.evidence.as_matrix`)."""
        return as_matrix(self.leaf_sequences)


class Shapes:
    """Numbers for the shapes of nodes: the same number for nodes of the same structure over the same actions,
    whatever their occurrence numbers (the instances of one repeated subtask), a clique's children in any
    order.

    Args:
        leaves: The leaf labels (leaf ``i`` is node ``i``).
        groups: Internal nodes by id.
    """

    def __init__(self, leaves: Sequence[Leaf], groups: Mapping[int, Group]) -> None:
        self._leaves = leaves
        self._groups = groups
        self._numbers: dict[int, int] = {}
        self._forms: dict[tuple[object, ...], int] = {}

    def __call__(self, node: int) -> int:
        """The number of ``node``'s shape."""
        number = self._numbers.get(node)
        if number is None:
            group = self._groups.get(node)
            if group is None:
                form: tuple[object, ...] = ("action", self._leaves[node][0])
            else:
                parts = [self(child) for child in group.children]
                form = ("chain", *parts) if group.chain else ("clique", *sorted(parts))
            number = self._numbers[node] = self._forms.setdefault(form, len(self._forms))
        return number


class _Level(abc.ABC):
    """The demonstrations at one level of the decomposition: what the steps of :func:`_choose` ask of them.

    Two forms answer alike: :class:`_Lists` (one demonstration at a time) and :class:`_Matrix` (all of them
    at once, for many short demonstrations); :func:`_level` picks one.
    """

    size: int
    present: set[int]
    first: list[int]
    starts: set[int]
    ends: set[int]
    adjacent: set[tuple[int, int]]

    @property
    @abc.abstractmethod
    def nodes(self) -> IntMatrix:
        """``nodes[d, i]``: the i-th node of demonstration ``d`` (-1 after its end)."""

    def links(self) -> dict[int, int]:
        """``x -> y`` for the pairs always performed one right after the other: every ``x`` is followed by
        ``y`` and every ``y`` follows ``x``."""
        followers: dict[int, set[int]] = {}
        leaders: dict[int, set[int]] = {}
        for x, y in self.adjacent:
            followers.setdefault(x, set()).add(y)
            leaders.setdefault(y, set()).add(x)
        out: dict[int, int] = {}
        for x, after in followers.items():
            if len(after) == 1 and x not in self.ends:
                (y,) = after
                if y not in self.starts and len(leaders[y]) == 1:
                    out[x] = y
        return out

    def candidate_pairs(self) -> set[tuple[int, int]]:
        """Pairs whose closures hold every minimal candidate: those adjacent in the first sequence, and those
        adjacent elsewhere that involve a node the first sequence lacks (a set contiguous everywhere with two
        members in the first sequence holds a pair adjacent there; otherwise it holds such a node next to
        another member)."""
        seen = set(self.first)
        pairs = set(itertools.pairwise(self.first))
        pairs.update(pair for pair in self.adjacent if pair[0] not in seen or pair[1] not in seen)
        return pairs

    @abc.abstractmethod
    def closure(self, pair: tuple[int, int], limit: int) -> frozenset[int] | None:
        """The smallest set holding ``pair`` whose present members are contiguous in every sequence, or None
        when it outgrows ``limit``."""

    @abc.abstractmethod
    def positions(self, members: Sequence[int]) -> IntMatrix:
        """``positions[d, i]``: where demonstration ``d`` performs ``members[i]`` (-1: not at all)."""

    @abc.abstractmethod
    def chain_order(self, members: Sequence[int]) -> tuple[int, ...] | None:
        """The members in the one order every demonstration performing any of them performs all of them in,
        or None when there is no such order."""

    @abc.abstractmethod
    def performers(self) -> dict[int, set[int]]:
        """Node -> the demonstrations performing it."""

    @abc.abstractmethod
    def rewritten(self, replace: dict[int, int], size: int, many: int) -> _Level:
        """The next level: each member of a group replaced by the group (node ids below ``size``)."""

    @abc.abstractmethod
    def sequences(self) -> list[list[int]]:
        """Every demonstration as a list of node ids."""


def _level(sequences: list[list[int]], size: int, many: int) -> _Level:
    """A level in the form that suits it: as matrices from ``many`` demonstrations on when they outnumber the
    steps of the longest, else as lists."""
    if len(sequences) >= many and len(sequences) > max(map(len, sequences), default=0):
        return _Matrix(as_matrix(sequences), size)
    return _Lists(sequences, size)


class _Lists(_Level):
    """A level as one list of node ids per demonstration (each node at most once)."""

    def __init__(self, sequences: list[list[int]], size: int) -> None:
        self._sequences = sequences
        self.size = size
        self.present = set(itertools.chain.from_iterable(sequences))
        self.first = sequences[0]
        self.starts = {sequence[0] for sequence in sequences if sequence}
        self.ends = {sequence[-1] for sequence in sequences if sequence}
        self.adjacent = set()
        for sequence in sequences:
            self.adjacent.update(itertools.pairwise(sequence))

    @cached_property
    def spots(self) -> dict[int, list[int]]:
        """Per node of the level, its position in each demonstration (-1: not performed)."""
        spots = {node: [-1] * len(self._sequences) for node in self.present}
        for d, sequence in enumerate(self._sequences):
            for i, node in enumerate(sequence):
                spots[node][d] = i
        return spots

    @cached_property
    def nodes(self) -> IntMatrix:
        """The sequences as a matrix (:func:`~supportive.learning.general.evidence.as_matrix`)."""
        return as_matrix(self._sequences)

    def closure(self, pair: tuple[int, int], limit: int) -> frozenset[int] | None:
        """See :meth:`_Level.closure`; its spans grown one node at a time."""
        return _closure(pair, self.spots, self._sequences, limit)

    def positions(self, members: Sequence[int]) -> IntMatrix:
        """See :meth:`_Level.positions`."""
        return np.array([self.spots[m] for m in members], dtype=np.int64).T

    def chain_order(self, members: Sequence[int]) -> tuple[int, ...] | None:
        """See :meth:`_Level.chain_order`."""
        columns = [self.spots[m] for m in members]
        found: list[int] | None = None
        for row in zip(*columns, strict=True):
            if max(row) < 0:
                continue
            if min(row) < 0:
                return None
            order = sorted(range(len(row)), key=row.__getitem__)
            if found is None:
                found = order
            elif order != found:
                return None
        return None if found is None else tuple(members[i] for i in found)

    def performers(self) -> dict[int, set[int]]:
        """See :meth:`_Level.performers`."""
        out: dict[int, set[int]] = {node: set() for node in sorted(self.present)}
        for d, sequence in enumerate(self._sequences):
            for node in sequence:
                out[node].add(d)
        return out

    def rewritten(self, replace: dict[int, int], size: int, many: int) -> _Level:
        """See :meth:`_Level.rewritten`: a group is performed contiguously and every node once, so the
        group's are the only repeats."""
        return _level([list(dict.fromkeys(map(replace.get, s, s))) for s in self._sequences], size, many)

    def sequences(self) -> list[list[int]]:
        """See :meth:`_Level.sequences`."""
        return [list(sequence) for sequence in self._sequences]


class _Matrix(_Level):
    """A level as matrices: ``nodes[d, i]`` is the i-th node of demonstration ``d`` (-1 after its end) and
    ``at[d, n]`` the position of node ``n`` in it (-1 when it does not perform it)."""

    def __init__(self, nodes: IntMatrix, size: int) -> None:
        self._nodes = nodes
        self.size = size
        valid = nodes >= 0
        self.present = set(np.unique(nodes[valid]).tolist())
        self.first = nodes[0][valid[0]].tolist()
        lengths = valid.sum(axis=1)
        self.starts = set(nodes[lengths > 0, 0].tolist())
        self.ends = set(nodes[lengths > 0, lengths[lengths > 0] - 1].tolist())
        pairs = np.unique(nodes[:, :-1][valid[:, 1:]] * (size + 1) + nodes[:, 1:][valid[:, 1:]])
        before, after = np.divmod(pairs, size + 1)
        self.adjacent = set(zip(before.tolist(), after.tolist(), strict=True))

    @property
    def nodes(self) -> IntMatrix:
        """See :attr:`_Level.nodes`."""
        return self._nodes

    def closure(self, pair: tuple[int, int], limit: int) -> frozenset[int] | None:
        """See :meth:`_Level.closure`; a fixpoint over all demonstrations at once: every node inside a span
        joins."""
        member = np.zeros(self.size + 1, dtype=bool)  # the last entry stands for the padding
        member[list(pair)] = True
        columns = np.arange(self.nodes.shape[1])
        count = 2
        while True:
            where = self.at[:, member[:-1]]
            lo = np.where(where >= 0, where, self.nodes.shape[1]).min(axis=1)
            hi = where.max(axis=1)
            member[self.nodes[(columns >= lo[:, None]) & (columns <= hi[:, None])]] = True
            grown = int(np.count_nonzero(member))
            if grown == count:
                break
            count = grown
        if count > max(limit, 2):  # as when grown one node at a time: the pair itself is never refused
            return None
        return frozenset(np.flatnonzero(member).tolist())

    @cached_property
    def at(self) -> IntMatrix:
        """``at[d, n]``: the position of node ``n`` in demonstration ``d`` (-1 when it does not perform it)."""
        return positions_of(self.nodes, self.size)

    def positions(self, members: Sequence[int]) -> IntMatrix:
        """See :meth:`_Level.positions`."""
        return self.at[:, list(members)]

    def chain_order(self, members: Sequence[int]) -> tuple[int, ...] | None:
        """See :meth:`_Level.chain_order`."""
        positions = self.positions(members)
        performing = positions[(positions >= 0).any(axis=1)]
        orders = np.argsort(performing, axis=1)
        if len(performing) and (performing >= 0).all() and (orders == orders[0]).all():
            return tuple(members[i] for i in orders[0].tolist())
        return None

    def performers(self) -> dict[int, set[int]]:
        """See :meth:`_Level.performers`."""
        return {node: set(np.flatnonzero(self.at[:, node] >= 0).tolist()) for node in sorted(self.present)}

    def rewritten(self, replace: dict[int, int], size: int, many: int) -> _Level:
        """See :meth:`_Level.rewritten`."""
        new = np.arange(size + 1)
        new[-1] = -1  # the padding stays padding
        new[list(replace)] = list(replace.values())
        mapped = new[self.nodes]
        previous = np.concatenate([np.full((len(mapped), 1), -1), mapped[:, :-1]], axis=1)
        keep = (mapped >= 0) & (mapped != previous)  # a group is performed contiguously, every node once
        nodes = np.full((len(mapped), int(keep.sum(axis=1).max(initial=0))), -1, dtype=np.int64)
        rows, _ = np.nonzero(keep)
        nodes[rows, (np.cumsum(keep, axis=1) - 1)[keep]] = mapped[keep]
        return _Matrix(nodes, size)

    def sequences(self) -> list[list[int]]:
        """See :meth:`_Level.sequences`."""
        lengths = (self.nodes >= 0).sum(axis=1).tolist()
        return [row[:length] for row, length in zip(self.nodes.tolist(), lengths, strict=True)]


def decompose(
    labelled: Sequence[Sequence[Leaf]],
    *,
    evidence: float,
    order_support: int,
    modules: bool = True,
    max_module: int = 1000,
    many: int = 64,
) -> Decomposition:
    """Chains and cliques of the labelled demonstrations (see the module docstring).

    Args:
        labelled: Demonstrations as ``(action, instance)`` labels, each label at most once per demonstration.
        evidence: A clique nested in a clique stays a node of its own only when the chance of its contiguity
            under random placement of the free steps is below this
            (:func:`~supportive.learning.general.evidence.contiguity_chance`).
        order_support: Demonstrations showing a pair in one order that establish the order without a
            witness (see :func:`~supportive.learning.general.evidence.established_precedences`).
        modules: False keeps every leaf a root (no chain or clique is made).
        max_module: Candidates larger than this (nodes of one level) are not grown further (they are found
            only as the whole level); bounds the work on long demonstrations without structure.
        many: From this many demonstrations, when they also outnumber the steps of a level's longest, that
            level is worked on as matrices over all demonstrations at once, otherwise one demonstration at a
            time; only the speed depends on it.
    """
    order = {leaf: i for i, leaf in enumerate(dict.fromkeys(itertools.chain.from_iterable(labelled)))}
    result = Decomposition(tuple(order))
    rank = list(range(len(order)))
    result.leaf_sequences = [list(map(order.__getitem__, demo)) for demo in labelled]
    level = _level(result.leaf_sequences, len(order), many)
    presence = level.performers()
    formed: dict[int, tuple[_Level, tuple[int, ...]]] = {}  # clique -> the level it was formed at, its members
    chance: dict[int, float] = {}

    def chance_of(node: int) -> float:
        """The contiguity chance of a clique, at the level it was formed at (computed when first asked)."""
        if node not in chance:
            at, members = formed[node]
            chance[node] = matrix_contiguity_chance(at.nodes, members, at.size)
        return chance[node]

    closures: dict[frozenset[int], frozenset[int] | None] = {}  # pair -> closure, kept while no member merges
    while modules and len(level.present) > 1:
        chosen = _choose(level, rank, order_support, max_module, closures)
        if not chosen:
            break
        replace: dict[int, int] = {}
        for group in chosen:
            node = len(rank)
            whole = len(group.children) == len(level.present)
            if not group.chain and not whole:  # a clique of the whole level is contiguous by itself
                formed[node] = (level, group.children)
            weak = set()
            if not group.chain and not group.seen_in_full:
                weak = {m for m in group.children if m in formed and not supported(chance_of(m), evidence)}
            presence[node] = set().union(*(presence[m] for m in group.children))
            result.groups[node] = _spliced(group, result.groups, presence, weak, presence[node])
            rank.append(min(map(rank.__getitem__, group.children)))
            for member in group.children:
                replace[member] = node
        level = level.rewritten(replace, len(rank), many)
        closures = {  # one that outgrew the limit may fit once nodes in its span merge: try it again
            pair: found
            for pair, found in closures.items()
            if found is not None and not (found & replace.keys())
        }
    result.sequences = level.sequences()
    result.roots = sorted(level.present, key=rank.__getitem__)
    result.presence = {node: frozenset(ds) for node, ds in presence.items()}
    return result


def _choose(
    level: _Level,
    rank: list[int],
    order_support: int,
    max_module: int,
    closures: dict[frozenset[int], frozenset[int] | None],
) -> list[Group]:
    """This level's accepted candidates (see the module docstring); ``closures`` caches the closures of
    pairs from level to level (a closure none of whose members merged is the same at the next level: no node
    outside it was inside its span)."""
    links = level.links()
    candidates: dict[frozenset[int], None] = {}
    linked: dict[frozenset[int], tuple[int, int]] = {}
    tried: set[frozenset[int]] = set()
    for pair in sorted(level.candidate_pairs(), key=lambda p: (rank[p[0]], rank[p[1]])):
        key = frozenset(pair)
        if links.get(pair[0]) == pair[1]:  # always one right after the other: a link, a chain of two
            candidates[key] = None
            linked[key] = pair
            continue
        if key in tried:  # the same pair in the other order: the same closure
            continue
        tried.add(key)
        if key in closures:
            found = closures[key]
        else:
            # a closure of the whole level is no candidate (the whole level is classified apart): stop short of it
            found = closures[key] = level.closure(pair, min(max_module, len(level.present) - 1))
        if found is not None:
            candidates[found] = None
    whole = frozenset(level.present)
    ordered = sorted(candidates, key=lambda c: (len(c), min(map(rank.__getitem__, c))))
    chosen: list[Group] = []
    used: set[int] = set()
    for candidate in ordered:
        if candidate & used or candidate == whole:
            continue
        if candidate in linked:
            group: Group | None = Group(linked[candidate], True)
        else:
            group = _classify(level, sorted(candidate, key=rank.__getitem__), order_support)
        if group is None:
            continue
        chosen.append(group)
        used |= candidate
    if not chosen:
        group = _classify(level, sorted(level.present, key=rank.__getitem__), order_support)
        if group is not None:
            chosen.append(group)
    return chosen


def _closure(
    pair: tuple[int, int], spots: Mapping[int, Sequence[int]], sequences: Sequence[Sequence[int]], limit: int
) -> frozenset[int] | None:
    """:meth:`_Level.closure`, its spans grown one node at a time (``spots``: per node, its position in each
    sequence, -1 when absent)."""
    members = set(pair)
    frontier = list(pair)
    lo = [-1] * len(sequences)
    hi = [-1] * len(sequences)
    while frontier:
        node = frontier.pop()
        for d, p in enumerate(spots[node]):
            if p < 0:
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


def _classify(level: _Level, listed: list[int], order_support: int) -> Group | None:
    """The nodes ``listed`` (in rank order): a chain when one order fits every sequence, a clique when no
    order between two of them is established, else None."""
    chain = level.chain_order(listed)
    if chain is not None:
        return Group(chain, True)
    positions = level.positions(listed)
    facts: _OrderFacts
    if positions.shape[0] * len(listed) ** 2 <= _SMALL_CLASSIFY:
        facts = _ListFacts(positions.tolist())
    else:
        facts = _MatrixFacts(positions)
    if _topological(facts.successors, lambda i: i) is not None:
        mean = facts.mean_positions()
        order = _topological(facts.successors, lambda i: (mean[i], i))
        assert order is not None
        return Group(tuple(listed[i] for i in order), True)
    if facts.established(order_support):
        return None
    return Group(tuple(listed), False, _every_order(facts.complete_orders(), len(listed)))


_SMALL_CLASSIFY = 400
"""Up to this many sequences times members squared, :func:`_classify` reads the order evidence of a candidate
from lists (:class:`_ListFacts`), from there on as matrices (:class:`_MatrixFacts`): only the speed depends
on it (numpy's cost per call outweighs its speed per entry on a few dozen entries)."""


class _OrderFacts(abc.ABC):
    """What the sequences show about the order of some members (``positions[s, i]``: where sequence ``s``
    does member ``i``, -1: not at all; every member done by some sequence, as the nodes of a level are), as
    :func:`_classify` asks for it. Two forms answer alike: :class:`_ListFacts` and :class:`_MatrixFacts`.

    Attributes:
        successors: Member -> the members some sequence does after it (ascending).
    """

    successors: list[list[int]]

    @abc.abstractmethod
    def mean_positions(self) -> list[float]:
        """Mean relative position (0 to 1) of each member within the sequences performing it, summed in
        sequence order."""

    @abc.abstractmethod
    def established(self, order_support: int) -> bool:
        """Whether an order between two members is established
        (:func:`~supportive.learning.general.evidence.established_precedences`)."""

    @abc.abstractmethod
    def complete_orders(self) -> list[tuple[int, ...]]:
        """The order of the members in each sequence that performs them all."""


class _MatrixFacts(_OrderFacts):
    """:class:`_OrderFacts` read from the positions as a matrix."""

    def __init__(self, positions: IntMatrix) -> None:
        self._positions = positions
        self._before, self._together = position_pair_counts(positions)
        sources, targets = np.nonzero(self._before > 0)
        self.successors = [[] for _ in range(positions.shape[1])]
        for u, v in zip(sources.tolist(), targets.tolist(), strict=True):
            self.successors[u].append(v)

    def mean_positions(self) -> list[float]:
        """See :meth:`_OrderFacts.mean_positions`."""
        positions = self._positions
        present = positions >= 0
        performed = present.sum(axis=1)
        order = np.argsort(np.where(present, positions, positions.shape[1] + positions.max()), axis=1)
        place = np.empty_like(order)
        np.put_along_axis(place, order, np.arange(positions.shape[1])[None, :], axis=1)
        share = np.where(present, place / np.maximum(performed - 1, 1)[:, None], 0.0)
        total = np.cumsum(share, axis=0)[-1]  # one sequence after another, as a running sum would
        mean: list[float] = (total / present.sum(axis=0)).tolist()
        return mean

    def established(self, order_support: int) -> bool:
        """See :meth:`_OrderFacts.established`."""
        return bool(established_precedences(self._before, self._together, order_support).any())

    def complete_orders(self) -> list[tuple[int, ...]]:
        """See :meth:`_OrderFacts.complete_orders`."""
        complete = self._positions[(self._positions >= 0).all(axis=1)]
        return list(map(tuple, np.argsort(complete, axis=1).tolist()))


class _ListFacts(_OrderFacts):
    """:class:`_OrderFacts` read from the positions as lists, one sequence at a time."""

    def __init__(self, rows: list[list[int]]) -> None:
        self._rows = rows
        self._before, self._together = position_pair_counts_listed(rows, len(rows[0]) if rows else 0)
        self.successors = [[j for j, n in enumerate(counts) if n > 0] for counts in self._before]

    def mean_positions(self) -> list[float]:
        """See :meth:`_OrderFacts.mean_positions`."""
        size = len(self._rows[0])
        total = [0.0] * size
        performing = [0] * size
        for row in self._rows:
            done = sorted((p, i) for i, p in enumerate(row) if p >= 0)
            last = max(len(done) - 1, 1)
            for place, (_, i) in enumerate(done):
                total[i] += place / last
                performing[i] += 1
        return [t / n for t, n in zip(total, performing, strict=True)]

    def established(self, order_support: int) -> bool:
        """See :meth:`_OrderFacts.established`."""
        return establishes_any(self._before, self._together, order_support)

    def complete_orders(self) -> list[tuple[int, ...]]:
        """See :meth:`_OrderFacts.complete_orders`."""
        return [tuple(sorted(range(len(row)), key=row.__getitem__)) for row in self._rows if min(row) >= 0]


def _topological(successors: Sequence[Sequence[int]], key: Callable[[int], object]) -> list[int] | None:
    """The nodes ``0 … n-1`` of the graph ``successors`` (``successors[i]``: the nodes ``i`` has an edge to) in
    topological order, the ready node of smallest ``key`` first; None when the graph has a cycle."""
    indegree = [0] * len(successors)
    for targets in successors:
        for v in targets:
            indegree[v] += 1
    ready = [(key(i), i) for i, degree in enumerate(indegree) if degree == 0]
    heapq.heapify(ready)
    out: list[int] = []
    while ready:
        _, node = heapq.heappop(ready)
        out.append(node)
        for child in successors[node]:
            indegree[child] -= 1
            if indegree[child] == 0:
                heapq.heappush(ready, (key(child), child))
    return out if len(out) == len(indegree) else None


def _every_order(orders: Sequence[tuple[int, ...]], size: int) -> bool:
    """True when ``orders`` hold each of the ``size!`` orders of ``size`` members."""
    needed = 1
    for k in range(2, size + 1):
        needed *= k
        if needed > len(orders):
            return False
    return len(set(orders)) == needed


def _spliced(
    group: Group, groups: dict[int, Group], presence: dict[int, set[int]], weak: set[int], whole: set[int]
) -> Group:
    """Members that mean nothing of their own are replaced by their children: a chain in a chain performed
    whenever its siblings are (``whole``: the demonstrations performing any of them; both mean the same
    order; an optional sub-chain stays a node of its own), and a clique in a clique whose contiguity is not
    evidenced (``weak``: a clique of its own would claim it is never interleaved with its siblings)."""
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
