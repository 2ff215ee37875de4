"""Ctrl-C and SIGTERM in every long command (issue 25): a real ``supportive`` process is sent the signal while
it works; it exits with 130 (143 for SIGTERM) and one line saying what it kept and what it did not, prints
no traceback, and leaves nothing half-written (no output folder it did not finish, no temporary file).

The process starts through a two-line wrapper that says ``READY`` on stderr once ``supportive.cli`` is
imported (the signal is sent a moment later, while the command works); for the saves, the wrapper also holds
the write in the middle (``os.fsync`` of the new file, or a bag's third frame) and says ``WRITING``, so the
signal lands there exactly, as a kill would.
"""

from __future__ import annotations

import contextlib
import gc
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
import weakref
from collections.abc import Callable
from pathlib import Path

import pytest
from tests.conftest import CliRunner

from supportive import examples
from supportive.cli.interrupt import NOTHING_WRITTEN, handling
from supportive.errors import FormulaError, OptionError
from supportive.generate import generate_task
from supportive.io.taskfile import parse_task_file, write_task_file
from supportive.service.launch import free_port

REPO = Path(__file__).resolve().parents[2]
BAG = REPO / "examples" / "bags" / "ikea-chair"

WRAPPER = """
import os, sys, time
hold = sys.argv[1]
if hold == "fsync":  # the first os.fsync of a new file (atomic_write, create_new) waits: the middle of a save
    def held(fd):
        sys.stderr.write("WRITING\\n"); sys.stderr.flush(); time.sleep(120)
    os.fsync = held
elif hold == "bag":  # the third frame of a beliefs bag waits: the middle of writing the bag
    from supportive.io.rosbag import beliefs
    write = beliefs.BeliefBag.write
    def held(self, time_, record):
        if self.frames == 2:
            sys.stderr.write("WRITING\\n"); sys.stderr.flush(); time.sleep(120)
        write(self, time_, record)
    beliefs.BeliefBag.write = held
elif hold == "building":  # building the command line waits: before any command starts
    import typer.main
    def held(app):
        sys.stderr.write("BUILDING\\n"); sys.stderr.flush(); time.sleep(120)
    typer.main.get_command = held
sys.argv = ["supportive", *sys.argv[2:]]
from supportive.cli import main
sys.stderr.write("READY\\n"); sys.stderr.flush()
main()
"""


def interrupt(
    args: list[str],
    cwd: Path,
    *,
    after: float = 1.0,
    wait_for: str = "READY",
    hold: str = "",
    stdin: str = "",
    sig: int = signal.SIGINT,
    group: bool = False,
    until: Callable[[], bool] = lambda: True,
    printed: str = "",
) -> tuple[int, str, list[str]]:
    """Run ``supportive ARGS``; once it has said ``wait_for`` on stderr, ``until()`` holds and it has printed
    ``printed`` on stdout, wait ``after`` seconds and send ``sig`` (to its whole process group with ``group``,
    as a terminal's Ctrl-C does). Its input stays open after ``stdin`` (a person who types nothing more).
    Returns the status, stdout and the lines of stderr but ``READY``, ``WRITING`` and ``BUILDING``."""
    process = subprocess.Popen(
        [sys.executable, "-c", WRAPPER, hold, *args],
        cwd=cwd,
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=group,
        env={**os.environ, "COLUMNS": "200"},
    )
    assert process.stdin is not None and process.stderr is not None and process.stdout is not None
    process.stdin.write(stdin)
    process.stdin.flush()
    output: list[str] = []  # stdout, read as it comes (a thread, so that stderr can be read meanwhile)
    stdout = process.stdout

    def read() -> None:
        for line in iter(stdout.readline, ""):
            output.append(line)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    seen: list[str] = []
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        line = process.stderr.readline()
        assert line, (process.poll(), seen)
        seen.append(line.rstrip("\n"))
        if seen[-1] == wait_for:
            break
    while not (until() and printed in "".join(output)) and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(after)
    assert process.poll() is None, f"{args} ended before the signal: make it longer"
    if group:
        os.killpg(process.pid, sig)
    else:
        process.send_signal(sig)
    process.stdin.close()  # as communicate() would
    err = process.stderr.read()
    process.wait(timeout=120)
    reader.join(timeout=120)
    lines = [line for line in [*seen, *err.splitlines()] if line not in ("READY", "WRITING", "BUILDING")]
    return process.returncode, "".join(output), lines


def progress(line: str) -> bool:
    """A progress line a long run prints every 5 s when stderr is not a terminal."""
    return " trials, " in line


def assert_stopped(code: int, lines: list[str], sig: int = signal.SIGINT) -> str:
    """Exit 128 + the signal, one line (after any progress lines), no traceback; the line's statement."""
    said = [line for line in lines if not progress(line)]
    assert code == 128 + sig, (code, lines)
    assert len(said) == 1, lines
    how = "interrupted (Ctrl-C)" if sig == signal.SIGINT else "stopped (SIGTERM)"
    assert said[0].startswith(f"supportive: {how}: "), said
    return said[0].split(": ", 2)[2]


def leftovers(folder: Path) -> list[str]:
    """Temporary files and staging folders anywhere under ``folder``."""
    return sorted(str(p.relative_to(folder)) for p in folder.rglob(".*") if ".tmp" in p.name or ".partial" in p.name)


@pytest.fixture(scope="module")
def big_task(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A task that takes ``learn`` some seconds and ``evaluate`` a minute."""
    path = tmp_path_factory.mktemp("interrupt") / "big.yaml"
    write_task_file(generate_task(1000, 1, demonstrations=40), path)
    return path


@pytest.fixture(scope="module")
def long_stream(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """48,000 moments of contact events: some seconds of ``infer``."""
    rows = [json.loads(line) for line in (REPO / "examples" / "ikea-chair-observations.jsonl").read_text().splitlines()]
    path = tmp_path_factory.mktemp("interrupt") / "long.jsonl"
    path.write_text("".join(json.dumps({**r, "time": 30 * k + r["time"]}) + "\n" for k in range(1000) for r in rows))
    return path


def nothing_new(tmp_path: Path, before: set[str]) -> None:
    assert {p.name for p in tmp_path.iterdir()} == before and leftovers(tmp_path) == []


CASES: dict[str, Callable[[Path, Path, Path], list[str]]] = {
    "learn": lambda task, stream, out: ["learn", str(task), "-f", "json", "-o", str(out / "htn.json")],
    "evaluate": lambda task, stream, out: ["evaluate", str(task)],
    "generate": lambda task, stream, out: ["generate", "--actions", "100000", "-d", "2", "-o", str(out / "t.yaml")],
    "infer": lambda task, stream, out: ["infer", "ikea-chair", "-O", str(stream)],
    "caregiver": lambda task, stream, out: ["caregiver", "--steps", "10000", "--gif", str(out / "e.gif")],
    "support": lambda task, stream, out: ["support", "two-cells-led", "-e", "3000", "--render", str(out / "t.png")],
    "workbench-sim": lambda task, stream, out: ["workbench-sim", "--seconds", "3600"],
    "demo": lambda task, stream, out: ["demo"],
    "reproduce": lambda task, stream, out: ["reproduce", "edge-reduction", "-n", "1000", "-o", str(out / "run")],
    "bag export": lambda task, stream, out: ["bag", "export", str(task), "-o", str(out / "bag")],
}


@pytest.mark.parametrize("command", list(CASES))
def test_ctrl_c_exits_130_with_one_line_and_writes_nothing(
    command: str, tmp_path: Path, big_task: Path, long_stream: Path
) -> None:
    before = {p.name for p in tmp_path.iterdir()}
    code, _, lines = interrupt(CASES[command](big_task, long_stream, tmp_path), tmp_path, after=0.5)
    statement = assert_stopped(code, lines)
    assert statement.startswith("nothing written") or statement == f"bag {tmp_path / 'bag'} not written", lines
    nothing_new(tmp_path, before)


def test_sigterm_stops_like_ctrl_c_with_status_143(tmp_path: Path, big_task: Path) -> None:
    args = ["learn", str(big_task), "-o", str(tmp_path / "h.txt")]
    code, _, lines = interrupt(args, tmp_path, sig=signal.SIGTERM, after=0.5)
    assert assert_stopped(code, lines, signal.SIGTERM) == "nothing written"
    assert list(tmp_path.iterdir()) == []


def test_ctrl_c_at_a_terminal_stops_a_dask_run_without_a_worker_traceback(tmp_path: Path) -> None:
    """The whole process group gets the signal, the workers too (as from a terminal), while they start and
    while they run trials."""
    for after in (0.5, 2.0, 6.0):  # 1,000 trials: a run of a minute or more, still working when the signal comes
        args = ["reproduce", "edge-reduction", "-n", "1000", "--workers", "2", "-o", str(tmp_path / "run")]
        code, _, lines = interrupt(args, tmp_path, after=after, group=True)
        assert assert_stopped(code, lines).startswith("nothing written"), lines  # (to run/, once it was running)
        assert list(tmp_path.iterdir()) == []


def test_ctrl_c_while_the_command_line_is_built_stops_with_one_line(tmp_path: Path) -> None:
    # typer builds the command line (some tenths of a second) after the signals are handled: a Ctrl-C there
    # ended the program with a traceback and the signal's own status (-2), found by sending it at random times
    code, out, lines = interrupt(["learn", "blocks-tower"], tmp_path, hold="building", wait_for="BUILDING", after=0.2)
    assert assert_stopped(code, lines) == NOTHING_WRITTEN and out == ""


def test_an_interrupted_run_leaves_an_earlier_run_whole(tmp_path: Path) -> None:
    run = tmp_path / "run"
    code = subprocess.run([sys.executable, "-m", "supportive.cli", "reproduce", "edge-reduction", "-n", "2", "-o", str(run)],
                          capture_output=True, check=False).returncode
    assert code == 0
    files = {p.name: p.read_bytes() for p in run.iterdir()}
    code, _, lines = interrupt(["reproduce", "edge-reduction", "-n", "1000", "-o", str(run)], tmp_path, after=1.5)
    assert assert_stopped(code, lines).startswith("nothing written"), lines  # (to run/: once the run had begun)
    assert {p.name: p.read_bytes() for p in run.iterdir()} == files and leftovers(tmp_path) == []


def test_ctrl_c_in_teach_keeps_the_copy_and_says_the_demonstration_was_dropped(tmp_path: Path) -> None:
    source = tmp_path / "tower.yaml"
    shutil.copy(examples.path("blocks-tower"), source)
    copy = tmp_path / "tower.edited.yaml"  # made when the first demonstration is saved
    typed = "red\nyellow\ngreen\nwhite\norange\npurple\nblack\nblue\nred\nyellow\n"
    code, out, lines = interrupt(["teach", str(source)], tmp_path, stdin=typed, until=copy.exists, after=1.0)
    assert assert_stopped(code, lines) == (
        f"kept {copy}: 5 demonstrations, 4 when this session began; dropped the unfinished demonstration (2 steps)"
    )
    assert len(parse_task_file(copy).demonstrations) == 5 and "Demonstration d6:" in out


def test_ctrl_c_in_chat_keeps_every_change_acknowledged(tmp_path: Path) -> None:
    said = "When I am attaching the seat, I want you to hold the frames steady.\nyes\n"
    copy = tmp_path / "c.yaml"

    def saved() -> bool:  # the copy, made, then changed
        return copy.exists() and copy.read_bytes() != examples.path("ikea-chair").read_bytes()

    args = ["chat", "ikea-chair", "--save", "c.yaml"]
    code, out, lines = interrupt(args, tmp_path, stdin=said, until=saved, printed="hold", after=0.2)
    assert assert_stopped(code, lines) == "kept c.yaml: every change acknowledged is saved in it (1 change this session)"
    assert "hold" in out and any("hold" in b.text for b in parse_task_file(tmp_path / "c.yaml").behaviors)


def test_ctrl_c_while_serving_says_the_board_is_kept(tmp_path: Path) -> None:
    port = free_port()
    args = ["serve", "--db", f"sqlite:///{tmp_path / 'b.db'}", "--port", str(port)]

    def serving() -> bool:
        with socket.socket() as probe:
            return probe.connect_ex(("127.0.0.1", port)) == 0

    code, out, lines = interrupt(args, tmp_path, until=serving, after=0.2)
    assert assert_stopped(code, lines) == f"the board stopped; every operation it acknowledged is kept in sqlite:///{tmp_path / 'b.db'}"
    assert "new token for alice" in out


# -- a kill in the middle of a save: the old file or the new one, never a truncated one ------------------
# Each save is cut once: Ctrl-C and SIGTERM take one path (cli.interrupt turns both into the same stop), so the
# two signals alternate over the saves rather than each save being cut twice: every save is cut by one, and
# each signal cuts both a save over an existing file (Ctrl-C: teach, chat; SIGTERM: bag import) and the making
# of something new (Ctrl-C: the beliefs bag; SIGTERM: the working copy).


@pytest.mark.parametrize("sig", [signal.SIGINT], ids=["ctrl-c"])
def test_a_teach_save_cut_in_the_middle_leaves_the_file_as_it_was(tmp_path: Path, sig: int) -> None:
    copy = tmp_path / "tower.edited.yaml"  # carries on in it: the first write is the demonstration's save
    shutil.copy(examples.path("blocks-tower"), copy)
    before = copy.read_bytes()
    order = "red\nyellow\ngreen\nwhite\norange\npurple\nblack\nblue\n"
    code, _, lines = interrupt(["teach", str(copy)], tmp_path, hold="fsync", wait_for="WRITING", stdin=order, sig=sig, after=0.2)
    assert assert_stopped(code, lines, sig) == (
        f"kept {copy}: 4 demonstrations, 4 when this session began; dropped the demonstration being saved (the save "
        "did not finish)"
    )
    assert copy.read_bytes() == before and leftovers(tmp_path) == []


@pytest.mark.parametrize("sig", [signal.SIGTERM], ids=["sigterm"])
def test_a_new_working_copy_cut_in_the_middle_is_not_made(tmp_path: Path, sig: int) -> None:
    args = ["teach", "blocks-tower", "--save", "c.yaml"]  # made at the first save: the demonstration's
    order = "red\nyellow\ngreen\nwhite\norange\npurple\nblack\nblue\n"
    code, _, lines = interrupt(args, tmp_path, hold="fsync", wait_for="WRITING", stdin=order, sig=sig, after=0.2)
    assert assert_stopped(code, lines, sig) == (
        "nothing written; dropped the demonstration being saved (the save did not finish)"
    )
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("sig", [signal.SIGINT], ids=["ctrl-c"])
def test_a_chat_save_cut_in_the_middle_leaves_the_file_as_it_was(tmp_path: Path, sig: int) -> None:
    copy = tmp_path / "c.yaml"  # the copy exists: the first write is the change's save
    shutil.copy(examples.path("ikea-chair"), copy)
    before = copy.read_bytes()
    said = "When I am attaching the seat, I want you to hold the frames steady.\nyes\n"
    args = ["chat", "ikea-chair", "--save", str(copy)]
    code, _, lines = interrupt(args, tmp_path, hold="fsync", wait_for="WRITING", stdin=said, sig=sig, after=0.2)
    assert assert_stopped(code, lines, sig) == f"kept {copy}: every change acknowledged is saved in it (0 changes this session)"
    assert copy.read_bytes() == before and leftovers(tmp_path) == []


@pytest.mark.parametrize("sig", [signal.SIGTERM], ids=["sigterm"])
def test_a_bag_import_cut_in_the_middle_leaves_the_old_file(tmp_path: Path, sig: int) -> None:
    target = tmp_path / "chair.yaml"
    target.write_text("name: an earlier import\n")
    args = ["bag", "import", str(BAG), "--segment-topic", "/task/demonstration", "-o", str(target), "--force"]
    code, _, lines = interrupt(args, tmp_path, hold="fsync", wait_for="WRITING", sig=sig, after=0.2)
    assert assert_stopped(code, lines, sig) == f"{target} not written (it is as it was)"
    assert target.read_text() == "name: an earlier import\n" and leftovers(tmp_path) == []


@pytest.mark.parametrize("sig", [signal.SIGINT], ids=["ctrl-c"])
def test_a_beliefs_bag_cut_in_the_middle_is_not_left_behind(tmp_path: Path, sig: int) -> None:
    args = ["infer", "ikea-chair", "--bag", str(BAG), "--write-bag", str(tmp_path / "beliefs")]
    code, out, lines = interrupt(args, tmp_path, hold="bag", wait_for="WRITING", sig=sig, after=0.2)
    assert assert_stopped(code, lines, sig) == "nothing written"
    assert len(out.splitlines()) == 2  # the two frames before the one it stopped in
    assert list(tmp_path.iterdir()) == []  # neither the bag nor its hidden staging folder


def test_an_error_a_library_raises_from_a_ctrl_c_is_an_interruption(
    cli: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A library that turns a KeyboardInterrupt into an error of its own (``raise … from``) is still an
    interruption: 130 and the one line, no traceback (a Ctrl-C under load once landed in such a place)."""
    import supportive.io.taskfile as taskfile

    def parse(*args: object, **kwargs: object) -> None:
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as exc:
            raise RuntimeError("parsing stopped") from exc

    monkeypatch.setattr(taskfile, "parse_task_file", parse)
    code, out, err = cli(["learn", "blocks-v"])
    assert code == 130 and out == ""
    assert err.strip().splitlines() == ["supportive: interrupted (Ctrl-C): nothing written"]


class Finalised:
    """An object whose finaliser runs ``then``."""

    def __init__(self, then: Callable[[], None]) -> None:
        self.then = then

    def __del__(self) -> None:
        self.then()


def in_a_gc_callback(then: Callable[[], None]) -> None:
    """Run ``then`` in a garbage collector's callback (dask's scheduler installs one)."""

    def callback(phase: str, info: dict[str, int]) -> None:
        if phase == "start":
            then()

    gc.callbacks.append(callback)
    try:
        gc.collect()
    finally:
        gc.callbacks.remove(callback)


def in_a_weakref_callback(then: Callable[[], None]) -> None:
    """Run ``then`` in a weak reference's callback (the import system's module locks have them)."""
    target = Finalised(lambda: None)
    reference = weakref.ref(target, lambda _: then())
    del target
    assert reference() is None


def in_a_finaliser(then: Callable[[], None]) -> None:
    """Run ``then`` in an object's ``__del__``."""
    Finalised(then)


@pytest.mark.parametrize("where", [in_a_gc_callback, in_a_weakref_callback, in_a_finaliser])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_that_lands_where_python_drops_exceptions_is_not_lost(
    sig: int, where: Callable[[Callable[[], None]], None], capsys: pytest.CaptureFixture[str]
) -> None:
    """Python drops an exception raised in a gc callback, a weak reference's callback or a finaliser: a Ctrl-C
    landing in dask's gc callback once let a dask run go on to the end and exit 0, and one landing in an import
    lock's weakref callback made a run exit 1. It is delivered again, after the callback, and nothing is
    printed."""

    def land() -> None:
        signal.raise_signal(sig)
        sum(range(100))  # the handler runs here, inside the callback

    with handling() as stopped, pytest.raises(KeyboardInterrupt):
        where(land)
        for _ in range(500):  # sent again from another thread: it arrives a moment later
            time.sleep(0.01)
    assert stopped.signal == sig
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_caught_and_let_go_by_code_the_command_runs_is_sent_again(
    sig: int, capsys: pytest.CaptureFixture[str]
) -> None:
    """A library's bare ``except:`` (around an import) once caught a Ctrl-C that landed in it and let it go:
    the demo ran to its end and exited 0. The command, going on as if nothing came, is interrupted again."""
    deadline = time.monotonic() + 60
    with handling(astray_after=0.2) as stopped, pytest.raises(KeyboardInterrupt) as raised:
        with contextlib.suppress(BaseException):  # what a bare except that lets the signal go does
            signal.raise_signal(sig)
        while time.monotonic() < deadline:  # the command goes on: the signal comes again, 0.2 s later
            time.sleep(0.01)
    assert stopped.signal == sig and time.monotonic() < deadline
    assert raised.value.__context__ is None and capsys.readouterr().err == ""


def test_an_error_after_an_interruption_let_go_is_reported_as_the_interruption(
    cli: CliRunner, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A Ctrl-C that landed in a parser once left it in a wrong state: the demo stopped with exit 2 and an error
    about a formula it reads every time. The user pressed Ctrl-C: that is what the line says."""
    from supportive.cli import demo_tour

    def let_go(out: object) -> None:
        with contextlib.suppress(BaseException):
            signal.raise_signal(signal.SIGINT)
        raise FormulaError("cannot read the formula 'present(seat)'")

    monkeypatch.setattr(demo_tour, "run_demo", let_go)
    code, out, err = cli(["demo"])
    assert code == 130 and out == ""
    assert err.strip().splitlines() == [f"supportive: interrupted (Ctrl-C): {NOTHING_WRITTEN}"]


def test_the_wait_before_sending_again_must_be_above_zero() -> None:
    with pytest.raises(OptionError, match="astray_after must be above 0 seconds, got 0"), handling(astray_after=0):
        pass


@pytest.mark.parametrize("how", ["finally", "except"])
def test_an_interruption_handled_slowly_on_its_way_up_is_not_sent_again(how: str) -> None:
    """Cleaning up on an interruption's way up (closing a cluster: seconds) is not going on without it."""
    with handling(astray_after=0.2), pytest.raises(KeyboardInterrupt) as raised:
        try:
            signal.raise_signal(signal.SIGINT)
        except KeyboardInterrupt:
            if how == "except":
                time.sleep(1.0)  # five times astray_after
            raise
        finally:
            if how == "finally":
                time.sleep(1.0)
    assert raised.value.__context__ is None  # the interruption raised, not a second one raised in the cleanup


def test_an_error_dropped_while_a_command_runs_goes_to_the_hook_there_before(monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[BaseException | None] = []
    before = seen.append  # stands for the hook there was (Python's prints "Exception ignored in")
    monkeypatch.setattr(sys, "unraisablehook", lambda what: before(what.exc_value))

    def fail() -> None:
        raise ValueError("a finaliser's own error")

    hook = sys.unraisablehook
    with handling():
        in_a_finaliser(fail)
    assert [str(error) for error in seen] == ["a finaliser's own error"]
    assert sys.unraisablehook is hook


LOADING = """
import importlib.abc, sys, time, weakref
where = sys.argv[1]
def hold():
    sys.stderr.write("LOADING\\n"); sys.stderr.flush(); time.sleep(120)
class Held(importlib.abc.MetaPathFinder):  # the command's module waits as it is found: the middle of loading
    def find_spec(self, name, path, target=None):
        if name == "supportive.cli":
            if where == "import":
                hold()
            else:  # in a weak reference's callback, where Python drops an exception raised
                class Target: pass
                target = Target(); reference = weakref.ref(target, lambda _: hold()); del target
        return None
sys.meta_path.insert(0, Held())
sys.argv = ["supportive", "--help"]
from supportive.launch import main
main()
"""


@pytest.mark.parametrize("where", ["import", "weakref callback"])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_while_the_command_loads_stops_it_with_one_line(tmp_path: Path, sig: int, where: str) -> None:
    # The command's modules take some tenths of a second to import; a Ctrl-C in that time ends it as one later
    # does, not with a traceback from the middle of an import (the `supportive` program starts in
    # supportive.launch, which takes care of the signals before it loads them).
    process = subprocess.Popen(
        [sys.executable, "-c", LOADING, where], cwd=tmp_path, stderr=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    assert process.stderr is not None
    assert process.stderr.readline() == "LOADING\n"
    process.send_signal(sig)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 128 + sig
    assert out == ""
    how = "interrupted (Ctrl-C)" if sig == signal.SIGINT else "stopped (SIGTERM)"
    assert err.splitlines() == [f"supportive: {how}: nothing written"]
