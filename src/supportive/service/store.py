"""Where the board lives: SQLite by default, PostgreSQL by URL (SQLAlchemy 2 Core).

One row holds the board's current state and version; every accepted operation is appended to the event
log in the same transaction, so the log is exactly what was acknowledged and replaying it on the initial
board gives the current one. Writers are serialised per board: SQLite by ``BEGIN IMMEDIATE`` (WAL journal,
``synchronous=NORMAL``: a killed server loses nothing it acknowledged; only a power cut could lose the last
transactions), PostgreSQL by ``SELECT … FOR UPDATE`` on the board's row. Tokens are stored as SHA-256 hashes; a
SQLite file the store creates is readable by its owner only (0600).
"""

from __future__ import annotations

import contextlib
import json
import os
import queue
import threading
import time
from collections.abc import Iterator, Sequence
from concurrent.futures import Future
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import Any
from urllib.parse import quote

from sqlalchemy import Engine, create_engine, event, insert, inspect, select, update
from sqlalchemy.engine import Connection, make_url
from sqlalchemy.exc import ArgumentError, DatabaseError, OperationalError

from supportive.errors import BoardError, StoreError, TokenError
from supportive.service import agents as registry
from supportive.service.agents import Agent, AgentSetup, AgentSpec, TokenInfo
from supportive.service.reconcile import reconcile_board, structure_change
from supportive.service.tables import boards, events_table, metadata
from supportive.social.board import Role, TaskBoard

__all__ = ["BoardEvent", "BoardStore"]

_BATCH = 256  # most operations in one group commit


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


SUPPORTED = ("sqlite", "postgresql")
"""The databases a board is kept in (SQLAlchemy backend names)."""


def _check_supported(url: str) -> None:
    """Refuse a URL of a database the board does not support, saying which it does (SQLAlchemy would name a
    missing driver module, "No module named 'MySQLdb'").

    Raises:
        StoreError: for another database (the password, if any, hidden).
    """
    try:
        parsed = make_url(url)
    except ArgumentError:
        return  # not a URL: create_engine's error says so
    if parsed.get_backend_name() not in SUPPORTED:
        shown = parsed.render_as_string(hide_password=True)
        raise StoreError(
            f"cannot use database {shown!r}: a board is kept in SQLite (sqlite:///board.db) or PostgreSQL "
            "(postgresql+psycopg://user@host/board)"
        )


class BoardStore:
    """The board's database.

    Args:
        url: A SQLAlchemy URL: ``sqlite:///board.db`` (the default kind) or ``postgresql+psycopg://…``.
        create: Whether a SQLite database file that does not exist is made (``False`` for commands that only
            work on a board made before, such as ``supportive tokens``).

    Raises:
        StoreError: for a URL SQLAlchemy cannot use, or (``create=False``) a SQLite file that does not exist.
    """

    def __init__(self, url: str, *, create: bool = True) -> None:
        _check_supported(url)
        try:
            self.engine: Engine = create_engine(url, pool_pre_ping=True, **_engine_options(url))
        except (ArgumentError, ImportError) as exc:
            raise StoreError(f"cannot use database {url!r}: {exc}") from None
        self.url = url
        self.sqlite = self.engine.dialect.name == "sqlite"
        if self.sqlite:
            database = self.engine.url.database
            if not create and database and database != ":memory:":
                _check_has_board(database, self.shown_url)  # read only: a file without a board stays as it was
            _private_file(database)
            _serialise_sqlite(self.engine)
        # One writer thread per store commits queued operations in groups; the database's own lock still
        # orders writers of other processes.
        self._lock = threading.Lock()
        self._queue: queue.Queue[_Pending | None] = queue.Queue()
        self._writer: threading.Thread | None = None
        self._cached: tuple[int, TaskBoard] | None = None  # the board at a version this process wrote
        # Every request looks its token up: on a DB-API connection of its own, with the query compiled once
        # (through SQLAlchemy's execution a lookup took 173 µs on SQLite, a bare query 5 µs).
        self._lookup = registry.lookup_query().compile(dialect=self.engine.dialect)
        self._reader: Any = None
        self._reader_lock = threading.Lock()

    @property
    def shown_url(self) -> str:
        """The database's URL with any password hidden (to print)."""
        return self.engine.url.render_as_string(hide_password=True)

    def initialize(
        self, board: TaskBoard, agents: Sequence[AgentSpec], defaults: Sequence[AgentSpec] = ()
    ) -> tuple[bool, AgentSetup]:
        """Create the tables and the board on first use; on every start, bring the database to what it is
        started with, in one transaction: the agents (:func:`~supportive.service.agents.set_up_agents`: new
        ones are added with a token, roles follow ``agents``, tokens no longer given are revoked), then the
        board's lead-only marks and the claims their owners may no longer hold
        (:func:`~supportive.service.reconcile.reconcile_board`, logged as events). Whether the board was
        created now, and what was done (``setup.changes`` says what changed).

        Raises:
            StoreError: when the database cannot be reached, holds another task's board, or a board of this
                task with another structure (the task file was edited): nothing is written.
            TokenError: for an agent or token the board refuses (see ``set_up_agents``); nothing is written.
        """
        with self._guarded():
            metadata.create_all(self.engine)
            with self._write() as connection:
                row = connection.execute(
                    select(boards.c.task, boards.c.initial, boards.c.state, boards.c.version).where(boards.c.id == 1)
                ).first()
                created = row is None
                if row is None:
                    text = json.dumps(board.as_dict())
                    connection.execute(
                        insert(boards).values(id=1, task=board.task, version=0, initial=text, state=text)
                    )
                else:
                    self._check_same_task(row.task, row.initial, board)
                registry.upgrade(connection)
                setup = registry.set_up_agents(connection, agents, defaults)
                if row is not None:
                    current = TaskBoard.from_dict(json.loads(row.state))
                    said = self._reconcile(connection, board, int(row.version), current)
                    setup = replace(setup, changes=(*setup.changes, *said))
        return created, setup

    def _check_same_task(self, task: str, initial: str, board: TaskBoard) -> None:
        """Refuse a database whose board is another task's, or this task's made from another version of its
        file (:func:`~supportive.service.reconcile.structure_change`)."""
        if task != board.task:
            raise StoreError(f"the database holds the board of {task!r}, not {board.task!r}")
        changed = structure_change(TaskBoard.from_dict(json.loads(initial)), board)
        if changed is not None:
            raise StoreError(
                f"{self.shown_url} holds a board of {board.task!r} made from another version of the task file "
                f"({changed}): start a new board with another --db, or start this one with the task file it was "
                "made from (its history is kept either way)"
            )

    def _reconcile(self, connection: Connection, wanted: TaskBoard, version: int, current: TaskBoard) -> list[str]:
        """Bring the stored board to ``wanted``'s lead-only marks and take back the claims their owners may no
        longer hold (:func:`~supportive.service.reconcile.reconcile_board`), each change an event of the log;
        the sentences saying what changed."""
        agents = registry.all_agents(connection)
        working = {t.agent for t in registry.list_tokens(connection, revoked=False)}
        after, changes, said = reconcile_board(current, wanted, {a.id: a.role for a in agents}, working)
        if changes:
            now = round(time.time(), 6)
            events = [
                {"board": 1, **BoardEvent(version + i, now, agent, op, node).as_dict()}
                for i, (op, node, agent) in enumerate(changes, start=1)
            ]
            connection.execute(
                update(boards)
                .where(boards.c.id == 1)
                .values(state=json.dumps(after.as_dict()), version=version + len(changes))
            )
            connection.execute(insert(events_table), events)
        return said

    def open_existing(self) -> str:
        """Check that the database holds a board (made by ``supportive serve``) without creating anything but
        the ``tokens`` table a database of an earlier version lacks; the board's task.

        Raises:
            StoreError: when the database cannot be reached or holds no board.
        """
        with self._guarded():
            if not inspect(self.engine).has_table(boards.name):
                raise StoreError(f"no board in {self.shown_url} (start one with supportive serve)")
            metadata.create_all(self.engine)
            with self._write() as connection:
                task = connection.execute(select(boards.c.task).where(boards.c.id == 1)).scalar()
                if task is None:
                    raise StoreError(f"no board in {self.shown_url} (start one with supportive serve)")
                registry.upgrade(connection)
        return str(task)

    @contextmanager
    def _guarded(self) -> Iterator[None]:
        """Turn the database's own errors into one clear :class:`StoreError`."""
        try:
            yield
        except OperationalError as exc:
            raise StoreError(f"cannot reach database {self.shown_url}: {exc.orig}") from None
        except DatabaseError as exc:  # not a database, or one whose tables are not the board's
            raise StoreError(f"cannot use database {self.shown_url}: {exc.orig}") from None

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
        """The agent a token signs in as, or None (unknown or revoked: asked of the database every time, so a
        token revoked by another process stops working at once).

        Raises:
            StoreError: when the database cannot be reached (after one new connection was tried).
        """
        params = self._lookup.construct_params({"digest": registry.token_hash(token)})
        args: Any = tuple(params[k] for k in self._lookup.positiontup or ()) if self._lookup.positional else params
        failure = self.engine.dialect.loaded_dbapi.Error
        with self._reader_lock:
            for attempt in range(2):
                try:
                    if self._reader is None:
                        self._reader = self._open_reader()
                    cursor = self._reader.cursor()
                    try:
                        cursor.execute(str(self._lookup), args)
                        row = cursor.fetchone()
                    finally:
                        cursor.close()
                    break
                except failure as exc:  # a connection that broke (a restarted server): one new one, then give up
                    self._close_reader()
                    if attempt:
                        raise StoreError(f"cannot reach database {self.shown_url}: {exc}") from None
        return None if row is None else Agent(str(row[0]), str(row[1]), row[2])

    def _open_reader(self) -> Any:
        """A DB-API connection that sees every commit (autocommit), out of the pool, for token lookups."""
        pooled = self.engine.raw_connection()
        connection: Any = pooled.driver_connection
        pooled.detach()
        if not self.sqlite:  # SQLite's is in autocommit already (see _serialise_sqlite)
            connection.autocommit = True
        return connection

    def _close_reader(self) -> None:
        reader, self._reader = self._reader, None
        if reader is not None:
            with contextlib.suppress(Exception):  # closing a broken connection may fail too
                reader.close()

    def agents(self) -> list[Agent]:
        """Every agent, by id."""
        with self.engine.connect() as connection:
            return registry.all_agents(connection)

    def tokens(self, *, revoked: bool = True) -> list[TokenInfo]:
        """Every token's record (``revoked=False``: only those that work), by number; never the tokens."""
        with self._guarded(), self.engine.connect() as connection:
            return registry.list_tokens(connection, revoked=revoked)

    def add_token(
        self, agent: str, label: str = "", *, kind: str | None = None, role: Role | None = None
    ) -> tuple[TokenInfo, str]:
        """A new token for ``agent`` (:func:`~supportive.service.agents.add_token`): its record and the token,
        shown once.

        Raises:
            TokenError: for an agent the board does not have (without ``kind`` and ``role``), and the like.
        """
        with self._guarded(), self._write() as connection:
            return registry.add_token(connection, agent, label, kind=_kind(kind), role=role)

    def revoke_tokens(self, numbers: Sequence[int] = (), agent: str | None = None) -> list[TokenInfo]:
        """Revoke tokens by number, or every token of ``agent`` (:func:`~supportive.service.agents.revoke_tokens`);
        the ones revoked now.

        Raises:
            TokenError: for a number no token has, or an unknown agent.
        """
        with self._guarded(), self._write() as connection:
            return registry.revoke_tokens(connection, numbers, agent)

    def close(self) -> None:
        """Stop the writer (after what is queued) and close the connections."""
        if self._writer is not None and self._writer.is_alive():
            self._queue.put(None)
            self._writer.join(30)
        with self._reader_lock:
            self._close_reader()
        self.engine.dispose()

    @contextmanager
    def _write(self) -> Iterator[Connection]:
        with self.engine.connect().execution_options(supportive_write=True) as connection, connection.begin():
            yield connection


def _kind(kind: str | None) -> registry.AgentKind | None:
    if kind is None:
        return None
    if kind not in registry.KINDS:
        raise TokenError(f"unknown kind {kind!r}; choose {' or '.join(registry.KINDS)}")
    return "human" if kind == "human" else "robot"


def _check_has_board(database: str, shown: str) -> None:
    """Raise :class:`StoreError` unless the SQLite file ``database`` holds a board (opened read only)."""
    import sqlite3

    if not os.path.isfile(database):
        raise StoreError(f"no board in {shown}: {database} does not exist (start one with supportive serve)")
    try:
        with contextlib.closing(sqlite3.connect(f"file:{quote(database)}?mode=ro", uri=True)) as connection:
            found = connection.execute("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'boards'").fetchone()
    except sqlite3.Error as exc:
        raise StoreError(f"cannot use database {shown}: {exc}") from None
    if found is None:
        raise StoreError(f"no board in {shown} (start one with supportive serve)")


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
