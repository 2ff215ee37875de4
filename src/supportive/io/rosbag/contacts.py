"""Contact events in ROS bags: one message per moment (a frame), listing every pair of things that touch.

The convention (docs/ros.md): a contacts topic carries either

* ``std_msgs/msg/String`` — the touching pairs separated by commas or white space (``"hand-peg, peg-frame"``;
  an empty string: nothing touches), or
* any message with a ``string[] events`` field, such as ``supportive_msgs/msg/ContactFrame``
  (``std_msgs/Header header``, ``string[] events``).

A moment's time is the message's time in the bag (when it was recorded), which is also the time the beliefs
written back carry. Frames are read one at a time: a bag of any length streams in constant memory.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any

from rosbags.interfaces import Connection

from supportive.errors import BagError
from supportive.io.rosbag.bags import Bag, open_bag
from supportive.io.rosbag.types import CONTACT_FRAME
from supportive.io.rosbag.writing import BagWriter

__all__ = ["CONTACTS_TOPIC", "ContactFrame", "read_contact_frames", "write_contact_frames"]

CONTACTS_TOPIC = "/contacts"
_STRING = "std_msgs/msg/String"
_SEPARATORS = re.compile(r"[\s,]+")
_NOTHING = frozenset({""})

ContactFrame = tuple[frozenset[str], int]
"""The contact events that hold at one moment, and the moment's time in the bag (ns)."""


def _check_type(bag: Bag, connection: Connection) -> None:
    if connection.msgtype == _STRING:
        return
    fields = dict(bag.reader.typestore.fielddefs[connection.msgtype][1])
    if "events" not in fields:
        raise BagError(
            f"messages of type {connection.msgtype}; expected {_STRING} (the touching pairs, comma separated) "
            f"or a message with a string[] events field (like {CONTACT_FRAME})",
            path=bag.path,
            place=f"topic {connection.topic}",
        )


def _events(message: Any) -> frozenset[str]:
    events = getattr(message, "events", None)
    found = frozenset(_SEPARATORS.split(message.data) if events is None else events)
    return found - _NOTHING if "" in found else found


def read_contact_frames(
    path: Path, topic: str = CONTACTS_TOPIC, definitions: Sequence[Path] = ()
) -> Iterator[ContactFrame]:
    """The frames of a contacts topic, in time order, read as they are consumed.

    Raises:
        BagError: naming the bag and topic: a missing bag or topic, an empty topic, a wrong message type, a
            truncated or corrupt bag (raised when the damage is reached).
    """
    with open_bag(path, definitions) as bag:
        connections = bag.topic(topic)
        for connection in connections:
            _check_type(bag, connection)
        for _, time, message in bag.messages(connections):
            yield _events(message), time


def write_contact_frames(
    writer: BagWriter, frames: Iterable[ContactFrame], *, topic: str = CONTACTS_TOPIC, typed: bool = True
) -> int:
    """Write frames on a contacts topic, as ``supportive_msgs/msg/ContactFrame`` (``typed``, stamped with the
    frame's time) or as comma-separated ``std_msgs/msg/String``; how many were written."""
    connection = writer.topic(topic, CONTACT_FRAME if typed else _STRING)
    count = 0
    for events, time in frames:
        ordered = sorted(events)
        if typed:
            message = writer.message(CONTACT_FRAME, header=writer.header(time), events=ordered)
        else:
            message = writer.message(_STRING, data=",".join(ordered))
        writer.write(connection, time, message)
        count += 1
    return count
