"""Keyframes of actions in task files: read in both forms, written back, errors located."""

from __future__ import annotations

from pathlib import Path

import pytest

from supportive.errors import TaskFileError
from supportive.io.taskfile import dump_task, parse_task_file, parse_task_string, write_task_file
from supportive.tasks.spec import Action, Keyframe, TaskSpec

TEXT = """\
name: t
actions:
  - id: pick
    keyframes:
      - [1.35, 0.4]
      - {x: 1.35, y: 0.3, text: close the gripper, goal: true}
  - place
"""


def test_both_forms_read() -> None:
    spec = parse_task_string(TEXT, "yaml")
    pick, place = spec.actions
    assert pick.keyframes == (Keyframe(1.35, 0.4), Keyframe(1.35, 0.3, "close the gripper", goal=True))
    assert pick.keyframes[0].point == (1.35, 0.4)
    assert place.keyframes == ()


@pytest.mark.parametrize("fmt", ["yaml", "json"])
def test_keyframes_round_trip(fmt: str, tmp_path: Path) -> None:
    spec = parse_task_string(TEXT, "yaml")
    path = tmp_path / f"t.{fmt}"
    write_task_file(spec, path)
    assert parse_task_file(path) == spec


def test_writer_uses_the_pair_shorthand_when_nothing_else_is_said() -> None:
    text = dump_task(parse_task_string(TEXT, "yaml"), "yaml")
    assert "- [1.35, 0.4]\n" in text
    assert "text: close the gripper" in text and "goal: true" in text
    assert "keyframes" not in text.split("- id: place")[1]  # an action without keyframes writes none


def test_files_without_keyframes_read_and_write_as_before() -> None:
    spec = TaskSpec("old", actions=(Action("a", "do a"),))
    assert "keyframes" not in dump_task(spec, "yaml")
    assert parse_task_string("name: old\nactions: [{id: a, text: do a}]\n", "yaml") == spec


@pytest.mark.parametrize(
    ("keyframes", "message"),
    [
        ("[[0.1]]", "a keyframe is [x, y] or {x, y, text, goal}, got a list of length 1"),
        ("[[0.1, 0.2, 0.3]]", "got a list of length 3"),
        ("[[.nan, 0.2]]", "finite number"),
        ("[[0.1, .inf]]", "finite number"),
        ("[{x: 0.1}]", "missing required key 'y'"),
        ("[{x: 0.1, y: 0.2, z: 0.3}]", "unknown key 'z'"),
        ("[[left, 0.2]]", "expected a number"),
    ],
)
def test_bad_keyframes_are_located(keyframes: str, message: str) -> None:
    text = f"name: t\nactions:\n  - id: a\n    keyframes: {keyframes}\n"
    with pytest.raises(TaskFileError, match="keyframes") as caught:
        parse_task_string(text, "yaml", path="t.yaml")
    assert message in str(caught.value)
    assert str(caught.value).startswith("t.yaml:4: actions[0].keyframes[0]")
