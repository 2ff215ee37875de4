"""The board API in process (TestClient), on SQLite and PostgreSQL: what it allows, what it refuses, and that
a refused request leaves the board as it was."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import Any

import pytest
from fastapi.testclient import TestClient

from supportive.examples import load
from supportive.service.insight import Insight

Headers = Callable[[str], dict[str, str]]


def board(client: TestClient, headers: Headers) -> dict[str, Any]:
    response = client.get("/api/board", headers=headers("screen"))
    assert response.status_code == 200
    data: dict[str, Any] = response.json()
    return data


def detail_text(body: dict[str, Any]) -> str:
    """The words of an error: the ``detail`` string, or a 422's messages (an array, as the schema says)."""
    detail = body["detail"]
    if isinstance(detail, list):
        assert all(set(item) == {"loc", "msg", "type"} for item in detail)
        return "; ".join(item["msg"] for item in detail)
    assert isinstance(detail, str)
    return detail


def node_named(data: dict[str, Any], name: str) -> dict[str, Any]:
    return next(n for n in data["nodes"] if n["name"] == name)


def test_the_board_is_the_chairs_tree(client: TestClient, headers: Headers) -> None:
    data = board(client, headers)
    assert data["task"] == "ikea-chair" and data["version"] == 0
    root = data["nodes"][0]
    assert root["id"] == "n0" and root["parent"] is None and root["name"] == "Assemble chair"
    assert sum(n["kind"] == "action" for n in data["nodes"]) == 24
    assert node_named(data, "Attach seat")["lead_only"]
    me = client.get("/api/me", headers=headers("robot")).json()
    assert me == {"id": "robot", "kind": "robot", "role": "assistant"}
    assert [a["id"] for a in client.get("/api/agents", headers=headers("bob")).json()] == [
        "alice",
        "bob",
        "robot",
        "screen",
    ]


def test_claiming_claims_the_subtree_and_conflicts_are_refused(client: TestClient, headers: Headers) -> None:
    frame = node_named(board(client, headers), "Build frame")["id"]
    response = client.post(f"/api/nodes/{frame}/claim", headers=headers("robot"))
    assert response.status_code == 200
    data = response.json()["board"]
    owned = {n["id"] for n in data["nodes"] if n["owner"] == "robot"}
    assert frame in owned and len(owned) > 5 and data["version"] == 1
    child = node_named(data, "pick up the left side frame")["id"]
    for agent, node in (("alice", frame), ("alice", child), ("alice", "n0")):
        refused = client.post(f"/api/nodes/{node}/claim", headers=headers(agent))
        assert refused.status_code == 409 and "claimed by robot" in refused.json()["detail"]
    assert board(client, headers)["version"] == 1
    released = client.post(f"/api/nodes/{frame}/release", headers=headers("robot"))
    assert released.status_code == 200 and not any(n["owner"] for n in released.json()["board"]["nodes"])
    assert client.post(f"/api/nodes/{frame}/release", headers=headers("robot")).status_code == 409


def test_completion_waits_for_prerequisites_and_propagates(client: TestClient, headers: Headers) -> None:
    data = board(client, headers)
    pegs = node_named(data, "Add left pegs")
    assert client.post(f"/api/nodes/{pegs['parent']}/claim", headers=headers("alice")).status_code == 200
    left = pegs["parent"]
    chain = [n for n in data["nodes"] if n["parent"] == left]
    first, second = chain[0]["id"], chain[1]["id"]
    early = client.post(f"/api/nodes/{second}/complete", headers=headers("alice"))
    assert early.status_code == 409 and "must wait for" in early.json()["detail"]
    assert (
        client.post(
            f"/api/nodes/{first}/progress", headers=headers("alice"), json={"progress": 0.5}
        ).status_code
        == 200
    )
    assert client.post(f"/api/nodes/{first}/complete", headers=headers("alice")).status_code == 200
    assert client.post(f"/api/nodes/{second}/complete", headers=headers("alice")).status_code == 200
    for peg in pegs["children"]:
        assert client.post(f"/api/nodes/{peg}/complete", headers=headers("alice")).status_code == 200
    after = board(client, headers)
    assert {n["id"]: n["done"] for n in after["nodes"]}[left] is True
    assert node_named(after, "Add left pegs")["done"] and not after["nodes"][0]["done"]
    again = client.post(f"/api/nodes/{first}/complete", headers=headers("alice"))
    assert again.status_code == 409 and "already done" in again.json()["detail"]
    assert client.post(f"/api/nodes/{left}/claim", headers=headers("bob")).status_code == 409


def test_asymmetric_authority(client: TestClient, headers: Headers) -> None:
    data = board(client, headers)
    seat = node_named(data, "Attach seat")["id"]
    assistant = client.post(f"/api/nodes/{seat}/claim", headers=headers("robot"))
    assert assistant.status_code == 403 and "reserved for leads" in assistant.json()["detail"]
    assert (
        client.post("/api/nodes/n0/claim", headers=headers("robot")).status_code == 403
    )  # contains the seat
    for leaf in (n for n in data["nodes"] if n["parent"] == seat):  # inside the seat: its ancestor is lead-only
        inside = client.post(f"/api/nodes/{leaf['id']}/claim", headers=headers("robot"))
        assert inside.status_code == 403 and "reserved for leads" in inside.json()["detail"]
    observer = client.post(f"/api/nodes/{seat}/claim", headers=headers("screen"))
    assert observer.status_code == 403 and "observers" in observer.json()["detail"]
    assert client.post(f"/api/nodes/{seat}/claim", headers=headers("alice")).status_code == 200
    assert board(client, headers)["version"] == 1


@pytest.mark.parametrize(
    ("request_args", "status", "detail"),
    [
        ({"method": "POST", "url": "/api/nodes/n1/claim"}, 401, "missing token"),
        (
            {"method": "POST", "url": "/api/nodes/n1/claim", "headers": {"Authorization": "Bearer nope"}},
            401,
            "unknown token",
        ),
        ({"method": "POST", "url": "/api/nodes/n999/claim", "agent": "alice"}, 404, "no subtask 'n999'"),
        ({"method": "POST", "url": "/api/nodes/x1/claim", "agent": "alice"}, 422, "node"),
        (
            {
                "method": "POST",
                "url": "/api/nodes/n5/progress",
                "agent": "alice",
                "content": b"{bad",
                "json_header": True,
            },
            400,
            "not valid JSON",
        ),
        (
            {"method": "POST", "url": "/api/nodes/n5/progress", "agent": "alice", "json": {"progress": 2}},
            422,
            "progress",
        ),
        (
            {
                "method": "POST",
                "url": "/api/nodes/n5/progress",
                "agent": "alice",
                "json": {"progress": 0.1, "x": 1},
            },
            422,
            "unknown field",
        ),
        (
            {"method": "POST", "url": "/api/nodes/n5/progress", "agent": "alice", "json": {}},
            422,
            "missing field 'progress'",
        ),
        (
            {"method": "POST", "url": "/api/nodes/n5/progress", "agent": "alice", "json": {"progress": 0.1}},
            409,
            "not claimed by alice",
        ),
        ({"method": "POST", "url": "/api/nodes/n1/complete", "agent": "alice"}, 409, "not a single action"),
        (
            {
                "method": "POST",
                "url": "/api/nodes/n5/progress",
                "agent": "alice",
                "content": b"[" * 70_000,
                "json_header": True,
            },
            413,
            "larger than",
        ),
    ],
)
def test_bad_requests_are_refused_and_change_nothing(
    client: TestClient, headers: Headers, request_args: dict[str, Any], status: int, detail: str
) -> None:
    args = dict(request_args)
    agent = args.pop("agent", None)
    extra = args.pop("headers", {})
    if args.pop("json_header", False):
        extra = {**extra, "Content-Type": "application/json"}
    before = board(client, headers)
    response = client.request(**args, headers={**(headers(agent) if agent else {}), **extra})
    assert response.status_code == status, response.text
    assert detail in detail_text(response.json())
    assert board(client, headers) == before


def test_the_event_log_replays_to_the_board(client: TestClient, headers: Headers) -> None:
    from supportive.social.board import TaskBoard

    frame = node_named(board(client, headers), "Build frame")["id"]
    for op, agent in (("claim", "robot"), ("release", "robot"), ("claim", "bob")):
        assert client.post(f"/api/nodes/{frame}/{op}", headers=headers(agent)).status_code == 200
    events = client.get("/api/events", headers=headers("screen")).json()
    assert [(e["seq"], e["op"], e["agent"]) for e in events] == [
        (1, "claim", "robot"),
        (2, "release", "robot"),
        (3, "claim", "bob"),
    ]
    assert client.get("/api/events?after=2", headers=headers("screen")).json()[0]["seq"] == 3
    roles = {a["id"]: a["role"] for a in client.get("/api/agents", headers=headers("screen")).json()}
    state = client.app.state.service  # type: ignore[attr-defined]
    replayed = state.store.initial()
    for e in events:
        replayed = replayed.apply(e["op"], e["node"], e["agent"], roles[e["agent"]], e["progress"])
    current = board(client, headers)
    assert {"version": current["version"], **replayed.as_dict()} == current
    assert isinstance(replayed, TaskBoard)


def test_every_change_is_pushed_over_the_websocket(client: TestClient, headers: Headers) -> None:
    with client.websocket_connect("/api/ws?token=tok-screen") as socket:
        first = socket.receive_json()
        assert first["type"] == "snapshot" and first["board"]["version"] == 0
        assert client.post("/api/nodes/n1/claim", headers=headers("robot")).status_code == 200
        pushed = socket.receive_json()
        assert (
            pushed["type"] == "event" and pushed["event"]["op"] == "claim" and pushed["board"]["version"] == 1
        )
        assert pushed["board"]["nodes"][1]["owner"] == "robot"


def test_websockets_need_a_token(client: TestClient) -> None:
    from starlette.websockets import WebSocketDisconnect

    with (
        pytest.raises(WebSocketDisconnect) as refused,
        client.websocket_connect("/api/ws?token=nope") as socket,
    ):
        socket.receive_json()
    assert refused.value.code == 4401


def test_docs_and_page_are_served(client: TestClient) -> None:
    schema = client.get("/openapi.json").json()
    assert "/api/nodes/{node}/claim" in schema["paths"]
    for docs in ("/docs", "/redoc"):  # their scripts are served here: nothing from a CDN
        html = client.get(docs)
        assert html.status_code == 200 and "cdn" not in html.text.lower() and "http" not in html.text.lower()
        scripts = re.findall(r'src="([^"]+\.js)"', html.text)
        assert scripts and all(client.get(src).status_code == 200 for src in scripts)
    page = client.get("/")
    assert page.status_code == 200 and "task board" in page.text
    assert client.get("/static/app.js").status_code == 200


def test_insight_suggests_behaviors_and_follows_observations(client: TestClient, headers: Headers) -> None:
    first = client.get("/api/insight", headers=headers("screen")).json()
    assert first["inference"] is True and first["belief"] is None
    assert "hand-hex-key" not in {b["name"] for b in first["behaviors"]}  # the bolts have not begun
    seen = client.post("/api/observations", headers=headers("alice"), json={"events": ["hand-left_frame"]})
    assert seen.status_code == 200 and seen.json()["subgoals"][0][0].startswith("get_left_frame")
    belief = client.get("/api/insight", headers=headers("screen")).json()["belief"]
    assert belief[0]["name"].startswith("get_left_frame") and 0 < belief[0]["probability"] <= 1
    assert client.post("/api/observations", headers=headers("screen"), json={"events": []}).status_code == 403
    assert (
        client.post("/api/observations", headers=headers("alice"), json={"events": [""]}).status_code == 422
    )


def test_insight_tells_the_belief_in_words(client: TestClient, headers: Headers) -> None:
    """The goal view: likely subtasks by name, current and next actions by their text (never a bare id)."""
    assert client.get("/api/insight", headers=headers("screen")).json()["goal"] is None
    for events in (["hand-left_frame"], ["hand-left_frame", "left_frame-table"]):
        client.post("/api/observations", headers=headers("alice"), json={"events": events})
    insight = client.get("/api/insight", headers=headers("screen")).json()
    goal, belief = insight["goal"], insight["belief"]
    texts = load("ikea-chair").texts()
    assert goal["step"] == 2
    assert [e["action"] for e in goal["current"]] == [b["name"] for b in belief]
    for entry in goal["current"] + goal["next"]:
        assert entry["text"] == texts[entry["action"]] and 0 <= entry["probability"] <= 1
    assert goal["current"][0]["text"] == "stand the left side frame on the table"
    assert goal["subtasks"][0]["name"] == "Prepare left frame"
    assert [step["step"] for step in goal["recent"]] == [1, 2]
    assert goal["recent"][-1]["text"] == "stand the left side frame on the table"


def test_the_goal_view_flags_what_the_model_calls_off_script() -> None:
    """The tracker's probability that the step was off-script reaches the page as ``off_script`` (True from
    the mistake detector's default threshold on, None when the summary has none; ``surprise`` is shown, not used to flag);
    repeated actions keep their occurrence in words."""
    insight = Insight(load("ikea-chair"))
    base = {"step": 3, "subgoals": [["get_seat#2", 0.5]], "subtasks": [], "next": []}
    for extra, flagged in (
        ({}, None),
        ({"surprise": 9.5}, None),
        ({"off_script": 0.8, "surprise": 7.0}, True),
        ({"off_script": 0.2, "surprise": 0.3}, False),
        ({"off_script": 0.5}, True),
    ):
        insight.latest = {**base, **extra}
        goal = insight.goal()
        assert goal is not None and goal["off_script"] is flagged and goal["surprise"] == extra.get("surprise")
        assert goal["current"][0]["text"] == "pick up the seat (#2)"


def contacts(action: str) -> list[str]:
    """The contact events the chair's task file declares for ``action``."""
    return [event for event, _ in next(a for a in load("ikea-chair").actions if a.id == action).observations]


def test_a_skipped_step_is_raised_with_help_the_robot_can_carry_out(client: TestClient, headers: Headers) -> None:
    """A demonstration of the chair with "stand the right side frame on the table" skipped: the step after it
    raises a missing-step mistake in the answer to its observation, on the WebSocket and in ``/api/insight``,
    with when it was raised, the reminder the robot says, and the skipped step's board node, which the robot
    can then claim; the steps before it raise nothing."""
    shown = list(load("ikea-chair").demonstrations[0].actions)
    skipped = shown.index("place_right_frame")
    with client.websocket_connect("/api/ws?token=tok-screen") as socket:
        assert socket.receive_json()["type"] == "snapshot"
        for action in shown[:skipped]:
            answer = client.post("/api/observations", headers=headers("alice"), json={"events": contacts(action)})
            assert answer.status_code == 200 and answer.json()["mistake"] is None
            assert socket.receive_json()["type"] == "belief"
        started = time.time()
        answer = client.post(
            "/api/observations", headers=headers("alice"), json={"events": contacts(shown[skipped + 1])}
        )
        mistake = answer.json()["mistake"]
        assert socket.receive_json()["type"] == "belief"
        pushed = socket.receive_json()
    assert pushed == {"type": "mistake", "mistake": mistake}
    assert mistake["kind"] == "missing" and mistake["skipped"] == ["place_right_frame"]
    assert mistake["action"] == shown[skipped + 1] and started <= mistake["raised"] <= time.time()
    assert mistake["help"]["category"] == "enhancing awareness"
    assert "standing the right side frame on the table" in mistake["help"]["say"]
    insight = client.get("/api/insight", headers=headers("screen")).json()
    assert insight["mistakes"] == [mistake]
    nodes = {n["id"]: n for n in board(client, headers)["nodes"]}
    assert [nodes[i]["action"] for i in mistake["nodes"]] == ["place_right_frame"]
    (node,) = mistake["nodes"]
    assert client.post(f"/api/nodes/{node}/claim", headers=headers("robot")).status_code == 200
    assert board(client, headers)["nodes"][int(node[1:])]["owner"] == "robot"


def test_suggestions_follow_the_board(client: TestClient, headers: Headers) -> None:
    data = board(client, headers)
    leaves = [n for n in data["nodes"] if n["kind"] == "action"]
    for leaf in leaves[:12]:  # the whole frame: both side frames, pegs, both rails
        assert client.post(f"/api/nodes/{leaf['id']}/claim", headers=headers("alice")).status_code == 200
        assert client.post(f"/api/nodes/{leaf['id']}/complete", headers=headers("alice")).status_code == 200
    names = {b["name"] for b in client.get("/api/insight", headers=headers("screen")).json()["behaviors"]}
    assert "hand-hex-key" in names or "point-next-bolt" in names


def test_hands_make_social_force(client: TestClient, headers: Headers) -> None:
    for i in range(5):
        response = client.post(
            "/api/hands", headers=headers("alice"), json={"x": 0.2 + 0.05 * i, "y": 0.3, "t": 0.1 * i}
        )
        assert response.status_code == 200
    social = client.get("/api/social?nx=10&ny=4", headers=headers("screen")).json()
    alice = next(a for a in social["agents"] if a["id"] == "alice")
    assert alice["hand"] == [0.4, 0.3] and alice["ellipse"]["center"][0] > 0.4  # the centre leads the hand
    assert abs(alice["ellipse"]["angle"]) < 1e-6  # elongated along the motion
    assert len(social["field"]["values"]) == 40 and max(social["field"]["values"]) > 0
    assert social["workspace"] == [1.83, 0.762]
    without = client.get("/api/social?nx=10&ny=4&exclude=alice", headers=headers("robot")).json()
    assert max(without["field"]["values"]) == 0
    backwards = client.post("/api/hands", headers=headers("alice"), json={"x": 0.1, "y": 0.1, "t": 0.0})
    assert backwards.status_code == 409 and "before the latest" in backwards.json()["detail"]
    assert client.post("/api/hands", headers=headers("screen"), json={"x": 0.1, "y": 0.1}).status_code == 403
    bad = client.post(
        "/api/hands",
        headers={**headers("bob"), "Content-Type": "application/json"},
        content=b'{"x": 1e999, "y": 0}',
    )
    assert bad.status_code == 422


def test_workbench_readings_follow_the_hand(tmp_path: Any, headers: Headers) -> None:
    from supportive.examples import path as example_path
    from supportive.io.taskfile import parse_task_file
    from supportive.service.app import create_app
    from supportive.service.settings import ServiceSettings, board_of, parse_agent

    spec = parse_task_file(example_path("workbench-blocks"))
    settings = ServiceSettings(
        f"sqlite:///{tmp_path / 'w.db'}",
        board_of(spec),
        (parse_agent("alice:human:lead:tok-alice"), parse_agent("screen:human:observer:tok-screen")),
        spec,
    )
    with TestClient(create_app(settings)) as workbench:
        for i in range(4):  # the hand closes in on the red block
            workbench.post(
                "/api/hands", headers=headers("alice"), json={"x": 1.2 + 0.05 * i, "y": 0.3, "t": 0.1 * i}
            )
        readings = {
            r["action"]: r["reading"]
            for r in workbench.get("/api/social", headers=headers("screen")).json()["readings"]
        }
    assert readings["pick_red"] > 0.2 and readings["pick_red"] == max(readings.values()) and readings["locate_blue"] == 0.0
