"""A lead and a support agent working at one table at the same time (§3.2.9.1): makespan, conflicts and
the lead's planning effort.

Time advances in ticks of ``dt`` seconds; within a tick each agent's motion segments (travel, or a pause to
grasp, turn or release) run on, and their ends change the world. Each agent is a generator of segments:

* the **lead** asks its policy for the next step, takes the object the step binds (the nearest of its kind),
  and installs it; if the object is gone when its hand gets there, or it had to yield, it plans again;
* the **support agent** asks its planner for the best supportive action at the current state (with the
  lead's object in hand counted as installed) and executes it; when doing nothing is best it goes home and
  waits for the lead's next step.

Collisions are modelled conservatively: each arm is the segment from its base to its hand, and when the two
come closer than ``buffer`` the agent using fewer resources (holding or going for an object counts one) must
yield — the lead wins ties. Yielding means putting down what it holds where it is (or at the nearest free
spot), going home and starting again; in practice it is the support agent that yields, as in the thesis.
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Generator, Hashable
from dataclasses import dataclass, field
from typing import Any, Generic, Protocol, TypeVar

from supportive.envs.tabletop.geometry import Point, segment_distance
from supportive.envs.tabletop.items import quarter_turns
from supportive.envs.tabletop.operators import Install, Pick, Put, TabletopOperator
from supportive.envs.tabletop.state import Status, TabletopState
from supportive.envs.tabletop.world import TabletopWorld
from supportive.errors import PlanningError
from supportive.planning.problem import SupportProblem
from supportive.planning.selection import SupportPlanner
from supportive.planning.world import LEAD, SUPPORT
from supportive.seeding import Seed

__all__ = ["Event", "LeadPolicy", "LeadStep", "TeamResult", "run_team"]

GoalT = TypeVar("GoalT")
TargetT = TypeVar("TargetT", bound=Hashable)

_WAIT = 0.5  # seconds to wait before looking again for an object that is in the other agent's hand


@dataclass(frozen=True)
class LeadStep(Generic[TargetT]):
    """What a lead policy says to do next, and what deciding cost it.

    Attributes:
        op: The next step, or None when the policy has nothing left to do.
        nodes: Search nodes expanded (or plan steps evaluated) to decide.
        seconds: Wall-clock seconds spent deciding.
        replanned: Whether the policy made a new plan (rather than taking the next step of its plan).
    """

    op: Install[TargetT] | None
    nodes: int = 0
    seconds: float = 0.0
    replanned: bool = False


class LeadPolicy(Protocol[GoalT, TargetT]):
    """How a lead chooses its steps."""

    def next_step(
        self, world: TabletopWorld[GoalT, TargetT], state: TabletopState[GoalT]
    ) -> LeadStep[TargetT]:
        """The next step from ``state``."""
        ...

    def interrupted(self) -> None:
        """The last step could not be finished (its object was taken, or the lead had to yield)."""
        ...


@dataclass(frozen=True)
class Event:
    """Something that happened: when, to whom, what."""

    time: float
    agent: str
    text: str


@dataclass
class TeamResult(Generic[GoalT]):
    """The outcome of one run.

    Attributes:
        completed: Whether the goal was reached before the time limit.
        makespan: Seconds until the goal was reached (the time limit if it was not).
        lead_steps: Objects the lead installed.
        lead_nodes: Search nodes the lead's policy expanded, over the whole run.
        lead_plans: How many times it made a new plan.
        lead_planning_seconds: Wall-clock seconds the lead's policy spent deciding.
        support_actions: Supportive actions finished.
        support_decisions: Times the support agent chose what to do.
        support_planning_seconds: Wall-clock seconds its planner spent.
        conflicts: Counts of what went wrong, by kind (``support yielded``, ``lead yielded``,
            ``object taken``, ``waited for an object``, ``waited for a plan``).
        final: The last state.
        events: What happened, in order.
    """

    completed: bool
    makespan: float
    lead_steps: int = 0
    lead_nodes: int = 0
    lead_plans: int = 0
    lead_planning_seconds: float = 0.0
    support_actions: int = 0
    support_decisions: int = 0
    support_planning_seconds: float = 0.0
    conflicts: Counter[str] = field(default_factory=Counter)
    final: TabletopState[GoalT] | None = None
    events: list[Event] = field(default_factory=list)


@dataclass
class _Segment:
    start: Point
    end: Point
    seconds: float
    elapsed: float = 0.0

    def position(self) -> Point:
        if self.seconds <= 0:
            return self.end
        f = min(1.0, self.elapsed / self.seconds)
        return (
            self.start[0] + f * (self.end[0] - self.start[0]),
            self.start[1] + f * (self.end[1] - self.start[1]),
        )


class _Yield(Exception):
    """Thrown into an agent's generator when it must yield to the other agent."""


Process = Generator[_Segment, None, None]


class _Run(Generic[GoalT, TargetT]):
    """One run's mutable world and the two agents' processes."""

    def __init__(
        self,
        world: TabletopWorld[GoalT, TargetT],
        lead: LeadPolicy[GoalT, TargetT],
        planner: SupportPlanner[Any, Any, Any] | None,
        plans: tuple[tuple[TabletopOperator[TargetT], ...], ...],
        seed: Seed,
        record: bool,
    ) -> None:
        self.world = world
        self.state = world.initial_state
        self.lead = lead
        self.planner = planner
        self.problem = SupportProblem.of(world, plans) if planner is not None and plans else None
        self.seed = seed
        self.record = record
        self.now = 0.0
        self.lead_version = 0  # counts the lead's finished steps
        self.busy = {LEAD: False, SUPPORT: False}  # holding or going for an object
        self.retreating = {LEAD: False, SUPPORT: False}
        self.hands = {LEAD: world.lead_arm.home, SUPPORT: world.support_arm.home}
        self.positions = dict(self.hands)  # where the hands are now, mid-segment included
        self.result: TeamResult[GoalT] = TeamResult(False, 0.0)
        self.lead_target: tuple[int, Install[TargetT]] | None = None  # the object the lead is going for

    # -- helpers -------------------------------------------------------------------------------------------

    def log(self, agent: str, text: str) -> None:
        if self.record:
            self.result.events.append(Event(round(self.now, 3), agent, text))

    def travel(self, agent: str, end: Point) -> _Segment:
        arm = self.world.arm(agent)
        return _Segment(self.hands[agent], end, arm.travel(self.hands[agent], end))

    def pause(self, agent: str, seconds: float) -> _Segment:
        return _Segment(self.hands[agent], self.hands[agent], seconds)

    def sync_hands(self) -> None:
        self.state = TabletopState(
            self.state.poses, self.state.status, self.state.goal, (self.hands[LEAD], self.hands[SUPPORT])
        )

    def put_down(self, agent: str, item: int) -> Process:
        """Put the held object down where the hand is, or at the nearest free spot."""
        pose = self.state.poses[item]
        rotation = pose.rotation if pose is not None else 0
        spot = self.world.nearest_free_pose(self.state, item, self.hands[agent], rotation)
        if spot is None and pose is not None and self.world.is_free(self.state, item, pose):
            spot = pose
        if spot is None:
            raise PlanningError(f"nowhere to put {self.world.items[item].id} down")
        yield self.travel(agent, spot.point)
        self.hands[agent] = spot.point
        yield self.pause(agent, self.world.arm(agent).handling(releases=1))
        self.state = self.state.moved(item, spot, Status.TABLE)
        self.log(agent, f"put {self.world.items[item].id} down at ({spot.x:.0f}, {spot.y:.0f})")

    def retreat(self, agent: str) -> Process:
        """Yield: put down whatever is held, go home."""
        self.retreating[agent] = True
        self.busy[agent] = False
        held = self.state.held_by(Status.HELD_LEAD if agent == LEAD else Status.HELD_SUPPORT)
        if held is not None:
            yield from self.put_down(agent, held)
        yield self.travel(agent, self.world.arm(agent).home)
        self.hands[agent] = self.world.arm(agent).home
        self.retreating[agent] = False

    def planning_view(self) -> tuple[TabletopState[GoalT], float]:
        """The state the lead is making — the object it is going for, or holds, counted as installed (the
        support agent sees where the lead's arm is going, so it plans around that object) — and the seconds
        the lead still needs to finish that step."""
        self.sync_hands()
        if self.lead_target is None:
            return self.state, 0.0
        item, op = self.lead_target
        status = self.state.status[item]
        if status not in (Status.TABLE, Status.HELD_LEAD):
            return self.state, 0.0
        world, arm, hand = self.world, self.world.lead_arm, self.positions[LEAD]
        target = world.target_point(op.target)
        pose = self.state.poses[item]
        if status is Status.TABLE and pose is not None:
            turns = quarter_turns(
                pose.rotation, world.target_rotation(op.target), world.types[op.kind].symmetric
            )
            left = (
                arm.travel(hand, pose.point)
                + arm.handling(grasps=1, turns=turns)
                + arm.travel(pose.point, target)
            )
        else:
            left = arm.travel(hand, target)
        goal = world.receive(self.state.goal, item, op.target)
        return self.state.changed(item, None, Status.GOAL, goal), left + arm.handling(releases=1)

    # -- the lead ------------------------------------------------------------------------------------------

    def lead_process(self) -> Process:
        while not self.world.goal_reached(self.state):
            try:
                finished = yield from self.lead_step()
            except _Yield:
                self.result.conflicts["lead yielded"] += 1
                self.lead_target = None
                self.log(LEAD, "yields to the support agent")
                yield from self.retreat(LEAD)
                self.lead.interrupted()
                continue
            if finished:
                return

    def lead_step(self) -> Generator[_Segment, None, bool]:
        """One step of the lead; True when the goal is reached. A policy with no step while the goal is not
        reached (its objects are in the other agent's hand, say) waits and asks again."""
        world = self.world
        self.sync_hands()
        step = self.lead.next_step(world, self.state)
        self.result.lead_nodes += step.nodes
        self.result.lead_planning_seconds += step.seconds
        self.result.lead_plans += step.replanned
        if step.op is None:
            if world.goal_reached(self.state):
                return True
            self.result.conflicts["waited for a plan"] += 1
            yield self.pause(LEAD, _WAIT)
            return False
        op = step.op
        item = world.bind(self.state, op)
        if item is None or not world.can_receive(self.state.goal, op.kind, op.target):
            self.result.conflicts["waited for an object"] += 1
            yield self.pause(LEAD, _WAIT)
            return False
        pose = self.state.poses[item]
        if pose is None:
            raise PlanningError(f"{world.items[item].id} lies nowhere")
        self.busy[LEAD] = True
        self.lead_target = (item, op)
        yield self.travel(LEAD, pose.point)
        self.hands[LEAD] = pose.point
        if self.state.status[item] is not Status.TABLE or self.state.poses[item] != pose:
            self.busy[LEAD] = False
            self.lead_target = None
            self.result.conflicts["object taken"] += 1
            self.log(LEAD, f"{world.items[item].id} is gone: plan again")
            self.lead.interrupted()
            return False
        self.state = self.state.moved(item, pose, Status.HELD_LEAD)
        turns = quarter_turns(pose.rotation, world.target_rotation(op.target), world.types[op.kind].symmetric)
        yield self.pause(LEAD, world.lead_arm.handling(grasps=1, turns=turns))
        target = world.target_point(op.target)
        yield self.travel(LEAD, target)
        self.hands[LEAD] = target
        yield self.pause(LEAD, world.lead_arm.handling(releases=1))
        goal = world.receive(self.state.goal, item, op.target)
        moved = self.state.moved(item, None, Status.GOAL)
        self.state = TabletopState(moved.poses, moved.status, goal, self.state.hands)
        self.lead_target = None
        self.busy[LEAD] = False
        self.lead_version += 1
        self.result.lead_steps += 1
        self.log(LEAD, f"installed {world.items[item].id} at {world.describe_target(op.target)}")
        return False

    # -- the support agent -----------------------------------------------------------------------------------

    def support_process(self) -> Process:
        if self.planner is None or self.problem is None:
            return
        seen = -1
        while not self.world.goal_reached(self.state):
            try:
                if seen == self.lead_version:
                    yield self.pause(SUPPORT, _WAIT)
                    continue
                acted = yield from self.support_step()
                if not acted:
                    seen = self.lead_version
            except _Yield:
                self.result.conflicts["support yielded"] += 1
                self.log(SUPPORT, "yields to the lead")
                yield from self.retreat(SUPPORT)
                seen = self.lead_version

    def support_step(self) -> Generator[_Segment, None, bool]:
        """Decide and act once; False when doing nothing was best (the agent then waits at home)."""
        world = self.world
        began = time.perf_counter()
        seed = self.seed + self.result.support_decisions if isinstance(self.seed, int) else self.seed
        decision = self.planner_decide(seed)
        self.result.support_planning_seconds += time.perf_counter() - began
        self.result.support_decisions += 1
        if not decision.helps:
            if self.hands[SUPPORT] != world.support_arm.home:
                yield self.travel(SUPPORT, world.support_arm.home)
                self.hands[SUPPORT] = world.support_arm.home
            return False
        pick, put = decision.chosen.plan
        if not isinstance(pick, Pick) or not isinstance(put, Put):
            raise PlanningError(
                f"the tabletop team runs pick-and-place support plans, got {decision.chosen.plan!r}"
            )
        item = pick.item
        pose = self.state.poses[item]
        if pose is None or self.state.status[item] is not Status.TABLE:
            return True
        self.busy[SUPPORT] = True
        yield self.travel(SUPPORT, pose.point)
        self.hands[SUPPORT] = pose.point
        if self.state.status[item] is not Status.TABLE or self.state.poses[item] != pose:
            self.busy[SUPPORT] = False
            self.result.conflicts["object taken"] += 1
            return True
        self.state = self.state.moved(item, pose, Status.HELD_SUPPORT)
        arm = world.support_arm
        yield self.pause(SUPPORT, arm.handling(grasps=1))
        yield self.travel(SUPPORT, put.pose.point)
        self.hands[SUPPORT] = put.pose.point
        turns = quarter_turns(pose.rotation, put.pose.rotation, world.types[world.items[item].kind].symmetric)
        yield self.pause(SUPPORT, arm.handling(turns=turns))
        if world.is_free(self.state, item, put.pose):
            yield self.pause(SUPPORT, arm.handling(releases=1))
            self.state = self.state.moved(item, put.pose, Status.TABLE)
            self.log(SUPPORT, world.describe(put))
        else:
            yield from self.put_down(SUPPORT, item)
        self.busy[SUPPORT] = False
        self.result.support_actions += 1
        return True

    def planner_decide(self, seed: Seed) -> Any:
        if self.planner is None or self.problem is None:
            raise PlanningError("no support planner")
        state, busy = self.planning_view()
        return self.planner.decide(self.problem.at(state, busy), seed)

    # -- the clock -----------------------------------------------------------------------------------------

    def must_yield(self, positions: dict[str, Point], buffer: float) -> str | None:
        """The agent that must yield now, if the arms are too close."""
        lead_home, support_home = self.world.lead_arm.home, self.world.support_arm.home
        if positions[LEAD] == lead_home or positions[SUPPORT] == support_home:
            return None
        if segment_distance(lead_home, positions[LEAD], support_home, positions[SUPPORT]) >= buffer:
            return None
        loser = LEAD if self.busy[LEAD] < self.busy[SUPPORT] else SUPPORT
        return None if self.retreating[loser] else loser

    def run(self, dt: float, limit: float, buffer: float) -> TeamResult[GoalT]:
        processes: dict[str, Process | None] = {LEAD: self.lead_process(), SUPPORT: self.support_process()}
        segments: dict[str, _Segment | None] = {LEAD: None, SUPPORT: None}
        positions = self.positions

        def resume(agent: str, throw: BaseException | None = None) -> None:
            process = processes[agent]
            segments[agent] = None
            if process is None:
                return
            try:
                segments[agent] = process.throw(throw) if throw is not None else next(process)
            except StopIteration:
                processes[agent] = None

        def advance(agent: str) -> None:
            left = dt
            while left > 0:
                if segments[agent] is None:
                    resume(agent)
                segment = segments[agent]
                if segment is None:
                    return
                need = segment.seconds - segment.elapsed
                if need > left:
                    segment.elapsed += left
                    positions[agent] = segment.position()
                    return
                left -= need
                positions[agent] = segment.end
                resume(agent)

        while self.now < limit and not self.world.goal_reached(self.state):
            advance(LEAD)
            if processes[LEAD] is None:
                break
            advance(SUPPORT)
            self.now += dt
            loser = self.must_yield(positions, buffer)
            if loser is not None:
                self.hands[loser] = positions[loser]
                resume(loser, _Yield())
        self.sync_hands()
        self.result.completed = self.world.goal_reached(self.state)
        self.result.makespan = round(min(self.now, limit), 3)
        self.result.final = self.state
        return self.result


def run_team(
    world: TabletopWorld[GoalT, TargetT],
    lead: LeadPolicy[GoalT, TargetT],
    planner: SupportPlanner[Any, Any, Any] | None = None,
    plans: tuple[tuple[TabletopOperator[TargetT], ...], ...] = (),
    *,
    seed: Seed = 0,
    dt: float = 0.05,
    limit: float = 1800.0,
    buffer: float = 6.0,
    record: bool = False,
) -> TeamResult[GoalT]:
    """Run the lead (and, given a planner, the support agent) from s_0 until the goal or ``limit`` seconds.

    Args:
        world: The world; its initial state is where the run starts.
        lead: The lead's policy.
        planner: The support agent's planner, fitted on ``plans``; None for a lead working alone.
        plans: Π_T, as the planner was fitted.
        seed: Seeds the support agent's sampling (an int: decision k uses ``seed + k``; a generator: every
            decision draws from it).
        dt: The clock's tick, seconds.
        limit: Give up after this many seconds.
        buffer: Least distance between the two arms, cm.
        record: Keep a list of events.

    Returns:
        The run's makespan, planning effort, conflicts and final state.
    """
    if dt <= 0 or limit <= 0 or buffer < 0:
        raise PlanningError("dt and limit must be > 0 and buffer >= 0")
    return _Run(world, lead, planner, plans, seed, record).run(dt, limit, buffer)
