"""Starting a board service from a task file: the settings, the agents' tokens kept beside a SQLite
database, the URL to open, uvicorn on 127.0.0.1."""

from __future__ import annotations

import json
import os
import socket
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from sqlalchemy.engine import make_url
from sqlalchemy.exc import ArgumentError

from supportive.io.taskfile import parse_task_file
from supportive.service.settings import DEFAULT_AGENTS, ServiceSettings, board_of, parse_agent
from supportive.service.store import AgentSpec, StoreError

__all__ = ["Launch", "free_port", "prepare", "serve"]


@dataclass(frozen=True)
class Launch:
    """A service ready to start, and what to tell the people who will use it."""

    settings: ServiceSettings
    host: str
    port: int
    tokens: dict[str, str]
    tokens_file: Path | None

    def url(self, agent: str | None = None) -> str:
        """The page's address, signed in as ``agent`` (by default the first lead) when its token is known."""
        base = f"http://{self.host}:{self.port}/"
        if agent is None:
            agent = next((a.id for a in self.settings.agents if a.role == "lead"), None)
        token = self.tokens.get(agent or "")
        return f"{base}#token={token}" if token else base


def prepare(
    task: Path,
    database: str,
    *,
    host: str = "127.0.0.1",
    port: int = 8000,
    agents: Sequence[str] = (),
    lead_only: Sequence[str] = (),
) -> Launch:
    """Read the task, make the board and agents, and find the tokens to show.

    For a SQLite database the tokens of agents created on first use are written beside it
    (``<database>.tokens.json``, readable by its owner only) and read back on later starts; for another
    database they are shown once, when created (or give them with ``name:kind:role:token``).

    Raises:
        TaskFileError: for a bad task file.
        StoreError: for a database URL that cannot be used.
    """
    spec = parse_task_file(task)
    board = board_of(spec, lead_only)
    specs = [parse_agent(text) for text in (agents or DEFAULT_AGENTS)]
    tokens_file = _tokens_file(database)
    known = _read_tokens(tokens_file)
    resolved: list[AgentSpec] = []
    for agent, text in zip(specs, agents or DEFAULT_AGENTS, strict=True):
        explicit = len(text.split(":")) == 4
        token = agent.token if explicit or agent.id not in known else known[agent.id]
        resolved.append(AgentSpec(agent.id, agent.kind, agent.role, token))
    settings = ServiceSettings(database, board, tuple(resolved), spec)
    tokens = {a.id: a.token for a in resolved}
    if tokens_file is not None:
        _write_tokens(tokens_file, {**known, **tokens})
    return Launch(settings, host, port, tokens, tokens_file)


def serve(launch: Launch) -> None:
    """Run the service until interrupted (uvicorn; one process)."""
    import gc

    import uvicorn

    from supportive.service.app import create_app

    app = create_app(launch.settings)
    gc.collect()
    gc.freeze()  # start-up objects never need collecting: full collections stay short under load
    uvicorn.run(app, host=launch.host, port=launch.port, log_level="warning", timeout_graceful_shutdown=3)


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _tokens_file(database: str) -> Path | None:
    try:
        url = make_url(database)
    except ArgumentError:
        raise StoreError(
            f"cannot use database {database!r}: expected a URL like sqlite:///board.db"
        ) from None
    if url.get_backend_name() != "sqlite" or not url.database or url.database == ":memory:":
        return None
    return Path(f"{url.database}.tokens.json")


def _read_tokens(path: Path | None) -> dict[str, str]:
    if path is None or not path.is_file():
        return {}
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise StoreError(f"{path}: cannot read the agents' tokens: {exc}") from None
    return {str(k): str(v) for k, v in data.items()} if isinstance(data, dict) else {}


def _write_tokens(path: Path, tokens: dict[str, str]) -> None:
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            json.dump(tokens, handle, indent=2)
    except OSError as exc:
        raise StoreError(f"{path}: cannot write the agents' tokens: {exc.strerror}") from None
