"""supportive: supportive behaviors for human-robot teaming.

Learn Clique/Chain HTNs from a few demonstrations (thesis §2.1) and build on them.

>>> from supportive import HTNLearner
>>> HTNLearner(mode="strict").fit([["knife", "carrots", "celery"], ["knife", "celery", "carrots"]]).htn_.complete
True
"""

from supportive.errors import SupportiveError, TaskFileError
from supportive.learning import HTNLearner, conjugate_task_graph, learn
from supportive.tasks import (
    HTN,
    ActionNode,
    ChainNode,
    CliqueNode,
    Demonstration,
    TaskGraph,
    TaskSpec,
)

__version__ = "0.1.0"

__all__ = [
    "HTN",
    "ActionNode",
    "ChainNode",
    "CliqueNode",
    "Demonstration",
    "HTNLearner",
    "SupportiveError",
    "TaskFileError",
    "TaskGraph",
    "TaskSpec",
    "__version__",
    "conjugate_task_graph",
    "learn",
]
