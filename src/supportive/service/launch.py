"""Starting a board service from a task file: the settings, the agents' tokens kept beside a SQLite
database, the URL to open, the server on 127.0.0.1 (:mod:`supportive.service.serving`)."""

from __future__ import annotations

import json
import socket
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from sqlalchemy.engine import make_url
from sqlalchemy.exc import ArgumentError

from supportive.errors import FileFormatError, InvalidValueError, StoreError, SupportiveError, naming
from supportive.io.atomic import atomic_write
from supportive.io.taskfile import parse_task_file
from supportive.service.settings import DEFAULT_AGENTS, ServiceSettings, board_of, parse_agent
from supportive.service.store import AgentSpec

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
    client_timeout: float = 10.0,
) -> Launch:
    """Read the task, make the board and agents, and find the tokens to show (nothing is written yet).

    For a SQLite database the tokens of agents created on first use are kept beside it
    (``<database>.tokens.json``, readable by its owner only) and read back on later starts; for another
    database they are shown once, when created (or give them with ``name:kind:role:token``).

    Raises:
        TaskFileError: for a bad task file.
        StoreError: for a database URL that cannot be used, or a tokens file that cannot be read.
        InvalidValueError: for an agent named twice, or two agents given one token.
    """
    spec = parse_task_file(task)
    try:
        board = board_of(spec, lead_only)
    except SupportiveError as exc:  # about the task file's contents: name the file
        raise naming(exc, task) from None
    texts = list(agents or DEFAULT_AGENTS)
    specs = [parse_agent(text) for text in texts]
    names = [agent.id for agent in specs]
    twice = next((name for name in names if names.count(name) > 1), None)
    if twice is not None:
        raise InvalidValueError(f"--agent: {twice!r} is named twice; give each agent once")
    tokens_file = _tokens_file(database)
    known = _read_tokens(tokens_file)
    resolved: list[AgentSpec] = []
    for agent, text in zip(specs, texts, strict=True):
        explicit = len(text.split(":")) == 4
        token = agent.token if explicit or agent.id not in known else known[agent.id]
        resolved.append(AgentSpec(agent.id, agent.kind, agent.role, token))
    shared = [a.token for a in resolved]
    if len(set(shared)) != len(shared):
        raise InvalidValueError("--agent: two agents have the same token; give each its own (or none)")
    settings = ServiceSettings(database, board, tuple(resolved), spec, client_timeout=client_timeout)
    tokens = {a.id: a.token for a in resolved}
    return Launch(settings, host, port, tokens, tokens_file)


def serve(launch: Launch, announce: Callable[[], None] = lambda: None) -> None:
    """Open the database (checked before anything is said: a bad one fails here), keep the tokens beside a
    SQLite database, call ``announce`` (the command prints the URL and tokens), then serve until SIGTERM or
    Ctrl-C (:func:`supportive.service.serving.run`).

    Raises:
        StoreError: when the database cannot be used or the tokens cannot be kept.
    """
    import gc

    from supportive.service.app import create_app
    from supportive.service.serving import run

    app = create_app(launch.settings)
    if launch.tokens_file is not None:
        _write_tokens(launch.tokens_file, {**_read_tokens(launch.tokens_file), **launch.tokens})
    announce()
    gc.collect()
    gc.freeze()  # start-up objects never need collecting: full collections stay short under load
    run(app, launch.host, launch.port, timeout=launch.settings.client_timeout)


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
    """The tokens, written atomically to a file readable by its owner only (whatever mode it had)."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        atomic_write(path, json.dumps(tokens, indent=2), mode=0o600)
    except (OSError, FileFormatError) as exc:
        raise StoreError(f"{path}: cannot write the agents' tokens: {exc}") from None
