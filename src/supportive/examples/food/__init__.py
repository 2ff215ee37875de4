"""Food-preparation task sets for the thesis's experiments: a registry by name.

* ``names()`` / ``load(name)``: the 12 tasks of the active-learning experiment (§2.2.10.1, Fig. 2.11), 10-14
  skills and 12-24 valid orderings each, with contact events on every action.
* ``transfer_names()`` / ``load_transfer(name)``: the 25 tasks of the transfer experiment (§2.1.7.4,
  Fig. 2.6), 6-14 steps each over one shared dictionary of 39 primitive actions.

These live apart from the bundled examples (:mod:`supportive.examples`), which they do not join.

>>> len(names()), len(transfer_names())
(12, 25)
>>> load("omelette").name
'omelette'
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from supportive.errors import TaskFileError
from supportive.io.taskfile import parse_task_file
from supportive.tasks.spec import TaskSpec

__all__ = ["load", "load_transfer", "names", "path", "transfer_names", "transfer_path"]


def _folder() -> Path:
    return Path(str(resources.files(__package__)))


def _transfer_folder() -> Path:
    return _folder() / "transfer"


def _find(folder: Path, name: str, what: str) -> Path:
    file = folder / f"{name}.yaml"
    if not file.is_file():
        known = ", ".join(sorted(p.stem for p in folder.glob("*.yaml")))
        raise TaskFileError(f"no {what} {name!r}; known: {known}")
    return file


def names() -> list[str]:
    """Names of the active-learning tasks, sorted."""
    return sorted(p.stem for p in _folder().glob("*.yaml"))


def path(name: str) -> Path:
    """The file of an active-learning task.

    Raises:
        TaskFileError: for an unknown name.
    """
    return _find(_folder(), name, "food task")


def load(name: str) -> TaskSpec:
    """Parse an active-learning task.

    Raises:
        TaskFileError: for an unknown name.
    """
    return parse_task_file(path(name))


def transfer_names() -> list[str]:
    """Names of the transfer-experiment tasks, sorted."""
    return sorted(p.stem for p in _transfer_folder().glob("*.yaml"))


def transfer_path(name: str) -> Path:
    """The file of a transfer-experiment task.

    Raises:
        TaskFileError: for an unknown name.
    """
    return _find(_transfer_folder(), name, "transfer task")


def load_transfer(name: str) -> TaskSpec:
    """Parse a transfer-experiment task.

    Raises:
        TaskFileError: for an unknown name.
    """
    return parse_task_file(transfer_path(name))
