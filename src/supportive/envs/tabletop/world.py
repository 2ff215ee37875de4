"""A tabletop world for supportive-behavior planning: a lead builds in a goal area it alone may change,
from objects on a shared table that a support agent may rearrange (§3.2.9.1).

:class:`TabletopWorld` implements :class:`~supportive.planning.world.SupportWorld` for any such task; a
concrete world (the circuit board, the chair's assembly area) says what the goal area holds and what may go
where by implementing its few abstract methods.

Predicates, computed on demand (:meth:`TabletopWorld.holds`): ``on_table(x)``, ``<goal_predicate>(x)``
(``on_board(x)`` for circuits), ``holding(agent, x)``, ``reachable(agent, x)``, ``removable(x)`` (an object
in the goal area that nothing rests on). Resources (what two agents contend for): each object by index, the
space cells under a footprint, and ``"goal-area"``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Hashable, Mapping, Sequence
from dataclasses import dataclass
from typing import ClassVar, Generic, TypeVar

import numpy as np

from supportive.envs.tabletop.arms import ArmModel
from supportive.envs.tabletop.geometry import Point, Rect
from supportive.envs.tabletop.items import Item, ItemType, TablePose, quarter_turns
from supportive.envs.tabletop.layout import TableLayout
from supportive.envs.tabletop.operators import Install, Pick, Put, TabletopOperator
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.errors import PlanningError
from supportive.planning.world import LEAD, SUPPORT, Effects, Predicate

__all__ = ["Move", "TabletopWorld"]

GoalT = TypeVar("GoalT")
TargetT = TypeVar("TargetT", bound=Hashable)

_GOAL_AREA = "goal-area"
_Binding = tuple[int | None, float, float, int]
"""The object an Install binds (None: none), the lead's seconds of travel to it and on to the target, and the
quarter turns it needs."""
_POSITION_STEP = 1.0  # sampled positions are whole centimetres: a discretised task area


@dataclass(frozen=True)
class Move:
    """A hypothetical change: object ``item`` moved to ``pose`` (§3.2.5.1)."""

    item: int
    pose: TablePose


class TabletopWorld(ABC, Generic[GoalT, TargetT]):
    """Objects on a table, a lead building in the goal area, a support agent rearranging the rest.

    Args:
        layout: The table, goal area, tray and reaches.
        types: Every object kind, by name.
        items: The objects (ids unique).
        initial: s_0.
        lead: The lead's arm.
        support: The support agent's arm.
        prohibited: P (default: never add or delete ``<goal_predicate>(*)`` — the goal area is the lead's).
    """

    goal_predicate: ClassVar[str] = "in_goal"
    """The predicate that holds of objects in the goal area."""

    def __init__(
        self,
        layout: TableLayout,
        types: Mapping[str, ItemType],
        items: Sequence[Item],
        initial: TabletopState[GoalT],
        lead: ArmModel,
        support: ArmModel,
        prohibited: Sequence[str] | None = None,
    ) -> None:
        ids = [item.id for item in items]
        if len(set(ids)) != len(ids):
            raise PlanningError("object ids must be unique")
        unknown = sorted({item.kind for item in items} - set(types))
        if unknown:
            raise PlanningError(f"objects of unknown kinds: {', '.join(unknown)}")
        if len(initial.poses) != len(items) or len(initial.status) != len(items):
            raise PlanningError("the initial state must give every object a pose and a status")
        self.layout = layout
        self.types = dict(types)
        self.items = tuple(items)
        self._initial = initial
        self.lead_arm = lead
        self.support_arm = support
        self._prohibited = tuple(prohibited) if prohibited is not None else (f"{self.goal_predicate}(*)",)
        self._index = {item.id: i for i, item in enumerate(self.items)}
        self._by_kind: dict[str, tuple[int, ...]] = {}
        for i, item in enumerate(self.items):
            self._by_kind[item.kind] = (*self._by_kind.get(item.kind, ()), i)
        self._bound: tuple[object, object, _Binding] = (None, None, (None, 0.0, 0.0, 0))

    # -- what a concrete world says ------------------------------------------------------------------------

    @abstractmethod
    def target_point(self, target: TargetT) -> Point:
        """Where on the table plane an object installed at ``target`` goes."""

    @abstractmethod
    def target_rotation(self, target: TargetT) -> int:
        """The rotation (quarter turns, table frame) an object must have to go in at ``target``."""

    @abstractmethod
    def can_receive(self, goal: GoalT, kind: str, target: TargetT) -> bool:
        """Whether an object of ``kind`` may go in at ``target`` now (geometry, support, order)."""

    @abstractmethod
    def receive(self, goal: GoalT, item: int, target: TargetT) -> GoalT:
        """The goal area with object ``item`` installed at ``target``."""

    @abstractmethod
    def can_release(self, goal: GoalT, item: int) -> bool:
        """Whether object ``item`` can be taken out of the goal area (nothing rests on it)."""

    @abstractmethod
    def release(self, goal: GoalT, item: int) -> GoalT:
        """The goal area without object ``item``."""

    @abstractmethod
    def installed(self, goal: GoalT) -> Mapping[TargetT, str]:
        """What the goal area holds: the kind installed at each target."""

    @abstractmethod
    def goal_reached(self, state: TabletopState[GoalT]) -> bool:
        """Whether s_G holds."""

    @abstractmethod
    def describe_target(self, target: TargetT) -> str:
        """A target in a few words."""

    # -- the SupportWorld protocol ---------------------------------------------------------------------------

    @property
    def initial_state(self) -> TabletopState[GoalT]:
        """s_0."""
        return self._initial

    @property
    def support_capabilities(self) -> frozenset[str]:
        """C_s: the support agent picks and places objects."""
        return frozenset({"pick", "place"})

    @property
    def prohibited(self) -> tuple[str, ...]:
        """P."""
        return self._prohibited

    def objects(self, state: TabletopState[GoalT]) -> tuple[str, ...]:
        """Every object's id."""
        return tuple(item.id for item in self.items)

    def index(self, item_id: str) -> int:
        """The index of the object called ``item_id``.

        Raises:
            PlanningError: for an unknown id.
        """
        try:
            return self._index[item_id]
        except KeyError:
            raise PlanningError(f"no object called {item_id!r}") from None

    def footprint_of(self, item: int, pose: TablePose) -> Rect:
        """The rectangle object ``item`` covers at ``pose``."""
        return pose.footprint(self.types[self.items[item].kind])

    def arm(self, agent: str) -> ArmModel:
        """The arm of ``agent`` (``lead`` or ``support``).

        Raises:
            PlanningError: for another agent.
        """
        if agent == LEAD:
            return self.lead_arm
        if agent == SUPPORT:
            return self.support_arm
        raise PlanningError(f"unknown agent {agent!r}: expected {LEAD!r} or {SUPPORT!r}")

    def reachable(self, state: TabletopState[GoalT], agent: str, item: int) -> bool:
        """Whether ``agent`` reaches object ``item`` where it lies (or in the goal area)."""
        pose = state.poses[item]
        if state.status[item] is Status.GOAL or pose is None:
            return state.status[item] is Status.GOAL and self.layout.reach(agent == LEAD).overlaps(
                self.layout.goal_area
            )
        return self.layout.reach(agent == LEAD).contains(pose.point)

    def is_free(self, state: TabletopState[GoalT], item: int, pose: TablePose) -> bool:
        """Whether object ``item`` could lie at ``pose``: on a surface, off the goal area, clear of the other
        objects lying about."""
        footprint = self.footprint_of(item, pose)
        if not self.layout.lies_on_surface(footprint):
            return False
        gap = self.layout.clearance
        for other, (other_pose, status) in enumerate(zip(state.poses, state.status, strict=True)):
            if (
                other != item
                and status is Status.TABLE
                and other_pose is not None
                and footprint.overlaps(self.footprint_of(other, other_pose), gap)
            ):
                return False
        return True

    def holds(self, state: TabletopState[GoalT], predicate: Predicate) -> bool:
        """Whether a predicate holds (see the module docstring for the names).

        Raises:
            PlanningError: for an unknown predicate or object.
        """
        name, args = predicate[0], predicate[1:]
        if name == "holding" and len(args) == 2:
            held = state.held_by(Status.HELD_LEAD if args[0] == LEAD else Status.HELD_SUPPORT)
            return held is not None and self.items[held].id == args[1]
        if name == "reachable" and len(args) == 2:
            return self.reachable(state, args[0], self.index(args[1]))
        if len(args) == 1:
            item = self.index(args[0])
            if name == "on_table":
                return state.status[item] is Status.TABLE
            if name == self.goal_predicate:
                return state.status[item] is Status.GOAL
            if name == "removable":
                return state.status[item] is Status.GOAL and self.can_release(state.goal, item)
        raise PlanningError(f"unknown predicate {predicate!r}")

    def bind(self, state: TabletopState[GoalT], op: Install[TargetT]) -> int | None:
        """The object the lead would use for ``op``: of its kind, on the table within reach, soonest at the
        target (travel and turns); ties go to the first object."""
        return self._binding(state, op)[0]

    def _binding(self, state: TabletopState[GoalT], op: Install[TargetT]) -> _Binding:
        """:meth:`bind`'s object, with the lead's seconds of travel to it and from it to the target and the
        quarter turns it needs (what :meth:`duration` adds up); remembered for the last state and operator,
        which the planner's estimates ask about three times in a row (preconditions, duration, effects)."""
        last_state, last_op, last = self._bound
        if last_state is state and (last_op is op or last_op == op):
            return last
        best: _Binding = (None, 0.0, 0.0, 0)
        kind = self.types.get(op.kind)
        if kind is not None:
            arm = self.lead_arm
            target = self.target_point(op.target)
            rotation = self.target_rotation(op.target)
            reach = self.layout.reach(True)
            hand = state.hands[0]
            poses, status = state.poses, state.status
            best_cost = float("inf")
            for item in self._by_kind.get(op.kind, ()):
                pose = poses[item]
                if status[item] is not Status.TABLE or pose is None or not reach.contains(pose.point):
                    continue  # (what reachable() says of an object on the table)
                there = arm.travel(hand, pose.point)
                turns = quarter_turns(pose.rotation, rotation, kind.symmetric)
                onward = arm.travel(pose.point, target)
                cost = there + arm.handling(turns=turns) + onward
                if cost < best_cost:
                    best, best_cost = (item, there, onward, turns), cost
        self._bound = (state, op, best)
        return best

    def preconditions_hold(
        self, state: TabletopState[GoalT], operator: TabletopOperator[TargetT], agent: str
    ) -> bool:
        """Install: an object of the kind is within the lead's reach and the target accepts it. Pick: the hand
        is empty and the object is within reach (in the goal area only if nothing rests on it). Put: the
        object is in this hand and the pose is free and within reach."""
        held_status = Status.HELD_LEAD if agent == LEAD else Status.HELD_SUPPORT
        if isinstance(operator, Install):
            return (
                agent == LEAD
                and state.held_by(Status.HELD_LEAD) is None
                and self.can_receive(state.goal, operator.kind, operator.target)
                and self.bind(state, operator) is not None
            )
        if isinstance(operator, Pick):
            item = operator.item
            status = state.status[item]
            if state.held_by(held_status) is not None or not self.reachable(state, agent, item):
                return False
            return status is Status.TABLE or (status is Status.GOAL and self.can_release(state.goal, item))
        if isinstance(operator, Put):
            return (
                state.status[operator.item] is held_status
                and self.layout.reach(agent == LEAD).contains(operator.pose.point)
                and self.is_free(state, operator.item, operator.pose)
            )
        raise PlanningError(f"not an operator of this world: {operator!r}")

    def apply(
        self, state: TabletopState[GoalT], operator: TabletopOperator[TargetT], agent: str
    ) -> TabletopState[GoalT]:
        """The state after the operator (its preconditions hold)."""
        if isinstance(operator, Install):
            item = self.bind(state, operator)
            if item is None:
                raise PlanningError(f"no {operator.kind} within the lead's reach")
            goal = self.receive(state.goal, item, operator.target)
            return state.changed(item, None, Status.GOAL, goal, (True, self.target_point(operator.target)))
        if isinstance(operator, Pick):
            item = operator.item
            lead = agent == LEAD
            status = Status.HELD_LEAD if lead else Status.HELD_SUPPORT
            pose = state.poses[item]
            if state.status[item] is Status.GOAL:
                goal = self.release(state.goal, item)
                pose = TablePose(*self.layout.goal_area.center, 0)
                return state.changed(item, pose, status, goal, (lead, pose.point))
            if pose is None:
                raise PlanningError(f"{self.items[item].id} lies nowhere")
            return state.changed(item, pose, status, None, (lead, pose.point))
        if isinstance(operator, Put):
            return state.changed(
                operator.item, operator.pose, Status.TABLE, None, (agent == LEAD, operator.pose.point)
            )
        raise PlanningError(f"not an operator of this world: {operator!r}")

    def duration(self, state: TabletopState[GoalT], operator: TabletopOperator[TargetT], agent: str) -> float:
        """Seconds of motion: travel to the object, grasp, turn, travel to the target, release."""
        arm = self.arm(agent)
        hand = state.hands[0 if agent == LEAD else 1]
        if isinstance(operator, Install):
            item, there, onward, turns = self._binding(state, operator)
            if item is None:
                return float("inf")
            if agent != LEAD:  # the lead binds the object; another arm's travel is its own
                pose = state.poses[item]
                assert pose is not None  # bound: it lies on the table
                there, onward = arm.travel(hand, pose.point), arm.travel(pose.point, self.target_point(operator.target))
            return there + onward + arm.handling(grasps=1, turns=turns, releases=1)
        if isinstance(operator, Pick):
            return arm.travel(hand, self._point_of(state, operator.item)) + arm.handling(grasps=1)
        if isinstance(operator, Put):
            source = state.poses[operator.item]
            symmetric = self.types[self.items[operator.item].kind].symmetric
            turns = 0 if source is None else quarter_turns(source.rotation, operator.pose.rotation, symmetric)
            return arm.travel(hand, operator.pose.point) + arm.handling(turns=turns, releases=1)
        raise PlanningError(f"not an operator of this world: {operator!r}")

    def resources(
        self, state: TabletopState[GoalT], operator: TabletopOperator[TargetT], agent: str
    ) -> frozenset[Hashable]:
        """The object, the space cells under it (where it lies, or where it goes) and, for Install, the goal
        area."""
        if isinstance(operator, Install):
            item = self.bind(state, operator)
            pose = state.poses[item] if item is not None else None
            if item is None or pose is None:
                return frozenset({_GOAL_AREA})
            return frozenset({item, _GOAL_AREA}) | self.layout.cells(self.footprint_of(item, pose))
        if isinstance(operator, Pick):
            pose = state.poses[operator.item]
            if state.status[operator.item] is Status.GOAL or pose is None:
                return frozenset({operator.item, _GOAL_AREA})
            return frozenset({operator.item}) | self.layout.cells(self.footprint_of(operator.item, pose))
        if isinstance(operator, Put):
            return frozenset({operator.item}) | self.layout.cells(
                self.footprint_of(operator.item, operator.pose)
            )
        raise PlanningError(f"not an operator of this world: {operator!r}")

    def effects(
        self, state: TabletopState[GoalT], operator: TabletopOperator[TargetT], agent: str
    ) -> Effects:
        """Install: on_table(x) → <goal_predicate>(x). Pick: on_table(x) or <goal_predicate>(x) →
        holding(agent, x). Put: holding(agent, x) → on_table(x)."""
        if isinstance(operator, Install):
            item = self.bind(state, operator)
            if item is None:
                return Effects()
            name = self.items[item].id
            return Effects(frozenset({(self.goal_predicate, name)}), frozenset({("on_table", name)}))
        if isinstance(operator, Pick):
            name = self.items[operator.item].id
            was = self.goal_predicate if state.status[operator.item] is Status.GOAL else "on_table"
            return Effects(frozenset({("holding", agent, name)}), frozenset({(was, name)}))
        if isinstance(operator, Put):
            name = self.items[operator.item].id
            return Effects(frozenset({("on_table", name)}), frozenset({("holding", agent, name)}))
        raise PlanningError(f"not an operator of this world: {operator!r}")

    def remaining_plan(
        self, state: TabletopState[GoalT], plan: Sequence[TabletopOperator[TargetT]]
    ) -> tuple[TabletopOperator[TargetT], ...] | None:
        """The plan's steps still to do (see :meth:`remaining_installs`)."""
        return self.remaining_installs(state, plan)

    def remaining_installs(
        self, state: TabletopState[GoalT], plan: Sequence[TabletopOperator[TargetT]]
    ) -> tuple[Install[TargetT], ...] | None:
        """The plan's steps whose target does not hold their kind yet; None when the goal area holds
        something the plan does not put there.

        Raises:
            PlanningError: for a lead plan with a step that is not an Install.
        """
        steps = [op for op in plan if isinstance(op, Install)]
        if len(steps) != len(plan):
            raise PlanningError("a lead plan of a tabletop world installs objects: every step is an Install")
        done = self.installed(state.goal)
        wanted = {op.target: op.kind for op in steps}
        if any(wanted.get(target) != kind for target, kind in done.items()):
            return None
        return tuple(op for op in steps if done.get(op.target) != op.kind)

    def sample_moves(self, state: TabletopState[GoalT], rng: np.random.Generator, count: int) -> list[Move]:
        """``count`` single-object moves (§3.2.5.1: "a randomly sampled new location and/or pose"): an object
        not in anyone's hand, then, each a third of the time, a new rotation where it lies, a new location
        with its rotation, or both; locations come from the layout's placement sampler (whole centimetres).
        Objects in the goal area are drawn too; it is P that forbids moving them."""
        movable = [i for i, s in enumerate(state.status) if s in (Status.TABLE, Status.GOAL)]
        if not movable:
            return []
        moves = []
        for _ in range(count):
            item = movable[int(rng.integers(len(movable)))]
            pose = state.poses[item]
            mode = int(rng.integers(3)) if pose is not None and state.status[item] is Status.TABLE else 2
            if mode == 0 and pose is not None:
                x, y = pose.x, pose.y
            else:
                x, y = self.layout.sample_placement(rng)
                x = round(x / _POSITION_STEP) * _POSITION_STEP
                y = round(y / _POSITION_STEP) * _POSITION_STEP
            rotation = pose.rotation if mode == 1 and pose is not None else int(rng.integers(4))
            moves.append(Move(item, TablePose(x, y, rotation)))
        return moves

    def support_plan(self, state: TabletopState[GoalT], move: Move) -> tuple[Pick, Put] | None:
        """Pick the object, put it at the new pose; None when the pose is not free or out of reach, or it is
        where the object already lies."""
        if state.poses[move.item] == move.pose and state.status[move.item] is Status.TABLE:
            return None
        if not self.layout.reach(False).contains(move.pose.point) or not self.is_free(
            state, move.item, move.pose
        ):
            return None
        if not self.reachable(state, SUPPORT, move.item):
            return None
        return (Pick(move.item), Put(move.item, move.pose))

    def describe(self, operator: TabletopOperator[TargetT]) -> str:
        """The operator in a few words."""
        if isinstance(operator, Install):
            return f"install a {operator.kind} at {self.describe_target(operator.target)}"
        if isinstance(operator, Pick):
            return f"pick up {self.items[operator.item].id}"
        if isinstance(operator, Put):
            pose = operator.pose
            where = (
                "in the tray"
                if self.layout.tray is not None and self.layout.tray.contains(pose.point)
                else "at"
            )
            return f"put {self.items[operator.item].id} {where} ({pose.x:.0f}, {pose.y:.0f}) cm, turned {90 * pose.rotation}°"
        raise PlanningError(f"not an operator of this world: {operator!r}")

    def nearest_free_pose(
        self, state: TabletopState[GoalT], item: int, point: Point, rotation: int
    ) -> TablePose | None:
        """The free pose nearest ``point`` (same rotation, then the others) for putting ``item`` down: rings of
        2 cm steps out to 40 cm; None if there is none."""
        for radius in range(0, 41, 2):
            steps = max(1, int(2 * np.pi * radius / 2))
            for k in range(steps):
                angle = 2 * np.pi * k / steps
                x = round(point[0] + radius * np.cos(angle))
                y = round(point[1] + radius * np.sin(angle))
                for turn in (rotation, *(r for r in range(4) if r != rotation)):
                    pose = TablePose(float(x), float(y), turn)
                    if self.is_free(state, item, pose):
                        return pose
        return None

    def _point_of(self, state: TabletopState[GoalT], item: int) -> Point:
        pose = state.poses[item]
        if state.status[item] is Status.GOAL or pose is None:
            return self.layout.goal_area.center
        return pose.point
