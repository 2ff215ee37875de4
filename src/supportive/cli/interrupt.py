"""What Ctrl-C (SIGINT) and SIGTERM do to a command: it stops where it is, leaves no file half-written (every
write is atomic), exits with status 130 (143 for SIGTERM) and says in one line on stderr what it kept and
what it did not::

    supportive: interrupted (Ctrl-C): kept my-tower.yaml (2 demonstrations saved this session); dropped the unfinished demonstration (3 steps)

:func:`handling` turns SIGTERM into the same interruption as Ctrl-C (so ``finally`` blocks and staged writes
clean up) for as long as the command runs. A command says what an interruption would leave with
:func:`explained` (its statement is made after the interruption, so it can look at what is on disk) or
:func:`writing` (one file or folder it writes: kept when it changed, else not written); without either,
the line says nothing was written.
"""

from __future__ import annotations

import os
import queue
import signal
import sys
import threading
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from types import FrameType

from supportive.stop_line import NOTHING_WRITTEN, stop_line

__all__ = ["NOTHING_WRITTEN", "Interruption", "changes", "explained", "handling", "interruption", "writing"]


@dataclass
class Interruption:
    """The interruption of the running command.

    Attributes:
        signal: The signal that stopped it (``SIGINT`` for Ctrl-C unless SIGTERM was recorded).
        statements: What the command said it kept and did not, innermost first.
    """

    signal: int = signal.SIGINT
    statements: list[str] = field(default_factory=list)

    @property
    def status(self) -> int:
        """The exit status: 128 plus the signal's number (130 for Ctrl-C, 143 for SIGTERM)."""
        return 128 + int(self.signal)

    def line(self) -> str:
        """The one line to print."""
        return stop_line(self.signal, "; ".join(dict.fromkeys(s for s in self.statements if s)) or NOTHING_WRITTEN)


_current = Interruption()


def interruption() -> Interruption:
    """The running command's interruption (what :func:`handling` and the statements recorded)."""
    return _current


@contextmanager
def handling() -> Iterator[Interruption]:
    """While the block runs, SIGTERM raises ``KeyboardInterrupt`` like Ctrl-C does (recording which signal it
    was); the previous handlers come back afterwards. Yields the interruption, fresh. Outside the main thread
    (where Python runs signal handlers) only the interruption is made fresh.

    Python runs a signal's handler wherever the main thread is, and an exception raised where nothing can
    catch it — a garbage collector's callback (dask's scheduler installs one), a weak reference's callback
    (the import system's locks have them), a finaliser — is handed to :func:`sys.unraisablehook` and dropped,
    not passed on: the signal would be lost and the command go on. While the block runs, an interruption
    dropped so is not printed but sent again, from a thread of the block's own, until it arrives where it can
    be raised; other dropped exceptions go to the hook that was there before."""
    _current.signal = signal.SIGINT
    _current.statements.clear()
    if threading.current_thread() is not threading.main_thread():
        yield _current
        return
    again = _Resender()
    unraisable = sys.unraisablehook

    def stop(signum: int, frame: FrameType | None) -> None:
        _current.signal = signum
        raise KeyboardInterrupt

    def dropped(what: sys.UnraisableHookArgs) -> None:
        if what.exc_type is not None and issubclass(what.exc_type, KeyboardInterrupt):
            again.send(_current.signal)
        else:
            unraisable(what)

    sys.unraisablehook = dropped
    previous = {number: signal.signal(number, stop) for number in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield _current
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler if handler is not None else signal.SIG_DFL)
        sys.unraisablehook = unraisable
        again.close()


class _Resender:
    """A thread that sends the main thread a signal again when asked (a queue written from a signal handler:
    :class:`queue.SimpleQueue` is reentrant)."""

    def __init__(self) -> None:
        self._queue: queue.SimpleQueue[int | None] = queue.SimpleQueue()
        self._main = threading.get_ident()
        self._thread = threading.Thread(target=self._run, name="supportive-signal-again", daemon=True)
        self._thread.start()

    def send(self, signum: int) -> None:
        """Send ``signum`` to the main thread again, from the thread."""
        self._queue.put(signum)

    def close(self) -> None:
        """Stop the thread."""
        self._queue.put(None)
        self._thread.join()

    def _run(self) -> None:
        while (signum := self._queue.get()) is not None:
            signal.pthread_kill(self._main, signum)


@contextmanager
def explained(statement: Callable[[], str]) -> Iterator[None]:
    """An interruption of the block is explained by ``statement()``, made after it (so it can look at the
    files): what was kept and what was not."""
    try:
        yield
    except KeyboardInterrupt:
        _current.statements.append(statement())
        raise


@contextmanager
def writing(path: Path | None, what: str = "") -> Iterator[None]:
    """The block writes ``path`` (a file or a folder, atomically): an interruption says it was kept when it
    changed, and that it was not written otherwise. ``None`` writes nothing (stdout)."""
    if path is None:
        yield
        return
    existed = path.exists()
    changed = changes([path])

    def statement() -> str:
        name = f"{what} {path}".strip()
        if changed():
            return f"kept {name} (written before the interruption)"
        return f"{name} not written" + (" (it is as it was)" if existed else "")

    with explained(statement):
        yield


def changes(paths: Sequence[Path]) -> Callable[[], list[Path]]:
    """A function saying which of ``paths`` (files or folders) have changed since now: replaced, made,
    removed, or written to."""
    before = {path: _state(path) for path in paths}
    return lambda: [path for path in paths if _state(path) != before[path]]


def _state(path: Path) -> tuple[int, int, int] | None:
    """What tells a file or folder apart from the one before it: inode, size, modification time."""
    try:
        info = os.stat(path)
    except OSError:
        return None
    return info.st_ino, info.st_size, info.st_mtime_ns
