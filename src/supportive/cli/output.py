"""What every command shares: the consoles it prints to, one line of a user's text, checks of option values,
and naming the file in an error about its contents."""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import typer

from supportive.errors import FileFormatError, MissingExtraError, SupportiveError, TaskFileError, naming
from supportive.render.terminal import printable, terminal_console
from supportive.tasks.spec import TaskSpec

__all__ = ["about", "csv_note", "err", "finite", "line_editing", "local_workers", "out", "say", "write_text"]

out = terminal_console(soft_wrap=False)  # wraps at words to the terminal's width (COLUMNS when set)
err = terminal_console(stderr=True)  # an error is one line, whatever its length


def say(line: object, *, to_stderr: bool = False, whole: bool = False) -> None:
    """Print one line that may hold a user's text: as text (never markup or emoji), escaped for the terminal
    (:mod:`supportive.render.terminal`); ``whole`` keeps it on one line whatever the terminal's width (a URL,
    a token or a command to copy and paste)."""
    console = err if to_stderr else out
    console.print(printable(str(line)), markup=False, soft_wrap=whole or console.soft_wrap)


def finite(value: float | None) -> float | None:
    """A float option's value when it is a number (click lets ``nan`` through its ranges)."""
    if value is not None and not math.isfinite(value):
        raise typer.BadParameter(f"expected a finite number, got {value}")
    return value


def local_workers(value: int | None) -> int | None:
    """A ``--workers`` value for processes on this machine: at most twice its cores (at least 2). More only
    slow a run down, each process costing memory (a dask worker some 100 MB); a cluster has ``--scheduler``.

    Raises:
        OptionError: for more.
    """
    import os

    from supportive.errors import OptionError

    most = max(2, 2 * (os.cpu_count() or 1))
    if value is not None and value > most:
        raise OptionError(
            f"{value} processes on a machine with {os.cpu_count()} cores: give at most {most} (twice the cores)",
            "--workers",
        )
    return value


@contextmanager
def about(path: Path) -> Iterator[None]:
    """Name ``path`` in an error the library raises about its contents (a demonstration, the task) without
    naming the file; file errors name it already, and a missing extra is not the file's fault."""
    try:
        yield
    except (FileFormatError, MissingExtraError):
        raise
    except SupportiveError as exc:
        raise naming(exc, path) from None


def write_text(text: str, output: Path | None) -> None:
    """Print ``text``, or write it to ``output`` (atomically; a failure names the file)."""
    if output is None:
        sys.stdout.write(text)
        return
    from supportive.cli.interrupt import writing
    from supportive.io.atomic import atomic_write

    with writing(output):
        atomic_write(output, text, error=TaskFileError)


def line_editing() -> bool:
    """Give ``input()`` line editing and history (arrow keys, Ctrl-A/E, …) where Python has readline and the
    input is a terminal; whether it did. Importing :mod:`readline` is all it takes."""
    if not sys.stdin.isatty():
        return False
    try:
        import readline  # noqa: F401 - importing it turns line editing on for input()
    except ImportError:  # a Python built without it (Windows): plain input
        return False
    return True


def csv_note(spec: TaskSpec, fmt: str, output: Path | None) -> None:
    """Say on stderr, in one line, what a task written as CSV leaves out (the structure, the action texts, …):
    nothing when the format is not CSV or nothing is lost."""
    from supportive.io.taskfile import csv_leaves_out

    if fmt != "csv":
        return
    lost = csv_leaves_out(spec)
    if lost:
        where = output if output is not None else "the CSV"
        said = ", ".join(lost[:-1]) + (" and " if len(lost) > 1 else "") + lost[-1]
        say(
            f"supportive: note: {where} holds the demonstrations only: {said} {'are' if len(lost) > 1 else 'is'} "
            "not written (.yaml or .json keeps them)",
            to_stderr=True,
        )
