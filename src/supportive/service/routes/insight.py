"""What the robot thinks: the goal-inference belief, the mistakes it noticed and the supportive behaviors that
may run now."""

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
    latest steps); ``mistakes``: the latest mistakes noticed, newest first (each: ``id``, ``raised`` in Unix
    seconds, ``step``, ``action`` and its ``text``, ``kind``, ``probability``, the ``prerequisites`` or
    ``skipped`` steps it names, the ``help`` offered — ``category``, ``behavior``, ``say`` — and ``nodes``, the
    board's not-done nodes of the steps it names, which the robot may claim to help); ``behaviors``: the
    task's supportive behaviors whose start condition holds and stop condition does not."""
    state = service(request)
    board, _ = await run_in_threadpool(state.store.board)
    suggestions = await run_in_threadpool(state.insight.suggestions, board)
    return {
        "inference": state.insight.inference,
        "belief": state.insight.belief(),
        "goal": state.insight.goal(),
        "mistakes": list(state.insight.mistakes),
        "behaviors": suggestions,
    }


@router.post("/observations", summary="Report what touches what now (contact events), for goal inference")
async def observe(request: Request, me: Me, body: Annotated[ObservationIn, Body()]) -> dict[str, Any]:
    """``{"events": ["hand-seat", "seat-left_frame"]}``; the belief after it, with ``mistake``: the mistake
    this step raised (as ``/api/insight`` lists them; every screen is sent it as a ``{"type": "mistake"}``
    event), or None. 409 when the task has no goal inference; 403 for observers."""
    if me.role == "observer":
        raise HTTPException(403, "observers may not report observations")
    state = service(request)
    board, _ = await run_in_threadpool(state.store.board)
    before = state.insight.raised
    try:
        summary = await run_in_threadpool(state.insight.update, list(body.events), board)
    except SupportiveError as exc:
        raise HTTPException(409, str(exc)) from None
    state.hub.publish({"type": "belief", "belief": state.insight.belief()})
    mistake = state.insight.latest_mistake() if state.insight.raised != before else None
    if mistake is not None:
        state.hub.publish({"type": "mistake", "mistake": mistake})
    return {**summary, "mistake": mistake}
