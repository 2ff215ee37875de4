"""Normal form: same orderings, two or more children everywhere, no chain in a chain."""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive.generate import GenerationError, is_normalised, normalise
from supportive.tasks.htn import ActionNode, ChainNode, CliqueNode, Node, count_orderings, iter_orderings

Shape = str | tuple[str, list["Shape"]]

# Any nesting, one-child nodes and chains in chains included.
shapes: st.SearchStrategy[Shape] = st.recursive(
    st.just("leaf"),
    lambda inner: st.tuples(st.sampled_from(["chain", "clique"]), st.lists(inner, min_size=1, max_size=3)),
    max_leaves=6,
)


def build(shape: Shape, names: Iterator[str]) -> Node:
    if isinstance(shape, str):
        return ActionNode(next(names))
    kind, parts = shape
    children = tuple(build(part, names) for part in parts)
    return ChainNode(children) if kind == "chain" else CliqueNode(children)


@given(shape=shapes)
def test_normalise_keeps_orderings_and_reaches_normal_form(shape: Shape) -> None:
    node = build(shape, (f"a{i}" for i in itertools.count()))
    flat = normalise(node)
    assert is_normalised(flat)
    assert count_orderings(flat) == count_orderings(node)
    assert set(iter_orderings(flat)) == set(iter_orderings(node))
    assert normalise(flat) == flat


def test_chain_in_chain_is_spliced_and_single_children_vanish() -> None:
    a, b, c, d = (ActionNode(x) for x in "abcd")
    node = ChainNode((a, ChainNode((b, CliqueNode((ChainNode((c,)),)))), d), "top")
    flat = normalise(node)
    assert flat == ChainNode((a, b, c, d))
    assert isinstance(flat, ChainNode) and flat.name == "top"
    assert not is_normalised(node)


def test_clique_in_clique_is_kept() -> None:
    a, b, c = (ActionNode(x) for x in "abc")
    node = CliqueNode((CliqueNode((a, b)), c))
    assert normalise(node) == node
    assert is_normalised(node)
    assert count_orderings(node) == 4  # not 6: a and b are never split by c


def test_empty_node_is_an_error() -> None:
    with pytest.raises(GenerationError, match="no children"):
        normalise(ChainNode((ActionNode("a"), CliqueNode(()))))
    assert not is_normalised(CliqueNode(()))
