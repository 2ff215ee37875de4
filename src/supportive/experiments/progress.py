"""Progress of a run: a rich bar on a terminal; otherwise (piped, in a log, in CI) one line on stderr every
:data:`PERIOD` seconds, so a long run is never silent."""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

__all__ = ["PERIOD", "progress_bar"]

PERIOD = 5.0
"""Seconds between progress lines when stderr is not a terminal."""


@contextmanager
def progress_bar(description: str, total: int, *, enabled: bool = True) -> Iterator[Callable[[], None]]:
    """A function to call once per finished trial; it advances a bar on stderr when stderr is a terminal, and
    otherwise prints ``description: k/total trials, m:ss`` to stderr every :data:`PERIOD` seconds.

    Args:
        description: What is running (shown left of the bar).
        total: Number of trials.
        enabled: False to stay silent.

    >>> with progress_bar("demo", 2, enabled=False) as advance:
    ...     advance()
    """
    console = Console(stderr=True)
    if not enabled:
        yield lambda: None
        return
    if not console.is_terminal:
        with _lines(description, total) as advance:
            yield advance
        return
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn())
    with Progress(*columns, console=console) as bar:
        task = bar.add_task(description, total=total)
        yield lambda: bar.advance(task)


@contextmanager
def _lines(description: str, total: int) -> Iterator[Callable[[], None]]:
    """A progress line on stderr every :data:`PERIOD` seconds, from a thread, until the run ends."""
    done = 0
    stop = threading.Event()
    start = time.monotonic()

    def advance() -> None:
        nonlocal done
        done += 1

    def report() -> None:
        while not stop.wait(PERIOD):
            minutes, seconds = divmod(int(time.monotonic() - start), 60)
            sys.stderr.write(f"{description}: {done}/{total} trials, {minutes}:{seconds:02d}\n")
            sys.stderr.flush()

    thread = threading.Thread(target=report, name="progress", daemon=True)
    thread.start()
    try:
        yield advance
    finally:
        stop.set()
        thread.join()
