"""ROS bags in and out (the ``ros`` extra, built on rosbags: ROS 1 bags and rosbag2 with MCAP or SQLite3
storage, no ROS installation needed): demonstrations and contact events read from bags, demonstrations,
contact events and beliefs written to them. See docs/ros.md for the conventions."""

from supportive.errors import MissingExtraError

try:
    import rosbags  # noqa: F401
except ImportError as exc:  # pragma: no cover - the extra is installed wherever the tests run
    raise MissingExtraError("reading and writing ROS bags", "rosbags", "ros") from exc

from supportive.io.rosbag.bags import Bag, bag_name, open_bag, resolve_bag
from supportive.io.rosbag.beliefs import BeliefBag
from supportive.io.rosbag.contacts import (
    CONTACTS_TOPIC,
    ContactFrame,
    read_contact_frames,
    write_contact_frames,
)
from supportive.io.rosbag.demonstrations import (
    ACTIONS_TOPIC,
    SEGMENT_TOPIC,
    import_demonstrations,
    read_demonstrations,
    write_demonstrations,
)
from supportive.io.rosbag.types import load_definitions, typestore
from supportive.io.rosbag.writing import STORAGES, BagWriter, Storage

__all__ = [
    "ACTIONS_TOPIC",
    "CONTACTS_TOPIC",
    "SEGMENT_TOPIC",
    "STORAGES",
    "Bag",
    "BagWriter",
    "BeliefBag",
    "ContactFrame",
    "Storage",
    "bag_name",
    "import_demonstrations",
    "load_definitions",
    "open_bag",
    "read_contact_frames",
    "read_demonstrations",
    "resolve_bag",
    "typestore",
    "write_contact_frames",
    "write_demonstrations",
]
