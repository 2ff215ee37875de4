"""Social force over the API (§3.4.4): agents (or a hand tracker) post hand positions; anyone reads each
agent's ellipse, the combined force over the workspace, and every action's reading at its keyframes."""

from __future__ import annotations

import time
from typing import Annotated, Any

import numpy as np
from fastapi import APIRouter, Body, Depends, HTTPException, Query, Request
from numpy.typing import ArrayLike, NDArray

from supportive.errors import SocialError
from supportive.service.agents import Agent
from supportive.service.schemas import HandIn
from supportive.service.state import current_agent, service
from supportive.social.field import ForceField
from supportive.social.reading import reading

__all__ = ["router"]

router = APIRouter(prefix="/api", tags=["social"])
Me = Annotated[Agent, Depends(current_agent)]


@router.post("/hands", summary="Report where your hand (or end effector) is now")
async def post_hand(request: Request, me: Me, body: Annotated[HandIn, Body()]) -> dict[str, Any]:
    """``{"x": 0.4, "y": 0.3, "t": 12.5}`` in workspace metres; ``t`` defaults to the server's clock (seconds
    since it started). Times must not go backwards for one agent (409). Observers may not post."""
    if me.role == "observer":
        raise HTTPException(403, "observers may not report hand positions")
    state = service(request)
    _within(state.settings.workspace, body)
    t = body.t if body.t is not None else time.monotonic() - state.started
    try:
        state.forces.update(me.id, t, (body.x, body.y))
    except SocialError as exc:
        raise HTTPException(409, str(exc)) from None
    return {"agent": me.id, "t": t}


REACH = 1.0
"""How far outside the workspace (metres, on every side) a hand may be reported: a person's arm reaches about
this far beyond the table's edge; a position farther out is a tracker's or a client's mistake (422)."""


def hand_bounds(workspace: tuple[float, float]) -> tuple[tuple[float, float], tuple[float, float]]:
    """The least and most ``x`` and ``y`` a hand may have on a workspace of this width and depth: the
    workspace and :data:`REACH` around it (the OpenAPI document says so too)."""
    width, depth = workspace
    return (-REACH, width + REACH), (-REACH, depth + REACH)


def _within(workspace: tuple[float, float], hand: HandIn) -> None:
    """Refuse (422, in the shape of FastAPI's validation errors) a hand outside :func:`hand_bounds`."""
    problems = []
    for axis, value, (low, high) in zip(("x", "y"), (hand.x, hand.y), hand_bounds(workspace), strict=True):
        if not low <= value <= high:
            problems.append(
                {
                    "loc": ["body", axis],
                    "msg": f"{axis}: {value:g} m is outside the workspace; {axis} must be within {low:g} .. "
                    f"{high:g} m (the {workspace[0]:g} m × {workspace[1]:g} m workbench and {REACH:g} m around it)",
                    "type": "outside_workspace",
                }
            )
    if problems:
        raise HTTPException(422, problems)


@router.get(
    "/social", summary="Each agent's social-force ellipse, the force over the workspace, and readings"
)
async def read_social(
    request: Request,
    me: Me,
    nx: Annotated[int, Query(ge=2, le=200)] = 48,
    ny: Annotated[int, Query(ge=2, le=200)] = 20,
    exclude: Annotated[
        str | None, Query(description="An agent to leave out (a robot reading others' force).")
    ] = None,
) -> dict[str, Any]:
    """``agents``: hand and ellipse per agent (``center``, ``half_axes``, ``axes``, ``angle``); ``field``: the
    combined force (max over agents) on an ``nx`` × ``ny`` grid over the workspace, row by row from y = 0;
    ``readings``: each action with keyframes, its reading (largest force at its keyframes)."""
    state = service(request)
    forces = state.forces
    width, depth = state.settings.workspace
    agents = [a for a in forces.agents if a != exclude]
    roles = state.agents
    described = []
    for name in forces.agents:
        force = forces.force(name)
        samples = force.samples
        ellipse = force.ellipse()
        described.append(
            {
                "id": name,
                "kind": roles[name].kind if name in roles else "human",
                "hand": None if len(samples) == 0 else [float(v) for v in samples[-1]],
                "ellipse": None
                if ellipse is None
                else {
                    "center": list(ellipse.center),
                    "half_axes": list(ellipse.half_axes),
                    "axes": [list(a) for a in ellipse.axes],
                    "angle": ellipse.rotation,
                },
            }
        )
    xs = (np.arange(nx) + 0.5) * width / nx
    ys = (np.arange(ny) + 0.5) * depth / ny
    grid = np.array([(x, y) for y in ys for x in xs])
    values = forces.field(grid, agents) if agents else np.zeros(len(grid))
    readings = []
    spec = state.settings.spec
    if spec is not None:
        source = _Combined(forces, agents)
        for action in spec.actions:
            if action.keyframes:
                readings.append(
                    {"action": action.id, "reading": reading(source, [k.point for k in action.keyframes])}
                )
    return {
        "workspace": [width, depth],
        "agents": described,
        "field": {"nx": nx, "ny": ny, "values": [round(float(v), 4) for v in values]},
        "readings": readings,
    }


class _Combined:
    """The force of some agents of a field, as one force source."""

    def __init__(self, forces: ForceField, agents: list[str]) -> None:
        self.forces = forces
        self.agents = agents

    def field(self, points: ArrayLike) -> NDArray[np.float64]:
        """The largest of the agents' forces at each point (zeros with no agent)."""
        xy = np.asarray(points, dtype=float)
        return self.forces.field(xy, self.agents) if self.agents else np.zeros(len(xy))
