"""The board service (§3.4.3): a FastAPI app that people and robots share a task tree through.

``create_app(settings)`` builds it: the JSON API under ``/api`` (agents authenticate with ``Authorization:
Bearer <token>``; a WebSocket at ``/api/ws?token=…`` pushes every change), the web page at ``/``, OpenAPI docs
at ``/docs`` and ``/redoc`` (their scripts served by the app itself, from the fastapi-offline package: no CDN). Errors are JSON ``{"detail": "…"}`` with a 4xx status: 400 malformed, 401 no or wrong token,
403 not allowed for the agent's role, 404 unknown subtask, 409 in conflict with the board, 413 too large,
422 a field out of range.
"""

from __future__ import annotations

import json
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from fastapi_offline import FastAPIOffline
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from supportive.service.hub import Hub
from supportive.service.routes import board, insight, live, social
from supportive.service.settings import ServiceSettings
from supportive.service.state import ServiceState
from supportive.service.store import BoardStore
from supportive.social.board import BoardError

__all__ = ["create_app"]


class _LimitBody:
    """ASGI middleware: refuse a request body larger than ``limit`` bytes with 413, before it is read whole."""

    def __init__(self, app: ASGIApp, limit: int) -> None:
        self.app = app
        self.limit = limit

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = dict(scope.get("headers", [])).get(b"content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.limit:
            await _too_large(send, self.limit)
            return
        seen = 0

        async def limited() -> Message:
            nonlocal seen
            message = await receive()
            if message["type"] == "http.request":
                seen += len(message.get("body", b""))
                if seen > self.limit:
                    raise _TooLarge
            return message

        try:
            await self.app(scope, limited, send)
        except _TooLarge:
            await _too_large(send, self.limit)


class _TooLarge(Exception):
    pass


async def _too_large(send: Send, limit: int) -> None:
    body = json.dumps({"detail": f"request body larger than {limit} bytes"}).encode()
    await send(
        {
            "type": "http.response.start",
            "status": 413,
            "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())],
        }
    )
    await send({"type": "http.response.body", "body": body})


def create_app(settings: ServiceSettings) -> FastAPI:
    """The board service for ``settings`` (its database is created and the board added on first use).

    Raises:
        StoreError: when the database cannot be used.
    """
    store = BoardStore(settings.database)
    store.initialize(settings.board, settings.agents)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        yield
        store.close()

    app = FastAPIOffline(
        title="supportive task board",
        summary="A shared task tree that people and robots claim subtasks from (thesis §3.4.3).",
        version="1",
        lifespan=lifespan,
    )
    app.state.service = ServiceState(settings, store, Hub())
    app.add_middleware(_LimitBody, limit=settings.max_body)

    @app.exception_handler(BoardError)
    async def _board_error(request: Request, exc: BoardError) -> JSONResponse:
        return JSONResponse({"detail": exc.message}, status_code=exc.status)

    @app.exception_handler(RequestValidationError)
    async def _invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        return JSONResponse({"detail": _validation_message(exc)}, status_code=_validation_status(exc))

    app.include_router(board.router)
    app.include_router(live.router)
    app.include_router(insight.router)
    app.include_router(social.router)
    app.mount("/static", StaticFiles(directory=settings.static), name="static")

    @app.get("/", include_in_schema=False)
    async def _index() -> FileResponse:
        return FileResponse(settings.static / "index.html")

    return app


def _validation_status(exc: RequestValidationError) -> int:
    return 400 if any(error.get("type") == "json_invalid" for error in exc.errors()) else 422


def _validation_message(exc: RequestValidationError) -> str:
    parts: list[str] = []
    for error in exc.errors()[:3]:
        where = ".".join(str(p) for p in error.get("loc", ()) if p != "body")
        kind = error.get("type")
        if kind == "json_invalid":
            parts.append("the body is not valid JSON")
        elif kind == "extra_forbidden":
            parts.append(f"unknown field {where!r}")
        elif kind == "missing":
            parts.append(f"missing field {where!r}")
        else:
            parts.append(f"{where or 'body'}: {error.get('msg', 'invalid')}")
    return "; ".join(parts)
