"""Writing a new ROS bag: rosbag2 with MCAP (ROS 2's default since Iron) or SQLite3 storage, or a ROS 1
``.bag``; every message type defined in the bag, so any reader can decode it.

A bag is built in a hidden folder beside its destination and moved into place only once complete: a failure
leaves nothing behind, and an existing file or folder is never overwritten.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Sequence
from pathlib import Path
from types import TracebackType
from typing import Any, Literal, Self

from rosbags.interfaces import (
    Connection,
    Qos,
    QosDurability,
    QosHistory,
    QosLiveliness,
    QosReliability,
    QosTime,
)
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2

from supportive.errors import BagError
from supportive.io.rosbag.types import RosVersion, first_line, typestore

__all__ = ["LATCHED", "STORAGES", "BagWriter", "Storage"]

Storage = Literal["mcap", "sqlite3", "rosbag1"]
STORAGES: tuple[Storage, ...] = ("mcap", "sqlite3", "rosbag1")
"""Bag formats: rosbag2 with MCAP or SQLite3 storage, and ROS 1 bags."""

_INFINITE = QosTime(sec=9223372036, nsec=854775807)  # what rmw reports for "no limit"
LATCHED = Qos(
    history=QosHistory.KEEP_LAST,
    depth=1,
    reliability=QosReliability.RELIABLE,
    durability=QosDurability.TRANSIENT_LOCAL,
    deadline=_INFINITE,
    lifespan=_INFINITE,
    liveliness=QosLiveliness.AUTOMATIC,
    liveliness_lease_duration=_INFINITE,
    avoid_ros_namespace_conventions=False,
)
"""The QoS of a latched ROS 2 topic (transient local, reliable, keep last 1): a subscriber that comes late
still gets the last message, and ``ros2 bag play`` republishes it that way."""


class BagWriter:
    """A new bag, written message by message; use it as a context manager.

    Args:
        path: Where the bag goes: a directory for rosbag2, a ``.bag`` file for ROS 1. Must not exist.
        storage: ``mcap``, ``sqlite3`` or ``rosbag1``.
        definitions: Extra ``.msg`` / ``.idl`` files or folders for message types of one's own.

    Raises:
        BagError: when the destination exists or cannot be written.
    """

    def __init__(self, path: Path, storage: Storage = "mcap", definitions: Sequence[Path] = ()) -> None:
        if storage not in STORAGES:
            raise BagError(f"unknown bag format {storage!r}; choose {', '.join(STORAGES)}", path=path)
        if (storage == "rosbag1") != (path.suffix == ".bag"):
            want = "a .bag file" if storage == "rosbag1" else "a directory name without .bag"
            raise BagError(f"{storage} bags are written as {want}", path=path)
        if path.exists():
            raise BagError(
                "exists already; a bag is never overwritten: remove it or choose another", path=path
            )
        self.path = path
        self.storage: Storage = storage
        self.ros: RosVersion = 1 if storage == "rosbag1" else 2
        self.store = typestore(self.ros, definitions)
        self._staging: Path | None = None
        self._writer: Writer1 | Writer2 | None = None

    def __enter__(self) -> Self:
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._staging = Path(tempfile.mkdtemp(prefix=f".{self.path.name}.", dir=self.path.parent))
            target = self._staging / self.path.name
            if self.ros == 1:
                self._writer = Writer1(target)
            else:
                plugin = StoragePlugin.MCAP if self.storage == "mcap" else StoragePlugin.SQLITE3
                self._writer = Writer2(target, version=Writer2.VERSION_LATEST, storage_plugin=plugin)
            self._writer.open()
        except Exception as exc:  # rosbags' writers and the file system fail in many ways
            self._discard()
            raise BagError(f"cannot write the bag: {first_line(exc)}", path=self.path) from None
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, trace: TracebackType | None
    ) -> None:
        writer, self._writer = self._writer, None
        if writer is None:
            return
        if kind is not None:
            self._discard()
            return
        try:
            writer.close()
            if self._staging is None or self.path.exists():
                raise BagError("appeared while the bag was being written; not overwriting it", path=self.path)
            os.rename(self._staging / self.path.name, self.path)
        except BagError:
            self._discard()
            raise
        except Exception as exc:  # as above
            self._discard()
            raise BagError(f"cannot write the bag: {first_line(exc)}", path=self.path) from None
        self._discard()

    def _discard(self) -> None:
        if self._staging is not None:
            shutil.rmtree(self._staging, ignore_errors=True)
            self._staging = None

    def topic(self, name: str, msgtype: str, *, latched: bool = False) -> Connection:
        """Add a topic of one message type; ``latched`` makes it transient local (ROS 2) or latching (ROS 1)."""
        writer = self._open()
        if isinstance(writer, Writer1):
            return writer.add_connection(name, msgtype, typestore=self.store, latching=1 if latched else None)
        qos = [LATCHED] if latched else []
        return writer.add_connection(name, msgtype, typestore=self.store, offered_qos_profiles=qos)

    def message(self, msgtype: str, **fields: Any) -> object:
        """A message of this bag's type store: ``message("std_msgs/msg/String", data="hi")``."""
        return self.store.types[msgtype](**fields)

    def stamp(self, nanoseconds: int) -> object:
        """A ``builtin_interfaces/msg/Time`` (ROS 1: ``time``) at this time.

        Raises:
            BagError: for a time a stamp cannot hold (see :meth:`write`).
        """
        self._check_time(nanoseconds)
        sec, nanosec = divmod(nanoseconds, 1_000_000_000)
        return self.message("builtin_interfaces/msg/Time", sec=sec, nanosec=nanosec)

    def header(self, nanoseconds: int, frame_id: str = "") -> object:
        """A ``std_msgs/msg/Header`` stamped at this time (ROS 1's carries a zero ``seq``)."""
        extra: dict[str, Any] = {"seq": 0} if self.ros == 1 else {}
        return self.message("std_msgs/msg/Header", stamp=self.stamp(nanoseconds), frame_id=frame_id, **extra)

    def write(self, connection: Connection, nanoseconds: int, message: object) -> None:
        """Write one message, received at ``nanoseconds`` on the bag's clock.

        Raises:
            BagError: for a time outside 0 to ``2**31 - 1`` seconds (1970 to 2038: what a ROS 2 stamp's signed
                32-bit seconds hold, and within ROS 1's unsigned ones); the bag is then not made.
        """
        self._check_time(nanoseconds)
        writer = self._open()
        msgtype = connection.msgtype
        if isinstance(writer, Writer1):
            writer.write(connection, nanoseconds, self.store.serialize_ros1(message, msgtype))
        else:
            writer.write(connection, nanoseconds, self.store.serialize_cdr(message, msgtype))

    def _check_time(self, nanoseconds: int) -> None:
        if not 0 <= nanoseconds < 2**31 * 1_000_000_000:
            raise BagError(
                f"a message at {nanoseconds / 1e9:,.0f} s: a bag holds times from 0 to 2,147,483,647 s (1970 to 2038)",
                path=self.path,
            )

    def _open(self) -> Writer1 | Writer2:
        if self._writer is None:
            raise BagError("the bag is not open for writing (use the writer in a with block)", path=self.path)
        return self._writer
