"""An assembly workshop as a tabletop world: the "materials retrieval" class of supportive behaviors (§3.1).

The lead assembles a product in an assembly area only it works in. Each step of the task that needs a part
installs one object of that kind there (the object the lead reaches soonest is used); a step that needs a
tool needs that tool in the assembly area first, and a tool, once fetched, stays. The order of the steps
comes from the plans (orderings of the task's structure), so a step is possible whenever it has not been done
and its tool is at hand. The support agent may stage parts and tools on the table; P forbids it
``in_assembly(*)``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from supportive.envs.tabletop.arms import ArmModel
from supportive.envs.tabletop.geometry import Point
from supportive.envs.tabletop.items import Item, ItemType, TablePose
from supportive.envs.tabletop.layout import TableLayout
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.envs.tabletop.world import TabletopWorld
from supportive.errors import PlanningError

__all__ = ["Assembly", "WorkshopWorld", "tool_slot"]

Assembly = tuple[tuple[str, int], ...]
"""What the assembly area holds: (slot, object) pairs in the order they went in."""


def tool_slot(tool: str) -> str:
    """The slot a tool goes into when it is first fetched."""
    return f"tool:{tool}"


class WorkshopWorld(TabletopWorld[Assembly, str]):
    """Parts and tools on a table, an assembly area for the lead.

    Args:
        layout: The table; its goal area is the assembly area.
        types: Every kind of part and tool, by name.
        pieces: Every object: id, kind and where it lies at the start.
        slots: Each step that takes a part: the part's kind, by slot (step) name.
        tools: The tool each such step needs, by slot, when it needs one.
        lead: The lead's arm.
        support: The support agent's arm.
    """

    goal_predicate = "in_assembly"

    def __init__(
        self,
        layout: TableLayout,
        types: Mapping[str, ItemType],
        pieces: Sequence[tuple[str, str, TablePose]],
        slots: Mapping[str, str],
        tools: Mapping[str, str],
        lead: ArmModel,
        support: ArmModel,
    ) -> None:
        unknown = sorted(set(tools) - set(slots))
        if unknown:
            raise PlanningError(f"tools for steps that take no part: {', '.join(unknown)}")
        self.slots = dict(slots)
        self.tools = dict(tools)
        kinds = {**slots, **{tool_slot(t): t for t in tools.values()}}
        self.kinds_by_slot = kinds
        names = sorted(kinds)
        area = layout.goal_area
        columns = max(1, int(len(names) ** 0.5 + 0.999))
        rows = -(-len(names) // columns)
        self._points = {
            name: (
                area.x0 + area.width * (0.5 + i % columns) / columns,
                area.y0 + area.height * (0.5 + i // columns) / rows,
            )
            for i, name in enumerate(names)
        }
        empty: Assembly = ()
        initial = TabletopState(
            tuple(pose for _, _, pose in pieces),
            tuple(Status.TABLE for _ in pieces),
            empty,
            (lead.home, support.home),
        )
        super().__init__(layout, types, [Item(i, k) for i, k, _ in pieces], initial, lead, support)

    def target_point(self, target: str) -> Point:
        """Where in the assembly area the slot's object goes."""
        return self._points[target]

    def target_rotation(self, target: str) -> int:
        """Parts go in lying along x."""
        return 0

    def can_receive(self, goal: Assembly, kind: str, target: str) -> bool:
        """The slot is known, takes this kind, is still empty, and its tool (if any) is in the area."""
        if self.kinds_by_slot.get(target) != kind or any(slot == target for slot, _ in goal):
            return False
        tool = self.tools.get(target)
        return tool is None or any(slot == tool_slot(tool) for slot, _ in goal)

    def receive(self, goal: Assembly, item: int, target: str) -> Assembly:
        """The assembly with the object in the slot."""
        return (*goal, (target, item))

    def can_release(self, goal: Assembly, item: int) -> bool:
        """Nothing assembled comes out again."""
        return False

    def release(self, goal: Assembly, item: int) -> Assembly:
        """Refused: assembled objects stay.

        Raises:
            PlanningError: always.
        """
        raise PlanningError(f"{self.items[item].id} is assembled and stays")

    def installed(self, goal: Assembly) -> Mapping[str, str]:
        """Each filled slot and its kind."""
        return {slot: self.kinds_by_slot[slot] for slot, _ in goal}

    def goal_reached(self, state: TabletopState[Assembly]) -> bool:
        """Every step's slot is filled."""
        done = {slot for slot, _ in state.goal}
        return all(slot in done for slot in self.slots)

    def describe_target(self, target: str) -> str:
        """The slot's name."""
        return target
