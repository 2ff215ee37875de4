"""Live updates: a WebSocket that sends the board, then every acknowledged change."""

from __future__ import annotations

import contextlib
from typing import Annotated

from fastapi import APIRouter, Depends, WebSocket, WebSocketDisconnect
from starlette.concurrency import run_in_threadpool

from supportive.service.state import ServiceState, socket_agent
from supportive.service.store import Agent

__all__ = ["router"]

router = APIRouter(prefix="/api", tags=["live"])


@router.websocket("/ws")
async def updates(websocket: WebSocket, agent: Annotated[Agent | None, Depends(socket_agent)]) -> None:
    """``/api/ws?token=…``: first ``{"type": "snapshot", "board": …}``, then ``{"type": "event", "event": …,
    "board": …}`` for every change. An unknown token is refused (close code 4401)."""
    if agent is None:
        await websocket.close(code=4401, reason="missing or unknown token")
        return
    state: ServiceState = websocket.app.state.service
    await websocket.accept()
    queue = state.hub.subscribe()
    try:
        board, version = await run_in_threadpool(state.store.board)
        await websocket.send_json({"type": "snapshot", "board": {"version": version, **board.as_dict()}})
        while True:
            message = await queue.get()
            if message is None:
                await websocket.close(code=1013, reason="too slow: reconnect")
                return
            await websocket.send_json(message)
    except WebSocketDisconnect:
        return
    finally:
        state.hub.unsubscribe(queue)
        with contextlib.suppress(RuntimeError):
            await websocket.close()
