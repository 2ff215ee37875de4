"""Running the board service under uvicorn with what uvicorn leaves out: client timeouts and a clean stop.

* **Slow or idle clients.** uvicorn closes a kept-alive connection that stays idle (5 s) but waits forever for
  a request that never completes: a connection that sends nothing, or its request head a byte at a time, holds
  a slot for good. Here every request head must arrive within ``timeout`` seconds of the connection opening
  (or of the previous response), the body within ``timeout`` seconds of the head (:mod:`supportive.service.app`
  answers 408 otherwise), and a client that stops reading its response for ``3 × timeout`` seconds is cut off.
  WebSockets are pinged every 20 s and closed when a ping is not answered in 20 s (uvicorn's own).
* **SIGTERM** stops the service gracefully: no new connections, requests in flight finish (3 s at most; a
  request that reaches an idle kept-alive connection within :data:`DRAIN` seconds of the stop is answered too,
  with ``Connection: close``, rather than cut off),
  WebSockets are closed with 1012 (service restart), the store's writer commits what it was given, and the
  process exits with status 0 — a stop that was asked for is not a failure. Ctrl-C (SIGINT) does the same and
  ends with the usual 130.
"""

from __future__ import annotations

import asyncio
import signal
import socket
from types import FrameType
from typing import Any

import uvicorn
from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol

__all__ = ["DRAIN", "run"]

DRAIN = 0.5
"""Seconds an idle kept-alive connection stays open once a stop begins, to answer a request already on its
way (well within the 3 s grace period)."""


class _TimedHttp(HttpToolsProtocol):
    """uvicorn's HTTP protocol with a deadline for each request head and for a stalled reader."""

    head_timeout = 10.0

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._head_timer: asyncio.TimerHandle | None = None
        self._write_timer: asyncio.TimerHandle | None = None
        self._drain_timer: asyncio.TimerHandle | None = None
        self._draining = False

    def _arm(self) -> None:
        self._disarm()
        self._head_timer = self.loop.call_later(self.head_timeout, self._too_slow)

    def _disarm(self) -> None:
        if self._head_timer is not None:
            self._head_timer.cancel()
            self._head_timer = None

    def _too_slow(self) -> None:
        self._head_timer = None
        if not self.transport.is_closing() and (self.cycle is None or self.cycle.response_complete):
            self.transport.close()

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        self._arm()

    def on_headers_complete(self) -> None:
        self._disarm()
        super().on_headers_complete()
        if self._draining and self.cycle is not None:
            self.cycle.keep_alive = False  # the service is stopping: this is the connection's last request

    def on_response_complete(self) -> None:
        super().on_response_complete()
        if not self.transport.is_closing():
            self._arm()  # the next request's head has the same deadline

    def pause_writing(self) -> None:
        super().pause_writing()
        if self._write_timer is None:
            self._write_timer = self.loop.call_later(3 * self.head_timeout, self.transport.abort)

    def resume_writing(self) -> None:
        super().resume_writing()
        if self._write_timer is not None:
            self._write_timer.cancel()
            self._write_timer = None

    def shutdown(self) -> None:
        """A graceful stop: a connection in the middle of a request finishes it (then closes); an idle
        kept-alive one gets :data:`DRAIN` seconds more, so a request its client sent as the stop began is
        answered (with ``Connection: close``) instead of cut off unanswered."""
        if self.cycle is not None and not self.cycle.response_complete:
            super().shutdown()
            return
        if self._drain_timer is None:
            self._draining = True
            self._drain_timer = self.loop.call_later(DRAIN, self._close_idle)

    def _close_idle(self) -> None:
        if self.cycle is None or self.cycle.response_complete:
            self.transport.close()
        else:
            self.cycle.keep_alive = False  # closes once its response is sent

    def connection_lost(self, exc: Exception | None) -> None:
        if self._drain_timer is not None:
            self._drain_timer.cancel()
        self._disarm()
        if self._write_timer is not None:
            self._write_timer.cancel()
        super().connection_lost(exc)


class _Server(uvicorn.Server):
    """uvicorn's server, except that a SIGTERM it shut down for gracefully ends the process with status 0
    (uvicorn re-raises the signal after the shutdown, which ends it with 143)."""

    def handle_exit(self, sig: int, frame: FrameType | None) -> None:
        super().handle_exit(sig, frame)
        if sig == signal.SIGTERM:
            self._captured_signals.remove(sig)


def run(app: Any, listener: socket.socket, *, timeout: float = 10.0) -> None:
    """Serve ``app`` on the bound socket ``listener`` until SIGTERM or Ctrl-C, with client deadlines of
    ``timeout`` seconds."""
    protocol = type("TimedHttp", (_TimedHttp,), {"head_timeout": timeout})
    host, port = listener.getsockname()[:2]
    config = uvicorn.Config(
        app,
        host=host,
        port=port,
        http=protocol,
        log_level="warning",
        timeout_graceful_shutdown=3,
        timeout_keep_alive=5,
    )
    _Server(config).run(sockets=[listener])
