"""How the ``supportive`` program says it was stopped by a signal: one line, the same whether the signal came
while the command was loading (:mod:`supportive.launch`) or while it worked (:mod:`supportive.cli.interrupt`).

This module imports nothing from the package, so the program can say it before the command is loaded.
"""

from __future__ import annotations

import signal

__all__ = ["NOTHING_WRITTEN", "stop_line"]

NOTHING_WRITTEN = "nothing written"
"""What the line says when the command had written nothing."""


def stop_line(signum: int, said: str = NOTHING_WRITTEN) -> str:
    """The line for a stop by signal ``signum`` (Ctrl-C or another), saying ``said`` about the files.

    >>> stop_line(signal.SIGINT)
    'supportive: interrupted (Ctrl-C): nothing written'
    >>> stop_line(signal.SIGTERM, "kept board.db")
    'supportive: stopped (SIGTERM): kept board.db'
    """
    how = "interrupted (Ctrl-C)" if signum == signal.SIGINT else f"stopped ({signal.Signals(signum).name})"
    return f"supportive: {how}: {said}"
