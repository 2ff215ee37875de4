"""Tokens that survive restarts (issue 25): kept only as hashes in the board's database, shown once when made,
never minted again by a restart, listed, added and revoked by ``supportive tokens``; a revoked token is
refused at once on HTTP and on a new WebSocket, and an open WebSocket using it is closed with 4401. The same
on SQLite and PostgreSQL, against real ``supportive serve`` processes."""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from pathlib import Path

import pytest
import sqlalchemy
from fastapi.testclient import TestClient
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from supportive.errors import TokenError
from supportive.service.agents import token_hash

from .conftest import ServeProcess, chair_settings

CliRunner = Callable[[list[str]], tuple[int, str, str]]


def test_restarts_keep_every_token_shown_and_a_revoked_one_is_refused_at_once(served: ServeProcess, cli: CliRunner) -> None:
    """``supportive tokens`` runs in this process, the board in another."""
    first = served.start()
    assert sorted(first) == ["alice", "robot", "screen"] and len(set(first.values())) == 3
    assert f"#token={first['alice']}" in served.banner[0]
    code, out, err = cli(["tokens", "add", "robot", "--label", "arm 2", "--db", served.database])
    assert code == 0, err
    arm2 = out.strip()
    assert re.fullmatch(r"[A-Za-z0-9_-]{24}", arm2) and "token 4 of robot" in err and arm2 not in err
    shown = {**first, "arm2": arm2}
    who = {"alice": "alice", "robot": "robot", "screen": "screen", "arm2": "robot"}

    for restart in range(2):  # the same command again, twice: no token made, every token shown still works
        served.stop()
        assert served.start() == {}, served.banner
        assert "#token=" not in served.banner[0] and "agents as before: alice (human, lead)" in "\n".join(served.banner)
        assert {name: served.me(token, "id") for name, token in shown.items()} == who
        assert {name: served.socket(token, "type") for name, token in shown.items()} == dict.fromkeys(shown, "snapshot")
        if restart:
            break
        # revoke robot's first token while the board runs: refused at once, its open socket closed
        with connect(f"ws://127.0.0.1:{served.port}/api/ws?token={shown['robot']}") as open_socket:
            assert json.loads(open_socket.recv(timeout=10))["type"] == "snapshot"
            code, out, err = cli(["tokens", "revoke", "2", "--db", served.database])
            assert code == 0 and out.startswith("revoked token 2 of robot"), err
            assert served.me(shown["robot"], "id") == 401
            assert served.socket(shown["robot"], "type") == 4401
            with pytest.raises(ConnectionClosed) as closed:
                open_socket.recv(timeout=5)  # token_recheck is 1 s
            assert closed.value.rcvd is not None and closed.value.rcvd.code == 4401
        assert served.me(arm2, "id") == "robot"  # the agent keeps its other token
        shown.pop("robot")
        who.pop("robot")

    rows = json.loads(cli(["tokens", "list", "--json", "--db", served.database])[1])
    assert [(r["number"], r["agent"], r["label"], r["revoked"] is None) for r in rows] == [
        (1, "alice", "made by serve", True),
        (2, "robot", "made by serve", False),
        (3, "screen", "made by serve", True),
        (4, "robot", "arm 2", True),
    ]
    assert served.me(first["robot"], "id") == 401 and served.socket(first["robot"], "type") == 4401  # still, after a restart


def test_a_given_token_is_kept_and_a_revoked_one_cannot_be_given_again(database: str) -> None:
    from supportive.service.app import create_app
    from supportive.service.settings import parse_agent
    from supportive.service.store import BoardStore

    settings = chair_settings(database)
    create_app(settings).state.service.store.close()
    store = BoardStore(database)
    robot = next(t for t in store.tokens() if t.agent == "robot")
    assert [t.number for t in store.revoke_tokens([robot.number])] == [robot.number]
    assert store.revoke_tokens([robot.number]) == []  # revoked before: left as it was
    store.close()
    cases = [
        ("robot:robot:assistant:tok-robot", "the token given was revoked"),
        ("bob:human:lead:tok-alice", "the token given is another agent's"),
        ("alice:robot:lead:tok-alice", "'alice' is a human on this board, not a robot: an agent keeps its kind"),
    ]
    for text, problem in cases:
        changed = type(settings)(database, settings.board, (parse_agent(text),), settings.spec)
        with pytest.raises(TokenError, match=problem):
            create_app(changed)
    again = create_app(settings.__class__(database, settings.board, (parse_agent("alice:human:lead:tok-alice"),)))
    setup = again.state.service.setup
    assert setup.shown == {} and [a.id for a in setup.agents] == ["alice", "bob", "robot", "screen"]
    again.state.service.store.close()


def test_a_database_of_an_earlier_version_keeps_its_tokens(tmp_path: Path) -> None:
    """Before the tokens table, each agent's one token hash was a column of ``agents``: those tokens keep
    working, and are listed as kept from an earlier version."""
    database = f"sqlite:///{tmp_path / 'board.db'}"
    settings = chair_settings(database)
    engine = sqlalchemy.create_engine(database)
    with engine.begin() as connection:
        connection.exec_driver_sql(
            "CREATE TABLE agents (id VARCHAR(64) PRIMARY KEY, kind VARCHAR(16) NOT NULL, role VARCHAR(16) NOT NULL, "
            "token_hash VARCHAR(64) NOT NULL UNIQUE)"
        )
        connection.exec_driver_sql(
            f"INSERT INTO agents VALUES ('alice', 'human', 'lead', '{token_hash('old-alice')}')"
        )
    engine.dispose()
    from supportive.service.app import create_app

    with TestClient(create_app(settings)) as client:
        assert client.get("/api/me", headers={"Authorization": "Bearer old-alice"}).json()["id"] == "alice"
        assert client.get("/api/me", headers={"Authorization": "Bearer tok-alice"}).status_code == 200  # given now
        labels = [(t.agent, t.label) for t in client.app.state.service.store.tokens()]  # type: ignore[attr-defined]
    assert labels[0] == ("alice", "kept from an earlier version") and ("alice", "given to serve") in labels


def test_an_earlier_versions_plain_text_tokens_file_is_shown_a_last_time_and_removed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from supportive import examples
    from supportive.cli import serve as serve_command
    from supportive.service import launch, serving

    database = f"sqlite:///{tmp_path / 'board.db'}"
    monkeypatch.setattr(serving, "run", lambda *args, **kwargs: None)  # start, announce, and stop at once
    first = launch.prepare(examples.path("ikea-chair"), database)
    launch.serve(first, serve_command.announce)
    made = dict(re.findall(r"new token for (\w+) \([^)]*\): (\S+)$", capsys.readouterr().out, re.MULTILINE))
    old = tmp_path / "board.db.tokens.json"
    old.write_text(json.dumps({"alice": made["alice"], "robot": "forged"}))
    launch.serve(launch.prepare(examples.path("ikea-chair"), database), serve_command.announce)
    said = capsys.readouterr().out
    assert f"token for alice (human, lead), shown this last time: {made['alice']}" in said
    assert "forged" not in said and f"#token={made['alice']}" in said and "removing it" in said
    assert not old.exists()


def test_tokens_commands_need_a_board_and_create_nothing(tmp_path: Path, cli: CliRunner) -> None:
    empty = tmp_path / "empty.db"
    sqlalchemy.create_engine(f"sqlite:///{empty}").connect().close()  # a database, without a board
    for database in ("none.db", "empty.db"):
        for args in (["list"], ["add", "alice"], ["revoke", "1"]):
            code, out, err = cli(["tokens", *args, "--db", f"sqlite:///{tmp_path / database}"])
            assert code == 2 and out == "" and len(err.splitlines()) == 1, err
            assert err.startswith(f"supportive: error: no board in sqlite:///{tmp_path / database}"), err
    assert [p.name for p in tmp_path.iterdir()] == ["empty.db"] and empty.stat().st_size == 0


def test_revoking_every_token_of_an_agent_keeps_the_agent(tmp_path: Path, cli: CliRunner) -> None:
    from supportive.service.app import create_app

    database = f"sqlite:///{tmp_path / 'board.db'}"
    with TestClient(create_app(chair_settings(database))) as client:
        code, out, err = cli(["tokens", "add", "bob", "--db", database, "--label", "bob's tablet"])
        second = out.strip()
        assert code == 0 and client.get("/api/me", headers={"Authorization": f"Bearer {second}"}).json()["id"] == "bob"
        code, out, err = cli(["tokens", "revoke", "--agent", "bob", "--db", database])
        assert code == 0 and [line.split(" of ")[0] for line in out.splitlines()] == ["revoked token 2", "revoked token 5"]
        for token in ("tok-bob", second):
            assert client.get("/api/me", headers={"Authorization": f"Bearer {token}"}).status_code == 401
        assert "bob" in [a["id"] for a in client.get("/api/agents", headers={"Authorization": "Bearer tok-alice"}).json()]
        code, out, err = cli(["tokens", "add", "carol", "--kind", "robot", "--role", "assistant", "--db", database])
        assert code == 0 and client.get("/api/me", headers={"Authorization": f"Bearer {out.strip()}"}).json() == {
            "id": "carol", "kind": "robot", "role": "assistant"}
    for args, problem in [
        (["revoke", "99"], "no token numbered 99"),
        (["revoke"], "name the tokens to revoke by number"),
        (["add", "dave"], "no agent 'dave' on this board (agents: alice, bob, carol, robot, screen)"),
        (["add", "dave", "--kind", "robot"], "give --kind and --role together"),
        (["add", "alice", "--kind", "robot", "--role", "lead"], "'alice' is a human lead on this board"),
        (["add", "x" * 65, "--kind", "robot", "--role", "lead"], "an agent's name is at most 64 characters"),
        (["add", "alice", "--label", "l" * 201], "a token's label is at most 200 characters"),
        (["add", "alice", "--label", "given to serve"], "the label 'given to serve' is serve's own"),
    ]:
        code, out, err = cli(["tokens", *args, "--db", database])
        assert code == 2 and out == "" and len(err.splitlines()) == 1 and problem in err, err
