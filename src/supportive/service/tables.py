"""The board's database tables (SQLAlchemy 2 Core), the same on SQLite and PostgreSQL.

* ``boards`` — one row: the task, the board as created (``initial``) and as it is now (``state``), and its
  version (the sequence number of the last acknowledged operation).
* ``events`` — every acknowledged operation, in order.
* ``agents`` — who may use the board: name, kind, role. ``token_hash`` is the hash of the agent's first token,
  kept because databases made before the ``tokens`` table have the column (it is not used to sign in).
* ``tokens`` — every token an agent was given, as a SHA-256 hash (never the token itself): a number to name it
  by, when it was made, a label saying what it is for, and when it was revoked (``NULL`` while it works).
"""

from __future__ import annotations

from sqlalchemy import Column, Float, ForeignKey, Integer, MetaData, String, Table, Text

__all__ = ["AGENT_NAME_LENGTH", "LABEL_LENGTH", "agents_table", "boards", "events_table", "metadata", "tokens_table"]

AGENT_NAME_LENGTH = 64
"""The longest agent name (the column's width)."""
LABEL_LENGTH = 200
"""The longest label a token may carry (the column's width)."""

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
    Column("id", String(AGENT_NAME_LENGTH), primary_key=True),
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
tokens_table = Table(
    "tokens",
    metadata,
    Column("id", Integer, primary_key=True, autoincrement=True),
    Column("agent", String(AGENT_NAME_LENGTH), ForeignKey("agents.id"), nullable=False, index=True),
    Column("hash", String(64), nullable=False, unique=True),
    Column("created", Float, nullable=False),
    Column("label", String(LABEL_LENGTH), nullable=False),
    Column("revoked", Float, nullable=True),
)
