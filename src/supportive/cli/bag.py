"""``supportive bag``: demonstrations from ROS bags into task files, and back (the ``ros`` extra).

Parses arguments and calls :mod:`supportive.io.rosbag`; no logic of its own. Errors are
:class:`~supportive.errors.SupportiveError`, which the main command prints as one line (exit status 2).
"""

from __future__ import annotations

import os
import sys
from dataclasses import replace
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.interrupt import writing
from supportive.cli.output import csv_note, finite
from supportive.errors import OptionError, TaskFileError

__all__ = ["bag_app"]

bag_app = typer.Typer(
    no_args_is_help=True,
    help="ROS bags (ROS 1, rosbag2 MCAP or SQLite3): demonstrations in and out. Needs the ros extra.",
)


class BagFormat(StrEnum):
    """Bag formats ``bag export`` writes."""

    mcap = "mcap"
    sqlite3 = "sqlite3"
    rosbag1 = "rosbag1"


Types = Annotated[
    list[Path] | None,
    typer.Option("--types", help="A .msg/.idl file or folder of message types the bag lacks; repeatable."),
]


@bag_app.command("import")
def import_bags(
    bags: Annotated[list[Path], typer.Argument(help="Bags: ROS 1 .bag files or rosbag2 directories.")],
    actions_topic: Annotated[
        str, typer.Option("--actions-topic", help="Topic of the actions (String ids or action/start/end).")
    ] = "/task/action",
    segment_topic: Annotated[
        str | None,
        typer.Option(
            "--segment-topic", help="Topic whose messages start each demonstration (default: one per bag)."
        ),
    ] = None,
    agent: Annotated[
        str | None, typer.Option("--agent", help="Who demonstrated, where the bag does not say.")
    ] = None,
    task: Annotated[
        Path | None,
        typer.Option(
            "--task",
            help="A task file: its actions are the known ids; the output keeps all but its demonstrations.",
        ),
    ] = None,
    name: Annotated[
        str | None, typer.Option("--name", help="The task's name (default: --task's, or the first bag's).")
    ] = None,
    types: Types = None,
    output: Annotated[
        Path | None,
        typer.Option(
            "--output", "-o", help="Task file to write: .yaml, .json or .csv (default: YAML on stdout)."
        ),
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="Replace the -o file when it exists (never one of the inputs).")
    ] = False,
) -> None:
    """Read each bag (or each segment of a bag) as a demonstration and write them as a task file."""
    from supportive.io.rosbag import bag_name, import_demonstrations
    from supportive.io.taskfile import dump_task, format_of, parse_task_file, write_task_file
    from supportive.tasks.spec import TaskSpec

    if segment_topic == actions_topic:
        raise OptionError(f"--segment-topic and --actions-topic are both {actions_topic}: give two topics")
    if output is not None:
        _check_output(output, [*bags, *([task] if task is not None else []), *(types or [])], force=force)
    fmt = format_of(output) if output is not None else "yaml"
    template = parse_task_file(task) if task is not None else None
    vocabulary = {a.id for a in template.actions} if template is not None and template.actions else None
    demonstrations = import_demonstrations(
        bags,
        actions_topic=actions_topic,
        segment_topic=segment_topic,
        agent=agent,
        vocabulary=vocabulary,
        definitions=types or (),
    )
    if template is None:
        spec = TaskSpec(name or bag_name(bags[0]), (), None, demonstrations)
    else:
        spec = replace(template, name=name or template.name, demonstrations=demonstrations)
    csv_note(spec, fmt, output)  # what a CSV leaves out (the template's structure, texts, …)
    if output is None:
        sys.stdout.write(dump_task(spec, fmt))
        return
    with writing(output):
        write_task_file(spec, output, fmt)
    typer.echo(f"wrote {output}: {len(demonstrations)} demonstrations", err=True)


def _check_output(output: Path, inputs: list[Path], *, force: bool) -> None:
    """Refuse an output that is one of the inputs or inside one (a rosbag2 folder, a --types folder), a
    folder, and a file that exists without ``--force``.

    Raises:
        FileFormatError: naming the output and the problem.
    """
    from supportive.io.atomic import check_apart, real_path

    check_apart(output, inputs, "-o")
    if real_path(output).is_dir():
        raise TaskFileError("-o is a folder; name a .yaml, .json or .csv file", path=output)
    if os.path.lexists(output) and not force:
        raise TaskFileError("exists already; give --force to replace it, or another -o", path=output)


@bag_app.command("export")
def export_bag(
    task: Annotated[
        Path, typer.Argument(help="Task file whose demonstrations to write, or a bundled example's name.")
    ],
    output: Annotated[
        Path, typer.Option("--output", "-o", help="The new bag: a directory, or a .bag file for rosbag1.")
    ],
    storage: Annotated[
        BagFormat, typer.Option("--format", help="mcap, sqlite3 (rosbag2) or rosbag1.")
    ] = BagFormat.mcap,
    actions_topic: Annotated[
        str, typer.Option("--actions-topic", help="Topic of the actions.")
    ] = "/task/action",
    segment_topic: Annotated[
        str, typer.Option("--segment-topic", help="Topic of the demonstration markers.")
    ] = "/task/demonstration",
    start: Annotated[
        float,
        typer.Option(
            "--start",
            min=0.0,
            max=2_147_483_647.0,
            callback=finite,
            help="When the first demonstration begins (seconds since 1970; a bag's times end in 2038).",
        ),
    ] = 1_704_067_200.0,
) -> None:
    """Write a task's demonstrations into a new bag, each after a marker; `bag import --segment-topic` reads
    them back."""
    from supportive.examples import task_path
    from supportive.io.rosbag import BagWriter, write_demonstrations
    from supportive.io.taskfile import parse_task_file

    task = task_path(task)
    spec = parse_task_file(task)
    if not spec.demonstrations:
        raise TaskFileError("no demonstrations to write", path=task, place="demonstrations")
    with writing(output, "bag"), BagWriter(output, storage.value) as writer:
        write_demonstrations(
            writer,
            spec.demonstrations,
            start=int(start) * 1_000_000_000 + round(start % 1 * 1e9),
            actions_topic=actions_topic,
            segment_topic=segment_topic,
        )
    typer.echo(f"wrote {output}: {len(spec.demonstrations)} demonstrations", err=True)
