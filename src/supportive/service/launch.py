"""Starting a board service from a task file: the settings, the agents and the tokens made now (shown once),
the URL to open, the server on 127.0.0.1 (:mod:`supportive.service.serving`).

Tokens live in the board's database only, as hashes (:mod:`supportive.service.agents`). An earlier version
kept a SQLite board's tokens in plain text beside it (``board.db.tokens.json``); the first start of this one
shows the tokens of that file that still work, this last time, and removes it.
"""

from __future__ import annotations

import contextlib
import errno
import json
import socket
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from sqlalchemy.engine import make_url
from sqlalchemy.exc import ArgumentError

from supportive.errors import InvalidValueError, ServiceError, StoreError, SupportiveError, naming
from supportive.io.taskfile import parse_task_file
from supportive.service.agents import AgentSetup
from supportive.service.settings import ServiceSettings, board_of, parse_agent
from supportive.service.store import BoardStore

__all__ = ["Launch", "Started", "free_port", "legacy_tokens_file", "listen", "prepare", "serve"]


@dataclass(frozen=True)
class Launch:
    """A service ready to start."""

    settings: ServiceSettings
    host: str
    port: int


@dataclass(frozen=True)
class Started:
    """What starting the service did, to tell the people who will use it.

    Attributes:
        launch: The service.
        setup: The agents, and the tokens made now (shown this once).
        database: The database's URL, any password hidden.
        retired: Tokens read from an earlier version's plain-text tokens file that still work, by agent (the
            file is removed once they are shown).
        retired_file: That file, when there was one.
    """

    launch: Launch
    setup: AgentSetup
    database: str
    retired: dict[str, str] = field(default_factory=dict)
    retired_file: Path | None = None

    def url(self) -> str:
        """The page's address, signed in as the first lead whose token is shown now (else without a token:
        the page asks for one)."""
        base = f"http://{self.launch.host}:{self.launch.port}/"
        shown = {**self.retired, **self.setup.shown}
        lead = next((a.id for a in self.setup.agents if a.role == "lead" and a.id in shown), None)
        return f"{base}#token={shown[lead]}" if lead is not None else base


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
    """Read the task, make the board and check the agents asked for (nothing is written yet, and no token is
    drawn: an agent's token is made when the agent is, by :func:`serve`).

    Raises:
        TaskFileError: for a bad task file.
        StoreError: for a database URL that cannot be used.
        InvalidValueError: for an agent named twice, or two agents given one token.
    """
    spec = parse_task_file(task)
    try:
        board = board_of(spec, lead_only)
    except SupportiveError as exc:  # about the task file's contents: name the file
        raise naming(exc, task) from None
    specs = [parse_agent(text) for text in agents]
    names = [agent.id for agent in specs]
    twice = next((name for name in names if names.count(name) > 1), None)
    if twice is not None:
        raise InvalidValueError(f"--agent: {twice!r} is named twice; give each agent once")
    given = [a.token for a in specs if a.token is not None]
    if len(set(given)) != len(given):
        raise InvalidValueError("--agent: two agents have the same token; give each its own (or none)")
    legacy_tokens_file(database)  # checks the URL's shape before anything is said
    settings = ServiceSettings(database, board, tuple(specs), spec, client_timeout=client_timeout)
    return Launch(settings, host, port)


def serve(launch: Launch, announce: Callable[[Started], None] = lambda started: None) -> None:
    """Open the database and set up the agents (checked before anything is said: a bad database or agent
    fails here), call ``announce`` (the command prints the URL and the tokens made now), then serve until
    SIGTERM or Ctrl-C (:func:`supportive.service.serving.run`).

    Raises:
        StoreError: when the database cannot be used.
        TokenError: for an agent or token the board refuses.
    """
    import gc

    from supportive.service.app import create_app
    from supportive.service.serving import run

    listener = listen(launch.host, launch.port)  # a busy port fails here, before a token is printed
    try:
        app = create_app(launch.settings)
    except BaseException:
        listener.close()
        raise
    state = app.state.service
    old = legacy_tokens_file(launch.settings.database)
    retired = _working_tokens(old, state.store) if old is not None and old.is_file() else {}
    announce(Started(launch, state.setup, state.store.shown_url, retired, old if _exists(old) else None))
    if old is not None:
        with contextlib.suppress(OSError):  # plain-text tokens: never kept (announce said so)
            old.unlink()
    gc.collect()
    gc.freeze()  # start-up objects never need collecting: full collections stay short under load
    run(app, listener, timeout=launch.settings.client_timeout)


def listen(host: str, port: int) -> socket.socket:
    """A TCP socket bound to ``host:port`` (the service's, handed to the server).

    Raises:
        ServiceError: when the address is in use or cannot be used.
    """
    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except OSError as exc:
        raise ServiceError(f"cannot listen on {host}: {exc.strerror or exc}") from None
    family, kind, proto, _, address = infos[0]
    listener = socket.socket(family, kind, proto)
    listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    try:
        listener.bind(address)
    except OSError as exc:
        listener.close()
        if exc.errno == errno.EADDRINUSE:
            raise ServiceError(f"port {port} on {host} is in use (another board?): give another --port") from None
        raise ServiceError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from None
    return listener


def free_port() -> int:
    """A TCP port on 127.0.0.1 that nothing listens on now."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def legacy_tokens_file(database: str) -> Path | None:
    """Where an earlier version kept a SQLite board's tokens in plain text (``<database>.tokens.json``); None
    for another database.

    Raises:
        StoreError: for text that is not a database URL.
    """
    try:
        url = make_url(database)
    except ArgumentError:
        raise StoreError(
            f"cannot use database {database!r}: expected a URL like sqlite:///board.db"
        ) from None
    if url.get_backend_name() != "sqlite" or not url.database or url.database == ":memory:":
        return None
    return Path(f"{url.database}.tokens.json")


def _exists(path: Path | None) -> bool:
    return path is not None and path.exists()


def _working_tokens(path: Path, store: BoardStore) -> dict[str, str]:
    """The tokens of an earlier version's tokens file that still sign in as their agent (an unreadable file
    gives none)."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError):
        return {}
    if not isinstance(data, dict):
        return {}
    working = {}
    for agent, token in data.items():
        if isinstance(token, str):
            found = store.agent_for_token(token)
            if found is not None and found.id == agent:
                working[str(agent)] = token
    return working
