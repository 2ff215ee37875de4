"""What a running board service holds: its settings, store, hub of subscribers, the agents' tokens, and the
authentication every route shares."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Annotated

from fastapi import Depends, Header, HTTPException, Query, Request, WebSocket

from supportive.service.hub import Hub
from supportive.service.insight import Insight
from supportive.service.settings import ServiceSettings
from supportive.service.store import Agent, BoardStore, token_hash
from supportive.social.field import ForceField

__all__ = ["ServiceState", "current_agent", "service", "socket_agent"]


@dataclass
class ServiceState:
    """The running service."""

    settings: ServiceSettings
    store: BoardStore
    hub: Hub
    tokens: dict[str, Agent] = field(default_factory=dict)
    insight: Insight = field(init=False)
    forces: ForceField = field(default_factory=ForceField)
    started: float = field(default_factory=time.monotonic)

    agents: dict[str, Agent] = field(init=False)

    def __post_init__(self) -> None:
        self.insight = Insight(self.settings.spec)
        by_id = {agent.id: agent for agent in self.store.agents()}
        self.agents = by_id
        self.tokens = {
            token_hash(spec.token): by_id[spec.id] for spec in self.settings.agents if spec.id in by_id
        }

    def agent(self, token: str) -> Agent | None:
        """The agent of a token (tokens of agents created by earlier runs are looked up in the database)."""
        digest = token_hash(token)
        agent = self.tokens.get(digest)
        if agent is None:
            agent = self.store.agent_for_token(token)
            if agent is not None:
                self.tokens[digest] = agent
        return agent


def service(request: Request) -> ServiceState:
    """The service of the request's app."""
    state: ServiceState = request.app.state.service
    return state


async def current_agent(request: Request, authorization: Annotated[str | None, Header()] = None) -> Agent:
    """The agent whose ``Authorization: Bearer <token>`` this is.

    Raises:
        HTTPException: 401 without a token or with an unknown one.
    """
    if authorization is None or not authorization.startswith("Bearer "):
        raise HTTPException(
            401,
            "missing token: send Authorization: Bearer <your agent's token>",
            headers={"WWW-Authenticate": "Bearer"},
        )
    agent = service(request).agent(authorization.removeprefix("Bearer ").strip())
    if agent is None:
        raise HTTPException(401, "unknown token", headers={"WWW-Authenticate": "Bearer"})
    return agent


async def socket_agent(websocket: WebSocket, token: Annotated[str, Query()] = "") -> Agent | None:
    """The agent of a WebSocket's ``?token=`` (None when it is missing or unknown)."""
    state: ServiceState = websocket.app.state.service
    return state.agent(token) if token else None


CurrentAgent = Annotated[Agent, Depends(current_agent)]
