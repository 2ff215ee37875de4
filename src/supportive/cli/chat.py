"""``supportive chat``: tell the robot how to help and hear it explain its policy, in a copy of the task file."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.interrupt import NOTHING_WRITTEN, explained
from supportive.cli.output import about, line_editing, out, say
from supportive.render.terminal import printable

__all__ = ["chat"]


def chat(
    file: Annotated[
        Path,
        typer.Argument(help="Task file with a structure, or a bundled example's name; it is not changed."),
    ],
    save: Annotated[
        Path | None,
        typer.Option(
            "--save",
            help="The copy changed behaviors are saved to (default: NAME.edited.yaml beside FILE, or here for a "
            "bundled example); when it exists, the conversation carries on in it.",
        ),
    ] = None,
    matcher: Annotated[
        str,
        typer.Option(
            "--matcher", metavar="bow|embeddings", help="Subtask matcher: bow (bag of words) or embeddings (needs the extra)."
        ),
    ] = "bow",
) -> None:
    """Tell the robot how to help and ask it to explain its policy, in plain sentences (§3.3)."""
    from supportive.cli.chat_console import ChatConsole
    from supportive.errors import OptionError
    from supportive.examples import task_path
    from supportive.io.working_copy import working_copy
    from supportive.language.understand import MATCHERS

    if matcher not in MATCHERS:
        raise OptionError(f"unknown matcher {matcher!r}; choose {' or '.join(MATCHERS)}", "--matcher")

    def read() -> str:
        return input("> ")

    copy = working_copy(task_path(file), save)
    with about(file):
        console = ChatConsole(copy.reads(), read, say, matcher, copy=copy)  # the copy is made at the first change
    out.print(printable(copy.describe()), markup=False, soft_wrap=True)  # a path stays whole, to copy and paste
    line_editing()

    def stopped() -> str:
        """What an interruption kept: the copy, with every change acknowledged."""
        if not copy.exists:
            return NOTHING_WRITTEN
        changes = f"{console.saved} change{'s' if console.saved != 1 else ''}"
        return f"kept {copy.path}: every change acknowledged is saved in it ({changes} this session)"

    with about(file), explained(stopped):
        console.run()
