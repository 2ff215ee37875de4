"""``supportive chat`` driven through stdin, and the console driven by a script."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from supportive import examples
from supportive.chat import ChatConsole
from supportive.io import parse_task_file


def _console(path: Path, lines: list[str], shown: list[str]) -> ChatConsole:
    feed = iter(lines)

    def read() -> str:
        try:
            return next(feed)
        except StopIteration:
            raise EOFError from None

    return ChatConsole(path, read, shown.append)


def test_a_confirmed_preference_is_saved_and_explained_back(tmp_path: Path) -> None:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    shown: list[str] = []
    _console(path, [
        "When I am tightening the bolts, I want you to shine a light on the bolt until the rear left bolt is tight",
        "yes",
    ], shown).run()
    saved = parse_task_file(path)
    light = next(b for b in saved.behaviors if b.text == "shine a light on the bolt")
    assert light.subtasks == ("Fasten nuts and bolts",) and light.termination == "bolted(rear_left)"
    assert any(line.startswith("By 'tightening the bolts', do you mean Fasten nuts and bolts?") for line in shown)
    assert any("OK. I will now shine a light on the bolt. While you are fastening nuts and bolts" in line for line in shown)


def test_declining_or_picking_another_candidate(tmp_path: Path) -> None:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    before = parse_task_file(path)
    shown: list[str] = []
    _console(path, ["While I attach the front rail, please hold the side frames steady", "no"], shown).run()
    assert parse_task_file(path) == before and "All right, I changed nothing." in shown
    _console(path, ["While I attach the front rail, please hold the side frames steady", "2"], shown).run()
    frames = next(b for b in parse_task_file(path).behaviors if b.name == "hold-frames")
    assert "Mount supports" in frames.subtasks


def test_chat_command_reads_stdin(tmp_path: Path) -> None:
    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    script = shutil.which("supportive", path=str(Path(sys.executable).parent))
    assert script is not None
    result = subprocess.run(
        [script, "chat", str(path)],
        input="How will you help me screw the seat?\nWhen will you hold the seat?\nfoo bar\n\nbehaviors\n"
        "When will you juggle?\nquit\n",
        capture_output=True, text=True, check=False,
    )
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "When you are screwing seat, I can give you screws" in out
    assert "While you are attaching seat, I will hold the seat in place" in out
    assert "I did not understand 'foo bar'" in out and "Say something, or 'quit'." in out
    assert "- give-screws: give you screws (materials retrieval; during Screw seat)" in out
    assert "I have no behavior like 'juggle'" in out
    missing = subprocess.run([script, "chat", str(tmp_path / "none.yaml")], capture_output=True, text=True, check=False)
    assert missing.returncode == 2 and "no such file" in missing.stderr and "Traceback" not in missing.stderr
