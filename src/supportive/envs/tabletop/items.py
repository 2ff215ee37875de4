"""Objects on a table: their kinds, sizes and poses (position and a rotation in quarter turns).

>>> wire = ItemType("wire3", length=10.0, width=3.0, symmetric=True)
>>> TablePose(20.0, 30.0, 1).footprint(wire)
Rect(x0=18.5, y0=25.0, x1=21.5, y1=35.0)
>>> quarter_turns(0, 2, symmetric=True), quarter_turns(0, 3, symmetric=False)
(0, 1)
"""

from __future__ import annotations

from dataclasses import dataclass

from supportive.envs.tabletop.geometry import Point, Rect
from supportive.errors import PlanningError

__all__ = ["Item", "ItemType", "TablePose", "quarter_turns"]


@dataclass(frozen=True)
class ItemType:
    """A kind of object: its size and whether a half turn leaves it the same.

    Attributes:
        name: The kind (``"wire3"``, ``"screwdriver"``).
        length: Extent along its own axis, cm.
        width: Extent across it, cm.
        symmetric: A half turn maps it onto itself (a wire, unlike a battery or an LED).
        text: Words for people (``"a 3-snap wire"``).
    """

    name: str
    length: float
    width: float
    symmetric: bool = False
    text: str = ""

    def __post_init__(self) -> None:
        if self.length <= 0 or self.width <= 0:
            raise PlanningError(f"item type {self.name}: length and width must be > 0")


@dataclass(frozen=True)
class Item:
    """One object: an id unique in its world, and its kind."""

    id: str
    kind: str


@dataclass(frozen=True)
class TablePose:
    """Where an object lies on the table: its centre and rotation (0 = its axis along x, 1 = along y, …)."""

    x: float
    y: float
    rotation: int = 0

    @property
    def point(self) -> Point:
        """Its centre."""
        return (self.x, self.y)

    def footprint(self, kind: ItemType) -> Rect:
        """The rectangle the object covers."""
        half_long, half_wide = kind.length / 2, kind.width / 2
        if self.rotation % 2:
            half_long, half_wide = half_wide, half_long
        return Rect(self.x - half_long, self.y - half_wide, self.x + half_long, self.y + half_wide)


def quarter_turns(start: int, end: int, symmetric: bool) -> int:
    """Quarter turns needed to bring rotation ``start`` to ``end`` (0, 1 or 2; a symmetric object never
    needs a half turn)."""
    turns = (end - start) % 4
    turns = min(turns, 4 - turns)
    return 0 if symmetric and turns == 2 else turns
