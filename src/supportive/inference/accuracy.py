"""How often goal inference ranks the truth first: the current subgoal, and the subtask that encloses it.

**Ties share the credit.** Subgoals (or subtasks) whose probabilities tie share it: ``1/k`` when the truth
is one of ``k`` tied first, instead of ``numpy.argmax`` giving it all to the first of them. Ties are common (a
moment with no contact event scores every action alike, and a clique's successors get equal transition mass),
and which of two exactly tied values comes out larger after rounding depends on how numpy's vectorised sums
meet memory alignment, which differs from process to process: with plain ``argmax`` the same stream does not
always give the same accuracy twice. Values within :data:`TIE_TOLERANCE` of the largest (relatively) count as
tied: far above rounding noise (about 1e-16), far below any real difference between beliefs.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from supportive.errors import LearningError
from supportive.inference.hmm import FlatHMM, HierarchicalHMM
from supportive.inference.observations import Observation, ObservationModel
from supportive.inference.tracker import ProgressHMM
from supportive.tasks.htn import HTN, Leaf

__all__ = ["TIE_TOLERANCE", "InferenceAccuracy", "filter_accuracy", "first_share", "inference_accuracy"]

TIE_TOLERANCE = 1e-9
"""Relative gap below which two probabilities count as tied."""


@dataclass(frozen=True)
class InferenceAccuracy:
    """Share of steps at which the true current subgoal (and its enclosing subtask: the leaf's parent node) had
    the highest filtered probability, ties shared (see the module docstring).

    Attributes:
        subgoal: Share of steps at which the true subgoal was ranked first.
        subtask: The same for the true enclosing subtask.
        steps: Steps scored.
        seconds: Wall-clock time of each ``GoalFilter.update`` when asked for (``timed``), else empty.
    """

    subgoal: float
    subtask: float
    steps: int
    seconds: tuple[float, ...] = field(default=(), repr=False)


def first_share(values: np.ndarray, truth: int, tolerance: float = TIE_TOLERANCE) -> float:
    """The credit for ranking entry ``truth`` first: 1 when it alone is largest, ``1/k`` when it is one of
    ``k`` entries within ``tolerance`` (relative) of the largest, else 0.

    >>> first_share(np.array([0.2, 0.5, 0.3]), 1), first_share(np.array([0.4, 0.4 + 1e-17, 0.2]), 0)
    (1.0, 0.5)
    >>> first_share(np.array([0.2, 0.5, 0.3]), 2)
    0.0
    """
    top = float(values.max())
    tied = values >= top - tolerance * top
    if not tied[truth]:
        return 0.0
    return 1.0 / int(np.count_nonzero(tied))


def filter_accuracy(
    model: FlatHMM | HierarchicalHMM | ProgressHMM,
    observations: Sequence[Observation],
    truth: Sequence[Leaf],
    *,
    timed: bool = False,
) -> InferenceAccuracy:
    """Run a fresh online filter of ``model`` over a labelled stream and score every step (ties shared); with
    ``timed``, also time each filter update alone with :func:`time.perf_counter`.

    Raises:
        LearningError: when the stream is empty or its observations and truth differ in length.
    """
    if not truth:
        raise LearningError("accuracy needs a non-empty stream")
    layout = model.layout_
    index = {leaf: i for i, leaf in enumerate(layout.leaves)}
    running = model.filter()
    counter = time.perf_counter
    seconds: list[float] = []
    subgoal = subtask = 0.0
    for observation, leaf in zip(observations, truth, strict=True):
        started = counter()
        belief = running.update(observation)
        if timed:
            seconds.append(counter() - started)
        true_leaf = index[leaf]
        subgoal += first_share(belief.subgoals, true_leaf)
        subtask += first_share(belief.enclosing, int(layout.parent_of_leaf[true_leaf]) + 1)
    steps = len(truth)
    return InferenceAccuracy(subgoal / steps, subtask / steps, steps, tuple(seconds))


def inference_accuracy(
    htn: HTN,
    model: ObservationModel,
    observations: Sequence[Observation],
    truth: Sequence[Leaf],
    *,
    mean_duration: float = 5.0,
    timed: bool = False,
) -> dict[str, InferenceAccuracy]:
    """Accuracy of the flat and the hierarchical HMM on one labelled stream (see :func:`filter_accuracy`).

    The enclosing subtask of a subgoal is its parent node (subgoals directly under the task's top count as one
    group); its probability is the summed probability of the subgoals sharing that parent. With ``timed``,
    each result also carries its per-update wall-clock seconds.
    """
    return {
        "flat": filter_accuracy(
            FlatHMM(htn, model, mean_duration=mean_duration).fit(), observations, truth, timed=timed
        ),
        "hierarchical": filter_accuracy(
            HierarchicalHMM(htn, model, mean_duration=mean_duration).fit(), observations, truth, timed=timed
        ),
    }
