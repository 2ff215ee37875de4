"""What a board service is made of: its database, its board, its agents and limits."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import cast

from supportive.errors import InvalidValueError, ServiceError
from supportive.io.values import check_id
from supportive.learning.learner import learn
from supportive.service.agents import AgentKind, AgentSpec, check_agent_name
from supportive.service.tables import AGENT_NAME_LENGTH
from supportive.social.board import ROLES, TaskBoard
from supportive.tasks.htn import CliqueNode
from supportive.tasks.spec import TaskSpec

__all__ = ["AGENT_NAME_LENGTH", "DEFAULT_AGENTS", "ServiceSettings", "board_of", "default_agents", "parse_agent"]


DEFAULT_AGENTS = ("alice:human:lead", "robot:robot:assistant", "screen:human:observer")
"""The agents a new board starts with unless told otherwise: a human lead, a robot assistant, a screen."""


@dataclass(frozen=True)
class ServiceSettings:
    """A board service.

    Attributes:
        database: SQLAlchemy URL (``sqlite:///board.db``, ``postgresql+psycopg://user@127.0.0.1/db``).
        board: The board to create on first use; at a later start, its lead-only marks are the board's
            (the task's structure must be the same: :mod:`supportive.service.reconcile`).
        agents: The agents asked for, which the board is brought to at every start
            (:func:`~supportive.service.agents.set_up_agents`): those it does not have are added, each with a
            token (the one given, else a new one, shown once); those it has take the role given (and must keep
            their kind); tokens from ``serve`` no longer given are revoked. Empty: a board without agents gets
            :data:`DEFAULT_AGENTS`, a board with agents keeps them.
        spec: The task file, when the board came from one (behaviors, observations, keyframes).
        max_body: The largest request body accepted, bytes.
        workspace: The workbench's width and depth (metres) that hand positions and the force field live in
            (default: the thesis's 1.83 m × 0.762 m Collaborative Workbench).
        client_timeout: Seconds a client has to send a request's head, and then its body
            (:mod:`supportive.service.serving`).
        token_recheck: Seconds between checks that an open WebSocket's token still works (one revoked while
            the socket is open is closed with 4401 within this time; every HTTP request is checked anyway).
    """

    database: str
    board: TaskBoard
    agents: tuple[AgentSpec, ...]
    spec: TaskSpec | None = None
    max_body: int = 64 * 1024
    workspace: tuple[float, float] = (1.83, 0.762)
    client_timeout: float = 10.0
    token_recheck: float = 1.0
    static: Path = field(default_factory=lambda: Path(__file__).parent / "static")


def board_of(spec: TaskSpec, lead_only: Sequence[str] = ()) -> TaskBoard:
    """The board of a task: its ground-truth structure when the file has one, else the hierarchy learned from
    its demonstrations (a partial hierarchy's top-level parts under one clique).

    Raises:
        SupportiveError: for a task with neither a structure nor demonstrations.
    """
    if spec.structure is not None:
        root = spec.structure
    elif spec.demonstrations:
        htn = learn(spec).htn_
        root = htn.roots[0] if htn.complete else CliqueNode(tuple(htn.roots), name=spec.name)
    else:
        raise ServiceError(f"task {spec.name!r} has no structure and no demonstrations to learn one from")
    return TaskBoard.from_node(spec.name, root, spec.texts(), lead_only)


def default_agents() -> tuple[AgentSpec, ...]:
    """:data:`DEFAULT_AGENTS`, parsed (without tokens: each is drawn when the agent is made)."""
    return tuple(parse_agent(text) for text in DEFAULT_AGENTS)


def parse_agent(text: str) -> AgentSpec:
    """``name:kind:role[:token]`` (kind human or robot; role lead, assistant or observer); without a token, one
    is drawn at random when the agent is made (and only then).

    Raises:
        SupportiveError: for text of another shape.
    """
    parts = text.split(":")
    if (
        len(parts) not in (3, 4)
        or not parts[0]
        or parts[1] not in ("human", "robot")
        or parts[2] not in ROLES
    ):
        raise InvalidValueError(
            f"agent {text!r}: expected name:kind:role[:token], kind human or robot, role {', '.join(ROLES)}"
        )
    check_agent_name(parts[0])
    if len(parts) == 4 and parts[3]:
        try:
            check_id(parts[3], what="a token")
        except ValueError as exc:
            raise InvalidValueError(f"agent {parts[0]!r}: {exc}") from None
    token = parts[3] if len(parts) == 4 and parts[3] else None
    return AgentSpec(parts[0], cast(AgentKind, parts[1]), parts[2], token)
