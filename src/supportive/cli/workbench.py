"""``supportive workbench-sim``: the Collaborative Workbench with a simulated person and robot."""

from __future__ import annotations

from typing import Annotated

import typer

from supportive.cli.output import finite, say
from supportive.errors import OptionError

__all__ = ["workbench_sim"]


def workbench_sim(
    role: Annotated[
        str, typer.Option("--role", metavar="student|peer|instructor", help="The robot's role: student, peer or instructor.")
    ] = "student",
    seconds: Annotated[
        float, typer.Option("--seconds", min=1.0, max=3600.0, callback=finite, help="Simulated seconds at most.")
    ] = 40.0,
    url: Annotated[
        str | None,
        typer.Option(
            "--url", help="A running board of the workbench task (default: one started in this process)."
        ),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", min=0, help="Breaks the robot's ties.")] = 0,
) -> None:
    """Run the Collaborative Workbench (§3.4) on this machine: a board service, a simulated person's hand and
    a simulated robot that reads the person's social force and acts as a student, a peer or an instructor."""
    from supportive.cli.workbench_sim import ROLES, run_workbench

    if role not in ROLES:
        raise OptionError(f"unknown role {role!r}; choose {', '.join(ROLES)}", "--role")
    say(f"workbench-blocks, the robot as {role}:")
    run_workbench(role, url=url, seconds=seconds, seed=seed, tell=say)
