"""The bundled example tasks and circuit scenarios (also in the repository's ``examples/``): registries by
name.

>>> "ikea-chair" in names(), "two-cells-led" in circuit_names()
(True, True)
"""

from __future__ import annotations

from collections.abc import Callable
from importlib import resources
from pathlib import Path

from supportive.errors import ScenarioFileError, TaskFileError
from supportive.io.taskfile import parse_task_file
from supportive.tasks.spec import TaskSpec

__all__ = ["circuit_names", "circuit_path", "load", "names", "path", "scenario_path", "task_path"]


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


def task_path(file: str | Path) -> Path:
    """A task file the user named: the file when it exists (or has a suffix), else the bundled example of that
    name, else the path as given (reading it then says it is missing).

    >>> task_path("ikea-chair").name, str(task_path("my-task.yaml"))
    ('ikea-chair.yaml', 'my-task.yaml')

    Raises:
        TaskFileError: for a name without a suffix that is neither a file nor a bundled example (the message
            says what a task file's name ends in, and lists the examples).
    """
    found = _named(file, names(), path)
    if found is None:
        raise TaskFileError(
            "no such file, nor a bundled example of that name; expected a task file (.yaml, .yml, .json or .csv) "
            f"or one of: {', '.join(names())}",
            path=file,
        )
    return found


def _named(file: str | Path, bundled: list[str], path_of: Callable[[str], Path]) -> Path | None:
    """``file`` itself, or the bundled file of that name when it is no file and has no suffix; None for a name
    without a suffix that is neither."""
    given = Path(file)
    if not given.suffix and not given.exists():
        return path_of(str(file)) if str(file) in bundled else None
    return given


def load(name: str) -> TaskSpec:
    """Parse a bundled example."""
    return parse_task_file(path(name))


def circuit_names() -> list[str]:
    """Names of the bundled circuit scenarios (``examples/circuits``), sorted."""
    return sorted(p.stem for p in (_folder() / "circuits").glob("*.yaml"))


def circuit_path(name: str) -> Path:
    """The file of a bundled circuit scenario.

    Raises:
        ScenarioFileError: for an unknown name.
    """
    file = _folder() / "circuits" / f"{name}.yaml"
    if not file.is_file():
        raise ScenarioFileError(f"no bundled circuit scenario {name!r}; known: {', '.join(circuit_names())}")
    return file


def scenario_path(file: str | Path) -> Path:
    """A circuit scenario the user named: the file when it exists (or has a suffix), else the bundled scenario of
    that name, else the path as given (reading it then says it is missing).

    >>> scenario_path("two-cells-led").name, str(scenario_path("my-table.yaml"))
    ('two-cells-led.yaml', 'my-table.yaml')

    Raises:
        ScenarioFileError: for a name without a suffix that is neither a file nor a bundled scenario (naming
            the task examples when it is one of them: ``support`` reads circuit scenarios, not task files).
    """
    found = _named(file, circuit_names(), circuit_path)
    if found is None:
        task = " (that is a bundled task, for learn, teach, chat, …)" if str(file) in names() else ""
        raise ScenarioFileError(
            f"no such file, nor a bundled circuit scenario of that name{task}; expected a scenario file "
            f"(.yaml, .yml or .json) or one of: {', '.join(circuit_names())}",
            path=file,
        )
    return found
