"""The household world's dynamics (§3.5.5): a novice who bumps into things and a caregiver who moves them.

Damage (§3.5.5.2): a stairwell 5, a candle 4, an empty table 1, a wall, a toy bin or the caregiver 0. A
collision leaves the novice where it was. The caregiver's seven actions (§3.5.5.3) are the four moves,
``wait``, ``get`` (lift a candle off a table beside it) and ``place`` (put the candle it holds on an empty
table beside it). With several tables beside it, ``get`` and ``place`` take the first in north, east, south,
west order that fits. The caregiver may stand on a stairwell cell, which blocks it: a novice walking into it
bumps into the robot instead of falling.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from supportive.errors import WorldError
from supportive.worlds.household.grid_map import MOVES, Cell, GridMap, Terrain

__all__ = [
    "CAREGIVER_ACTIONS",
    "DAMAGE",
    "NOVICE_ACTIONS",
    "Collision",
    "HouseholdWorld",
]

DAMAGE: dict[str, int] = {"stairs": 5, "candle": 4, "table": 1, "wall": 0, "bin": 0, "caregiver": 0}
"""Damage of a novice's collision with each kind of thing (§3.5.5.2)."""

NOVICE_ACTIONS: tuple[str, ...] = tuple(MOVES)
"""The novice's actions: 4-connected moves."""

CAREGIVER_ACTIONS: tuple[str, ...] = (*MOVES, "wait", "get", "place")
"""The caregiver's seven actions (§3.5.5.3)."""


@dataclass(frozen=True)
class Collision:
    """A novice's bump: into what, where, and the damage it did."""

    kind: str
    cell: Cell
    damage: int


@dataclass
class HouseholdWorld:
    """The mutable state of one episode: where the novice and caregiver are, where the candles stand.

    Args:
        grid: The map.
        novice: The novice's cell (open floor).
        caregiver: The caregiver's cell, or None when there is no caregiver.
        candles: The tables holding a candle now (see :meth:`start` for the map's own).
        carrying: Whether the caregiver holds a candle.

    >>> from supportive.worlds.household.grid_map import parse_map
    >>> world = HouseholdWorld.start(parse_map("######\\n#B..C#\\n#...S#\\n######\\n"), novice=(2, 3))
    >>> world.move_novice("east")
    Collision(kind='stairs', cell=(2, 4), damage=5)
    >>> world.move_novice("north"), world.novice
    (None, (1, 3))
    """

    grid: GridMap
    novice: Cell
    caregiver: Cell | None = None
    candles: set[Cell] = field(default_factory=set)
    carrying: bool = False

    @classmethod
    def start(cls, grid: GridMap, novice: Cell, caregiver: Cell | None = None) -> HouseholdWorld:
        """A world at the start of an episode: the candles where the map puts them."""
        return cls(grid, novice, caregiver, set(grid.candles))

    def copy(self) -> HouseholdWorld:
        """An independent copy (for looking ahead)."""
        return HouseholdWorld(self.grid, self.novice, self.caregiver, set(self.candles), self.carrying)

    def collision_at(self, cell: Cell) -> Collision | None:
        """What the novice would bump into on entering ``cell`` (None when it can walk there)."""
        if cell == self.caregiver:
            return Collision("caregiver", cell, DAMAGE["caregiver"])
        kind = self.grid.at(cell)
        if kind is Terrain.FLOOR:
            return None
        if kind is Terrain.TABLE:
            name = "candle" if cell in self.candles else "table"
        else:
            name = {Terrain.WALL: "wall", Terrain.STAIRS: "stairs", Terrain.BIN: "bin"}[kind]
        return Collision(name, cell, DAMAGE[name])

    def move_novice(self, action: str) -> Collision | None:
        """Apply a novice move; return the collision it caused (the novice then stays), or None.

        Raises:
            WorldError: for an action that is not a move.
        """
        if action not in MOVES:
            raise WorldError(f"unknown novice action {action!r} (expected one of {', '.join(MOVES)})")
        dr, dc = MOVES[action]
        target = (self.novice[0] + dr, self.novice[1] + dc)
        collision = self.collision_at(target)
        if collision is None:
            self.novice = target
        return collision

    def caregiver_can_enter(self, cell: Cell) -> bool:
        """True when the caregiver may step onto ``cell`` now (open floor or stairs, not the novice's cell)."""
        return self.grid.at(cell) in (Terrain.FLOOR, Terrain.STAIRS) and cell != self.novice

    def table_for(self, action: str) -> Cell | None:
        """The table ``get`` or ``place`` would use from the caregiver's cell now, or None."""
        if self.caregiver is None:
            return None
        for _, cell in self.grid.neighbours(self.caregiver):
            if self.grid.at(cell) is not Terrain.TABLE:
                continue
            if action == "get" and not self.carrying and cell in self.candles:
                return cell
            if action == "place" and self.carrying and cell not in self.candles:
                return cell
        return None

    def act_caregiver(self, action: str) -> bool:
        """Apply one caregiver action; return whether it changed anything (a blocked move or a ``get`` with no
        candle beside it does nothing).

        Raises:
            WorldError: for an unknown action or when there is no caregiver.
        """
        if self.caregiver is None:
            raise WorldError("this world has no caregiver")
        if action not in CAREGIVER_ACTIONS:
            raise WorldError(
                f"unknown caregiver action {action!r} (expected one of {', '.join(CAREGIVER_ACTIONS)})"
            )
        if action in MOVES:
            dr, dc = MOVES[action]
            target = (self.caregiver[0] + dr, self.caregiver[1] + dc)
            if not self.caregiver_can_enter(target):
                return False
            self.caregiver = target
            return True
        if action == "wait":
            return False
        table = self.table_for(action)
        if table is None:
            return False
        if action == "get":
            self.candles.discard(table)
            self.carrying = True
        else:
            self.candles.add(table)
            self.carrying = False
        return True

    def blocked_stairs(self) -> Cell | None:
        """The stairwell cell the caregiver stands in, or None."""
        if self.caregiver is not None and self.grid.at(self.caregiver) is Terrain.STAIRS:
            return self.caregiver
        return None
