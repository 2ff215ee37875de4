"""Demonstrations in ROS bags: read each bag (or each segment of one) as a demonstration, and write a task's
demonstrations into a bag.

The convention (docs/ros.md):

* **Actions** on one topic (default ``/task/action``), either ``std_msgs/msg/String`` — the action id, published
  when the action starts — or any message with fields ``action`` (string), ``start`` and ``end``
  (``builtin_interfaces/Time`` on the bag's clock, or ``float64`` seconds on it), such as
  ``supportive_msgs/msg/ActionSpan``; a zero ``end`` means the end is not known.
* **Segments**, optionally, on another topic (``/task/demonstration`` by ``bag export``): each message starts a
  new demonstration. ``std_msgs/msg/String`` names it (its ``data``), ``std_msgs/msg/Empty`` just marks it, and
  a message with ``id`` and ``agent`` string fields (``supportive_msgs/msg/Demonstration``) names it and who
  performed it. Without a segment topic the whole bag is one demonstration, named after the bag.
* **Times** in the task file are seconds since the demonstration began: its segment marker, or the bag's first
  message (where a player's clock starts; or the earliest start, for an action that began before the
  recording did). Steps are ordered by start.
"""

from __future__ import annotations

import bisect
from collections.abc import Callable, Collection, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rosbags.interfaces import Connection

from supportive.errors import BagError
from supportive.io.rosbag.bags import Bag, open_bag, seconds
from supportive.io.rosbag.types import ACTION_SPAN, DEMONSTRATION
from supportive.io.rosbag.writing import BagWriter
from supportive.io.values import check_id
from supportive.tasks.spec import Demonstration, Step

__all__ = [
    "ACTIONS_TOPIC",
    "SEGMENT_TOPIC",
    "import_demonstrations",
    "read_demonstrations",
    "write_demonstrations",
]

ACTIONS_TOPIC = "/task/action"
SEGMENT_TOPIC = "/task/demonstration"
_STRING = "std_msgs/msg/String"
_EMPTY = "std_msgs/msg/Empty"
_SECOND = 1_000_000_000


@dataclass(frozen=True)
class _Marker:
    time: int
    id: str | None
    agent: str | None


@dataclass(frozen=True)
class _Action:
    time: int
    action: str
    start: int
    end: int | None


def _nanoseconds(value: Any) -> int:
    """A ``builtin_interfaces/Time`` or a number of seconds, in nanoseconds."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return round(value * _SECOND)
    return int(value.sec) * _SECOND + int(value.nanosec)


def _fields(bag: Bag, connection: Connection) -> set[str]:
    return {name for name, _ in bag.reader.typestore.fielddefs[connection.msgtype][1]}


def _action_reader(bag: Bag, connection: Connection) -> Callable[[Any, int], _Action]:
    topic = connection.topic
    if connection.msgtype == _STRING:
        return lambda msg, time: _Action(time, str(msg.data).strip(), time, None)
    if {"action", "start", "end"} <= _fields(bag, connection):

        def span(msg: Any, time: int) -> _Action:
            start, end = (_nanoseconds(getattr(msg, key)) for key in ("start", "end"))
            return _Action(time, str(msg.action).strip(), start or time, end or None)

        return span
    raise BagError(
        f"messages of type {connection.msgtype}; expected {_STRING} (the action id) or a message with "
        f"fields action, start and end (like {ACTION_SPAN})",
        path=bag.path,
        place=f"topic {topic}",
    )


def _marker_reader(bag: Bag, connection: Connection) -> Callable[[Any, int], _Marker]:
    if connection.msgtype == _STRING:
        return lambda msg, time: _Marker(time, str(msg.data).strip() or None, None)
    if connection.msgtype == _EMPTY:
        return lambda msg, time: _Marker(time, None, None)
    if "id" in _fields(bag, connection):
        return lambda msg, time: _Marker(
            time, str(msg.id).strip() or None, str(getattr(msg, "agent", "")).strip() or None
        )
    raise BagError(
        f"messages of type {connection.msgtype}; expected {_STRING} (the demonstration's id), {_EMPTY}, or a "
        f"message with fields id and agent (like {DEMONSTRATION})",
        path=bag.path,
        place=f"topic {connection.topic}",
    )


def read_demonstrations(
    path: Path,
    *,
    actions_topic: str = ACTIONS_TOPIC,
    segment_topic: str | None = None,
    agent: str | None = None,
    vocabulary: Collection[str] | None = None,
    definitions: Sequence[Path] = (),
) -> list[Demonstration]:
    """The demonstrations one bag holds (see the module's convention).

    Args:
        path: The bag.
        actions_topic: Where the actions are.
        segment_topic: Where the segment markers are, if the bag holds several demonstrations.
        agent: Who performed them, where the bag does not say.
        vocabulary: The known action ids; another id is an error. ``None``: any id.
        definitions: ``.msg`` / ``.idl`` files or folders for message types the bag does not define.

    Raises:
        BagError: naming the bag, the topic and the problem: a missing bag or topic, an empty topic, a wrong
            message type, an unknown or empty action id, an end before its start, an empty segment, actions
            before the first segment marker, a truncated or corrupt bag.
    """
    with open_bag(path, definitions) as bag:
        action_connections = bag.topic(actions_topic)
        read_action = {c.id: _action_reader(bag, c) for c in action_connections}
        marker_connections = bag.topic(segment_topic) if segment_topic is not None else []
        read_marker = {c.id: _marker_reader(bag, c) for c in marker_connections}
        actions: list[_Action] = []
        markers: list[_Marker] = []
        for connection, time, message in bag.messages([*action_connections, *marker_connections]):
            if connection.topic == actions_topic and connection.id in read_action:
                actions.append(
                    _checked(bag, actions_topic, read_action[connection.id](message, time), vocabulary)
                )
            else:
                markers.append(read_marker[connection.id](message, time))
        if segment_topic is None:
            origin = min([bag.start_time, *(a.start for a in actions)])
            return [_demonstration(bag, actions_topic, actions, origin, bag.name, agent)]
        return _segments(bag, actions_topic, segment_topic, actions, markers, agent)


def _checked(bag: Bag, topic: str, action: _Action, vocabulary: Collection[str] | None) -> _Action:
    def fail(problem: str) -> BagError:
        return BagError(problem, path=bag.path, place=f"topic {topic}")

    when = f"at {seconds(action.time - bag.start_time):.3f} s"
    if not action.action:
        raise fail(f"an empty action id {when}")
    try:
        check_id(action.action, action=True, what=f"the action id of the message {when}")
    except ValueError as exc:
        raise fail(str(exc)) from None
    if vocabulary is not None and action.action not in vocabulary:
        raise fail(f"action {action.action!r} {when} is not one of the task's actions")
    if action.end is not None and action.end < action.start:
        raise fail(f"action {action.action!r} {when} ends before it starts")
    return action


def _segments(
    bag: Bag,
    topic: str,
    segment_topic: str,
    actions: list[_Action],
    markers: list[_Marker],
    agent: str | None,
) -> list[Demonstration]:
    times = [m.time for m in markers]
    groups: list[list[_Action]] = [[] for _ in markers]
    for action in actions:
        index = bisect.bisect_right(times, action.time) - 1
        if index < 0:
            raise BagError(
                f"action {action.action!r} at {seconds(action.time - bag.start_time):.3f} s comes before the "
                f"first demonstration marker on {segment_topic}",
                path=bag.path,
                place=f"topic {topic}",
            )
        groups[index].append(action)
    demonstrations = []
    for number, (marker, group) in enumerate(zip(markers, groups, strict=True), start=1):
        name = marker.id or f"{bag.name}-{number}"
        for value, what in ((marker.id, "id"), (marker.agent, "agent")):
            if value is not None:
                try:
                    check_id(value, what=f"the demonstration {what} of the marker at {seconds(marker.time - bag.start_time):.3f} s")
                except ValueError as exc:
                    raise BagError(str(exc), path=bag.path, place=f"topic {segment_topic}") from None
        if not group:
            raise BagError(
                f"demonstration {name!r} (marker at {seconds(marker.time - bag.start_time):.3f} s) has no actions",
                path=bag.path,
                place=f"topic {segment_topic}",
            )
        demonstrations.append(_demonstration(bag, topic, group, marker.time, name, marker.agent or agent))
    return demonstrations


def _demonstration(
    bag: Bag, topic: str, actions: list[_Action], origin: int, name: str, agent: str | None
) -> Demonstration:
    steps = []
    for action in sorted(actions, key=lambda a: a.start):
        if action.start < origin:
            raise BagError(
                f"action {action.action!r} starts before its demonstration {name!r} begins",
                path=bag.path,
                place=f"topic {topic}",
            )
        end = None if action.end is None else seconds(action.end - origin)
        steps.append(Step(action.action, seconds(action.start - origin), end))
    return Demonstration(tuple(steps), name, agent)


def import_demonstrations(
    paths: Iterable[Path],
    *,
    actions_topic: str = ACTIONS_TOPIC,
    segment_topic: str | None = None,
    agent: str | None = None,
    vocabulary: Collection[str] | None = None,
    definitions: Sequence[Path] = (),
) -> tuple[Demonstration, ...]:
    """The demonstrations of several bags, in order (see :func:`read_demonstrations`).

    Raises:
        BagError: for any bag's problem, or two demonstrations with the same id.
    """
    found: dict[str, Path] = {}
    demonstrations: list[Demonstration] = []
    for path in paths:
        for demo in read_demonstrations(
            path,
            actions_topic=actions_topic,
            segment_topic=segment_topic,
            agent=agent,
            vocabulary=vocabulary,
            definitions=definitions,
        ):
            assert demo.id is not None
            if demo.id in found:
                raise BagError(
                    f"demonstration id {demo.id!r} is also in {found[demo.id]}: name the segments apart",
                    path=path,
                )
            found[demo.id] = path
            demonstrations.append(demo)
    return tuple(demonstrations)


def write_demonstrations(
    writer: BagWriter,
    demonstrations: Sequence[Demonstration],
    *,
    start: int,
    actions_topic: str = ACTIONS_TOPIC,
    segment_topic: str = SEGMENT_TOPIC,
) -> list[int]:
    """Write demonstrations one after another, each after a marker on ``segment_topic`` (the next begins a
    second after the last step of the one before); when each begins (ns).

    A step's times are kept to the nanosecond. A step without a start comes one second after the step before
    it (the first: at its marker). When any step has an end, actions are ``supportive_msgs/msg/ActionSpan``
    (a zero end for steps without one), otherwise ``std_msgs/msg/String`` at the start.

    Args:
        writer: An open bag.
        demonstrations: What to write.
        start: When the first demonstration begins (ns on the bag's clock).
        actions_topic: Where the actions go.
        segment_topic: Where the markers go.
    """
    spans = any(step.end is not None for demo in demonstrations for step in demo.steps)
    action_type = ACTION_SPAN if spans else _STRING
    actions = writer.topic(actions_topic, action_type)
    markers = writer.topic(segment_topic, DEMONSTRATION)
    origin = start
    origins = []
    for demo in demonstrations:
        origins.append(origin)
        writer.write(markers, origin, writer.message(DEMONSTRATION, id=demo.id or "", agent=demo.agent or ""))
        time = origin
        latest = origin
        for index, step in enumerate(demo.steps):
            if step.start is not None:
                time = origin + round(step.start * _SECOND)
            elif index:
                time += _SECOND
            end = None if step.end is None else origin + round(step.end * _SECOND)
            latest = max(latest, time, end or time)
            if spans:
                message = writer.message(
                    ACTION_SPAN,
                    action=step.action,
                    start=writer.stamp(time),
                    end=writer.stamp(0 if end is None else end),
                )
            else:
                message = writer.message(_STRING, data=step.action)
            writer.write(actions, time, message)
        origin = latest + _SECOND
    return origins
