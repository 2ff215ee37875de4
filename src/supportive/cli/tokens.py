"""``supportive tokens``: list, add and revoke the task board's tokens, in its database (the ``server`` extra).

A token is shown once, when it is made (by ``serve`` for a new agent, or by ``tokens add``), and kept only as
its hash; these commands work on the database whether or not the board is running, and a token revoked here
is refused by a running board at once.
"""

from __future__ import annotations

import json
import sys
from datetime import datetime
from enum import StrEnum
from typing import TYPE_CHECKING, Annotated

import typer

from supportive.cli.output import out, say

if TYPE_CHECKING:
    from supportive.service.agents import TokenInfo
    from supportive.service.store import BoardStore

__all__ = ["tokens_app"]

tokens_app = typer.Typer(
    no_args_is_help=True,
    help="The task board's tokens: list them, add one, revoke some (in the board's database; needs the server "
    "extra).",
)


class Kind(StrEnum):
    """Kinds of agent."""

    human = "human"
    robot = "robot"


class AgentRole(StrEnum):
    """Roles of agent."""

    lead = "lead"
    assistant = "assistant"
    observer = "observer"


Database = Annotated[
    str,
    typer.Option("--db", help="The board's database: sqlite:///board.db or postgresql+psycopg://user@127.0.0.1/db."),
]


def _open(database: str) -> BoardStore:
    """The board's database, which must hold a board already (nothing is created, not even a SQLite file)."""
    from supportive.service.launch import legacy_tokens_file
    from supportive.service.store import BoardStore

    legacy_tokens_file(database)  # a URL of the right shape, or one line saying what is expected
    store = BoardStore(database, create=False)
    try:
        store.open_existing()
    except BaseException:
        store.close()
        raise
    return store


def _when(seconds: float | None) -> str:
    return "" if seconds is None else datetime.fromtimestamp(seconds).astimezone().strftime("%Y-%m-%d %H:%M")


def _described(token: TokenInfo) -> str:
    return f"token {token.number} of {token.agent} ({token.kind}, {token.role}), made {_when(token.created)}, {token.label!r}"


@tokens_app.command("list")
def list_tokens(
    db: Database = "sqlite:///board.db",
    working: Annotated[bool, typer.Option("--working", help="Only the tokens that work (not revoked).")] = False,
    as_json: Annotated[bool, typer.Option("--json", help="Print JSON instead of a table.")] = False,
) -> None:
    """List the board's tokens: number, agent, kind, role, when made, label, and when revoked (never the
    tokens themselves: they are kept only as hashes)."""
    from supportive.render.tables import fitted_table

    store = _open(db)
    try:
        found = store.tokens(revoked=not working)
    finally:
        store.close()
    if as_json:
        sys.stdout.write(json.dumps([t.as_dict() for t in found], indent=2) + "\n")
        return
    rows = [
        [str(t.number), t.agent, t.kind, t.role, _when(t.created), t.label, _when(t.revoked) or "works"]
        for t in found
    ]
    title = f"tokens of the board in {store.shown_url}"
    headers = ["number", "agent", "kind", "role", "made", "label", "revoked"]
    out.print(fitted_table(out, title, headers, rows, numeric=(0,)))


@tokens_app.command("add")
def add_token(
    agent: Annotated[str, typer.Argument(help="The agent the token signs in as.")],
    db: Database = "sqlite:///board.db",
    label: Annotated[
        str, typer.Option("--label", help="What the token is for (say, which robot or screen uses it).")
    ] = "",
    kind: Annotated[
        Kind | None, typer.Option("--kind", help="A new agent's kind (with --role): human or robot.")
    ] = None,
    role: Annotated[
        AgentRole | None,
        typer.Option("--role", metavar="lead|assistant|observer", help="A new agent's role (with --kind): lead, assistant or observer."),
    ] = None,
) -> None:
    """Make a new token for an agent (a new agent too, given --kind and --role) and print it on stdout, this
    once: it is kept only as a hash. The agent's other tokens keep working."""
    from supportive.errors import OptionError
    from supportive.service.agents import check_agent_name

    if (kind is None) != (role is None):
        raise OptionError("give --kind and --role together (they make a new agent), or neither")
    if kind is not None:
        check_agent_name(agent)  # before the database is opened: the rules of serve --agent
    store = _open(db)
    try:
        token, text = store.add_token(
            agent, label, kind=None if kind is None else kind.value, role=None if role is None else role.value
        )
    finally:
        store.close()
    sys.stdout.write(text + "\n")
    sys.stdout.flush()
    say(
        f"{_described(token)}: shown this once. Revoke it with: supportive tokens revoke {token.number} "
        f"--db {store.shown_url}",
        to_stderr=True,
        whole=True,
    )


@tokens_app.command("revoke")
def revoke_tokens(
    numbers: Annotated[
        list[int] | None, typer.Argument(help="Numbers of the tokens to revoke (supportive tokens list).")
    ] = None,
    db: Database = "sqlite:///board.db",
    agent: Annotated[
        str | None, typer.Option("--agent", help="Revoke every token of this agent.")
    ] = None,
) -> None:
    """Revoke tokens: a running board refuses them at once (401; an open WebSocket is closed with 4401 within
    a second). The agent stays, with its other tokens."""
    from supportive.errors import OptionError

    if not numbers and agent is None:
        raise OptionError("name the tokens to revoke by number (supportive tokens list), or give --agent NAME")
    store = _open(db)
    try:
        revoked = store.revoke_tokens(numbers or (), agent)
    finally:
        store.close()
    for token in revoked:
        say(f"revoked {_described(token)}", whole=True)
    if not revoked:
        say("nothing to revoke: the tokens named were revoked before")
