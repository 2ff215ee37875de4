"""The ``strict`` learner (the thesis's §2.1 as first implemented here): task graph, CTG (Algorithm 1),
compaction (Algorithm 2) and alternative hierarchies by ambiguity resolution (Algorithms 3–4).

It shares nothing with :mod:`supportive.learning.general` (an import-linter contract keeps the two wings
independent); :class:`~supportive.learning.learner.HTNLearner` chooses between them.
"""

from supportive.learning.strict.ambiguity import resolve_ambiguity
from supportive.learning.strict.compaction import Compaction
from supportive.learning.strict.conjugate import conjugate_task_graph, update_conjugate
from supportive.learning.strict.coverage import admitted_path_count
from supportive.learning.strict.learner import StrictLearner, StrictResult

__all__ = [
    "Compaction",
    "StrictLearner",
    "StrictResult",
    "admitted_path_count",
    "conjugate_task_graph",
    "resolve_ambiguity",
    "update_conjugate",
]
