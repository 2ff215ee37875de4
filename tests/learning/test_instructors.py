from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Sequence
from unittest import mock

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from supportive import examples
from supportive.errors import LearningError
from supportive.generate import random_structure
from supportive.learning import HTNLearner, instructors
from supportive.learning.instructors import (
    PartialOrder,
    SimulatedInstructor,
    demonstrate,
    pooled_learner,
    pooled_task_graph,
)
from supportive.tasks.htn import (
    ActionNode,
    ChainNode,
    CliqueNode,
    Node,
    admits,
    allowed_next,
    sample_ordering,
    to_leaves,
)
from supportive.tasks.spec import Demonstration, Step
from supportive.tasks.task_graph import TaskGraph


def _structure(name: str) -> Node:
    structure = examples.load(name).structure
    assert structure is not None
    return structure


def _valid(structure: Node, actions: list[str]) -> bool:
    return admits(structure, to_leaves(actions))


def _run(person: SimulatedInstructor, queries: dict[int, str]) -> list[str]:
    """One demonstration with ``queries[k]`` asked before step k (0-based)."""
    person.begin_demonstration()
    done: list[str] = []
    while (action := person.next_action(tuple(done), queries.get(len(done)))) is not None:
        done.append(action)
    return done


def _shortest(structure: Node, done: list[str], action: str) -> int | None:
    """Brute force: fewest steps (the action included) until ``action``'s next performance, by BFS."""
    start = to_leaves(done)
    target = (action, done.count(action) + 1)
    if target not in structure.leaves:
        return None
    frontier, depth, seen = [start], 0, {frozenset(start)}
    while frontier:
        depth += 1
        following = []
        for prefix in frontier:
            counts = Counter(a for a, _ in prefix)
            for leaf in allowed_next(structure, prefix):
                if leaf[1] != counts[leaf[0]] + 1:
                    continue
                if leaf == target:
                    return depth
                key = frozenset((*prefix, leaf))
                if key not in seen:
                    seen.add(key)
                    following.append((*prefix, leaf))
        frontier = following
    raise AssertionError("target unreachable")


def _relabel(node: Node, names: dict[str, str]) -> Node:
    if isinstance(node, ActionNode):
        return ActionNode(names[node.action])
    children = tuple(_relabel(child, names) for child in node.children)
    return ChainNode(children) if isinstance(node, ChainNode) else CliqueNode(children)


def _with_occurrences(node: Node, seen: dict[str, int]) -> Node:
    """Number repeated actions depth first (the order a chain forces)."""
    if isinstance(node, ActionNode):
        seen[node.action] = seen.get(node.action, 0) + 1
        return ActionNode(node.action, seen[node.action])
    children = tuple(_with_occurrences(child, seen) for child in node.children)
    return ChainNode(children) if isinstance(node, ChainNode) else CliqueNode(children)


structures = st.builds(
    random_structure,
    st.integers(1, 8),
    st.integers(0, 10_000),
    profile=st.sampled_from(["ikea", "uniform"]),
)


@st.composite
def repeated_structures(draw: st.DrawFn) -> Node:
    """Two random sub-tasks in a chain, the second reusing some of the first's actions (done twice)."""
    first = draw(structures)
    second = draw(structures)
    first_actions = sorted({a for a, _ in first.leaves})
    second_actions = sorted({a for a, _ in second.leaves})
    reuse = draw(st.lists(st.booleans(), min_size=len(second_actions), max_size=len(second_actions)))
    names = {
        a: first_actions[i] if again and i < len(first_actions) else f"z{i}"
        for i, (a, again) in enumerate(zip(second_actions, reuse, strict=True))
    }
    return _with_occurrences(ChainNode((first, _relabel(second, names))), {})


# ---------------------------------------------------------------- invariants


@given(structures, st.integers(0, 2**31), st.floats(0, 1))
def test_preferred_path_is_a_valid_ordering_and_demonstrated_as_is(
    structure: Node, seed: int, perturbation: float
) -> None:
    person = SimulatedInstructor(structure, perturbation=perturbation, seed=seed)
    assert _valid(structure, list(person.preferred_path))
    assert person.preferred_leaves == to_leaves(person.preferred_path)
    assert demonstrate(person) == list(person.preferred_path)


@given(st.one_of(structures, repeated_structures()), st.integers(0, 2**31), st.data())
def test_demonstrations_with_random_queries_are_valid(
    structure: Node, seed: int, data: st.DataObject
) -> None:
    person = SimulatedInstructor(structure, perturbation=0.5, seed=seed)
    actions = [*sorted({a for a, _ in structure.leaves}), "not-in-task"]
    n = len(structure.leaves)
    for _ in range(3):
        queries = data.draw(st.dictionaries(st.integers(0, n - 1), st.sampled_from(actions), max_size=4))
        assert _valid(structure, _run(person, queries))


@given(st.one_of(structures, repeated_structures()), st.integers(0, 2**31), st.data())
def test_heeded_query_is_performed_at_the_earliest_allowable_time(
    structure: Node, seed: int, data: st.DataObject
) -> None:
    base = [a for a, _ in sample_ordering(structure, seed)]  # any valid base path
    person = SimulatedInstructor(structure, base, seed=seed)
    n = len(structure.leaves)
    at = data.draw(st.integers(0, n - 1))
    query = data.draw(st.sampled_from(sorted({a for a, _ in structure.leaves})))
    prefix = list(person.preferred_path[:at])
    steps = person.steps_to(prefix, query)
    assert steps == _shortest(structure, prefix, query)
    done = _run(person, {at: query})
    assert _valid(structure, done)
    assert done[:at] == prefix
    if steps is None:  # every performance already done: ignored
        assert done == list(person.preferred_path)
    elif steps <= person.horizon:
        # the queried performance comes exactly ``steps`` steps later, and never sooner is possible
        occurrence = prefix.count(query) + 1
        position = [i for i, a in enumerate(done) if a == query][occurrence - 1]
        assert position == at + steps - 1
        for k in range(at, position):  # no valid continuation reaches it sooner
            assert person.steps_to(done[:k], query) == position - k + 1
    else:
        assert done == list(person.preferred_path)


@given(structures, st.integers(0, 2**31))
def test_same_seed_same_path_and_answers(structure: Node, seed: int) -> None:
    a = SimulatedInstructor(structure, perturbation=0.6, seed=seed)
    b = SimulatedInstructor(structure, perturbation=0.6, seed=np.random.default_rng(seed))
    assert a.preferred_path == b.preferred_path
    rng = np.random.default_rng(seed)
    actions = sorted({x for x, _ in structure.leaves})
    queries = {int(k): actions[int(rng.integers(len(actions)))] for k in rng.integers(0, len(actions), 3)}
    assert _run(a, queries) == _run(b, queries)


@given(structures)
def test_no_perturbation_keeps_the_base_path(structure: Node) -> None:
    person = SimulatedInstructor(structure, perturbation=0.0, seed=1)
    assert person.preferred_path == tuple(a for a, _ in structure.leaves)


def test_perturbations_are_small_and_differ_between_instructors() -> None:
    tower = _structure("blocks-tower")
    base = [a for a, _ in tower.leaves]
    paths = {SimulatedInstructor(tower, seed=s).preferred_path for s in range(30)}
    assert len(paths) > 3
    for path in paths:
        assert path[0] == "red" and path[-1] == "blue"
        assert all(
            abs(path.index(a) - i) <= 1 for i, a in enumerate(base)
        )  # each block moves one place at most
    given_base = ["red", "black", "purple", "orange", "white", "green", "yellow", "blue"]
    assert SimulatedInstructor(tower, given_base, perturbation=0.0).preferred_path == tuple(given_base)


# ---------------------------------------------------------------- hand-checked block tasks

TOWER = ["red", "yellow", "green", "white", "orange", "purple", "black", "blue"]
V = ["red", "yellow", "blue", "purple", "green", "black", "white", "orange"]
TOWERS = ["yellow", "green", "white", "red", "blue", "purple", "black", "orange"]


def test_blocks_tower_queries() -> None:
    person = SimulatedInstructor(_structure("blocks-tower"), perturbation=0.0)
    assert list(person.preferred_path) == TOWER
    assert person.steps_to(["red"], "black") == 1
    assert _run(person, {1: "black"}) == [
        "red",
        "black",
        "yellow",
        "green",
        "white",
        "orange",
        "purple",
        "blue",
    ]
    assert person.steps_to([], "black") == 2  # red first
    assert _run(person, {0: "black"})[:2] == ["red", "black"]
    assert person.steps_to([], "blue") == 8  # ignored
    assert _run(person, {0: "blue"}) == TOWER
    assert person.steps_to(TOWER[:4], "blue") == 4  # orange, purple, black first: beyond the horizon
    assert _run(person, {4: "blue"}) == TOWER
    assert person.steps_to(TOWER[:5], "blue") == 3  # purple, black, then blue: heeded (and same as preferred)
    assert person.steps_to(["red"], "red") is None  # done already
    assert _run(person, {1: "red", 2: "not-a-block"}) == TOWER


def test_blocks_v_queries() -> None:
    person = SimulatedInstructor(_structure("blocks-v"), perturbation=0.0)
    assert list(person.preferred_path) == V
    # at the start green (row 3) needs red and all of row 2 first: 5 steps, ignored
    assert person.steps_to([], "green") == 5
    assert _run(person, {0: "green"}) == V
    assert person.steps_to(["red"], "black") == 4  # still beyond the horizon
    assert _run(person, {1: "black"}) == V
    # after red, yellow: blue and purple, then black: 3 steps, heeded
    assert person.steps_to(["red", "yellow"], "black") == 3
    assert _run(person, {2: "black"}) == [
        "red",
        "yellow",
        "blue",
        "purple",
        "black",
        "green",
        "white",
        "orange",
    ]
    assert person.steps_to(V[:4], "orange") == 3
    assert _run(person, {4: "orange"}) == [
        "red",
        "yellow",
        "blue",
        "purple",
        "green",
        "black",
        "orange",
        "white",
    ]


def test_blocks_towers_queries() -> None:
    person = SimulatedInstructor(_structure("blocks-towers"), perturbation=0.0)
    assert list(person.preferred_path) == TOWERS
    assert _run(person, {0: "blue"}) == [
        "red",
        "blue",
        "yellow",
        "green",
        "white",
        "purple",
        "black",
        "orange",
    ]
    assert _run(person, {0: "orange"}) == [
        "purple",
        "black",
        "orange",
        "yellow",
        "green",
        "white",
        "red",
        "blue",
    ]
    # after yellow its tower must be finished first
    assert person.steps_to(["yellow"], "purple") == 3
    assert _run(person, {1: "purple"}) == [
        "yellow",
        "green",
        "white",
        "purple",
        "black",
        "orange",
        "red",
        "blue",
    ]
    assert person.steps_to(["yellow"], "orange") == 5
    assert _run(person, {1: "orange"}) == TOWERS


def test_plan_persists_and_latest_heeded_query_wins() -> None:
    person = SimulatedInstructor(_structure("blocks-towers"), perturbation=0.0)
    person.begin_demonstration()
    assert person.next_action((), "orange") == "purple"
    assert person.next_action(("purple",), None) == "black"  # still on the way to orange
    assert person.next_action(("purple", "black"), None) == "orange"
    assert person.next_action(("purple", "black", "orange"), None) == "yellow"
    # a new heeded query replaces the pending plan; an ignored one leaves it
    assert person.next_action((), "orange") == "purple"
    assert person.next_action(("purple",), "blue") == "black"  # blue is 4 steps away: ignored
    assert person.next_action(("purple", "black"), None) == "orange"
    person.begin_demonstration()
    assert person.next_action((), "white") == "yellow"
    assert person.next_action(("yellow",), "green") == "green"
    assert person.next_action(("yellow", "green"), None) == "white"
    assert person.next_action(tuple(TOWERS), "red") is None


def test_horizon_is_a_parameter() -> None:
    v = _structure("blocks-v")
    assert _run(SimulatedInstructor(v, perturbation=0.0, horizon=5), {0: "green"})[:5] == [
        "red",
        "yellow",
        "blue",
        "purple",
        "green",
    ]
    assert _run(SimulatedInstructor(v, perturbation=0.0, horizon=0), {1: "purple"}) == V


def test_repeated_actions() -> None:
    a1, a2, a3 = ActionNode("a", 1), ActionNode("a", 2), ActionNode("a", 3)
    task = ChainNode((a1, CliqueNode((ActionNode("b"), a2, ActionNode("c"))), a3, ActionNode("d")))
    person = SimulatedInstructor(task, perturbation=0.0)
    assert person.preferred_path == ("a", "b", "a", "c", "a", "d")
    assert person.steps_to(["a"], "a") == 1  # its second performance
    assert _run(person, {1: "a"}) == ["a", "a", "b", "c", "a", "d"]
    assert person.steps_to(["a", "b", "a"], "a") == 2  # c, then the third a
    assert _run(person, {3: "a"}) == ["a", "b", "a", "c", "a", "d"]
    assert person.steps_to(["a"], "d") == 5
    assert person.steps_to(["a", "b", "a", "c", "a"], "a") is None
    for seed in range(20):
        other = SimulatedInstructor(task, perturbation=0.9, seed=seed)
        assert _valid(task, list(other.preferred_path))
        assert _valid(task, _run(other, {1: "c", 2: "a", 4: "d"}))


@pytest.mark.parametrize("name", ["blocks-tower", "blocks-v", "blocks-towers", "ikea-chair"])
def test_example_tasks(name: str) -> None:
    structure = _structure(name)
    actions = sorted({a for a, _ in structure.leaves})
    for seed in range(5):
        person = SimulatedInstructor(structure, seed=seed)
        assert _valid(structure, demonstrate(person))
        for k, query in enumerate(actions):
            assert _valid(structure, _run(person, {k % len(structure.leaves): query, 3: query}))


# ---------------------------------------------------------------- bad input


def test_bad_input_raises_learning_errors() -> None:
    tower = _structure("blocks-tower")
    with pytest.raises(LearningError, match="not a valid ordering"):
        SimulatedInstructor(tower, ["blue", *TOWER[1:-1], "red"])
    with pytest.raises(LearningError, match="perturbation"):
        SimulatedInstructor(tower, perturbation=1.5)
    with pytest.raises(LearningError, match="horizon"):
        SimulatedInstructor(tower, horizon=-1)
    person = SimulatedInstructor(tower)
    with pytest.raises(LearningError, match="not a valid prefix"):
        person.next_action(("yellow",), None)
    with pytest.raises(LearningError, match="not in the task"):
        person.next_action(("red", "pink"), None)
    with pytest.raises(LearningError, match="not in the task"):
        person.steps_to(["red", "red"], "blue")
    with pytest.raises(LearningError, match="not a valid prefix"):  # asked again: refused again, not remembered
        person.next_action(("yellow",), None)


def _fewest_steps(structure: Node, done: Sequence[str], action: str) -> int | None:
    """Brute force: in how many steps ``action``'s next performance can come after ``done`` (breadth first
    over every valid way on)."""
    leaves = to_leaves(done)
    target = (action, sum(a == action for a in done) + 1)
    if target not in structure.leaves:
        return None
    frontier, depth = {frozenset(leaves)}, 1
    while frontier:
        if any(target in allowed_next(structure, state) for state in frontier):
            return depth
        frontier = {state | {leaf} for state in frontier for leaf in allowed_next(structure, state)}
        depth += 1
    return None


@given(structures, st.integers(0, 2**31), st.data())
def test_answers_do_not_depend_on_what_was_asked_before(structure: Node, seed: int, data: st.DataObject) -> None:
    """The instructor remembers the prefixes she has checked (and forgets them past a bound): questions in
    any order, on a small memory passed many times over, and to a copy of her, get the brute-force answer."""
    person = SimulatedInstructor(structure, perturbation=0.5, seed=seed)
    path = list(person.preferred_path)
    actions = sorted(set(path))
    questions = [
        (path[: data.draw(st.integers(0, len(path)))], data.draw(st.sampled_from(actions))) for _ in range(8)
    ]
    expected = [_fewest_steps(structure, done, a) for done, a in questions]
    with mock.patch.object(instructors, "_PREFIXES_KEPT", 3):
        assert [person.steps_to(done, a) for done, a in questions] == expected
        assert len(person._prefixes) <= 3
    assert [person.steps_to(done, a) for done, a in questions] == expected
    assert [copy.copy(person).steps_to(done, a) for done, a in questions[::-1]] == expected[::-1]


# ---------------------------------------------------------------- pooling


def _team(name: str, size: int, demos: int = 4) -> list[HTNLearner]:
    structure = _structure(name)
    actions = sorted({a for a, _ in structure.leaves})
    learners = []
    for member in range(size):
        person = SimulatedInstructor(structure, seed=member)
        rng = np.random.default_rng(member)
        sequences = [demonstrate(person)]
        for _ in range(demos - 1):
            queries = {int(k): actions[int(rng.integers(len(actions)))] for k in (1, 3, 5)}
            sequences.append(_run(person, queries))
        learners.append(HTNLearner().fit(sequences))
    return learners


@pytest.mark.parametrize("name", ["blocks-tower", "blocks-v", "blocks-towers"])
def test_pooling_is_the_union(name: str) -> None:
    team = _team(name, 3)
    graph = pooled_task_graph([learner.task_graph_ for learner in team])
    pooled = pooled_learner(team)
    direct = HTNLearner().fit(
        [
            [learner.task_graph_.subgoals[s][0] for s in d]
            for learner in team
            for d in learner.task_graph_.demonstrations
        ]
    )
    assert graph.path_count() == pooled.task_graph_.path_count() == direct.task_graph_.path_count()
    assert all(graph.path_count() >= learner.task_graph_.path_count() for learner in team)
    assert len(graph.demonstrations) == sum(len(learner.task_graph_.demonstrations) for learner in team)
    for learner in team:  # every member's known executions are known to the union
        for path in learner.task_graph_.iter_paths():
            assert graph.contains([a for a, _ in path])
    assert pooled.htn_.admits(demonstrate(SimulatedInstructor(_structure(name), seed=0)))


def test_pooling_edge_cases() -> None:
    assert pooled_task_graph([]).path_count() == 0
    with pytest.raises(LearningError, match="no demonstrations"):
        pooled_learner([])
    with pytest.raises(LearningError, match="not fitted"):
        pooled_learner([HTNLearner()])
    explicit = TaskGraph()
    explicit.add_demonstration(Demonstration((Step("a", state=frozenset({"x"})),), "d1"))
    with pytest.raises(LearningError, match="explicit states"):
        pooled_task_graph([explicit])


# ---------------------------------------------------------------------------------------------- partial orders

_A, _B, _C, _D = ("a", 1), ("b", 1), ("c", 1), ("d", 1)
_DIAMOND = PartialOrder([_A, _B, _C, _D], [(_A, _B), (_A, _C), (_B, _D), (_C, _D)])


def test_partial_order_allows_a_leaf_once_its_predecessors_are_done() -> None:
    assert _DIAMOND.allowed_next([]) == {_A}
    assert _DIAMOND.allowed_next([_A]) == {_B, _C}
    assert _DIAMOND.allowed_next([_A, _C]) == {_B}
    assert _DIAMOND.allowed_next([_A, _B, _C, _D]) == frozenset()
    assert _DIAMOND.predecessors[_D] == {_A, _B, _C}  # transitive
    with pytest.raises(ValueError):
        _DIAMOND.allowed_next([_B])
    assert _DIAMOND.admits([_A, _C, _B, _D]) and not _DIAMOND.admits([_A, _D, _B, _C])
    assert _DIAMOND.linearize(["d", "c", "b", "a"]) == ("a", "c", "b", "d")
    with pytest.raises(LearningError):
        PartialOrder([_A, _B], [(_A, _B), (_B, _A)])


def test_instructor_over_a_partial_order_follows_it_and_heeds_queries() -> None:
    person = SimulatedInstructor(_DIAMOND, ["a", "b", "c", "d"], perturbation=0.0)
    assert demonstrate(person) == ["a", "b", "c", "d"]
    person.begin_demonstration()
    assert person.next_action(("a",), "c") == "c"  # allowed next: heeded at once
    assert person.steps_to(("a",), "d") == 3  # b and c first
    assert person.steps_to((), "d") == 4
    person.begin_demonstration()
    assert person.next_action((), "d") == "a"  # 4 steps away: beyond the horizon of 3, ignored
    with pytest.raises(LearningError):
        SimulatedInstructor(_DIAMOND, ["a", "d", "b", "c"])


def test_instructor_over_a_partial_order_perturbs_within_it() -> None:
    for seed in range(20):
        person = SimulatedInstructor(_DIAMOND, ["a", "b", "c", "d"], perturbation=1.0, seed=seed)
        assert _DIAMOND.admits(person.preferred_leaves)
        assert demonstrate(person) == list(person.preferred_path)


def test_unprompted_deviation_varies_demonstrations_but_stays_valid() -> None:
    from supportive import examples

    structure = examples.load("blocks-tower").structure
    assert structure is not None
    steady = SimulatedInstructor(structure, seed=4)
    drifting = SimulatedInstructor(structure, seed=4, deviation=0.3)
    assert steady.preferred_path == drifting.preferred_path
    seen = set()
    for _ in range(8):
        drifting.begin_demonstration()
        path = demonstrate(drifting)
        assert admits(structure, to_leaves(path))
        seen.add(tuple(path))
    assert len(seen) > 1
    assert {tuple(demonstrate(steady)) for _ in range(3)} == {steady.preferred_path}
