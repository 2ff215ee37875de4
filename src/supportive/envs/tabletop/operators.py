"""The operators of a tabletop world.

* ``Install(kind, target)`` — the lead's motor primitive: take the object of ``kind`` that it can reach
  soonest, turn it as the target needs, and put it into the goal area at ``target``. Plans name kinds, not
  objects ("it may not matter which particular 500Ω resistor is used", §3.2.3): the object is bound when
  the step is taken.
* ``Pick(item)`` and ``Put(item, pose)`` — moving one object about the table; the support agent's
  operators (``pick`` and ``place`` are its capabilities C_s).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Generic, TypeVar

from supportive.envs.tabletop.items import TablePose

__all__ = ["Install", "Pick", "Put", "TabletopOperator"]

TargetT = TypeVar("TargetT")


@dataclass(frozen=True)
class Install(Generic[TargetT]):
    """Put an object of ``kind`` into the goal area at ``target`` (the lead's operator)."""

    kind: str
    target: TargetT

    @property
    def name(self) -> str:
        """The operator prototype."""
        return "install"


@dataclass(frozen=True)
class Pick:
    """Grasp object ``item`` (an index into the world's objects)."""

    item: int

    @property
    def name(self) -> str:
        """The operator prototype."""
        return "pick"


@dataclass(frozen=True)
class Put:
    """Put the held object ``item`` down on a surface at ``pose``."""

    item: int
    pose: TablePose

    @property
    def name(self) -> str:
        """The operator prototype."""
        return "place"


TabletopOperator = Install[TargetT] | Pick | Put
"""Any operator of a tabletop world whose install targets are ``TargetT``."""
