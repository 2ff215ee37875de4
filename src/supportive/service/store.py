"""Where the board lives: SQLite by default, PostgreSQL by URL (SQLAlchemy 2 Core).

One row holds the board's current state and version; every accepted operation is appended to the event
log in the same transaction, so the log is exactly what was acknowledged and replaying it on the initial
board gives the current one. Writers are serialised per board: SQLite by ``BEGIN IMMEDIATE`` (WAL journal,
``synchronous=NORMAL``: a killed server loses nothing it acknowledged; only a power cut could lose the last
transactions), PostgreSQL by ``SELECT … FOR UPDATE`` on the board's row. Tokens are stored as SHA-256 hashes; a
SQLite file the store creates is readable by its owner only (0600).
"""

from __future__ import annotations

import hashlib
import json
import os
import queue
import threading
import time
from collections.abc import Iterator, Sequence
from concurrent.futures import Future
from contextlib import contextmanager
from dataclasses import dataclass, field
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
from sqlalchemy.exc import ArgumentError, DatabaseError, OperationalError

from supportive.errors import BoardError, StoreError
from supportive.social.board import ROLES, Role, TaskBoard

__all__ = ["Agent", "AgentKind", "AgentSpec", "BoardEvent", "BoardStore", "token_hash"]

_BATCH = 256  # most operations in one group commit

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


@dataclass
class _Pending:
    """An operation waiting for the writer, and where its outcome goes."""

    op: str
    node: str
    agent: Agent
    progress: float | None
    result: Future[tuple[TaskBoard, BoardEvent]] = field(default_factory=Future)


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
            _private_file(self.engine.url.database)
            _serialise_sqlite(self.engine)
        # One writer thread per store commits queued operations in groups; the database's own lock still
        # orders writers of other processes.
        self._lock = threading.Lock()
        self._queue: queue.Queue[_Pending | None] = queue.Queue()
        self._writer: threading.Thread | None = None
        self._cached: tuple[int, TaskBoard] | None = None  # the board at a version this process wrote

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
        except DatabaseError as exc:  # not a database, or one whose tables are not the board's
            raise StoreError(f"cannot use database {self.url}: {exc.orig}") from None
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
        """Apply one operation atomically and return once it is committed: the board after it, and its event.

        Operations wait in a queue for the store's writer thread, which applies every operation waiting, each
        checked on the board the ones before it left, and commits them in one transaction (a group commit):
        an operation is acknowledged only after the transaction holding it has committed.

        Raises:
            BoardError: when the board refuses it (nothing is written for it).
            StoreError: when the transaction fails (nothing of it is acknowledged).
        """
        pending = _Pending(op, node, agent, progress)
        with self._lock:
            if self._writer is None or not self._writer.is_alive():
                self._writer = threading.Thread(target=self._write_forever, name="board-writer", daemon=True)
                self._writer.start()
        self._queue.put(pending)
        return pending.result.result()

    def _write_forever(self) -> None:
        while True:
            first = self._queue.get()
            if first is None:
                return
            batch = [first]
            while len(batch) < _BATCH:
                try:
                    item = self._queue.get_nowait()
                except queue.Empty:
                    break
                if item is None:
                    self._queue.put(None)
                    break
                batch.append(item)
            self._commit(batch)

    def _commit(self, batch: list[_Pending]) -> None:
        """Apply ``batch`` in order in one transaction; resolve each operation once it has committed."""
        outcomes: list[tuple[_Pending, tuple[TaskBoard, BoardEvent] | BaseException]] = []
        try:
            with self._write() as connection:
                query = select(boards.c.version).where(boards.c.id == 1)
                if not self.sqlite:
                    query = query.with_for_update()
                version = int(connection.execute(query).scalar_one())
                current = self._cached
                if current is None or current[0] != version:  # another process wrote, or first use
                    text = connection.execute(select(boards.c.state).where(boards.c.id == 1)).scalar_one()
                    current = (version, TaskBoard.from_dict(json.loads(text)))
                board = current[1]
                events: list[dict[str, Any]] = []
                for item in batch:
                    try:
                        board = board.apply(item.op, item.node, item.agent.id, item.agent.role, item.progress)
                    except BoardError as refused:
                        outcomes.append((item, refused))
                        continue
                    version += 1
                    done = BoardEvent(
                        version, round(time.time(), 6), item.agent.id, item.op, item.node, item.progress
                    )
                    events.append({"board": 1, **done.as_dict()})
                    outcomes.append((item, (board, done)))
                if events:
                    connection.execute(
                        update(boards)
                        .where(boards.c.id == 1)
                        .values(state=json.dumps(board.as_dict()), version=version)
                    )
                    connection.execute(insert(events_table), events)
                self._cached = (version, board)  # if the commit fails the version no longer matches: reread
        except Exception as exc:  # the transaction failed: no operation of it is acknowledged
            failure = StoreError(f"the board could not be saved: {exc}")
            for item in batch:
                item.result.set_exception(failure)
            return
        for item, outcome in outcomes:
            if isinstance(outcome, BaseException):
                item.result.set_exception(outcome)
            else:
                item.result.set_result(outcome)

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
        """Stop the writer (after what is queued) and close the connections."""
        if self._writer is not None and self._writer.is_alive():
            self._queue.put(None)
            self._writer.join(30)
        self.engine.dispose()

    @contextmanager
    def _write(self) -> Iterator[Connection]:
        with self.engine.connect().execution_options(supportive_write=True) as connection, connection.begin():
            yield connection


def _private_file(database: str | None) -> None:
    """Create a new SQLite database file readable and writable by its owner only (SQLite gives its -wal and
    -shm files the database's mode); an existing file keeps the mode its owner gave it."""
    if not database or database == ":memory:" or database.startswith("file:"):
        return
    try:
        os.close(os.open(database, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
    except FileExistsError:
        return
    except OSError as exc:
        raise StoreError(f"cannot create database file {database}: {exc.strerror}") from None


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
