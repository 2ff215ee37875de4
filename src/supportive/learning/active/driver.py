"""Drive a teaching session against a (simulated) instructor."""

from __future__ import annotations

from typing import Protocol

from supportive.errors import LearningError
from supportive.learning.active.session import TeachingSession
from supportive.tasks.spec import Demonstration

__all__ = ["InstructorLike", "run_session"]


class InstructorLike(Protocol):
    """What :func:`run_session` needs of an instructor (see ``supportive.learning.instructors``)."""

    def begin_demonstration(self) -> None:
        """Get ready for a new demonstration."""

    def next_action(self, done: tuple[str, ...], query: str | None) -> str | None:
        """The next step after ``done``, given the learner's query (None: the demonstration is finished)."""


def run_session(
    session: TeachingSession,
    instructor: InstructorLike,
    demonstrations: int,
    *,
    max_steps: int = 10_000,
) -> list[Demonstration]:
    """Run ``demonstrations`` demonstrations: ask when the schedule says so, observe each step, learn at the end.

    Args:
        session: The session (its learner is updated in place).
        instructor: Performs steps and answers queries.
        demonstrations: How many demonstrations to run.
        max_steps: Guard against an instructor that never finishes.

    Returns:
        The demonstrations performed, in order.

    Raises:
        LearningError: for a negative count, an instructor that exceeds ``max_steps`` or performs an unknown
            action, or an empty demonstration.

    >>> class Chain:
    ...     def begin_demonstration(self) -> None: ...
    ...     def next_action(self, done, query):
    ...         return None if len(done) == 2 else ("a", "b")[len(done)]
    >>> [d.actions for d in run_session(TeachingSession(["a", "b"]), Chain(), 2)]
    [('a', 'b'), ('a', 'b')]
    """
    if demonstrations < 0:
        raise LearningError(f"the number of demonstrations must be >= 0, got {demonstrations}")
    performed: list[Demonstration] = []
    for _ in range(demonstrations):
        instructor.begin_demonstration()
        session.begin()
        while True:
            action = instructor.next_action(session.done, session.query())
            if action is None:
                break
            if len(session.done) >= max_steps:
                raise LearningError(
                    f"demonstration {len(session.demonstrations) + 1}: the instructor did not finish "
                    f"within {max_steps} steps"
                )
            session.observe(action)
        performed.append(session.end())
    return performed
