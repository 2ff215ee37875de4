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
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from types import FrameType

from supportive.errors import OptionError
from supportive.stop_line import NOTHING_WRITTEN, stop_line

__all__ = [
    "NOTHING_WRITTEN",
    "Interruption",
    "causes",
    "changes",
    "explained",
    "handling",
    "interruption",
    "writing",
]


@dataclass
class Interruption:
    """The interruption of the running command.

    Attributes:
        signal: The signal that stopped it (``SIGINT`` for Ctrl-C unless SIGTERM was recorded).
        statements: What the command said it kept and did not, innermost first.
        raised: Whether a signal was raised in the command as a ``KeyboardInterrupt`` (an error that follows
            may be its doing: code that caught it and let it go can be left in a wrong state).
        arrived: Whether it reached the top of the command line (set there): from then on it is not sent
            again, however long saying so takes.
    """

    signal: int = signal.SIGINT
    statements: list[str] = field(default_factory=list)
    raised: bool = False
    arrived: bool = False

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
def handling(astray_after: float = 0.5) -> Iterator[Interruption]:
    """While the block runs, SIGTERM raises ``KeyboardInterrupt`` like Ctrl-C does (recording which signal it
    was); the previous handlers come back afterwards. Yields the interruption, fresh. Outside the main thread
    (where Python runs signal handlers) only the interruption is made fresh.

    Python runs a signal's handler wherever the main thread is, and an exception raised where nothing can
    catch it — a garbage collector's callback (dask's scheduler installs one), a weak reference's callback
    (the import system's locks have them), a finaliser — is handed to :func:`sys.unraisablehook` and dropped,
    not passed on: the signal would be lost and the command go on. While the block runs, an interruption
    dropped so is not printed but sent again, from a thread of the block's own, until it arrives where it can
    be raised; other dropped exceptions go to the hook that was there before. An interruption can also be
    caught and let go by code the command runs, as a bare ``except:`` does (the demo once ran to its end and
    exited 0 after a Ctrl-C, and once stopped with an error about a formula it had read many times, the
    signal having landed in the parser): when the main thread goes on for ``astray_after`` seconds neither
    handling the interruption (an ``except`` or ``finally`` block, a ``with`` block's exit, running on its
    way up) nor passing it on, the same thread sends the signal again; and an error raised after an
    interruption is reported as the interruption (:attr:`Interruption.raised`), since it may be its doing.

    Args:
        astray_after: Seconds (above 0) the main thread may go on after an interruption, neither handling it
            nor passing it on, before the signal is sent again. Not fitted to data: the default, half a second,
            is far longer than the moment between a command's end and the line saying it was interrupted and
            far shorter than a person waits before pressing Ctrl-C again.

    Raises:
        OptionError: when ``astray_after`` is not above 0.
    """
    if not astray_after > 0:
        raise OptionError(f"astray_after must be above 0 seconds, got {astray_after}")
    _current.signal = signal.SIGINT
    _current.statements.clear()
    _current.raised = _current.arrived = False
    if threading.current_thread() is not threading.main_thread():
        yield _current
        return
    again = _Resender(astray_after)
    unraisable = sys.unraisablehook

    def stop(signum: int, frame: FrameType | None) -> None:
        _current.signal = signum
        _current.raised = True
        raised = KeyboardInterrupt()
        again.watch(raised)
        raise raised

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


_WATCH = "watch"
"""Put in the resender's queue when an interruption is to be watched (a word, where signals are numbers)."""


class _Resender:
    """A thread that sends the main thread a signal again: when asked (a queue written from a signal handler:
    :class:`queue.SimpleQueue` is reentrant), and when the interruption it watches has gone astray (see
    :func:`handling`)."""

    def __init__(self, astray_after: float) -> None:
        self._astray_after = astray_after
        self._queue: queue.SimpleQueue[int | str | None] = queue.SimpleQueue()
        self._main = threading.get_ident()
        self._watched: KeyboardInterrupt | None = None
        self._thread = threading.Thread(target=self._run, name="supportive-signal-again", daemon=True)
        self._thread.start()

    def send(self, signum: int) -> None:
        """Send ``signum`` to the main thread again, from the thread."""
        self._queue.put(signum)

    def watch(self, raised: KeyboardInterrupt) -> None:
        """Watch ``raised``, just raised in the main thread: it must be handled or passed on there."""
        self._watched = raised
        self._queue.put(_WATCH)

    def close(self) -> None:
        """Stop the thread."""
        self._queue.put(None)
        self._thread.join()

    def _run(self) -> None:
        astray_since: float | None = None
        while True:
            try:
                signum = self._queue.get(timeout=None if self._watched is None else self._astray_after / 5)
            except queue.Empty:
                if not self._astray():
                    astray_since = None
                    continue
                astray_since = time.monotonic() if astray_since is None else astray_since
                if time.monotonic() - astray_since < self._astray_after:
                    continue
                signum = _current.signal
            if signum is None:
                return
            astray_since = None
            if isinstance(signum, int):  # not _WATCH
                self._watched = None
                signal.pthread_kill(self._main, signum)

    def _astray(self) -> bool:
        """Whether the main thread is neither handling the watched interruption nor an exception it caused,
        and the interruption has not arrived."""
        if _current.arrived:
            return False
        handled = sys._current_exceptions().get(self._main)
        exception = handled[1] if isinstance(handled, tuple) else handled  # a 3-tuple before Python 3.12
        return not any(cause is self._watched for cause in causes(exception))


def causes(exception: BaseException | None) -> Iterator[BaseException]:
    """``exception`` and the exceptions it was raised from or while handling, innermost first."""
    seen: set[int] = set()
    while exception is not None and id(exception) not in seen:
        yield exception
        seen.add(id(exception))
        exception = exception.__cause__ or exception.__context__


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
