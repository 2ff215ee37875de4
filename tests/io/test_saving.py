"""Saving users' files loses nothing: comments and layout kept (teach, chat), mode and symlinks kept, atomic
(a failed write changes nothing), and one writer at a time (two sessions on one file keep both their saves)."""

from __future__ import annotations

import os
import queue
import shutil
import subprocess
import sys
import threading
from collections.abc import Callable
from pathlib import Path

import pytest

from supportive import examples
from supportive.cli.teach_console import TeachingConsole
from supportive.errors import TaskFileError
from supportive.io.atomic import atomic_write, exclusive
from supportive.io.task_edit import update_task_file
from supportive.io.taskfile import parse_task_file
from supportive.tasks.spec import Demonstration, TaskSpec

CliRunner = Callable[[list[str]], tuple[int, str, str]]

ORDER = ["red", "yellow", "green", "white", "orange", "purple", "black", "blue"]


def tower(tmp_path: Path) -> Path:
    path = tmp_path / "tower.yaml"
    shutil.copy(examples.path("blocks-tower"), path)
    return path


def add_demo(steps: list[str]) -> Callable[[TaskSpec], TaskSpec]:
    def change(spec: TaskSpec) -> TaskSpec:
        return spec.with_demonstrations([*spec.demonstrations, Demonstration.of(steps, id=f"d{len(spec.demonstrations) + 1}")])

    return change


def test_teach_keeps_comments_layout_and_every_untouched_line(tmp_path: Path) -> None:
    path = tower(tmp_path)
    before = path.read_text()
    typed = iter([*ORDER[:-1], "blue", "quit"])
    TeachingConsole(path, lambda: next(typed), lambda line: None).run()
    after = path.read_text()
    assert after.startswith(before)  # comments, flow style, quoting: every line as it was
    assert after[len(before) :] == "  - {id: d5, steps: [red, yellow, green, white, orange, purple, black, blue]}\n"
    assert len(parse_task_file(path).demonstrations) == 5


def test_chat_keeps_comments_and_changes_only_the_behavior(tmp_path: Path) -> None:
    from supportive.cli.chat_console import ChatConsole

    path = tmp_path / "chair.yaml"
    shutil.copy(examples.path("ikea-chair"), path)
    before = path.read_text().splitlines()
    typed = iter(["When I am attaching the seat, I want you to hold the frames steady.", "yes", "quit"])
    ChatConsole(path, lambda: next(typed), lambda line: None).run()
    after = path.read_text().splitlines()
    assert [line for line in before if line.lstrip().startswith("#")] == [
        line for line in after if line.lstrip().startswith("#")
    ]
    assert len(before) == len(after)
    changed = [i for i, (a, b) in enumerate(zip(before, after, strict=True)) if a != b]
    block = before.index("  - name: hold-frames")
    assert changed and all(block < i < block + 6 for i in changed)  # only the behavior that changed


def test_mode_and_symlinks_are_kept(tmp_path: Path, cli: CliRunner) -> None:
    real = tower(tmp_path)
    real.chmod(0o600)
    link = tmp_path / "link.yaml"
    link.symlink_to(real.name)
    update_task_file(link, add_demo(ORDER))
    assert link.is_symlink() and os.readlink(link) == real.name
    assert oct(real.stat().st_mode & 0o777) == "0o600" and len(parse_task_file(real).demonstrations) == 5
    out = tmp_path / "htn.json"
    out.write_text("{}")
    out.chmod(0o640)
    shown = tmp_path / "shown.json"
    shown.symlink_to(out.name)
    code, _, err = cli(["learn", str(real), "-f", "json", "-o", str(shown)])
    assert code == 0, err
    assert shown.is_symlink() and oct(out.stat().st_mode & 0o777) == "0o640" and '"complete"' in out.read_text()


def test_a_failed_write_changes_nothing_and_leaves_no_temporary(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path = tower(tmp_path)
    before = path.read_bytes()

    def disk_full(*args: object) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("supportive.io.atomic.os.replace", disk_full)
    with pytest.raises(TaskFileError, match=r"tower\.yaml: cannot write: No space left on device"):
        update_task_file(path, add_demo(ORDER))
    assert path.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["tower.yaml"]


def test_two_teach_sessions_on_one_file_keep_both_demonstrations(tmp_path: Path) -> None:
    """Both sessions read the file before either saves; each save is applied to the file as it is then."""
    path = tower(tmp_path)
    lines: dict[str, queue.Queue[str]] = {"a": queue.Queue(), "b": queue.Queue()}
    started = {"a": threading.Event(), "b": threading.Event()}

    def session(name: str) -> None:
        def read() -> str:
            started[name].set()
            return lines[name].get(timeout=60)

        TeachingConsole(path, read, lambda line: None).run(demonstrations=1)

    threads = [threading.Thread(target=session, args=(name,)) for name in "ab"]
    for thread in threads:
        thread.start()
    for event in started.values():
        assert event.wait(60)  # both have read the file and wait for their first step
    for step in ORDER:
        lines["a"].put(step)
    threads[0].join(60)
    for step in reversed(ORDER):
        lines["b"].put(step)
    threads[1].join(60)
    demos = parse_task_file(path).demonstrations
    assert [d.id for d in demos] == ["d1", "d2", "d3", "d4", "d5", "d6"]
    assert demos[4].actions == tuple(ORDER) and demos[5].actions == tuple(reversed(ORDER))


SECOND_WRITER = """
import sys
from supportive.io.task_edit import update_task_file
from supportive.tasks.spec import Demonstration
update_task_file(sys.argv[1], lambda s: s.with_demonstrations([*s.demonstrations, Demonstration.of(["blue"] , id="late")]))
"""


def test_a_second_writer_waits_for_the_lock(tmp_path: Path) -> None:
    """While one process holds the file's lock and saves, another's save waits, then applies to what was
    saved: nothing is overwritten."""
    path = tmp_path / "t.yaml"
    path.write_text("name: t\nactions: [red, blue]\ndemonstrations:\n  - {id: d1, steps: [red, blue]}\n")
    with exclusive(path):
        writer = subprocess.Popen([sys.executable, "-c", SECOND_WRITER, str(path)], stderr=subprocess.PIPE)
        with pytest.raises(subprocess.TimeoutExpired):
            writer.wait(1.0)  # it is blocked on the lock (it would have finished long before otherwise)
        atomic_write(path, path.read_text() + "  - {id: mine, steps: [blue, red]}\n")
    assert writer.wait(60) == 0, writer.stderr.read() if writer.stderr else ""
    assert [d.id for d in parse_task_file(path).demonstrations] == ["d1", "mine", "late"]


def test_hddl_to_an_existing_file_is_refused_and_writes_nothing(tmp_path: Path, cli: CliRunner) -> None:
    target = tmp_path / "chair.hddl"
    target.write_text("mine\n")
    code, out, err = cli(["learn", str(examples.path("blocks-v")), "-f", "hddl", "-o", str(target)])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert f"{target}: is a file, not a directory" in err and "Traceback" not in err
    assert target.read_text() == "mine\n" and sorted(p.name for p in tmp_path.iterdir()) == ["chair.hddl"]


def test_a_read_only_file_is_refused_not_replaced(tmp_path: Path) -> None:
    """Issue 28: as a user other than root, ``learn -o ro.yaml`` replaced a read-only file (a rename may replace
    a file its owner cannot write). Root may write any file, so as root the check runs as ``nobody``, in a
    child process."""
    import tempfile

    from supportive.errors import FileFormatError

    if os.geteuid() == 0:  # a folder nobody can reach (pytest's are root's only)
        tmp_path = Path(tempfile.mkdtemp(prefix="supportive-ro-"))
    target = tmp_path / "ro.yaml"
    target.write_text("mine\n", encoding="utf-8")
    target.chmod(0o444)

    def attempt() -> str:
        try:
            atomic_write(target, "new\n")
        except FileFormatError as exc:
            return str(exc)
        return "written"

    if os.geteuid() != 0:
        outcome = attempt()
    else:
        shutil.chown(tmp_path, "nobody")
        shutil.chown(target, "nobody")
        reader, writer = os.pipe()
        child = os.fork()
        if child == 0:  # pragma: no cover - the child reports through the pipe
            os.close(reader)
            try:
                os.setgid(65534)
                os.setuid(65534)
                os.write(writer, attempt().encode())
            finally:
                os._exit(0)
        os.close(writer)
        with os.fdopen(reader) as pipe:
            outcome = pipe.read()
        os.waitpid(child, 0)
    assert outcome == f"{target}: cannot write: the file is read-only (make it writable to replace it)"
    assert target.read_text(encoding="utf-8") == "mine\n" and sorted(p.name for p in tmp_path.iterdir()) == ["ro.yaml"]
    if os.geteuid() == 0:
        shutil.rmtree(tmp_path)
