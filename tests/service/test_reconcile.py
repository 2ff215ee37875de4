"""A board follows what it is started with, restart by restart (issue 28): roles and lead-only marks from the
command line win (logged and shown in the banner), a token no longer given is revoked, claims an agent may no
longer hold go back to the pool, and a task file edited under the same name is refused. Checked against the
independent model of the rules (rules_model.py): first the board's own logic under random operations and
random restarts, then the service on SQLite and PostgreSQL over HTTP and WebSocket, then real ``serve``
processes in the issue's two scenarios."""

from __future__ import annotations

import random
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import yaml
from fastapi.testclient import TestClient
from hypothesis import given
from hypothesis import strategies as st
from starlette.websockets import WebSocketDisconnect

from supportive.errors import BoardError
from supportive.examples import path as example_path
from supportive.io.taskfile import parse_task_file
from supportive.service.app import create_app
from supportive.service.launch import free_port
from supportive.service.reconcile import reconcile_board
from supportive.service.settings import ServiceSettings, board_of, parse_agent
from supportive.social.board import Role, TaskBoard

from .conftest import ServeProcess
from .rules_model import RulesModel

SPEC = parse_task_file(example_path("ikea-chair"))
NAMES = ("Attach seat", "Screw seat", "Mount supports", "Fasten rear left bolt")
ROLES: tuple[Role, ...] = ("lead", "assistant", "observer")
PEOPLE = ("alice", "bob", "robot")


def board(lead_only: Sequence[str] = ()) -> TaskBoard:
    return board_of(SPEC, lead_only)


@given(st.data())
def test_the_board_and_a_start_follow_the_model_of_the_rules(data: st.DataObject) -> None:
    """Random operations by agents of random roles, with starts between them that change roles, lead-only
    marks and who has a working token: every status and every board equals the model's."""
    current = board()
    model = RulesModel.of(current.as_dict()["nodes"])
    roles: dict[str, Role] = {"alice": "lead", "robot": "assistant"}
    leaves = [n.id for n in current.nodes]
    for _ in range(data.draw(st.integers(1, 4))):
        lead_only = data.draw(st.lists(st.sampled_from(NAMES), max_size=2, unique=True))
        roles = {name: data.draw(st.sampled_from(ROLES)) for name in PEOPLE}
        working = set(data.draw(st.lists(st.sampled_from(PEOPLE), unique=True)))
        current, _, _ = reconcile_board(current, board(lead_only), roles, working)
        model.restart({n.id for n in board(lead_only).nodes if n.lead_only}, roles, working)
        assert model.matches(current.as_dict()["nodes"]) == []
        for _ in range(data.draw(st.integers(0, 25))):
            agent = data.draw(st.sampled_from(sorted(working) or ["alice"]))
            op = data.draw(st.sampled_from(["claim", "release", "complete", "progress"]))
            node = data.draw(st.sampled_from(leaves))
            want = model.step(op, node, agent, roles.get(agent, "observer"))
            try:
                current = current.apply(op, node, agent, roles.get(agent, "observer"), 0.5)
                got = 200
            except BoardError as refused:
                got = {"invalid": 400, "forbidden": 403, "missing": 404, "conflict": 409}[refused.reason]
            assert (op, node, agent, got) == (op, node, agent, want)
            assert model.matches(current.as_dict()["nodes"]) == []


# -- the service, restart by restart, on both databases ----------------------------------------------------


def settings(database: str, agents: Sequence[str], lead_only: Sequence[str]) -> ServiceSettings:
    return ServiceSettings(database, board(lead_only), tuple(parse_agent(a) for a in agents), SPEC)


def status_of(client: TestClient, token: str) -> tuple[int, str | None]:
    response = client.get("/api/me", headers={"Authorization": f"Bearer {token}"})
    return response.status_code, response.json().get("role") if response.status_code == 200 else None


def socket_board(client: TestClient, token: str) -> list[dict[str, Any]] | int:
    """The snapshot's nodes a WebSocket with ``token`` gets, or the code it is closed with."""
    with client.websocket_connect(f"/api/ws?token={token}") as ws:
        try:
            message = ws.receive_json()
        except WebSocketDisconnect as closed:
            return closed.code
        return list(message["board"]["nodes"])


def test_restart_by_restart_the_service_follows_its_command_line_and_the_model(database: str) -> None:
    """Six starts on one database, each with a random command line (roles, tokens new or kept, agents left
    out, lead-only marks), 30 random operations over HTTP between them; after each start every token ever
    given signs in as the model says (HTTP and WebSocket), and the board both give is the model's."""
    rng = random.Random(28)
    given: dict[str, str] = {}  # token -> agent, every token ever given
    working: dict[str, str] = {}  # agent -> its working token
    roles: dict[str, Role] = {}
    model: RulesModel | None = None
    for start in range(6):
        agents = [name for name in PEOPLE if start == 0 or rng.random() < 0.8] or ["alice"]
        command = []
        for name in agents:
            role = rng.choice(ROLES)
            token = working[name] if name in working and rng.random() < 0.5 else f"{name}-{start}-token"
            command.append(f"{name}:{'robot' if name == 'robot' else 'human'}:{role}:{token}")
            roles[name] = role
            given[token] = name
        lead_only = rng.sample(NAMES, rng.randint(0, 2))
        for name in set(working) - set(agents):  # no longer given: revoked
            del working[name]
        working.update({line.split(":")[0]: line.split(":")[3] for line in command})
        with TestClient(create_app(settings(database, command, lead_only))) as client:
            nodes = client.get("/api/board", headers={"Authorization": f"Bearer {working[agents[0]]}"}).json()["nodes"]
            if model is None:
                model = RulesModel.of(nodes)
            model.restart({n["id"] for n in nodes if n["name"] in lead_only}, roles, set(working))
            assert model.matches(nodes) == [], f"start {start}: {command} {lead_only}"
            for token, name in given.items():
                works = working.get(name) == token
                assert status_of(client, token) == ((200, roles[name]) if works else (401, None)), (start, name)
                seen = socket_board(client, token)
                assert seen == 4401 if not works else isinstance(seen, list) and model.matches(seen) == []
            ids = [n["id"] for n in nodes]
            for _ in range(30):
                name = rng.choice(sorted(working))
                op = rng.choice(["claim", "claim", "complete", "release", "progress"])
                node = rng.choice(ids)
                body = {"progress": 0.5} if op == "progress" else None
                response = client.post(
                    f"/api/nodes/{node}/{op}", json=body, headers={"Authorization": f"Bearer {working[name]}"}
                )
                assert response.status_code == model.step(op, node, name, roles[name]), (start, op, node, name)
            after = client.get("/api/board", headers={"Authorization": f"Bearer {working[agents[0]]}"}).json()
            assert model.matches(after["nodes"]) == []
            store = client.app.state.service.store  # type: ignore[attr-defined]
            replayed = store.initial()  # the log, the starts' own changes with it, gives the board
            for event in store.events(limit=100_000):
                replayed = replayed.apply(event.op, event.node, event.agent, "lead", event.progress)
            assert {"version": after["version"], **replayed.as_dict()} == after
    assert {e.op for e in store.events(limit=100_000)} >= {"claim", "reserve", "free"}  # each kind was met


def test_a_task_file_edited_under_the_same_name_is_refused_and_the_board_kept(
    database: str, tmp_path: Path, cli: Any
) -> None:
    with TestClient(create_app(settings(database, ["alice:human:lead:tok-a"], ()))) as client:
        assert client.post("/api/nodes/n4/claim", headers={"Authorization": "Bearer tok-a"}).status_code == 200
    data = yaml.safe_load(example_path("ikea-chair").read_text(encoding="utf-8"))
    data["actions"].append({"id": "admire", "text": "admire the chair"})
    data["structure"] = {"chain": [data["structure"], "admire"], "name": "Assemble and admire"}
    edited = tmp_path / "chair.yaml"
    edited.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    code, out, err = cli(["serve", "--task", str(edited), "--db", database, "--port", str(free_port())])
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert "made from another version of the task file" in err and "start a new board with another --db" in err
    with TestClient(create_app(settings(database, ["alice:human:lead:tok-a"], ()))) as client:  # kept as it was
        events = client.get("/api/events", headers={"Authorization": "Bearer tok-a"}).json()
        assert [(e["op"], e["node"]) for e in events] == [("claim", "n4")]


# -- real `serve` processes: the two scenarios ------------------------------------------------------


def seat(board: dict[str, Any]) -> dict[str, Any]:
    return next(n for n in board["nodes"] if n["name"] == "Attach seat")


def test_a_robot_demoted_by_the_command_line_loses_its_role_its_old_token_and_its_claims(served: ServeProcess) -> None:
    served.start(
        "--lead-only", "Attach seat",
        "--agent", "alice:human:lead:ALICE-TOKEN-123", "--agent", "robot:robot:lead:OLD-TOKEN-123",
    )
    assert served.post("/api/nodes/n35/claim", "OLD-TOKEN-123") == 200  # a lead may
    served.stop()
    served.start("--lead-only", "Attach seat", "--agent", "robot:robot:observer:NEW-TOKEN-456")
    banner = "\n".join(served.banner)
    assert "new token for robot (robot, observer): NEW-TOKEN-456" in banner
    assert "changed at this start: robot is now an observer (was a lead)" in banner
    assert "changed at this start: robot's token 2 from serve is given no more: revoked" in banner
    assert "changed at this start: alice is not on the command line: revoked its token 1 from serve" in banner
    assert re.search(r"robot's claim of 'Attach seat' \(n35\) went back to the pool: robot is an observer", banner)
    assert served.me("OLD-TOKEN-123", "role") == 401 and served.socket("OLD-TOKEN-123", "board") == 4401
    assert served.me("ALICE-TOKEN-123", "role") == 401 and served.socket("ALICE-TOKEN-123", "board") == 4401
    assert served.me("NEW-TOKEN-456", "role") == "observer"
    assert served.post("/api/nodes/n35/claim", "NEW-TOKEN-456") == 403
    now = served.socket("NEW-TOKEN-456", "board")
    assert isinstance(now, dict) and seat(now)["owner"] is None and seat(now)["lead_only"]
    served.stop()
    assert "robot is now an observer (was a lead)" in served.stderr  # logged at the start too


def test_a_subtask_made_lead_only_at_a_restart_is_refused_to_an_assistant(served: ServeProcess) -> None:
    agents = ("--agent", "alice:human:lead:tok-alice", "--agent", "robot:robot:assistant:tok-robot")
    served.start(*agents)
    assert served.post("/api/nodes/n36/claim", "tok-robot") == 200  # not reserved yet
    served.stop()
    served.start(*agents, "--lead-only", "Attach seat")
    assert "changed at this start: 'Attach seat' (n35) is now lead-only" in "\n".join(served.banner)
    assert served.post("/api/nodes/n35/claim", "tok-robot") == 403
    assert served.post("/api/nodes/n37/claim", "tok-robot") == 403
    now = served.socket("tok-robot", "board")
    assert isinstance(now, dict) and seat(now)["lead_only"]
    assert all(n["owner"] is None for n in now["nodes"] if n["id"] in ("n35", "n36"))  # given back
    assert served.post("/api/nodes/n35/claim", "tok-alice") == 200
    served.stop()
    served.start(*agents)  # and without it again: open to the assistant once more (alice keeps her claim)
    assert "changed at this start: 'Attach seat' (n35) is no longer lead-only" in "\n".join(served.banner)
    assert served.post("/api/nodes/n35/release", "tok-alice") == 200
    assert served.post("/api/nodes/n35/claim", "tok-robot") == 200
