"""The food-preparation task sets (issue #4): 12 active-learning tasks (§2.2.10.1) and 25 transfer tasks over
one 39-action dictionary (§2.1.7.4)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import pytest

from supportive import examples
from supportive.errors import TaskFileError
from supportive.examples import food
from supportive.io.taskfile import parse_task_file, write_task_file
from supportive.learning import HTNLearner
from supportive.tasks.htn import (
    Node,
    canonical,
    count_orderings,
    internal_nodes,
    iter_orderings,
    leaf_actions,
)
from supportive.tasks.spec import TaskSpec


def _structure(spec: TaskSpec) -> Node:
    assert spec.structure is not None, f"{spec.name} has no structure"
    return spec.structure


def _learns_exactly(structure: Node) -> None:
    demos = [[action for action, _ in order] for order in iter_orderings(structure)]
    htn = HTNLearner(mode="strict").fit(demos).htn_  # every ordering, however few: invariant 3
    assert len(htn.roots) == 1
    assert canonical(htn.roots[0]) == canonical(structure)


def _every_node_named(structure: Node) -> None:
    unnamed = [leaf_actions(node) for node in internal_nodes(structure) if not node.name]
    assert not unnamed, f"unnamed chain/clique over {unnamed}"


def _each_action_once(spec: TaskSpec) -> None:
    used = leaf_actions(_structure(spec))
    assert len(used) == len(set(used)), "an action repeats in the structure"
    assert sorted(used) == sorted(spec.action_ids())


def _demonstrations_valid(spec: TaskSpec) -> None:
    valid = {tuple(a for a, _ in order) for order in iter_orderings(_structure(spec))}
    for demo in spec.demonstrations:
        assert demo.actions in valid, f"{demo.id} is not a valid ordering"


# --- active-learning tasks ---------------------------------------------------------------------------------


def test_active_learning_set() -> None:
    assert len(food.names()) == 12
    assert not set(food.names()) & set(examples.names()), "food tasks must not join the bundled examples"


@pytest.mark.parametrize("name", food.names())
def test_active_learning_task(name: str) -> None:
    spec = food.load(name)
    structure = _structure(spec)
    assert spec.name == name
    assert 10 <= len(spec.actions) <= 14
    assert 12 <= count_orderings(structure) <= 24
    _each_action_once(spec)
    _every_node_named(structure)
    for action in spec.actions:
        assert action.text and action.text != action.id
        assert action.observations, f"{action.id} has no observations"
    _demonstrations_valid(spec)


@pytest.mark.parametrize("name", food.names())
def test_active_learning_task_is_learned_from_all_orderings(name: str) -> None:
    _learns_exactly(_structure(food.load(name)))


@pytest.mark.parametrize("name", food.names())
def test_active_learning_task_round_trips(name: str, tmp_path: Path) -> None:
    spec = food.load(name)
    path = tmp_path / f"{name}.yaml"
    write_task_file(spec, path)
    assert parse_task_file(path) == spec


def test_unknown_names_are_errors() -> None:
    with pytest.raises(TaskFileError, match="omelette"):
        food.load("no-such-dish")
    with pytest.raises(TaskFileError, match="minestrone"):
        food.load_transfer("no-such-dish")


# --- transfer tasks ----------------------------------------------------------------------------------------


def _transfer_specs() -> Iterator[TaskSpec]:
    for name in food.transfer_names():
        yield food.load_transfer(name)


def test_transfer_set_shares_one_dictionary_of_39_actions() -> None:
    specs = list(_transfer_specs())
    assert len(specs) == 25
    texts: dict[str, set[str | None]] = {}
    observations: dict[str, set[tuple[tuple[str, float], ...]]] = {}
    for spec in specs:
        for action in spec.actions:
            texts.setdefault(action.id, set()).add(action.text)
            observations.setdefault(action.id, set()).add(action.observations)
    assert len(texts) == 39
    assert {a: t for a, t in texts.items() if len(t) != 1} == {}
    assert {a: o for a, o in observations.items() if len(o) != 1} == {}
    assert all(None not in t for t in texts.values())


def _subtasks(node: Node) -> Iterator[tuple[str, frozenset[str]]]:
    for inner in internal_nodes(node):
        if inner.name:
            yield inner.name, frozenset(leaf_actions(inner))


def test_transfer_tasks_share_subtasks() -> None:
    specs = list(_transfer_specs())
    uses: Counter[tuple[str, frozenset[str]]] = Counter()
    for spec in specs:
        uses.update(set(_subtasks(_structure(spec))))
    shared = {name for (name, _), count in uses.items() if count >= 3}
    assert {"Heat oil", "Melt butter", "Boil water", "Cook pasta", "Beat eggs", "Season"} <= shared
    # a name always stands for the same actions
    by_name: dict[str, set[frozenset[str]]] = {}
    for name, leaves in uses:
        by_name.setdefault(name, set()).add(leaves)
    for name in ("Heat oil", "Melt butter", "Boil water", "Cook pasta", "Season", "Chop mirepoix"):
        assert len(by_name[name]) == 1, name


@pytest.mark.parametrize("name", food.transfer_names())
def test_transfer_task(name: str) -> None:
    spec = food.load_transfer(name)
    structure = _structure(spec)
    assert spec.name == name
    assert 6 <= len(spec.actions) <= 14
    assert count_orderings(structure) <= 5000
    _each_action_once(spec)
    _every_node_named(structure)
    _demonstrations_valid(spec)
    _learns_exactly(structure)
