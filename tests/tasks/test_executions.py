"""The executions automaton against independent oracles: the recursive enumeration of a structure's
sequences (``iter_orderings``) and brute force over every sequence of its leaves, with optional nodes."""

from __future__ import annotations

import itertools
from collections import Counter
from collections.abc import Callable, Iterator, Sequence
from typing import TypeVar

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

from supportive.tasks.executions import Executions
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    Node,
    count_orderings,
    first_leaves,
    iter_orderings,
    last_leaves,
    sample_ordering,
    successor_pairs,
)

T = TypeVar("T")
StepT = TypeVar("StepT", str, tuple[str, int])

Shape = str | tuple[str, bool, list["Shape"]]

shapes: st.SearchStrategy[Shape] = st.recursive(
    st.sampled_from(["leaf", "optional"]),
    lambda inner: st.tuples(
        st.sampled_from(["chain", "clique"]), st.booleans(), st.lists(inner, min_size=2, max_size=3)
    ),
    max_leaves=5,
)


def build(shape: Shape, names: Iterator[str]) -> Node:
    if isinstance(shape, str):
        return ActionNode(next(names), optional=shape == "optional")
    kind, optional, parts = shape
    children = tuple(build(part, names) for part in parts)
    return (ChainNode if kind == "chain" else CliqueNode)(children, optional=optional)


@st.composite
def structures(draw: st.DrawFn) -> Node:
    shape = draw(shapes)
    return build(shape, (f"a{i}" for i in itertools.count()))


def every_sequence(leaves: tuple[Leaf, ...]) -> Iterator[tuple[Leaf, ...]]:
    for size in range(len(leaves) + 1):
        for subset in itertools.combinations(leaves, size):
            yield from itertools.permutations(subset)


@given(structures())
def test_language_agrees_with_enumeration_and_brute_force(structure: Node) -> None:
    enumerated = list(iter_orderings(structure))
    assert len(enumerated) == len(set(enumerated)) == count_orderings(structure)
    machine = Executions(HTN("t", (structure,)))
    admitted = {s for s in every_sequence(structure.leaves) if machine.accepts_leaves(s)}
    assert admitted == set(enumerated)
    assert machine.accepts([a for a, _ in enumerated[0]])  # action ids too


@given(structures())
def test_first_last_and_successors_match_the_language(structure: Node) -> None:
    sequences = [s for s in iter_orderings(structure) if s]
    assume(sequences)
    assert first_leaves(structure) == {s[0] for s in sequences}
    assert last_leaves(structure) == {s[-1] for s in sequences}
    assert successor_pairs(structure) == {pair for s in sequences for pair in itertools.pairwise(s)}


@given(structures(), st.integers(0, 2**32 - 1))
def test_moves_are_the_next_leaves_of_admitted_sequences(structure: Node, seed: int) -> None:
    machine = Executions(HTN("t", (structure,)))
    sequences = list(iter_orderings(structure))
    target = sequences[seed % len(sequences)]
    states = machine.initial()
    for k in range(len(target) + 1):
        prefix = target[:k]
        expected = {s[k] for s in sequences if s[:k] == prefix and len(s) > k}
        (state,) = states
        assert {machine.leaves[i] for i in machine.moves(state)} == expected
        assert machine.can_finish(state) == (prefix in set(sequences))
        if k < len(target):
            states = (machine.moves(state)[machine.index[target[k]]],)


def test_sampling_is_uniform_over_the_language() -> None:
    node = CliqueNode((ActionNode("a"), ActionNode("b", optional=True), ActionNode("c", optional=True)))
    rng = np.random.default_rng(3)
    counts = Counter(sample_ordering(node, rng) for _ in range(11_000))
    assert set(counts) == set(iter_orderings(node)) and len(counts) == 11
    assert max(counts.values()) - min(counts.values()) < 220  # about 1000 each


def test_repeated_instances_are_matched_by_context() -> None:
    leg = [
        ChainNode((ActionNode("pick", k), ActionNode("align", k, optional=True), ActionNode("spin", k)))
        for k in (1, 2)
    ]
    machine = Executions(HTN("t", (CliqueNode(tuple(leg)),)))
    assert machine.accepts(["pick", "spin", "pick", "align", "spin"])  # the first leg skips its align
    assert not machine.accepts(["pick", "pick", "align", "spin", "spin"])  # legs are never interleaved
    assert not machine.accepts(["pick", "spin", "pick", "spin", "pick", "spin"])  # only two legs


def test_partial_hierarchy_follows_its_top_level() -> None:
    from supportive.tasks.htn import TopLevel

    a, b, c = ActionNode("a"), ActionNode("b"), ActionNode("c", optional=True)
    top = TopLevel(initial=(0,), terminal=(2, 3), edges=((0, 0, 1), (1, 1, 2), (2, 2, 3)))
    htn = HTN("t", (a, b, c), top)
    assert htn.admits(["a", "b"]) and htn.admits(["a", "b", "c"])
    assert not htn.admits(["b", "a"]) and not htn.admits(["a"])
    assert htn.count_orderings() == 2


def moves_by_brute_force(admits: Callable[[Sequence[T]], bool], steps: list[T]) -> list[int]:
    """Positions whose step, moved anywhere else, makes ``steps`` admitted: every move tried."""
    out = []
    for i, step in enumerate(steps):
        rest = steps[:i] + steps[i + 1 :]
        if any(admits([*rest[:j], step, *rest[j:]]) for j in range(len(rest) + 1) if j != i):
            out.append(i)
    return out


@given(structures(), st.data())
def test_single_moves_agree_with_trying_every_move(structure: Node, data: st.DataObject) -> None:
    htn = HTN("t", (structure,))
    valid = data.draw(st.sampled_from(list(iter_orderings(structure))))
    leaves = [
        *valid,
        *data.draw(st.lists(st.sampled_from(structure.leaves), max_size=1)),
    ]  # maybe one step more
    for _ in range(data.draw(st.integers(0, 2)) if leaves else 0):  # and zero to two steps moved
        step = leaves.pop(data.draw(st.integers(0, len(leaves) - 1)))
        leaves.insert(data.draw(st.integers(0, len(leaves))), step)
    actions = [action for action, _ in leaves]
    for steps, expected in (
        (leaves, moves_by_brute_force(htn.admits_leaves, leaves)),
        (actions, moves_by_brute_force(htn.admits, actions)),
    ):
        assert list(htn.executions.single_moves(steps, range(len(steps)))) == expected
        assert list(htn.executions.single_moves(steps, reversed(range(len(steps))))) == expected[::-1]


def merges(steps: Sequence[T], inserted: Sequence[T]) -> Iterator[tuple[tuple[int, ...], list[T]]]:
    """Every way of doing ``inserted`` among ``steps`` (their order kept), with the order the search tries them
    in: place by place, a step of ``inserted`` (by index) before the next of ``steps``."""
    if not inserted and not steps:
        yield (), []
        return
    for i, step in enumerate(inserted):
        for key, rest in merges(steps, [*inserted[:i], *inserted[i + 1 :]]):
            yield (i, *key), [step, *rest]
    if steps:
        for key, rest in merges(steps[1:], inserted):
            yield (len(inserted), *key), [steps[0], *rest]


@given(structures(), st.data())
def test_insertions_agree_with_trying_every_place(structure: Node, data: st.DataObject) -> None:
    htn = HTN("t", (structure,))
    leaves = list(data.draw(st.sampled_from(list(iter_orderings(structure)))))
    assume(leaves)
    left_out = [leaves.pop(data.draw(st.integers(0, len(leaves) - 1))) for _ in range(min(2, len(leaves)))]
    if data.draw(st.booleans()) and len(leaves) > 1:  # sometimes no place will do
        leaves.insert(data.draw(st.integers(0, len(leaves) - 1)), leaves.pop())
    inserted = data.draw(st.sampled_from([left_out, left_out[:1], [left_out[0], *structure.leaves[:1]]]))
    _assert_first_insertions(htn, htn.admits_leaves, leaves, inserted)
    _assert_first_insertions(htn, htn.admits, [action for action, _ in leaves], [action for action, _ in inserted])


def _assert_first_insertions(
    htn: HTN, admits: Callable[[Sequence[StepT]], bool], steps: list[StepT], extra: list[StepT]
) -> None:
    found = sorted(((key, merged) for key, merged in merges(steps, extra) if admits(merged)), key=lambda m: m[0])
    assert htn.executions.with_insertions(steps, extra) == (found[0][1] if found else None)


def test_single_moves_follow_the_top_level() -> None:
    from supportive.tasks.htn import TopLevel

    top = TopLevel(initial=(0,), terminal=(3,), edges=((0, 0, 1), (1, 1, 2), (2, 2, 3)))
    htn = HTN("t", (ActionNode("a"), ActionNode("b"), ActionNode("c")), top)
    assert list(htn.executions.single_moves(["b", "c", "a"], range(3))) == [2]  # a to the front
    assert list(htn.executions.single_moves(["b", "a", "c"], range(3))) == [0, 1]  # a swap: either step
    assert list(htn.executions.single_moves(["c", "b", "a"], range(3))) == []  # two steps out of place
