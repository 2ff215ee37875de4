"""The board: read it, and claim, release, report progress on and complete its subtasks."""

from __future__ import annotations

import json
from typing import Annotated, Any

from fastapi import APIRouter, Body, Depends, Path, Query, Request, Response
from starlette.concurrency import run_in_threadpool

from supportive.service.agents import Agent
from supportive.service.schemas import ProgressIn
from supportive.service.state import current_agent, service

__all__ = ["router"]

router = APIRouter(prefix="/api", tags=["board"])

NodeId = Annotated[str, Path(pattern=r"^n[0-9]{1,6}$", description="A subtask's id, like n3.")]
Me = Annotated[Agent, Depends(current_agent)]
ERRORS: dict[int | str, dict[str, Any]] = {
    401: {"description": "missing or unknown token"},
    403: {"description": "not allowed for the agent's role"},
    404: {"description": "no such subtask"},
    409: {"description": "in conflict with the board (claimed by another, prerequisites not done, …)"},
}


@router.get("/board", summary="The task tree: every subtask with its owner, progress and completion")
async def read_board(request: Request, me: Me) -> dict[str, Any]:
    """The board and its version (the sequence number of the last acknowledged operation)."""
    board, version = await run_in_threadpool(service(request).store.board)
    return {"version": version, **board.as_dict()}


@router.get("/me", summary="The agent this token belongs to")
async def read_me(me: Me) -> dict[str, str]:
    """Your agent's id, kind and role."""
    return {"id": me.id, "kind": me.kind, "role": me.role}


@router.get("/agents", summary="Every agent of the board")
async def read_agents(request: Request, me: Me) -> list[dict[str, str]]:
    """Ids, kinds and roles (never tokens)."""
    agents = await run_in_threadpool(service(request).store.agents)
    return [{"id": a.id, "kind": a.kind, "role": a.role} for a in agents]


async def _operate(
    request: Request, me: Agent, op: str, node: str, progress: float | None = None
) -> Response:
    """Apply the operation, push it to subscribers, answer with the event and the board (JSON encoded once)."""
    state = service(request)
    board, event = await run_in_threadpool(state.store.apply, op, node, me, progress)
    message = {"event": event.as_dict(), "board": {"version": event.seq, **board.as_dict()}}
    state.hub.publish({"type": "event", **message})
    return Response(json.dumps(message), media_type="application/json")


@router.post("/nodes/{node}/claim", responses=ERRORS, summary="Claim a subtask (and everything under it)")
async def claim(request: Request, node: NodeId, me: Me) -> Response:
    """Refused when another agent owns it, something under it or above it, or it is done."""
    return await _operate(request, me, "claim", node)


@router.post("/nodes/{node}/release", responses=ERRORS, summary="Give a claimed subtask back")
async def release(request: Request, node: NodeId, me: Me) -> Response:
    """Its unfinished parts go back to the pool."""
    return await _operate(request, me, "release", node)


@router.post("/nodes/{node}/progress", responses=ERRORS, summary="Report progress on an action you own")
async def progress(request: Request, node: NodeId, me: Me, body: Annotated[ProgressIn, Body()]) -> Response:
    """``{"progress": 0.5}``."""
    return await _operate(request, me, "progress", node, body.progress)


@router.post("/nodes/{node}/complete", responses=ERRORS, summary="Complete an action you own")
async def complete(request: Request, node: NodeId, me: Me) -> Response:
    """Refused until its prerequisites are done; finished subtasks above it complete too."""
    return await _operate(request, me, "complete", node)


@router.get("/events", summary="The acknowledged operations, oldest first")
async def read_events(
    request: Request,
    me: Me,
    after: Annotated[int, Query(ge=0, le=2**63 - 1, description="Sequence number to start after.")] = 0,
    limit: Annotated[int, Query(ge=1, le=10_000, description="At most this many events.")] = 1000,
) -> list[dict[str, Any]]:
    """Operations with a sequence number above ``after`` (at most ``limit``, up to 10,000)."""
    events = await run_in_threadpool(service(request).store.events, after, limit)
    return [e.as_dict() for e in events]
