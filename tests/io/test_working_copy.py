"""The working copy ``teach`` and ``chat`` save to: made at the first change, whole or not at all."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from supportive import examples
from supportive.io.taskfile import parse_task_file
from supportive.io.working_copy import working_copy
from supportive.tasks.spec import Demonstration, TaskSpec


def _add(current: TaskSpec) -> TaskSpec:
    steps = ["red", "yellow", "green", "white", "orange", "purple", "black", "blue"]
    return current.with_demonstrations([*current.demonstrations, Demonstration.of(steps, id="d9")])


def test_the_copy_is_made_at_the_first_change_with_the_source_layout(tmp_path: Path) -> None:
    source = tmp_path / "tower.yaml"
    shutil.copy(examples.path("blocks-tower"), source)
    copy = working_copy(source)
    assert not copy.exists and copy.reads() == source
    saved = copy.update(_add)
    assert copy.made and copy.path == tmp_path / "tower.edited.yaml"
    assert parse_task_file(copy.path) == saved and saved.demonstrations[-1].id == "d9"
    comments = [line for line in source.read_text().splitlines() if line.lstrip().startswith("#")]
    assert comments and all(line in copy.path.read_text().splitlines() for line in comments)
    assert parse_task_file(source).demonstrations == examples.load("blocks-tower").demonstrations


def test_a_kill_while_the_copy_is_written_leaves_no_copy(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Issue 28: a kill while the copy was written left a truncated copy that every later session refused."""
    source = tmp_path / "tower.yaml"
    shutil.copy(examples.path("blocks-tower"), source)
    copy = working_copy(source)

    def killed(descriptor: int) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "fsync", killed)
    with pytest.raises(KeyboardInterrupt):
        copy.update(_add)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tower.yaml"]  # no copy, no temporary
    monkeypatch.undo()
    assert len(copy.update(_add).demonstrations) == len(parse_task_file(source).demonstrations) + 1
