from __future__ import annotations

import itertools

import pytest

from supportive.errors import TaskGraphError
from supportive.tasks.spec import Demonstration, Step
from supportive.tasks.task_graph import TaskGraph


def test_union_recombines_demonstrations() -> None:
    graph = TaskGraph()
    for order in ("abcd", "bacd", "abdc"):
        graph.add(list(order))
    assert graph.path_count() == 4  # badc is known too: the states merge
    assert graph.contains(list("badc"))
    assert not graph.contains(list("bdac"))
    assert sorted("".join(a for a, _ in p) for p in graph.iter_paths()) == ["abcd", "abdc", "bacd", "badc"]


def test_all_permutations_make_the_boolean_lattice() -> None:
    graph = TaskGraph()
    for order in itertools.permutations("abcde"):
        graph.add(list(order))
    assert graph.n_states == 2**5
    assert graph.n_edges == 5 * 2**4
    assert graph.path_count() == 120


def test_large_path_counts_are_exact_without_enumeration() -> None:
    graph = TaskGraph()
    # two orders per pair, 40 pairs in sequence: 2**40 known paths
    for flip in (False, True):
        steps = []
        for i in range(40):
            pair = [f"x{i}", f"y{i}"]
            steps += pair[::-1] if flip else pair
        graph.add(steps)
    for i in range(40):
        steps = []
        for j in range(40):
            pair = [f"x{j}", f"y{j}"]
            steps += pair[::-1] if j == i else pair
        graph.add(steps)
    assert graph.path_count() == 2**40


def test_repeated_action_states_are_multisets() -> None:
    graph = TaskGraph()
    update = graph.add(["stir", "heat", "stir"])
    assert [graph.subgoal_label(s) for _, s, _ in update.edges] == ["stir", "heat", "stir#2"]
    assert graph.prerequisites(3) == frozenset({"stir", "heat", "stir#2"})


def test_incremental_updates_report_what_changed() -> None:
    graph = TaskGraph()
    first = graph.add(list("abc"))
    assert len(first.edges) == 3 and first.new_terminal
    again = graph.add(list("abc"))
    assert not again.changed
    assert graph.path_count() == 1
    graph.add(list("bac"))
    assert graph.path_count() == 2


def _explicit(*steps: tuple[str, set[str]]) -> Demonstration:
    return Demonstration(tuple(Step(a, state=frozenset(s)) for a, s in steps), initial_state=frozenset())


def test_explicit_states_keep_order_dependent_outcomes_apart() -> None:
    graph = TaskGraph()
    graph.add_demonstration(_explicit(("red", {"red_on_table"}), ("blue", {"blue_on_red"})))
    graph.add_demonstration(_explicit(("blue", {"blue_on_table"}), ("red", {"red_on_blue"})))
    assert graph.n_states == 5  # no shared end state: the two stacks differ
    assert graph.path_count() == 2
    assert graph.prerequisites(1) == frozenset({"red_on_table"})


def test_contradicting_explicit_states_are_rejected() -> None:
    graph = TaskGraph()
    graph.add_demonstration(_explicit(("a", {"s1"}), ("b", {"s2"})))
    with pytest.raises(TaskGraphError, match="different actions"):
        graph.add_demonstration(_explicit(("c", {"s1"}), ("b", {"s2"})))


def test_mixing_explicit_and_derived_states_is_rejected() -> None:
    graph = TaskGraph()
    graph.add(["a", "b"])
    with pytest.raises(TaskGraphError, match="explicit states"):
        graph.add_demonstration(_explicit(("a", {"s1"})))


def test_empty_demonstration_is_rejected() -> None:
    with pytest.raises(TaskGraphError, match="no steps"):
        TaskGraph().add_demonstration(Demonstration(()))
