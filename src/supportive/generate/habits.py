"""People with habits: valid executions drawn the way people choose among them, not uniformly.

:meth:`KnownTask.sample <supportive.generate.mistakes.KnownTask.sample>` draws a task's valid executions
uniformly. People do not: they share a preferred order and each keeps close to it, so some valid orders are
common and some rare. :class:`HabitualPeople` is that population: its preferred order is one valid execution
(drawn uniformly); each demonstration is by a new person, who shifts every step's rank in the preferred order
by their own normal noise (standard deviation ``person_noise``) and then, at each point, picks among the
steps the task allows next with weight ``exp(-strength · rank)``. ``strength`` 0 is uniform over the steps
allowed next; every demonstration is valid. A model of people that calls a rare valid order a slip fails
here (the ``learner-settings`` experiment and ``make bench``'s ``bench_habits`` use it).

>>> from supportive.generate.mistakes import random_known_task
>>> task = random_known_task("partial order", 6, seed=1)
>>> people = HabitualPeople.of(task, strength=4.0, seed=2)
>>> demos = [people.demonstration(seed) for seed in range(20)]
>>> all(task.admits(d) for d in demos), sum(d == list(people.preferred) for d in demos) > 10
(True, True)
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from supportive.errors import GenerationError
from supportive.generate.mistakes import KnownTask
from supportive.seeding import Seed, rng_from

__all__ = ["HABIT_STRENGTHS", "PEOPLE", "HabitualPeople", "executions_by"]

HABIT_STRENGTHS = (1.0, 2.0, 4.0)
"""The strengths experiments draw from: people who often, mostly, and nearly always keep the habit (with
the default ``person_noise`` of 0.5, a step one rank behind another in the preferred order is taken first, when both are
allowed, about 29 %, 18 % and 12 % of the time: the person's own noise, not the strength, makes most of the
swaps at strength 4)."""
PEOPLE = ("uniform", "habits")
"""Who does a generated task's executions in the experiments that choose the learner's settings: everyone
drawing uniformly among the valid executions, or :class:`HabitualPeople` (see :func:`executions_by`)."""


@dataclass(frozen=True)
class HabitualPeople:
    """A population with a shared habit over ``task`` (see the module docstring).

    Attributes:
        task: The task whose valid executions they do.
        preferred: The population's preferred order, one valid execution.
        strength: How strongly they keep it, 0 or more (per rank, in the log weight of a step).
        person_noise: Standard deviation of each person's shift of each rank, 0 or more (default 0.5: people
            share the habit, not exactly; a property of the generated population, not a learner setting).
    """

    task: KnownTask
    preferred: tuple[str, ...]
    strength: float
    person_noise: float = 0.5

    def __post_init__(self) -> None:
        if not self.strength >= 0.0 or not self.person_noise >= 0.0:
            raise GenerationError(
                f"strength and person_noise must be 0 or more, got {self.strength} and {self.person_noise}"
            )
        if not self.task.admits(self.preferred):
            raise GenerationError(f"the preferred order {list(self.preferred)} is not a valid execution of the task")

    @classmethod
    def of(cls, task: KnownTask, strength: float, seed: Seed = None, **options: float) -> HabitualPeople:
        """People whose preferred order is drawn uniformly among ``task``'s valid executions (``options``: the
        other fields, e.g. ``person_noise``)."""
        return cls(task, tuple(task.sample(rng_from(seed))), strength, **options)

    def demonstration(self, seed: Seed = None) -> list[str]:
        """One valid execution by a new person of this population."""
        rng = rng_from(seed)
        rank: dict[str, float] = {}
        for i, step in enumerate(self.preferred):  # a repeated step: ranked where it is first preferred
            rank.setdefault(step, i + float(rng.normal(0.0, self.person_noise)))
        done: list[str] = []
        while allowed := self.task.allowed_next(done):
            logits = -self.strength * np.array([rank[step] for step in allowed])
            weights = np.exp(logits - logits.max())
            done.append(allowed[int(rng.choice(len(allowed), p=weights / weights.sum()))])
        return done


def executions_by(task: KnownTask, people: str, seed: Seed = None) -> Callable[[Seed], list[str]]:
    """How ``people`` (one of :data:`PEOPLE`) draw ``task``'s valid executions, each call one person's:
    ``task.sample`` for ``"uniform"``; for ``"habits"``, one :class:`HabitualPeople` population of a strength
    drawn from :data:`HABIT_STRENGTHS` with ``seed`` (then its preferred order, with the same generator).

    Raises:
        GenerationError: ``people`` is not one of :data:`PEOPLE`.

    >>> from supportive.generate.mistakes import random_known_task
    >>> task = random_known_task("uniform", 5, seed=0)
    >>> draw = executions_by(task, "habits", seed=1)
    >>> task.admits(draw(2)), draw(3) == executions_by(task, "habits", seed=1)(3)
    (True, True)
    """
    if people == "uniform":
        return task.sample
    if people == "habits":
        rng = rng_from(seed)
        return HabitualPeople.of(task, float(rng.choice(HABIT_STRENGTHS)), rng).demonstration
    raise GenerationError(f"people must be one of {', '.join(PEOPLE)}, got {people!r}")
