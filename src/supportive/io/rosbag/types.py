"""ROS message types: the distribution's standard ones, this package's ``supportive_msgs``, and a user's own
``.msg`` / ``.idl`` definitions, as rosbags type stores.

A ``.msg`` file is named by where it sits, as in a ROS package: ``my_msgs/msg/Step.msg`` defines
``my_msgs/msg/Step``. A folder is searched for every ``*.msg`` and ``*.idl`` under it, so a ROS workspace's
``src/`` or one package's folder both work; definitions may refer to each other in any order.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Literal

from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import FieldDesc, Typesdict
from rosbags.typesys import Stores, TypesysError, get_types_from_idl, get_types_from_msg, get_typestore
from rosbags.typesys.store import Typestore

from supportive.errors import BagError

__all__ = [
    "ACTION_SPAN",
    "CONTACT_FRAME",
    "DEMONSTRATION",
    "RosVersion",
    "first_line",
    "load_definitions",
    "typestore",
]

RosVersion = Literal[1, 2]
"""ROS 1 (``.bag`` files) or ROS 2 (rosbag2)."""

ACTION_SPAN = "supportive_msgs/msg/ActionSpan"
"""A demonstration step: ``string action``, ``builtin_interfaces/Time start``, ``builtin_interfaces/Time end``."""
DEMONSTRATION = "supportive_msgs/msg/Demonstration"
"""A segment marker: ``string id``, ``string agent``."""
CONTACT_FRAME = "supportive_msgs/msg/ContactFrame"
"""One moment's contact events: ``std_msgs/Header header``, ``string[] events``."""

_STORES: dict[RosVersion, Stores] = {1: Stores.ROS1_NOETIC, 2: Stores.ROS2_HUMBLE}


def load_definitions(path: Path) -> Typesdict:
    """The message types a ``.msg`` or ``.idl`` file, or every such file under a folder, defines.

    Raises:
        BagError: naming the file that is missing, misplaced (a ``.msg`` not in a ``<package>/msg/`` folder)
            or does not parse.
    """
    if path.is_dir():
        files = sorted(p for p in path.rglob("*") if p.suffix in (".msg", ".idl") and p.is_file())
        if not files:
            raise BagError("no .msg or .idl message definitions in this folder", path=path)
    elif path.is_file():
        files = [path]
    else:
        raise BagError("no such message definition file or folder", path=path)
    found: Typesdict = {}
    for file in files:
        found.update(_definitions_in(file))
    return found


def _definitions_in(file: Path) -> Typesdict:
    try:
        text = file.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise BagError(f"cannot read: {exc}", path=file) from None
    try:
        if file.suffix == ".idl":
            return get_types_from_idl(text)
        if file.suffix != ".msg":
            raise BagError("expected a .msg or .idl message definition", path=file)
        if file.parent.name != "msg" or not file.parent.parent.name:
            raise BagError(
                "a .msg file must sit in a <package>/msg/ folder, which names its type (my_msgs/msg/Step.msg)",
                path=file,
            )
        return get_types_from_msg(text, f"{file.parent.parent.name}/msg/{file.stem}")
    except TypesysError as exc:
        raise BagError(f"invalid message definition: {first_line(exc)}", path=file) from None


def first_line(exc: BaseException) -> str:
    """An exception's message, its first line only (rosbags' messages may run over several)."""
    text = str(exc).strip()
    return text.splitlines()[0].rstrip(":") if text else type(exc).__name__


@cache
def _shipped() -> Typesdict:
    folder = Path(str(resources.files(__package__).joinpath("msg")))
    return load_definitions(folder)


def typestore(ros: RosVersion, definitions: Sequence[Path] = ()) -> Typestore:
    """A fresh type store: the standard types of ROS 1 Noetic or ROS 2 Humble, ``supportive_msgs``, and the
    definitions found at ``definitions`` (files or folders; a later one overrides an earlier one).

    >>> store = typestore(2)
    >>> sorted(f[0] for f in store.fielddefs["supportive_msgs/msg/ActionSpan"][1])
    ['action', 'end', 'start']

    Raises:
        BagError: for a definition that is missing or invalid.
    """
    store = get_typestore(_STORES[ros])
    added: Typesdict = dict(_shipped())
    for path in definitions:
        added.update(load_definitions(path))
    known = set(store.fielddefs) | set(added)
    for name, (_, fields) in sorted(added.items()):
        for field, desc in fields:
            used = _used_type(desc)
            if used is not None and used not in known:
                raise BagError(
                    f"message definitions do not fit together: {name} field {field!r} is a {used}, "
                    "which no definition gives (add its .msg to --types)"
                )
    try:
        store.register(added)
    except TypesysError as exc:
        raise BagError(f"message definitions do not fit together: {first_line(exc)}") from None
    return store


def _used_type(desc: FieldDesc) -> str | None:
    """The message type a field holds (itself or as array / sequence elements), if not a primitive."""
    if desc[0] == Nodetype.NAME:
        return desc[1]
    if desc[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE):
        inner = desc[1][0]
        return inner[1] if inner[0] == Nodetype.NAME else None
    return None
