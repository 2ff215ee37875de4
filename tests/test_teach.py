from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from supportive import examples
from supportive.io.taskfile import parse_task_file
from supportive.learning.active import QuerySchedule
from supportive.teach import TeachingConsole

TOWERS = ["yellow", "green", "white", "red", "blue", "purple", "black", "orange"]


def _console(path: Path, lines: list[str], shown: list[str]) -> TeachingConsole:
    script = iter(lines)

    def read() -> str:
        try:
            return next(script)
        except StopIteration:
            raise EOFError from None

    return TeachingConsole(path, read, shown.append, "distance", QuerySchedule(after_steps=(0, 2, 4)), seed=0)


def test_teaching_saves_demonstrations_and_asks_in_words(tmp_path: Path) -> None:
    path = tmp_path / "towers.yaml"
    shutil.copy(examples.path("blocks-towers"), path)
    shown: list[str] = []
    order = ["red", "blue", "purple", "black", "orange", "yellow", "green", "white"]
    spec = _console(path, [*order, *order[:2], "quit"], shown).run()
    saved = parse_task_file(path)
    assert saved == spec
    assert [d.actions for d in saved.demonstrations][-1] == tuple(order)
    assert (
        len(saved.demonstrations) == 5 and saved.demonstrations[-1].id == "d5"
    )  # the unfinished one is dropped
    questions = [line for line in shown if "robot: Can you place the" in line]
    assert questions and all(line.endswith("block next?") for line in questions)
    assert any("dropped the unfinished demonstration (2 steps)" in line for line in shown)


def test_bad_input_is_answered_not_crashed_on(tmp_path: Path) -> None:
    path = tmp_path / "towers.yaml"
    shutil.copy(examples.path("blocks-towers"), path)
    shown: list[str] = []
    _console(path, ["", "bogus", "99", "done", *TOWERS], shown).run(demonstrations=1)
    assert any("(empty line)" in line for line in shown)
    assert any("unknown action 'bogus'" in line for line in shown)
    assert any("unknown action '99'" in line for line in shown)
    assert any("nothing performed yet" in line for line in shown)
    assert parse_task_file(path).demonstrations[-1].actions == tuple(TOWERS)


def test_numbers_select_actions_and_a_new_file_starts_learning(tmp_path: Path) -> None:
    path = tmp_path / "knife.yaml"
    path.write_text("name: knife\nactions: [knife, carrots, celery]\n")
    shown: list[str] = []
    _console(path, ["1", "3", "2", "1", "2", "3"], shown).run()
    saved = parse_task_file(path)
    assert [d.actions for d in saved.demonstrations] == [
        ("knife", "celery", "carrots"),
        ("knife", "carrots", "celery"),
    ]
    assert any("hierarchy: complete" in line for line in shown)


def test_teach_command_reads_stdin(tmp_path: Path) -> None:
    path = tmp_path / "towers.yaml"
    shutil.copy(examples.path("blocks-towers"), path)
    script = shutil.which("supportive", path=str(Path(sys.executable).parent))
    assert script is not None
    order = ["purple", "black", "orange", "yellow", "green", "white", "red", "blue"]
    result = subprocess.run(
        [script, "teach", str(path), "--strategy", "connectivity", "--ask-after", "0,3"],
        input="\n".join([*order, "nonsense"]) + "\n",
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "robot: Can you place the" in result.stdout
    assert "unknown action 'nonsense'" in result.stdout
    assert parse_task_file(path).demonstrations[-1].actions == tuple(order)
    bad = subprocess.run(
        [script, "teach", str(path), "--strategy", "psychic"], capture_output=True, text=True, check=False
    )
    assert bad.returncode == 2 and bad.stderr.strip().startswith(
        "supportive: error: --strategy: unknown strategy 'psychic'"
    )
