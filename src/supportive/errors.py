"""The exceptions of `supportive`: one root, one subclass per kind of trouble, all defined here.

Every message names where the problem is (file, line, field, option) and the value that was wrong, and what
was expected, so the CLI can print it as one line without a traceback. An error about a value also derives
from the built-in exception a Python caller would expect (``ValueError``; ``KeyError`` for an unknown name;
``RuntimeError`` for a call out of order), so ``except ValueError`` keeps working.

This module imports nothing from the package: every layer may raise these.
"""

from __future__ import annotations

import math
from collections.abc import Hashable, Sequence
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
    "FormulaError",
    "GenerationError",
    "InvalidValueError",
    "LanguageError",
    "LearningError",
    "MapFileError",
    "MissingExtraError",
    "NoCoverError",
    "NotFittedError",
    "ObservationFileError",
    "OptionError",
    "PlanningError",
    "ResetNeededError",
    "SafetyError",
    "ScenarioFileError",
    "SearchLimitError",
    "SentenceTooLongError",
    "ServiceError",
    "SocialError",
    "StoreError",
    "SupportiveError",
    "TaskFileError",
    "TaskGraphError",
    "TaskModelError",
    "TokenError",
    "TooManyOrderingsError",
    "UnderstandingError",
    "UnknownHelpError",
    "UnknownNameError",
    "WorldError",
    "naming",
]


class SupportiveError(Exception):
    """Root of every error `supportive` raises on purpose."""


def naming(error: SupportiveError, where: str | Path) -> SupportiveError:
    """``error`` with ``where`` (a file) put before its message, for an error about a file's contents raised
    where the file was not known; its class and attributes are kept.

    >>> str(naming(LearningError("demonstration 2: no steps"), "task.yaml"))
    'task.yaml: demonstration 2: no steps'
    """
    error.args = (f"{where}: {error}",)
    return error


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


class InvalidValueError(SupportiveError, ValueError):
    """A value is of the wrong kind or out of range (a number, an id, a text); the message names what it is
    and the value. Raised where no file is known: a schema's field (the file's reader then names the file), a
    library argument."""


class OptionError(SupportiveError, ValueError):
    """A command-line option's value is invalid, or options that cannot go together were given.

    Args:
        problem: What is wrong and what was expected.
        option: The option (``--folds``), when one is to blame; the message then starts with it.
    """

    def __init__(self, problem: str, option: str | None = None) -> None:
        self.problem = problem
        self.option = option
        super().__init__(f"{option}: {problem}" if option else problem)


class TaskModelError(SupportiveError, ValueError):
    """A task model was given something it cannot hold (a done set its structure cannot reach, a predicate
    with the wrong number of arguments)."""


class FormulaError(TaskModelError):
    """A formula (of a behavior's initiation or termination) that does not parse; the message says where."""


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


class SearchLimitError(PlanningError):
    """A search stopped at the limit of work it was given before it had its answer (the message names the
    limit and what to change): a search never runs on without a word."""


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


class WorldError(SupportiveError, ValueError):
    """A simulated world or its RL environment was given what it cannot use: an unknown move, an action out of
    range, a reset option off the map, a render mode it does not have, a caregiver action where there is no
    caregiver."""


class ResetNeededError(SupportiveError, RuntimeError):
    """An RL environment was stepped or rendered before ``reset()`` (or after its episode ended)."""


class SafetyError(SupportiveError, ValueError):
    """The safety model or the caregiver was given a setting out of range (a probability outside (0, 1], a
    horizon of 0, …) or asked to act in a world without a caregiver."""


class LanguageError(SupportiveError, ValueError):
    """Language (understanding, explaining, fluency) was given input it cannot use: weights that are no
    distribution, an unknown method, a region that cannot be told apart, …"""


class UnknownNameError(LanguageError, KeyError):
    """No subtask or behavior of the task has that name; the message lists the known ones."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class UnderstandingError(LanguageError):
    """An utterance the grammar cannot read; the message says what was understood and what form to use.

    Args:
        text: What the person said.
        understood: The leading part that was understood (as they said it), or None.
        missing: What is missing after it ("what you want me to do").
        expected: The forms to use instead.
    """

    def __init__(self, text: str, understood: str | None, missing: str, expected: str) -> None:
        self.text = text
        self.understood = understood
        self.missing = missing
        self.expected = expected
        if understood:
            message = f"I understood '{understood}' but not {missing}; say: {expected}"
        else:
            message = f"I did not understand '{text.strip()}'; say {expected}"
        super().__init__(message)


class SentenceTooLongError(UnderstandingError):
    """An utterance longer than the sentence limit (:data:`~supportive.io.limits.MAX_SENTENCE_CHARS`):
    refused before parsing (the Earley parser's time grows faster than the sentence).

    Args:
        text: What the person said.
        limit: The most characters a sentence may have.
    """

    def __init__(self, text: str, limit: int) -> None:
        self.text = text
        self.understood = None
        self.missing = ""
        self.expected = ""
        LanguageError.__init__(
            self,
            f"That is {len(text):,} characters; I read sentences of at most {limit}: "
            "say it in shorter sentences, one at a time.",
        )


class UnknownHelpError(UnderstandingError):
    """A request for help the robot has no behavior for and no verb of help it knows ("juggle"): it is not
    made up as a new behavior.

    Args:
        phrase: The behavior phrase.
        message: What the robot answers (what it can do instead).
    """

    def __init__(self, phrase: str, message: str) -> None:
        super().__init__(phrase, None, "a kind of help", "")
        self.args = (message,)


_SHOWN_STATES = 10  # states a NoCoverError message lists before "… and N more"


class NoCoverError(SupportiveError):
    """Every target state must be covered, and some cannot be.

    The caller turns this into "I have no words for …": ``uncoverable`` holds the target states that no
    allowed conjunction (at most ``max_literals`` literals; for ESPRESSO, any) separates from the irrelevant
    states: every such conjunction that holds in one of them also holds in an irrelevant state.

    Args:
        uncoverable: The target states that cannot be covered.
        reason: Why, as the start of the message (the states are appended).
        order: The table's states, to list ``uncoverable`` in a stable order.
    """

    def __init__(self, uncoverable: frozenset[Hashable], reason: str, order: Sequence[Hashable] = ()) -> None:
        self.uncoverable = uncoverable
        self.reason = reason
        listed = [s for s in order if s in uncoverable] or sorted(uncoverable, key=repr)
        shown = ", ".join(repr(s) for s in listed[:_SHOWN_STATES])
        if len(listed) > _SHOWN_STATES:
            shown += f", … and {len(listed) - _SHOWN_STATES} more"
        super().__init__(f"{reason}: {shown}")


class ServiceError(SupportiveError):
    """The board service cannot do what was asked: a task it cannot make a board of, goal inference on a
    board without it, a running service that answered with an error."""


class StoreError(SupportiveError, ValueError):
    """The board's database cannot be used (a bad URL, a server that does not answer, another task in it)."""


class TokenError(StoreError):
    """An agent or token the board's database does not have, or a change to them it refuses (a token given
    that was revoked or is another agent's, an agent asked for with another kind or role)."""


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
