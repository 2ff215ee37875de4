"""Learning algorithms over the model: Algorithm 1 (CTG), Algorithm 2 (CC-HTN), Algorithms 3–4 (ambiguity)."""

from supportive.learning.ambiguity import resolve_ambiguity
from supportive.learning.compaction import Compaction
from supportive.learning.conjugate import conjugate_task_graph, update_conjugate
from supportive.learning.coverage import admitted_path_count
from supportive.learning.instructors import (
    SimulatedInstructor,
    demonstrate,
    pooled_learner,
    pooled_task_graph,
)
from supportive.learning.invariants import invariant_violations
from supportive.learning.learner import HTNLearner, LearningStats, learn
from supportive.learning.macros import MacroAction, macro_actions, macro_library

__all__ = [
    "Compaction",
    "HTNLearner",
    "LearningStats",
    "MacroAction",
    "SimulatedInstructor",
    "admitted_path_count",
    "conjugate_task_graph",
    "demonstrate",
    "invariant_violations",
    "learn",
    "macro_actions",
    "macro_library",
    "pooled_learner",
    "pooled_task_graph",
    "resolve_ambiguity",
    "update_conjugate",
]
