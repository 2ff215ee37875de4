"""Opening a ROS bag and reading one topic's messages from it, every failure a :class:`BagError` naming the
bag and the topic.

A bag is a ROS 1 ``.bag`` file or a rosbag2 directory (``metadata.yaml`` beside ``.mcap`` or ``.db3`` files;
naming one of those files means its directory). Messages are read one at a time, in time order, so a topic of
any length is read in constant memory.
"""

from __future__ import annotations

import stat
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from rosbags.highlevel import AnyReader
from rosbags.interfaces import Connection
from rosbags.typesys import TypesysError

from supportive.errors import BagError
from supportive.io.rosbag.types import RosVersion, first_line, typestore

__all__ = ["Bag", "bag_name", "open_bag", "resolve_bag", "seconds"]


def seconds(nanoseconds: int) -> float:
    """A duration or time on the bag's clock, in seconds (exact to the nanosecond where a float can be).

    >>> seconds(2_500_000_000)
    2.5
    """
    return nanoseconds / 1e9


def resolve_bag(path: Path) -> tuple[Path, RosVersion]:
    """The bag a path names, and its ROS version.

    A rosbag2 directory's entries must be regular files or folders: a FIFO, socket or device in it (which
    would block the reader, or feed it without end) or a symbolic link that loops is refused before anything
    is opened.

    Raises:
        BagError: when the path is missing, is not a bag, or holds something that is not a file.
    """
    _check_entry(path, path)
    if path.is_file() and path.suffix in (".mcap", ".db3") and (path.parent / "metadata.yaml").is_file():
        _check_folder(path.parent)
        return path.parent, 2
    if path.is_file() and path.suffix == ".bag":
        return path, 1
    if path.is_dir() and (path / "metadata.yaml").is_file():
        _check_folder(path)
        return path, 2
    if not path.exists():
        raise BagError("no such bag", path=path)
    raise BagError(
        "not a ROS bag: expected a ROS 1 .bag file or a rosbag2 directory (with metadata.yaml)", path=path
    )


def _check_folder(folder: Path) -> None:
    for entry in sorted(folder.iterdir()):
        _check_entry(entry, folder)


def _check_entry(entry: Path, bag: Path) -> None:
    """Refuse a path that is a symbolic link that loops, or neither a regular file nor a folder."""
    try:
        mode = entry.stat().st_mode
    except FileNotFoundError:
        if entry.is_symlink():
            raise BagError(f"{entry.name} is a symbolic link to nothing", path=bag) from None
        return  # missing: the caller says so
    except OSError as exc:  # ELOOP and the like
        raise BagError(f"cannot read {entry.name}: {exc.strerror}", path=bag) from None
    if not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        kind = "a FIFO" if stat.S_ISFIFO(mode) else "a socket or device"
        raise BagError(f"{entry.name} is {kind}, not a file: a bag holds files only", path=bag)


def bag_name(path: Path) -> str:
    """A bag's name: its file's stem (ROS 1) or its directory's name (rosbag2).

    Raises:
        BagError: when the path is missing or is not a bag.
    """
    resolved, ros = resolve_bag(path)
    return resolved.stem if ros == 1 else resolved.name


class Bag:
    """An open bag: its topics, and the messages of one or more of them, deserialized.

    Args:
        path: The bag (as :func:`resolve_bag` resolved it).
        reader: The open rosbags reader.
    """

    def __init__(self, path: Path, reader: AnyReader) -> None:
        self.path = path
        self.reader = reader

    @property
    def name(self) -> str:
        """The bag's name: its file's stem or its directory's name."""
        return bag_name(self.path)

    @property
    def start_time(self) -> int:
        """The time of the bag's first message (ns), where a player's clock starts."""
        return int(self.reader.start_time)

    def topic(self, name: str) -> list[Connection]:
        """The connections of a topic (several publishers may share one).

        Raises:
            BagError: when the bag has no such topic, or the topic has no messages.
        """
        found = [c for c in self.reader.connections if c.topic == name]
        if not found:
            topics = sorted({c.topic for c in self.reader.connections})
            raise BagError(
                f"no topic {name} in the bag (it has: {', '.join(topics) or 'no topics'})", path=self.path
            )
        if sum(c.msgcount for c in found) == 0:
            raise BagError("the topic has no messages", path=self.path, place=f"topic {name}")
        for connection in found:
            if connection.msgtype not in self.reader.typestore.fielddefs:
                raise BagError(
                    f"message type {connection.msgtype} is defined neither in the bag nor in ROS's standard "
                    "types: give its .msg or .idl definition with --types FILE_OR_FOLDER",
                    path=self.path,
                    place=f"topic {name}",
                )
        return found

    def messages(self, connections: Sequence[Connection]) -> Iterator[tuple[Connection, int, Any]]:
        """The messages of these connections in time order: connection, time (ns), message.

        Raises:
            BagError: when the bag turns out truncated or corrupt, or a message cannot be decoded.
        """
        deserialize = self.reader.deserialize
        try:
            for connection, time, raw in self.reader.messages(connections=connections):
                yield connection, time, deserialize(raw, connection.msgtype)
        except Exception as exc:  # rosbags raises many kinds for a damaged file; each is one line here
            topics = ", ".join(sorted({c.topic for c in connections}))
            raise BagError(
                f"cannot read the bag: {first_line(exc)}", path=self.path, place=f"topic {topics}"
            ) from None


@contextmanager
def open_bag(path: Path, definitions: Sequence[Path] = ()) -> Iterator[Bag]:
    """Open a bag for reading.

    Message types come from the definitions the bag carries (ROS 1 bags, rosbag2 since Iron, MCAP); types it
    does not define (a Humble SQLite3 bag defines none) come from ROS 2 Humble's (or ROS 1 Noetic's) standard
    types, ``supportive_msgs`` and the ``.msg`` / ``.idl`` files or folders in ``definitions``.

    Raises:
        BagError: when the bag is missing, not a bag, truncated or corrupt.
    """
    resolved, ros = resolve_bag(path)
    store = typestore(ros, definitions)
    try:
        reader = AnyReader([resolved], default_typestore=store)
        reader.open()
    except Exception as exc:  # rosbags reports a damaged bag with many exception types
        raise BagError(f"cannot open the bag: {first_line(exc)}", path=path) from None
    try:
        known = reader.typestore.fielddefs
        if any(c.msgtype not in known for c in reader.connections):
            try:
                reader.typestore.register({k: v for k, v in store.fielddefs.items() if k not in known})
            except TypesysError as exc:
                raise BagError(
                    f"the bag's message definitions conflict with the standard ones: {first_line(exc)}",
                    path=path,
                ) from None
        yield Bag(resolved, reader)
    finally:
        reader.close()
