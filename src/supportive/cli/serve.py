"""``supportive serve``: the shared task board as a web service."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from supportive.cli.output import finite, say

__all__ = ["serve"]


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
            help="name:kind:role[:token], repeatable (default: alice lead, robot assistant, screen observer).",
        ),
    ] = None,
    lead_only: Annotated[
        list[str] | None,
        typer.Option("--lead-only", help="A subtask (name or action id) only leads may do; repeatable."),
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
    subtasks through. The database is checked before the URL and tokens are printed; SIGTERM stops it
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

    def announce() -> None:
        say(f"task board for {launch.settings.board.task} at {launch.url()}")
        for spec in launch.settings.agents:
            say(f"  {spec.id} ({spec.kind}, {spec.role}): token {spec.token}")
        if launch.tokens_file is not None:
            say(f"  (tokens kept in {launch.tokens_file}; API docs at http://{host}:{port}/docs)")

    run_service(launch, announce)
