from __future__ import annotations

from supportive import examples
from supportive.learning import learn
from supportive.learning.macros import macro_actions, macro_library
from supportive.tasks.htn import admits, to_leaves


def test_chair_macros_are_its_subtasks() -> None:
    htn = learn(examples.load("ikea-chair"), mode="strict").htn_
    macros = {m.name: m for m in macro_actions(htn)}
    left = macros["Prepare left frame"]
    assert left.actions[:2] == ("get_left_frame", "place_left_frame") and left.size == 4
    assert left.count_sequences() == 2
    assert sorted(left.sequences()) == sorted(
        [
            ("get_left_frame", "place_left_frame", "peg_left_front", "peg_left_rear"),
            ("get_left_frame", "place_left_frame", "peg_left_rear", "peg_left_front"),
        ]
    )
    for macro in macros.values():
        assert admits(macro.node, to_leaves(macro.actions))
        assert admits(macro.node, to_leaves(macro.sample(3)))
    assert "Fasten nuts and bolts" not in macros  # not learned yet, so not offered
    general = {m.name for m in macro_actions(learn(examples.load("ikea-chair")).htn_)}
    assert "Fasten nuts and bolts" in general  # the general learner infers it from the bolts' runs


def test_min_size_and_transfer() -> None:
    htn = learn(examples.load("blocks-towers")).htn_
    assert all(m.size >= 3 for m in macro_actions(htn, min_size=3))
    assert {m.size for m in macro_actions(htn)} >= {2, 3}
    tower = next(m for m in macro_actions(htn) if m.name == "Yellow tower")
    assert tower.applicable({"yellow", "green", "white", "red"})
    assert not tower.applicable({"yellow", "green"})


def test_library_keeps_each_subtask_once() -> None:
    htn = learn(examples.load("knife-carrots-celery"), mode="strict").htn_
    assert len(macro_library([htn, htn])) == len(macro_actions(htn)) == 2
