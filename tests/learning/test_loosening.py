"""The least loosening of a hierarchy that admits a step out of place, against brute force: every subtask
holding the step tried from the lowest up, each judged by enumerating the flattened hierarchy's orders."""

from __future__ import annotations

import itertools

from hypothesis import assume, given
from hypothesis import strategies as st
from tests.tasks.test_executions import structures

from supportive.learning.general.loosening import flattened, loosened_for
from supportive.tasks.htn import HTN, ActionNode, ChainNode, CliqueNode, Leaf, Node, canonical, iter_orderings


def holding(node: Node, leaf: Leaf) -> list[Node]:
    """The internal nodes holding ``leaf``, from ``node`` down."""
    if isinstance(node, ActionNode) or leaf not in node.leaves:
        return []
    return [node, *(n for child in node.children for n in holding(child, leaf))]


def swapped(node: Node, old: Node, new: Node) -> Node:
    if node is old:
        return new
    if isinstance(node, ActionNode):
        return node
    kind = ChainNode if isinstance(node, ChainNode) else CliqueNode
    return kind(tuple(swapped(child, old, new) for child in node.children), optional=node.optional)


def moved(order: tuple[Leaf, ...], source: int, target: int) -> tuple[Leaf, ...]:
    steps = list(order)
    steps.insert(target, steps.pop(source))
    return tuple(steps)


@given(structures())
def test_a_flattened_subtask_admits_its_orders_and_every_rearrangement_of_them(structure: Node) -> None:
    flat = flattened(structure)
    admitted = set(iter_orderings(flat))
    for order in iter_orderings(structure):
        assert set(itertools.permutations(order)) <= admitted
    assert all(isinstance(child, ActionNode) for child in getattr(flat, "children", ()))
    assert sorted(flat.leaves) == sorted(structure.leaves)


@given(structures(), st.data())
def test_the_lowest_subtask_whose_flattening_admits_a_moved_step_is_the_one_flattened(
    structure: Node, data: st.DataObject
) -> None:
    orders = list(iter_orderings(structure))
    order = data.draw(st.sampled_from(orders))
    assume(len(order) >= 2)
    source = data.draw(st.integers(0, len(order) - 1))
    target = data.draw(st.integers(0, len(order) - 1))
    demonstration, leaf = moved(order, source, target), order[source]
    htn = HTN("t", (structure,))

    expected: Node | None = structure if demonstration in orders else None
    for node in reversed(holding(structure, leaf)) if expected is None else ():
        candidate = swapped(structure, node, flattened(node))
        if demonstration in set(iter_orderings(candidate)):
            expected = candidate
            break

    found = loosened_for(htn, [(demonstration, leaf)])
    if expected is None:
        assert found is None
    else:
        assert found is not None and canonical(found.roots[0]) == canonical(expected)
        assert found.admits_leaves(demonstration)
        assert set(orders) <= set(iter_orderings(found.roots[0]))  # looser: it admits all it admitted


def test_a_step_no_root_holds_has_no_loosening_and_the_root_is_the_last_resort() -> None:
    chain = ChainNode((ActionNode("a"), ActionNode("b")))
    htn = HTN("t", (ChainNode((chain, ActionNode("c"))),))
    assert loosened_for(htn, [((("b", 1), ("a", 1), ("c", 1)), ("x", 1))]) is None
    # c moved first: only the root holds c, so the root is flattened, and b before a comes with it
    found = loosened_for(htn, [((("c", 1), ("a", 1), ("b", 1)), ("c", 1))])
    assert found is not None and found.admits_leaves((("c", 1), ("b", 1), ("a", 1)))
    # a moved after b: the inner chain is enough, c stays last
    found = loosened_for(htn, [((("b", 1), ("a", 1), ("c", 1)), ("a", 1))])
    assert found is not None and not found.admits_leaves((("c", 1), ("b", 1), ("a", 1)))
    assert found.admits_leaves((("b", 1), ("a", 1), ("c", 1)))
