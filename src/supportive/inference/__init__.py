"""Goal inference: observation models, the thesis's flat and hierarchical HMM filters built from an HTN
(§2.1.7.1), the progress-aware tracker that knows what is done, and the next-step predictor; every filter is
a :class:`Filter` (``update(events)``; the tracker also ``observe(action)``); and the online mistake detector
over the tracker (:class:`MistakeDetector`, its :class:`StepVerdict` after each step)."""

from supportive.inference.filtering import ActionFilter, Belief, Filter
from supportive.inference.hmm import FlatHMM, GoalFilter, HierarchicalHMM
from supportive.inference.mistakes import MistakeDetector, StepVerdict
from supportive.inference.observations import Observation, ObservationModel
from supportive.inference.predictor import StepPredictor
from supportive.inference.tracker import END_LABEL, ProgressBelief, ProgressFilter, ProgressHMM

__all__ = [
    "END_LABEL",
    "ActionFilter",
    "Belief",
    "Filter",
    "FlatHMM",
    "GoalFilter",
    "HierarchicalHMM",
    "MistakeDetector",
    "Observation",
    "ObservationModel",
    "ProgressBelief",
    "ProgressFilter",
    "ProgressHMM",
    "StepPredictor",
    "StepVerdict",
]
