"""Request bodies of the board API (pydantic); every field checked, unknown keys refused."""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from supportive.io.values import Coordinate, Seconds

__all__ = ["ErrorOut", "HandIn", "ObservationIn", "ProgressIn"]


class _Strict(BaseModel):
    """Unknown keys refused, and no coercion: ``true`` or ``"0.5"`` where a number belongs is a 422, as is
    ``1`` where text belongs (an integer where a float belongs is a number, and accepted)."""

    model_config = ConfigDict(extra="forbid", strict=True)


class ProgressIn(_Strict):
    """``{"progress": 0.5}``: the share of a leaf that is done."""

    progress: Annotated[float, Field(ge=0.0, le=1.0, allow_inf_nan=False)]


class HandIn(_Strict):
    """``{"x": 0.4, "y": 0.2, "t": 12.5}``: where the agent's hand (or end effector) is, metres on the
    workbench; ``t`` in seconds (default: the server's clock). Coordinates within ±10^6 and times within
    ±10^11 s (:mod:`supportive.io.values`): the force computed from them stays finite."""

    x: Coordinate
    y: Coordinate
    t: Seconds | None = None


class ObservationIn(_Strict):
    """``{"events": ["hand-seat"]}``: the contact events that hold at this moment (at most 64)."""

    events: Annotated[list[Annotated[str, Field(min_length=1, max_length=80)]], Field(max_length=64)]


class ErrorOut(BaseModel):
    """Every refusal but 422: ``{"detail": "what was wrong"}``."""

    detail: str
