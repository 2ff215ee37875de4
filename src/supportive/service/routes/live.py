"""Live updates: a WebSocket that sends the board, then every acknowledged change."""

from __future__ import annotations

import asyncio
import contextlib
from typing import Annotated, Any

from fastapi import APIRouter, Depends, WebSocket, WebSocketDisconnect
from starlette.concurrency import run_in_threadpool
from starlette.websockets import WebSocketState

from supportive.service.agents import Agent
from supportive.service.state import ServiceState, socket_agent

__all__ = ["router"]

router = APIRouter(prefix="/api", tags=["live"])


@router.websocket("/ws")
async def updates(websocket: WebSocket, agent: Annotated[Agent | None, Depends(socket_agent)]) -> None:
    """``/api/ws?token=…``: first ``{"type": "snapshot", "board": …}``, then ``{"type": "event", "event": …,
    "board": …}`` for every change. An unknown or revoked token is refused (close code 4401), and an open
    socket whose token is revoked is closed with 4401 within ``token_recheck`` seconds. The socket ends when
    the client goes, or falls too far behind (1013: reconnect)."""
    if agent is None:  # accepted first, so the client sees the close code (refused before, it gets HTTP 403)
        await websocket.accept()
        await websocket.close(code=4401, reason="missing or unknown token")
        return
    state: ServiceState = websocket.app.state.service
    await websocket.accept()
    queue = state.hub.subscribe()
    gone = asyncio.ensure_future(_until_closed(websocket))
    token = websocket.query_params.get("token", "")
    revoked = asyncio.ensure_future(_until_revoked(state, token))
    try:
        board, version = await run_in_threadpool(state.store.board)
        await websocket.send_json({"type": "snapshot", "board": {"version": version, **board.as_dict()}})
        while True:
            message = asyncio.ensure_future(queue.get())
            await asyncio.wait({message, gone, revoked}, return_when=asyncio.FIRST_COMPLETED)
            if not message.done():
                message.cancel()
                if revoked.done() and not gone.done():
                    await websocket.close(code=4401, reason="token revoked")
                return
            update: dict[str, Any] | None = message.result()
            if update is None:
                await websocket.close(code=1013, reason="too slow: reconnect")
                return
            await websocket.send_json(update)
    except WebSocketDisconnect:
        return
    finally:
        gone.cancel()
        revoked.cancel()
        state.hub.unsubscribe(queue)
        if websocket.client_state is WebSocketState.CONNECTED and websocket.application_state is WebSocketState.CONNECTED:
            with contextlib.suppress(WebSocketDisconnect, RuntimeError):  # the client may go meanwhile
                await websocket.close()


async def _until_revoked(state: ServiceState, token: str) -> None:
    """Return once ``token`` no longer works (asked of the database every ``token_recheck`` seconds)."""
    while True:
        await asyncio.sleep(state.settings.token_recheck)
        if await run_in_threadpool(state.agent, token) is None:
            return


async def _until_closed(websocket: WebSocket) -> None:
    """Read (and ignore) what the client sends until it disconnects."""
    with contextlib.suppress(WebSocketDisconnect, RuntimeError):
        while True:
            await websocket.receive_text()
