from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from supportive.errors import TaskModelError
from supportive.generate import Profile, random_structure
from supportive.learning.general.top_order import precedence_top_level
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Counts,
    Leaf,
    Node,
    TopLevel,
    admits,
    allowed_next,
    canonical,
    count_orderings,
    internal_nodes,
    iter_orderings,
    mean_action_depth,
    node_count,
    node_edges,
    sample_ordering,
    successor_pairs,
    to_leaves,
)

A, B, C, D = (ActionNode(x) for x in "abcd")


def test_counts_match_enumeration() -> None:
    node = CliqueNode((ChainNode((A, B)), CliqueNode((C, D))))
    orders = list(iter_orderings(node))
    assert count_orderings(node) == len(orders) == len(set(orders)) == 4
    assert all(admits(node, o) for o in orders)
    assert not admits(node, to_leaves("acbd"))


def test_clique_forbids_interleaving() -> None:
    node = CliqueNode((ChainNode((A, B)), ChainNode((C, D))))
    assert admits(node, to_leaves("abcd")) and admits(node, to_leaves("cdab"))
    assert not admits(node, to_leaves("acbd"))
    assert not admits(node, to_leaves("bacd"))


def test_big_counts_do_not_enumerate() -> None:
    node = CliqueNode(tuple(ActionNode(f"x{i}") for i in range(60)))
    assert count_orderings(node) == math.factorial(60)


def test_canonical_merges_chain_in_chain_but_not_clique_in_clique() -> None:
    assert canonical(ChainNode((ChainNode((A, B)), C))) == canonical(ChainNode((A, B, C)))
    assert canonical(CliqueNode((CliqueNode((A, B)), C))) != canonical(CliqueNode((A, B, C)))
    assert canonical(CliqueNode((A, B))) == canonical(CliqueNode((B, A)))
    assert canonical(ChainNode((A, B))) != canonical(ChainNode((B, A)))


def test_sample_is_seeded_and_admitted() -> None:
    node = CliqueNode(tuple(ActionNode(f"x{i}") for i in range(8)))
    assert sample_ordering(node, 3) == sample_ordering(node, 3)
    assert len({sample_ordering(node, s) for s in range(20)}) > 10
    assert admits(node, sample_ordering(node, 5))


def test_repeated_actions_are_numbered() -> None:
    assert to_leaves(["stir", "pour", "stir"]) == (("stir", 1), ("pour", 1), ("stir", 2))
    assert ActionNode("stir", 2).label == "stir#2"


def test_sizes_and_depth() -> None:
    node = ChainNode((A, CliqueNode((B, C)), D))
    assert node_count(node) == 6
    assert node_edges(node) == 2 + 2  # chain: a -> clique -> d; clique: b and c to the clique node
    assert len(successor_pairs(node)) == 2 + 2 + 2  # a -> b, c; b <-> c; b, c -> d
    assert mean_action_depth([node]) == pytest.approx((1 + 2 + 2 + 1) / 4)
    assert HTN("t", (node,)).edge_count() == 4


def test_edges_of_chains_cliques_and_transitions_into_cliques() -> None:
    # §2.1.7.3: a clique of |V| subgoals needs |V|^2 - |V| flat edges but |V| in the CC-HTN
    for k in range(3, 12):
        clique = CliqueNode(tuple(ActionNode(f"x{i}") for i in range(k)))
        assert (node_edges(clique), len(successor_pairs(clique))) == (k, k * k - k)
        chain = ChainNode(tuple(ActionNode(f"x{i}") for i in range(k)))
        assert (node_edges(chain), len(successor_pairs(chain))) == (k - 1, k - 1)
    assert (node_edges(CliqueNode((A, B))), len(successor_pairs(CliqueNode((A, B))))) == (2, 2)
    assert node_edges(A) == len(successor_pairs(A)) == 0
    # each transition into or out of a clique: one edge instead of one per member
    e = ActionNode("e")
    node = ChainNode((A, CliqueNode((B, C, D)), e))
    assert len(successor_pairs(node)) == 3 + 6 + 3
    assert node_edges(node) == 2 + 3
    # a partial hierarchy adds its top-level transitions
    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 0, 1), (1, 1, 3), (0, 1, 2), (2, 0, 3)))
    assert HTN("t", (ChainNode((A, B)), C), top).edge_count() == 1 + 0 + 4


@given(st.integers(5, 60), st.integers(0, 10_000), st.sampled_from(["ikea", "uniform"]))
def test_cc_htn_never_needs_more_edges_than_the_flat_model(n: int, seed: int, profile: Profile) -> None:
    # Flat pairs of different internal nodes differ (their least common ancestor differs), and each node of
    # k >= 2 children has at least k - 1 (chain) or k(k - 1) >= k (clique) of them: never fewer than its edges.
    structure = random_structure(n, seed, profile=profile)
    htn = HTN("t", (structure,))
    edges, flat = htn.edge_count(), len(htn.successor_pairs())
    assert edges <= flat
    if any(isinstance(x, CliqueNode) and len(x.children) >= 3 for x in internal_nodes(structure)):
        assert edges < flat


@given(
    st.lists(st.tuples(st.integers(0, 4), st.integers(0, 3), st.integers(0, 4)), max_size=8),
    st.lists(st.integers(0, 4), max_size=3),
)
def test_top_levels_equal_as_languages_hash_alike_whatever_their_counts(
    edges: list[tuple[int, int, int]], terminal: list[int]
) -> None:
    """The hash is worked out once, from the fields compared (initial, terminal, edges): equal top levels
    hash equal, the counts and the free roots (not compared) play no part."""
    top = TopLevel(initial=(0,), terminal=tuple(terminal), edges=tuple(edges))
    other = TopLevel(initial=(0,), terminal=tuple(terminal), edges=tuple(list(edges)), free=frozenset({0}))
    assert top == other and hash(top) == hash(other) == hash(((0,), tuple(terminal), tuple(edges)))
    assert {top: 1}[other] == 1
    assert (TopLevel((0,), tuple(terminal), (*edges, (9, 0, 9))) == top) is False


def test_a_top_level_with_other_counts_is_the_same_language_sharing_its_successors() -> None:
    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 0, 1), (1, 1, 3), (0, 1, 2), (2, 0, 3)), free=frozenset({1}))
    counts = Counts(first=(2, 1), after=((0, 2), (1, 0)))
    counted = top.with_counts(counts)
    assert counted == top and counted.counts == counts and top.counts is None and counted.free == top.free
    assert counted.successors() is top.successors() and hash(counted) == hash(top)
    assert counted.count_orderings() == top.count_orderings() == 2


def test_partial_htn_admits_through_its_top_level() -> None:
    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 0, 1), (1, 1, 3), (0, 1, 2), (2, 0, 3)))
    htn = HTN("t", (ChainNode((A, B)), C), top)
    assert not htn.complete
    assert htn.admits(["a", "b", "c"]) and htn.admits(["c", "a", "b"])
    assert not htn.admits(["a", "c", "b"]) and not htn.admits(["a", "b"])
    assert htn.count_orderings() == 2


def test_successor_pairs_match_enumeration() -> None:
    node = ChainNode((A, CliqueNode((ChainNode((B, C)), D)), ActionNode("e")))
    seen: set[tuple[Leaf, Leaf]] = set()
    for order in iter_orderings(node):
        seen.update(itertools.pairwise(order))
    assert successor_pairs(node) == seen
    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 0, 1), (1, 1, 3), (0, 1, 2), (2, 0, 3)))
    htn = HTN("t", (ChainNode((A, B)), C), top)
    assert htn.successor_pairs() == {(("a", 1), ("b", 1)), (("b", 1), ("c", 1)), (("c", 1), ("a", 1))}


@given(st.integers(3, 9), st.integers(0, 10_000), st.sampled_from(["ikea", "uniform"]))
def test_allowed_next_matches_enumeration(n: int, seed: int, profile: Profile) -> None:
    from supportive.generate import random_structure

    structure = random_structure(n, seed, profile=profile)
    orders = list(iter_orderings(structure))
    prefix_next: dict[frozenset[tuple[str, int]], set[tuple[str, int]]] = {}
    for order in orders:
        for k in range(len(order) + 1):
            prefix_next.setdefault(frozenset(order[:k]), set()).update(order[k : k + 1])
    for order in orders[:20]:
        for k in range(len(order) + 1):
            assert allowed_next(structure, order[:k]) == prefix_next[frozenset(order[:k])]


def test_allowed_next_rejects_invalid_prefixes() -> None:
    with pytest.raises(ValueError, match="later part"):
        allowed_next(ChainNode((A, B, C)), [("b", 1)])
    with pytest.raises(ValueError, match="under way"):
        allowed_next(CliqueNode((ChainNode((A, B)), ChainNode((C, D)))), [("a", 1), ("c", 1)])


def _root(draw: st.DrawFn, name: str) -> Node:
    """A small root over actions named ``name…``: an action, or a chain or clique of two or three, any of them
    optional, so some roots may be performed as nothing though not optional themselves."""
    kind = draw(st.sampled_from(["action", "chain", "clique"]))
    if kind == "action":
        return ActionNode(name, optional=draw(st.booleans()))
    children = tuple(ActionNode(f"{name}{i}", optional=draw(st.booleans())) for i in range(draw(st.integers(2, 3))))
    node = ChainNode(children) if kind == "chain" else CliqueNode(children)
    return replace(node, optional=draw(st.booleans()))


@st.composite
def partial_htns(draw: st.DrawFn) -> HTN:
    """Two to four roots and a top level of root orders: each order a path through the sets of roots done
    (orders sharing a set share its state), ending where an order ends."""
    roots = tuple(_root(draw, name) for name in "pqrs"[: draw(st.integers(2, 4))])
    number: dict[frozenset[int], int] = {frozenset(): 0}
    edges: set[tuple[int, int, int]] = set()
    terminal: set[int] = set()
    for _ in range(draw(st.integers(1, 5))):
        order = draw(st.permutations(range(len(roots))))[: draw(st.integers(1, len(roots)))]
        done: frozenset[int] = frozenset()
        for root in order:
            after = done | {root}
            number.setdefault(after, len(number))
            edges.add((number[done], root, number[after]))
            done = after
        terminal.add(number[done])
    return HTN("t", roots, TopLevel(initial=(0,), terminal=tuple(sorted(terminal)), edges=tuple(sorted(edges))))


def _paths(top: TopLevel, state: int) -> Iterator[tuple[int, ...]]:
    if state in top.terminal:
        yield ()
    for root, dst in top.successors().get(state, {}).items():
        for rest in _paths(top, dst):
            yield (root, *rest)


def test_a_required_root_that_may_be_performed_as_nothing_adds_the_orders_without_it() -> None:
    maybe = CliqueNode((ActionNode("b", optional=True), ActionNode("c", optional=True)))  # required, nullable
    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 0, 1), (1, 1, 3), (0, 1, 2), (2, 0, 3)))
    htn = HTN("t", (A, maybe), top)
    # a alone (the clique performed as nothing, before or after it: once), and a before or after b, c, bc, cb
    assert htn.count_orderings() == 1 + 2 * 4


@st.composite
def partial_order_htns(draw: st.DrawFn) -> HTN:
    """Two to four roots under the general learner's partial order of roots (seen orders of some of them, the
    rest skippable): its ``free`` hint names the roots whose silent passage the count may leave out."""
    roots = tuple(_root(draw, name) for name in "pqrs"[: draw(st.integers(2, 4))])
    orders = [
        list(draw(st.permutations(range(len(roots))))[: draw(st.integers(1, len(roots)))])
        for _ in range(draw(st.integers(1, 6)))
    ]
    required = frozenset.intersection(*(frozenset(order) for order in orders))
    top = precedence_top_level(
        range(len(roots)),
        orders,
        required,
        order_support=draw(st.integers(1, 3)),
        order_penalty=draw(st.sampled_from([None, 0.0, 1.0, 3.0])),
    )
    return HTN("t", roots, top)


@settings(max_examples=300, deadline=None)
@given(htn=st.one_of(partial_htns(), partial_order_htns()))
def test_a_partial_htn_counts_each_leaf_sequence_once(htn: HTN) -> None:
    """Brute force: every path of the top level, each root on it performed in each of its ways (as nothing
    too, when it may be), the distinct leaf sequences counted; a root performed as nothing on one path gives
    what another path gives, and counts once."""
    assert htn.top_level is not None
    sequences = {
        tuple(leaf for part in parts for leaf in part)
        for path in _paths(htn.top_level, htn.top_level.initial[0])
        for parts in itertools.product(*(set(iter_orderings(htn.roots[r])) for r in path))
    }
    assert htn.count_orderings() == len(sequences)


def test_a_top_level_with_a_cycle_is_refused_when_roots_pass_silently() -> None:
    looping = TopLevel(initial=(0,), terminal=(1,), edges=((0, 0, 1), (1, 1, 0)))
    with pytest.raises(TaskModelError, match="cycle"):
        looping.count_orderings(None, [1])


@settings(max_examples=200, deadline=None)
@given(htn=st.one_of(partial_htns(), partial_order_htns()))
def test_the_required_leaves_are_those_every_admitted_sequence_performs(htn: HTN) -> None:
    """Brute force: the leaves common to every leaf sequence of every path of the top level."""
    assert htn.top_level is not None
    sequences = [
        {leaf for part in parts for leaf in part}
        for path in _paths(htn.top_level, htn.top_level.initial[0])
        for parts in itertools.product(*(set(iter_orderings(htn.roots[r])) for r in path))
    ]
    assert set(htn.required_leaves) == set.intersection(*sequences)
    assert HTN("t", (htn.roots[0],)).required_leaves == tuple(
        leaf for leaf in htn.roots[0].leaves if all(leaf in s for s in map(set, iter_orderings(htn.roots[0])))
    )
