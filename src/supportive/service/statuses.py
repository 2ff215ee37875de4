"""The HTTP status the service answers a refused board operation with (the board itself knows no HTTP).

>>> from supportive.errors import BoardError
>>> board_status(BoardError("conflict", "'Seat' is already done"))
409
"""

from __future__ import annotations

from supportive.errors import BoardError, BoardRefusal

__all__ = ["BOARD_STATUSES", "board_status"]

BOARD_STATUSES: dict[BoardRefusal, int] = {"invalid": 400, "forbidden": 403, "missing": 404, "conflict": 409}
"""A refusal's reason -> its HTTP status."""


def board_status(error: BoardError) -> int:
    """The HTTP status of a refused board operation: 400, 403, 404 or 409."""
    return BOARD_STATUSES[error.reason]
