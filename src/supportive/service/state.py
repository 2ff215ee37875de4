"""What a running board service holds: its settings, store, hub of subscribers, the agents, and the
authentication every route shares (a token is looked up in the database on every request, so one revoked by
``supportive tokens revoke`` in another process is refused at once)."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Annotated

from fastapi import Depends, HTTPException, Query, Request, Security, WebSocket
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from supportive.service.agents import Agent, AgentSetup
from supportive.service.hub import Hub
from supportive.service.insight import Insight
from supportive.service.settings import ServiceSettings
from supportive.service.store import BoardStore
from supportive.social.field import ForceField

__all__ = ["BEARER", "ServiceState", "current_agent", "service", "socket_agent"]


@dataclass
class ServiceState:
    """The running service."""

    settings: ServiceSettings
    store: BoardStore
    hub: Hub
    setup: AgentSetup
    insight: Insight = field(init=False)
    forces: ForceField = field(default_factory=ForceField)
    started: float = field(default_factory=time.monotonic)

    agents: dict[str, Agent] = field(init=False)

    def __post_init__(self) -> None:
        self.insight = Insight(self.settings.spec)
        self.agents = {agent.id: agent for agent in self.setup.agents}

    def agent(self, token: str) -> Agent | None:
        """The agent a token signs in as now, or None (unknown or revoked); asked of the database every time.
        An agent added while the service runs (``supportive tokens add NAME --kind … --role …``) is known from
        its first request on."""
        agent = self.store.agent_for_token(token)
        if agent is not None and agent.id not in self.agents:
            self.agents[agent.id] = agent
        return agent


def service(request: Request) -> ServiceState:
    """The service of the request's app."""
    state: ServiceState = request.app.state.service
    return state


BEARER = HTTPBearer(
    auto_error=False,
    scheme_name="token",
    description="An agent's token: `serve` prints it once when it is made; `supportive tokens add` makes more.",
)
"""The API's security scheme (the OpenAPI document declares it, so /docs can authorise with a token)."""


async def current_agent(
    request: Request, credentials: Annotated[HTTPAuthorizationCredentials | None, Security(BEARER)] = None
) -> Agent:
    """The agent whose ``Authorization: Bearer <token>`` this is.

    Raises:
        HTTPException: 401 without a token or with an unknown one.
    """
    if credentials is None:
        raise HTTPException(
            401,
            "missing token: send Authorization: Bearer <your agent's token>",
            headers={"WWW-Authenticate": "Bearer"},
        )
    agent = service(request).agent(credentials.credentials.strip())
    if agent is None:
        raise HTTPException(401, "unknown token", headers={"WWW-Authenticate": "Bearer"})
    return agent


async def socket_agent(websocket: WebSocket, token: Annotated[str, Query()] = "") -> Agent | None:
    """The agent of a WebSocket's ``?token=`` (None when it is missing or unknown)."""
    state: ServiceState = websocket.app.state.service
    return state.agent(token) if token else None


CurrentAgent = Annotated[Agent, Depends(current_agent)]
