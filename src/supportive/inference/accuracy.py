"""How often goal inference ranks the truth first: the current subgoal, and the subtask that encloses it."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from supportive.inference.hmm import FlatHMM, HierarchicalHMM
from supportive.inference.observations import Observation, ObservationModel
from supportive.tasks.htn import HTN, Leaf

__all__ = ["InferenceAccuracy", "inference_accuracy"]


@dataclass(frozen=True)
class InferenceAccuracy:
    """Share of steps at which the true current subgoal (and its enclosing subtask: the leaf's parent node) had
    the highest filtered probability."""

    subgoal: float
    subtask: float
    steps: int


def _score(
    model: FlatHMM | HierarchicalHMM, observations: Sequence[Observation], truth: Sequence[Leaf]
) -> InferenceAccuracy:
    layout = model.layout_
    index = {leaf: i for i, leaf in enumerate(layout.leaves)}
    running = model.filter()
    hits_leaf = hits_parent = 0
    for observation, leaf in zip(observations, truth, strict=True):
        belief = running.update(observation)
        true_leaf = index[leaf]
        hits_leaf += int(np.argmax(belief.subgoals) == true_leaf)
        hits_parent += int(np.argmax(belief.enclosing) == layout.parent_of_leaf[true_leaf] + 1)
    steps = len(truth)
    return InferenceAccuracy(hits_leaf / steps, hits_parent / steps, steps)


def inference_accuracy(
    htn: HTN,
    model: ObservationModel,
    observations: Sequence[Observation],
    truth: Sequence[Leaf],
    *,
    mean_duration: float = 5.0,
) -> dict[str, InferenceAccuracy]:
    """Accuracy of the flat and the hierarchical HMM on one labelled stream.

    The enclosing subtask of a subgoal is its parent node (subgoals directly under the task's top count as one
    group); its probability is the summed probability of the subgoals sharing that parent.
    """
    return {
        "flat": _score(FlatHMM(htn, model, mean_duration=mean_duration), observations, truth),
        "hierarchical": _score(HierarchicalHMM(htn, model, mean_duration=mean_duration), observations, truth),
    }
