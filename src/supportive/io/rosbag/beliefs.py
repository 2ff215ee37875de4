"""Beliefs written back as a ROS 2 bag (MCAP), to look at beside the recording in Foxglove or RViz.

For every frame, at the frame's own time, under a namespace (default ``/supportive``):

| topic | type | what |
|---|---|---|
| ``belief`` | ``std_msgs/msg/String`` | the whole belief as JSON: the line ``supportive infer`` prints |
| ``subgoal`` | ``std_msgs/msg/String`` | the most probable current subgoal |
| ``subgoal/probability`` | ``std_msgs/msg/Float64`` | its probability |
| ``subtask`` | ``std_msgs/msg/String`` | the most probable enclosing subtask |
| ``subtask/probability`` | ``std_msgs/msg/Float64`` | its probability |
| ``next`` | ``std_msgs/msg/String`` | the most probable next subgoal |
| ``next/probability`` | ``std_msgs/msg/Float64`` | its probability |
| ``surprise`` | ``std_msgs/msg/Float64`` | how surprising the frame was, when the filter reports it |
| ``mistake/probability`` | ``std_msgs/msg/Float64`` | at a frame where a new step began: the probability it is a mistake |
| ``mistake`` | ``std_msgs/msg/String`` | at a frame where a step is judged a mistake: the verdict and the help the robot offers, as JSON |

and once, at the first frame's time, ``hierarchy`` (``std_msgs/msg/String``, latched: transient local QoS): the
learned hierarchy as ``supportive learn --format json`` writes it.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from types import TracebackType
from typing import Any, Self

from rosbags.interfaces import Connection

from supportive.io.rosbag.writing import BagWriter

__all__ = ["NAMESPACE", "BeliefBag"]

NAMESPACE = "/supportive"
_STRING = "std_msgs/msg/String"
_FLOAT = "std_msgs/msg/Float64"
_LABELS = (("subgoal", "subgoals"), ("subtask", "subtasks"), ("next", "next"))


class BeliefBag:
    """A new MCAP bag of beliefs, one frame at a time; use it as a context manager.

    Args:
        path: The bag's directory (must not exist).
        hierarchy: The learned hierarchy, as JSON data.
        namespace: Prefix of every topic.
    """

    def __init__(self, path: Path, hierarchy: Mapping[str, Any], namespace: str = NAMESPACE) -> None:
        self.writer = BagWriter(path, "mcap")
        self.hierarchy = hierarchy
        self.namespace = namespace.rstrip("/")
        self.frames = 0
        self._topics: dict[str, Connection] = {}

    def __enter__(self) -> Self:
        self.writer.__enter__()
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, trace: TracebackType | None
    ) -> None:
        self.writer.__exit__(kind, error, trace)

    def _topic(self, name: str, msgtype: str, *, latched: bool = False) -> Connection:
        if name not in self._topics:
            self._topics[name] = self.writer.topic(f"{self.namespace}/{name}", msgtype, latched=latched)
        return self._topics[name]

    def _write(self, name: str, msgtype: str, time: int, data: object, *, latched: bool = False) -> None:
        connection = self._topic(name, msgtype, latched=latched)
        self.writer.write(connection, time, self.writer.message(msgtype, data=data))

    def write(self, time: int, record: Mapping[str, Any]) -> None:
        """Write one frame's belief (the record ``infer`` prints) at ``time`` (ns on the recording's clock)."""
        if not self.frames:
            self._write("hierarchy", _STRING, time, json.dumps(self.hierarchy), latched=True)
        self.frames += 1
        self._write("belief", _STRING, time, json.dumps(record))
        for topic, key in _LABELS:
            ranked = record.get(key) or []
            if ranked:
                label, probability = ranked[0]
                self._write(topic, _STRING, time, str(label))
                self._write(f"{topic}/probability", _FLOAT, time, float(probability))
        surprise = record.get("surprise")
        if surprise is not None:
            self._write("surprise", _FLOAT, time, float(surprise))
        mistake = record.get("mistake")
        if mistake is not None:
            self._write("mistake/probability", _FLOAT, time, float(mistake["probability"]))
            if mistake["mistake"]:
                self._write("mistake", _STRING, time, json.dumps(mistake))
