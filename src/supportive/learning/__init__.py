"""Learning CC-HTNs from demonstrations: :class:`HTNLearner` in front of two learners, ``strict`` (the
thesis's Algorithms 1–4, :mod:`supportive.learning.strict`) and ``general`` (:mod:`supportive.learning.general`)."""

from supportive.learning.instructors import (
    SimulatedInstructor,
    demonstrate,
    pooled_learner,
    pooled_task_graph,
)
from supportive.learning.invariants import invariant_violations
from supportive.learning.learner import HTNLearner, LearningStats, learn
from supportive.learning.macros import MacroAction, macro_actions, macro_library
from supportive.learning.strict import (
    Compaction,
    admitted_path_count,
    conjugate_task_graph,
    resolve_ambiguity,
    update_conjugate,
)

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
