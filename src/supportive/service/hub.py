"""Pushing every change to the board's WebSocket subscribers."""

from __future__ import annotations

import asyncio
from contextlib import suppress
from typing import Any

__all__ = ["Hub"]

_QUEUE = 256


class Hub:
    """Subscribers' queues; a message published reaches every subscriber (a slow one that falls
    :data:`_QUEUE` messages behind is dropped, and its socket closed by its handler)."""

    def __init__(self) -> None:
        self._queues: set[asyncio.Queue[dict[str, Any] | None]] = set()

    def subscribe(self) -> asyncio.Queue[dict[str, Any] | None]:
        """A new subscriber's queue."""
        queue: asyncio.Queue[dict[str, Any] | None] = asyncio.Queue(_QUEUE)
        self._queues.add(queue)
        return queue

    def unsubscribe(self, queue: asyncio.Queue[dict[str, Any] | None]) -> None:
        """Forget a subscriber."""
        self._queues.discard(queue)

    def publish(self, message: dict[str, Any]) -> None:
        """Send ``message`` to every subscriber (call from the event loop)."""
        for queue in list(self._queues):
            try:
                queue.put_nowait(message)
            except asyncio.QueueFull:  # too slow: make room for the sentinel that ends its stream
                self._queues.discard(queue)
                with suppress(asyncio.QueueEmpty):
                    queue.get_nowait()
                queue.put_nowait(None)
