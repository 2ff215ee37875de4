"""The board's agents and their tokens, in its database.

A token is shown once, when it is made, and stored only as its SHA-256 hash (a drawn token has 144 random
bits, so the hash cannot be turned back). An agent may hold several tokens (one per robot, screen or person
using it); each has a number, a label and the time it was made, and works until it is revoked. Nothing here
ever makes a token the caller did not ask for: starting the service again adds no token to an agent it knows
(but one whose only token was given before and is given no more), and keeps every token that works but those
of ``serve`` the command line no longer gives (:func:`set_up_agents`).

These functions work inside a transaction the caller opens (:class:`~supportive.service.store.BoardStore`
opens them); each raises :class:`~supportive.errors.TokenError` for an agent or token it cannot use, before
it has written anything.
"""

from __future__ import annotations

import hashlib
import secrets
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from sqlalchemy import Select, bindparam, func, insert, select, update
from sqlalchemy.engine import Connection

from supportive.errors import InvalidValueError, TokenError
from supportive.io.values import check_id
from supportive.service.tables import AGENT_NAME_LENGTH, LABEL_LENGTH, agents_table, tokens_table
from supportive.social.board import ROLES, Role

__all__ = [
    "KINDS",
    "SERVE_LABELS",
    "Agent",
    "AgentKind",
    "AgentSetup",
    "AgentSpec",
    "TokenInfo",
    "add_token",
    "agent_for_token",
    "all_agents",
    "check_agent_name",
    "list_tokens",
    "lookup_query",
    "new_token",
    "revoke_tokens",
    "set_up_agents",
    "token_hash",
    "upgrade",
    "with_article",
]

AgentKind = Literal["human", "robot"]
KINDS: tuple[AgentKind, ...] = ("human", "robot")
"""The kinds of agent."""


@dataclass(frozen=True)
class AgentSpec:
    """An agent asked for: its name, kind, role and, when one was given, its token (else one is drawn when the
    agent is made)."""

    id: str
    kind: AgentKind
    role: Role
    token: str | None = None


@dataclass(frozen=True)
class Agent:
    """An agent of the board."""

    id: str
    kind: str
    role: Role


@dataclass(frozen=True)
class TokenInfo:
    """What the database knows of a token (never the token itself).

    Attributes:
        number: The token's number, to name it by (``supportive tokens revoke NUMBER``).
        agent: The agent it signs in as; ``kind`` and ``role`` are the agent's.
        created: When it was made (seconds since 1970).
        label: What it is for (``made by serve``, or the label given to ``tokens add``).
        revoked: When it was revoked, or None while it works.
    """

    number: int
    agent: str
    kind: str
    role: str
    created: float
    label: str
    revoked: float | None = None

    @property
    def active(self) -> bool:
        """Whether the token still works."""
        return self.revoked is None

    def as_dict(self) -> dict[str, Any]:
        """Plain JSON data."""
        return {
            "number": self.number,
            "agent": self.agent,
            "kind": self.kind,
            "role": self.role,
            "created": self.created,
            "label": self.label,
            "revoked": self.revoked,
        }


@dataclass(frozen=True)
class AgentSetup:
    """What starting the service did to the agents.

    Attributes:
        shown: The tokens made now, by agent (drawn, or given with ``--agent name:kind:role:token``): the only
            time they can be shown.
        agents: Every agent of the board.
        working: How many tokens work (made now or before).
        changes: What this start changed because the command line and the database differed (roles taken
            from the command line, tokens revoked, and — added by the store — lead-only marks and claims given
            back), one sentence each: logged and shown in the banner.
    """

    shown: dict[str, str]
    agents: tuple[Agent, ...]
    working: int
    changes: tuple[str, ...] = ()


def check_agent_name(name: str) -> str:
    """``name``, checked as an agent's name: an id (no control character, …) of at most
    :data:`~supportive.service.tables.AGENT_NAME_LENGTH` characters.

    Raises:
        InvalidValueError: naming the agent (cut to the limit) and the problem.
    """
    try:
        check_id(name, what="an agent's name")
        if len(name) > AGENT_NAME_LENGTH:
            raise InvalidValueError(f"an agent's name is at most {AGENT_NAME_LENGTH} characters, got {len(name)}")
    except ValueError as exc:
        raise InvalidValueError(f"agent {name[:AGENT_NAME_LENGTH]!r}: {exc}") from None
    return name


def token_hash(token: str) -> str:
    """The stored form of a token: its SHA-256, in hex."""
    return hashlib.sha256(token.encode("utf-8")).hexdigest()


def new_token(nbytes: int = 18) -> str:
    """A new random token: ``nbytes`` random bytes (default 18, 144 bits), URL-safe base64 (24 characters)."""
    return secrets.token_urlsafe(nbytes)


def upgrade(connection: Connection) -> int:
    """Give every agent without a row in ``tokens`` one from its ``token_hash`` (a database made before the
    ``tokens`` table existed keeps the tokens it had); how many were added."""
    have = select(tokens_table.c.agent)
    rows = connection.execute(
        select(agents_table.c.id, agents_table.c.token_hash).where(agents_table.c.id.not_in(have))
    ).all()
    now = time.time()
    for row in rows:
        connection.execute(
            insert(tokens_table).values(
                agent=row.id, hash=row.token_hash, created=now, label="kept from an earlier version"
            )
        )
    return len(rows)


SERVE_LABELS = ("given to serve", "made by serve")
"""The labels of the tokens ``serve`` makes or is given: its own, which a later start reconciles with its
command line (a token of ``supportive tokens add``, or one kept from an earlier version, stays until revoked)."""
_RESERVED_LABELS = (*SERVE_LABELS, "kept from an earlier version")


def set_up_agents(
    connection: Connection, specs: Sequence[AgentSpec], defaults: Sequence[AgentSpec] = ()
) -> AgentSetup:
    """Bring the board's agents to the ones asked for (the command line wins):

    * an agent the board does not have is added, with the token given, else a new one (shown once);
    * a known agent asked for with another role takes that role (the change is reported);
    * a known agent asked for with a token keeps that token; its other tokens from ``serve`` are revoked (a
      token no longer given stops working); one asked for without a token keeps the tokens ``serve`` drew
      for it, loses one that was given before (and gets a new one, shown once, when that was its last);
    * a known agent not asked for loses every token from ``serve`` (it stays on the board, for the log).

    Tokens made by ``supportive tokens add`` (or kept from an earlier version) are kept. ``defaults`` are the agents of a board that has none
    yet (used when ``specs`` is empty); with no ``specs``, a board that has agents keeps them as they are.

    Raises:
        TokenError: for an agent asked for with another kind than the board's, a role that is not one, or a
            given token that another agent holds or that was revoked.
    """
    known = {a.id: a for a in all_agents(connection)}
    wanted = list(specs) or (list(defaults) if not known else [])
    shown: dict[str, str] = {}
    changes: list[str] = []
    for spec in wanted:
        if spec.role not in ROLES:
            raise TokenError(f"agent {spec.id}: unknown role {spec.role!r}; choose {', '.join(ROLES)}")
        agent = known.get(spec.id)
        if agent is not None and agent.kind != spec.kind:
            raise TokenError(
                f"agent {spec.id!r} is a {agent.kind} on this board, not a {spec.kind}: an agent keeps its "
                "kind (give another name for another agent)"
            )
        if agent is not None and agent.role != spec.role:
            connection.execute(update(agents_table).where(agents_table.c.id == spec.id).values(role=spec.role))
            known[spec.id] = Agent(spec.id, spec.kind, spec.role)
            changes.append(f"{spec.id} is now {with_article(spec.role)} (was {with_article(agent.role)}): the command line says so")
        if spec.token is not None:
            held = _holder(connection, spec.token)
            if held is not None:
                holder, revoked = held
                if holder != spec.id:
                    raise TokenError(f"agent {spec.id}: the token given is another agent's; give another")
                if revoked:
                    raise TokenError(
                        f"agent {spec.id}: the token given was revoked (supportive tokens list); give another"
                    )
            if agent is not None:
                _retire(connection, spec.id, SERVE_LABELS, keep=token_hash(spec.token), changes=changes)
            if held is not None:
                continue  # the agent's, and it works: nothing to add
        elif agent is not None:
            before = _working(connection, spec.id)
            _retire(connection, spec.id, ("given to serve",), changes=changes)
            if not before or _working(connection, spec.id):
                continue  # it keeps a token that works (or had none working: tokens revoke said so)
        token = spec.token or new_token()
        if agent is None:
            connection.execute(
                insert(agents_table).values(
                    id=spec.id, kind=spec.kind, role=spec.role, token_hash=token_hash(token)
                )
            )
            known[spec.id] = Agent(spec.id, spec.kind, spec.role)
        label = "given to serve" if spec.token else "made by serve"
        _insert(connection, spec.id, token, label)
        shown[spec.id] = token
    if specs:
        for name in sorted(set(known) - {spec.id for spec in specs}):
            _retire(connection, name, SERVE_LABELS, changes=changes, why="is not on the command line")
    working = connection.execute(
        select(func.count()).select_from(tokens_table).where(tokens_table.c.revoked.is_(None))
    ).scalar_one()
    return AgentSetup(shown, tuple(known[name] for name in sorted(known)), int(working), tuple(changes))


def with_article(word: str) -> str:
    """``word`` after "a" or "an" ("an assistant", "a lead")."""
    return f"an {word}" if word[:1] in ("a", "e", "i", "o", "u") else f"a {word}"


def _working(connection: Connection, agent: str) -> int:
    query = select(func.count()).select_from(tokens_table).where(
        tokens_table.c.agent == agent, tokens_table.c.revoked.is_(None)
    )
    return int(connection.execute(query).scalar_one())


def _retire(
    connection: Connection,
    agent: str,
    labels: Sequence[str],
    *,
    changes: list[str],
    keep: str | None = None,
    why: str = "",
) -> None:
    """Revoke ``agent``'s working tokens labelled one of ``labels`` (but the one whose hash is ``keep``),
    saying so in ``changes``."""
    query = select(tokens_table.c.id).where(
        tokens_table.c.agent == agent, tokens_table.c.revoked.is_(None), tokens_table.c.label.in_(labels)
    )
    if keep is not None:
        query = query.where(tokens_table.c.hash != keep)
    numbers = [int(n) for n in connection.execute(query).scalars()]
    if not numbers:
        return
    connection.execute(update(tokens_table).where(tokens_table.c.id.in_(numbers)).values(revoked=time.time()))
    listed = f"token{'s' if len(numbers) > 1 else ''} {', '.join(map(str, numbers))}"
    if why:
        changes.append(f"{agent} {why}: revoked its {listed} from serve")
    else:
        changes.append(f"{agent}'s {listed} from serve {'are' if len(numbers) > 1 else 'is'} given no more: revoked")


def lookup_query() -> Select[Any]:
    """The query for the agent (id, kind, role) of a working token whose hash is the parameter ``digest``."""
    return (
        select(agents_table.c.id, agents_table.c.kind, agents_table.c.role)
        .join(tokens_table, tokens_table.c.agent == agents_table.c.id)
        .where(tokens_table.c.hash == bindparam("digest"), tokens_table.c.revoked.is_(None))
    )


def agent_for_token(connection: Connection, token: str) -> Agent | None:
    """The agent a token signs in as, or None when it is unknown or revoked."""
    row = connection.execute(lookup_query(), {"digest": token_hash(token)}).first()
    return None if row is None else Agent(row.id, row.kind, row.role)


def all_agents(connection: Connection) -> list[Agent]:
    """Every agent, by name."""
    rows = connection.execute(select(agents_table).order_by(agents_table.c.id)).all()
    return [Agent(r.id, r.kind, r.role) for r in rows]


def list_tokens(connection: Connection, *, revoked: bool = True) -> list[TokenInfo]:
    """Every token (``revoked=False``: only those that work), by number."""
    query = (
        select(tokens_table, agents_table.c.kind, agents_table.c.role)
        .join(agents_table, tokens_table.c.agent == agents_table.c.id)
        .order_by(tokens_table.c.id)
    )
    if not revoked:
        query = query.where(tokens_table.c.revoked.is_(None))
    return [_info(row) for row in connection.execute(query)]


def add_token(
    connection: Connection,
    agent: str,
    label: str = "",
    *,
    kind: AgentKind | None = None,
    role: Role | None = None,
) -> tuple[TokenInfo, str]:
    """A new token for ``agent`` (made with ``kind`` and ``role`` when the board has no such agent); the
    token's record and the token, which is not kept and cannot be shown again.

    Raises:
        TokenError: for an unknown agent without a kind and role, a kind or role that differs from a known
            agent's, or a label over :data:`~supportive.service.tables.LABEL_LENGTH` characters.
        InvalidValueError: for a new agent's name that is not one (:func:`check_agent_name`).
    """
    if len(label) > LABEL_LENGTH:
        raise TokenError(f"a token's label is at most {LABEL_LENGTH} characters, got {len(label)}")
    if label in _RESERVED_LABELS:
        raise TokenError(f"the label {label!r} is serve's own; give another")
    known = {a.id: a for a in all_agents(connection)}
    if agent not in known:
        check_agent_name(agent)
    token = new_token()
    if agent not in known:
        if kind is None or role is None:
            names = ", ".join(known) or "none"
            raise TokenError(
                f"no agent {agent!r} on this board (agents: {names}); give --kind and --role to add one"
            )
        if role not in ROLES or kind not in KINDS:
            raise TokenError(f"agent {agent}: expected kind {' or '.join(KINDS)} and role {', '.join(ROLES)}")
        connection.execute(
            insert(agents_table).values(id=agent, kind=kind, role=role, token_hash=token_hash(token))
        )
    else:
        have = known[agent]
        if (kind is not None and kind != have.kind) or (role is not None and role != have.role):
            raise TokenError(
                f"agent {agent!r} is a {have.kind} {have.role} on this board: an agent keeps its kind and role"
            )
    number = _insert(connection, agent, token, label or "made by tokens add")
    return _by_number(connection, number), token


def revoke_tokens(
    connection: Connection, numbers: Sequence[int] = (), agent: str | None = None
) -> list[TokenInfo]:
    """Revoke the tokens numbered ``numbers`` and, with ``agent``, every token of that agent: they stop
    working at once (a request with one is refused). Returns the tokens revoked now (one revoked before is
    left as it was).

    Raises:
        TokenError: for a number no token has, or an agent the board does not have.
    """
    wanted = set(numbers)
    if agent is not None:
        if agent not in {a.id for a in all_agents(connection)}:
            raise TokenError(f"no agent {agent!r} on this board")
        mine = select(tokens_table.c.id).where(tokens_table.c.agent == agent)
        wanted |= {int(n) for n in connection.execute(mine).scalars()}
    existing = {int(n) for n in connection.execute(select(tokens_table.c.id)).scalars()}
    unknown = sorted(wanted - existing)
    if unknown:
        raise TokenError(f"no token numbered {', '.join(map(str, unknown))} (supportive tokens list shows them)")
    live = [t for t in list_tokens(connection, revoked=False) if t.number in wanted]
    if live:
        now = time.time()
        connection.execute(
            update(tokens_table).where(tokens_table.c.id.in_([t.number for t in live])).values(revoked=now)
        )
        live = [_by_number(connection, t.number) for t in live]
    return live


def _insert(connection: Connection, agent: str, token: str, label: str) -> int:
    digest = token_hash(token)
    connection.execute(insert(tokens_table).values(agent=agent, hash=digest, created=time.time(), label=label))
    return int(connection.execute(select(tokens_table.c.id).where(tokens_table.c.hash == digest)).scalar_one())


def _holder(connection: Connection, token: str) -> tuple[str, bool] | None:
    """The agent holding a token and whether it is revoked, or None when no agent ever held it."""
    query = select(tokens_table.c.agent, tokens_table.c.revoked).where(tokens_table.c.hash == token_hash(token))
    row = connection.execute(query).first()
    return None if row is None else (str(row.agent), row.revoked is not None)


def _by_number(connection: Connection, number: int) -> TokenInfo:
    query = (
        select(tokens_table, agents_table.c.kind, agents_table.c.role)
        .join(agents_table, tokens_table.c.agent == agents_table.c.id)
        .where(tokens_table.c.id == number)
    )
    return _info(connection.execute(query).one())


def _info(row: Any) -> TokenInfo:
    return TokenInfo(
        int(row.id), str(row.agent), str(row.kind), str(row.role), float(row.created), str(row.label), row.revoked
    )
