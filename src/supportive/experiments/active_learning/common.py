"""Active learning: what both experiments share — teaching one task, pooling, seeds and statistics.

A simulated instructor (:class:`~supportive.learning.instructors.SimulatedInstructor`) teaches a fresh learner
through a :class:`~supportive.learning.active.TeachingSession`; the measure is the number of known unique
origin→terminal paths of the learner's environment-space task graph (§2.2.8). Pooled instruction is the
union of the learned graphs (§2.2.8, §2.2.10.1): every member's demonstrations replayed into one graph.

Only the task graph and its CTG matter to the query strategies and to the measure, so the learner is an
:class:`~supportive.learning.learner.HTNLearner` without alternative hierarchies (``alternatives=0``): the
path counts are the same, the search for alternative CC-HTNs of a partial hierarchy is skipped.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from supportive.generate import sample_orderings
from supportive.learning.active import QuerySchedule, TeachingSession, run_session
from supportive.learning.instructors import SimulatedInstructor
from supportive.learning.learner import HTNLearner
from supportive.tasks.htn import Node
from supportive.tasks.task_graph import TaskGraph

__all__ = [
    "DEVIATION",
    "NO_QUERIES",
    "STRATEGIES",
    "Taught",
    "anova",
    "instructor_rng",
    "known_paths",
    "make_instructor",
    "session_rng",
    "teach",
]

DEVIATION = 0.2
"""Per-demonstration probability of each adjacent swap of an instructor's preferred path (unprompted
variation). Without it a simulated instructor repeats herself exactly, and the late, never-queried parts of a
13-step recipe never vary (comprehension plateaus: 25 % on the food tasks); 0.2 brings the random strategy's
iteration-4 comprehension near the thesis's 25.9 %."""

STRATEGIES = ("random", "distance", "connectivity")
"""The three query strategies of §2.2.6, in the order the reports list them."""

NO_QUERIES = QuerySchedule(after_steps=(), max_per_demonstration=0)
"""The passive condition's schedule: the learner never asks."""


@dataclass(frozen=True)
class Taught:
    """What one instructor taught one learner: the demonstrations and the known paths after each one."""

    demonstrations: tuple[tuple[str, ...], ...]
    paths: tuple[int, ...]


def instructor_rng(instructor_seed: int, task: int) -> np.random.Generator:
    """The generator of an instructor's preferred path for task number ``task`` (the same for every strategy,
    as in the pilot study: "participants were likely to remain true to their initial demonstration sequence
    for each task across algorithms")."""
    return np.random.default_rng([instructor_seed, task])


def session_rng(instructor_seed: int, task: int, strategy: int) -> np.random.Generator:
    """The generator of a session's tie-breaking (and random) query choices."""
    return np.random.default_rng([instructor_seed, task, strategy, 1])


def make_instructor(
    structure: Node, *, instructor_seed: int, task: int, own_base: bool
) -> SimulatedInstructor:
    """The simulated instructor ``instructor_seed`` for task number ``task``: the same person (preferred path,
    unprompted variation from day to day) whatever strategy she teaches.

    With ``own_base`` her base path is a valid ordering drawn uniformly for her (her own habit) instead of the
    structure's canonical order; either way it is then perturbed (``perturbation=0.2``).
    """
    rng = instructor_rng(instructor_seed, task)
    base = [a for a, _ in sample_orderings(structure, 1, rng)[0]] if own_base else None
    return SimulatedInstructor(structure, base, deviation=DEVIATION, seed=rng)


def teach(
    structure: Node,
    actions: Sequence[str],
    *,
    instructor_seed: int,
    task: int,
    strategy: str,
    strategy_index: int,
    schedule: QuerySchedule,
    demonstrations: int,
    own_base: bool = False,
) -> Taught:
    """One instructor (:func:`make_instructor`) teaches a fresh learner ``demonstrations`` times with
    ``strategy`` on ``schedule``.

    Returns the demonstrations performed and the learner's known path count after each.
    """
    instructor = make_instructor(structure, instructor_seed=instructor_seed, task=task, own_base=own_base)
    session = TeachingSession(
        actions,
        strategy,
        schedule,
        seed=session_rng(instructor_seed, task, strategy_index),
        learner=HTNLearner(mode="strict", alternatives=0),
    )
    paths: list[int] = []
    for _ in range(demonstrations):
        run_session(session, instructor, 1)
        paths.append(session.learner.task_graph_.path_count())
    return Taught(tuple(d.actions for d in session.demonstrations), tuple(paths))


def known_paths(*taught: Sequence[Sequence[str]]) -> int:
    """Known origin→terminal paths of the union of the given demonstrations' graphs (pooled instruction; the
    same graph as :func:`~supportive.learning.instructors.pooled_task_graph` of the members' graphs)."""
    graph = TaskGraph()
    for g, demos in enumerate(taught):
        for d, actions in enumerate(demos):
            graph.add(list(actions), f"g{g + 1}.d{d + 1}")
    return graph.path_count()


def anova(groups: Sequence[Sequence[float]]) -> dict[str, Any]:
    """One-way ANOVA across ``groups`` (the thesis's test): F, p and degrees of freedom; F and p are None when
    every value is equal (no variance)."""
    k, n = len(groups), sum(len(g) for g in groups)
    out: dict[str, Any] = {"df": [k - 1, n - k], "F": None, "p": None}
    values = [v for g in groups for v in g]
    if len(set(values)) <= 1:
        return out
    from scipy.stats import f_oneway

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = f_oneway(*groups)
    f, p = float(result.statistic), float(result.pvalue)
    if math.isfinite(f):
        out["F"], out["p"] = round(f, 4), round(p, 6)
    else:  # no variance within the groups but some between them
        out["F"], out["p"] = None, 0.0
    return out
