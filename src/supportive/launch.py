"""Where the ``supportive`` program starts: it takes care of Ctrl-C and SIGTERM, then loads the command.

The command's modules (:mod:`supportive.cli` and what it draws on) take some tenths of a second to import. A
signal in that time used to end the program with a traceback from the middle of an import; here it ends it
as one that comes later does (:mod:`supportive.cli.interrupt`): one line, status 130 (143 for SIGTERM),
nothing written. This module imports nothing of the package before the signals are taken care of.
"""

from __future__ import annotations

import signal
import sys
import threading
from types import FrameType

__all__ = ["main"]

_STOPPING = (signal.SIGINT, signal.SIGTERM)


def main() -> None:
    """The ``supportive`` program: :func:`supportive.cli.main`, loaded with the signals taken care of."""
    here = threading.current_thread() is threading.main_thread()  # where Python runs signal handlers
    previous = {number: signal.signal(number, _while_loading) for number in _STOPPING} if here else {}
    from supportive.cli import main as run

    for number, handler in previous.items():
        signal.signal(number, handler if handler is not None else signal.SIG_DFL)
    run()


def _while_loading(signum: int, frame: FrameType | None) -> None:
    """Stop at once, in the words the command uses for a stop before it wrote anything."""
    how = "interrupted (Ctrl-C)" if signum == signal.SIGINT else f"stopped ({signal.Signals(signum).name})"
    sys.stderr.write(f"supportive: {how}: nothing written\n")
    sys.stderr.flush()
    raise SystemExit(128 + signum)
