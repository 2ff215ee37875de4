"""The ROS example client (examples/ros/board_client.py, HTTP only) run as a program against a real board
server on 127.0.0.1: completed actions, hand positions, contact events, and following the events."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx
from tests.service.conftest import TOKENS

CLIENT = Path(__file__).resolve().parents[2] / "examples" / "ros" / "board_client.py"


def run(url: str, agent: str, *args: str) -> subprocess.CompletedProcess[str]:
    command = [sys.executable, str(CLIENT), "--url", url, "--token", TOKENS[agent], *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=60)


def test_the_example_client_drives_a_real_board(
    tmp_path: Path, server_factory: Callable[..., Any], headers: Callable[[str], dict[str, str]]
) -> None:
    server = server_factory(f"sqlite:///{tmp_path / 'board.db'}")
    done = run(server.url, "robot", "complete", "get_left_frame", "place_left_frame")
    assert done.returncode == 0, done.stderr
    events = [json.loads(line) for line in done.stdout.splitlines()]
    assert [(e["op"], e["agent"]) for e in events] == [("complete", "robot"), ("complete", "robot")]
    board = httpx.get(f"{server.url}/api/board", headers=headers("screen"), timeout=30).json()
    finished = {n["action"] for n in board["nodes"] if n["done"] and n["action"]}
    assert finished == {"get_left_frame", "place_left_frame"}

    refused = run(server.url, "robot", "complete", "place_right_frame")
    assert refused.returncode == 1 and "refused: 409" in refused.stderr and "must wait for" in refused.stderr

    for t, x in ((1.0, 0.40), (1.1, 0.45)):
        moved = run(server.url, "alice", "hand", str(x), "0.3", "--t", str(t))
        assert moved.returncode == 0 and json.loads(moved.stdout) == {"agent": "alice", "t": t}
    social = httpx.get(f"{server.url}/api/social", headers=headers("screen"), timeout=30).json()
    assert next(a for a in social["agents"] if a["id"] == "alice")["hand"] == [0.45, 0.3]
    backwards = run(server.url, "alice", "hand", "0.5", "0.3", "--t", "0.5")
    assert backwards.returncode == 1 and "refused: 409" in backwards.stderr

    seen = run(server.url, "alice", "contacts", "hand-seat", "seat-left_frame")
    assert seen.returncode == 0 and json.loads(seen.stdout)
    insight = httpx.get(f"{server.url}/api/insight", headers=headers("screen"), timeout=30).json()
    assert insight["belief"] is not None

    log = httpx.get(f"{server.url}/api/events", headers=headers("screen"), timeout=30).json()
    followed = run(server.url, "screen", "follow", "--after", "0", "--count", str(len(log)))
    assert followed.returncode == 0
    assert [json.loads(line) for line in followed.stdout.splitlines()] == log
