"""The three invariants of every learned HTN (DESIGN.md), as hypothesis properties over random structures."""

from __future__ import annotations

import itertools
from collections.abc import Iterator

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

from supportive.learning import HTNLearner, invariant_violations
from supportive.learning.learner import Mode
from supportive.tasks.htn import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Leaf,
    Node,
    canonical,
    count_orderings,
    iter_orderings,
    sample_ordering,
)

Shape = str | tuple[str, list["Shape"]]

shapes: st.SearchStrategy[Shape] = st.recursive(
    st.just("leaf"),
    lambda inner: st.tuples(st.sampled_from(["chain", "clique"]), st.lists(inner, min_size=2, max_size=3)),
    max_leaves=7,
)


def build(shape: Shape, names: Iterator[str]) -> Node:
    """A normalised structure: no chain directly in a chain."""
    if isinstance(shape, str):
        return ActionNode(next(names))
    kind, parts = shape
    children: list[Node] = []
    for part in parts:
        child = build(part, names)
        if kind == "chain" and isinstance(child, ChainNode):
            children.extend(child.children)
        else:
            children.append(child)
    return ChainNode(tuple(children)) if kind == "chain" else CliqueNode(tuple(children))


@st.composite
def structures(draw: st.DrawFn, max_orderings: int = 1500) -> Node:
    shape = draw(shapes)
    assume(shape != "leaf")
    node = build(shape, (f"a{i}" for i in itertools.count()))
    assume(count_orderings(node) <= max_orderings)
    return node


def actions(leaves: tuple[Leaf, ...]) -> list[str]:
    return [a for a, _ in leaves]


def internal_nodes(node: Node) -> Iterator[Node]:
    if not isinstance(node, ActionNode):
        yield node
        for child in node.children:
            yield from internal_nodes(child)


def assert_invariants_1_and_2(learner: HTNLearner) -> None:
    """An enumeration oracle, independent of :func:`invariant_violations` (which must agree with it)."""
    htn: HTN = learner.htn_
    graph = learner.task_graph_
    assert invariant_violations(graph, htn) == []
    for demo in graph.demonstrations:
        assert htn.admits_leaves([graph.subgoals[s] for s in demo]), (
            "invariant 1: a demonstration is rejected"
        )
    executions = list(graph.iter_paths())
    assert len(executions) == graph.path_count()
    for root in htn.roots:
        for node in internal_nodes(root):
            members = set(node.leaves)
            for execution in executions:
                positions = [i for i, leaf in enumerate(execution) if leaf in members]
                assert positions == list(range(positions[0], positions[0] + len(members))), (
                    f"invariant 2: {node} is interleaved in {execution}"
                )
    for execution in executions:
        assert htn.admits_leaves(execution), "every known execution is admitted"


MODES = st.sampled_from(["general", "strict"])


@given(structures(), MODES)
def test_all_orderings_recover_the_structure(structure: Node, mode: Mode) -> None:
    demos = [actions(o) for o in iter_orderings(structure)]
    # the general learner makes subtasks from subtask_demonstrations demonstrations on (or of a single one)
    assume(mode == "strict" or len(demos) >= HTNLearner().subtask_demonstrations or len(demos) == 1)
    learner = HTNLearner(mode=mode).fit(demos)
    assert learner.task_graph_.path_count() == count_orderings(structure)
    assert learner.htn_.complete
    assert canonical(learner.htn_.roots[0]) == canonical(structure), "invariant 3"
    assert learner.htn_.count_orderings() == count_orderings(structure)
    assert invariant_violations(learner.task_graph_, learner.htn_, structure) == []
    assert_invariants_1_and_2(learner)


@given(structures(), st.integers(1, 5), st.integers(0, 2**32 - 1), MODES)
def test_sampled_demonstrations_keep_invariants(structure: Node, k: int, seed: int, mode: Mode) -> None:
    rng = np.random.default_rng(seed)
    demos = [actions(sample_ordering(structure, rng)) for _ in range(k)]
    learner = HTNLearner(mode=mode).fit(demos)
    assert_invariants_1_and_2(learner)
    for alternative in learner.htn_.alternatives:  # the general learner's: tests/learning/test_wings.py
        assert alternative.complete
        if mode == "strict":  # a restriction: every execution it admits is known
            assert all(learner.task_graph_.contains(actions(o)) for o in iter_orderings(alternative.roots[0]))


@given(st.lists(st.permutations(["a", "b", "c", "d", "e"]), min_size=1, max_size=8), MODES)
def test_arbitrary_permutations_keep_invariants(demos: list[list[str]], mode: Mode) -> None:
    assert_invariants_1_and_2(HTNLearner(mode=mode, slips=False).fit(demos))


@given(structures(max_orderings=300), st.integers(0, 2**32 - 1), st.integers(1, 6), MODES)
def test_partial_fit_equals_fit(structure: Node, seed: int, k: int, mode: Mode) -> None:
    rng = np.random.default_rng(seed)
    demos = [actions(sample_ordering(structure, rng)) for _ in range(k)]
    incremental = HTNLearner(mode=mode)
    for demo in demos:
        incremental.partial_fit(demo)
        batch = HTNLearner(mode=mode).fit(demos[: len(incremental.task_graph_.demonstrations)])
        assert incremental.htn_.canonical() == batch.htn_.canonical()
        assert incremental.htn_.top_level == batch.htn_.top_level
        assert incremental.ctg_.n_edges == batch.ctg_.n_edges
        assert incremental.stats_.task_graph == batch.stats_.task_graph


def test_violations_are_reported() -> None:
    learner = HTNLearner(mode="strict").fit([list("abcd"), list("acbd")])
    graph = learner.task_graph_
    interleaved = HTN(
        "t", (ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("d"))), ActionNode("c"))),)
    )
    problems = invariant_violations(graph, interleaved)
    assert any(p.startswith("invariant 1") for p in problems)
    assert any(p.startswith("invariant 2") for p in problems)
    flat = HTN("t", (CliqueNode(tuple(ActionNode(x) for x in "abcd")),))
    structure = ChainNode((ActionNode("a"), CliqueNode((ActionNode("b"), ActionNode("c"))), ActionNode("d")))
    assert invariant_violations(graph, flat, structure) == [
        "invariant 3: all valid orderings are known but the structure was not recovered"
    ]
