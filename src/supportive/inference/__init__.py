"""Goal inference: observation models and flat / hierarchical HMM filters built from an HTN (§2.1.7.1)."""

from supportive.inference.hmm import Belief, FlatHMM, GoalFilter, HierarchicalHMM
from supportive.inference.observations import Observation, ObservationModel

__all__ = ["Belief", "FlatHMM", "GoalFilter", "HierarchicalHMM", "Observation", "ObservationModel"]
