"""What the robot thinks: the goal-inference belief and the supportive behaviors that may run now."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, Body, Depends, HTTPException, Request
from starlette.concurrency import run_in_threadpool

from supportive.errors import SupportiveError
from supportive.service.agents import Agent
from supportive.service.schemas import ObservationIn
from supportive.service.state import current_agent, service

__all__ = ["router"]

router = APIRouter(prefix="/api", tags=["insight"])
Me = Annotated[Agent, Depends(current_agent)]


@router.get("/insight", summary="The goal-inference belief and the supportive behaviors that may run now")
async def read_insight(request: Request, me: Me) -> dict[str, Any]:
    """``inference``: whether the task has goal inference; ``belief``: the most likely current actions (None
    before any observation, or without inference); ``goal``: the same belief for people (likely subtasks,
    current and next actions with their text, ``surprise`` and ``off_script`` when the model reports them, the
    latest steps); ``behaviors``: the task's supportive behaviors whose start condition holds and stop
    condition does not."""
    state = service(request)
    board, _ = await run_in_threadpool(state.store.board)
    suggestions = await run_in_threadpool(state.insight.suggestions, board)
    return {
        "inference": state.insight.inference,
        "belief": state.insight.belief(),
        "goal": state.insight.goal(),
        "behaviors": suggestions,
    }


@router.post("/observations", summary="Report what touches what now (contact events), for goal inference")
async def observe(request: Request, me: Me, body: Annotated[ObservationIn, Body()]) -> dict[str, Any]:
    """``{"events": ["hand-seat", "seat-left_frame"]}``; the belief after it. 409 when the task has no
    goal inference; 403 for observers."""
    if me.role == "observer":
        raise HTTPException(403, "observers may not report observations")
    state = service(request)
    try:
        summary = await run_in_threadpool(state.insight.observe, list(body.events))
    except SupportiveError as exc:
        raise HTTPException(409, str(exc)) from None
    state.hub.publish({"type": "belief", "belief": state.insight.belief()})
    return summary
