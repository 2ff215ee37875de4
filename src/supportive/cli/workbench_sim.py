"""``supportive workbench-sim``: the Collaborative Workbench's whole loop on one machine (§3.4).

A board service runs the construction task (``examples/workbench-blocks.yaml``); a simulated person and a
simulated robot arm are both clients of its HTTP API. The person's hand follows a script (posted as hand
positions, and its claims and completions go through the board like anyone's); the robot reads the person's
social force from the service (the ellipse it serves), decides with a role policy, claims, moves its end
effector through its skill's keyframes (posting its positions too), and completes — as a student (the
person's gestures are cues it follows), a peer (it keeps out of the person's way and gives up a subtask the
person moves into) or an instructor (it demonstrates the next skill in growing stages until the person
starts it).

Time is simulated (ticks of ``dt`` seconds, sent as the hand positions' timestamps), so a run takes as long
as the requests do and the same seed gives the same story.
"""

from __future__ import annotations

import itertools
import math
import tempfile
import threading
import time
from collections import Counter
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import httpx
import numpy as np
from numpy.typing import ArrayLike, NDArray

from supportive.errors import ServiceError, SocialError
from supportive.examples import path as example_path
from supportive.io.taskfile import parse_task_file
from supportive.social.ellipse import ForceEllipse
from supportive.social.instructor import InstructorPolicy
from supportive.social.roles import Candidate, PeerPolicy, RoleAction, RoleDecision, StudentPolicy
from supportive.tasks.spec import Action, TaskSpec

__all__ = ["ROLES", "BoardClient", "Line", "ServedForce", "run_workbench", "serve_in_background"]

RoleName = Literal["student", "peer", "instructor"]
ROLES: tuple[RoleName, ...] = ("student", "peer", "instructor")
"""The robot's roles."""

PERSON = ("alice", "alice-token")
ROBOT = ("robot", "robot-token")
_SPEED = 0.5  # metres per second, the robot's end effector
_DWELL = 0.4  # seconds at each keyframe
_REST_PERSON = (0.9, 0.72)
_REST_ROBOT = (0.665, 0.62)


@dataclass(frozen=True)
class Line:
    """One line of the story: when (simulated seconds), who, what."""

    t: float
    who: str
    text: str

    def __str__(self) -> str:
        return f"{self.t:5.1f} s  {self.who:6}  {self.text}"


class BoardClient:
    """The board API for one agent (httpx, keep-alive).

    Raises:
        SupportiveError: from every call, when the service answers with an error the caller did not expect.
    """

    def __init__(self, url: str, token: str) -> None:
        self.http = httpx.Client(base_url=url, headers={"Authorization": f"Bearer {token}"}, timeout=30)

    def board(self) -> dict[str, Any]:
        """The board."""
        data: dict[str, Any] = self._json(self.http.get("/api/board"))
        return data

    def operate(self, op: str, node: str) -> bool:
        """Claim, release or complete ``node``: True when the board accepted it (a 409 is a refusal)."""
        response = self.http.post(f"/api/nodes/{node}/{op}")
        if response.status_code == 409:
            return False
        self._json(response)
        return True

    def hand(self, t: float, point: tuple[float, float]) -> None:
        """Post where this agent's hand is at simulated time ``t``."""
        self._json(self.http.post("/api/hands", json={"x": point[0], "y": point[1], "t": t}))

    def force_of_others(self, me: str) -> ServedForce:
        """The other agents' social force, from the ellipses the service serves."""
        agents = self._json(self.http.get("/api/social", params={"nx": 2, "ny": 2, "exclude": me}))["agents"]
        return ServedForce(
            tuple(
                ForceEllipse(
                    tuple(e["center"]), tuple(e["half_axes"]), (tuple(e["axes"][0]), tuple(e["axes"][1]))
                )
                for a in agents
                if a["id"] != me and (e := a["ellipse"]) is not None
            )
        )

    def close(self) -> None:
        """Close the connection."""
        self.http.close()

    @staticmethod
    def _json(response: httpx.Response) -> Any:
        if response.status_code >= 400:
            raise ServiceError(f"the board answered {response.status_code}: {response.text}")
        return response.json()


@dataclass(frozen=True)
class ServedForce:
    """Other agents' force as the service serves it: the largest of their ellipses' forces."""

    ellipses: tuple[ForceEllipse, ...]

    def field(self, points: ArrayLike) -> NDArray[np.float64]:
        """The force at each point, in [0, 1]."""
        xy = np.asarray(points, dtype=float).reshape(-1, 2)
        if not self.ellipses:
            return np.zeros(len(xy))
        combined: NDArray[np.float64] = np.max([e.field(xy) for e in self.ellipses], axis=0)
        return combined


@contextmanager
def serve_in_background(task: Path | None = None) -> Iterator[str]:
    """A board service for the workbench task on 127.0.0.1 in this process (a temporary SQLite database),
    with the person and the robot as agents; yields its URL."""
    import uvicorn

    from supportive.service.app import create_app
    from supportive.service.launch import free_port
    from supportive.service.settings import ServiceSettings, board_of, parse_agent

    spec = parse_task_file(task or example_path("workbench-blocks"))
    with tempfile.TemporaryDirectory() as directory:
        settings = ServiceSettings(
            f"sqlite:///{Path(directory) / 'workbench.db'}",
            board_of(spec),
            (
                parse_agent(f"{PERSON[0]}:human:lead:{PERSON[1]}"),
                parse_agent(f"{ROBOT[0]}:robot:lead:{ROBOT[1]}"),
            ),
            spec,
        )
        port = free_port()
        server = uvicorn.Server(
            uvicorn.Config(create_app(settings), host="127.0.0.1", port=port, log_level="warning")
        )
        thread = threading.Thread(target=server.run, daemon=True)
        thread.start()
        url = f"http://127.0.0.1:{port}"
        for _ in range(300):
            if server.started:
                break
            time.sleep(0.02)
        try:
            yield url
        finally:
            server.should_exit = True
            thread.join(10)


@dataclass
class _Arm:
    """The robot's end effector: where it is and the keyframes it is moving through (it stays ``_DWELL``
    seconds at each: a keyframe is a pose to reach, a gripper to open or close)."""

    position: tuple[float, float] = _REST_ROBOT
    route: list[tuple[float, float]] = field(default_factory=list)
    waited: float = 0.0

    def go(self, points: Sequence[tuple[float, float]]) -> None:
        """Move through ``points``, in order."""
        self.route = list(points)
        self.waited = 0.0

    def step(self, dt: float) -> bool:
        """Move (or dwell) for ``dt`` seconds; True once the route is done."""
        budget = dt
        while self.route and budget > 1e-12:
            target = self.route[0]
            gap = math.dist(self.position, target)
            if gap > 1e-9:
                move = min(gap, _SPEED * budget)
                f = move / gap
                self.position = (
                    self.position[0] + f * (target[0] - self.position[0]),
                    self.position[1] + f * (target[1] - self.position[1]),
                )
                budget -= move / _SPEED
                continue
            stay = min(budget, _DWELL - self.waited)
            self.waited += stay
            budget -= stay
            if self.waited >= _DWELL - 1e-9:
                self.route.pop(0)
                self.waited = 0.0
        return not self.route


Script = Callable[[float], tuple[float, float]]
"""The person's hand position at a simulated time."""


def _glide(stops: Sequence[tuple[float, tuple[float, float]]]) -> Script:
    """A hand that is at each stop at its time and moves in a straight line between them."""

    def at(t: float) -> tuple[float, float]:
        if t <= stops[0][0]:
            return stops[0][1]
        for (t0, p0), (t1, p1) in itertools.pairwise(stops):
            if t <= t1:
                f = (t - t0) / (t1 - t0)
                return (p0[0] + f * (p1[0] - p0[0]), p0[1] + f * (p1[1] - p0[1]))
        return stops[-1][1]

    return at


class _Story:
    """The run's shared state: the clients, the clock, the lines told."""

    def __init__(self, url: str, spec: TaskSpec, tell: Callable[[Line], None], dt: float) -> None:
        self.person = BoardClient(url, PERSON[1])
        self.robot = BoardClient(url, ROBOT[1])
        self.spec = spec
        self.actions = {a.id: a for a in spec.actions}
        self.tell = tell
        self.dt = dt
        self.t = 0.0
        self.lines: list[Line] = []
        self.arm = _Arm()
        self.done_by: Counter[str] = Counter()

    def say(self, who: str, text: str) -> None:
        """Tell a line; an action id quoted in it (``'pick_red'``, as the role policies name subtasks) is said
        by its text (``'pick up the red block'``), as the person's lines say it."""
        for action in self.actions.values():
            if action.text and action.text != action.id:
                text = text.replace(repr(action.id), repr(action.text))
        line = Line(round(self.t, 2), who, text)
        self.lines.append(line)
        self.tell(line)

    def completed(self, who: str, action: str) -> None:
        """Count a subtask ``who`` completed, and tell it."""
        self.done_by[who] += 1
        self.say(who, f"completed {action!r}")

    def summary(self, seconds: float) -> str:
        """The run in one line: how long it took, which subtasks each agent completed, whether the task is done."""
        nodes = self.nodes()
        done = sum(n["done"] for n in nodes.values())
        by = ", ".join(f"{who} {count}" for who, count in sorted(self.done_by.items())) or "nobody"
        end = "the task is finished" if done == len(nodes) else f"stopped at {seconds:g} s, the task unfinished"
        return f"after {self.t:.1f} s: {done} of {len(nodes)} subtasks done ({by}); {end}"

    def nodes(self) -> dict[str, dict[str, Any]]:
        """The board's action nodes by action id."""
        return {n["action"]: n for n in self.robot.board()["nodes"] if n["kind"] == "action"}

    def candidates(self) -> list[Candidate]:
        """The actions the robot could take now: not done, ready, with keyframes."""
        out = []
        for action, node in self.nodes().items():
            if node["done"] or not node["ready"] or not self.actions[action].keyframes:
                continue
            out.append(
                Candidate.from_action(
                    self.actions[action],
                    claimed=node["owner"] not in (None, ROBOT[0]),
                    current=node["owner"] == ROBOT[0],
                )
            )
        return out

    def tick(self, hand: Script) -> None:
        self.person.hand(self.t, hand(self.t))
        self.robot.hand(self.t, self.arm.position)

    def finished(self) -> bool:
        return all(n["done"] for n in self.nodes().values())

    def close(self) -> None:
        self.person.close()
        self.robot.close()


def _student(story: _Story, seconds: float, seed: int) -> None:
    """The person points at the blue block, then where it goes, then the red block, then the bases; the
    robot waits for each cue and does what is pointed at."""
    blue, green, red = (0.55, 0.30), (0.84, 0.35), (1.35, 0.30)
    cues = [
        (0.0, _REST_PERSON),
        (1.5, _REST_PERSON),
        (2.5, blue),
        (6.0, blue),
        (7.0, green),
        (12.0, green),
        (13.0, (0.665, 0.62)),
        (16.0, (0.665, 0.62)),
        (17.0, red),
        (21.0, red),
        (22.0, (0.915, 0.35)),
        (27.0, (0.915, 0.35)),
        (28.0, (1.165, 0.62)),
    ]
    hand = _glide(cues)
    policy = StudentPolicy(min_force=0.3, seed=seed)
    current: tuple[str, str] | None = None
    last: RoleDecision | None = None
    while story.t < seconds and not story.finished():
        story.tick(hand)
        if current is None:
            decision = policy.decide(story.candidates(), story.robot.force_of_others(ROBOT[0]))
            if decision.action is RoleAction.START and decision.subtask is not None:
                node = story.nodes()[decision.subtask]["id"]
                if story.robot.operate("claim", node):
                    current = (decision.subtask, node)
                    story.arm.go([k.point for k in story.actions[decision.subtask].keyframes])
                    story.say("robot", f"student: {decision.reason}")
            elif last is None or decision.action != last.action:
                story.say("robot", f"student: {decision.reason}")
            last = decision
        elif story.arm.step(story.dt):
            story.robot.operate("complete", current[1])
            story.completed("robot", current[0])
            current = None
        story.t += story.dt


def _peer(story: _Story, seconds: float, seed: int) -> None:
    """The person works at the blue block; the robot, a peer, takes what keeps out of the person's way (the
    red block). Then the person reaches over for the red block: the robot gives it up and takes the blue
    block, now free of the person; the person picks up the red block."""
    hand = _glide(
        [
            (0.0, (0.55, 0.30)),
            (0.6, (0.55, 0.30)),
            (1.0, (1.35, 0.30)),
            (3.5, (1.35, 0.30)),
            (4.5, _REST_PERSON),
        ]
    )
    policy = PeerPolicy(switch_margin=0.2, halt_below=-0.5, seed=seed)
    current: tuple[str, str] | None = None
    said: set[str] = set()
    red = story.nodes()["pick_red"]["id"]
    person_red = "free"
    while story.t < seconds and not story.finished():
        story.tick(hand)
        decision = policy.decide(story.candidates(), story.robot.force_of_others(ROBOT[0]))
        if decision.action in (RoleAction.START, RoleAction.SWITCH) and decision.subtask is not None:
            if current is not None:
                story.robot.operate("release", current[1])
            node = story.nodes()[decision.subtask]["id"]
            if story.robot.operate("claim", node):
                current = (decision.subtask, node)
                story.arm.go([k.point for k in story.actions[decision.subtask].keyframes])
                story.say("robot", f"peer: {decision.reason}")
        elif decision.action in (RoleAction.HALT, RoleAction.IDLE) and decision.reason not in said:
            story.say("robot", f"peer: {decision.reason}")
            said.add(decision.reason)
        if decision.action is not RoleAction.HALT and current is not None and story.arm.step(story.dt):
            story.robot.operate("complete", current[1])
            story.completed("robot", current[0])
            current = None
        if person_red == "free" and story.t >= 1.2 and story.person.operate("claim", red):
            person_red = "claimed"
            story.say("alice", "claims 'pick up the red block'")
        elif person_red == "claimed" and story.t >= 3.0 and story.person.operate("complete", red):
            person_red = "done"
            story.done_by["alice"] += 1
            story.say("alice", "picked up the red block")
        story.t += story.dt


def _instructor(story: _Story, seconds: float, seed: int) -> None:
    """The robot teaches the red branch first: it demonstrates picking up the red block in growing stages,
    short of grasping it, until the person reaches for the red block; then the person does it."""
    order = [story.actions[a] for a in ("pick_red", "locate_blue")]
    teacher = InstructorPolicy(trigger=0.3, skills=order)
    hand = _glide(
        [
            (0.0, _REST_PERSON),
            (9.0, _REST_PERSON),
            (10.5, (1.35, 0.30)),
            (14.0, (1.35, 0.30)),
            (15.0, _REST_PERSON),
            (24.0, _REST_PERSON),
            (25.5, (0.55, 0.30)),
        ]
    )
    skill: Action | None = None
    shown: tuple[Action | None, int] | None = None  # the skill and repetition last told
    while story.t < seconds and not teacher.done:
        story.tick(hand)
        if teacher.skill is not skill:
            skill = teacher.skill
            if skill is not None:
                story.say("robot", f"instructor: shows how to {skill.text}")
        if story.arm.step(story.dt):
            reading = teacher.reading(story.robot.force_of_others(ROBOT[0]))
            target = teacher.next_target(min(1.0, reading))
            if target is None:
                taken = teacher.taken_up[-1]
                story.say(
                    "robot",
                    f"instructor: the student has begun {taken!r} (force {reading:.2f}): stops showing",
                )
                node = story.nodes()[taken]["id"]
                if story.person.operate("claim", node) and story.person.operate("complete", node):
                    story.done_by["alice"] += 1
                    story.say("alice", f"does {story.actions[taken].text!r}")
                story.arm.go([_REST_ROBOT])
            else:
                if (skill, teacher.repetition) != shown:
                    steps = " -> ".join(k.text or f"({k.x}, {k.y})" for k in teacher.cycle())
                    story.say("robot", f"instructor: repetition {teacher.repetition}: {steps}")
                    shown = (skill, teacher.repetition)
                story.arm.go([target.point])
        story.t += story.dt
    del seed


_SCENARIOS: dict[RoleName, Callable[[_Story, float, int], None]] = {
    "student": _student,
    "peer": _peer,
    "instructor": _instructor,
}


def run_workbench(
    role: RoleName,
    *,
    url: str | None = None,
    seconds: float = 40.0,
    dt: float = 0.1,
    seed: int = 0,
    tell: Callable[[Line], None] = lambda line: None,
) -> list[Line]:
    """Run the workbench loop with the robot in ``role``; the story, line by line.

    The story ends with a line by ``board``: how long the run took, the subtasks each agent completed, and
    whether the task is finished.

    Args:
        role: ``student``, ``peer`` or ``instructor``.
        url: A running board service of the workbench task with agents ``alice`` (token ``alice-token``) and
            ``robot`` (``robot-token``); None starts one in this process.
        seconds: Simulated seconds at most.
        dt: The simulation's tick.
        seed: Breaks the role policies' ties.
        tell: Called with each line as it happens.

    Raises:
        SupportiveError: for an unknown role, or a service that refuses what the simulation needs.
    """
    if role not in _SCENARIOS:
        raise SocialError(f"unknown role {role!r}: choose {', '.join(ROLES)}")
    spec = parse_task_file(example_path("workbench-blocks"))
    if url is None:
        with serve_in_background() as local:
            return _run(local, spec, role, seconds, dt, seed, tell)
    return _run(url, spec, role, seconds, dt, seed, tell)


def _run(
    url: str,
    spec: TaskSpec,
    role: RoleName,
    seconds: float,
    dt: float,
    seed: int,
    tell: Callable[[Line], None],
) -> list[Line]:
    story = _Story(url, spec, tell, dt)
    try:
        _SCENARIOS[role](story, seconds, seed)
        story.say("board", story.summary(seconds))
    finally:
        story.close()
    return story.lines
