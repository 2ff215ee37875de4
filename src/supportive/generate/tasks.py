"""Whole generated tasks: structure, actions with text, and demonstrations; and the thesis-like task set."""

from __future__ import annotations

from typing import Literal

import numpy as np

from supportive.errors import GenerationError
from supportive.generate.ikea import IkeaParams
from supportive.generate.orderings import all_demonstrations, sample_demonstrations
from supportive.generate.structures import Profile, random_structure
from supportive.generate.uniform import UniformParams
from supportive.generate.vocabulary import action_text
from supportive.seeding import Seed, rng_from
from supportive.tasks.htn import leaf_actions, mean_action_depth
from supportive.tasks.spec import Action, TaskSpec

__all__ = ["THESIS_DEPTH_RANGE", "generate_task", "ikea_task_set"]

THESIS_DEPTH_RANGE: tuple[float, float] = (1.99, 3.61)
"""Range of the mean primitive depth over the 76 tasks of §2.1.7.2 (their mean: 2.84)."""


def generate_task(
    n_actions: int,
    seed: Seed = None,
    *,
    demonstrations: int | Literal["all"] = 4,
    profile: Profile = "ikea",
    name: str | None = None,
    params: IkeaParams | UniformParams | None = None,
    distinct: bool = False,
    limit: int = 1000,
) -> TaskSpec:
    """A random task: its ground-truth structure, its actions with text, and demonstrations of it.

    The structure is drawn first, from the same generator, so ``generate_task(n, s).structure ==
    random_structure(n, s)`` for an int seed ``s``; demonstrations are then drawn uniformly among the
    orderings the structure admits (:func:`~supportive.tasks.htn.sample_ordering`).

    Args:
        n_actions: Number of subgoals (at least 1).
        seed: Seed or generator (see :mod:`supportive.seeding`).
        demonstrations: How many demonstrations to draw, or ``"all"`` for one per valid ordering.
        profile: ``"ikea"`` or ``"uniform"`` (see :func:`random_structure`).
        name: Task name; ``"<profile>-<n_actions>"`` (plus ``-s<seed>`` for an int seed) when omitted.
        params: The profile's knobs.
        distinct: Draw demonstrations without replacement (see
            :func:`~supportive.generate.orderings.sample_orderings`).
        limit: Most orderings ``demonstrations="all"`` may enumerate.

    Raises:
        GenerationError: for bad arguments.
        TooManyOrderingsError: when ``demonstrations="all"`` and there are more than ``limit`` orderings.

    >>> task = generate_task(12, seed=3)
    >>> len(task.actions), [d.id for d in task.demonstrations]
    (12, ['d1', 'd2', 'd3', 'd4'])
    """
    if demonstrations != "all" and (isinstance(demonstrations, str) or demonstrations < 0):
        raise GenerationError(f"demonstrations must be a count >= 0 or 'all', got {demonstrations!r}")
    rng = rng_from(seed)
    structure = random_structure(n_actions, rng, profile=profile, params=params)
    if demonstrations == "all":
        demos = all_demonstrations(structure, limit)
    else:
        demos = sample_demonstrations(structure, demonstrations, rng, distinct=distinct)
    if name is None:
        name = f"{profile}-{n_actions}" + (f"-s{seed}" if isinstance(seed, int) else "")
    actions = tuple(Action(action, action_text(action)) for action in leaf_actions(structure))
    return TaskSpec(name, actions, structure, demos)


def ikea_task_set(
    count: int = 76,
    sizes: tuple[int, int] = (10, 100),
    seed: Seed = 0,
    *,
    demonstrations: int = 4,
    depth_range: tuple[float, float] | None = THESIS_DEPTH_RANGE,
    params: IkeaParams | None = None,
    distinct: bool = False,
    max_attempts: int = 1000,
) -> tuple[TaskSpec, ...]:
    """The thesis-like evaluation set of §2.1.7.2: ``count`` IKEA-like tasks, ``demonstrations`` random
    execution paths each.

    Sizes are spread evenly over ``sizes`` (both ends included). Each task gets its own int seed, drawn from
    ``seed`` and written into its name (``ikea-007-n18-s<seed>``), so ``generate_task(n, s)`` rebuilds it
    alone. With ``depth_range`` (by default the thesis's 1.99–3.61), a task whose mean primitive depth falls
    outside it is redrawn with the next seed; with the default parameters about 2% are redrawn (see the
    package docstring), so the set's depths match the thesis's range without bending their distribution
    much.

    Args:
        count: Number of tasks.
        sizes: Least and most subgoals.
        seed: Seed or generator for the whole set.
        demonstrations: Demonstrations per task (drawn uniformly).
        depth_range: Accepted mean primitive depths, or ``None`` to accept every task.
        params: The ikea profile's knobs.
        distinct: Draw each task's demonstrations without replacement.
        max_attempts: Most draws per task before giving up.

    Raises:
        GenerationError: for bad arguments, or when no task within ``depth_range`` is found in
            ``max_attempts`` draws.
    """
    low, high = sizes
    if count < 0 or not 1 <= low <= high:
        raise GenerationError(
            f"need count >= 0 and sizes (low, high) with 1 <= low <= high, got {count}, {sizes}"
        )
    if max_attempts < 1:
        raise GenerationError(f"max_attempts must be at least 1, got {max_attempts}")
    rng = rng_from(seed)
    tasks = []
    for index, size in enumerate(np.linspace(low, high, count).round().astype(int), 1):
        for _ in range(max_attempts):
            task_seed = int(rng.integers(2**31))
            task = generate_task(
                int(size),
                task_seed,
                demonstrations=demonstrations,
                name=f"ikea-{index:03d}-n{size}-s{task_seed}",
                params=params,
                distinct=distinct,
            )
            assert task.structure is not None
            depth = mean_action_depth([task.structure])
            if depth_range is None or depth_range[0] <= depth <= depth_range[1]:
                tasks.append(task)
                break
        else:
            raise GenerationError(
                f"task {index}: no structure of {size} actions with mean depth in {depth_range} "
                f"after {max_attempts} draws"
            )
    return tuple(tasks)
