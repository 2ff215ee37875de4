"""The table: the shared surface, the lead-only goal area (a snap board, an assembly area), an optional tray
beside the support agent that the lead cannot reach, each arm's reach, and the coarse grid of space cells
that says which operators contend for the same space (Algorithm 5's "physical space utilized").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from supportive.envs.tabletop.geometry import Point, Rect
from supportive.errors import PlanningError

__all__ = ["TableLayout"]

_STAGING_TRIES = 20


@dataclass(frozen=True)
class TableLayout:
    """Where things may lie and who reaches what.

    Attributes:
        table: The shared table top.
        goal_area: Where the lead builds (inside the table); nothing else may lie there.
        tray: A surface beside the support agent that the lead cannot reach, or None.
        lead_reach: What the lead reaches (default: the whole table — the thesis's full shared reach).
        support_reach: What the support agent reaches (default: the table and the tray).
        cell: Side of a space cell, cm.
        clearance: Least gap between two objects lying side by side, cm.
        staging: The share of sampled placements drawn near the goal area (the rest are uniform over the
            surfaces): the thesis samples "legal placement positions and poses in the task area"; most useful
            places are next to where the lead builds, so half the samples look there.
        staging_band: How far from the goal area those placements may be, cm.
    """

    table: Rect
    goal_area: Rect
    tray: Rect | None = None
    lead_reach: Rect | None = None
    support_reach: Rect | None = None
    cell: float = 10.0
    clearance: float = 1.0
    staging: float = 0.5
    staging_band: float = 15.0

    def __post_init__(self) -> None:
        if not self.table.encloses(self.goal_area):
            raise PlanningError(f"the goal area {self.goal_area} is not on the table {self.table}")
        if self.tray is not None and self.tray.overlaps(self.table):
            raise PlanningError(f"the tray {self.tray} overlaps the table {self.table}")
        if self.cell <= 0 or self.clearance < 0:
            raise PlanningError("cell must be > 0 and clearance >= 0")
        if not 0 <= self.staging <= 1 or self.staging_band <= 0:
            raise PlanningError("staging must be in [0, 1] and staging_band > 0")

    @property
    def surfaces(self) -> tuple[Rect, ...]:
        """Where objects may be put down: the table, and the tray if there is one."""
        return (self.table,) if self.tray is None else (self.table, self.tray)

    @property
    def bounds(self) -> Rect:
        """The rectangle around every surface."""
        rects = self.surfaces
        return Rect(
            min(r.x0 for r in rects),
            min(r.y0 for r in rects),
            max(r.x1 for r in rects),
            max(r.y1 for r in rects),
        )

    def reach(self, lead: bool) -> Rect:
        """What the lead (or the support agent) reaches."""
        if lead:
            return self.lead_reach or self.table
        return self.support_reach or self.bounds

    def lies_on_surface(self, footprint: Rect) -> bool:
        """Whether an object with this footprint lies wholly on one surface and off the goal area."""
        if footprint.overlaps(self.goal_area, self.clearance):
            return False
        return any(surface.encloses(footprint) for surface in self.surfaces)

    def cells(self, footprint: Rect) -> frozenset[tuple[str, int, int]]:
        """The space cells a footprint covers, as ``("cell", column, row)``."""
        return _cells(self, footprint)

    def sample_placement(self, rng: np.random.Generator) -> Point:
        """A position to try putting an object down: with probability ``staging``, uniform in the band of
        ``staging_band`` cm around the goal area (on the table, outside the goal area); otherwise uniform over
        the surfaces, each picked by its area."""
        if self.staging > 0 and rng.random() < self.staging:
            band = self.goal_area.grown(self.staging_band)
            for _ in range(_STAGING_TRIES):
                x, y = band.x0 + rng.random() * band.width, band.y0 + rng.random() * band.height
                if self.table.contains((x, y)) and not self.goal_area.contains((x, y)):
                    return (x, y)
        surfaces = self.surfaces
        areas = [s.width * s.height for s in surfaces]
        pick = rng.random() * sum(areas)
        chosen = surfaces[-1]
        for surface, area in zip(surfaces, areas, strict=True):
            if pick < area:
                chosen = surface
                break
            pick -= area
        return (chosen.x0 + rng.random() * chosen.width, chosen.y0 + rng.random() * chosen.height)


@lru_cache(maxsize=65536)
def _cells(layout: TableLayout, footprint: Rect) -> frozenset[tuple[str, int, int]]:
    """The space cells of a footprint (remembered: planners ask about the same footprints again and again)."""
    origin = layout.bounds
    c0 = math.floor((footprint.x0 - origin.x0) / layout.cell)
    c1 = math.floor((footprint.x1 - origin.x0) / layout.cell)
    r0 = math.floor((footprint.y0 - origin.y0) / layout.cell)
    r1 = math.floor((footprint.y1 - origin.y0) / layout.cell)
    return frozenset(("cell", c, r) for c in range(c0, c1 + 1) for r in range(r0, r1 + 1))
