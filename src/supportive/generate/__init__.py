"""Generated tasks: random chain/clique structures, their valid orderings, and thesis-like task sets.

Two profiles make structures (:func:`random_structure`): ``"uniform"`` splits the leaves recursively at random
points; ``"ikea"`` draws assembly-like tasks (§2.1.7.2) of parts (``pick``, ``place``, fasten connectors),
steps attaching identical parts in any order, and sub-assemblies built independently. Every structure is
normalised (:func:`normalise`) and has distinct, readable action ids (``pick_leg_3``, ``fasten_bolt_12``).

Calibration of the ``"ikea"`` defaults: over 6 × 76 tasks of 10–100 subgoals (sizes evenly spread, seeds
0–5), the mean primitive depth per task averaged 2.85 (sd 0.34, min 1.00, max 3.69), with 98% of tasks
inside the thesis's 1.99–3.61 (its mean: 2.84). By size (40 seeds each): about 2.1 ± 0.45 at 10 subgoals,
2.8 ± 0.3 at 30, 2.9 ± 0.15 at 100, and 3.0 for thousands. The tasks outside the range are small ones (a
10-subgoal task can be one flat chain, depth 1); :func:`ikea_task_set` redraws them.

>>> task = generate_task(20, seed=7)
>>> len(task.actions), len(task.demonstrations), task.actions[0].text.startswith(("pick up", "fasten"))
(20, 4, True)
"""

from supportive.errors import GenerationError, TooManyOrderingsError
from supportive.generate.ikea import IkeaParams, ikea_structure
from supportive.generate.mistakes import Injected, KnownTask, inject, random_known_task
from supportive.generate.normalise import is_normalised, normalise
from supportive.generate.orderings import (
    all_demonstrations,
    as_demonstrations,
    sample_demonstrations,
    sample_orderings,
    valid_orderings,
)
from supportive.generate.partial_orders import PartialOrderTask, random_partial_order
from supportive.generate.statistics import ikea_statistics, structure_statistics
from supportive.generate.structures import Profile, random_structure
from supportive.generate.tasks import THESIS_DEPTH_RANGE, generate_task, ikea_task_set
from supportive.generate.uniform import UniformParams, uniform_structure
from supportive.generate.vocabulary import action_text

__all__ = [
    "THESIS_DEPTH_RANGE",
    "GenerationError",
    "IkeaParams",
    "Injected",
    "KnownTask",
    "PartialOrderTask",
    "Profile",
    "TooManyOrderingsError",
    "UniformParams",
    "action_text",
    "all_demonstrations",
    "as_demonstrations",
    "generate_task",
    "ikea_statistics",
    "ikea_structure",
    "ikea_task_set",
    "inject",
    "is_normalised",
    "normalise",
    "random_known_task",
    "random_partial_order",
    "random_structure",
    "sample_demonstrations",
    "sample_orderings",
    "structure_statistics",
    "uniform_structure",
    "valid_orderings",
]
