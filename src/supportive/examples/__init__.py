"""The bundled example tasks (also in the repository's ``examples/``): a registry by name.

>>> "ikea-chair" in names()
True
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from supportive.errors import TaskFileError
from supportive.io.taskfile import parse_task_file
from supportive.tasks.spec import TaskSpec

__all__ = ["load", "names", "path"]


def _folder() -> Path:
    return Path(str(resources.files(__package__)))


def names() -> list[str]:
    """Names of the bundled examples, sorted."""
    return sorted(p.stem for p in _folder().glob("*.yaml"))


def path(name: str) -> Path:
    """The file of a bundled example.

    Raises:
        TaskFileError: for an unknown name.
    """
    file = _folder() / f"{name}.yaml"
    if not file.is_file():
        raise TaskFileError(f"no bundled example {name!r}; known: {', '.join(names())}")
    return file


def load(name: str) -> TaskSpec:
    """Parse a bundled example."""
    return parse_task_file(path(name))
