"""Real servers on 127.0.0.1 under concurrent load, on SQLite and PostgreSQL: racing claims never give a
subtask two owners, the acknowledged log replays to the final board, and a server killed with SIGKILL loses
nothing it acknowledged."""

from __future__ import annotations

import http.client
import json
import random
import threading
import time
from collections.abc import Callable
from typing import Any

import httpx

from supportive.social.board import TaskBoard

AGENTS = {"alice": "lead", "bob": "lead", "robot": "assistant", "screen": "observer"}


def replay(initial: TaskBoard, events: list[dict[str, Any]]) -> TaskBoard:
    """The board after the log; raises BoardError if the server acknowledged something the board forbids."""
    board = initial
    for e in events:
        board = board.apply(e["op"], e["node"], e["agent"], AGENTS[e["agent"]], e["progress"])  # type: ignore[arg-type]
    return board


def fetch(url: str, headers: Callable[[str], dict[str, str]]) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    board = httpx.get(f"{url}/api/board", headers=headers("screen"), timeout=30).json()
    events = httpx.get(f"{url}/api/events?limit=10000", headers=headers("screen"), timeout=30).json()
    after = events[-1]["seq"] if events else 0
    while True:
        more = httpx.get(
            f"{url}/api/events?after={after}&limit=10000", headers=headers("screen"), timeout=30
        ).json()
        if not more:
            return board, events
        events += more
        after = more[-1]["seq"]


def initial_board(database: str) -> TaskBoard:
    from supportive.service.store import BoardStore

    store = BoardStore(database)
    try:
        return store.initial()
    finally:
        store.close()


def test_fifty_clients_racing_for_the_same_subtasks_never_make_two_owners(
    database: str, server_factory: Callable[..., Any], headers: Callable[[str], dict[str, str]]
) -> None:
    server = server_factory(database)
    board, _ = fetch(server.url, headers)
    contested = [n["id"] for n in board["nodes"] if n["parent"] in (None, "n0")][:4]
    contested += [n["id"] for n in board["nodes"] if n["kind"] == "action"][:4]
    wins: dict[str, list[str]] = {node: [] for node in contested}
    lock = threading.Lock()
    start = threading.Barrier(50)

    def racer(index: int) -> None:
        agent = ("alice", "bob", "robot")[index % 3]
        with httpx.Client(base_url=server.url, headers=headers(agent), timeout=30) as client:
            start.wait()
            for node in contested:
                if client.post(f"/api/nodes/{node}/claim").status_code == 200:
                    with lock:
                        wins[node].append(agent)

    threads = [threading.Thread(target=racer, args=(i,)) for i in range(50)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    final, events = fetch(server.url, headers)
    replayed = replay(initial_board(database), events)  # a double ownership would raise here
    assert {"version": final["version"], **replayed.as_dict()} == final
    owners = {n["id"]: n["owner"] for n in final["nodes"]}
    for node, agents in wins.items():
        assert len(set(agents)) <= 1  # only one agent ever won it (it may win again: claims are idempotent)
        if agents:
            assert owners[node] == agents[0]
    for node in final["nodes"]:  # ownership is consistent down every subtree
        for child in node["children"]:
            child_node = final["nodes"][int(child[1:])]
            if node["owner"] and not child_node["done"]:
                assert child_node["owner"] == node["owner"]


def test_ten_thousand_mixed_operations_replay_to_the_final_board(
    database: str, server_factory: Callable[..., Any], headers: Callable[[str], dict[str, str]]
) -> None:
    server = server_factory(database)
    board, _ = fetch(server.url, headers)
    nodes = [n["id"] for n in board["nodes"]]
    acknowledged: list[int] = []
    statuses: list[int] = []
    lock = threading.Lock()

    def worker(index: int) -> None:
        rng = random.Random(index)
        agent = ("alice", "bob", "robot", "screen")[index % 4]
        # The standard library's client, one kept-alive connection per thread: 10,000 requests from 20
        # threads cost httpx about as much CPU as the server takes to answer them.
        connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=60)
        try:
            for _ in range(500):
                op = rng.choice(("claim", "claim", "release", "progress", "complete", "complete"))
                node = rng.choice(nodes)
                body = json.dumps({"progress": round(rng.random(), 3)}) if op == "progress" else ""
                sent = {**headers(agent), "Content-Type": "application/json"} if body else headers(agent)
                connection.request("POST", f"/api/nodes/{node}/{op}", body=body, headers=sent)
                response = connection.getresponse()
                answer = response.read()
                with lock:
                    statuses.append(response.status)
                    if response.status == 200:
                        acknowledged.append(json.loads(answer)["event"]["seq"])
        finally:
            connection.close()

    threads = [threading.Thread(target=worker, args=(i,)) for i in range(20)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert len(statuses) == 10_000 and set(statuses) <= {200, 400, 403, 409}
    final, events = fetch(server.url, headers)
    assert sorted(acknowledged) == [e["seq"] for e in events] == list(range(1, len(events) + 1))
    replayed = replay(initial_board(database), events)
    assert {"version": final["version"], **replayed.as_dict()} == final
    assert final["version"] == len(acknowledged) > 100


def test_a_killed_server_loses_nothing_it_acknowledged(
    database: str, server_factory: Callable[..., Any], headers: Callable[[str], dict[str, str]]
) -> None:
    server = server_factory(database)
    board, _ = fetch(server.url, headers)
    nodes = [n["id"] for n in board["nodes"]]
    acknowledged: dict[int, tuple[str, str, str]] = {}
    lock = threading.Lock()
    stop = threading.Event()

    def worker(index: int) -> None:
        rng = random.Random(100 + index)
        agent = ("alice", "bob", "robot")[index % 3]
        with httpx.Client(base_url=server.url, headers=headers(agent), timeout=5) as client:
            while not stop.is_set():
                op, node = rng.choice(("claim", "release", "complete")), rng.choice(nodes)
                try:
                    response = client.post(f"/api/nodes/{node}/{op}")
                except httpx.HTTPError:
                    return  # the server is gone
                if response.status_code == 200:
                    event = response.json()["event"]
                    with lock:
                        acknowledged[event["seq"]] = (event["op"], event["node"], event["agent"])

    threads = [threading.Thread(target=worker, args=(i,)) for i in range(8)]
    for thread in threads:
        thread.start()
    deadline = time.monotonic() + 20
    while len(acknowledged) < 150 and time.monotonic() < deadline:
        time.sleep(0.05)
    server.kill()
    stop.set()
    for thread in threads:
        thread.join()
    assert len(acknowledged) >= 150
    again = server_factory(database, server.port)
    final, events = fetch(again.url, headers)
    logged = {e["seq"]: (e["op"], e["node"], e["agent"]) for e in events}
    assert all(logged.get(seq) == what for seq, what in acknowledged.items())
    replayed = replay(initial_board(database), events)
    assert {"version": final["version"], **replayed.as_dict()} == final


def test_a_real_server_refuses_bad_requests_without_changing_the_board(
    database: str, server_factory: Callable[..., Any], headers: Callable[[str], dict[str, str]]
) -> None:
    server = server_factory(database)
    before, _ = fetch(server.url, headers)
    with httpx.Client(base_url=server.url, timeout=30) as client:
        json_header = {**headers("alice"), "Content-Type": "application/json"}
        assert (
            client.post("/api/nodes/n5/progress", headers=json_header, content=b"{not json").status_code
            == 400
        )
        assert (
            client.post("/api/nodes/n1/claim", headers={"Authorization": "Bearer wrong"}).status_code == 401
        )
        assert client.post("/api/nodes/n404/claim", headers=headers("alice")).status_code == 404
        assert (
            client.post("/api/nodes/n5/progress", headers=json_header, content=b"0" * 200_000).status_code
            == 413
        )
        assert client.post("/api/nodes/n1/claim", headers=headers("screen")).status_code == 403
    after, events = fetch(server.url, headers)
    assert after == before and events == []
