"""When a learner may ask (§2.2.7.1, §2.2.10): after given step counts, a few times per demonstration."""

from __future__ import annotations

from dataclasses import dataclass

from supportive.errors import LearningError

__all__ = ["QuerySchedule"]


@dataclass(frozen=True)
class QuerySchedule:
    """When queries are made during a demonstration.

    Args:
        after_steps: Ask after this many steps of a demonstration (0: at the start).
        max_per_demonstration: At most this many queries per demonstration (None: no limit).
        skip_first_demonstrations: Ask nothing during this many first demonstrations of a session.

    >>> QuerySchedule(after_steps=(0, 2, 4)).should_query(demonstration=0, step=2, asked=1)
    True
    >>> QuerySchedule(skip_first_demonstrations=1).should_query(demonstration=0, step=1, asked=0)
    False

    Raises:
        LearningError: for a negative step, limit or skip count.
    """

    after_steps: tuple[int, ...] = (1, 3, 5)
    max_per_demonstration: int | None = None
    skip_first_demonstrations: int = 0

    def __post_init__(self) -> None:
        steps = tuple(self.after_steps)
        if any(not isinstance(s, int) or isinstance(s, bool) or s < 0 for s in steps):
            raise LearningError(f"query schedule: after_steps must be step counts >= 0, got {steps!r}")
        object.__setattr__(self, "after_steps", tuple(sorted(set(steps))))
        if self.max_per_demonstration is not None and self.max_per_demonstration < 0:
            raise LearningError(
                f"query schedule: max_per_demonstration must be >= 0 or None, got {self.max_per_demonstration}"
            )
        if self.skip_first_demonstrations < 0:
            raise LearningError(
                "query schedule: skip_first_demonstrations must be >= 0, "
                f"got {self.skip_first_demonstrations}"
            )

    @classmethod
    def thesis(cls, task: int) -> QuerySchedule:
        """The pilot study's schedule for task 1, 2 or 3 (§2.2.7): after steps 1, 3, 5 (tasks 1, 2) or at the
        start and after steps 2, 4 (task 3); 3 queries per demonstration, none in the first.

        Raises:
            LearningError: for another task number.
        """
        steps = {1: (1, 3, 5), 2: (1, 3, 5), 3: (0, 2, 4)}.get(task)
        if steps is None:
            raise LearningError(f"the thesis's query schedule is for tasks 1, 2 or 3, not {task!r}")
        return cls(after_steps=steps, max_per_demonstration=3, skip_first_demonstrations=1)

    def should_query(self, *, demonstration: int, step: int, asked: int) -> bool:
        """True when a query is due.

        Args:
            demonstration: 0-based index of the demonstration in the session.
            step: Steps done so far in this demonstration.
            asked: Queries already made in this demonstration.
        """
        if demonstration < self.skip_first_demonstrations:
            return False
        if self.max_per_demonstration is not None and asked >= self.max_per_demonstration:
            return False
        return step in self.after_steps
