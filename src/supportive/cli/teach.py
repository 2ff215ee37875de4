"""``supportive teach``: teach a task by demonstration at the terminal, in a copy of the task file."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.interrupt import NOTHING_WRITTEN, explained
from supportive.cli.output import about, line_editing, out, say
from supportive.render.terminal import printable

__all__ = ["teach"]


def teach(
    file: Annotated[
        Path, typer.Argument(help="Task file (.yaml or .json) or a bundled example's name; it is not changed.")
    ],
    save: Annotated[
        Path | None,
        typer.Option(
            "--save",
            help="The copy your demonstrations are saved to (default: NAME.edited.yaml beside FILE, or here for "
            "a bundled example); when it exists, teaching carries on in it.",
        ),
    ] = None,
    strategy: Annotated[
        str, typer.Option("--strategy", metavar="distance|connectivity|random", help="Query strategy: distance, connectivity or random.")
    ] = "distance",
    after: Annotated[
        str,
        typer.Option("--ask-after", help="Ask after these step counts (0: at the start), comma-separated."),
    ] = "1,3,5",
    demonstrations: Annotated[
        int | None, typer.Option("--demonstrations", "-d", min=1, help="Stop after this many.")
    ] = None,
    seed: Annotated[
        int, typer.Option("--seed", min=0, help="Seeds the choice among equally good questions.")
    ] = 0,
) -> None:
    """Teach a task by demonstration at the terminal; the robot asks for actions as you go (§2.2)."""
    from supportive.cli.teach_console import TeachingConsole
    from supportive.errors import OptionError, SupportiveError
    from supportive.examples import task_path
    from supportive.io.taskfile import parse_task_file
    from supportive.io.working_copy import working_copy
    from supportive.learning.active import QuerySchedule, strategy_names

    if strategy not in strategy_names():
        raise OptionError(
            f"unknown strategy {strategy!r}; choose one of {', '.join(strategy_names())}", "--strategy"
        )
    try:
        steps = tuple(int(x) for x in after.split(",") if x.strip())
    except ValueError:
        raise OptionError(f"expected step counts like 1,3,5, got {after!r}", "--ask-after") from None
    schedule = QuerySchedule(after_steps=steps, max_per_demonstration=len(steps))

    def read() -> str:
        return input("> ")

    copy = working_copy(task_path(file), save)
    with about(file):
        console = TeachingConsole(copy.reads(), read, say, strategy, schedule, seed, copy=copy)
        at_start = len(console.prepare().demonstrations)  # a task the session refuses: refused before any copy
    out.print(printable(copy.describe()), markup=False, soft_wrap=True)  # a path stays whole, to copy and paste
    line_editing()

    def stopped() -> str:
        """What an interruption kept: the copy as last saved; what it dropped: the demonstration under way,
        or the one being saved when the save did not finish."""
        dropped = console.in_progress
        lost = [f"dropped the unfinished demonstration ({dropped} step{'s' if dropped != 1 else ''})"] if dropped else []
        if not copy.exists:  # nothing saved yet: no copy was made
            unsaved = ["dropped the demonstration being saved (the save did not finish)"] if console.saving else []
            return "; ".join([NOTHING_WRITTEN, *lost, *unsaved])
        try:
            count = len(parse_task_file(copy.path).demonstrations)
        except SupportiveError:  # changed meanwhile by someone else: say no more than is known
            return "; ".join([f"kept {copy.path}", *lost])
        if console.saving and count <= at_start + console.recorded:
            lost.append("dropped the demonstration being saved (the save did not finish)")
        return "; ".join([f"kept {copy.path}: {count} demonstrations, {at_start} when this session began", *lost])

    with about(file), explained(stopped):
        console.run(demonstrations)
