"""The model of danger (§3.5.4): expected damage of each hazard given the novice's trajectory.

    E(d_o | τ) = (1 − P(safe | τ)) · P(reach_o | τ) · d_o

The thesis takes P(reach_o | τ) to be "the normalized distance of the agent from o", an estimate of the steps
the novice needs to reach and bump into o. We normalise it as

    P(reach_o | τ) = max(0, 1 − (steps_o − 1) / H)

where ``steps_o`` is the novice's shortest walk to bump into o (1 when beside it: P = 1) and H, the
*horizon*, is how many novice steps ahead the caregiver looks (default ``HORIZON`` = 5: a hazard 6 or more
steps away scores 0). Normalising by the map's longest walk instead (tried first) makes every hazard of a
large house look about equally near, and the caregiver guards a far stairwell while the novice plays at the
other end; the horizon keeps its attention where the novice can get to before it could intervene elsewhere.
A stairwell the caregiver stands in cannot be fallen down: its expected damage is 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from supportive.errors import SafetyError
from supportive.worlds.household.distances import UNREACHABLE, MapDistances
from supportive.worlds.household.grid_map import Cell
from supportive.worlds.household.world import DAMAGE, HouseholdWorld

__all__ = ["HORIZON", "DangerModel", "Hazard"]

HORIZON = 5.0
"""Default reach horizon H, in novice steps."""


@dataclass(frozen=True)
class Hazard:
    """A thing the novice can hurt itself on, as it stands now."""

    cell: Cell
    kind: str
    damage: int


class DangerModel:
    """Expected damage per hazard.

    Args:
        distances: The map's distances.
        horizon: H of the reach normalisation, in novice steps.

    >>> from supportive.worlds.household import parse_map
    >>> model = DangerModel(MapDistances(parse_map("######\\n#B...#\\n#...S#\\n######\\n")), horizon=4)
    >>> model.reach((2, 4), (2, 3)), model.reach((2, 4), (2, 1)), model.reach((2, 4), (1, 1))
    (1.0, 0.5, 0.0)
    """

    def __init__(self, distances: MapDistances, horizon: float = HORIZON) -> None:
        self.distances = distances
        self.horizon = horizon
        if self.horizon <= 0:
            raise SafetyError(f"horizon must be > 0, got {self.horizon}")

    def steps(self, hazard: Cell, novice: Cell) -> int:
        """The novice's shortest walk to bump into ``hazard`` (``UNREACHABLE`` when it cannot)."""
        table = self.distances.to_collide.get(hazard)
        i = self.distances.novice.index.get(novice)
        if table is None or i is None:
            return int(UNREACHABLE)
        return int(table[i])

    def reach(self, hazard: Cell, novice: Cell) -> float:
        """P(reach_hazard | τ) from the novice's cell."""
        return max(0.0, 1.0 - (self.steps(hazard, novice) - 1) / self.horizon)

    def reach_all(self, novice: Cell) -> dict[Cell, float]:
        """P(reach) of every hazard cell (stairs and tables) from the novice's cell."""
        i = self.distances.novice.index[novice]
        return {
            cell: max(0.0, 1.0 - (float(table[i]) - 1.0) / self.horizon)
            for cell, table in self.distances.to_collide.items()
        }

    @staticmethod
    def hazards(world: HouseholdWorld) -> list[Hazard]:
        """The hazards as the world stands: stairwells (not the blocked one), candles, empty tables."""
        blocked = world.blocked_stairs()
        out = [Hazard(s, "stairs", DAMAGE["stairs"]) for s in world.grid.stairs if s != blocked]
        for table in world.grid.tables:
            kind = "candle" if table in world.candles else "table"
            out.append(Hazard(table, kind, DAMAGE[kind]))
        return out

    def expected_damage(self, world: HouseholdWorld, p_safe: float) -> dict[Cell, float]:
        """E(d_o | τ) of every hazard of the world (a blocked stairwell is absent)."""
        reach = self.reach_all(world.novice)
        unsafe = 1.0 - p_safe
        return {h.cell: unsafe * reach.get(h.cell, 0.0) * h.damage for h in self.hazards(world)}

    def total(self, world: HouseholdWorld, p_safe: float) -> float:
        """The sum of expected damages: the danger the novice is in."""
        return float(np.sum(list(self.expected_damage(world, p_safe).values())))

