"""Where the ``supportive`` program starts: it takes care of Ctrl-C and SIGTERM, then loads the command.

The command's modules (:mod:`supportive.cli` and what it draws on) take some tenths of a second to import. A
signal in that time used to end the program with a traceback from the middle of an import; here it ends it
as one that comes later does (:mod:`supportive.cli.interrupt`): one line, status 130 (143 for SIGTERM),
nothing written. Before the signals are taken care of it imports nothing of the package but the words of that
line (:mod:`supportive.stop_line`; with it the package loads its error classes, nothing more).
"""

from __future__ import annotations

import os
import signal
import sys
import threading
from types import FrameType

from supportive.stop_line import stop_line  # as light as this module: it imports nothing of the package

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
    """Stop at once, in the words the command uses for a stop before it wrote anything.

    The program ends here rather than raising :class:`SystemExit`: a signal can land where Python drops an
    exception (a weak reference's callback — the import system's module locks have them — or a finaliser),
    and loading would go on. Nothing is written while the command loads, so nothing is left to clean up."""
    sys.stderr.write(stop_line(signum) + "\n")
    sys.stderr.flush()
    os._exit(128 + signum)
