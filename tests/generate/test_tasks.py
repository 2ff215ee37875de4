"""Generated task specs and the thesis-like IKEA task set."""

from __future__ import annotations

import re

import numpy as np
import pytest

from supportive.generate import (
    THESIS_DEPTH_RANGE,
    GenerationError,
    TooManyOrderingsError,
    generate_task,
    ikea_statistics,
    ikea_task_set,
    random_structure,
)
from supportive.tasks.htn import admits, count_orderings, leaf_actions, mean_action_depth, to_leaves
from supportive.tasks.spec import TaskSpec


def test_task_holds_structure_actions_and_demonstrations() -> None:
    task = generate_task(25, 11)
    assert task.name == "ikea-25-s11"
    assert task.structure == random_structure(25, 11)
    assert [a.id for a in task.actions] == list(leaf_actions(task.structure))
    assert len(task.demonstrations) == 4
    assert all(admits(task.structure, to_leaves(d.actions)) for d in task.demonstrations)
    texts = task.texts()
    for action, text in texts.items():
        verb = action.split("_")[0]
        assert text.startswith({"pick": "pick up ", "place": "place ", "fasten": "fasten "}.get(verb, verb))
        assert text.endswith(" " + action.rsplit("_", 1)[1])


def test_action_text_examples() -> None:
    task = generate_task(40, 2)
    texts = task.texts()
    pick = next(a for a in texts if a.startswith("pick_"))
    assert texts[pick] == "pick up " + pick[len("pick_") :].replace("_", " ")
    uniform = generate_task(5, 2, profile="uniform")
    assert uniform.texts()["step_3"] == "perform step 3"
    assert uniform.name == "uniform-5-s2"


def test_all_demonstrations_option() -> None:
    task = generate_task(6, 4, demonstrations="all", profile="uniform", limit=10**6)
    assert task.structure is not None
    assert len(task.demonstrations) == count_orderings(task.structure)
    assert len({d.actions for d in task.demonstrations}) == len(task.demonstrations)
    with pytest.raises(TooManyOrderingsError):
        generate_task(60, 4, demonstrations="all")


def test_same_seed_same_task_and_different_seeds_differ() -> None:
    first, second = generate_task(70, 8, demonstrations=5), generate_task(70, 8, demonstrations=5)
    assert first == second
    assert repr(first) == repr(second)
    other = generate_task(70, 9, demonstrations=5)
    assert other.structure != first.structure
    assert other.demonstrations != first.demonstrations


def test_generator_seed_and_name() -> None:
    task = generate_task(10, np.random.default_rng(1), name="mine")
    assert task.name == "mine"
    assert generate_task(10, np.random.default_rng(1)).name == "ikea-10"


def test_bad_demonstration_counts() -> None:
    with pytest.raises(GenerationError):
        generate_task(10, demonstrations=-1)
    with pytest.raises(GenerationError):
        generate_task(10, demonstrations="some")  # type: ignore[arg-type]


@pytest.fixture(scope="module")
def thesis_set() -> tuple[TaskSpec, ...]:
    return ikea_task_set(seed=2017)


def test_task_set_is_thesis_like(thesis_set: tuple[TaskSpec, ...]) -> None:
    assert len(thesis_set) == 76
    sizes = [len(t.actions) for t in thesis_set]
    assert min(sizes) == 10 and max(sizes) == 100
    assert sizes == sorted(sizes)
    assert len({t.name for t in thesis_set}) == 76
    stats = ikea_statistics(thesis_set)
    low, high = THESIS_DEPTH_RANGE
    assert low <= stats["min_depth"] and stats["max_depth"] <= high
    assert abs(stats["mean_depth"] - 2.84) < 0.15
    assert stats["mean_demonstrations"] == 4
    for task in thesis_set:
        assert task.structure is not None
        assert all(admits(task.structure, to_leaves(d.actions)) for d in task.demonstrations)


def test_task_set_names_rebuild_each_task(thesis_set: tuple[TaskSpec, ...]) -> None:
    for task in thesis_set[::15]:
        match = re.fullmatch(r"ikea-\d{3}-n(\d+)-s(\d+)", task.name)
        assert match is not None
        size, seed = match.groups()
        assert generate_task(int(size), int(seed), name=task.name) == task


def test_task_set_is_deterministic(thesis_set: tuple[TaskSpec, ...]) -> None:
    again = ikea_task_set(seed=2017)
    assert [t.name for t in again] == [t.name for t in thesis_set]
    assert again == thesis_set
    assert [t.name for t in ikea_task_set(seed=2018)] != [t.name for t in thesis_set]


def test_raw_generator_is_calibrated_to_the_thesis() -> None:
    tasks = ikea_task_set(seed=7, depth_range=None, demonstrations=0)
    depths = np.array([mean_action_depth([t.structure]) for t in tasks if t.structure is not None])
    low, high = THESIS_DEPTH_RANGE
    assert np.mean((depths >= low) & (depths <= high)) >= 0.9
    assert 2.65 <= depths.mean() <= 3.05


def test_task_set_options() -> None:
    tasks = ikea_task_set(5, sizes=(20, 30), seed=1, demonstrations=2, distinct=True)
    assert [len(t.actions) for t in tasks] == [20, 22, 25, 28, 30]
    assert all(len({d.actions for d in t.demonstrations}) == 2 for t in tasks)
    with pytest.raises(GenerationError, match="no structure"):
        ikea_task_set(2, seed=1, depth_range=(9.0, 9.5), max_attempts=3)
    with pytest.raises(GenerationError):
        ikea_task_set(3, sizes=(0, 10))
    assert ikea_task_set(0) == ()
