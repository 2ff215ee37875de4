"""The bundled IKEA chair (examples/ikea-chair.yaml) as a workshop: its parts and tools on a table, plans
from its structure's orderings.

Parts by step: the side frames, pegs, the two rails, bolts, nuts, the seat and screws; the nuts need the hex
key and the screws the screwdriver. Steps that take nothing from the table (standing a frame up, seating a
rail) are left out of the plans: they take the same time whatever the table looks like.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from supportive.envs.tabletop.arms import ArmModel
from supportive.envs.tabletop.geometry import Rect
from supportive.envs.tabletop.items import ItemType, TablePose
from supportive.envs.tabletop.layout import TableLayout
from supportive.envs.tabletop.operators import Install, TabletopOperator
from supportive.envs.workshop.world import WorkshopWorld, tool_slot
from supportive.errors import PlanningError
from supportive.examples import load
from supportive.generate.orderings import sample_orderings

__all__ = ["CHAIR_PARTS", "CHAIR_TOOLS", "CHAIR_TYPES", "WorkshopPlan", "chair_plans", "chair_workshop"]

WorkshopPlan = tuple[TabletopOperator[str], ...]
"""A lead plan of the workshop: Install steps in the order of one ordering of the task."""

CHAIR_PARTS = {
    "get_left_frame": "left_frame",
    "get_right_frame": "right_frame",
    "peg_left_front": "peg",
    "peg_left_rear": "peg",
    "peg_right_front": "peg",
    "peg_right_rear": "peg",
    "get_front_support": "front_rail",
    "get_back_support": "back_rail",
    "insert_bolt_fl": "bolt",
    "insert_bolt_fr": "bolt",
    "insert_bolt_rl": "bolt",
    "insert_bolt_rr": "bolt",
    "tighten_nut_fl": "nut",
    "tighten_nut_fr": "nut",
    "tighten_nut_rl": "nut",
    "tighten_nut_rr": "nut",
    "get_seat": "seat",
    "screw_seat_left": "screw",
    "screw_seat_right": "screw",
}
"""The part each step of the chair takes from the table."""

CHAIR_TOOLS = {
    **{f"tighten_nut_{corner}": "hex_key" for corner in ("fl", "fr", "rl", "rr")},
    "screw_seat_left": "screwdriver",
    "screw_seat_right": "screwdriver",
}
"""The tool each step needs."""

CHAIR_TYPES = {
    "left_frame": ItemType("left_frame", 30.0, 5.0, False, "the left side frame"),
    "right_frame": ItemType("right_frame", 30.0, 5.0, False, "the right side frame"),
    "front_rail": ItemType("front_rail", 24.0, 3.0, True, "the front support rail"),
    "back_rail": ItemType("back_rail", 24.0, 3.0, True, "the back support rail"),
    "seat": ItemType("seat", 22.0, 20.0, False, "the seat"),
    "peg": ItemType("peg", 3.0, 1.0, True, "a wooden peg"),
    "bolt": ItemType("bolt", 5.0, 1.0, False, "a bolt"),
    "nut": ItemType("nut", 1.5, 1.5, True, "a nut"),
    "screw": ItemType("screw", 3.0, 1.0, False, "a screw"),
    "hex_key": ItemType("hex_key", 7.0, 2.0, False, "the hex key"),
    "screwdriver": ItemType("screwdriver", 14.0, 3.0, False, "the screwdriver"),
}
"""Sizes of the chair's parts and tools, cm."""

_TABLE = Rect(0.0, 0.0, 140.0, 90.0)
_ASSEMBLY = Rect(45.0, 3.0, 95.0, 38.0)


def chair_workshop(
    seed: int | np.random.Generator | None = 0, *, lead: float = 1.0, support: float = 1.0
) -> WorkshopWorld:
    """The chair's parts (one per step) and both tools scattered on a 140 × 90 cm table, the assembly area
    on the lead's side.

    Raises:
        PlanningError: when the table is too crowded to scatter on (it is not, for the chair).
    """
    rng = np.random.default_rng(seed)
    layout = TableLayout(_TABLE, _ASSEMBLY)
    kinds = [*CHAIR_PARTS.values(), *sorted(set(CHAIR_TOOLS.values()))]
    pieces: list[tuple[str, str, TablePose]] = []
    counts: dict[str, int] = {}
    for kind in kinds:
        for _ in range(10_000):
            pose = TablePose(float(rng.integers(6, 135)), float(rng.integers(6, 85)), int(rng.integers(4)))
            footprint = pose.footprint(CHAIR_TYPES[kind])
            if layout.lies_on_surface(footprint) and not any(
                footprint.overlaps(other.footprint(CHAIR_TYPES[k]), layout.clearance)
                for _, k, other in pieces
            ):
                counts[kind] = counts.get(kind, 0) + 1
                pieces.append((f"{kind}-{counts[kind]}", kind, pose))
                break
        else:
            raise PlanningError("the table is too crowded for the chair's parts")
    arms = (
        ArmModel("lead", (70.0, -12.0), speed_factor=lead),
        ArmModel("support", (70.0, 104.0), speed_factor=support),
    )
    return WorkshopWorld(layout, CHAIR_TYPES, pieces, CHAIR_PARTS, CHAIR_TOOLS, *arms)


def chair_plans(count: int = 20, seed: int | np.random.Generator | None = 0) -> tuple[WorkshopPlan, ...]:
    """Π_T: ``count`` distinct orderings of the chair's structure, each as the installs it makes (a tool
    fetched just before the first step that needs it)."""
    structure = load("ikea-chair").structure
    if structure is None:
        raise PlanningError("the bundled chair has no structure")
    return tuple(_plan(order) for order in sample_orderings(structure, count, seed, distinct=True))


def _plan(order: Sequence[tuple[str, int]]) -> WorkshopPlan:
    steps: list[TabletopOperator[str]] = []
    fetched: set[str] = set()
    for action, _ in order:
        if action not in CHAIR_PARTS:
            continue
        tool = CHAIR_TOOLS.get(action)
        if tool is not None and tool not in fetched:
            fetched.add(tool)
            steps.append(Install(tool, tool_slot(tool)))
        steps.append(Install(CHAIR_PARTS[action], action))
    return tuple(steps)
