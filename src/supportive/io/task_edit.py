"""Saving a change to a user's task file the way a careful editor would: under a lock, on the file as it is
now, keeping its comments and layout, atomically (what ``teach`` and ``chat`` save through).

:func:`update_task_file` locks the file (:func:`~supportive.io.atomic.exclusive`), reads it again, applies the
caller's change to the task it holds *now* (so a second session's demonstration saved meanwhile is kept, not
overwritten), and writes the result back with :func:`~supportive.io.atomic.atomic_write`. A YAML file is edited
in ruamel.yaml's round-trip mode: only the parts of the task that changed are rewritten — an unchanged action,
demonstration or behavior keeps its text, comments and style, and a new item takes the style of the one
before it (``- {id: d5, steps: [a, b]}`` after flow-style demonstrations). JSON has no comments: it keeps
its key order and unchanged items.
"""

from __future__ import annotations

import io
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedBase, CommentedMap, CommentedSeq
from ruamel.yaml.util import load_yaml_guess_indent

from supportive.errors import TaskFileError
from supportive.io.atomic import atomic_write, exclusive
from supportive.io.safe_load import read_text
from supportive.io.taskfile import Format, dump_task, format_of, parse_task_string, task_to_dict
from supportive.tasks.spec import TaskSpec

__all__ = ["edited_text", "update_task_file"]

# The task's fields in file order, each with how its items are matched between the old and the new task.
_LISTS: dict[str, Callable[[Any], object]] = {
    "actions": lambda a: a.id,
    "demonstrations": lambda d: d.id,
    "predicates": lambda p: p.name,
    "behaviors": lambda b: b.name,
}
_FIELDS = ("name", "actions", "structure", "demonstrations", "objects", "predicates", "behaviors")


def update_task_file(path: str | Path, change: Callable[[TaskSpec], TaskSpec]) -> TaskSpec:
    """Apply ``change`` to the task in the file at ``path`` and save it, keeping what did not change.

    Args:
        path: An existing task file (.yaml, .yml, .json or .csv; a symlink is followed and stays a link).
        change: Gets the task as the file holds it now; returns the task to save.

    Returns:
        The task saved.

    Raises:
        TaskFileError: when the file cannot be read, is not a valid task, or cannot be written (the file is
            then as it was).
    """
    fmt = format_of(path)
    with exclusive(path, error=TaskFileError) as target:
        text = read_text(target, TaskFileError)
        old = parse_task_string(text, fmt, path=path)
        new = change(old)
        if new == old:
            return old
        atomic_write(target, edited_text(text, fmt, old, new, path=path), error=TaskFileError)
    return new


def edited_text(text: str, fmt: Format, old: TaskSpec, new: TaskSpec, *, path: str | Path | None = None) -> str:
    """The text of a task file (``text``, in format ``fmt``, holding ``old``) changed to hold ``new``,
    keeping what did not change (comments and layout of YAML, key order of JSON).

    Raises:
        TaskFileError: (naming ``path``) when ``text`` is not a valid task.
    """
    if fmt == "yaml":
        updated = _edit_yaml(text, old, new)
    elif fmt == "json":
        updated = _edit_json(text, old, new)
    else:
        updated = dump_task(new, fmt)
    if parse_task_string(updated, fmt, path=path) != new:  # never save what would not read back as `new`
        updated = dump_task(new, fmt)
    return updated


def _merge(document: dict[str, Any], old: TaskSpec, new: TaskSpec, fresh: dict[str, Any], make: Callable[[Any, Any], Any]) -> None:
    """Make ``document`` (the file's data, edited in place) hold ``new``: fields and items equal in ``old``
    and ``new`` are left as they are; ``fresh`` is ``new`` in the file schema; ``make(value, like)`` turns a
    fresh value into the document's kind, styled like ``like``."""
    for key in _FIELDS:
        before, after = getattr(old, key), getattr(new, key)
        if before == after and (key in document or not after):
            continue
        if key not in fresh:
            document.pop(key, None)
            continue
        current = document.get(key)
        if key in _LISTS and isinstance(current, list) and len(current) == len(before):
            _merge_items(current, before, after, fresh[key], _LISTS[key], make)
        else:
            document[key] = make(fresh[key], current)


def _merge_items(
    items: list[Any],
    before: Sequence[Any],
    after: Sequence[Any],
    fresh: list[Any],
    key: Callable[[Any], object],
    make: Callable[[Any, Any], Any],
) -> None:
    """Edit the document's list ``items`` (one per item of ``before``) to hold ``after``, reusing every item
    that did not change, so its comments and style stay."""
    position = {key(item): index for index, item in enumerate(before)}
    like = items[-1] if items else None
    wanted = []
    for item, data in zip(after, fresh, strict=True):
        index = position.get(key(item))
        if index is not None and before[index] == item:
            wanted.append(items[index])
        else:
            wanted.append(make(data, items[index] if index is not None else like))
    if wanted[: len(items)] == items[: len(wanted)] and all(a is b for a, b in zip(wanted, items, strict=False)):
        del items[len(wanted) :]  # the common case: items kept in place, some appended or dropped at the end
        items.extend(wanted[len(items) :])
    else:
        items[:] = wanted


# ------------------------------------------------------------------------------------------------- YAML
def _round_trip(text: str) -> tuple[YAML, Any]:
    _, indent, offset = load_yaml_guess_indent(text)
    yaml = YAML()  # round-trip mode: comments, key order, flow or block style and quotes are kept
    yaml.preserve_quotes = True
    yaml.width = 4096  # never re-wrap a line the user wrote
    yaml.indent(mapping=2, sequence=indent or 2, offset=offset or 0)
    return yaml, yaml.load(text)


def _styled(value: Any, like: Any) -> Any:
    """``value`` (plain data) as ruamel nodes, each list or mapping in flow style where the matching part of
    ``like`` (the item it replaces, or the one before it) is."""
    node: CommentedMap | CommentedSeq
    if isinstance(value, dict):
        node = CommentedMap()
        for key, item in value.items():
            node[key] = _styled(item, like.get(key) if isinstance(like, dict) else None)
    elif isinstance(value, list):
        node = CommentedSeq(
            _styled(item, like[0] if isinstance(like, list) and like else None) for item in value
        )
        if len(value) == 2 and all(isinstance(v, int | float) for v in value):
            node.fa.set_flow_style()  # a keyframe's [x, y]
    else:
        return value
    if isinstance(like, CommentedBase) and like.fa.flow_style():
        node.fa.set_flow_style()
    return node


def _edit_yaml(text: str, old: TaskSpec, new: TaskSpec) -> str:
    yaml, document = _round_trip(text)
    if not isinstance(document, CommentedMap):
        return dump_task(new, "yaml")
    _merge(document, old, new, task_to_dict(new), _styled)
    out = io.StringIO()
    yaml.dump(document, out)
    return out.getvalue()


# ------------------------------------------------------------------------------------------------- JSON
def _edit_json(text: str, old: TaskSpec, new: TaskSpec) -> str:
    document = json.loads(text)
    if not isinstance(document, dict):
        raise TaskFileError("expected a mapping with at least 'name'", path=None)
    _merge(document, old, new, task_to_dict(new), lambda value, like: value)
    return json.dumps(document, indent=2, ensure_ascii=False) + "\n"
