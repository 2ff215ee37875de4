"""The exceptions of `supportive`: one root, one subclass per kind of trouble.

Every message names where the problem is (file, line, field) and what was expected, so the CLI can print it
as one line without a traceback.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

__all__ = [
    "BagError",
    "BoardError",
    "BoardRefusal",
    "CircuitError",
    "DatasetError",
    "ExperimentError",
    "ExportError",
    "FileFormatError",
    "GenerationError",
    "LearningError",
    "MapFileError",
    "MissingExtraError",
    "NotFittedError",
    "ObservationFileError",
    "PlanningError",
    "ScenarioFileError",
    "SocialError",
    "SupportiveError",
    "TaskFileError",
    "TaskGraphError",
    "TooManyOrderingsError",
]


class SupportiveError(Exception):
    """Root of every error `supportive` raises on purpose."""


class FileFormatError(SupportiveError, ValueError):
    """A file the user gave is unreadable or malformed; the message says where.

    Args:
        problem: What is wrong and, where it helps, what was expected.
        path: The file, when the text came from one.
        place: The field, as a path like ``demonstrations[1].steps[3]``.
        line: The 1-based line of the problem, when known.
        column: The 1-based column on that line, when known.
    """

    def __init__(
        self,
        problem: str,
        *,
        path: str | Path | None = None,
        place: str | None = None,
        line: int | None = None,
        column: int | None = None,
    ) -> None:
        self.problem = problem
        self.path = None if path is None else str(path)
        self.place = place
        self.line = line
        self.column = column
        super().__init__(self._render())

    def _render(self) -> str:
        where = self.path or "<text>"
        if self.line is not None:
            where += f":{self.line}"
            if self.column is not None:
                where += f":{self.column}"
        if self.place:
            where += f": {self.place}"
        return f"{where}: {self.problem}"


class TaskFileError(FileFormatError):
    """A task file (YAML, JSON or CSV) is unreadable or breaks the schema."""


class ObservationFileError(FileFormatError):
    """An observation stream (contact events per moment) is unreadable or malformed."""


class BagError(FileFormatError):
    """A ROS bag is missing, unreadable or corrupt, or a topic in it is missing, empty or of the wrong type;
    the message names the bag and the topic."""


class MapFileError(FileFormatError):
    """A household map (one character per cell) is unreadable or unusable; the message gives line and column."""


class ScenarioFileError(FileFormatError):
    """A support-planning scenario file (a table, its objects and a goal) is unreadable or breaks the schema."""


class TaskGraphError(SupportiveError, ValueError):
    """Demonstrations that cannot form a task graph (for example, explicit states that contradict each other)."""


class LearningError(SupportiveError, ValueError):
    """A learning algorithm was given input it cannot work with."""


class NotFittedError(LearningError, AttributeError):
    """An estimator was used before ``fit``."""


class ExportError(SupportiveError):
    """An export (HDDL, DOT, …) failed or needs an optional dependency that is not installed."""


class PlanningError(SupportiveError, ValueError):
    """A planning problem is malformed or has no solution the planner can find (no plan reaches the goal,
    a plan names an object the world does not have, …)."""


class CircuitError(PlanningError):
    """A circuit piece placed where it cannot go (off the board, overlapping, unsupported), or an unknown
    piece kind."""


class SocialError(SupportiveError, ValueError):
    """Social force or a role policy was given input it cannot use (a sample out of time order, a non-finite
    position, a threshold out of range, a subtask both claimed by another agent and one's own, …)."""


BoardRefusal = Literal["invalid", "forbidden", "missing", "conflict"]
"""Why the task board refuses an operation."""


class BoardError(SupportiveError):
    """An operation the task board refuses (the service answers it with an HTTP status of its choosing).

    Args:
        reason: Why: ``"invalid"`` a malformed operation (an unknown operation, progress outside [0, 1], a
            lead-only name that is no subtask's), ``"forbidden"`` the agent's role may not, ``"missing"`` no
            such node, ``"conflict"`` the board's state does not allow it now.
        message: What was wrong, for people.
    """

    def __init__(self, reason: BoardRefusal, message: str) -> None:
        self.reason: BoardRefusal = reason
        self.message = message
        super().__init__(message)


class DatasetError(SupportiveError, ValueError):
    """A dataset on disk is missing or malformed."""


class GenerationError(SupportiveError, ValueError):
    """A generator was asked for something it cannot make (a task of no actions, a probability above 1, …)."""


class TooManyOrderingsError(GenerationError, LearningError):
    """A structure admits more orderings than the caller allowed to enumerate.

    Args:
        count: How many orderings the structure admits.
        limit: The most the caller allowed.
    """

    def __init__(self, count: int, limit: int) -> None:
        self.count = count
        self.limit = limit
        shown = str(count) if count < 10**12 else f"about 10^{int(math.log10(count))}"
        super().__init__(
            f"the structure admits {shown} orderings, more than the limit of {limit}: "
            "sample demonstrations instead, or raise the limit"
        )


class ExperimentError(SupportiveError, ValueError):
    """An experiment run was asked for something it cannot do (an unknown experiment, a bad trial count, both
    ``workers`` and ``scheduler``, a scheduler it cannot reach, …)."""


class MissingExtraError(SupportiveError, ImportError):
    """A feature needs an optional dependency (an extra) that is not installed.

    Args:
        feature: What needs it (``"running on a dask cluster"``).
        module: The module that failed to import.
        extra: The extra that installs it (``"distributed"``).
    """

    def __init__(self, feature: str, module: str, extra: str) -> None:
        self.feature = feature
        self.module = module
        self.extra = extra
        super().__init__(
            f"{feature} needs {module}, which is not installed: pip install 'supportive[{extra}]'"
        )
