"""``supportive serve``: the shared task board as a web service."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from supportive.cli.interrupt import NOTHING_WRITTEN, explained
from supportive.cli.output import finite, say

if TYPE_CHECKING:
    from supportive.service.launch import Started

__all__ = ["announce", "serve"]


def serve(
    task: Annotated[
        Path | None,
        typer.Option(
            "--task",
            help="Task file (or a bundled example's name) whose structure or learned HTN is the board "
            "(default: the chair).",
        ),
    ] = None,
    db: Annotated[
        str,
        typer.Option(
            "--db", help="Database URL: sqlite:///board.db or postgresql+psycopg://user@127.0.0.1/db."
        ),
    ] = "sqlite:///board.db",
    host: Annotated[str, typer.Option("--host", help="Address to listen on.")] = "127.0.0.1",
    port: Annotated[int, typer.Option("--port", min=1, max=65535, help="Port to listen on.")] = 8000,
    agent: Annotated[
        list[str] | None,
        typer.Option(
            "--agent",
            help="name:kind:role[:token], repeatable (default: alice lead, robot assistant, screen observer). "
            "At a restart the list wins: roles follow it, tokens it no longer gives are revoked.",
        ),
    ] = None,
    lead_only: Annotated[
        list[str] | None,
        typer.Option(
            "--lead-only",
            help="A subtask (name or action id) only leads may do; repeatable. At a restart the board's "
            "lead-only subtasks become exactly these.",
        ),
    ] = None,
    client_timeout: Annotated[
        float,
        typer.Option(
            "--client-timeout",
            min=0.1,
            max=3600.0,
            callback=finite,
            help="Seconds a client has to send a request's head, then its body; idle ones are closed.",
        ),
    ] = 10.0,
) -> None:
    """Serve the shared task board (§3.4.3): a web page and a JSON/WebSocket API that people and robots claim
    subtasks through. The database is checked before the URL and tokens are printed; a token is printed once,
    when it is made (later starts make none: `supportive tokens` lists, adds and revokes them). At every start
    the command line wins over the database (roles, lead-only subtasks, tokens no longer given are revoked;
    each change is printed), and a task file edited since the board was made is refused. SIGTERM stops it
    gracefully (exit status 0)."""
    from supportive.examples import task_path
    from supportive.service.launch import prepare
    from supportive.service.launch import serve as run_service

    launch = prepare(
        task_path(task or "ikea-chair"),
        db,
        host=host,
        port=port,
        agents=agent or (),
        lead_only=lead_only or (),
        client_timeout=client_timeout,
    )
    running: list[Started] = []

    def stopped() -> str:
        """What an interruption kept: every operation the board acknowledged (once it was opened)."""
        if not running:
            return NOTHING_WRITTEN
        return f"the board stopped; every operation it acknowledged is kept in {running[0].database}"

    def tell(started: Started) -> None:
        running.append(started)
        announce(started)

    with explained(stopped):
        run_service(launch, tell)


def announce(started: Started) -> None:
    """Print where the board is and the tokens made now (the only time they are shown), then flush: a log or
    a pipe has them before the first request."""
    launch, setup = started.launch, started.setup
    say(f"task board for {launch.settings.board.task} at {started.url()}", whole=True)
    kinds = {a.id: f"{a.kind}, {a.role}" for a in setup.agents}
    for name, token in setup.shown.items():
        say(f"  new token for {name} ({kinds[name]}): {token}", whole=True)
    if started.retired_file is not None:
        say(f"  {started.retired_file} held tokens in plain text (an earlier version's); removing it.")
        for name, token in started.retired.items():
            say(f"  token for {name} ({kinds.get(name, '?')}), shown this last time: {token}", whole=True)
    for change in setup.changes:
        say(f"  changed at this start: {change}", whole=True)
    known = ", ".join(f"{a.id} ({kinds[a.id]})" for a in setup.agents if a.id not in setup.shown)
    if known:
        say(f"  agents as before: {known}; {setup.working - len(setup.shown)} working tokens made before", whole=True)
    say(
        "  tokens are shown only when made and kept as hashes: note them. "
        f"More, or revoke one: supportive tokens add|list|revoke --db {started.database}",
        whole=True,
    )
    say(f"  API docs at http://{launch.host}:{launch.port}/docs")
    sys.stdout.flush()
