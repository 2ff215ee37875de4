"""Where the board lives: SQLite by default, PostgreSQL by URL (SQLAlchemy 2 Core).

One row holds the board's current state and version; every accepted operation is appended to the event
log in the same transaction, so the log is exactly what was acknowledged and replaying it on the initial
board gives the current one. Writers are serialised per board: SQLite by ``BEGIN IMMEDIATE`` (WAL journal,
``synchronous=NORMAL``: a killed server loses nothing it acknowledged; only a power cut could lose the last
transactions), PostgreSQL by ``SELECT … FOR UPDATE`` on the board's row. Tokens are stored as SHA-256 hashes.
"""

from __future__ import annotations

import hashlib
import json
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any, Literal

from sqlalchemy import (
    Column,
    Engine,
    Float,
    ForeignKey,
    Integer,
    MetaData,
    String,
    Table,
    Text,
    create_engine,
    event,
    insert,
    select,
    update,
)
from sqlalchemy.engine import Connection
from sqlalchemy.exc import ArgumentError, OperationalError

from supportive.errors import SupportiveError
from supportive.service.tree import ROLES, Role, TaskBoard

__all__ = ["Agent", "AgentKind", "AgentSpec", "BoardEvent", "BoardStore", "StoreError", "token_hash"]

AgentKind = Literal["human", "robot"]

metadata = MetaData()
boards = Table(
    "boards",
    metadata,
    Column("id", Integer, primary_key=True),
    Column("task", String(200), nullable=False),
    Column("version", Integer, nullable=False),
    Column("initial", Text, nullable=False),
    Column("state", Text, nullable=False),
)
agents_table = Table(
    "agents",
    metadata,
    Column("id", String(64), primary_key=True),
    Column("kind", String(16), nullable=False),
    Column("role", String(16), nullable=False),
    Column("token_hash", String(64), nullable=False, unique=True),
)
events_table = Table(
    "events",
    metadata,
    Column("seq", Integer, primary_key=True, autoincrement=False),
    Column("board", Integer, ForeignKey("boards.id"), nullable=False),
    Column("at", Float, nullable=False),
    Column("agent", String(64), nullable=False),
    Column("op", String(16), nullable=False),
    Column("node", String(16), nullable=False),
    Column("progress", Float, nullable=True),
)


class StoreError(SupportiveError, ValueError):
    """The database cannot be used (a bad URL, a server that does not answer, another task in it)."""


@dataclass(frozen=True)
class AgentSpec:
    """An agent to create: its name, kind, role and token (kept only as a hash)."""

    id: str
    kind: AgentKind
    role: Role
    token: str


@dataclass(frozen=True)
class Agent:
    """An agent of the board."""

    id: str
    kind: str
    role: Role


@dataclass(frozen=True)
class BoardEvent:
    """One acknowledged operation: its sequence number (= the board's version after it), when, who, what."""

    seq: int
    at: float
    agent: str
    op: str
    node: str
    progress: float | None = None

    def as_dict(self) -> dict[str, Any]:
        """Plain JSON data."""
        return {
            "seq": self.seq,
            "at": self.at,
            "agent": self.agent,
            "op": self.op,
            "node": self.node,
            "progress": self.progress,
        }


def token_hash(token: str) -> str:
    """The stored form of a token."""
    return hashlib.sha256(token.encode("utf-8")).hexdigest()


class BoardStore:
    """The board's database.

    Args:
        url: A SQLAlchemy URL: ``sqlite:///board.db`` (the default kind) or ``postgresql+psycopg://…``.

    Raises:
        StoreError: for a URL SQLAlchemy cannot use.
    """

    def __init__(self, url: str) -> None:
        try:
            self.engine: Engine = create_engine(url, pool_pre_ping=True, **_engine_options(url))
        except (ArgumentError, ImportError) as exc:
            raise StoreError(f"cannot use database {url!r}: {exc}") from None
        self.url = url
        self.sqlite = self.engine.dialect.name == "sqlite"
        if self.sqlite:
            _serialise_sqlite(self.engine)

    def initialize(self, board: TaskBoard, agents: Sequence[AgentSpec]) -> bool:
        """Create the tables and the board on first use; True when it was created now.

        Agents are added if new; an existing agent keeps its token and role.

        Raises:
            StoreError: when the database cannot be reached, or holds another task's board.
        """
        try:
            metadata.create_all(self.engine)
            with self._write() as connection:
                existing = connection.execute(select(boards.c.task).where(boards.c.id == 1)).scalar()
                created = existing is None
                if created:
                    text = json.dumps(board.as_dict())
                    connection.execute(
                        insert(boards).values(id=1, task=board.task, version=0, initial=text, state=text)
                    )
                elif existing != board.task:
                    raise StoreError(f"the database holds the board of {existing!r}, not {board.task!r}")
                known = {r.id for r in connection.execute(select(agents_table.c.id))}
                for spec in agents:
                    if spec.role not in ROLES:
                        raise StoreError(f"agent {spec.id}: unknown role {spec.role!r}")
                    if spec.id not in known:
                        connection.execute(
                            insert(agents_table).values(
                                id=spec.id, kind=spec.kind, role=spec.role, token_hash=token_hash(spec.token)
                            )
                        )
        except OperationalError as exc:
            raise StoreError(f"cannot reach database {self.url}: {exc.orig}") from None
        return created

    def board(self) -> tuple[TaskBoard, int]:
        """The current board and its version."""
        with self.engine.connect() as connection:
            row = connection.execute(select(boards.c.state, boards.c.version).where(boards.c.id == 1)).one()
        return TaskBoard.from_dict(json.loads(row.state)), int(row.version)

    def initial(self) -> TaskBoard:
        """The board as it was created (for replaying the log)."""
        with self.engine.connect() as connection:
            text = connection.execute(select(boards.c.initial).where(boards.c.id == 1)).scalar_one()
        return TaskBoard.from_dict(json.loads(text))

    def apply(
        self, op: str, node: str, agent: Agent, progress: float | None = None
    ) -> tuple[TaskBoard, BoardEvent]:
        """Apply one operation atomically: read, check, write the new board and the event, commit.

        Raises:
            BoardError: when the board refuses it (nothing is written).
        """
        with self._write() as connection:
            query = select(boards.c.state, boards.c.version).where(boards.c.id == 1)
            if not self.sqlite:
                query = query.with_for_update()
            row = connection.execute(query).one()
            board = TaskBoard.from_dict(json.loads(row.state)).apply(op, node, agent.id, agent.role, progress)
            seq = int(row.version) + 1
            done = BoardEvent(seq, round(time.time(), 6), agent.id, op, node, progress)
            connection.execute(
                update(boards).where(boards.c.id == 1).values(state=json.dumps(board.as_dict()), version=seq)
            )
            connection.execute(insert(events_table).values(board=1, **done.as_dict()))
        return board, done

    def events(self, after: int = 0, limit: int = 1000) -> list[BoardEvent]:
        """Acknowledged operations with a sequence number above ``after``, oldest first."""
        query = (
            select(events_table)
            .where(events_table.c.board == 1, events_table.c.seq > after)
            .order_by(events_table.c.seq)
            .limit(limit)
        )
        with self.engine.connect() as connection:
            return [
                BoardEvent(r.seq, r.at, r.agent, r.op, r.node, r.progress) for r in connection.execute(query)
            ]

    def agent_for_token(self, token: str) -> Agent | None:
        """The agent whose token this is, or None."""
        query = select(agents_table).where(agents_table.c.token_hash == token_hash(token))
        with self.engine.connect() as connection:
            row = connection.execute(query).first()
        return None if row is None else Agent(row.id, row.kind, row.role)

    def agents(self) -> list[Agent]:
        """Every agent, by id."""
        with self.engine.connect() as connection:
            rows = connection.execute(select(agents_table).order_by(agents_table.c.id)).all()
        return [Agent(r.id, r.kind, r.role) for r in rows]

    def close(self) -> None:
        """Close the connections."""
        self.engine.dispose()

    @contextmanager
    def _write(self) -> Iterator[Connection]:
        with self.engine.connect().execution_options(supportive_write=True) as connection, connection.begin():
            yield connection


def _engine_options(url: str) -> dict[str, Any]:
    if url.startswith("sqlite"):
        return {"connect_args": {"check_same_thread": False, "timeout": 30}}
    return {"pool_size": 10, "max_overflow": 20}


def _serialise_sqlite(engine: Engine) -> None:
    """SQLite: WAL, NORMAL sync, and every writing transaction BEGIN IMMEDIATE (one writer at a time, no
    deadlocks from upgrading a read lock; readers are not blocked); pysqlite's own transaction handling off."""

    @event.listens_for(engine, "connect")
    def _connect(dbapi_connection: Any, record: Any) -> None:
        dbapi_connection.isolation_level = None
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA journal_mode=WAL")
        cursor.execute("PRAGMA synchronous=NORMAL")
        cursor.execute("PRAGMA busy_timeout=30000")
        cursor.close()

    @event.listens_for(engine, "begin")
    def _begin(connection: Connection) -> None:
        writing = connection.get_execution_options().get("supportive_write", False)
        connection.exec_driver_sql("BEGIN IMMEDIATE" if writing else "BEGIN")
