"""Imported by the fork server of a local dask cluster, first of its preloads: there it ignores Ctrl-C, and
so do the worker processes it forks (Python's fork server hands its children the handlers it had once its
preloads were imported).

A terminal's Ctrl-C reaches every process of its foreground group; a worker that took it would die with a
traceback while the run, which gets it too, stops and closes the cluster in order. Imported anywhere else
(a doctest run, a reader's ``import``), this module changes nothing.
"""

from __future__ import annotations

import signal
import sys
import threading

__all__ = ["imported_by_fork_server"]


def imported_by_fork_server() -> bool:
    """Whether this import runs inside ``multiprocessing.forkserver.main`` (the fork server's preloads)."""
    frame = sys._getframe()
    while frame is not None:
        if frame.f_globals.get("__name__") == "multiprocessing.forkserver" and frame.f_code.co_name == "main":
            return True
        frame = frame.f_back  # type: ignore[assignment]
    return False


if imported_by_fork_server() and threading.current_thread() is threading.main_thread():
    signal.signal(signal.SIGINT, signal.SIG_IGN)
