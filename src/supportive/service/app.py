"""The board service (§3.4.3): a FastAPI app that people and robots share a task tree through.

``create_app(settings)`` builds it: the JSON API under ``/api`` (agents authenticate with ``Authorization:
Bearer <token>``; a WebSocket at ``/api/ws?token=…`` pushes every change), the web page at ``/``, OpenAPI docs
at ``/docs`` and ``/redoc`` (their scripts served by the app itself, from the fastapi-offline package: no CDN).
Errors are JSON ``{"detail": "…"}`` with a 4xx status: 400 malformed, 401 no or wrong token, 403 not allowed
for the agent's role, 404 unknown subtask, 408 a body too slow, 409 in conflict with the board, 413 too large;
422 (a field out of range or unknown) has FastAPI's ``{"detail": [{"loc", "msg", "type"}]}``, as the OpenAPI
schema says.
"""

from __future__ import annotations

import asyncio
import json
import logging
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse
from fastapi.staticfiles import StaticFiles
from fastapi_offline import FastAPIOffline
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from supportive.errors import BoardError
from supportive.service.hub import Hub
from supportive.service.routes import board, insight, live, social
from supportive.service.routes.social import hand_bounds
from supportive.service.schemas import ErrorOut
from supportive.service.settings import ServiceSettings, default_agents
from supportive.service.state import ServiceState
from supportive.service.statuses import board_status
from supportive.service.store import BoardStore

__all__ = ["create_app"]

_log = logging.getLogger("supportive.service")


class _LimitBody:
    """ASGI middleware: read a request's whole body first, refusing one larger than ``limit`` bytes with 413
    (declared or chunked) and one that does not arrive within ``timeout`` seconds with 408; the app then gets
    the body at once."""

    def __init__(self, app: ASGIApp, limit: int, timeout: float) -> None:
        self.app = app
        self.limit = limit
        self.timeout = timeout

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = dict(scope.get("headers", [])).get(b"content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.limit:
            await _refuse(send, 413, f"request body larger than {self.limit} bytes")
            return
        body = bytearray()
        try:
            async with asyncio.timeout(self.timeout):
                while True:
                    message = await receive()
                    if message["type"] != "http.request":  # the client went away
                        return
                    body += message.get("body", b"")
                    if len(body) > self.limit:
                        await _refuse(send, 413, f"request body larger than {self.limit} bytes")
                        return
                    if not message.get("more_body", False):
                        break
        except TimeoutError:
            await _refuse(send, 408, f"the request body did not arrive within {self.timeout:g} s")
            return
        delivered = False

        async def replay() -> Message:
            nonlocal delivered
            if not delivered:
                delivered = True
                return {"type": "http.request", "body": bytes(body), "more_body": False}
            return await receive()  # after the body: wait for the disconnect

        await self.app(scope, replay, send)


async def _refuse(send: Send, status: int, detail: str) -> None:
    body = json.dumps({"detail": detail}).encode()
    await send(
        {
            "type": "http.response.start",
            "status": status,
            "headers": [
                (b"content-type", b"application/json"),
                (b"content-length", str(len(body)).encode()),
                (b"connection", b"close"),
            ],
        }
    )
    await send({"type": "http.response.body", "body": body})


def create_app(settings: ServiceSettings) -> FastAPI:
    """The board service for ``settings`` (its database is created and the board added on first use; the
    agents asked for are set up: ``app.state.service.setup`` has the tokens made now, to show once).

    Raises:
        StoreError: when the database cannot be used.
        TokenError: for an agent or token the board refuses (an agent asked for with another role, a revoked
            token given again).
    """
    store = BoardStore(settings.database)
    try:
        _, setup = store.initialize(settings.board, settings.agents, default_agents())
    except BaseException:
        store.close()
        raise
    for change in setup.changes:  # the command line and the database differed: say what this start changed
        _log.warning("board %s: %s", store.shown_url, change)

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        yield
        store.close()

    app = FastAPIOffline(
        title="supportive task board",
        summary="A shared task tree that people and robots claim subtasks from (thesis §3.4.3).",
        version="1",
        lifespan=lifespan,
        responses={
            status: {"model": ErrorOut, "description": description}
            for status, description in (
                (400, "malformed request"),
                (401, "missing or unknown token"),
                (403, "not allowed for the agent's role"),
                (404, "no such subtask"),
                (408, "the request body was too slow"),
                (409, "in conflict with the board"),
                (413, "request body too large"),
            )
        },
    )
    app.state.service = ServiceState(settings, store, Hub(), setup)
    app.add_middleware(_LimitBody, limit=settings.max_body, timeout=settings.client_timeout)

    @app.exception_handler(BoardError)
    async def _board_error(request: Request, exc: BoardError) -> JSONResponse:
        return JSONResponse({"detail": exc.message}, status_code=board_status(exc))

    @app.exception_handler(RequestValidationError)
    async def _invalid(request: Request, exc: RequestValidationError) -> JSONResponse:
        if _validation_status(exc) == 400:
            return JSONResponse({"detail": "the body is not valid JSON"}, status_code=400)
        return JSONResponse({"detail": _validation_details(exc)}, status_code=422)

    app.include_router(board.router)
    app.include_router(live.router)
    app.include_router(insight.router)
    app.include_router(social.router)
    app.mount("/static", StaticFiles(directory=settings.static), name="static")
    app.openapi = lambda: _with_workspace(app, settings.workspace)  # type: ignore[method-assign]

    @app.get("/", include_in_schema=False)
    async def _index() -> FileResponse:
        return FileResponse(settings.static / "index.html")

    @app.get("/favicon.ico", include_in_schema=False)
    async def _icon() -> FileResponse:
        return FileResponse(settings.static / "favicon.ico", media_type="image/vnd.microsoft.icon")

    return app


def _with_workspace(app: FastAPI, workspace: tuple[float, float]) -> dict[str, Any]:
    """The OpenAPI document, with the bounds this board puts on a hand's ``x`` and ``y`` (its workspace and
    the reach around it, :func:`~supportive.service.routes.social.hand_bounds`), made once."""
    if app.openapi_schema is None:
        schema = FastAPI.openapi(app)
        hand = schema["components"]["schemas"]["HandIn"]["properties"]
        for axis, (low, high) in zip(("x", "y"), hand_bounds(workspace), strict=True):
            hand[axis].update(minimum=low, maximum=high)
        app.openapi_schema = schema
    return app.openapi_schema


def _validation_status(exc: RequestValidationError) -> int:
    return 400 if any(error.get("type") == "json_invalid" for error in exc.errors()) else 422


def _validation_details(exc: RequestValidationError) -> list[dict[str, Any]]:
    """FastAPI's 422 ``detail`` (the OpenAPI schema's array of ``{loc, msg, type}``), each ``msg`` one clear
    sentence naming the field."""
    details = []
    for error in exc.errors():
        where = ".".join(str(p) for p in error.get("loc", ()) if p != "body")
        kind = str(error.get("type", "value_error"))
        if kind == "extra_forbidden":
            message = f"unknown field {where!r}"
        elif kind == "string_pattern_mismatch" and tuple(error.get("loc", ())) == ("path", "node"):
            message = "node: a subtask's id is n and a number of at most six digits, like n3 (GET /api/board lists them)"
        elif kind == "missing":
            message = f"missing field {where!r}"
        else:
            message = f"{where or 'body'}: {error.get('msg', 'invalid')}"
        details.append({"loc": [str(p) if not isinstance(p, int) else p for p in error.get("loc", ())], "msg": message, "type": kind})
    return details
