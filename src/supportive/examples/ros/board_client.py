"""A robot's client of the task board, over its HTTP API only (Python's standard library, nothing else), to
copy into a ROS 2 node: report completed actions, hand positions and contact events, and follow the board's
events. docs/ros.md shows the rclpy node around it.

Run it against a board (``make serve`` prints the URL and tokens)::

    python examples/ros/board_client.py --url http://127.0.0.1:8000 --token TOKEN complete get_left_frame
    python examples/ros/board_client.py --url … --token … hand 0.42 0.31 --t 12.5
    python examples/ros/board_client.py --url … --token … contacts hand-seat seat-left_frame
    python examples/ros/board_client.py --url … --token … follow --after 0 --count 5

Each command prints the service's JSON answer (``follow``: one event per line). A refusal (the action is
claimed by someone else, its prerequisites are not done, …) prints the service's reason and exits with 1.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from typing import Any


class BoardRefused(Exception):
    """The board answered with an error: ``status`` and the service's ``detail``."""

    def __init__(self, status: int, detail: str) -> None:
        super().__init__(f"{status}: {detail}")
        self.status = status
        self.detail = detail


class TaskBoard:
    """One agent's view of a task board service.

    Args:
        url: The service, like ``http://127.0.0.1:8000``.
        token: The agent's token (``Authorization: Bearer`` on every request).
        timeout: Seconds to wait for an answer.
    """

    def __init__(self, url: str, token: str, timeout: float = 10.0) -> None:
        self.url = url.rstrip("/")
        self.token = token
        self.timeout = timeout

    def request(self, method: str, path: str, body: dict[str, Any] | None = None) -> Any:
        """One request; the decoded JSON answer.

        Raises:
            BoardRefused: for a 4xx or 5xx answer.
        """
        data = None if body is None else json.dumps(body).encode()
        headers = {"Authorization": f"Bearer {self.token}"}
        if data is not None:
            headers["Content-Type"] = "application/json"
        call = urllib.request.Request(f"{self.url}{path}", data=data, headers=headers, method=method)
        try:
            with urllib.request.urlopen(call, timeout=self.timeout) as answer:
                return json.loads(answer.read())
        except urllib.error.HTTPError as error:
            try:
                detail = json.loads(error.read()).get("detail", error.reason)
            except ValueError:
                detail = error.reason
            raise BoardRefused(error.code, str(detail)) from None

    def board(self) -> dict[str, Any]:
        """``GET /api/board``: every node with its owner, progress and completion."""
        answer: dict[str, Any] = self.request("GET", "/api/board")
        return answer

    def node_of(self, action: str) -> dict[str, Any]:
        """The first unfinished node that performs ``action``.

        Raises:
            BoardRefused: (404) when no unfinished node performs it.
        """
        for node in self.board()["nodes"]:
            if node["action"] == action and not node["done"]:
                return dict(node)
        raise BoardRefused(404, f"no unfinished subtask performs {action!r}")

    def complete(self, action: str) -> dict[str, Any]:
        """Report that this agent finished ``action``: claim its node unless it is ours already
        (``POST /api/nodes/{id}/claim``), then ``POST /api/nodes/{id}/complete``; the completion's event."""
        node = self.node_of(action)
        me = self.request("GET", "/api/me")["id"]
        if node["owner"] != me:
            self.request("POST", f"/api/nodes/{node['id']}/claim")
        answer: dict[str, Any] = self.request("POST", f"/api/nodes/{node['id']}/complete")
        return dict(answer["event"])

    def hand(self, x: float, y: float, t: float | None = None) -> dict[str, Any]:
        """``POST /api/hands``: where the hand (or end effector) is, metres on the workbench, at ``t`` seconds
        (default: the server's clock); times must go forwards."""
        body: dict[str, Any] = {"x": x, "y": y} | ({} if t is None else {"t": t})
        answer: dict[str, Any] = self.request("POST", "/api/hands", body)
        return answer

    def contacts(self, events: list[str]) -> dict[str, Any]:
        """``POST /api/observations``: the contact events that hold now; the belief after them."""
        answer: dict[str, Any] = self.request("POST", "/api/observations", {"events": events})
        return answer

    def events(self, after: int = 0, limit: int = 100) -> list[dict[str, Any]]:
        """``GET /api/events?after=N&limit=M``: acknowledged operations after sequence number ``after``."""
        answer: list[dict[str, Any]] = self.request("GET", f"/api/events?after={after}&limit={limit}")
        return answer

    def follow(self, after: int = 0, poll: float = 0.2) -> Iterator[dict[str, Any]]:
        """Every event after ``after``, as it comes (polling ``/api/events``; the WebSocket ``/api/ws`` pushes
        the same events without polling)."""
        while True:
            batch = self.events(after)
            for event in batch:
                after = event["seq"]
                yield event
            if not batch:
                time.sleep(poll)


def main(argv: list[str] | None = None) -> int:
    """The command line above; the exit status."""
    parser = argparse.ArgumentParser(description="A robot's client of the task board (HTTP only).")
    parser.add_argument("--url", required=True)
    parser.add_argument("--token", required=True)
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("complete").add_argument("actions", nargs="+")
    hand = commands.add_parser("hand")
    hand.add_argument("x", type=float)
    hand.add_argument("y", type=float)
    hand.add_argument("--t", type=float)
    commands.add_parser("contacts").add_argument("events", nargs="*")
    follow = commands.add_parser("follow")
    follow.add_argument("--after", type=int, default=0)
    follow.add_argument("--count", type=int, default=None, help="stop after this many events")
    args = parser.parse_args(argv)
    board = TaskBoard(args.url, args.token)
    try:
        if args.command == "complete":
            for action in args.actions:
                print(json.dumps(board.complete(action)))
        elif args.command == "hand":
            print(json.dumps(board.hand(args.x, args.y, args.t)))
        elif args.command == "contacts":
            print(json.dumps(board.contacts(args.events)))
        else:
            for seen, event in enumerate(board.follow(args.after), start=1):
                print(json.dumps(event), flush=True)
                if args.count is not None and seen >= args.count:
                    break
    except BoardRefused as refusal:
        print(f"board_client: refused: {refusal}", file=sys.stderr)
        return 1
    except urllib.error.URLError as error:
        print(f"board_client: cannot reach {args.url}: {error.reason}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
